
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

// `c ? t : f` for triples (WGSL's select takes scalars and vectors only).
fn select316(f: F, t: F, c: bool) -> F {
    if (c) {
        return t;
    }
    return f;
}
