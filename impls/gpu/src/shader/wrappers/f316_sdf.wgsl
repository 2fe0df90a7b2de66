
// In: p (three triples). Out: status, distance (s, e, m), colour (s, e, m).
@compute @workgroup_size(64)
fn harness_sdf(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if (i >= harness_params.count) {
        return;
    }
    let p = array<vec3<i32>, 3>(harness_load(i * 9u), harness_load(i * 9u + 3u), harness_load(i * 9u + 6u));
    let r = sdf(p);
    harness_out[i * 7u] = harness_status();
    harness_store(i * 7u + 1u, r[0]);
    harness_store(i * 7u + 4u, r[1]);
}
