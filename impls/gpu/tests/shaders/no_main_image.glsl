// A fragment shader written for another host: its entry point is main.
out vec4 color;
void main() {
    color = vec4(1.0);
}
