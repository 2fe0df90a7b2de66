//! An engine that computes as another one does and records the branch
//! decisions of the run ([`Engine::decide`]): which, the side taken and the
//! operands' values. The scene-derived vector generators read a render's
//! decisions through it (where the hit surface, the shadow or the bounce
//! count changes between neighbouring pixels).

use crate::consts::Consts;
use crate::engine::{Decision, Engine, Tuning, R};
use crate::vec3::V3;
use common::F316;

/// One decision of a recorded run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Decided {
    pub decision: Decision,
    pub taken: bool,
    /// The operands' values (`gt(a, b)`: `[a, b]`).
    pub operands: [f64; 2],
}

/// `inner`, recording its decisions into `log`.
pub struct Recorder<'a, E> {
    pub inner: E,
    pub log: &'a mut Vec<Decided>,
}

/// Methods that pass their operands to the inner engine.
macro_rules! pass {
    ($($name:ident($($arg:ident),*) -> $out:ty;)*) => {
        $(fn $name(&mut self, $($arg: Self::N),*) -> R<$out> {
            self.inner.$name($($arg),*)
        })*
    };
}

impl<E: Engine> Engine for Recorder<'_, E> {
    type N = E::N;

    fn constant(x: f64) -> Option<E::N> {
        E::constant(x)
    }
    fn to_f64(v: E::N) -> f64 {
        E::to_f64(v)
    }
    fn triple(v: E::N) -> Option<F316> {
        E::triple(v)
    }
    fn from_triple(t: F316) -> R<E::N> {
        E::from_triple(t)
    }
    fn negate(a: E::N) -> E::N {
        E::negate(a)
    }
    fn sign_bit(a: E::N) -> bool {
        E::sign_bit(a)
    }

    pass! {
        gt(a, b) -> bool;
        add(a, b) -> E::N;
        sub(a, b) -> E::N;
        mul(a, b) -> E::N;
        div(a, b) -> E::N;
        pow(a, b) -> E::N;
        sqrt(a) -> E::N;
        floor(a) -> E::N;
        mod2(a) -> E::N;
        double(a) -> E::N;
        quarter(a) -> E::N;
    }

    fn contracts(&self) -> bool {
        self.inner.contracts()
    }
    fn mul_add(&mut self, a: E::N, b: E::N, c: E::N) -> R<E::N> {
        self.inner.mul_add(a, b, c)
    }

    fn set_tuning(&mut self, tuning: Option<Tuning>) -> Option<Tuning> {
        self.inner.set_tuning(tuning)
    }

    fn decide(&mut self, decision: Decision, operands: [E::N; 2], taken: bool) -> bool {
        self.log.push(Decided {
            decision,
            taken,
            operands: operands.map(E::to_f64),
        });
        taken
    }

    fn normalize(&mut self, v: V3<E::N>) -> R<V3<E::N>> {
        self.inner.normalize(v)
    }
    fn diffuse(&mut self, k: &Consts<E::N>, a: E::N) -> R<E::N> {
        self.inner.diffuse(k, a)
    }
    fn specular(&mut self, k: &Consts<E::N>, s: E::N) -> R<E::N> {
        self.inner.specular(k, s)
    }
    fn ambient(&mut self, k: &Consts<E::N>) -> R<E::N> {
        self.inner.ambient(k)
    }
    fn dither_value(&mut self, k: &Consts<E::N>, v: E::N, b: usize) -> R<E::N> {
        self.inner.dither_value(k, v, b)
    }
}
