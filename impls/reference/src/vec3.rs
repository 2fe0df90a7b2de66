//! Vector helpers of spec section 3, generic over the engine. They are not
//! operations of their own: in a trace they appear as frames of the path.

use crate::engine::{Decision, Engine, R};

/// A 3-vector of engine numbers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct V3<N> {
    pub x: N,
    pub y: N,
    pub z: N,
}

impl<N> V3<N> {
    /// Build a vector from its components.
    pub const fn new(x: N, y: N, z: N) -> Self {
        V3 { x, y, z }
    }
}

/// Component-wise `a + b`.
pub fn add<E: Engine>(e: &mut E, a: V3<E::N>, b: V3<E::N>) -> R<V3<E::N>> {
    Ok(V3::new(
        e.add(a.x, b.x)?,
        e.add(a.y, b.y)?,
        e.add(a.z, b.z)?,
    ))
}

/// Component-wise `a - b`.
pub fn sub<E: Engine>(e: &mut E, a: V3<E::N>, b: V3<E::N>) -> R<V3<E::N>> {
    Ok(V3::new(
        e.sub(a.x, b.x)?,
        e.sub(a.y, b.y)?,
        e.sub(a.z, b.z)?,
    ))
}

/// Each component times the scalar `k` (`mul(component, k)`).
pub fn scale<E: Engine>(e: &mut E, a: V3<E::N>, k: E::N) -> R<V3<E::N>> {
    Ok(V3::new(e.mul(a.x, k)?, e.mul(a.y, k)?, e.mul(a.z, k)?))
}

/// `a + b * k` component-wise: `add(a, scale(b, k))`, or one multiply-add
/// per component in an engine that [contracts](Engine::contracts).
pub fn add_scaled<E: Engine>(e: &mut E, a: V3<E::N>, b: V3<E::N>, k: E::N) -> R<V3<E::N>> {
    if e.contracts() {
        return Ok(V3::new(
            e.mul_add(b.x, k, a.x)?,
            e.mul_add(b.y, k, a.y)?,
            e.mul_add(b.z, k, a.z)?,
        ));
    }
    let t = scale(e, b, k)?;
    add(e, a, t)
}

/// `add(add(mul(ax,bx), mul(ay,by)), mul(az,bz))`; contracted, each
/// product after the first is fused with the sum before it:
/// `fma(az, bz, fma(ay, by, ax*bx))`.
pub fn dot<E: Engine>(e: &mut E, a: V3<E::N>, b: V3<E::N>) -> R<E::N> {
    e.frame(
        || "dot".into(),
        |e| {
            let xx = e.mul(a.x, b.x)?;
            if e.contracts() {
                let s = e.mul_add(a.y, b.y, xx)?;
                return e.mul_add(a.z, b.z, s);
            }
            let yy = e.mul(a.y, b.y)?;
            let s = e.add(xx, yy)?;
            let zz = e.mul(a.z, b.z)?;
            e.add(s, zz)
        },
    )
}

/// `sqrt(dot(v, v))`.
pub fn length<E: Engine>(e: &mut E, v: V3<E::N>) -> R<E::N> {
    e.frame(
        || "length".into(),
        |e| {
            let d = dot(e, v, v)?;
            e.sqrt(d)
        },
    )
}

/// `(ay*bz - by*az, az*bx - bz*ax, ax*by - bx*ay)`, each as `sub(mul, mul)`;
/// contracted, the second product is fused: `fma(-by, az, ay*bz)`.
pub fn cross<E: Engine>(e: &mut E, a: V3<E::N>, b: V3<E::N>) -> R<V3<E::N>> {
    e.frame(
        || "cross".into(),
        |e| {
            let mut c = |p: E::N, q: E::N, r: E::N, s: E::N| -> R<E::N> {
                let m1 = e.mul(p, q)?;
                if e.contracts() {
                    return e.mul_add(E::negate(r), s, m1);
                }
                let m2 = e.mul(r, s)?;
                e.sub(m1, m2)
            };
            Ok(V3::new(
                c(a.y, b.z, b.y, a.z)?,
                c(a.z, b.x, b.z, a.x)?,
                c(a.x, b.y, b.x, a.y)?,
            ))
        },
    )
}

/// `normalize(v)`, as the engine's formulation defines it.
pub fn normalize<E: Engine>(e: &mut E, v: V3<E::N>) -> R<V3<E::N>> {
    e.frame(|| "normalize".into(), |e| e.normalize(v))
}

/// `dot(a, b)` clamped to [0, 1]: 0 when its sign bit is set (also -0),
/// 1 when it is greater than 1.
pub fn angle<E: Engine>(e: &mut E, a: V3<E::N>, b: V3<E::N>, one: E::N, zero: E::N) -> R<E::N> {
    e.frame(
        || "angle".into(),
        |e| {
            let d = dot(e, a, b)?;
            if e.decide(Decision::AngleLow, [d, zero], E::sign_bit(d)) {
                return Ok(zero);
            }
            let above = e.gt(d, one)?;
            Ok(if e.decide(Decision::AngleHigh, [d, one], above) {
                one
            } else {
                d
            })
        },
    )
}
