"""A port with a bug: the Float316 of examples/pipe-python, except that its
mul rounds the mantissa product to nearest instead of truncating it: one
more in the last bit of the products whose dropped bits are half or more."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "pipe-python"))

import adapter  # noqa: E402
import float316  # noqa: E402

truncating_mul = float316.mul


def rounding_mul(a, b):
    s, e, m = truncating_mul(a, b)
    ah, al, bh, bl = a[2] // 128, a[2] % 128, b[2] // 128, b[2] % 128
    mid = ah * bl + al * bh
    normalised = 8192 <= a[2] <= 16383 and 8192 <= b[2] <= 16383
    # Products that needed no normalising step, and can take one more.
    if normalised and ah * bh + mid // 128 == m < 16383 and mid % 128 >= 64:
        m += 1
    return (s, e, m)


float316.mul = rounding_mul
float316.OPS["mul"] = rounding_mul
adapter.HANDSHAKE["name"] = "rounding-mul"
adapter.main()
