// The seed scene as a user's WGSL shader (docs/shaders.md): the harness
// calls `pixel` for every pixel and `sdf` for the sdf level. Written as a
// WGSL user would write it, with WGSL's built-ins (length, normalize, dot).

const MAX_DIST: f32 = 12.0;
const CAM: vec3<f32> = vec3<f32>(0.0, 1.5, 4.0);
const LIGHT: vec3<f32> = vec3<f32>(2.0, 5.0, -1.0);
const BACKGROUND: f32 = 0.835;

// x: signed distance, y: colour.
fn closest(a: vec2<f32>, b: vec2<f32>) -> vec2<f32> {
    return select(b, a, a.x < b.x);
}

fn scene(p: vec3<f32>) -> vec2<f32> {
    let cells = floor(p.x) + floor(p.z);
    let parity = cells - 2.0 * floor(cells / 2.0);
    let ground = vec2<f32>(p.y + 1.0, 1.0 + 0.7 * parity);
    let sphere = vec2<f32>(length(p - vec3<f32>(-1.5, 0.0, 0.0)) - 1.0, 0.7);
    let q = p - vec3<f32>(1.5, 0.0, 0.0);
    let torus = vec2<f32>(length(vec2<f32>(length(q.xz) - 1.0, q.y)) - 0.25, 0.7);
    return closest(closest(sphere, torus), ground);
}

fn sdf(p: vec3<f32>) -> vec2<f32> {
    return scene(p);
}

fn march(ro: vec3<f32>, rd: vec3<f32>, steps: i32) -> vec2<f32> {
    var depth = 0.0;
    var col = 0.0;
    for (var i = 0; i < steps; i++) {
        let s = scene(ro + depth * rd);
        col = s.y;
        depth += s.x;
        if (s.x < 0.01 || depth > MAX_DIST) {
            break;
        }
    }
    return vec2<f32>(depth, col);
}

fn normal(p: vec3<f32>) -> vec3<f32> {
    let h = 0.005;
    let k = vec2<f32>(1.0, -1.0);
    return normalize(k.xyy * scene(p + k.xyy * h).x + k.yyx * scene(p + k.yyx * h).x
        + k.yxy * scene(p + k.yxy * h).x + k.xxx * scene(p + k.xxx * h).x);
}

fn light(p: vec3<f32>, n: vec3<f32>) -> f32 {
    let l = normalize(LIGHT - p);
    let c = normalize(CAM - p);
    let a = clamp(dot(l, n), 0.0, 1.0);
    let r = 2.0 * a * n - l;
    return 0.9 * a * 0.7 + 0.7 * pow(clamp(dot(r, c), 0.0, 1.0), 4.0) * 0.5;
}

// coord: the pixel's centre, origin at the top left (WebGPU's fragment
// position); resolution: the image size.
fn pixel(coord: vec2<f32>, resolution: vec2<f32>) -> f32 {
    let px = coord - 0.5;
    let uv = vec2<f32>(px.x - 0.5 * resolution.x, -(px.y - 0.5 * resolution.y)) / resolution.y;
    let forward = normalize(CAM);
    let right = normalize(cross(vec3<f32>(0.0, 1.0, 0.0), forward));
    let up = cross(forward, right);
    let rd = mat3x3<f32>(right, up, forward) * normalize(vec3<f32>(uv, -1.0));
    let hit = march(CAM, rd, 64);
    if (hit.x > MAX_DIST) {
        return BACKGROUND;
    }
    let p = CAM + hit.x * rd;
    let n = normal(p);
    var value = hit.y * light(p, n) + 0.2 * BACKGROUND;
    let o = p + n * 0.01 * 2.0;
    if (march(o, normalize(LIGHT - p), 32).x < length(LIGHT - o)) {
        value *= 0.25;
    }
    return value;
}
