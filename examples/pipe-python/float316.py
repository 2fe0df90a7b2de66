"""Float316 in Python, written from the format's rules (the reference
implementation is impls/reference/src/float316.rs): the port this
directory's adapter wraps. Every integer is a
Jack word: 16-bit two's complement, wrapping, division truncating toward
zero. A value is a tuple (s, e, m). A result is ("value", v), where v is a
tuple or, for gt, a bool; or ("sys_error", code), ("hang",) or
("out_of_domain",)."""

ONE = (0, 127, 8192)
MINUS_ONE = (1, 127, 8192)
THREE_HALVES = (0, 127, 12288)
ZERO = (0, 0, 0)


class Trap(Exception):
    """A Jack program that would call Sys.error, loop for ever, or index
    outside its tables."""

    def __init__(self, *outcome):
        super().__init__(outcome)
        self.outcome = outcome


def w(x):
    """x as a Jack word."""
    return ((x + 32768) & 0xFFFF) - 32768


def jdiv(a, b):
    """Jack's integer division: truncates toward zero (Python's // floors)."""
    q = abs(a) // abs(b)
    return w(q if (a < 0) == (b < 0) else -q)


def is_zero(a):
    return a[1] == 0 and a[2] == 0


def gt(a, b):
    if a[0] != b[0]:
        return a[0] == 0 and b[0] == 1
    p, q = (a, b) if a[0] == 0 else (b, a)
    return p[1] > q[1] or (p[1] == q[1] and p[2] > q[2])


def add(a, b):
    big, small = (b, a) if (b[1], b[2]) > (a[1], a[2]) else (a, b)
    if is_zero(small):
        return big
    if big[0] != small[0] and big[1] == small[1] and big[2] == small[2]:
        return ZERO
    sm = small[2]
    for _ in range(max(0, min(w(big[1] - small[1]), 16))):
        sm = jdiv(sm, 2)
    e = big[1]
    if big[0] == small[0]:
        m = w(big[2] + sm)
        if m > 16383:
            m, e = jdiv(m, 2), w(e + 1)
    else:
        m = w(big[2] - sm)
        while m < 8192:
            if m == 0:
                raise Trap("hang")
            m, e = w(m * 2), w(e - 1)
    return (big[0], e, m)


def sub(a, b):
    return add(a, (1 - (b[0] & 1), b[1], b[2]))


def mul(a, b):
    sign = w(a[0] + b[0]) & 1
    if is_zero(a) or is_zero(b):
        return (sign, 0, 0)
    e = w(a[1] + b[1] - 126)
    ah, al = jdiv(a[2], 128), w(a[2] & 127)
    bh, bl = jdiv(b[2], 128), w(b[2] & 127)
    mid = w(w(ah * bl) + w(al * bh))
    m = w(w(ah * bh) + jdiv(mid, 128))
    if m > 0:
        while m < 8192:
            m, e = w(m * 2), w(e - 1)
    return (sign, e, m)


def div(a, b):
    sign = w(a[0] + b[0]) & 1
    if is_zero(a):
        return (sign, 0, 0)
    if is_zero(b):
        raise Trap("sys_error", 1)
    e = w(a[1] + 127 - b[1])
    r, d, q = a[2], b[2], 0
    for i in range(13, -1, -1):
        if r >= d:
            q, r = w(q + (1 << i)), w(r - d)
        d = jdiv(d, 2)
    if q == 0:
        raise Trap("hang")
    while q < 8192:
        q, e = w(q * 2), w(e - 1)
    return (sign, e, q)


def shift_exponent(a, delta):
    return (a[0], w(a[1] + delta), a[2]) if a[1] > 0 else a


def halve(a):
    return shift_exponent(a, -1)


def double(a):
    return shift_exponent(a, 1)


def quarter(a):
    return shift_exponent(a, -2)


def floor(a):
    if a[1] < 127:
        return ZERO if a[0] == 0 else MINUS_ONE
    i = w(a[1] - 127)
    if i > 13:
        raise Trap("out_of_domain")
    kept = w(a[2] & ~((1 << (13 - i)) - 1))
    r = (a[0], a[1], kept)
    return add(r, MINUS_ONE) if a[0] == 1 and kept != a[2] else r


def mod2(a):
    if a[2] == 0:
        return ZERO
    i = w(a[1] - 127)
    if not 0 <= i <= 13:
        raise Trap("out_of_domain")
    return ONE if a[2] & (1 << (13 - i)) else ZERO


def sqrt(x):
    if x[0] == 1:
        raise Trap("sys_error", 2)
    g = (0, w(jdiv(x[1], 2) + (64 if x[1] & 1 else 63)), x[2])
    for _ in range(2):
        g = halve(add(g, div(x, g)))
    return (0, g[1], g[2])


def inv_sqrt(x):
    if x[0] == 1:
        raise Trap("sys_error", 3)
    x2 = (0, w(x[1] - 1), x[2])
    y = (0, w(190 - jdiv(x[1], 2)), 8192)
    for _ in range(2):
        t = mul(mul(x2, y), y)
        y = mul(y, sub(THREE_HALVES, t))
    return (0, y[1], y[2])


OPS = {"gt": gt, "add": add, "sub": sub, "mul": mul, "div": div, "floor": floor,
       "mod2": mod2, "sqrt": sqrt, "inv_sqrt": inv_sqrt, "halve": halve,
       "double": double, "quarter": quarter}


def apply(op, *args):
    """The outcome of one operation."""
    try:
        return ("value", OPS[op](*args))
    except Trap as t:
        return t.outcome
