//! The number type the scene is written against: one trait, [`Engine`], with
//! the operations the scene needs and the few policy hooks where the float
//! formulation of the spec (section 7) differs structurally from the
//! Float316 pipeline (sections 3-6). The scene code is written once, generic
//! over it.

use crate::consts::Consts;
use crate::vec3::V3;
use common::{Outcome, F316};
use std::fmt::Debug;

/// Why a Float316 computation stopped without a value. Carried by `?`
/// through the scene and turned into an [`Outcome`] at the public API.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Trap {
    /// `Sys.error(code)` in the Jack program.
    SysError(i16),
    /// A loop that never ends in the Jack program.
    Hang,
    /// An input outside the operation's domain.
    OutOfDomain,
}

/// A branch decision of the pipeline, as [`Engine::decide`] reports it
/// (defined with the scene's intermediate form, which marks them).
pub use scene::ir::Decision;
/// An operation variant chosen for one call site.
pub use scene::ir::Tuning;

/// A result inside the scene: a value or a trap.
pub type R<T> = Result<T, Trap>;

/// Convert an internal result to the shared [`Outcome`].
pub fn outcome<T>(r: R<T>) -> Outcome<T> {
    match r {
        Ok(v) => Outcome::Value(v),
        Err(Trap::SysError(c)) => Outcome::SysError(c),
        Err(Trap::Hang) => Outcome::Hang,
        Err(Trap::OutOfDomain) => Outcome::OutOfDomain,
    }
}

/// The arithmetic of one implementation, plus its policy hooks. An engine is
/// a small value that may carry a configuration and a tracer; the scene code
/// borrows it mutably for the duration of one computation.
pub trait Engine {
    /// The number type.
    type N: Copy + Debug + Send + Sync;

    /// Encode a scene constant (`None` when it cannot be represented).
    fn constant(x: f64) -> Option<Self::N>;
    /// The exact value as f64.
    fn to_f64(v: Self::N) -> f64;
    /// The Float316 triple, for the Float316 engine only.
    fn triple(v: Self::N) -> Option<F316>;
    /// The number from a Float316 triple (its f64 value for floats): out
    /// of domain when that value is not finite in the number type (a legal
    /// triple can exceed f32's and f64's range).
    fn from_triple(t: F316) -> R<Self::N>;

    /// `a > b`.
    fn gt(&mut self, a: Self::N, b: Self::N) -> R<bool>;
    /// `a + b`.
    fn add(&mut self, a: Self::N, b: Self::N) -> R<Self::N>;
    /// `a - b`.
    fn sub(&mut self, a: Self::N, b: Self::N) -> R<Self::N>;
    /// `a * b`.
    fn mul(&mut self, a: Self::N, b: Self::N) -> R<Self::N>;
    /// `a / b`.
    fn div(&mut self, a: Self::N, b: Self::N) -> R<Self::N>;
    /// Square root.
    fn sqrt(&mut self, a: Self::N) -> R<Self::N>;
    /// Largest integer not above `a`.
    fn floor(&mut self, a: Self::N) -> R<Self::N>;
    /// `a mod 2` for an integral `a`: 0 or 1, also for negative `a`.
    fn mod2(&mut self, a: Self::N) -> R<Self::N>;
    /// `2 * a`.
    fn double(&mut self, a: Self::N) -> R<Self::N>;
    /// `a / 4`.
    fn quarter(&mut self, a: Self::N) -> R<Self::N>;
    /// `a` to the power `b`. Only IEEE engines have it: a Float316 program
    /// raises to integer powers by multiplying, so the default is a trap.
    fn pow(&mut self, a: Self::N, b: Self::N) -> R<Self::N> {
        let _ = (a, b);
        Err(Trap::OutOfDomain)
    }
    /// Whether the scene's multiply-adds are computed as one fused
    /// operation each ([`Engine::mul_add`]), as a GPU driver may contract
    /// them. Only a float engine with the `fma` variant does; every other
    /// engine computes the product and the sum apart, in the spec's order.
    #[inline(always)]
    fn contracts(&self) -> bool {
        false
    }
    /// `c + a * b` (called where [`Engine::contracts`]). A fused engine
    /// rounds once; by default the product, then `add(c, product)`.
    #[inline(always)]
    fn mul_add(&mut self, a: Self::N, b: Self::N, c: Self::N) -> R<Self::N> {
        let p = self.mul(a, b)?;
        self.add(c, p)
    }
    /// The same value with its sign flipped (not a traced operation).
    fn negate(a: Self::N) -> Self::N;
    /// Whether the sign bit is set (negative or -0).
    fn sign_bit(a: Self::N) -> bool;

    /// Run `f` inside a named frame of the trace's call path. Engines that
    /// do not trace just run `f`; `name` is only called when tracing.
    #[inline(always)]
    fn frame<T>(&mut self, name: impl FnOnce() -> String, f: impl FnOnce(&mut Self) -> R<T>) -> R<T>
    where
        Self: Sized,
    {
        let _ = name;
        f(self)
    }

    /// Compute with the operation variant `tuning` from now on (`None`:
    /// the engine's own arithmetic), for the statements of a tuned call
    /// site; returns the previous choice. Only the Float316 engine has
    /// such variants; the default ignores them.
    #[inline(always)]
    fn set_tuning(&mut self, tuning: Option<Tuning>) -> Option<Tuning> {
        let _ = tuning;
        None
    }

    /// The pipeline took the branch `decision` (`taken`) on `operands`
    /// (for a comparison `gt(a, b)`: `[a, b]`). Returns `taken`; engines
    /// that explain runs record it.
    #[inline(always)]
    fn decide(&mut self, decision: Decision, operands: [Self::N; 2], taken: bool) -> bool {
        let _ = (decision, operands);
        taken
    }

    // ---- Policy hooks: where section 7 differs from sections 3-6. ----

    /// `normalize(v)`: Float316 scales by `invSqrt(dot(v, v))`; floats divide
    /// each component by `sqrt(x*x + y*y + z*z)`.
    fn normalize(&mut self, v: V3<Self::N>) -> R<V3<Self::N>>
    where
        Self: Sized;
    /// The diffuse term from `angle(L, n)`: `mul(0.63, a)` in Float316,
    /// `(0.9 * a) * 0.7` in floats.
    fn diffuse(&mut self, k: &Consts<Self::N>, a: Self::N) -> R<Self::N>;
    /// The specular term from `angle(R, C)`: `((s*s)*(s*s)) * 0.35` in
    /// Float316 (as two squarings), `(0.7 * pow(s, 4)) * 0.5` in floats.
    fn specular(&mut self, k: &Consts<Self::N>, s: Self::N) -> R<Self::N>;
    /// The ambient term `0.2 * 0.835` (a truncated constant 0.167 in
    /// Float316, a product evaluated in the float type otherwise).
    fn ambient(&mut self, k: &Consts<Self::N>) -> R<Self::N>;
    /// The dithered value for a clamped value `v` and the Bayer entry at
    /// index `b`, to be compared with 0.5: Float316 `add(v, (B-32)/64)`;
    /// floats `(v + B/64) - 0.5`.
    fn dither_value(&mut self, k: &Consts<Self::N>, v: Self::N, b: usize) -> R<Self::N>;
}
