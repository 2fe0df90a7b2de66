
// ---- Helpers of kernels generated from a scene (scene_wgsl.rs) ----

// The angle clamp of the scene's intermediate form: 0 when the sign bit is
// set (also -0), 1 when above 1.
fn clamp01_316(d: F) -> F {
    if (d.s == 1) {
        return ZERO;
    }
    if (gt(d, ONE)) {
        return ONE;
    }
    return d;
}

// The newton-1 variants of a tuned call site: one Newton step.
fn sqrt316_newton1(x: F) -> F {
    return sqrt316_steps(x, 1);
}

fn vlength_newton1(v: V) -> F {
    return sqrt316_newton1(vdot(v, v));
}

fn vnormalize_newton1(v: V) -> V {
    return scale(v, inv_sqrt_steps(vdot(v, v), 1));
}

// The truncated-product variant of `mul`: the high halves' product alone.
fn mul_truncated(a: F, b: F) -> F {
    let s = (a.s + b.s) & 1;
    if (is_zero(a) || is_zero(b)) {
        return F(s, 0, 0);
    }
    var e = w(a.e + b.e - 126);
    var m = w((a.m / 128) * (b.m / 128));
    // 0 < m < 8192 reaches 8192 within 13 doublings.
    if (m > 0) {
        for (var k = 0; k < 13 && m < 8192; k++) {
            m = m * 2;
            e = w(e - 1);
        }
    }
    return F(s, e, m);
}

// The floor-direct variant of `floor`: the spec's value, a negative
// non-integer stepping down on its mantissa where `floor316` calls `add`.
fn floor316_direct(a: F) -> F {
    // Where `floor316` calls no `add` (a small, out-of-domain, positive or
    // integral input), its own answer.
    let i = a.e - 127;
    if (a.e < 127 || i > 13 || a.s == 0) {
        return floor316(a);
    }
    let unit = 1 << u32(13 - i);
    let mp = a.m & ~(unit - 1);
    if (mp == a.m) {
        return a;
    }
    let m = w(mp + unit);
    if (m > 16383) {
        return F(1, w(a.e + 1), m / 2);
    }
    return F(1, a.e, m);
}

// `c ? t : f` for triples (WGSL's select takes scalars and vectors only).
fn select316(f: F, t: F, c: bool) -> F {
    if (c) {
        return t;
    }
    return f;
}

// A triple and a vector from the input words, a triple into the output
// words (the prelude's bindings).
fn load_f(base: u32) -> F {
    return F(bitcast<i32>(inp[base]), bitcast<i32>(inp[base + 1u]), bitcast<i32>(inp[base + 2u]));
}

fn load_v(base: u32) -> V {
    return V(load_f(base), load_f(base + 3u), load_f(base + 6u));
}

fn store_f(base: u32, a: F) {
    outp[base] = bitcast<u32>(a.s);
    outp[base + 1u] = bitcast<u32>(a.e);
    outp[base + 2u] = bitcast<u32>(a.m);
}
