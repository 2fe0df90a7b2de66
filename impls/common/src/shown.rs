//! Numbers in messages: a value a user gave or an implementation answered
//! is shown in Rust's shortest form that reads back to it, in scientific
//! notation when it is very large or very small, so that `1e300` is never
//! printed as a 301-digit number (issue 35 item 11).

use std::fmt;

/// The magnitude from which a value is shown in scientific notation.
pub const LARGE: f64 = 1e15;
/// The magnitude below which a (non-zero) value is shown in scientific
/// notation.
pub const SMALL: f64 = 1e-6;

/// `x` for a message: `0.25`, `-3`, `1e300`, `1.5e-9`, `NaN`, `inf`.
pub fn shown(x: f64) -> String {
    Shown(x).to_string()
}

/// [`shown`] for an f32 value (its own shortest form, not its f64
/// widening's: `0.1`, not `0.10000000149011612`).
pub fn shown_f32(x: f32) -> String {
    Shown(x).to_string()
}

/// A number shown as [`shown`] shows it, for `format!` arguments.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shown<T>(pub T);

impl<T: Copy + Into<f64> + fmt::Display + fmt::LowerExp> fmt::Display for Shown<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let magnitude = self.0.into().abs();
        if magnitude.is_finite() && magnitude != 0.0 && !(SMALL..LARGE).contains(&magnitude) {
            write!(f, "{:e}", self.0)
        } else {
            write!(f, "{}", self.0)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn large_and_small_magnitudes_are_scientific() {
        assert_eq!(shown(1e300), "1e300");
        assert_eq!(shown(-1e300), "-1e300");
        assert_eq!(shown(f64::MAX), "1.7976931348623157e308");
        assert_eq!(shown(1.5e-9), "1.5e-9");
        assert_eq!(shown(5e-324), "5e-324");
        assert_eq!(shown_f32(f32::MAX), "3.4028235e38");
        assert_eq!(shown(1e15), "1e15");
        assert_eq!(shown(147564945390421670000.0), "1.4756494539042167e20");
    }

    #[test]
    fn ordinary_values_are_plain() {
        assert_eq!(shown(0.0), "0");
        assert_eq!(shown(-0.0), "-0");
        assert_eq!(shown(0.25), "0.25");
        assert_eq!(shown(-3.0), "-3");
        assert_eq!(shown(123456.789), "123456.789");
        assert_eq!(shown(999999999999999.9), "999999999999999.9");
        assert_eq!(shown(1e-6), "0.000001");
        assert_eq!(shown_f32(0.1), "0.1");
        assert_eq!(shown(f64::NAN), "NaN");
        assert_eq!(shown(f64::INFINITY), "inf");
        assert_eq!(shown(f64::NEG_INFINITY), "-inf");
    }
}
