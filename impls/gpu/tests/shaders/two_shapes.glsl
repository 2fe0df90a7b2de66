// A turned box and a ball on a floor, lit from above: a Shadertoy shader
// written as an outsider would, declared by following docs/shaders.md alone
// (the acceptance rehearsal of the shader kind). Its idioms: #define, mat2
// rotation of a swizzle (`bp.xz *= Rot(a)`), an int `for` loop with
// `break`, integer literals in float constructors, `.5`-style literals.
#define MAX_STEPS 100
#define MAX_DIST 20.0
#define SURF_DIST 0.001

mat2 Rot(float a) {
    float s = sin(a), c = cos(a);
    return mat2(c, -s, s, c);
}

float sdBox(vec3 p, vec3 b) {
    vec3 q = abs(p) - b;
    return length(max(q, 0.0)) + min(max(q.x, max(q.y, q.z)), 0.0);
}

float GetDist(vec3 p) {
    float plane = p.y;
    vec3 bp = p - vec3(-1.0, 0.75, 6.0);
    bp.xz *= Rot(0.6);
    float box = sdBox(bp, vec3(0.75)) - 0.05;
    float sphere = length(p - vec3(1.2, 1.0, 6.0)) - 1.0;
    return min(plane, min(box, sphere));
}

float RayMarch(vec3 ro, vec3 rd) {
    float dO = 0.0;
    for (int i = 0; i < MAX_STEPS; i++) {
        vec3 p = ro + rd * dO;
        float dS = GetDist(p);
        dO += dS;
        if (dO > MAX_DIST || abs(dS) < SURF_DIST) break;
    }
    return dO;
}

vec3 GetNormal(vec3 p) {
    vec2 e = vec2(0.001, 0);
    vec3 n = GetDist(p) - vec3(GetDist(p - e.xyy), GetDist(p - e.yxy), GetDist(p - e.yyx));
    return normalize(n);
}

float GetLight(vec3 p) {
    vec3 lightPos = vec3(2, 5, 3);
    vec3 l = normalize(lightPos - p);
    vec3 n = GetNormal(p);
    float dif = clamp(dot(n, l), 0., 1.);
    float d = RayMarch(p + n * SURF_DIST * 2., l);
    if (d < length(lightPos - p)) dif *= .1;
    return dif;
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec2 uv = (fragCoord - .5 * iResolution.xy) / iResolution.y;
    vec3 ro = vec3(0, 1, 0);
    vec3 rd = normalize(vec3(uv.x, uv.y, 1));
    float d = RayMarch(ro, rd);
    vec3 p = ro + rd * d;
    float dif = GetLight(p);
    vec3 col = vec3(dif);
    col = mix(col, vec3(.6, .7, .9), smoothstep(10., MAX_DIST, d));
    col = pow(col, vec3(.4545));
    fragColor = vec4(col, 1.0);
}
