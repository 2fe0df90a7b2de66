"""Pipe adapters that fail in known ways, for the gate tests: each must fail
every command that compares, with a message that names it.

  hang-f32          an f32 port (sdf, pixels) that answers `hang` to every input
  crash-after N     a Float316 port (ops, the example port's arithmetic) that
                    answers N inputs correctly and then crashes
  no-start          a port that exits before its handshake
  aliased-sub       a Float316 ops port with traces whose inv_sqrt is right
                    but whose trace shows sub(1.5, 0.5) = -1 inside it (its
                    sub writes its result over an operand, and the sign it
                    flips is dropped later): a trace difference that does
                    not reach the answer
  no-domain-check   the example port without its domain check: floor and
                    mod2 of a value the reference models no result for
                    answer a value, as a user's program that floors any
                    value does
"""
import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "..", "examples", "pipe-python"))

mode = sys.argv[1]
if mode == "no-start":
    print("faulty: cannot open its configuration", file=sys.stderr)
    sys.exit(3)

if mode == "hang-f32":
    handshake = {"numbers": "f32", "levels": ["sdf", "pixels"]}
else:
    import adapter  # the example adapter and its port
    handshake = {"numbers": "float316", "levels": ["ops"]}
    crash_at = int(sys.argv[2]) if mode == "crash-after" else None
handshake.update({"protocol": 1, "name": "faulty-" + mode, "trace": mode == "aliased-sub"})
out = sys.stdout
out.write(json.dumps(handshake) + "\n")
out.flush()


def answer(request):
    if mode == "hang-f32":
        return {"id": request["id"], "outcome": "hang"}
    reply = adapter.answer(request)
    if mode == "no-domain-check" and reply.get("outcome") == "out_of_domain":
        reply = {"id": request["id"], "value": request["a"]}
    if request.get("trace"):
        args = [request["a"]] + ([request["b"]] if "b" in request else [])
        reply["trace"] = [{"op": request["op"], "args": args, "result": reply["value"]}]
        if request["op"] == "inv_sqrt":
            reply["trace"].append({"op": "sub", "args": [[0, 127, 12288], [0, 126, 8192]],
                                   "result": [1, 127, 8192], "path": ["inv_sqrt"]})
    return reply


answered = 0
for header in sys.stdin:
    batch = json.loads(header)
    for _ in range(batch["count"]):
        request = json.loads(sys.stdin.readline())
        if mode == "crash-after" and answered == crash_at:
            out.flush()
            print("Traceback (most recent call last):", file=sys.stderr)
            print("ZeroDivisionError: in faulty.answer", file=sys.stderr)
            sys.stderr.flush()
            os._exit(1)
        out.write(json.dumps(answer(request)) + "\n")
        answered += 1
    out.write(json.dumps({"batch": batch["batch"], "count": batch["count"]}) + "\n")
    out.flush()
