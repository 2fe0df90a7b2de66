
// In: x, y (row 0 at the top). Out: status, fragColor (4 words, f32 bits).
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= harness_count) {
        return;
    }
    // Shadertoy's fragCoord: the pixel's centre, origin at the bottom left.
    vec2 fragCoord = vec2(float(harness_in[i * 2u]) + 0.5, (HARNESS_HEIGHT - 0.5) - float(harness_in[i * 2u + 1u]));
    vec4 fragColor = vec4(0.0);
    mainImage(fragColor, fragCoord);
    harness_out[i * 5u] = harness_runaway ? 2u : 0u;
    harness_out[i * 5u + 1u] = floatBitsToUint(fragColor.r);
    harness_out[i * 5u + 2u] = floatBitsToUint(fragColor.g);
    harness_out[i * 5u + 3u] = floatBitsToUint(fragColor.b);
    harness_out[i * 5u + 4u] = floatBitsToUint(fragColor.a);
}
