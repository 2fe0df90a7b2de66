
// ---- Helpers of kernels generated from a scene (scene_wgsl.rs) ----

// a mod 2 of an integral a: 0 or 1, also for negative a.
fn mod2_f32(a: f32) -> f32 {
    return a - 2.0 * floor(a / 2.0);
}

// The angle clamp: 0 when the sign bit is set (also -0), 1 when above 1.
fn clamp01_f32(d: f32) -> f32 {
    if ((bitcast<u32>(d) >> 31u) == 1u) {
        return 0.0;
    }
    if (d > 1.0) {
        return 1.0;
    }
    return d;
}
