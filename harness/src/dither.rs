//! The reference pipeline's last steps, for a port that answers a pixel's
//! shade alone (a Jack program that clamps and dithers inline in its render
//! loop, a pipe adapter without a dither): the clamp to [0, 1] and the 8x8
//! ordered dither, computed as the reference computes them in the port's
//! number type. The white bit is a function of the clamped shade and (x, y)
//! alone, so computing it here is exact.

use crate::implementation::Num;
use common::image_consts::bayer;
use common::{Op, OpValue, Outcome, F316};

/// One Float316 operation of ref-f316.
fn ref_op(op: Op, args: &[F316]) -> Outcome<OpValue> {
    reference::op(op, args, reference::Arith::default()).expect("the operands fit the operation")
}

fn ref_gt(a: F316, b: F316) -> Outcome<bool> {
    ref_op(Op::Gt, &[a, b]).map(|v| v == OpValue::Bool(true))
}

/// ref-f316's clamp (unless `clamped`) and dither with its own operations:
/// a shade above 1 is 1, a negative one 0; pixel (x, y) is white when
/// `add(shade, (B - 32) / 64) > 0.5`, B the Bayer entry of (x, y).
pub fn float316(shade: F316, clamped: bool, x: usize, y: usize) -> Outcome<(F316, bool)> {
    let value = if clamped {
        shade
    } else {
        match ref_gt(shade, F316::ONE) {
            Outcome::Value(true) => F316::ONE,
            Outcome::Value(false) if shade.s == 1 => F316::ZERO,
            Outcome::Value(false) => shade,
            trap => return trap.map(|_| (shade, false)),
        }
    };
    let threshold = (f64::from(bayer(x, y)) - 32.0) / 64.0;
    let threshold = F316::from_f64_truncating(threshold).expect("a Bayer threshold is exact");
    let dithered = match ref_op(Op::Add, &[value, threshold]) {
        Outcome::Value(OpValue::Num(d)) => d,
        other => return other.map(|_| (value, false)),
    };
    let half = F316::new(0, 126, 8192);
    ref_gt(dithered, half).map(|white| (value, white))
}

/// The clamp and dither of ref-f64 and ref-f32, in the shade's own type:
/// white when `(shade + B / 64) - 0.5 > 0.5`.
fn ieee<T>(shade: T, x: usize, y: usize) -> (T, bool)
where
    T: Copy + PartialOrd + From<u8> + std::ops::Add<Output = T> + std::ops::Sub<Output = T>,
    T: std::ops::Div<Output = T> + SignBit,
{
    let one = T::from(1);
    let value = if shade > one {
        one
    } else if shade.sign_bit() {
        T::from(0)
    } else {
        shade
    };
    let half = one / T::from(2);
    let dithered = (value + T::from(bayer(x, y)) / T::from(64)) - half;
    (value, dithered > half)
}

/// The sign bit of an IEEE float (set for -0 too).
trait SignBit {
    fn sign_bit(self) -> bool;
}

impl SignBit for f64 {
    fn sign_bit(self) -> bool {
        self.is_sign_negative()
    }
}

impl SignBit for f32 {
    fn sign_bit(self) -> bool {
        self.is_sign_negative()
    }
}

/// A pixel's shade, clamped, and its white bit, in the shade's number type.
pub fn finish(shade: Num, x: usize, y: usize) -> Outcome<(Num, bool)> {
    match shade {
        Num::F316(t) => float316(t, false, x, y).map(|(v, w)| (Num::F316(v), w)),
        Num::F64(v) => {
            let (v, w) = ieee(v, x, y);
            Outcome::Value((Num::F64(v), w))
        }
        Num::F32(v) => {
            let (v, w) = ieee(v, x, y);
            Outcome::Value((Num::F32(v), w))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use reference::{RefImpl, Reference};

    /// Over a row of pixels, the white bit computed from each reference's
    /// own shade is the reference's white bit, in all three number types.
    #[test]
    fn the_white_bit_of_a_shade_is_the_references() {
        for imp in [RefImpl::F316, RefImpl::F64, RefImpl::F32] {
            let r = Reference::seed(imp);
            for x in (0..512).step_by(3) {
                let y = 150 + x % 8;
                let Outcome::Value(p) = r.pixel(x, y) else {
                    continue;
                };
                let shade = match (imp, p.value.triple) {
                    (RefImpl::F316, Some(t)) => Num::F316(t),
                    (RefImpl::F32, _) => Num::F32(p.value.value as f32),
                    _ => Num::F64(p.value.value),
                };
                assert_eq!(
                    finish(shade, x, y),
                    Outcome::Value((shade, p.white)),
                    "{imp:?} ({x},{y})"
                );
            }
        }
    }
}
