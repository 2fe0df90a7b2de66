
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
