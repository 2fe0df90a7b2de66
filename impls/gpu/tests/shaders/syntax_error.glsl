// A Shadertoy shader with a missing semicolon on line 5.
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec2 uv = fragCoord / iResolution.xy;
    float d = length(uv - 0.5)
    fragColor = vec4(vec3(d), 1.0);
}
