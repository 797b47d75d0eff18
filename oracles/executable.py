"""Any program as an implementation: the executable protocol (docs/protocol.md).

``--impl 'exec:./my_driver --flag'`` starts the program once and keeps it
running across examples (as Berkeley TestFloat drives a floating-point
implementation, and an LSP client a language server).  Requests and answers
are one JSON object per line on the program's stdin and stdout:

- first the handshake: ``{"protocol": "ddg-oracle", "version": 1, "method": "hello"}``,
  answered with ``{"name": ..., "methods": [...], "machine_epsilon": ...,
  "conventions": {...}}`` (``methods``: the protocol methods the program
  implements; the other two optional: float64 and the reference's conventions
  by default);
- then one request per call: ``{"id": 7, "method": "angle_defects", "V": [[x, y,
  z], ...], "F": [[i, j, k], ...]}`` (``planar_delaunay``: ``"P": [[x, y], ...]``;
  ``solve_dirichlet`` also ``"boundary": [i, ...], "values": [x, ...]``),
  floats written so that they round-trip (read them with ``strtod``), answered
  with ``{"id": 7, "value": ...}`` in the shape docs/protocol.md gives per
  method, or ``{"id": 7, "error": {"kind": "outside_domain" | "failed",
  "message": ...}}``.

The program's failures are the implementation's: it dies, hangs (no answer
within ``timeout`` seconds), writes a line that is not JSON, answers another
id or the wrong shape: each raises :class:`DriverFailed` (a crash of the
implementation, reported with its input; the program is restarted for the
next call).  ``outside_domain`` raises :class:`~ddg_oracle.protocol.methods.OutsideDomain`.
What the program printed on stderr is kept and quoted when it fails.
"""

from __future__ import annotations

import json
import os
import selectors
import shlex
import subprocess
import tempfile
import time

import numpy as np
import scipy.sparse

from ..protocol.answers import MalformedAnswer, indices_problem, problem, read, reals_problem
from ..protocol.arrays import checked_arrays
from ..protocol.budget import check_time_left, cut_short, time_left
from ..protocol.methods import (FLOAT64_EPSILON, METHODS, BadDeclaration, OutsideDomain,
                                checked_epsilon)
from ..protocol.processes import NotSent, call_limit, exit_text, stderr_tail

PROTOCOL_VERSION = 1
#: the longest answer line read: this many bytes, plus as many per vertex and face of the
#: request (a sparse Laplacian takes about 500 bytes per vertex); a longer line is garbage
ANSWER_BYTES, ANSWER_BYTES_PER_ROW = 1 << 20, 4096
#: seconds a program may take to answer the handshake (it may import a lot, or JIT)
START_TIMEOUT = 60.0


class DriverFailed(RuntimeError):
    """The program died, hung, or answered something that is not a protocol answer."""


def _as_sparse(value, method: str):
    if not isinstance(value, dict) or not {"shape", "rows", "cols", "values"} <= set(value):
        raise DriverFailed(f"{method}: expected a sparse matrix "
                           '{"shape", "rows", "cols", "values"}, got ' + _short(value))
    _raise_if(indices_problem(method, value["shape"], "a size")
              or indices_problem(method, value["rows"], "a row index")
              or indices_problem(method, value["cols"], "a column index")
              or reals_problem(method, value["values"]))
    n, m = value["shape"]
    return scipy.sparse.csr_matrix((np.asarray(value["values"], dtype=np.float64),
                                    (np.asarray(value["rows"], dtype=np.int64),
                                     np.asarray(value["cols"], dtype=np.int64))), shape=(n, m))


def _array(value, method: str, shape: tuple, dtype) -> np.ndarray:
    try:
        a = np.asarray(value, dtype=dtype)
    except (TypeError, ValueError):
        raise DriverFailed(f"{method}: expected an array of shape {shape}, got "
                           f"{_short(value)}") from None
    if a.ndim != len(shape) or any(s is not None and s != d for s, d in zip(shape, a.shape)):
        raise DriverFailed(f"{method}: expected shape {tuple('*' if s is None else s for s in shape)}"
                           f", got {a.shape}")
    return a


def _short(value) -> str:
    text = json.dumps(value)
    return text if len(text) <= 120 else text[:117] + "..."


#: the dtype and shape of each argument of a request (protocol.methods.Method.arguments)
_ARGUMENTS = {"V": (np.float64, 2), "F": (np.int64, 2), "P": (np.float64, 2),
              "boundary": (np.int64, 1), "values": (np.float64, 1)}
#: the shape of a "numbers" answer by its element (n vertices, m faces of the request)
_NUMBERS_SHAPE = {"corner": lambda n, m: (m, 3), "vertex": lambda n, m: (n,),
                  "vertex coordinate": lambda n, m: (n, 3)}


def decode_value(method: str, value, n: int, m: int):
    """The protocol value of ``method`` from its JSON answer (docs/protocol.md), read by the
    method's kind and element (:class:`~ddg_oracle.protocol.methods.Method`).  Each element
    must be of its kind before it is converted (:mod:`ddg_oracle.protocol.answers`): numbers
    written as strings, 0.4 as a vertex index or ``"yes"`` as a flag were converted by numpy
    and passed; an integral number such as ``2.0`` is an integer, as JSON Schema says."""
    spec = METHODS.get(method)
    if spec is None:
        raise DriverFailed(f"{method}: not a protocol method")
    try:
        return _decoded(method, spec, value, n, m)
    except MalformedAnswer as e:
        raise DriverFailed(str(e)) from None


def _decoded(method: str, spec, value, n: int, m: int):
    kind = spec.kind
    if kind in ("integer", "boolean"):
        return read(method, value)
    if kind == "numbers" and spec.element == "total":
        return float(read(method, value))
    if kind == "edges":
        if not isinstance(value, list) or not all(isinstance(t, list) and len(t) == 3
                                                 for t in value):
            raise DriverFailed(f"{method}: expected a list of [i, j, H] triples, got "
                               f"{_short(value)}")
        _raise_if(indices_problem(method, [t[:2] for t in value])
                  or reals_problem(method, [t[2] for t in value]))
        out: dict = {}
        for i, j, h in value:
            e = (min(int(i), int(j)), max(int(i), int(j)))
            if e in out:                # a later value would replace the first silently
                raise DriverFailed(f"{method}: edge {list(e)} is given twice")
            out[e] = float(h)
        return out
    if kind == "matrix":
        L = _as_sparse(value, method)
        if L.shape != (n, n):
            raise DriverFailed(f"{method}: expected a {n} x {n} matrix, got {L.shape}")
        return L
    if kind == "intrinsic triangulation":
        if not isinstance(value, dict) or set(value) != {"F", "l2"}:
            raise DriverFailed(f'{method}: expected {{"F": ..., "l2": ...}}, got {_short(value)}')
        _raise_if(problem(method, (value["F"], value["l2"])))
        F2 = _array(value["F"], method, (None, 3), np.int64)
        return F2, _array(value["l2"], method, (len(F2), 3), np.float64)
    _raise_if(problem(method, value))
    if kind == "loops":
        if not isinstance(value, list):
            raise DriverFailed(f"{method}: expected a list of vertex lists, got {_short(value)}")
        return [[int(v) for v in loop] for loop in value]
    if kind == "numbers":
        return _array(value, method, _NUMBERS_SHAPE[spec.element](n, m), np.float64)
    if kind == "flags":
        return _array(value, method, (m, 3), bool)
    return _array(value, method, (None, 3), np.int64)            # a planar triangulation


def _raise_if(why: str | None) -> None:
    if why is not None:
        raise DriverFailed(why)


def program_of(argv: list[str]) -> list[str]:
    """The part of a command line that names the program, without its own arguments: up to
    its last existing file (``node driver.js``, ``python3 /abs/driver.py``,
    ``./cotan_driver``) or a ``-m module``; else the first word.  A convention counterpart
    is this program started with other arguments.

    >>> import sys
    >>> program_of([sys.executable, "-m", "mydriver", "--sign=libigl"])[1:]
    ['-m', 'mydriver']
    >>> program_of(["no-such-program", "--weights=library"])
    ['no-such-program']
    """
    end = 1
    for k, a in enumerate(argv):
        if os.path.isfile(a):
            end = k + 1
        elif a == "-m" and k + 1 < len(argv):
            end = k + 2
    return list(argv[:end])


def _manifest(path: str, spec: str) -> dict:
    """A driver manifest (docs/protocol.md): the handshake's fields plus ``command``, the
    program and its arguments (files relative to the manifest's directory);
    ``conventions.counterpart`` may name another manifest, relative to this one."""
    try:
        with open(path, encoding="utf-8") as f:
            manifest = json.load(f)
    except (OSError, ValueError) as e:
        raise DriverFailed(f"{spec}: cannot read the manifest: {e}") from None
    command = manifest.get("command") if isinstance(manifest, dict) else None
    if not (isinstance(command, list) and command and all(isinstance(a, str) for a in command)):
        raise DriverFailed(f"{spec}: a manifest needs \"command\": [program, arguments...], "
                           f"got {_short(manifest)}")
    here = os.path.dirname(os.path.abspath(path))
    out = dict(manifest)
    out["command"] = [os.path.join(here, a) if not os.path.isabs(a) and
                      os.path.exists(os.path.join(here, a)) else a for a in command]
    other = (manifest.get("conventions") or {}).get("counterpart")
    if isinstance(other, str) and other.endswith(".json") and not other.startswith("exec:"):
        out["conventions"] = {**manifest["conventions"],
                              "counterpart": "exec:" + os.path.join(here, other)}
    return out


class Executable:
    """A program speaking the executable protocol, as an implementation object.

    Only the methods the program lists in its handshake exist on the object (so
    properties needing others are not applicable).  ``timeout``: seconds per call, per
    10,000 faces of the input (``processes.call_limit``).
    """

    def __init__(self, command: str | list[str], timeout: float = 60.0, cwd=None):
        argv = shlex.split(command) if isinstance(command, str) else list(command)
        if not argv:
            raise ValueError("exec: needs a command, e.g. exec:./my_driver")
        # files named relative to here are made absolute, so the spec (and a replay
        # snippet that loads it) works from any directory
        base = cwd or os.getcwd()
        argv = [os.path.abspath(os.path.join(base, a))
                if not os.path.isabs(a) and os.path.isfile(os.path.join(base, a)) else a
                for a in argv]
        self.spec = "exec:" + shlex.join(argv)
        # a manifest (exec:driver.json) says what the handshake would: no hello is sent
        self.manifest = _manifest(argv[0], self.spec) if len(argv) == 1 and \
            argv[0].endswith(".json") and os.path.isfile(argv[0]) else None
        self.argv = self.manifest["command"] if self.manifest else argv
        self.timeout, self.cwd = timeout, cwd
        self._proc = None
        self._next_id = 0
        self._buffer = bytearray()
        fd, self._stderr = tempfile.mkstemp(prefix="ddg-oracle-exec-", suffix=".stderr")
        os.close(fd)
        hello = self._start()
        methods = hello.get("methods")
        if not isinstance(methods, list) or not methods:
            self.close()
            raise DriverFailed(f"{self.spec}: the handshake lists no methods: {_short(hello)}")
        if not all(isinstance(x, str) for x in methods):
            self.close()
            raise DriverFailed(f"{self.spec}: the handshake's methods must be names (strings): "
                               f"{_short(methods)}")
        unknown = sorted(set(methods) - set(METHODS))
        if unknown:
            self.close()
            raise DriverFailed(f"{self.spec}: the handshake lists unknown methods {unknown}; "
                               f"the protocol's are {', '.join(METHODS)}")
        self.methods = frozenset(methods)
        self.name = str(hello.get("name") or os.path.basename(self.argv[0]))
        try:
            self.machine_epsilon = checked_epsilon(
                hello.get("machine_epsilon", FLOAT64_EPSILON), "its handshake")
        except BadDeclaration as e:
            self.close()
            raise DriverFailed(str(e)) from None
        self.conventions = self._conventions(hello.get("conventions"))

    def _conventions(self, declared) -> dict:
        """The handshake's ``{"follows": {id: what differs}, "counterpart_arguments":
        [...]}`` as the protocol's ``conventions`` attribute: the counterpart is this
        program with those arguments (docs/protocol.md)."""
        if isinstance(declared, str) or (isinstance(declared, dict) and declared
                                         and "follows" not in declared):
            # a preset or a map of the vocabulary (properties.conventions): validated here
            from ..properties.conventions import parse
            try:
                parse(declared)
            except ValueError as e:
                self.close()
                raise DriverFailed(f"{self.spec}: {e}") from None
            return declared
        if declared is not None and not isinstance(declared, dict):
            self.close()
            raise DriverFailed(f"{self.spec}: conventions must be an object, got "
                               f"{_short(declared)}")
        if not declared or not declared.get("follows"):
            return {}
        if self.manifest and "counterpart" in declared:      # another manifest, or any spec
            return {"follows": declared["follows"], "counterpart": declared["counterpart"]}
        args = declared.get("counterpart_arguments", [])
        if not isinstance(args, list) or not all(isinstance(a, str) for a in args):
            self.close()
            raise DriverFailed(f"{self.spec}: conventions.counterpart_arguments must be a list "
                               f"of strings, got {_short(args)}")
        return {"follows": declared["follows"],
                "counterpart": "exec:" + shlex.join([*program_of(self.argv), *args])}

    # --- the process ------------------------------------------------------------------

    def _start(self) -> dict:
        with open(self._stderr, "w"):
            pass
        try:
            self._proc = subprocess.Popen(self.argv, stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                          stderr=open(self._stderr, "ab"), cwd=self.cwd,
                                          start_new_session=True)
        except OSError as e:
            raise DriverFailed(f"{self.spec}: cannot start {self.argv[0]!r}: "
                               f"{e.strerror or e}") from None
        self._buffer = bytearray()
        if self.manifest:
            return self.manifest
        try:
            self._send({"protocol": "ddg-oracle", "version": PROTOCOL_VERSION,
                        "method": "hello"}, "hello")
            hello = self._receive("hello", START_TIMEOUT)
        except DriverFailed:
            raise
        except BaseException:
            # interrupted mid-handshake (a restart inside a task whose budget's alarm rang):
            # its hello answer would be read as the next request's, a false crash
            self._stop()
            raise
        if not isinstance(hello, dict):
            raise DriverFailed(f"{self.spec}: the handshake answer is not an object: "
                               f"{_short(hello)}")
        return hello

    def _stop(self) -> None:
        if self._proc is not None:
            try:
                os.killpg(self._proc.pid, 9)        # the program and anything it started
            except OSError:
                pass
            self._proc.wait()
            for stream in (self._proc.stdin, self._proc.stdout):
                try:
                    stream.close()
                except OSError:
                    pass
        self._proc = None

    def _fail(self, method: str, how: str) -> DriverFailed:
        """Stop the program (a fresh one answers the next call) and say what went wrong."""
        code = None
        if self._proc is not None:
            try:
                code = self._proc.wait(timeout=0.5)   # it closed its output: let it finish dying
            except subprocess.TimeoutExpired:
                code = None                            # still running (hung, or garbage)
        self._stop()
        if code is not None:
            how += (f" (it died with {exit_text(code)})" if code < 0
                    else f" (it exited with code {code})")
        said = self.stderr_tail()
        return DriverFailed(f"{self.name if hasattr(self, 'name') else self.spec}.{method}: "
                            f"{how}" + (f"; it printed: {said}" if said else ""))

    def stderr_tail(self) -> str:
        """The last lines the program wrote to stderr, or ''."""
        return stderr_tail(self._stderr)

    def _send(self, obj, method: str) -> None:
        try:
            self._proc.stdin.write((json.dumps(obj) + "\n").encode())
            self._proc.stdin.flush()
        except (BrokenPipeError, OSError):
            raise self._fail(method, "the program is not reading its input") from None

    def _receive(self, method: str, timeout: float, longest: int = 1 << 30,
                 budget_cut: float | None = None):
        """The next answer line, parsed: at most ``timeout`` seconds and ``longest`` bytes.
        ``budget_cut``: the wait is the rest of a check task's budget, and the call began
        then (out of time: :func:`~ddg_oracle.protocol.budget.cut_short` decides whether
        the program hangs)."""
        deadline = time.monotonic() + timeout
        buffer, seen = self._buffer, 0
        # a blank line is no answer (console.log() with nothing to print): skipped, as
        # serve() skips blank request lines
        while (end := buffer.find(b"\n", seen)) < 0 or not buffer[:end].strip():
            if end >= 0:
                del buffer[:end + 1]
                seen = 0
                continue
            seen = len(buffer)
            left = deadline - time.monotonic()
            if left <= 0:
                if budget_cut is not None:
                    self._stop()
                    raise cut_short(f"{self.name}.{method}", budget_cut)
                raise self._fail(method, f"no answer within {timeout:.3g} s (killed)")
            with selectors.DefaultSelector() as sel:
                sel.register(self._proc.stdout, selectors.EVENT_READ)
                if not sel.select(left):
                    continue
            chunk = os.read(self._proc.stdout.fileno(), 1 << 16)
            if not chunk:
                raise self._fail(method, "the program closed its output (it died or exited)")
            buffer += chunk                     # a bytearray: no copy of what came before
            if len(buffer) > longest:
                raise self._fail(method, f"an answer line longer than {longest:,} bytes, more "
                                         f"than any answer to this request needs")
        line = bytes(buffer[:end])
        del buffer[:end + 1]
        try:
            return json.loads(line)
        except (json.JSONDecodeError, UnicodeDecodeError):
            text = line[:80].decode("utf-8", "replace")
            raise self._fail(method, f"answered a line that is not JSON: {text!r}") from None

    # --- calls ------------------------------------------------------------------------

    def call(self, method: str, *args):
        """Send ``method`` with its arguments (the protocol's ``arguments``: V, F, and for
        some methods more, or planar points P) and return the decoded answer."""
        if self._proc is None or self._proc.poll() is not None:
            if self._proc is not None:
                self._stop()
            self._start()
        self._next_id += 1
        k = self._next_id
        names = METHODS[method].arguments
        if len(args) != len(names):
            raise TypeError(f"{method} takes {', '.join(names)}, got {len(args)} arguments")
        given = dict(zip(names, args))
        if "V" in given:
            try:
                given["V"], given["F"] = checked_arrays(given["V"], given["F"])
            except ValueError as e:
                raise NotSent(f"not sent to {self.name}: {e}") from None
        request = {"id": k, "method": method}
        for name, x in given.items():
            dtype, ndim = _ARGUMENTS[name]
            a = np.asarray(x, dtype=dtype)
            request[name] = (a if ndim == 2 else a.reshape(-1)).tolist()
        n = len(request["V"] if "V" in request else request["P"])
        m = len(request.get("F", ()))
        # inside a check task, wait at most what its budget has left (protocol.budget):
        # an answer still missing then is this program's hang
        check_time_left(f"{self.name}.{method}")
        left, limit = time_left(), call_limit(self.timeout, max(n, m))
        wait = limit if left is None else min(limit, left)
        started = time.monotonic()
        try:
            self._send(request, method)
            answer = self._receive(method, wait, ANSWER_BYTES + ANSWER_BYTES_PER_ROW * (n + m),
                                   started if wait < limit else None)
        except DriverFailed:
            raise
        except BaseException:
            # interrupted (a signal, the example's time limit) with the request or its answer
            # in the pipe: the next call would read that answer as its own
            self._stop()
            raise
        if not isinstance(answer, dict) or answer.get("id") != k:
            raise self._fail(method, f"answered {_short(answer)} to request id {k}")
        if "error" in answer:
            err = answer["error"] if isinstance(answer["error"], dict) else {"message": answer["error"]}
            message = str(err.get("message", ""))
            if err.get("kind") == "outside_domain":
                raise OutsideDomain(message)
            raise DriverFailed(f"{self.name}.{method} failed: {message}")
        if "value" not in answer:
            raise self._fail(method, f"answered without a value: {_short(answer)}")
        return decode_value(method, answer["value"], n, m)

    def __getattr__(self, method: str):
        if method in METHODS and method in self.__dict__.get("methods", ()):
            return lambda *args: self.call(method, *args)
        raise AttributeError(method)

    def close(self) -> None:
        self._stop()
        try:
            os.unlink(self._stderr)
        except OSError:
            pass

    def __del__(self):
        try:
            self.close()
        except Exception:  # noqa: BLE001  (interpreter shutdown)
            pass


# --- the other side: a program serving an implementation object ------------------------------


def encode_value(method: str, value):
    """The JSON answer of a protocol value (the inverse of :func:`decode_value`)."""
    if scipy.sparse.issparse(value):
        c = scipy.sparse.coo_matrix(value)
        return {"shape": list(c.shape), "rows": c.row.tolist(), "cols": c.col.tolist(),
                "values": c.data.tolist()}
    kind = METHODS[method].kind if method in METHODS else None
    if kind == "edges":
        return [[int(i), int(j), float(h)] for (i, j), h in value.items()]
    if kind == "intrinsic triangulation":
        F2, l2 = value
        return {"F": np.asarray(F2).tolist(), "l2": np.asarray(l2).tolist()}
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, (np.integer, np.floating, np.bool_)):
        return value.item()
    return value


def serve(impl, stdin=None, stdout=None, name: str | None = None) -> None:
    """Answer protocol requests for the Python object ``impl`` until stdin ends: the
    protocol's server side, for a Python program that wants to be checked as a process
    (and the reference a driver in another language can be compared with).

    >>> import io
    >>> class Chi:
    ...     def euler_characteristic(self, V, F):
    ...         return len(V) - 3 + len(F)
    >>> out = io.StringIO()
    >>> serve(Chi(), io.StringIO('{"method": "hello"}\\n{"id": 1, "method": '
    ...       '"euler_characteristic", "V": [[0,0,0],[1,0,0],[0,1,0]], "F": [[0,1,2]]}\\n'), out)
    >>> print(out.getvalue().strip())
    {"name": "Chi", "methods": ["euler_characteristic"], "machine_epsilon": 2.220446049250313e-16}
    {"id": 1, "value": 1}
    """
    import sys
    from ..protocol.methods import capabilities, implementation_name, machine_epsilon
    stdin = stdin or sys.stdin
    stdout = stdout or sys.stdout
    for line in stdin:
        if not line.strip():
            continue
        request = json.loads(line)
        method = request.get("method")
        if method == "hello":
            answer = {"name": name or implementation_name(impl),
                      "methods": sorted(capabilities(impl), key=list(METHODS).index),
                      "machine_epsilon": machine_epsilon(impl)}
            declared = getattr(impl, "conventions", None)
            if declared and (isinstance(declared, str) or "follows" not in declared):
                answer["conventions"] = declared     # the vocabulary's (properties.conventions)
        else:
            k = request.get("id")
            try:
                args = [np.asarray(request[a], dtype=_ARGUMENTS[a][0])
                        for a in METHODS[method].arguments]
                value = getattr(impl, method)(*args)
                answer = {"id": k, "value": encode_value(method, value)}
            except OutsideDomain as e:
                answer = {"id": k, "error": {"kind": "outside_domain", "message": str(e)}}
            except Exception as e:  # noqa: BLE001  (the implementation's failure, reported)
                answer = {"id": k, "error": {"kind": "failed",
                                             "message": f"{type(e).__name__}: {e}"}}
        stdout.write(json.dumps(answer) + "\n")
        stdout.flush()
