// A shader that never ends: the loop's condition cannot become false.
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    float t = 0.0;
    for (int i = 0; i >= 0; i += 0) {
        t += 1.0;
    }
    fragColor = vec4(t);
}
