//! `Math` (spec section 3.1) as plain functions, so the VM can call the hot
//! ones directly without going through [`crate::Os::call`].

use crate::Profile;
use common::jack_int;

/// `Math.multiply`: the low 16 bits of the exact product (300*300 = 24464).
#[inline]
pub fn multiply(a: i16, b: i16) -> i16 {
    jack_int::mul(a, b)
}

/// How `Math.divide` rounds: toward zero (the desktop tools, -7/2 = -3) or
/// toward minus infinity (the web IDE, -7/2 = -4). Each profile has its
/// own ([`DivideRule::of`]); a machine may take the other one and keep
/// every other rule of its profile (the fault `web-divide`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DivideRule {
    /// Truncating toward zero.
    Truncate,
    /// Rounding toward minus infinity.
    Floor,
}

impl DivideRule {
    /// The rule of `profile`'s OS.
    pub const fn of(profile: Profile) -> DivideRule {
        match profile {
            Profile::Desktop => DivideRule::Truncate,
            Profile::Web => DivideRule::Floor,
        }
    }
}

impl From<Profile> for DivideRule {
    fn from(profile: Profile) -> DivideRule {
        DivideRule::of(profile)
    }
}

/// `Math.divide` under `rule` (a [`Profile`] stands for its own rule):
/// truncating toward zero on the desktop (-7/2 = -3), rounding toward
/// minus infinity on the web (-7/2 = -4). `None` for a zero divisor (ERR3,
/// result 0). -32768/-1 = -32768.
#[inline]
pub fn divide(rule: impl Into<DivideRule>, a: i16, b: i16) -> Option<i16> {
    match rule.into() {
        DivideRule::Truncate => jack_int::div(a, b),
        DivideRule::Floor => jack_int::div_floor(a, b),
    }
}

/// `Math.min` (signed).
#[inline]
pub fn min(a: i16, b: i16) -> i16 {
    a.min(b)
}

/// `Math.max` (signed).
#[inline]
pub fn max(a: i16, b: i16) -> i16 {
    a.max(b)
}

/// `Math.abs`, wrapping: abs(-32768) = -32768.
#[inline]
pub fn abs(x: i16) -> i16 {
    x.wrapping_abs()
}

/// `Math.sqrt`: floor(sqrt(x)); `None` for a negative x (ERR4, result 0).
#[inline]
pub fn sqrt(x: i16) -> Option<i16> {
    u16::try_from(x).ok().map(|x| isqrt(i32::from(x)) as i16)
}

/// floor(sqrt(n)) for 0 <= n < 2^31, exact.
pub(crate) fn isqrt(n: i32) -> i32 {
    let mut r = f64::from(n).sqrt() as i32;
    while r * r > n {
        r -= 1;
    }
    while (r + 1) * (r + 1) <= n {
        r += 1;
    }
    r
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn documented_values() {
        assert_eq!(multiply(300, 300), 24464);
        assert_eq!(divide(Profile::Desktop, -7, 2), Some(-3));
        assert_eq!(divide(Profile::Web, -7, 2), Some(-4));
        assert_eq!(divide(Profile::Web, 7, -2), Some(-4));
        assert_eq!(divide(Profile::Desktop, -47, 2), Some(-23));
        assert_eq!(divide(Profile::Web, -32768, -1), Some(-32768));
        assert_eq!(divide(Profile::Desktop, -32768, -1), Some(-32768));
        assert_eq!(divide(Profile::Desktop, 5, 0), None);
        assert_eq!(divide(Profile::Web, 5, 0), None);
        assert_eq!(divide(DivideRule::Floor, -7, 2), Some(-4));
        assert_eq!(divide(DivideRule::Truncate, -7, 2), Some(-3));
        assert_eq!(abs(-32768), -32768);
        assert_eq!(abs(-5), 5);
        assert_eq!(min(-1, 32767), -1);
        assert_eq!(max(-1, 32767), 32767);
        assert_eq!(sqrt(-1), None);
        assert_eq!(sqrt(32767), Some(181));
        assert_eq!(sqrt(0), Some(0));
        assert_eq!(sqrt(15), Some(3));
        assert_eq!(sqrt(16), Some(4));
    }

    proptest! {
        #[test]
        fn multiply_is_the_wrapped_product(a in any::<i16>(), b in any::<i16>()) {
            prop_assert_eq!(multiply(a, b), (i32::from(a) * i32::from(b)) as i16);
        }

        #[test]
        fn divide_matches_i32_arithmetic(a in any::<i16>(), b in any::<i16>()) {
            let (x, y) = (i32::from(a), i32::from(b));
            let trunc = (y != 0).then(|| (x / y) as i16);
            let floor = (y != 0).then(|| ((x as f64 / y as f64).floor() as i32) as i16);
            prop_assert_eq!(divide(Profile::Desktop, a, b), trunc);
            prop_assert_eq!(divide(Profile::Web, a, b), floor);
        }

        #[test]
        fn sqrt_is_the_integer_square_root(x in 0i16..) {
            let r = i32::from(sqrt(x).unwrap());
            prop_assert!(r * r <= i32::from(x) && (r + 1) * (r + 1) > i32::from(x));
        }
    }
}
