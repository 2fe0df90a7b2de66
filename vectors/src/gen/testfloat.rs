//! Float316 operand cases in the manner of Berkeley TestFloat: every
//! combination of a sign, an exponent from a table and a mantissa pattern
//! from a table, at two levels, with weighted random pairs interleaved at
//! level 2 (see `docs/coverage.md`).
//!
//! The exponent tables hold the edges (0, 1, 2, 253..=255), the values
//! around the bias (126..=128), the scene's magnitudes (119..=133) and
//! exponents that underflowed below 0 and are fed back into an operation.
//! The mantissa tables hold the patterns of the 13 stored fraction bits
//! (the leading one alone, single bits, runs of ones from the top and from
//! the bottom, all ones less one bit) and words that set the carry and
//! overflow-detector bits above the leading one (16384, 24576, 32767), plus
//! 0, which makes a zero with exponent 0 and the non-canonical value
//! otherwise.
//!
//! Counts per operation, of the order of TestFloat's for a 16-bit format
//! (408 / 46,464 at level 1, 2,448 / 1,254,528 at level 2):
//!
//! | level | unary | binary |
//! |---|---:|---:|
//! | 1 | 408 | 46,656 |
//! | 2 | 2,448 | 1,254,528 |

use super::Draw;
use crate::set::{Level, OpVector, Vector, VectorSet};
use common::{Op, F316};
use std::fmt;
use std::str::FromStr;

/// A TestFloat level: 1 is quick, 2 is thorough.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CaseLevel {
    /// Tables only: 408 unary, 46,656 binary cases.
    One,
    /// Larger tables and weighted random pairs: 2,448 unary, 1,254,528
    /// binary cases.
    Two,
}

impl CaseLevel {
    /// Both levels.
    pub const ALL: [CaseLevel; 2] = [CaseLevel::One, CaseLevel::Two];

    /// The level's number (1 or 2).
    pub fn number(self) -> u8 {
        match self {
            CaseLevel::One => 1,
            CaseLevel::Two => 2,
        }
    }

    /// The category every table case of this level carries.
    pub fn table_category(self) -> &'static str {
        match self {
            CaseLevel::One => "testfloat-1",
            CaseLevel::Two => "testfloat-2",
        }
    }

    /// (exponents, mantissas) of a unary operand.
    fn unary_tables(self) -> (&'static [i16], &'static [i16]) {
        match self {
            CaseLevel::One => (EXPONENTS_1, MANTISSAS_1),
            CaseLevel::Two => (EXPONENTS_2, MANTISSAS_2),
        }
    }

    /// (exponents, mantissas) of each operand of a binary operation.
    fn binary_tables(self) -> (&'static [i16], &'static [i16]) {
        match self {
            CaseLevel::One => (EXPONENTS_1, BINARY_MANTISSAS_1),
            CaseLevel::Two => (BINARY_EXPONENTS_2, BINARY_MANTISSAS_2),
        }
    }

    /// How many weighted random pairs follow the table pairs.
    fn random_pairs(self) -> usize {
        match self {
            CaseLevel::One => 0,
            CaseLevel::Two => LEVEL_2_RANDOM_PAIRS,
        }
    }

    /// How many cases `op` gets at this level.
    pub fn count(self, op: Op) -> usize {
        if op.arity() == 1 {
            let (e, m) = self.unary_tables();
            2 * e.len() * m.len()
        } else {
            let (e, m) = self.binary_tables();
            let per_operand = 2 * e.len() * m.len();
            per_operand * per_operand + self.random_pairs()
        }
    }
}

impl fmt::Display for CaseLevel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.number())
    }
}

impl FromStr for CaseLevel {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "1" => Ok(CaseLevel::One),
            "2" => Ok(CaseLevel::Two),
            _ => Err(format!("unknown case level `{s}` (expected 1 or 2)")),
        }
    }
}

/// Level 1 exponents: zero and the lowest, an underflowed one, the scene's
/// range ends, the bias and its neighbours, the highest.
const EXPONENTS_1: &[i16] = &[-1, 0, 1, 2, 119, 126, 127, 128, 133, 253, 254, 255];

/// Level 2 exponents: level 1's and more underflowed values, every exponent
/// of the scene's magnitudes, and steps through the middle of the range.
const EXPONENTS_2: &[i16] = &[
    -40, -13, -2, -1, 0, 1, 2, 3, 14, 64, 100, 113, 118, 119, 120, 121, 122, 123, 124, 125, 126,
    127, 128, 129, 130, 131, 132, 133, 134, 140, 141, 160, 200, 253, 254, 255,
];

/// Binary level 2 exponents: every difference from 0 to 15 occurs between
/// two entries near the bias (alignment shifts of 0 to 15 bits), plus the
/// edges and an underflowed value.
const BINARY_EXPONENTS_2: &[i16] = &[
    -20, 0, 1, 2, 112, 118, 120, 122, 123, 124, 125, 126, 127, 128, 129, 130, 131, 133, 135, 141,
    200, 253, 254, 255,
];

/// Level 1 mantissas (17): 0, the leading one alone, all ones, the lowest
/// bit, all ones less the lowest bit, the top fraction bit alone and
/// cleared, single middle bits, runs of ones from the top and the bottom,
/// and the carry and overflow-detector bits.
const MANTISSAS_1: &[i16] = &[
    0,
    8192,
    16383,
    8193,
    16382,
    8192 | 4096,
    16383 & !4096,
    8192 | 64,
    8192 | 2,
    8192 | 0b1_1100_0000_0000, // a run of three ones from the top
    8192 | 0b0_0000_0000_0111, // a run of three ones from the bottom
    8192 | 0b1_1111_1110_0000,
    8192 | 0b0_0000_0111_1111,
    16383 & !64,
    16384,
    24576,
    32767,
];

/// Level 2 mantissas (34): level 1's and every single fraction bit.
const MANTISSAS_2: &[i16] = &[
    0,
    8192,
    16383,
    8193,
    16382,
    8192 | 4096,
    16383 & !4096,
    8192 | 2048,
    8192 | 1024,
    8192 | 512,
    8192 | 256,
    8192 | 128,
    8192 | 64,
    8192 | 32,
    8192 | 16,
    8192 | 8,
    8192 | 4,
    8192 | 2,
    8192 | 0b1_1000_0000_0000,
    8192 | 0b1_1100_0000_0000,
    8192 | 0b1_1111_1110_0000,
    8192 | 0b1_1111_1111_1100,
    8192 | 0b0_0000_0000_0011,
    8192 | 0b0_0000_0000_0111,
    8192 | 0b0_0000_0111_1111,
    8192 | 0b0_0000_0001_1111,
    16383 & !2048,
    16383 & !64,
    16383 & !2,
    16384,
    16385,
    24576,
    32766,
    32767,
];

/// Binary level 1 mantissas (9): both ends, the lowest bit, the top
/// fraction bit, runs of ones and the carry bit.
const BINARY_MANTISSAS_1: &[i16] = &[
    0,
    8192,
    16383,
    8193,
    16382,
    8192 | 4096,
    8192 | 0b1_1100_0000_0000,
    8192 | 0b0_0000_0000_0111,
    16384,
];

/// Binary level 2 mantissas (23).
const BINARY_MANTISSAS_2: &[i16] = &[
    0,
    8192,
    16383,
    8193,
    8194,
    16382,
    16381,
    8192 | 4096,
    16383 & !4096,
    8192 | 2048,
    8192 | 64,
    8192 | 0b1_1000_0000_0000,
    8192 | 0b1_1111_1110_0000,
    8192 | 0b0_0000_0000_0011,
    8192 | 0b0_0000_0111_1111,
    8192 | 0b0_0000_0001_1111,
    16383 & !64,
    16383 & !1024,
    12289,
    8192 | 0b1_0101_0101_0101, // alternating bits
    16384,
    24576,
    32767,
];

/// Weighted random pairs at level 2: with the table pairs they make
/// TestFloat's 1,254,528 binary cases.
const LEVEL_2_RANDOM_PAIRS: usize = 1_254_528 - (2 * 24 * 23) * (2 * 24 * 23);

/// The category of the weighted random pairs.
pub const RANDOM_CATEGORY: &str = "testfloat-2-random";

/// Every (sign, exponent, mantissa) of the tables, signs outermost.
fn table_values(exponents: &'static [i16], mantissas: &'static [i16]) -> Vec<F316> {
    (0..=1i16)
        .flat_map(|s| {
            exponents
                .iter()
                .flat_map(move |&e| mantissas.iter().map(move |&m| F316::new(s, e, m)))
        })
        .collect()
}

/// One weighted random operand pair: half of them have exponents at most
/// 15 apart (alignment and cancellation in add and sub, carries in mul),
/// a quarter are of the scene's magnitudes, a quarter anywhere in
/// -40..=255; one mantissa in eight is a table pattern.
fn random_pair(d: &mut Draw) -> (F316, F316) {
    let mantissa = |d: &mut Draw| {
        if d.one(&(0..8u8)) == 0 {
            BINARY_MANTISSAS_2[d.one(&(0..BINARY_MANTISSAS_2.len()))]
        } else {
            d.one(&(8192..=16383i16))
        }
    };
    let (ea, eb) = match d.one(&(0..4u8)) {
        0 | 1 => {
            let ea = d.one(&(1..=254i16));
            (ea, (ea + d.one(&(-15..=15i16))).clamp(-40, 255))
        }
        2 => (d.one(&(119..=133i16)), d.one(&(119..=133i16))),
        _ => (d.one(&(-40..=255i16)), d.one(&(-40..=255i16))),
    };
    let a = F316::new(d.one(&(0..=1i16)), ea, mantissa(d));
    let b = F316::new(d.one(&(0..=1i16)), eb, mantissa(d));
    (a, b)
}

/// The cases of `op` at `level`, in a fixed order; `seed` fixes the random
/// pairs (the tables do not depend on it).
pub fn cases(op: Op, level: CaseLevel, seed: u64) -> Vec<Vector> {
    let vector = |category: &str, a, b| {
        Vector::Op(OpVector {
            category: category.to_string(),
            op,
            a,
            b,
        })
    };
    let category = level.table_category();
    if op.arity() == 1 {
        let (e, m) = level.unary_tables();
        return table_values(e, m)
            .into_iter()
            .map(|a| vector(category, a, None))
            .collect();
    }
    let (e, m) = level.binary_tables();
    let values = table_values(e, m);
    let mut out = Vec::with_capacity(level.count(op));
    for &a in &values {
        out.extend(values.iter().map(|&b| vector(category, a, Some(b))));
    }
    let op_number = Op::ALL.iter().position(|&o| o == op).unwrap_or(0) as u64;
    let mut d = Draw::new(seed ^ (op_number << 32));
    for _ in 0..level.random_pairs() {
        let (a, b) = random_pair(&mut d);
        out.push(vector(RANDOM_CATEGORY, a, Some(b)));
    }
    out
}

/// The default seed of the random pairs.
pub const DEFAULT_SEED: u64 = 316;

/// The cases of `ops` at `level` as one vector set, named
/// `testfloat-LEVEL` (or `testfloat-LEVEL-OP` for a single operation).
pub fn set(ops: &[Op], level: CaseLevel, seed: u64) -> VectorSet {
    let name = match ops {
        [op] => format!("testfloat-{level}-{op}"),
        _ => format!("testfloat-{level}"),
    };
    let description =
        format!(
        "TestFloat-style Float316 cases, level {level}: sign x exponent table x mantissa pattern \
         table{} (docs/coverage.md)",
        if level == CaseLevel::Two { ", then weighted random pairs" } else { "" }
    );
    let vectors = ops.iter().flat_map(|&op| cases(op, level, seed)).collect();
    VectorSet::new(&name, Level::Ops, &description, Some(seed), vectors)
}

/// The set a `testfloat-LEVEL[-OP]` name stands for (with the default
/// seed), or `None` for any other name.
pub fn named(name: &str) -> Option<VectorSet> {
    let rest = name.strip_prefix("testfloat-")?;
    let (level, op) = match rest.split_once('-') {
        Some((level, op)) => (level, Some(op.parse::<Op>().ok()?)),
        None => (rest, None),
    };
    let level: CaseLevel = level.parse().ok()?;
    let ops = op.map_or_else(|| Op::ALL.to_vec(), |op| vec![op]);
    Some(set(&ops, level, DEFAULT_SEED))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_stand_for_their_sets() {
        let s = named("testfloat-1-sqrt").unwrap();
        assert_eq!(
            (s.name.as_str(), s.vectors.len()),
            ("testfloat-1-sqrt", 408)
        );
        assert_eq!(
            named("testfloat-1").unwrap().vectors.len(),
            7 * 408 + 5 * 46_656
        );
        for bad in ["testfloat-3", "testfloat-1-nope", "ops-small", "testfloat-"] {
            assert!(named(bad).is_none(), "{bad}");
        }
    }

    #[test]
    fn counts_match_the_documented_table() {
        for op in Op::ALL {
            let (one, two) = if op.arity() == 1 {
                (408, 2_448)
            } else {
                (46_656, 1_254_528)
            };
            assert_eq!(CaseLevel::One.count(op), one, "{op}");
            assert_eq!(CaseLevel::Two.count(op), two, "{op}");
        }
        assert_eq!(cases(Op::Sqrt, CaseLevel::Two, 1).len(), 2_448);
        assert_eq!(cases(Op::Add, CaseLevel::One, 1).len(), 46_656);
    }

    #[test]
    fn tables_have_no_repeated_entries() {
        for table in [
            EXPONENTS_1,
            EXPONENTS_2,
            BINARY_EXPONENTS_2,
            MANTISSAS_1,
            MANTISSAS_2,
            BINARY_MANTISSAS_1,
            BINARY_MANTISSAS_2,
        ] {
            let mut sorted = table.to_vec();
            sorted.sort_unstable();
            sorted.dedup();
            assert_eq!(sorted.len(), table.len(), "{table:?}");
        }
        assert_eq!(MANTISSAS_1.len(), 17);
        assert_eq!(MANTISSAS_2.len(), 34);
        assert_eq!(EXPONENTS_2.len(), 36);
    }

    #[test]
    fn every_alignment_shift_occurs_between_binary_exponents() {
        for gap in 0..=15 {
            assert!(
                BINARY_EXPONENTS_2
                    .iter()
                    .any(|a| BINARY_EXPONENTS_2.contains(&(a + gap)) && (110..=145).contains(a)),
                "gap {gap}"
            );
        }
    }

    #[test]
    fn random_pairs_depend_on_the_seed_and_tables_do_not() {
        let a = cases(Op::Div, CaseLevel::Two, 7);
        let b = cases(Op::Div, CaseLevel::Two, 8);
        let tables = CaseLevel::Two.count(Op::Div) - LEVEL_2_RANDOM_PAIRS;
        assert_eq!(a[..tables], b[..tables]);
        assert_ne!(a[tables..], b[tables..]);
        assert_eq!(a, cases(Op::Div, CaseLevel::Two, 7));
        assert!(a[tables..].iter().all(|v| v.category() == RANDOM_CATEGORY));
    }

    #[test]
    fn patterns_cover_single_bits_runs_and_detector_bits() {
        for bit in 1..13 {
            assert!(MANTISSAS_2.contains(&(8192 | (1 << bit))), "bit {bit}");
        }
        for word in [0, 8192, 16383, 16384, 32767] {
            assert!(MANTISSAS_1.contains(&word));
        }
    }
}
