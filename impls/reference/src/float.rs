//! The float formulation of the scene (spec section 7) in IEEE f64 or f32:
//! native operations, correctly rounded `sqrt`, libm `floor` and `pow`.

use crate::consts::Consts;
use crate::engine::{Engine, Trap, R};
use crate::formulation::{self, Formulated, Formulation};
use crate::vec3::V3;
use common::F316;
use std::fmt::Debug;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// The IEEE float types the float engine runs on.
pub trait IeeeFloat:
    Copy
    + Debug
    + Send
    + Sync
    + PartialOrd
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// The nearest value to `x` (`None` when not finite in this type).
    fn from_f64(x: f64) -> Option<Self>;
    /// The exact value as f64.
    fn to_f64(self) -> f64;
    fn sqrt(self) -> Self;
    fn floor(self) -> Self;
    fn powf(self, p: Self) -> Self;
    /// `self * a + b` rounded once (IEEE fusedMultiplyAdd).
    fn mul_add(self, a: Self, b: Self) -> Self;
    fn rem_euclid(self, r: Self) -> Self;
    fn is_sign_negative(self) -> bool;
}

macro_rules! ieee_float {
    ($t:ty) => {
        impl IeeeFloat for $t {
            fn from_f64(x: f64) -> Option<Self> {
                let v = x as $t;
                v.is_finite().then_some(v)
            }
            fn to_f64(self) -> f64 {
                f64::from(self)
            }
            fn sqrt(self) -> Self {
                <$t>::sqrt(self)
            }
            fn floor(self) -> Self {
                <$t>::floor(self)
            }
            fn powf(self, p: Self) -> Self {
                <$t>::powf(self, p)
            }
            fn mul_add(self, a: Self, b: Self) -> Self {
                <$t>::mul_add(self, a, b)
            }
            fn rem_euclid(self, r: Self) -> Self {
                <$t>::rem_euclid(self, r)
            }
            fn is_sign_negative(self) -> bool {
                <$t>::is_sign_negative(self)
            }
        }
    };
}

ieee_float!(f64);
ieee_float!(f32);

/// The float engine: never traps, does not trace; `fused` when it
/// contracts multiply-adds (the `fma` variant).
#[derive(Clone, Copy, Debug, Default)]
pub struct FloatEngine<T> {
    fused: bool,
    number: std::marker::PhantomData<T>,
}

impl<T> FloatEngine<T> {
    /// A float engine that rounds every operation apart (the spec).
    pub fn new() -> Self {
        FloatEngine::contracting(false)
    }

    /// A float engine that computes multiply-adds fused when `fused`.
    pub fn contracting(fused: bool) -> Self {
        FloatEngine {
            fused,
            number: std::marker::PhantomData,
        }
    }
}

fn lit<T: IeeeFloat>(x: f64) -> T {
    T::from_f64(x).expect("a literal of the float formulation is finite")
}

impl<T: IeeeFloat> Engine for FloatEngine<T> {
    type N = T;

    fn constant(x: f64) -> Option<T> {
        T::from_f64(x)
    }

    fn to_f64(v: T) -> f64 {
        v.to_f64()
    }

    fn triple(_: T) -> Option<F316> {
        None
    }

    fn from_triple(t: F316) -> R<T> {
        T::from_f64(t.to_f64()).ok_or(Trap::OutOfDomain)
    }

    fn gt(&mut self, a: T, b: T) -> R<bool> {
        Ok(a > b)
    }

    fn add(&mut self, a: T, b: T) -> R<T> {
        Ok(a + b)
    }

    fn sub(&mut self, a: T, b: T) -> R<T> {
        Ok(a - b)
    }

    fn mul(&mut self, a: T, b: T) -> R<T> {
        Ok(a * b)
    }

    fn div(&mut self, a: T, b: T) -> R<T> {
        Ok(a / b)
    }

    fn sqrt(&mut self, a: T) -> R<T> {
        Ok(a.sqrt())
    }

    fn floor(&mut self, a: T) -> R<T> {
        Ok(a.floor())
    }

    fn mod2(&mut self, a: T) -> R<T> {
        Ok(a.rem_euclid(lit(2.0)))
    }

    fn double(&mut self, a: T) -> R<T> {
        Ok(lit::<T>(2.0) * a)
    }

    fn quarter(&mut self, a: T) -> R<T> {
        Ok(a * lit(0.25))
    }

    fn pow(&mut self, a: T, b: T) -> R<T> {
        Ok(a.powf(b))
    }

    fn contracts(&self) -> bool {
        self.fused
    }

    fn mul_add(&mut self, a: T, b: T, c: T) -> R<T> {
        Ok(if self.fused {
            a.mul_add(b, c)
        } else {
            c + a * b
        })
    }

    fn negate(a: T) -> T {
        -a
    }

    fn sign_bit(a: T) -> bool {
        a.is_sign_negative()
    }

    fn normalize(&mut self, v: V3<T>) -> R<V3<T>> {
        formulation::normalize(self, v)
    }

    fn diffuse(&mut self, k: &Consts<T>, a: T) -> R<T> {
        formulation::diffuse(self, k, a)
    }

    fn specular(&mut self, k: &Consts<T>, s: T) -> R<T> {
        formulation::specular(self, k, s)
    }

    fn ambient(&mut self, k: &Consts<T>) -> R<T> {
        formulation::ambient(self, k)
    }

    fn dither_value(&mut self, k: &Consts<T>, v: T, b: usize) -> R<T> {
        formulation::dither_value(self, k, v, b)
    }
}

impl<T: IeeeFloat> Formulated for FloatEngine<T> {
    const FORMULATION: Formulation = Formulation::Ieee;

    fn inv_sqrt(&mut self, x: T) -> R<T> {
        Ok(lit::<T>(1.0) / x.sqrt())
    }
}
