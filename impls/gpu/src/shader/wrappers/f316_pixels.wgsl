
// In: x, y. Out: status, the shade (s, e, m), white (0 or 1).
@compute @workgroup_size(64)
fn harness_pixels(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if (i >= harness_params.count) {
        return;
    }
    let r = pixel(vec2<i32>(i32(harness_in[i * 2u]), i32(harness_in[i * 2u + 1u])));
    harness_out[i * 5u] = harness_status();
    harness_store(i * 5u + 1u, r.xyz);
    harness_out[i * 5u + 4u] = select(0u, 1u, r.w != 0);
}
