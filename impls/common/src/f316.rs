//! The Float316 triple `(s, e, m)` as stored in Jack objects (three 16-bit
//! fields in the order s, e, m). The arithmetic lives in the reference
//! implementation; this is only the value and its interpretation.

use serde::{Deserialize, Serialize};
use std::fmt;

/// A Float316 value: sign `s` (0 or 1), biased exponent `e` (bias 127) and a
/// 16-bit mantissa `m` whose normalised form lies in [8192, 16383].
/// Value: `(-1)^s * m * 2^(e - 140)`. Fields are Jack words; any triple can
/// be represented, including non-canonical and out-of-domain ones.
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(from = "[i16; 3]", into = "[i16; 3]")]
pub struct F316 {
    pub s: i16,
    pub e: i16,
    pub m: i16,
}

impl F316 {
    /// Positive zero (0,0,0).
    pub const ZERO: F316 = F316::new(0, 0, 0);
    /// Negative zero (1,0,0).
    pub const NEG_ZERO: F316 = F316::new(1, 0, 0);
    /// 1.0 = (0,127,8192).
    pub const ONE: F316 = F316::new(0, 127, 8192);

    /// Build a triple from its fields.
    pub const fn new(s: i16, e: i16, m: i16) -> Self {
        F316 { s, e, m }
    }

    /// Zero in the sense of the spec's zero tests: `e = 0 and m = 0`
    /// (either sign). The non-canonical (0,61,0) is not zero.
    pub const fn is_zero(self) -> bool {
        self.e == 0 && self.m == 0
    }

    /// A normalised value: sign 0 or 1, mantissa in [8192, 16383].
    pub const fn is_normalised(self) -> bool {
        (self.s == 0 || self.s == 1) && self.m >= 8192
    }

    /// The exact real value of the triple, `(-1)^s * m * 2^(e - 140)`, as f64
    /// (exact for every triple: m has at most 16 bits).
    pub fn to_f64(self) -> f64 {
        let sign = if self.s & 1 == 1 { -1.0 } else { 1.0 };
        sign * (self.m as f64) * 2f64.powi(self.e as i32 - 140)
    }

    /// Encode a real number by truncating (not rounding) the mantissa to 13
    /// fraction bits, as the spec encodes its decimal constants. Returns
    /// `None` when the value is not finite or its exponent does not fit in
    /// 1..=32767. Zero gives (0,0,0) or (1,0,0).
    pub fn from_f64_truncating(x: f64) -> Option<Self> {
        if !x.is_finite() {
            return None;
        }
        let s = if x.is_sign_negative() { 1 } else { 0 };
        let a = x.abs();
        if a == 0.0 {
            return Some(F316::new(s, 0, 0));
        }
        // a = f * 2^k with f in [1, 2).
        let mut k = a.log2().floor() as i32;
        // Guard against log2 rounding at exact powers of two.
        while 2f64.powi(k) > a {
            k -= 1;
        }
        while 2f64.powi(k + 1) <= a {
            k += 1;
        }
        let m = (a / 2f64.powi(k - 13)).floor() as i32;
        let e = k + 127;
        if !(1..=32767).contains(&e) || !(8192..=16383).contains(&m) {
            return None;
        }
        Some(F316::new(s, e as i16, m as i16))
    }

    /// The same value with its sign flipped.
    pub const fn negated(self) -> Self {
        F316::new(1 - (self.s & 1), self.e, self.m)
    }
}

impl From<[i16; 3]> for F316 {
    fn from(t: [i16; 3]) -> Self {
        F316::new(t[0], t[1], t[2])
    }
}

impl From<F316> for [i16; 3] {
    fn from(v: F316) -> Self {
        [v.s, v.e, v.m]
    }
}

impl fmt::Debug for F316 {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "({},{},{})", self.s, self.e, self.m)
    }
}

impl fmt::Display for F316 {
    /// `(s,e,m)=value`, e.g. `(0,127,8192)=1`, the value as
    /// [`crate::shown`] shows it (`(0,1124,8192)=2.78...e300`, never 301
    /// digits).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "({},{},{})={}",
            self.s,
            self.e,
            self.m,
            crate::Shown(self.to_f64())
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The value is shown compactly: `1.3393857589828342e300` for 2^997,
    /// not its 301 digits (issue 35 item 11).
    #[test]
    fn a_huge_or_tiny_value_is_shown_compactly() {
        assert_eq!(
            F316::new(0, 1124, 8192).to_string(),
            "(0,1124,8192)=1.3393857589828342e300"
        );
        assert_eq!(
            F316::new(0, 48, 8857).to_string(),
            "(0,48,8857)=1.7886569056108804e-24"
        );
        assert_eq!(F316::ONE.to_string(), "(0,127,8192)=1");
    }

    #[test]
    fn spec_constants_round_trip() {
        let table: &[(f64, [i16; 3])] = &[
            (1.0, [0, 127, 8192]),
            (-1.0, [1, 127, 8192]),
            (1.5, [0, 127, 12288]),
            (0.5, [0, 126, 8192]),
            (2.0, [0, 128, 8192]),
            (5.0, [0, 129, 10240]),
            (12.0, [0, 130, 12288]),
            (124.0, [0, 133, 15872]),
            (512.0, [0, 136, 8192]),
            (-25.75, [1, 131, 13184]),
            (0.01, [0, 120, 10485]),
            (0.005, [0, 119, 10485]),
            (0.7, [0, 126, 11468]),
            (0.835, [0, 126, 13680]),
            (0.167, [0, 124, 10944]),
            (0.63, [0, 126, 10321]),
            (0.35, [0, 125, 11468]),
            (0.25, [0, 125, 8192]),
            (0.02, [0, 121, 10485]),
        ];
        for &(x, t) in table {
            assert_eq!(F316::from_f64_truncating(x), Some(F316::from(t)), "{x}");
        }
        assert_eq!(F316::new(0, 127, 8193).to_f64(), 1.0001220703125);
        assert_eq!(F316::new(1, 131, 13184).to_f64(), -25.75);
    }

    #[test]
    fn zero_tests_ignore_non_canonical() {
        assert!(F316::ZERO.is_zero());
        assert!(F316::NEG_ZERO.is_zero());
        assert!(!F316::new(0, 61, 0).is_zero());
        assert_eq!(F316::from_f64_truncating(-0.0), Some(F316::NEG_ZERO));
    }

    #[test]
    fn serde_as_triple() {
        let v = F316::new(1, 131, 13184);
        assert_eq!(serde_json::to_string(&v).unwrap(), "[1,131,13184]");
        let back: F316 = serde_json::from_str("[1,131,13184]").unwrap();
        assert_eq!(back, v);
    }
}
