//! Equivalence classes of the binary operations on normalised operands,
//! for exhaustive sweeps (`harness sweep OP`; the argument is written out in
//! `docs/coverage.md`).
//!
//! On normalised operands (mantissas in 8192..=16383, so neither is a zero)
//! and away from the 16-bit wrap of the exponent:
//! - `add` and `sub` depend on the exponents only through their difference
//!   `d = a.e - b.e`, and the result's exponent moves with them: adding `k`
//!   to both exponents adds `k` to the result's. Every `|d| >= 14` behaves
//!   like 14, since 14 halvings take any mantissa below 16384 to 0.
//!   Classes: 4 sign pairs x 29 differences x 8192^2 mantissa pairs.
//! - `mul` and `div` compute the result's mantissa from the mantissas alone;
//!   the exponents only add (`a.e + b.e - 126`, `a.e - b.e + 127`) before
//!   the same normalisation. Classes: 4 sign pairs x 8192^2 mantissa pairs.
//! - `gt` depends on the signs, the sign of `d` and the order of the
//!   mantissas. Classes: 4 sign pairs x 3 orders of the exponents x 8192^2.
//!
//! A class's representative has `b.e = 127` and `a.e = 127 + d`.

use crate::set::OpVector;
use common::{Op, F316};

/// Mantissas of normalised values: 8192..=16383.
const MANTISSAS: u64 = 8192;
/// Exponent differences of add and sub: -14..=14.
const ADD_GAPS: u64 = 29;
/// The largest exponent difference that still changes the result.
const MAX_GAP: i64 = 14;

/// The category of every sweep vector.
pub const CATEGORY: &str = "sweep";

/// How many exponent classes `op` has (the differences it depends on), or
/// `None` when `op` has no sweep.
fn exponent_classes(op: Op) -> Option<u64> {
    match op {
        Op::Add | Op::Sub => Some(ADD_GAPS),
        Op::Mul | Op::Div => Some(1),
        Op::Gt => Some(3),
        _ => None,
    }
}

/// The binary operations that have a sweep.
pub const SWEPT: [Op; 5] = [Op::Add, Op::Sub, Op::Mul, Op::Div, Op::Gt];

/// How many classes `op` has, or `None` when it has no sweep.
pub fn class_count(op: Op) -> Option<u64> {
    exponent_classes(op).map(|gaps| 4 * gaps * MANTISSAS * MANTISSAS)
}

/// The exponent difference `a.e - b.e` of exponent class `g`.
fn gap(op: Op, g: u64) -> i64 {
    match op {
        Op::Add | Op::Sub => g as i64 - MAX_GAP,
        Op::Gt => g as i64 - 1,
        _ => 0,
    }
}

/// The representative of class `index` of `op` (`index < class_count(op)`).
pub fn representative(op: Op, index: u64) -> OpVector {
    let gaps = exponent_classes(op).expect("representative of a swept operation");
    let mb = index % MANTISSAS;
    let ma = (index / MANTISSAS) % MANTISSAS;
    let g = (index / (MANTISSAS * MANTISSAS)) % gaps;
    let signs = index / (MANTISSAS * MANTISSAS * gaps);
    let d = gap(op, g) as i16;
    OpVector {
        category: CATEGORY.to_string(),
        op,
        a: F316::new((signs >> 1) as i16, 127 + d, 8192 + ma as i16),
        b: Some(F316::new((signs & 1) as i16, 127, 8192 + mb as i16)),
    }
}

/// The class index of normalised operands `a` and `b` under `op`: the
/// inverse of [`representative`] on representatives, and on any other pair
/// the class whose result it shares (up to the exponent shift).
pub fn class_of(op: Op, a: F316, b: F316) -> u64 {
    let gaps = exponent_classes(op).expect("class of a swept operation");
    let d = i64::from(a.e) - i64::from(b.e);
    let g = match op {
        Op::Add | Op::Sub => (d.clamp(-MAX_GAP, MAX_GAP) + MAX_GAP) as u64,
        Op::Gt => (d.signum() + 1) as u64,
        _ => 0,
    };
    let signs = (a.s as u64) << 1 | b.s as u64;
    let ma = (a.m - 8192) as u64;
    let mb = (b.m - 8192) as u64;
    ((signs * gaps + g) * MANTISSAS + ma) * MANTISSAS + mb
}

/// Whether class `index` belongs to shard `k` of `n`: the first SplitMix64
/// output seeded with the index, modulo `n` (a vector's shard depends only
/// on its class).
pub fn in_shard(index: u64, k: u32, n: u32) -> bool {
    common::SplitMix64::new(index).below(u64::from(n)) == u64::from(k)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts() {
        assert_eq!(class_count(Op::Add), Some(4 * 29 * 8192 * 8192));
        assert_eq!(class_count(Op::Mul), Some(4 * 8192 * 8192));
        assert_eq!(class_count(Op::Gt), Some(12 * 8192 * 8192));
        assert_eq!(class_count(Op::Sqrt), None);
    }

    #[test]
    fn class_of_inverts_representative() {
        for op in SWEPT {
            let n = class_count(op).unwrap();
            for index in [0, 1, 8191, 8192, n / 3, n / 2 + 12345, n - 1] {
                let v = representative(op, index);
                assert_eq!(class_of(op, v.a, v.b.unwrap()), index, "{op} {index}");
            }
        }
    }

    #[test]
    fn wide_gaps_fall_into_the_widest_class() {
        let a = F316::new(0, 200, 9000);
        let b = F316::new(1, 100, 12000);
        let v = representative(Op::Add, class_of(Op::Add, a, b));
        assert_eq!(v.a.e - v.b.unwrap().e, 14);
    }

    #[test]
    fn shards_split_classes_evenly() {
        let per: Vec<usize> = (0..4)
            .map(|k| (0..40_000u64).filter(|&i| in_shard(i, k, 4)).count())
            .collect();
        assert_eq!(per.iter().sum::<usize>(), 40_000);
        assert!(per.iter().all(|&c| (9_000..11_000).contains(&c)), "{per:?}");
    }
}
