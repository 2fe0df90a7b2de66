
// A Float316 number is vec3<i32>(s, e, m), one Jack word per field.
fn harness_load(base: u32) -> vec3<i32> {
    return vec3<i32>(
        bitcast<i32>(harness_in[base]),
        bitcast<i32>(harness_in[base + 1u]),
        bitcast<i32>(harness_in[base + 2u]),
    );
}

fn harness_store(base: u32, v: vec3<i32>) {
    harness_out[base] = bitcast<u32>(v.x);
    harness_out[base + 1u] = bitcast<u32>(v.y);
    harness_out[base + 2u] = bitcast<u32>(v.z);
}
