//! Float316 arithmetic, bit-exact with the Jack program (spec section 2).
//!
//! Every integer operation goes through [`common::jack_int`], so any triple,
//! normalised or not, wraps exactly as a Jack word does. Loops that never
//! end in Jack are detected and reported as [`Trap::Hang`]; every loop here
//! is bounded (a non-zero 16-bit word doubled reaches either a normalised
//! value or 0 within 16 steps; halving reaches 0 within 16 steps).
//!
//! The engine is generic over a [`Recorder`]; with [`Untraced`], tracing
//! compiles away and the operations inline into the scene code.

use crate::consts::Consts;
use crate::engine::{Engine, Trap, Tuning, R};
use crate::formulation::{self, Formulated, Formulation};
use crate::settings::{Arith, ArithSource, SpecArith};
use crate::tracer::{Recorder, Tracer, Untraced};
use crate::vec3::V3;
use common::jack_int as j;
use common::{Op, OpValue, F316};

/// -1.0, added by `floor` to a negative non-integer.
const MINUS_ONE: F316 = F316::new(1, 127, 8192);
/// 1.5, in `invSqrt`'s Newton step.
const THREE_HALVES: F316 = F316::new(0, 127, 12288);
/// Smallest normalised mantissa.
const M_MIN: i16 = 8192;
/// Largest normalised mantissa.
const M_MAX: i16 = 16383;

/// `F316::is_zero`, inlined here (the hot path crosses no crate boundary).
#[inline(always)]
fn is_zero(a: F316) -> bool {
    a.e == 0 && a.m == 0
}

/// Double a positive word until it reaches `M_MIN`, subtracting the number
/// of doublings from `e` (Jack's `while (m < 8192)` loop, in one step: a
/// positive word never wraps before reaching `M_MIN`). Branch-free: no
/// doubling when `m` is already at least `M_MIN`.
#[inline(always)]
fn normalise_positive(m: i16, e: i16) -> (i16, i16) {
    debug_assert!(m > 0);
    let k = ((m as u16).leading_zeros() as i16 - 2).max(0);
    (m << k, j::sub(e, k))
}

/// `m` halved `shift` times, each halving truncating toward zero (none when
/// `shift <= 0`): one truncating division by `2^shift`, done with shifts.
/// A non-negative `m` (the usual case) is one arithmetic shift (15 places
/// already leave 0); a negative one goes through [`trunc_shift_negative`].
#[inline(always)]
fn trunc_shift(m: i16, shift: i16) -> i16 {
    if m < 0 {
        return trunc_shift_negative(m, shift);
    }
    m >> shift.clamp(0, 15)
}

/// [`trunc_shift`] of a negative word, out of line so that the common case
/// stays a branch and a shift.
#[cold]
#[inline(never)]
fn trunc_shift_negative(m: i16, shift: i16) -> i16 {
    let n = shift.clamp(0, 16) as u32;
    (-((-i32::from(m)) >> n)) as i16
}

/// `2^i` for `i` in 0..=13 (Jack: a table of powers of two).
fn pow2(i: i16) -> i16 {
    debug_assert!((0..=13).contains(&i));
    1 << i
}

/// A value an operation returns, as a trace records it.
trait Traceable: Copy {
    fn op_value(self) -> OpValue;
}

impl Traceable for F316 {
    fn op_value(self) -> OpValue {
        OpValue::Num(self)
    }
}

impl Traceable for bool {
    fn op_value(self) -> OpValue {
        OpValue::Bool(self)
    }
}

/// The Float316 engine: the spec's operations under an [`Arith`]
/// configuration (given at run time, or [`SpecArith`]), reporting to a
/// [`Recorder`].
pub struct F316Engine<Rec: Recorder = Untraced, A: ArithSource = Arith> {
    arith: A,
    recorder: Rec,
    /// The variant of a tuned call site being run, if any.
    tuning: Option<Tuning>,
}

impl F316Engine {
    /// An engine that does not trace.
    pub fn new(arith: Arith) -> Self {
        F316Engine {
            arith,
            recorder: Untraced,
            tuning: None,
        }
    }
}

impl F316Engine<Untraced, SpecArith> {
    /// An engine that does not trace, with the spec's arithmetic compiled
    /// in (the same results as `new(Arith::SPEC)`, faster).
    pub fn spec() -> Self {
        F316Engine {
            arith: SpecArith,
            recorder: Untraced,
            tuning: None,
        }
    }
}

impl<'t> F316Engine<&'t mut Tracer> {
    /// An engine that records every operation into `tracer`.
    pub fn with_tracer(arith: Arith, tracer: &'t mut Tracer) -> Self {
        F316Engine {
            arith,
            recorder: tracer,
            tuning: None,
        }
    }
}

impl<Rec: Recorder> F316Engine<Rec> {
    /// An engine that reports every operation to `recorder`.
    pub(crate) fn recording(arith: Arith, recorder: Rec) -> Self {
        F316Engine {
            arith,
            recorder,
            tuning: None,
        }
    }

    /// The recorder, with what it recorded.
    pub(crate) fn into_recorder(self) -> Rec {
        self.recorder
    }
}

impl<Rec: Recorder, A: ArithSource> F316Engine<Rec, A> {
    /// Run `body` as the operation `op` on `args`, recording it when tracing.
    #[inline(always)]
    fn traced<T: Traceable>(
        &mut self,
        op: Op,
        args: &[F316],
        body: impl FnOnce(&mut Self) -> R<T>,
    ) -> R<T> {
        if !Rec::ON {
            return body(self);
        }
        let index = self.recorder.open(op, args);
        if let Some(t) = self.tuning.filter(|t| t.changes(op)) {
            self.recorder.variant(op, t);
        }
        let result = body(self);
        self.recorder.close(index, result.map(Traceable::op_value));
        result
    }

    /// Newton steps in `sqrt` and `invSqrt`: the tuned site's, else the
    /// arithmetic's.
    #[inline(always)]
    fn newton_steps(&self) -> u8 {
        match self.tuning.and_then(Tuning::newton_steps) {
            Some(steps) => steps,
            None => self.arith.arith().newton_steps,
        }
    }

    /// `halve(a)`: exponent minus 1 when `a.e > 0`.
    #[inline(always)]
    pub fn halve(&mut self, a: F316) -> R<F316> {
        self.traced(Op::Halve, &[a], |_| Ok(shift_exponent(a, -1)))
    }

    /// `invSqrt(x)`: Newton iterations from `(0, 190 - x.e/2, 8192)`.
    pub fn inv_sqrt(&mut self, x: F316) -> R<F316> {
        self.traced(Op::InvSqrt, &[x], |s| {
            if x.s == 1 {
                return Err(Trap::SysError(3));
            }
            let x2 = F316::new(0, j::sub(x.e, 1), x.m);
            let mut y = F316::new(0, j::sub(190, j::halve(x.e)), M_MIN);
            for _ in 0..s.newton_steps() {
                let t = s.mul(x2, y)?;
                let t = s.mul(t, y)?;
                let t = s.sub(THREE_HALVES, t)?;
                y = s.mul(y, t)?;
            }
            Ok(F316::new(0, y.e, y.m))
        })
    }

    /// Any operation of the spec by name; `gt` gives a boolean.
    /// `args` must hold `op.arity()` operands.
    pub fn apply(&mut self, op: Op, args: &[F316]) -> R<OpValue> {
        let a = args[0];
        let b = || args[1];
        let num = |r: R<F316>| r.map(OpValue::Num);
        match op {
            Op::Gt => self.gt(a, b()).map(OpValue::Bool),
            Op::Add => num(self.add(a, b())),
            Op::Sub => num(self.sub(a, b())),
            Op::Mul => num(self.mul(a, b())),
            Op::Div => num(self.div(a, b())),
            Op::Floor => num(self.floor(a)),
            Op::Mod2 => num(self.mod2(a)),
            Op::Sqrt => num(self.sqrt(a)),
            Op::InvSqrt => num(self.inv_sqrt(a)),
            Op::Halve => num(self.halve(a)),
            Op::Double => num(self.double(a)),
            Op::Quarter => num(self.quarter(a)),
        }
    }
}

/// `a > b` (spec: signs first, then exponent, then mantissa).
fn gt(a: F316, b: F316) -> bool {
    if a.s != b.s {
        return a.s == 0 && b.s == 1;
    }
    let magnitude_gt = |p: F316, q: F316| p.e > q.e || (p.e == q.e && p.m > q.m);
    if a.s == 0 {
        magnitude_gt(a, b)
    } else {
        magnitude_gt(b, a)
    }
}

/// `add(a, b)` without tracing (it calls no other operation).
#[inline(always)]
fn add(arith: &Arith, a: F316, b: F316) -> R<F316> {
    let (big, small) = if b.e > a.e || (b.e == a.e && b.m > a.m) {
        (b, a)
    } else {
        (a, b)
    };
    if is_zero(small) {
        return Ok(big);
    }
    let mut shift = j::sub(big.e, small.e);
    if arith.add_alignment_off_by_one && shift > 0 {
        shift = j::add(shift, 1);
    }
    if arith.add_drops_operand_at_gap_14 && shift >= 14 {
        return Ok(big);
    }
    // Halving `shift` times, each truncating toward zero, equals one
    // truncating division by 2^shift; after 16 halvings any word is 0.
    let sm = trunc_shift(small.m, shift);
    let mut e = big.e;
    let mut m;
    if big.s == small.s {
        m = j::add(big.m, sm);
        let carry = if arith.add_carry_by_bit_test {
            m & 16384 != 0
        } else {
            m > M_MAX
        };
        if carry {
            m = j::halve(m);
            e = j::add(e, 1);
        }
    } else {
        m = j::sub(big.m, sm);
        if m > 0 {
            (m, e) = normalise_positive(m, e);
        } else if big.e == small.e && big.m == small.m {
            // Exact cancellation (Jack tests for it before aligning; only
            // equal magnitudes of opposite signs get here with m == 0).
            return Ok(F316::ZERO);
        } else {
            // Doubling a negative word reaches 0 (a hang) or wraps to a
            // value of at least M_MIN within 16 steps.
            while m < M_MIN {
                if m == 0 {
                    return Err(Trap::Hang);
                }
                m = j::mul(m, 2);
                e = j::sub(e, 1);
            }
        }
    }
    Ok(F316 { s: big.s, e, m })
}

/// `mul(a, b)`: the product of the 7-bit halves, low*low dropped unless
/// the configuration keeps it.
#[inline(always)]
fn mul(arith: &Arith, a: F316, b: F316) -> F316 {
    if (a.m | b.m) as u16 <= M_MAX as u16 {
        let m = mantissa_product_small(arith, a.m, b.m);
        // A zero operand has m = 0, which makes the product 0: a positive
        // product means neither operand is zero, so Jack's zero test fails.
        if m > 0 {
            let sign = j::and(j::add(a.s, b.s), 1);
            let (m, e) = normalise_positive(m, j::sub(j::add(a.e, b.e), 126));
            return F316 { s: sign, e, m };
        }
    }
    mul_any(arith, a, b)
}

/// `mul(a, b)` for any words, as Jack computes it.
fn mul_any(arith: &Arith, a: F316, b: F316) -> F316 {
    let sign = j::and(j::add(a.s, b.s), 1);
    if is_zero(a) || is_zero(b) {
        return F316::new(sign, 0, 0);
    }
    let mut e = j::sub(j::add(a.e, b.e), 126);
    let mut m = mantissa_product(arith, a.m, b.m);
    if m > 0 {
        (m, e) = normalise_positive(m, e);
    }
    F316 { s: sign, e, m }
}

/// `mul(a, b)` of the `truncated-product` variant: the spec's `mul` with
/// the mantissa product `(a.m / 128) * (b.m / 128)` alone, the two mixed
/// products left out (at most 2/64 of the product below the spec's).
fn mul_truncated(a: F316, b: F316) -> F316 {
    let sign = j::and(j::add(a.s, b.s), 1);
    if is_zero(a) || is_zero(b) {
        return F316::new(sign, 0, 0);
    }
    let mut e = j::sub(j::add(a.e, b.e), 126);
    let high = |m: i16| j::div(m, 128).unwrap_or(0);
    let mut m = j::mul(high(a.m), high(b.m));
    if m > 0 {
        (m, e) = normalise_positive(m, e);
    }
    F316 { s: sign, e, m }
}

/// `floor`'s step down of a negative non-integer `r` (its fraction bits
/// cleared; `unit` the mantissa's unit at the integer's last bit) under the
/// `floor-direct` variant: `unit` added to the mantissa, renormalised
/// once, as `add(r, -1.0)` computes it (the spec: -1.0's mantissa halved
/// `r.e - 127` times is `unit`) without the call.
fn step_down(r: F316, unit: i16) -> F316 {
    let m = j::add(r.m, unit);
    if m > M_MAX {
        F316::new(r.s, j::add(r.e, 1), j::halve(m))
    } else {
        F316::new(r.s, r.e, m)
    }
}

/// mul's mantissa product for any words, as Jack computes it.
fn mantissa_product(arith: &Arith, am: i16, bm: i16) -> i16 {
    let split = |m: i16| (j::div(m, 128).unwrap_or(0), j::and(m, 127));
    let (ah, al) = split(am);
    let (bh, bl) = split(bm);
    let mut mid = j::add(j::mul(ah, bl), j::mul(al, bh));
    if arith.mul_keeps_low_product {
        mid = j::add(mid, j::div(j::mul(al, bl), 128).unwrap_or(0));
    }
    j::add(j::mul(ah, bh), j::div(mid, 128).unwrap_or(0))
}

/// [`mantissa_product`] for mantissas in 0..=16383 (normalised ones among
/// them): the halves are below 128, so no sum exceeds 32384, no word wraps
/// and each truncating division by 128 is a shift.
#[inline(always)]
fn mantissa_product_small(arith: &Arith, am: i16, bm: i16) -> i16 {
    debug_assert!((0..=M_MAX).contains(&am) && (0..=M_MAX).contains(&bm));
    let (a, b) = (am as u32, bm as u32);
    let (ah, al, bh, bl) = (a >> 7, a & 127, b >> 7, b & 127);
    let mut mid = ah * bl + al * bh;
    if arith.mul_keeps_low_product {
        mid += (al * bl) >> 7;
    }
    (ah * bh + (mid >> 7)) as i16
}

/// `div(a, b)`: long division with a shrinking divisor.
#[inline(always)]
fn div(arith: &Arith, a: F316, b: F316) -> R<F316> {
    let sign = j::and(j::add(a.s, b.s), 1);
    // Normalised mantissas are not 0, so neither operand is zero.
    let q = if is_normalised(a.m) && is_normalised(b.m) {
        long_division_normalised(a.m, b.m)
    } else {
        if is_zero(a) {
            return Ok(F316::new(sign, 0, 0));
        }
        if is_zero(b) {
            return Err(Trap::SysError(1));
        }
        long_division(a.m, b.m)
    };
    let e = j::sub(j::add(a.e, 127), b.e);
    // q is a sum of distinct powers 2^0..2^13: 0 <= q <= 16383.
    if q == 0 {
        return Err(Trap::Hang);
    }
    if arith.div_normalises_once && q < M_MIN {
        return Ok(F316 {
            s: sign,
            e: j::sub(e, 1),
            m: j::mul(q, 2),
        });
    }
    let (q, e) = normalise_positive(q, e);
    Ok(F316 { s: sign, e, m: q })
}

/// `div(x, g)` when `x` and `g` are positive and share a normalised
/// mantissa (sqrt's start value has x's mantissa): the long division of
/// equal normalised mantissas gives 8192, so the quotient is
/// `(0, x.e + 127 - g.e, 8192)`. `None` for any other operands.
#[inline(always)]
fn div_by_same_mantissa(x: F316, g: F316) -> Option<F316> {
    (x.s == 0 && g.s == 0 && g.m == x.m && is_normalised(x.m)).then(|| F316 {
        s: 0,
        e: j::sub(j::add(x.e, 127), g.e),
        m: M_MIN,
    })
}

/// div's quotient loop for any mantissas, as Jack runs it: `d` shrinks by
/// truncating halving, `if (r >= d) { q += 2^i; r -= d }` for i = 13..0.
fn long_division(mut r: i16, mut d: i16) -> i16 {
    let mut q = 0i16;
    for i in (0..=13).rev() {
        // Branch-free form of `if (r >= d) { q += 2^i; r -= d }`.
        let taken = j::neg(i16::from(r >= d));
        q = j::add(q, j::and(pow2(i), taken));
        r = j::sub(r, j::and(d, taken));
        d = j::halve(d);
    }
    q
}

/// Whether `m` is a normalised mantissa (8192..=16383).
#[inline(always)]
fn is_normalised(m: i16) -> bool {
    (M_MIN..=M_MAX).contains(&m)
}

/// [`long_division`] for normalised mantissas: no word wraps, halving is a
/// shift, the first seven steps unroll into subtract-and-select, and the
/// last seven come from [`LOW_QUOTIENT`]: the divisors of steps 7..13 are
/// `(b >> 7) >> j`, so those steps depend only on `(b >> 7, r)`, and after
/// step 6 the remainder is below [`REMAINDERS`] (at most `(b >> 6) + 5`, as
/// the exhaustive test shows).
#[inline(always)]
fn long_division_normalised(a: i16, b: i16) -> i16 {
    debug_assert!(is_normalised(a) && is_normalised(b));
    let b = b as u32;
    // The remainder (below 2^14) in the low 16 bits, the quotient bits
    // above them: one select per step updates both.
    let mut rq = a as u32;
    for k in 0..7 {
        let d = b >> k;
        if rq & 0xffff >= d {
            rq = rq + (1 << (29 - k)) - d;
        }
    }
    let (q, r) = ((rq >> 16) as i16, (rq & 0xffff) as usize);
    q | i16::from(LOW_QUOTIENT[((b >> 7) - 64) as usize * REMAINDERS + r])
}

/// Remainders the table covers per divisor (0..=260 occur).
const REMAINDERS: usize = 264;

/// Quotient bits 6..0 of the long division steps 7..13, indexed by
/// `((b >> 7) - 64) * REMAINDERS + r` for a normalised divisor `b` and the
/// remainder `r` left by steps 0..6.
static LOW_QUOTIENT: [u8; 64 * REMAINDERS] = low_quotient_table();

const fn low_quotient_table() -> [u8; 64 * REMAINDERS] {
    let mut table = [0u8; 64 * REMAINDERS];
    let mut high = 64;
    while high < 128 {
        let mut r0 = 0;
        while r0 < REMAINDERS {
            let (mut r, mut q, mut j) = (r0, 0u8, 0);
            while j < 7 {
                let d = high >> j;
                if r >= d {
                    r -= d;
                    q |= 1 << (6 - j);
                }
                j += 1;
            }
            table[(high - 64) * REMAINDERS + r0] = q;
            r0 += 1;
        }
        high += 1;
    }
    table
}

/// `halve`, `double`, `quarter`: add `delta` to the exponent when `a.e > 0`.
fn shift_exponent(a: F316, delta: i16) -> F316 {
    if a.e > 0 {
        F316::new(a.s, j::add(a.e, delta), a.m)
    } else {
        a
    }
}

/// `mod2(a)` for an integral `a`: 1.0 when the units bit is set.
fn mod2(a: F316) -> R<F316> {
    if a.m == 0 {
        return Ok(F316::ZERO);
    }
    let i = j::sub(a.e, 127);
    if !(0..=13).contains(&i) {
        return Err(Trap::OutOfDomain);
    }
    if j::and(a.m, pow2(13 - i)) != 0 {
        Ok(F316::ONE)
    } else {
        Ok(F316::ZERO)
    }
}

/// sqrt's start value: `(0, x.e/2 + 64, x.m)` for odd `x.e`, else
/// `(0, x.e/2 + 63, x.m)`. The fault computes the exponent as
/// `(x.e - 127)/2 + 127` instead, which differs exactly when `x.e < 127`
/// and `x.e - 127` is odd.
fn sqrt_guess(arith: &Arith, x: F316) -> F316 {
    let e = if arith.sqrt_guess_from_biased_difference {
        j::add(j::halve(j::sub(x.e, 127)), 127)
    } else if j::and(x.e, 1) == 1 {
        j::add(j::halve(x.e), 64)
    } else {
        j::add(j::halve(x.e), 63)
    };
    F316::new(0, e, x.m)
}

impl<Rec: Recorder, A: ArithSource> Engine for F316Engine<Rec, A> {
    type N = F316;

    fn constant(x: f64) -> Option<F316> {
        F316::from_f64_truncating(x)
    }

    fn to_f64(v: F316) -> f64 {
        v.to_f64()
    }

    fn triple(v: F316) -> Option<F316> {
        Some(v)
    }

    fn from_triple(t: F316) -> R<F316> {
        Ok(t)
    }

    fn set_tuning(&mut self, tuning: Option<Tuning>) -> Option<Tuning> {
        std::mem::replace(&mut self.tuning, tuning)
    }

    #[inline(always)]
    fn gt(&mut self, a: F316, b: F316) -> R<bool> {
        self.traced(Op::Gt, &[a, b], |_| Ok(gt(a, b)))
    }

    #[inline(always)]
    fn add(&mut self, a: F316, b: F316) -> R<F316> {
        self.traced(Op::Add, &[a, b], |s| add(&s.arith.arith(), a, b))
    }

    #[inline(always)]
    fn sub(&mut self, a: F316, b: F316) -> R<F316> {
        self.traced(Op::Sub, &[a, b], |s| s.add(a, b.negated()))
    }

    #[inline(always)]
    fn mul(&mut self, a: F316, b: F316) -> R<F316> {
        self.traced(Op::Mul, &[a, b], |s| {
            Ok(if s.tuning == Some(Tuning::TruncatedProduct) {
                mul_truncated(a, b)
            } else {
                mul(&s.arith.arith(), a, b)
            })
        })
    }

    #[inline(always)]
    fn div(&mut self, a: F316, b: F316) -> R<F316> {
        self.traced(Op::Div, &[a, b], |s| div(&s.arith.arith(), a, b))
    }

    #[inline(always)]
    fn sqrt(&mut self, x: F316) -> R<F316> {
        self.traced(Op::Sqrt, &[x], |s| {
            if x.s == 1 {
                return Err(Trap::SysError(2));
            }
            let mut g = sqrt_guess(&s.arith.arith(), x);
            for _ in 0..s.newton_steps() {
                // The start value has x's mantissa: its quotient needs no
                // long division (a traced run records the div as usual).
                let t = match div_by_same_mantissa(x, g) {
                    Some(t) if !Rec::ON => t,
                    _ => s.div(x, g)?,
                };
                g = s.add(g, t)?;
                g = s.halve(g)?;
            }
            Ok(F316::new(0, g.e, g.m))
        })
    }

    #[inline(always)]
    fn floor(&mut self, a: F316) -> R<F316> {
        self.traced(Op::Floor, &[a], |s| {
            if a.e < 127 {
                return Ok(if a.s == 0 { F316::ZERO } else { MINUS_ONE });
            }
            let i = j::sub(a.e, 127);
            if i > 13 {
                return Err(Trap::OutOfDomain);
            }
            let unit = pow2(13 - i);
            let kept = j::and(a.m, !j::sub(unit, 1));
            let r = F316::new(a.s, a.e, kept);
            if a.s == 1 && kept != a.m {
                if s.tuning == Some(Tuning::FloorDirect) {
                    Ok(step_down(r, unit))
                } else {
                    s.add(r, MINUS_ONE)
                }
            } else {
                Ok(r)
            }
        })
    }

    #[inline(always)]
    fn mod2(&mut self, a: F316) -> R<F316> {
        self.traced(Op::Mod2, &[a], |_| mod2(a))
    }

    #[inline(always)]
    fn double(&mut self, a: F316) -> R<F316> {
        self.traced(Op::Double, &[a], |_| Ok(shift_exponent(a, 1)))
    }

    #[inline(always)]
    fn quarter(&mut self, a: F316) -> R<F316> {
        self.traced(Op::Quarter, &[a], |_| Ok(shift_exponent(a, -2)))
    }

    fn negate(a: F316) -> F316 {
        a.negated()
    }

    fn sign_bit(a: F316) -> bool {
        a.s == 1
    }

    #[inline(always)]
    fn frame<T>(
        &mut self,
        name: impl FnOnce() -> String,
        f: impl FnOnce(&mut Self) -> R<T>,
    ) -> R<T> {
        if !Rec::ON {
            return f(self);
        }
        self.recorder.push(name());
        let r = f(self);
        self.recorder.pop();
        r
    }

    fn normalize(&mut self, v: V3<F316>) -> R<V3<F316>> {
        formulation::normalize(self, v)
    }

    fn diffuse(&mut self, k: &Consts<F316>, a: F316) -> R<F316> {
        formulation::diffuse(self, k, a)
    }

    fn specular(&mut self, k: &Consts<F316>, s: F316) -> R<F316> {
        formulation::specular(self, k, s)
    }

    fn ambient(&mut self, k: &Consts<F316>) -> R<F316> {
        formulation::ambient(self, k)
    }

    fn dither_value(&mut self, k: &Consts<F316>, v: F316, b: usize) -> R<F316> {
        formulation::dither_value(self, k, v, b)
    }
}

impl<Rec: Recorder, A: ArithSource> Formulated for F316Engine<Rec, A> {
    const FORMULATION: Formulation = Formulation::Float316;

    fn inv_sqrt(&mut self, x: F316) -> R<F316> {
        F316Engine::inv_sqrt(self, x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fast quotient equals Jack's loop for every pair of normalised
    /// mantissas (all 67 million).
    #[test]
    fn fast_quotient_equals_the_jack_loop_on_all_normalised_mantissas() {
        use rayon::prelude::*;
        (M_MIN..=M_MAX).into_par_iter().for_each(|a| {
            for b in M_MIN..=M_MAX {
                assert_eq!(
                    long_division_normalised(a, b),
                    long_division(a, b),
                    "{a} / {b}"
                );
            }
        });
    }

    /// Jack's `add` in its own order (cancellation tested before aligning,
    /// every normalising step a loop): the model `add` is checked against.
    fn add_in_jack_order(arith: &Arith, a: F316, b: F316) -> R<F316> {
        let (big, small) = if b.e > a.e || (b.e == a.e && b.m > a.m) {
            (b, a)
        } else {
            (a, b)
        };
        if is_zero(small) {
            return Ok(big);
        }
        if big.s != small.s && big.e == small.e && big.m == small.m {
            return Ok(F316::ZERO);
        }
        let mut shift = j::sub(big.e, small.e);
        if arith.add_alignment_off_by_one && shift > 0 {
            shift = j::add(shift, 1);
        }
        let sm = trunc_shift(small.m, shift);
        let (mut e, mut m);
        e = big.e;
        if big.s == small.s {
            m = j::add(big.m, sm);
            if m > M_MAX {
                m = j::halve(m);
                e = j::add(e, 1);
            }
        } else {
            m = j::sub(big.m, sm);
            while m < M_MIN {
                if m == 0 {
                    return Err(Trap::Hang);
                }
                m = j::mul(m, 2);
                e = j::sub(e, 1);
            }
        }
        Ok(F316 { s: big.s, e, m })
    }

    /// `add` equals Jack's order for every mantissa word against equal,
    /// neighbouring, doubled, halved and fixed mantissas, with exponents at
    /// and around the wrapping edges and every sign pairing.
    #[test]
    fn add_equals_jack_order() {
        let exponents = [i16::MIN, -1, 0, 127, 128, 142, i16::MAX];
        let signs = [(0, 0), (0, 1), (1, 0), (2, 1)];
        for flag in [false, true] {
            let arith = Arith {
                add_alignment_off_by_one: flag,
                ..Arith::SPEC
            };
            let others = |ma: i16| {
                [
                    ma,
                    ma.wrapping_add(1),
                    ma.wrapping_sub(1),
                    ma.wrapping_mul(2),
                    ma / 2,
                    0,
                    M_MIN,
                    M_MAX,
                    -1,
                ]
            };
            each_operand_pair(others, &exponents, &signs, |a, b| {
                assert_eq!(
                    add(&arith, a, b),
                    add_in_jack_order(&arith, a, b),
                    "{a:?} + {b:?}, flag = {flag}"
                );
            });
        }
    }

    /// Calls `check` on (s_a, e_a, m_a) and (s_b, e_b, m_b) for every
    /// mantissa word m_a (in parallel), every m_b of `others(m_a)`, every
    /// pair of `exponents` and every pair of `signs`.
    fn each_operand_pair<const N: usize>(
        others: impl Fn(i16) -> [i16; N] + Sync,
        exponents: &[i16],
        signs: &[(i16, i16)],
        check: impl Fn(F316, F316) + Sync,
    ) {
        use rayon::prelude::*;
        (i16::MIN..=i16::MAX).into_par_iter().for_each(|ma| {
            for mb in others(ma) {
                for &ea in exponents {
                    for &eb in exponents {
                        for &(sa, sb) in signs {
                            check(F316::new(sa, ea, ma), F316::new(sb, eb, mb));
                        }
                    }
                }
            }
        });
    }

    /// Jack's `Float316.mul` transcribed statement by statement (zero test
    /// first, the halves' products, the doubling loop): the model `mul`
    /// is checked against. It shares no helper with `mul` (not
    /// `mul_any`, which `mul` falls back to).
    fn mul_in_jack_order(arith: &Arith, a: F316, b: F316) -> F316 {
        let rs = j::and(j::add(a.s, b.s), 1);
        if (a.e | a.m) == 0 || (b.e | b.m) == 0 {
            return F316::new(rs, 0, 0);
        }
        let mut re = j::sub(j::add(a.e, b.e), 126);
        let ah = j::div(a.m, 128).unwrap();
        let bh = j::div(b.m, 128).unwrap();
        let mut mid = j::add(j::mul(ah, j::and(b.m, 127)), j::mul(j::and(a.m, 127), bh));
        if arith.mul_keeps_low_product {
            let low = j::mul(j::and(a.m, 127), j::and(b.m, 127));
            mid = j::add(mid, j::div(low, 128).unwrap());
        }
        let mut rm = j::add(j::mul(ah, bh), j::div(mid, 128).unwrap());
        if rm > 0 {
            while rm < M_MIN {
                rm = j::add(rm, rm);
                re = j::sub(re, 1);
            }
        }
        F316::new(rs, re, rm)
    }

    /// The spec's arithmetic, and the variant whose `mul` keeps the low
    /// product, with that flag.
    fn with_and_without_low_product() -> [(bool, Arith); 2] {
        [false, true].map(|keep| {
            (
                keep,
                Arith {
                    mul_keeps_low_product: keep,
                    ..Arith::SPEC
                },
            )
        })
    }

    /// `mul` equals Jack's order for every mantissa word against zero,
    /// small, normalised, out-of-range and related mantissas, with edge
    /// exponents, zero operands and sign pairings, with and without the
    /// low product.
    #[test]
    fn mul_equals_jack_order() {
        let exponents = [i16::MIN, 0, 127, i16::MAX];
        let signs = [(0, 0), (0, 1), (1, 1), (2, 3)];
        let others = |ma: i16| [ma, ma ^ 1, 0, 1, 127, 128, M_MIN, M_MAX, 16384, -1];
        for (keep, arith) in with_and_without_low_product() {
            each_operand_pair(others, &exponents, &signs, |a, b| {
                assert_eq!(
                    mul(&arith, a, b),
                    mul_in_jack_order(&arith, a, b),
                    "{a:?} * {b:?}, keep = {keep}"
                );
            });
        }
    }

    /// The shift-only mantissa product equals Jack's for every pair of
    /// mantissas in 0..=16383 (268 million), with and without the low
    /// product.
    #[test]
    fn small_mantissa_product_equals_jack_on_all_pairs() {
        use rayon::prelude::*;
        for (keep, arith) in with_and_without_low_product() {
            (0..=M_MAX).into_par_iter().for_each(|a| {
                for b in 0..=M_MAX {
                    assert_eq!(
                        mantissa_product_small(&arith, a, b),
                        mantissa_product(&arith, a, b),
                        "{a} * {b}, keep = {keep}"
                    );
                }
            });
        }
    }

    /// sqrt's first quotient without the long division equals `div` for
    /// every mantissa word, sign and exponents at and around the wrapping
    /// edges; it applies to every positive normalised `x`.
    #[test]
    fn quotient_of_same_mantissas_equals_div() {
        let exponents = [i16::MIN, -1, 0, 1, 63, 126, 127, 128, 190, i16::MAX];
        for m in i16::MIN..=i16::MAX {
            for s in [0, 1, 2, -1] {
                for xe in exponents {
                    for ge in exponents {
                        let (x, g) = (F316::new(s, xe, m), F316::new(0, ge, m));
                        let fast = div_by_same_mantissa(x, g);
                        if let Some(q) = fast {
                            assert_eq!(Ok(q), div(&Arith::SPEC, x, g), "{x:?} / {g:?}");
                        }
                        assert_eq!(fast.is_some(), s == 0 && is_normalised(m));
                        // A different mantissa never takes the shortcut.
                        let other = F316::new(0, ge, m.wrapping_add(1));
                        assert_eq!(div_by_same_mantissa(x, other), None);
                    }
                }
            }
        }
    }

    /// The fast paths' guard: exactly the mantissas 8192..=16383 (mutation
    /// testing found `is_normalised -> false`, which only turns the fast
    /// paths off, uncaught by the results).
    #[test]
    fn normalised_mantissas_are_8192_to_16383() {
        let normalised: Vec<i16> = (i16::MIN..=i16::MAX)
            .filter(|&m| is_normalised(m))
            .collect();
        assert_eq!(normalised.len(), 8192);
        assert_eq!((normalised[0], normalised[8191]), (8192, 16383));
    }

    /// The closed forms used for speed equal Jack's loops for every word.
    #[test]
    fn closed_forms_equal_the_jack_loops() {
        for m in i16::MIN..=i16::MAX {
            let mut h = m;
            assert_eq!(trunc_shift(m, -3), m);
            for shift in 0..=20i16 {
                let fast = trunc_shift(m, shift);
                assert_eq!(fast, h, "m = {m}, shift = {shift}");
                h = j::halve(h);
            }
            if m > 0 {
                let (mut lm, mut le) = (m, 0i16);
                while lm < M_MIN {
                    lm = j::mul(lm, 2);
                    le = j::sub(le, 1);
                }
                assert_eq!(normalise_positive(m, 0), (lm, le), "m = {m}");
            }
        }
    }

    /// An engine running every operation as `variant`'s call site does.
    fn tuned(variant: Tuning) -> F316Engine {
        let mut e = F316Engine::new(Arith::SPEC);
        e.set_tuning(Some(variant));
        e
    }

    /// `floor-direct` gives the spec's floor at every word of every sign and
    /// exponent of its domain (and the same trap outside it), where a
    /// negative non-integer's `add(r, -1.0)` is done on the mantissa.
    #[test]
    fn floor_direct_equals_floor_on_every_input() {
        use rayon::prelude::*;
        (i16::MIN..=i16::MAX).into_par_iter().for_each(|m| {
            let (mut spec, mut direct) = (F316Engine::new(Arith::SPEC), tuned(Tuning::FloorDirect));
            for e in (0..=142).chain([-1, 200, i16::MIN, i16::MAX]) {
                for s in 0..=1 {
                    let a = F316::new(s, e, m);
                    assert_eq!(spec.floor(a), direct.floor(a), "floor({a:?})");
                }
            }
        });
    }

    /// `truncated-product` keeps only the high halves' product: below the
    /// spec's product by the mixed products over 128, never above it.
    #[test]
    fn truncated_product_is_the_high_halves_product() {
        let mut e = tuned(Tuning::TruncatedProduct);
        let (a, b) = (F316::new(0, 127, 12345), F316::new(1, 130, 9999));
        let t = e.mul(a, b).unwrap();
        let m = (12345 / 128) * (9999 / 128);
        let (m, shift) = if m < M_MIN { (m * 2, 1) } else { (m, 0) };
        assert_eq!(t, F316::new(1, 127 + 130 - 126 - shift, m));
        let spec = F316Engine::new(Arith::SPEC).mul(a, b).unwrap();
        assert!(t.to_f64().abs() < spec.to_f64().abs(), "{t:?} {spec:?}");
        assert!(t.to_f64() / spec.to_f64() > 1.0 - 2.0 / 64.0);
        // Zero operands and signs as the spec's.
        assert_eq!(e.mul(F316::ZERO.negated(), a).unwrap(), F316::new(1, 0, 0));
        // Only `mul` changes.
        assert_eq!(e.add(a, b), F316Engine::new(Arith::SPEC).add(a, b));
    }
}
