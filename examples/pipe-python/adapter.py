"""A complete pipe adapter (docs/protocol.md) for a Python port of the
Float316 operations: level ops, no traces. Copy it, and replace
`float316.apply` with your port's entry point."""
import json
import sys

import float316  # the port: float316.apply(op, *args) -> outcome

HANDSHAKE = {"protocol": 1, "name": "float316.py", "numbers": "float316",
             "levels": ["ops"], "trace": False}


def answer(request):
    args = [tuple(request["a"])] + ([tuple(request["b"])] if "b" in request else [])
    outcome = float316.apply(request["op"], *args)
    reply = {"id": request["id"]}
    if outcome[0] == "value":
        value = outcome[1]
        reply["value"] = value if isinstance(value, bool) else list(value)
    else:
        reply["outcome"] = outcome[0]
        if outcome[0] == "sys_error":
            reply["code"] = outcome[1]
    return reply


def main(handshake=HANDSHAKE, answer_one=answer):
    """Write `handshake`, then answer every batch with `answer_one`."""
    out = sys.stdout
    out.write(json.dumps(handshake) + "\n")
    out.flush()
    for header in sys.stdin:
        batch = json.loads(header)
        for _ in range(batch["count"]):
            out.write(json.dumps(answer_one(json.loads(sys.stdin.readline()))) + "\n")
        out.write(json.dumps({"batch": batch["batch"], "count": batch["count"]}) + "\n")
        out.flush()


if __name__ == "__main__":
    main()
