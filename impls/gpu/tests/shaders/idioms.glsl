// A Shadertoy shader in the site's usual idioms, written to check that they
// are accepted: a version line, precision, macros with arguments, a struct,
// inout parameters, while/continue, matrices, hash noise, smoothstep, mix.
#version 300 es
precision highp float;

#define PI 3.14159265
#define ROT(a) mat2(cos(a), -sin(a), sin(a), cos(a))
#define SAT(x) clamp(x, 0.0, 1.0)

struct Ray {
    vec3 origin;
    vec3 dir;
};

float hash(vec2 p) {
    p = fract(p * vec2(123.34, 456.21));
    p += dot(p, p + 45.32);
    return fract(p.x * p.y);
}

float noise(vec2 p) {
    vec2 i = floor(p);
    vec2 f = fract(p);
    vec2 u = f * f * (3.0 - 2.0 * f);
    return mix(mix(hash(i), hash(i + vec2(1.0, 0.0)), u.x),
               mix(hash(i + vec2(0.0, 1.0)), hash(i + vec2(1.0, 1.0)), u.x), u.y);
}

float fbm(vec2 p) {
    float v = 0.0;
    float a = 0.5;
    for (int i = 0; i < 5; ++i) {
        v += a * noise(p);
        p = ROT(0.5) * p * 2.0;
        a *= 0.5;
    }
    return v;
}

float sdBox(vec3 p, vec3 b) {
    vec3 q = abs(p) - b;
    return length(max(q, 0.0)) + min(max(q.x, max(q.y, q.z)), 0.0);
}

float map(vec3 p) {
    p.xz *= ROT(iTime * 0.3 + PI / 4.0);
    float box = sdBox(p, vec3(0.6));
    float ground = p.y + 0.8 + 0.1 * fbm(p.xz);
    return min(box, ground);
}

void advance(inout Ray r, float t) {
    r.origin += r.dir * t;
}

void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec2 uv = (2.0 * fragCoord - iResolution.xy) / iResolution.y;
    Ray ray = Ray(vec3(0.0, 0.5, 3.0), normalize(vec3(uv, -1.5)));
    float total = 0.0;
    int steps = 0;
    while (steps < 100) {
        steps++;
        float d = map(ray.origin);
        if (d < 0.001) break;
        if (d > 20.0) { total = -1.0; break; }
        advance(ray, d);
        total += d;
        if (steps % 2 == 0) continue;
    }
    vec3 sky = mix(vec3(0.6, 0.7, 0.9), vec3(0.2, 0.3, 0.6), SAT(uv.y));
    vec3 col = total < 0.0 ? sky : vec3(1.0 - total / 10.0) * smoothstep(0.0, 1.0, fbm(ray.origin.xz * 3.0));
    fragColor = vec4(pow(SAT(col), vec3(0.4545)), 1.0);
}
