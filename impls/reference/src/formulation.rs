//! The two formulations of the scene's policy hooks (see [`Engine`]'s
//! hooks): Float316's (spec sections 3-6) and the IEEE float one (section
//! 7), written once over the engine's own operations, so that every engine
//! that follows a formulation, the shadow engine among them, computes it
//! with the same sequence of operations.

use crate::consts::Consts;
use crate::engine::{Engine, R};
use crate::vec3::{self, V3};

/// Which formulation an engine's hooks follow.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Formulation {
    /// Spec sections 3-6: `normalize` by `invSqrt`, truncated products.
    Float316,
    /// Spec section 7: `normalize` by division, `pow`, products in order.
    Ieee,
}

/// An engine with a formulation, and the operation only the Float316
/// formulation's hooks use.
pub trait Formulated: Engine {
    /// The formulation of its hooks.
    const FORMULATION: Formulation;
    /// `1/sqrt(x)` as one operation (Float316: the spec's `invSqrt`).
    fn inv_sqrt(&mut self, x: Self::N) -> R<Self::N>;
}

/// `normalize(v)`: Float316 scales by `invSqrt(dot(v, v))`; floats divide
/// each component by `length(v)`.
#[inline(always)]
pub fn normalize<E: Formulated>(e: &mut E, v: V3<E::N>) -> R<V3<E::N>> {
    match E::FORMULATION {
        Formulation::Float316 => {
            let d = vec3::dot(e, v, v)?;
            let k = e.inv_sqrt(d)?;
            vec3::scale(e, v, k)
        }
        Formulation::Ieee => {
            let l = vec3::length(e, v)?;
            Ok(V3::new(e.div(v.x, l)?, e.div(v.y, l)?, e.div(v.z, l)?))
        }
    }
}

/// The diffuse term: `mul(0.63, a)`, or `(0.9 * a) * 0.7`.
#[inline(always)]
pub fn diffuse<E: Formulated>(e: &mut E, k: &Consts<E::N>, a: E::N) -> R<E::N> {
    match E::FORMULATION {
        Formulation::Float316 => e.mul(k.diffuse_ki, a),
        Formulation::Ieee => {
            let t = e.mul(k.diffuse_k, a)?;
            e.mul(t, k.diffuse_i)
        }
    }
}

/// The specular term: `((s*s)*(s*s)) * 0.35`, or `(0.7 * pow(s, 4)) * 0.5`.
#[inline(always)]
pub fn specular<E: Formulated>(e: &mut E, k: &Consts<E::N>, s: E::N) -> R<E::N> {
    match E::FORMULATION {
        Formulation::Float316 => {
            let s = e.mul(s, s)?;
            let s = e.mul(s, s)?;
            e.mul(s, k.specular_ki)
        }
        Formulation::Ieee => {
            let four = E::constant(4.0).expect("4 is representable in every engine");
            let p = e.pow(s, four)?;
            let t = e.mul(k.specular_k, p)?;
            e.mul(t, k.specular_i)
        }
    }
}

/// The ambient term: the truncated constant 0.167, or `0.2 * 0.835`.
#[inline(always)]
pub fn ambient<E: Formulated>(e: &mut E, k: &Consts<E::N>) -> R<E::N> {
    match E::FORMULATION {
        Formulation::Float316 => Ok(k.ambient),
        Formulation::Ieee => e.mul(k.ambient_factor, k.background),
    }
}

/// The dithered value: `add(v, (B-32)/64)`, or `(v + B/64) - 0.5`.
#[inline(always)]
pub fn dither_value<E: Formulated>(e: &mut E, k: &Consts<E::N>, v: E::N, b: usize) -> R<E::N> {
    match E::FORMULATION {
        Formulation::Float316 => e.add(v, k.bayer_centred[b]),
        Formulation::Ieee => {
            let t = e.add(v, k.bayer[b])?;
            e.sub(t, k.half)
        }
    }
}
