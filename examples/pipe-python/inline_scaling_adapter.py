"""The adapter of a port that has no halve, double or quarter function: it
scales by 2 and 4 inline, inside its other operations, as many ports do.
Its handshake lists the operations it has (docs/protocol.md, `ops`), so the
harness sends it no other, counts those inputs as unsupported, and still
localizes through the operations it has. A request for an operation it
lacks, were one sent, is answered `unsupported`."""
import adapter  # the complete adapter of this folder

OPS = ["gt", "add", "sub", "mul", "div", "floor", "mod2", "sqrt", "inv_sqrt"]
HANDSHAKE = dict(adapter.HANDSHAKE, name="float316.py without scaling", ops=OPS)


def answer(request):
    if request["op"] not in OPS:
        return {"id": request["id"], "outcome": "unsupported"}
    return adapter.answer(request)


if __name__ == "__main__":
    adapter.main(HANDSHAKE, answer)
