// Float316 (spec sections 1-6) in WGSL integer arithmetic.
//
// Every field is a Jack word: an i32 that always holds a sign-extended 16-bit
// value. Additions, subtractions and products are wrapped back to 16 bits
// with `w` before any comparison, division or store; since wrapping is a ring
// homomorphism, wrapping once after a chain of + - * equals wrapping after
// each step. WGSL's i32 `/` truncates toward zero, as Jack's Math.divide.
//
// A computation stops being meaningful at its first failure (the Jack
// program would halt on Sys.error or loop forever): `fail` records the first
// failure in `status` and the computation runs on with bounded loops; the
// kernel then reports the status instead of the value.
//
// `gpu-f316` runs this file as a Float316 shader of the harness's convention
// (docs/shaders.md): `pixel`, `sdf` and `op` at the end are what the wrapper
// calls, `status` is read after each call, and `harness_bayer` is the
// wrapper's dither matrix. The scene kernels (scene_wgsl.rs) take its other
// items as a library.

struct F {
    s: i32,
    e: i32,
    m: i32,
}

struct V {
    x: F,
    y: F,
    z: F,
}

struct Surface {
    sd: F,
    col: F,
}

// Outcome kinds, as decoded in float316.rs (the convention's `status`). A Sys.error code is stored in the
// bits above the kind: kind | (code << 4).
const K_VALUE: i32 = 0;
const K_SYS_ERROR: i32 = 1;
const K_HANG: i32 = 2;
const K_OUT_OF_DOMAIN: i32 = 3;

var<private> status: i32 = 0;

fn fail(word: i32) {
    if (status == 0) {
        status = word;
    }
}

fn sys_error(code: i32) {
    fail(K_SYS_ERROR | (code << 4u));
}

// Reduce to a Jack word: keep the low 16 bits, sign-extended.
fn w(x: i32) -> i32 {
    return extractBits(x, 0u, 16u);
}

const ZERO: F = F(0, 0, 0);
const ONE: F = F(0, 127, 8192);
const NEG_ONE: F = F(1, 127, 8192);
const ONE_HALF: F = F(0, 127, 12288);
const HALF: F = F(0, 126, 8192);

fn is_zero(a: F) -> bool {
    return a.e == 0 && a.m == 0;
}

fn negated(a: F) -> F {
    return F(1 - (a.s & 1), a.e, a.m);
}

// ---- Operations (spec section 2) ----

fn gt(a: F, b: F) -> bool {
    if (a.s != b.s) {
        return a.s == 0 && b.s == 1;
    }
    if (a.s == 0) {
        if (a.e != b.e) {
            return a.e > b.e;
        }
        return a.m > b.m;
    }
    if (a.e != b.e) {
        return a.e < b.e;
    }
    return a.m < b.m;
}

// Double m and decrement e while m < 8192. A negative m doubled 16 times
// wraps to 0 and m = 0 never ends (the Jack program hangs), so 17 rounds
// always decide: the loop ends or m is 0.
fn normalise_up(m0: i32, e0: i32) -> F {
    var m = m0;
    var e = e0;
    for (var k = 0; k < 17; k++) {
        if (m >= 8192) {
            break;
        }
        if (m == 0) {
            fail(K_HANG);
            break;
        }
        m = w(m * 2);
        e = w(e - 1);
    }
    return F(0, e, m);
}

fn add(a: F, b: F) -> F {
    var big = a;
    var small = b;
    if (b.e > a.e || (b.e == a.e && b.m > a.m)) {
        big = b;
        small = a;
    }
    if (is_zero(small)) {
        return big;
    }
    if (a.s != b.s && a.e == b.e && a.m == b.m) {
        return ZERO;
    }
    // Halve small.m once per unit of the exponent difference; after 16
    // halvings (truncating toward zero) every Jack word is 0.
    var sm = small.m;
    let shifts = min(w(big.e - small.e), 16);
    for (var k = 0; k < shifts; k++) {
        sm = sm / 2;
    }
    if (a.s == b.s) {
        var m = w(big.m + sm);
        var e = big.e;
        if (m > 16383) {
            m = m / 2;
            e = w(e + 1);
        }
        return F(big.s, e, m);
    }
    let n = normalise_up(w(big.m - sm), big.e);
    return F(big.s, n.e, n.m);
}

fn sub(a: F, b: F) -> F {
    return add(a, negated(b));
}

fn mul(a: F, b: F) -> F {
    let s = (a.s + b.s) & 1;
    if (is_zero(a) || is_zero(b)) {
        return F(s, 0, 0);
    }
    var e = w(a.e + b.e - 126);
    let ah = a.m / 128;
    let al = a.m & 127;
    let bh = b.m / 128;
    let bl = b.m & 127;
    let mid = w(ah * bl + al * bh);
    var m = w(ah * bh + mid / 128);
    // 0 < m < 8192 reaches 8192 within 13 doublings.
    if (m > 0) {
        for (var k = 0; k < 13 && m < 8192; k++) {
            m = m * 2;
            e = w(e - 1);
        }
    }
    return F(s, e, m);
}

fn div(a: F, b: F) -> F {
    let s = (a.s + b.s) & 1;
    if (is_zero(a)) {
        return F(s, 0, 0);
    }
    if (is_zero(b)) {
        sys_error(1);
        return F(s, 0, 0);
    }
    var r = a.m;
    var d = b.m;
    var q = 0;
    for (var i = 13; i >= 0; i--) {
        if (r >= d) {
            q = q + (1 << u32(i));
            r = w(r - d);
        }
        d = d / 2;
    }
    // 0 <= q <= 16383: the normalisation ends unless q = 0.
    let n = normalise_up(q, w(a.e + 127 - b.e));
    return F(s, n.e, n.m);
}

fn halve(a: F) -> F {
    if (a.e > 0) {
        return F(a.s, w(a.e - 1), a.m);
    }
    return a;
}

fn double316(a: F) -> F {
    if (a.e > 0) {
        return F(a.s, w(a.e + 1), a.m);
    }
    return a;
}

fn quarter(a: F) -> F {
    if (a.e > 0) {
        return F(a.s, w(a.e - 2), a.m);
    }
    return a;
}

fn floor316(a: F) -> F {
    if (a.e < 127) {
        if (a.s == 0) {
            return ZERO;
        }
        return NEG_ONE;
    }
    let i = a.e - 127;
    if (i > 13) {
        fail(K_OUT_OF_DOMAIN);
        return a;
    }
    let mp = a.m & ~((1 << u32(13 - i)) - 1);
    let r = F(a.s, a.e, mp);
    if (a.s == 1 && mp != a.m) {
        return add(r, NEG_ONE);
    }
    return r;
}

fn mod2(a: F) -> F {
    if (a.m == 0) {
        return ZERO;
    }
    let i = w(a.e - 127);
    if (i < 0 || i > 13) {
        fail(K_OUT_OF_DOMAIN);
        return ZERO;
    }
    if ((a.m & (1 << u32(13 - i))) != 0) {
        return ONE;
    }
    return ZERO;
}

fn sqrt316(x: F) -> F {
    return sqrt316_steps(x, 2);
}

// sqrt with `steps` Newton steps (the spec takes 2; a tuned call site of a
// scene may take 1).
fn sqrt316_steps(x: F, steps: i32) -> F {
    if (x.s == 1) {
        sys_error(2);
        return x;
    }
    var g = F(0, w(x.e / 2 + 63), x.m);
    if ((x.e & 1) == 1) {
        g.e = w(x.e / 2 + 64);
    }
    for (var k = 0; k < steps; k++) {
        let t = div(x, g);
        g = halve(add(g, t));
    }
    return F(0, g.e, g.m);
}

fn inv_sqrt(x: F) -> F {
    return inv_sqrt_steps(x, 2);
}

// invSqrt with `steps` Newton steps (the spec takes 2).
fn inv_sqrt_steps(x: F, steps: i32) -> F {
    if (x.s == 1) {
        sys_error(3);
        return x;
    }
    let x2 = F(0, w(x.e - 1), x.m);
    var y = F(0, w(190 - x.e / 2), 8192);
    for (var k = 0; k < steps; k++) {
        var t = mul(x2, y);
        t = mul(t, y);
        t = sub(ONE_HALF, t);
        y = mul(y, t);
    }
    return F(0, y.e, y.m);
}

// ---- Vectors (spec section 3) ----

fn vadd(a: V, b: V) -> V {
    return V(add(a.x, b.x), add(a.y, b.y), add(a.z, b.z));
}

fn vsub(a: V, b: V) -> V {
    return V(sub(a.x, b.x), sub(a.y, b.y), sub(a.z, b.z));
}

fn scale(a: V, k: F) -> V {
    return V(mul(a.x, k), mul(a.y, k), mul(a.z, k));
}

fn vdot(a: V, b: V) -> F {
    return add(add(mul(a.x, b.x), mul(a.y, b.y)), mul(a.z, b.z));
}

fn vlength(v: V) -> F {
    return sqrt316(vdot(v, v));
}

fn vnormalize(v: V) -> V {
    return scale(v, inv_sqrt(vdot(v, v)));
}

fn vcross(a: V, b: V) -> V {
    return V(
        sub(mul(a.y, b.z), mul(b.y, a.z)),
        sub(mul(a.z, b.x), mul(b.z, a.x)),
        sub(mul(a.x, b.y), mul(b.x, a.y)),
    );
}

fn angle(a: V, b: V) -> F {
    let d = vdot(a, b);
    if (d.s == 1) {
        return ZERO;
    }
    if (gt(d, ONE)) {
        return ONE;
    }
    return d;
}

// ---- Scene (spec section 4) ----

const COL_OBJECT: F = F(0, 126, 11468); // 0.7
const SPHERE_CENTRE: V = V(F(1, 127, 12288), F(0, 0, 0), F(0, 0, 0)); // (-1.5, 0, 0)
const TORUS_CENTRE: V = V(F(0, 127, 12288), F(0, 0, 0), F(0, 0, 0)); // (1.5, 0, 0)
const TUBE: F = F(0, 125, 8192); // 0.25

fn unite(a: Surface, b: Surface) -> Surface {
    if (gt(b.sd, a.sd)) {
        return a;
    }
    return b;
}

fn scene(p: V) -> Surface {
    let floor_sd = add(p.y, ONE);
    let parity = mod2(add(floor316(p.x), floor316(p.z)));
    let floor_col = add(mul(parity, COL_OBJECT), ONE);

    let sphere_sd = sub(vlength(vsub(p, SPHERE_CENTRE)), ONE);

    let q = vsub(p, TORUS_CENTRE);
    let d1 = sub(sqrt316(add(mul(q.x, q.x), mul(q.z, q.z))), ONE);
    let torus_sd = sub(sqrt316(add(mul(d1, d1), mul(q.y, q.y))), TUBE);

    let objects = unite(Surface(sphere_sd, COL_OBJECT), Surface(torus_sd, COL_OBJECT));
    return unite(objects, Surface(floor_sd, floor_col));
}

// ---- Ray marching, normals, light (spec section 5) ----

const PRECISION: F = F(0, 120, 10485); // 0.01
const PRECISION2: F = F(0, 121, 10485); // 0.02
const MAX_DIST: F = F(0, 130, 12288); // 12.0
const H: F = F(0, 119, 10485); // 0.005
const NEG_H: F = F(1, 119, 10485);
const CAM: V = V(F(0, 0, 0), F(0, 127, 12288), F(0, 129, 8192)); // (0, 1.5, 4)
const LOOK_AT: V = V(F(0, 0, 0), F(0, 0, 0), F(0, 0, 0));
const WORLD_UP: V = V(F(0, 0, 0), F(0, 127, 8192), F(0, 0, 0));
const LIGHT: V = V(F(0, 128, 8192), F(0, 129, 10240), F(1, 127, 8192)); // (2, 5, -1)
const KD: F = F(0, 126, 10321); // 0.63
const KS: F = F(0, 125, 11468); // 0.35
const AMBIENT: F = F(0, 124, 10944); // 0.167
const BACKGROUND: F = F(0, 126, 13680); // 0.835

// march(ro, rd, steps): the final depth and the colour of the last evaluation.
fn march(ro: V, rd: V, steps: i32) -> Surface {
    var depth = ZERO;
    var col = ZERO;
    for (var k = 0; k < steps; k++) {
        let p = vadd(ro, scale(rd, depth));
        let s = scene(p);
        col = s.col;
        depth = add(depth, s.sd);
        if (gt(PRECISION, s.sd) || gt(depth, MAX_DIST)) {
            break;
        }
    }
    return Surface(depth, col);
}

fn normal(p: V) -> V {
    let k = array<V, 4>(
        V(H, NEG_H, NEG_H),
        V(NEG_H, NEG_H, H),
        V(NEG_H, H, NEG_H),
        V(H, H, H),
    );
    var d: array<F, 4>;
    for (var i = 0; i < 4; i++) {
        d[i] = scene(vadd(p, k[i])).sd;
    }
    var sum = scale(k[0], d[0]);
    for (var i = 1; i < 4; i++) {
        sum = vadd(sum, scale(k[i], d[i]));
    }
    return vnormalize(sum);
}

fn light(p: V, n: V) -> F {
    let l = vnormalize(vsub(LIGHT, p));
    let c = vnormalize(vsub(CAM, p));
    let a = double316(angle(l, n));
    let r = vsub(scale(n, a), l);
    let diffuse = mul(KD, angle(l, n));
    var s = angle(r, c);
    s = mul(s, s);
    s = mul(s, s);
    s = mul(s, KS);
    return add(diffuse, s);
}

// The shade of the image point (u, v), before clamping and dithering.
fn seed_shade(u: F, v: F) -> F {
    let forward = vnormalize(vsub(CAM, LOOK_AT));
    let right = vnormalize(vcross(WORLD_UP, forward));
    let up = vcross(forward, right);
    let r1 = V(right.x, up.x, forward.x);
    let r2 = V(right.y, up.y, forward.y);
    let r3 = V(right.z, up.z, forward.z);

    let d = vnormalize(V(u, v, NEG_ONE));
    let rd = V(vdot(r1, d), vdot(r2, d), vdot(r3, d));
    let hit = march(CAM, rd, 64);
    if (gt(hit.sd, MAX_DIST)) {
        return BACKGROUND;
    }
    let p = vadd(CAM, scale(rd, hit.sd));
    let n = normal(p);
    var value = add(mul(hit.col, light(p, n)), AMBIENT);
    let ld = vnormalize(vsub(LIGHT, p));
    let o = vadd(scale(n, PRECISION2), p);
    let shadow = march(o, ld, 32);
    if (gt(vlength(vsub(LIGHT, o)), shadow.sd)) {
        value = quarter(value);
    }
    return value;
}

// ---- Image (spec section 6) ----

// The exact Float316 of a non-negative integer n < 16384 (what the Jack
// program's counter reaches by adding 1.0 n times: every step is exact).
fn from_int(n: i32) -> F {
    if (n == 0) {
        return ZERO;
    }
    let top = i32(firstLeadingBit(u32(n)));
    return F(0, 127 + top, n << u32(13 - top));
}

// The dither threshold (B - 32) / 64 as an exact Float316 (`harness_bayer`
// is the shader wrapper's Bayer matrix).
fn dither(x: i32, y: i32) -> F {
    let k = harness_bayer(u32(x), u32(y)) - 32;
    if (k == 0) {
        return ZERO;
    }
    let mag = from_int(abs(k));
    return F(select(0, 1, k < 0), mag.e - 6, mag.m);
}

const C128: F = F(0, 134, 8192);
const C256: F = F(0, 135, 8192);

struct Shade {
    value: F,
    white: bool,
}

// The clamped value of pixel (x, y) before dithering, and whether the
// dithered pixel is white.
fn image_pixel(x: i32, y: i32) -> Shade {
    let u = div(sub(from_int(x), C256), C256);
    let v = negated(div(sub(from_int(y), C128), C256));
    var value = seed_shade(u, v);
    if (gt(value, ONE)) {
        value = ONE;
    } else if (value.s == 1) {
        value = ZERO;
    }
    let white = gt(add(value, dither(x, y)), HALF);
    return Shade(value, white);
}

// ---- Operations by code ----

// Op codes follow common::Op::ALL.
fn apply(op: u32, a: F, b: F) -> F {
    switch op {
        case 0u: {
            return F(0, 0, select(0, 1, gt(a, b)));
        }
        case 1u: {
            return add(a, b);
        }
        case 2u: {
            return sub(a, b);
        }
        case 3u: {
            return mul(a, b);
        }
        case 4u: {
            return div(a, b);
        }
        case 5u: {
            return floor316(a);
        }
        case 6u: {
            return mod2(a);
        }
        case 7u: {
            return sqrt316(a);
        }
        case 8u: {
            return inv_sqrt(a);
        }
        case 9u: {
            return halve(a);
        }
        case 10u: {
            return double316(a);
        }
        default: {
            return quarter(a);
        }
    }
}

// ---- The shader convention (docs/shaders.md) ----

fn f316_of(t: vec3<i32>) -> F {
    return F(t.x, t.y, t.z);
}

fn fields_of(a: F) -> vec3<i32> {
    return vec3<i32>(a.s, a.e, a.m);
}

// One operation (codes as in `apply`; gt answers 0 or 1 in m).
fn op(code: u32, a: vec3<i32>, b: vec3<i32>) -> vec3<i32> {
    return fields_of(apply(code, f316_of(a), f316_of(b)));
}

// The scene's distance and colour at p.
fn sdf(p: array<vec3<i32>, 3>) -> array<vec3<i32>, 2> {
    let s = scene(V(f316_of(p[0]), f316_of(p[1]), f316_of(p[2])));
    return array<vec3<i32>, 2>(fields_of(s.sd), fields_of(s.col));
}

// Pixel (x, y), row 0 at the top: the clamped shade before dithering and
// the dithered bit.
fn pixel(coord: vec2<i32>) -> vec4<i32> {
    let shade = image_pixel(coord.x, coord.y);
    return vec4<i32>(shade.value.s, shade.value.e, shade.value.m, select(0, 1, shade.white));
}
