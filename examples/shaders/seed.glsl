// The seed scene (a sphere, a torus and a checkered floor under one light),
// ported to a Shadertoy shader: paste it into shadertoy.com's editor and it
// runs there as it is; the harness runs the same file unmodified
// (harness.toml: kind = "shader", docs/shaders.md).
//
// Written the way Shadertoy code is written, with GLSL's built-ins
// (length, normalize, dot, mod, pow, a mat3 camera): their rounding is the
// driver's, which is part of what the comparison against ref-f64 measures.

const float MAX_DIST = 12.0;
const float EPSILON = 0.01;
const vec3 CAM = vec3(0.0, 1.5, 4.0);
const vec3 LIGHT = vec3(2.0, 5.0, -1.0);
const float BACKGROUND = 0.835;

// x: signed distance, y: colour (grey level of the material).
vec2 opUnion(vec2 a, vec2 b) {
    return a.x < b.x ? a : b;
}

float sdSphere(vec3 p, float r) {
    return length(p) - r;
}

float sdTorus(vec3 p, vec2 t) {
    vec2 q = vec2(length(p.xz) - t.x, p.y);
    return length(q) - t.y;
}

vec2 map(vec3 p) {
    float checker = mod(floor(p.x) + floor(p.z), 2.0);
    vec2 floorPlane = vec2(p.y + 1.0, 1.0 + 0.7 * checker);
    vec2 sphere = vec2(sdSphere(p - vec3(-1.5, 0.0, 0.0), 1.0), 0.7);
    vec2 torus = vec2(sdTorus(p - vec3(1.5, 0.0, 0.0), vec2(1.0, 0.25)), 0.7);
    return opUnion(opUnion(sphere, torus), floorPlane);
}

// The harness's sdf level: the scene's distance and colour at p.
vec2 sdf(vec3 p) {
    return map(p);
}

// Sphere tracing: x is the depth reached, y the colour last seen.
vec2 march(vec3 ro, vec3 rd, int steps) {
    float depth = 0.0;
    float col = 0.0;
    for (int i = 0; i < steps; i++) {
        vec2 s = map(ro + depth * rd);
        col = s.y;
        depth += s.x;
        if (s.x < EPSILON || depth > MAX_DIST) break;
    }
    return vec2(depth, col);
}

// The tetrahedron technique for the gradient.
vec3 calcNormal(vec3 p) {
    const float h = 0.005;
    const vec2 k = vec2(1.0, -1.0);
    return normalize(k.xyy * map(p + k.xyy * h).x +
                     k.yyx * map(p + k.yyx * h).x +
                     k.yxy * map(p + k.yxy * h).x +
                     k.xxx * map(p + k.xxx * h).x);
}

float lighting(vec3 p, vec3 n) {
    vec3 l = normalize(LIGHT - p);
    vec3 v = normalize(CAM - p);
    float ndotl = clamp(dot(l, n), 0.0, 1.0);
    vec3 r = 2.0 * ndotl * n - l;
    float diffuse = 0.9 * ndotl * 0.7;
    float specular = 0.7 * pow(clamp(dot(r, v), 0.0, 1.0), 4.0) * 0.5;
    return diffuse + specular;
}

mat3 lookAt(vec3 eye, vec3 target, vec3 worldUp) {
    vec3 forward = normalize(eye - target);
    vec3 right = normalize(cross(worldUp, forward));
    vec3 up = cross(forward, right);
    return mat3(right, up, forward);
}

void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    // The original's pixel grid: (0, 0) is the top-left pixel, the image
    // is 512x256 and the view spans 2 units across its width.
    vec2 px = vec2(fragCoord.x - 0.5, iResolution.y - 0.5 - fragCoord.y);
    vec2 uv = vec2(px.x - 0.5 * iResolution.x, -(px.y - 0.5 * iResolution.y)) / iResolution.y;

    vec3 rd = lookAt(CAM, vec3(0.0), vec3(0.0, 1.0, 0.0)) * normalize(vec3(uv, -1.0));
    vec2 hit = march(CAM, rd, 64);

    float value = BACKGROUND;
    if (hit.x <= MAX_DIST) {
        vec3 p = CAM + hit.x * rd;
        vec3 n = calcNormal(p);
        value = hit.y * lighting(p, n) + 0.2 * BACKGROUND;
        vec3 o = p + n * 0.01 * 2.0;
        if (march(o, normalize(LIGHT - p), 32).x < length(LIGHT - o)) {
            value *= 0.25;
        }
    }
    fragColor = vec4(vec3(clamp(value, 0.0, 1.0)), 1.0);
}
