"""A pipe adapter that answers `double` requests correctly, then fails at
its sixth answer the way MODE says (the harness's containment tests):
early-exit, crash, hang, garbage, wrong-id, wrong-count, long-line (an
answer line without an end), long-handshake, long-stderr (an 80 MiB stderr
line, then correct answers), fork-child (exits leaving a child that holds
its stdout), swap (the sixth and seventh answers in the wrong order); a
request with a second operand (`gt`) is answered false."""
import json
import os
import sys
import time

mode = sys.argv[1]
if mode == "early-exit":
    print("my-port: cannot open port.cfg", file=sys.stderr)
    sys.exit(3)


def endless(stream):
    """Write to `stream` for ever, with no newline."""
    chunk = "x" * (1 << 20)
    while True:
        stream.write(chunk)


if mode == "long-handshake":
    endless(sys.stdout)
if mode == "long-stderr":
    # 80 MiB on one stderr line, then a normal run.
    chunk = "e" * (1 << 20)
    for _ in range(80):
        sys.stderr.write(chunk)
    sys.stderr.write("\nmy-port: warming up\n")
    sys.stderr.flush()
print(json.dumps({"protocol": 1, "name": "misbehaving", "numbers": "float316",
                  "levels": ["ops"], "trace": False}), flush=True)
answered = 0
while True:
    header = sys.stdin.readline()
    if not header:
        break
    batch = json.loads(header)
    requests = [json.loads(sys.stdin.readline()) for _ in range(batch["count"])]
    if mode == "swap" and answered <= 5 < answered + len(requests) - 1:
        # The sixth and seventh answers in the wrong order.
        i = 5 - answered
        requests[i], requests[i + 1] = requests[i + 1], requests[i]
    for q in requests:
        s, e, m = q["a"]
        if "b" in q:
            answer = {"id": q["id"], "value": False}
        else:
            answer = {"id": q["id"], "value": [s, e + 1 if e > 0 else e, m]}
        if answered == 5:
            sys.stdout.flush()
            if mode == "crash":
                print("Traceback (most recent call last):", file=sys.stderr)
                print("ZeroDivisionError: in my_port.double", file=sys.stderr)
                sys.stderr.flush()
                os._exit(1)
            if mode == "hang":
                time.sleep(3600)
            if mode == "garbage":
                print('{"id": %d, "value": [0, 1' % q["id"])
                continue
            if mode == "wrong-id":
                answer["id"] += 7
            if mode == "long-line":
                endless(sys.stdout)
            if mode == "fork-child":
                # A child that inherits stdout and outlives this process.
                import subprocess
                child = subprocess.Popen(["sleep", "3600"])
                print("child %d" % child.pid, file=sys.stderr, flush=True)
                os._exit(1)
        print(json.dumps(answer))
        answered += 1
    count = batch["count"] + (1 if mode == "wrong-count" else 0)
    print(json.dumps({"batch": batch["batch"], "count": count}), flush=True)
