
// In: p (3 words, f32 bits). Out: status, distance, colour (f32 bits).
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= harness_count) {
        return;
    }
    vec3 p = vec3(uintBitsToFloat(harness_in[i * 3u]), uintBitsToFloat(harness_in[i * 3u + 1u]), uintBitsToFloat(harness_in[i * 3u + 2u]));
    vec2 s = sdf(p);
    harness_out[i * 3u] = harness_runaway ? 2u : 0u;
    harness_out[i * 3u + 1u] = floatBitsToUint(s.x);
    harness_out[i * 3u + 2u] = floatBitsToUint(s.y);
}
