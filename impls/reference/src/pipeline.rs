//! The scene, ray marcher, normals, light, camera ray, pixel and image of
//! spec sections 4-6, written once and generic over the [`Engine`]. The
//! float formulation (section 7) differs only through the engine's hooks.
//!
//! Evaluation order follows Jack's (arguments left to right, both operands
//! of `|` evaluated), so Float316 traces line up with the Jack program's.

use crate::consts::Consts;
use crate::engine::{Decision, Engine, R};
use crate::vec3::{self, V3};
use common::image_consts::{HEIGHT, WIDTH};
use rayon::prelude::*;

/// A signed distance and the colour of the nearest surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surface<N> {
    pub sd: N,
    pub col: N,
}

/// `union(a, b)`: a if `gt(b.sd, a.sd)`, else b.
fn union<E: Engine>(e: &mut E, a: Surface<E::N>, b: Surface<E::N>) -> R<Surface<E::N>> {
    let keep_a = e.gt(b.sd, a.sd)?;
    Ok(if e.decide(Decision::Union, [b.sd, a.sd], keep_a) {
        a
    } else {
        b
    })
}

/// The floor plane with its checkerboard colour.
fn floor<E: Engine>(e: &mut E, k: &Consts<E::N>, p: V3<E::N>) -> R<Surface<E::N>> {
    e.frame(
        || "floor".into(),
        |e| {
            let sd = e.add(p.y, k.floor_offset)?;
            let fx = e.floor(p.x)?;
            let fz = e.floor(p.z)?;
            let sum = e.add(fx, fz)?;
            let parity = e.mod2(sum)?;
            let odd = E::to_f64(parity) != 0.0;
            // An engine that overrides the decision gets the other square.
            let parity = match (odd, e.decide(Decision::Checker, [p.x, p.z], odd)) {
                (was, now) if was == now => parity,
                (_, true) => k.one,
                (_, false) => k.zero,
            };
            let col = if e.contracts() {
                e.mul_add(parity, k.floor_checker, k.floor_colour)?
            } else {
                let checker = e.mul(parity, k.floor_checker)?;
                e.add(checker, k.floor_colour)?
            };
            Ok(Surface { sd, col })
        },
    )
}

/// The sphere: `length(p - centre) - radius`.
fn sphere<E: Engine>(e: &mut E, k: &Consts<E::N>, p: V3<E::N>) -> R<Surface<E::N>> {
    e.frame(
        || "sphere".into(),
        |e| {
            let q = vec3::sub(e, p, k.sphere_centre)?;
            let l = vec3::length(e, q)?;
            let sd = e.sub(l, k.sphere_radius)?;
            Ok(Surface {
                sd,
                col: k.sphere_colour,
            })
        },
    )
}

/// The torus around the y axis.
fn torus<E: Engine>(e: &mut E, k: &Consts<E::N>, p: V3<E::N>) -> R<Surface<E::N>> {
    e.frame(
        || "torus".into(),
        |e| {
            let q = vec3::sub(e, p, k.torus_centre)?;
            let xx = e.mul(q.x, q.x)?;
            let r2 = if e.contracts() {
                e.mul_add(q.z, q.z, xx)?
            } else {
                let zz = e.mul(q.z, q.z)?;
                e.add(xx, zz)?
            };
            let r = e.sqrt(r2)?;
            let d1 = e.sub(r, k.ring_radius)?;
            let dd = e.mul(d1, d1)?;
            let t2 = if e.contracts() {
                e.mul_add(q.y, q.y, dd)?
            } else {
                let yy = e.mul(q.y, q.y)?;
                e.add(dd, yy)?
            };
            let t = e.sqrt(t2)?;
            let sd = e.sub(t, k.tube_radius)?;
            Ok(Surface {
                sd,
                col: k.torus_colour,
            })
        },
    )
}

/// `scene(p) = union(union(sphere, torus), floor)`, evaluated floor,
/// sphere, torus.
pub fn sdf<E: Engine>(e: &mut E, k: &Consts<E::N>, p: V3<E::N>) -> R<Surface<E::N>> {
    e.frame(
        || "scene".into(),
        |e| {
            let fl = floor(e, k, p)?;
            let sp = sphere(e, k, p)?;
            let to = torus(e, k, p)?;
            let objects = union(e, sp, to)?;
            union(e, objects, fl)
        },
    )
}

/// March from `ro` along `rd` for up to `steps` steps; returns the depth
/// and the colour of the last evaluation.
fn march<E: Engine>(
    e: &mut E,
    k: &Consts<E::N>,
    ro: V3<E::N>,
    rd: V3<E::N>,
    steps: u32,
    label: &'static str,
) -> R<(E::N, E::N)> {
    let mut depth = k.zero;
    let mut col = k.zero;
    for i in 0..steps {
        let stop = e.frame(
            || format!("{label} step {i}"),
            |e| {
                let p = vec3::add_scaled(e, ro, rd, depth)?;
                let s = sdf(e, k, p)?;
                depth = e.add(depth, s.sd)?;
                col = s.col;
                let hit = e.gt(k.precision, s.sd)?;
                let hit = e.decide(Decision::MarchHit, [k.precision, s.sd], hit);
                let far = e.gt(depth, k.max_distance)?;
                let far = e.decide(Decision::MarchFar, [depth, k.max_distance], far);
                Ok(hit | far)
            },
        )?;
        if stop {
            break;
        }
    }
    Ok((depth, col))
}

/// The normal at `p` from four tetrahedral samples.
fn normal<E: Engine>(e: &mut E, k: &Consts<E::N>, p: V3<E::N>) -> R<V3<E::N>> {
    e.frame(
        || "normal".into(),
        |e| {
            let mut d = [k.zero; 4];
            for (di, ki) in d.iter_mut().zip(k.normal_k) {
                let q = vec3::add(e, p, ki)?;
                *di = sdf(e, k, q)?.sd;
            }
            let mut n = vec3::scale(e, k.normal_k[0], d[0])?;
            for (&ki, &di) in k.normal_k.iter().zip(&d).skip(1) {
                n = vec3::add_scaled(e, n, ki, di)?;
            }
            vec3::normalize(e, n)
        },
    )
}

/// Diffuse plus specular light at `p` with normal `n`.
fn light<E: Engine>(e: &mut E, k: &Consts<E::N>, p: V3<E::N>, n: V3<E::N>) -> R<E::N> {
    e.frame(
        || "light".into(),
        |e| {
            let l = vec3::sub(e, k.light, p)?;
            let l = vec3::normalize(e, l)?;
            let c = vec3::sub(e, k.camera, p)?;
            let c = vec3::normalize(e, c)?;
            let a = vec3::angle(e, l, n, k.one, k.zero)?;
            let a = e.double(a)?;
            let r = if e.contracts() {
                let minus_l = V3::new(E::negate(l.x), E::negate(l.y), E::negate(l.z));
                vec3::add_scaled(e, minus_l, n, a)?
            } else {
                let na = vec3::scale(e, n, a)?;
                vec3::sub(e, na, l)?
            };
            let a = vec3::angle(e, l, n, k.one, k.zero)?;
            let diffuse = e.diffuse(k, a)?;
            let s = vec3::angle(e, r, c, k.one, k.zero)?;
            let specular = e.specular(k, s)?;
            e.add(diffuse, specular)
        },
    )
}

/// The spec's `pixel(u, v)`: the shade of the camera ray through (u, v),
/// before clamping.
pub fn shade<E: Engine>(e: &mut E, k: &Consts<E::N>, u: E::N, v: E::N) -> R<E::N> {
    let d = vec3::normalize(e, V3::new(u, v, k.view_z))?;
    let rd = e.frame(
        || "ray".into(),
        |e| {
            Ok(V3::new(
                vec3::dot(e, k.rows[0], d)?,
                vec3::dot(e, k.rows[1], d)?,
                vec3::dot(e, k.rows[2], d)?,
            ))
        },
    )?;
    let (depth, col) = march(e, k, k.camera, rd, k.view_steps, "march")?;
    let miss = e.gt(depth, k.max_distance)?;
    if e.decide(Decision::Miss, [depth, k.max_distance], miss) {
        return Ok(k.background);
    }
    let p = vec3::add_scaled(e, k.camera, rd, depth)?;
    let n = normal(e, k, p)?;
    let lit = light(e, k, p, n)?;
    let value = if e.contracts() {
        let ambient = e.ambient(k)?;
        e.mul_add(col, lit, ambient)?
    } else {
        let value = e.mul(col, lit)?;
        let ambient = e.ambient(k)?;
        e.add(value, ambient)?
    };
    e.frame(
        || "shadow".into(),
        |e| {
            let ld = vec3::sub(e, k.light, p)?;
            let ld = vec3::normalize(e, ld)?;
            let offset = vec3::scale(e, n, k.shadow_offset)?;
            let o = vec3::add(e, offset, p)?;
            let (shadow_depth, _) = march(e, k, o, ld, k.shadow_steps, "shadow march")?;
            let to_light = vec3::sub(e, k.light, o)?;
            let dist = vec3::length(e, to_light)?;
            let shadowed = e.gt(dist, shadow_depth)?;
            if e.decide(Decision::Shadow, [dist, shadow_depth], shadowed) {
                e.quarter(value)
            } else {
                Ok(value)
            }
        },
    )
}

/// The Float316 pixel counter for `n`: 0 plus 1.0, `n` times (as the image
/// loop counts).
pub fn counter<E: Engine>(e: &mut E, k: &Consts<E::N>, n: usize) -> R<E::N> {
    let mut c = k.zero;
    for _ in 0..n {
        c = e.add(c, k.one)?;
    }
    Ok(c)
}

/// The normalized coordinates `(u, v)` of the pixel with counters `xc`,
/// `yc`: the arguments of [`shade`].
#[inline]
pub fn coords<E: Engine>(e: &mut E, k: &Consts<E::N>, (xc, yc): (E::N, E::N)) -> R<(E::N, E::N)> {
    let u = e.sub(xc, k.half_width)?;
    let u = e.div(u, k.pixel_scale)?;
    let v = e.sub(yc, k.half_height)?;
    let v = E::negate(e.div(v, k.pixel_scale)?);
    Ok((u, v))
}

/// A pixel's clamped shade and its dithered bit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shaded<N> {
    pub value: N,
    pub white: bool,
}

/// Pixel (x, y) of the image, with its counters `xc`, `yc` (see
/// [`counter`]): coordinates, shade, clamp, dither.
pub fn pixel<E: Engine>(
    e: &mut E,
    k: &Consts<E::N>,
    (x, y): (usize, usize),
    (xc, yc): (E::N, E::N),
) -> R<Shaded<E::N>> {
    e.frame(
        || format!("pixel({x},{y})"),
        |e| {
            let uv = coords(e, k, (xc, yc))?;
            shaded(e, k, (x, y), uv)
        },
    )
}

/// Pixel (x, y) from its normalized coordinates `(u, v)`: shade, clamp,
/// dither (the part of [`pixel`] after [`coords`]).
#[inline]
pub fn shaded<E: Engine>(
    e: &mut E,
    k: &Consts<E::N>,
    (x, y): (usize, usize),
    (u, v): (E::N, E::N),
) -> R<Shaded<E::N>> {
    let value = shade(e, k, u, v)?;
    let above = e.gt(value, k.one)?;
    let value = if e.decide(Decision::ClampHigh, [value, k.one], above) {
        k.one
    } else if e.decide(Decision::ClampLow, [value, k.zero], E::sign_bit(value)) {
        k.zero
    } else {
        value
    };
    let dithered = e.frame(
        || "dither".into(),
        |e| e.dither_value(k, value, (y % 8) * 8 + (x % 8)),
    )?;
    let white = if k.dither_threshold_fault {
        !e.gt(k.half, dithered)?
    } else {
        e.gt(dithered, k.half)?
    };
    let white = e.decide(Decision::Dither, [dithered, k.half], white);
    Ok(Shaded { value, white })
}

/// Every pixel of the image, row by row, rows in parallel. `engine` makes
/// one engine per row.
pub fn image<E: Engine>(engine: impl Fn() -> E + Sync, k: &Consts<E::N>) -> Vec<R<Shaded<E::N>>>
where
    E::N: Send,
{
    (0..HEIGHT)
        .into_par_iter()
        .flat_map_iter(|y| {
            let mut e = engine();
            let row_counter = counter(&mut e, k, y);
            let mut xc = Ok(k.zero);
            (0..WIDTH)
                .map(|x| {
                    let r = match (row_counter, xc) {
                        (Ok(yc), Ok(c)) => pixel(&mut e, k, (x, y), (c, yc)),
                        (Err(t), _) | (_, Err(t)) => Err(t),
                    };
                    xc = xc.and_then(|c| e.add(c, k.one));
                    r
                })
                .collect::<Vec<_>>()
        })
        .collect()
}
