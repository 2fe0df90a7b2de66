// The float formulation of the seed scene (spec section 7) in WGSL f32, in
// the spec's evaluation order. Lengths and dot products are written out
// (x*x + y*y + z*z) instead of using the built-ins, whose formulas are the
// driver's choice.
//
// `gpu-f32` runs this file as a shader of the harness's convention
// (docs/shaders.md): `pixel` and `sdf` at the end are what the wrapper
// calls. The scene kernels (scene_wgsl.rs) take its other items as a library.

struct Surface {
    sd: f32,
    col: f32,
}

fn dot3(a: vec3<f32>, b: vec3<f32>) -> f32 {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

fn length3(v: vec3<f32>) -> f32 {
    return sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
}

fn length2(a: f32, b: f32) -> f32 {
    return sqrt(a * a + b * b);
}

fn normalize3(v: vec3<f32>) -> vec3<f32> {
    let l = length3(v);
    return vec3<f32>(v.x / l, v.y / l, v.z / l);
}

fn cross3(a: vec3<f32>, b: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(a.y * b.z - b.y * a.z, a.z * b.x - b.z * a.x, a.x * b.y - b.x * a.y);
}

fn angle(a: vec3<f32>, b: vec3<f32>) -> f32 {
    return clamp(dot3(a, b), 0.0, 1.0);
}

fn unite(a: Surface, b: Surface) -> Surface {
    if (a.sd < b.sd) {
        return a;
    }
    return b;
}

const SPHERE_CENTRE: vec3<f32> = vec3<f32>(-1.5, 0.0, 0.0);
const TORUS_CENTRE: vec3<f32> = vec3<f32>(1.5, 0.0, 0.0);

fn scene(p: vec3<f32>) -> Surface {
    let floor_sd = p.y + 1.0;
    let cells = floor(p.x) + floor(p.z);
    let parity = cells - 2.0 * floor(cells / 2.0);
    let floor_col = 1.0 + 0.7 * parity;

    let sphere_sd = length3(p - SPHERE_CENTRE) - 1.0;

    let q = p - TORUS_CENTRE;
    let d1 = length2(q.x, q.z) - 1.0;
    let torus_sd = length2(d1, q.y) - 0.25;

    let objects = unite(Surface(sphere_sd, 0.7), Surface(torus_sd, 0.7));
    return unite(objects, Surface(floor_sd, floor_col));
}

const MAX_DIST: f32 = 12.0;
const CAM: vec3<f32> = vec3<f32>(0.0, 1.5, 4.0);
const LOOK_AT: vec3<f32> = vec3<f32>(0.0, 0.0, 0.0);
const WORLD_UP: vec3<f32> = vec3<f32>(0.0, 1.0, 0.0);
const LIGHT: vec3<f32> = vec3<f32>(2.0, 5.0, -1.0);
const H: f32 = 0.005;

// The surface reached: sd is the marched depth, col the last evaluation's.
fn march(ro: vec3<f32>, rd: vec3<f32>, steps: i32) -> Surface {
    var depth = 0.0;
    var col = 0.0;
    for (var k = 0; k < steps; k++) {
        let p = vec3<f32>(ro.x + depth * rd.x, ro.y + depth * rd.y, ro.z + depth * rd.z);
        let s = scene(p);
        col = s.col;
        depth = depth + s.sd;
        if (s.sd < 0.01 || depth > MAX_DIST) {
            break;
        }
    }
    return Surface(depth, col);
}

fn normal(p: vec3<f32>) -> vec3<f32> {
    let k = array<vec3<f32>, 4>(
        vec3<f32>(H, -H, -H),
        vec3<f32>(-H, -H, H),
        vec3<f32>(-H, H, -H),
        vec3<f32>(H, H, H),
    );
    var d: array<f32, 4>;
    for (var i = 0; i < 4; i++) {
        d[i] = scene(p + k[i]).sd;
    }
    var sum = k[0] * d[0];
    for (var i = 1; i < 4; i++) {
        sum = sum + k[i] * d[i];
    }
    return normalize3(sum);
}

fn light(p: vec3<f32>, n: vec3<f32>) -> f32 {
    let l = normalize3(LIGHT - p);
    let c = normalize3(CAM - p);
    let r = (2.0 * angle(l, n)) * n - l;
    let diffuse = (0.9 * angle(l, n)) * 0.7;
    let specular = (0.7 * pow(angle(r, c), 4.0)) * 0.5;
    return diffuse + specular;
}

// The shade of the image point (u, v), before clamping and dithering.
fn seed_shade(u: f32, v: f32) -> f32 {
    let forward = normalize3(CAM - LOOK_AT);
    let right = normalize3(cross3(WORLD_UP, forward));
    let up = cross3(forward, right);
    let r1 = vec3<f32>(right.x, up.x, forward.x);
    let r2 = vec3<f32>(right.y, up.y, forward.y);
    let r3 = vec3<f32>(right.z, up.z, forward.z);

    let d = normalize3(vec3<f32>(u, v, -1.0));
    let rd = vec3<f32>(dot3(r1, d), dot3(r2, d), dot3(r3, d));
    let hit = march(CAM, rd, 64);
    if (hit.sd > MAX_DIST) {
        return 0.835;
    }
    let p = vec3<f32>(CAM.x + hit.sd * rd.x, CAM.y + hit.sd * rd.y, CAM.z + hit.sd * rd.z);
    let n = normal(p);
    // 0.2 * 0.835 rounded in f32, as the f32 formulation computes it.
    let ambient = f32(0.2) * f32(0.835);
    var value = hit.col * light(p, n) + ambient;
    let ld = normalize3(LIGHT - p);
    let o = p + (n * 0.01) * 2.0;
    let shadow = march(o, ld, 32);
    if (shadow.sd < length3(LIGHT - o)) {
        value = value * 0.25;
    }
    return value;
}

// ---- The shader convention (docs/shaders.md) ----

// The shade of the pixel whose centre is `coord` (origin at the top left);
// the harness clamps it to [0, 1] and dithers it (spec section 7).
fn pixel(coord: vec2<f32>, resolution: vec2<f32>) -> f32 {
    // The pixel's integer coordinates (exact in f32), then the spec's u, v.
    let x = coord.x - 0.5;
    let y = coord.y - 0.5;
    let u = (x - 0.5 * 512.0) / 256.0;
    let v = -((y - 0.5 * 256.0) / 256.0);
    return seed_shade(u, v);
}

// The scene's distance and colour at p.
fn sdf(p: vec3<f32>) -> vec2<f32> {
    let s = scene(p);
    return vec2<f32>(s.sd, s.col);
}
