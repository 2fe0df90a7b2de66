
// In: op code, a, b. Out: status, result (s, e, m).
@compute @workgroup_size(64)
fn harness_ops(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if (i >= harness_params.count) {
        return;
    }
    let r = op(harness_in[i * 7u], harness_load(i * 7u + 1u), harness_load(i * 7u + 4u));
    harness_out[i * 4u] = harness_status();
    harness_store(i * 4u + 1u, r);
}
