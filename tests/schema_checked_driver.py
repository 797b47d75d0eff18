"""The reference served through the executable protocol, checking every message against
docs/protocol.schema.json: a request or answer that does not validate ends the program
with exit code 3 and the validation error on stderr (so the run reports a crash)."""

import json
import sys
from pathlib import Path

import jsonschema

from ddg_oracle.oracles.exact_reference import ReferenceImplementation
from ddg_oracle.oracles.executable import serve

SCHEMA = json.loads((Path(__file__).resolve().parent.parent / "docs" / "protocol.schema.json")
                    .read_text(encoding="utf-8"))
COUNTS = Path(sys.argv[1]) if len(sys.argv) > 1 else None    # where to count what was checked
checked = {"requests": 0, "answers": 0}
jsonschema.Draft202012Validator.check_schema(SCHEMA)   # once: jsonschema.validate did it per message
validators: dict[str, jsonschema.Draft202012Validator] = {}


def check(message: dict, kind: str) -> None:
    if kind not in validators:
        validators[kind] = jsonschema.Draft202012Validator(
            {"$ref": f"#/$defs/{kind}", "$defs": SCHEMA["$defs"]})
    error = jsonschema.exceptions.best_match(validators[kind].iter_errors(message))
    if error is not None:                       # what jsonschema.validate would raise
        print(f"{kind} does not validate: {error.message}", file=sys.stderr)
        sys.exit(3)


def requests():
    for line in sys.stdin:
        message = json.loads(line)
        method = message.get("method")
        check(message, "hello.request" if method == "hello" else f"request.{method}")
        checked["requests"] += 1
        requests.method = method
        yield line


class Answers:
    def write(self, text: str) -> None:
        if not text.strip():
            return
        message = json.loads(text)
        method = requests.method
        check(message, "hello.answer" if method == "hello" else
              "error.answer" if "error" in message else f"answer.{method}")
        checked["answers"] += 1
        if COUNTS:
            COUNTS.write_text(json.dumps(checked))
        sys.stdout.write(text)

    def flush(self) -> None:
        sys.stdout.flush()


serve(ReferenceImplementation(), requests(), Answers())
