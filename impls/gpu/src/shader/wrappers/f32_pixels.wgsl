
// In: x, y. Out: status, the shade pixel() returns (f32 bits).
@compute @workgroup_size(64)
fn harness_pixels(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if (i >= harness_params.count) {
        return;
    }
    let coord = vec2<f32>(f32(harness_in[i * 2u]) + 0.5, f32(harness_in[i * 2u + 1u]) + 0.5);
    let shade = pixel(coord, vec2<f32>(HARNESS_WIDTH, HARNESS_HEIGHT));
    harness_out[i * 2u] = harness_status();
    harness_out[i * 2u + 1u] = bitcast<u32>(shade);
}
