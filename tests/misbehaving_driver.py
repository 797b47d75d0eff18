"""A protocol driver that misbehaves in one chosen way (tests/test_executable.py).

    python tests/misbehaving_driver.py MODE

It answers the handshake (offering euler_characteristic and cotan_laplacian) and then,
per request, according to MODE: ``ok`` answers correctly; ``dies`` exits; ``segfault``
kills itself with SIGSEGV after printing to stderr; ``hangs`` never answers; ``garbage``
prints a line that is not JSON; ``wrong-shape`` answers a list for the matrix;
``wrong-id`` answers another request's id; ``outside`` declines (outside_domain);
``fails`` reports an error; ``flaky`` dies on every other request; ``hangs-later``
answers three requests, then never answers; ``half-line`` writes the start of an answer
and no end of line; ``huge-line`` streams an answer line of 100 MB; ``slow-hello`` takes a
second to answer the handshake, then answers as ``ok``; ``blank-lines`` prints an empty
line before the handshake and before every answer (``console.log()``), else as ``ok``.
"""

import json
import os
import signal
import sys
import time

MODE = sys.argv[1]
count = 0
for line in sys.stdin:
    request = json.loads(line)
    if MODE == "blank-lines":
        print(flush=True)
    if request["method"] == "hello":
        if MODE == "slow-hello":
            time.sleep(1)
        print(json.dumps({"name": f"misbehaving-{MODE}",
                          "methods": ["euler_characteristic", "cotan_laplacian"]}), flush=True)
        continue
    count += 1
    k, F = request["id"], request["F"]      # no numpy: restarted per death (fast)
    edges = {tuple(sorted((int(f[a]), int(f[(a + 1) % 3])))) for f in F for a in range(3)}
    chi = len(request["V"]) - len(edges) + len(F)
    if MODE == "dies" or (MODE == "flaky" and count % 2 == 0):
        sys.exit(3)
    if MODE == "segfault":
        os.write(2, b"driver.c:17: about to dereference a null pointer\n")
        os.kill(os.getpid(), signal.SIGSEGV)
    if MODE == "hangs" or (MODE == "hangs-later" and count > 3):
        time.sleep(3600)
    if MODE == "half-line":
        sys.stdout.write(json.dumps({"id": k, "value": chi})[:-3])
        sys.stdout.flush()
        time.sleep(3600)
    if MODE == "huge-line":
        chunk = "1" * (1 << 20)
        sys.stdout.write('{"id": %d, "value": ' % k)
        for _ in range(100):
            sys.stdout.write(chunk)
        sys.stdout.write("}\n")
        sys.stdout.flush()
        continue
    if MODE == "garbage":
        print("Segmentation fault (core dumped)? no: just not JSON", flush=True)
        continue
    if MODE == "outside":
        print(json.dumps({"id": k, "error": {"kind": "outside_domain", "message": "no"}}),
              flush=True)
        continue
    if MODE == "fails":
        print(json.dumps({"id": k, "error": {"kind": "failed", "message": "not written yet"}}),
              flush=True)
        continue
    if request["method"] == "euler_characteristic":
        value = chi
    else:
        value = [[0.0]] if MODE == "wrong-shape" else {
            "shape": [len(request["V"])] * 2, "rows": [], "cols": [], "values": []}
    print(json.dumps({"id": k + 1 if MODE == "wrong-id" else k, "value": value}), flush=True)
