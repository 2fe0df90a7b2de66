//! Float316 operand vectors: random values over the exponent range, values
//! near 1.0 and near the scene's magnitudes, and the hard cases (signed
//! zeros, cancellation, exponent gaps, mantissa carry, exponents that
//! underflowed below 0 and are fed back, sqrt/invsqrt of tiny, huge and zero
//! inputs, division by zero, the non-canonical (0,61,0), the edges of floor
//! and mod2, and inputs that make add or div hang).

use super::Draw;
use crate::set::{OpVector, Vector};
use common::{Op, F316};
use proptest::prelude::*;

/// A normalised value with a random sign and an exponent in `e`.
pub fn normalised(e: std::ops::RangeInclusive<i16>) -> impl Strategy<Value = F316> {
    (0..=1i16, e, 8192..=16383i16).prop_map(|(s, e, m)| F316::new(s, e, m))
}

/// A normalised value anywhere in the 8-bit exponent range.
pub fn any_normalised() -> impl Strategy<Value = F316> {
    normalised(0..=255)
}

/// A value near 1.0 (exponents 126..=128).
pub fn near_one() -> impl Strategy<Value = F316> {
    normalised(126..=128)
}

/// A value of the scene's magnitudes (about 0.004 to 64).
pub fn scene_magnitude() -> impl Strategy<Value = F316> {
    normalised(119..=133)
}

/// A value whose exponent underflowed below 0 (as a product of tiny
/// values leaves it), odd and even exponents alike.
pub fn underflowed() -> impl Strategy<Value = F316> {
    normalised(-40..=-1)
}

const NON_CANONICAL: F316 = F316::new(0, 61, 0);
const ZEROS: [F316; 2] = [F316::ZERO, F316::NEG_ZERO];

/// The categories of operand vectors, each with how it draws operands for
/// one operation (`None`: the category does not apply to that operation).
pub const CATEGORIES: [&str; 16] = [
    "random",
    "near-one",
    "scene",
    "signed-zero",
    "cancellation",
    "exponent-gap",
    "mantissa-carry",
    "underflow",
    "underflow-fed-back",
    "tiny-huge",
    "div-by-zero",
    "non-canonical",
    "domain-edge",
    "exponent-zero",
    "hang",
    "wide-exponent",
];

fn pick<T: Copy>(d: &mut Draw, items: &[T]) -> T {
    items[d.one(&(0..items.len()))]
}

fn with_sign(v: F316, s: i16) -> F316 {
    F316::new(s, v.e, v.m)
}

/// Operands for one vector of `category` and `op`, or `None` when the
/// category means nothing for that operation.
fn operands(d: &mut Draw, category: &str, op: Op) -> Option<(F316, Option<F316>)> {
    let binary = op.arity() == 2;
    let second =
        |d: &mut Draw, s: &dyn Fn(&mut Draw) -> F316| if binary { Some(s(d)) } else { None };
    let draw_any = |d: &mut Draw| d.one(&any_normalised());
    let draw_scene = |d: &mut Draw| d.one(&scene_magnitude());
    Some(match category {
        "random" => (draw_any(d), second(d, &draw_any)),
        "near-one" => {
            let near = |d: &mut Draw| d.one(&near_one());
            (near(d), second(d, &near))
        }
        "scene" => (draw_scene(d), second(d, &draw_scene)),
        "signed-zero" => {
            let z = pick(d, &ZEROS);
            match (binary, d.one(&(0..3u8))) {
                (false, _) => (z, None),
                (true, 0) => (z, Some(pick(d, &ZEROS))),
                (true, 1) => (z, Some(draw_scene(d))),
                (true, _) => (draw_scene(d), Some(z)),
            }
        }
        "cancellation" if binary => {
            // Equal magnitudes whose effective signs differ, or differ by
            // one unit in the last place.
            let a = draw_scene(d);
            let m = (a.m + d.one(&(-1..=1i16))).clamp(8192, 16383);
            let s = if op == Op::Sub { a.s } else { 1 - a.s };
            (a, Some(F316::new(s, a.e, m)))
        }
        "exponent-gap" if binary => {
            let a = draw_scene(d);
            let gap = d.one(&(0..=30i16));
            let b = F316::new(d.one(&(0..=1i16)), a.e - gap, d.one(&(8192..=16383i16)));
            if d.one(&any::<bool>()) {
                (a, Some(b))
            } else {
                (b, Some(a))
            }
        }
        "mantissa-carry" => {
            let carry =
                |d: &mut Draw| F316::new(0, d.one(&(120..=134i16)), d.one(&(16300..=16383i16)));
            (carry(d), second(d, &carry))
        }
        "underflow" => {
            // Products and quotients whose exponent leaves the range.
            let tiny = |d: &mut Draw| d.one(&normalised(1..=20));
            match op {
                Op::Div => (tiny(d), Some(d.one(&normalised(200..=255)))),
                _ => (tiny(d), second(d, &tiny)),
            }
        }
        "underflow-fed-back" => {
            let u = d.one(&underflowed());
            let u = if matches!(op, Op::Sqrt | Op::InvSqrt) {
                with_sign(u, 0)
            } else {
                u
            };
            (u, second(d, &draw_scene))
        }
        "tiny-huge" => {
            let e = pick(d, &[1i16, 2, 3, 4, 5, 250, 251, 252, 253, 254, 255, 300]);
            let v = F316::new(0, e, d.one(&(8192..=16383i16)));
            (v, second(d, &draw_scene))
        }
        "div-by-zero" if op == Op::Div => (draw_scene(d), Some(pick(d, &ZEROS))),
        "non-canonical" => match (binary, d.one(&(0..3u8))) {
            (false, _) => (NON_CANONICAL, None),
            (true, 0) => (NON_CANONICAL, Some(draw_scene(d))),
            (true, 1) => (draw_scene(d), Some(NON_CANONICAL)),
            (true, _) => (NON_CANONICAL, Some(NON_CANONICAL)),
        },
        "domain-edge" if matches!(op, Op::Floor | Op::Mod2) => {
            // i = e - 127 around the domain 0..=13, integral or not.
            let e = 127 + d.one(&(-2..=15i16));
            let m = d.one(&(8192..=16383i16));
            let m = if op == Op::Mod2 && d.one(&any::<bool>()) {
                // Clear the fraction bits so that the value is an integer.
                let i = (e - 127).clamp(0, 13);
                m & !((1i16 << (13 - i)) - 1)
            } else {
                m
            };
            (F316::new(d.one(&(0..=1i16)), e, m), None)
        }
        "domain-edge" if matches!(op, Op::Sqrt | Op::InvSqrt) => {
            // Negative inputs, including -0: Sys.error.
            (
                F316::new(
                    1,
                    d.one(&(0..=140i16)),
                    pick(d, &[0i16, 8192, 12000, 16383]),
                ),
                None,
            )
        }
        "exponent-zero" if !binary => {
            let e = d.one(&(0..=3i16));
            (
                F316::new(d.one(&(0..=1i16)), e, pick(d, &[0i16, 8192, 16383])),
                None,
            )
        }
        "hang" => hang_case(d, op)?,
        "wide-exponent" => {
            let wide = |d: &mut Draw| d.one(&normalised(256..=32767));
            (wide(d), second(d, &wide))
        }
        _ => return None,
    })
}

/// Inputs for which the Jack program loops forever: add of different signs
/// whose aligned mantissas cancel to 0 without being equal, and division
/// of a non-canonical value with `m = 0`.
fn hang_case(d: &mut Draw, op: Op) -> Option<(F316, Option<F316>)> {
    let e = d.one(&(1..=200i16));
    match op {
        Op::Add => Some((F316::new(0, e + 1, 0), Some(F316::new(1, e, 0)))),
        Op::Sub => Some((F316::new(0, e + 1, 0), Some(F316::new(0, e, 0)))),
        Op::Div => Some((
            F316::new(d.one(&(0..=1i16)), e, 0),
            Some(d.one(&scene_magnitude())),
        )),
        _ => None,
    }
}

/// `per_category` vectors for every operation and every category that
/// applies to it, in a fixed order (operation, then category).
pub fn generate(seed: u64, per_category: usize) -> Vec<Vector> {
    let mut d = Draw::new(seed);
    let mut out = Vec::new();
    for op in Op::ALL {
        for category in CATEGORIES {
            for _ in 0..per_category {
                match operands(&mut d, category, op) {
                    Some((a, b)) => out.push(Vector::Op(OpVector {
                        category: category.to_string(),
                        op,
                        a,
                        b,
                    })),
                    None => break,
                }
            }
        }
    }
    out
}

/// Every normalised input of both signs (s in {0,1}, e in 0..=255, m in
/// 8192..=16383) plus the two zeros, for the exhaustive checks of unary
/// operations: 4,194,306 values. `slice` takes every n-th value only.
pub fn all_normalised(step: usize) -> impl Iterator<Item = F316> {
    let zeros = [F316::ZERO, F316::NEG_ZERO].into_iter();
    let all = (0..=1i16).flat_map(|s| {
        (0..=255i16).flat_map(move |e| (8192..=16383i16).map(move |m| F316::new(s, e, m)))
    });
    zeros.chain(all).step_by(step.max(1))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn generation_is_deterministic_and_covers_every_op() {
        let a = generate(316, 2);
        assert_eq!(a, generate(316, 2));
        assert_ne!(a, generate(317, 2));
        for op in Op::ALL {
            assert!(
                a.iter().any(|v| matches!(v, Vector::Op(o) if o.op == op)),
                "{op}"
            );
        }
        for v in &a {
            let Vector::Op(o) = v else { panic!() };
            assert_eq!(o.b.is_some(), o.op.arity() == 2, "{v}");
        }
    }

    #[test]
    fn hard_cases_are_present() {
        let all = generate(1, 3);
        let has =
            |f: &dyn Fn(&OpVector) -> bool| all.iter().any(|v| matches!(v, Vector::Op(o) if f(o)));
        assert!(has(&|o| o.op == Op::Div && o.b.is_some_and(F316::is_zero)));
        assert!(has(&|o| o.op == Op::Sqrt && o.a == NON_CANONICAL));
        assert!(has(&|o| o.op == Op::Sqrt && o.a.e < 0 && o.a.e % 2 != 0));
        assert!(has(&|o| o.op == Op::Add && o.category == "hang"));
    }

    #[test]
    fn exhaustive_domain_size() {
        assert_eq!(all_normalised(1).count(), 2 + 2 * 256 * 8192);
        assert_eq!(
            all_normalised(1000).count(),
            (2usize + 2 * 256 * 8192).div_ceil(1000)
        );
    }
}
