
// In: p (3 words, f32 bits). Out: status, distance, colour (f32 bits).
@compute @workgroup_size(64)
fn harness_sdf(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if (i >= harness_params.count) {
        return;
    }
    let p = vec3<f32>(
        bitcast<f32>(harness_in[i * 3u]),
        bitcast<f32>(harness_in[i * 3u + 1u]),
        bitcast<f32>(harness_in[i * 3u + 2u]),
    );
    let s = sdf(p);
    harness_out[i * 3u] = harness_status();
    harness_out[i * 3u + 1u] = bitcast<u32>(s.x);
    harness_out[i * 3u + 2u] = bitcast<u32>(s.y);
}
