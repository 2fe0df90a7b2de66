//! Jack integer semantics: 16-bit two's complement that wraps, and integer
//! division that truncates toward zero (the desktop VM emulator's
//! `Math.divide`, used by the seed program). Every implementation of
//! Float316 integer arithmetic goes through these helpers so that wrap-around
//! and rounding are decided in exactly one place.
//!
//! `div_floor` exists only to model the other behaviour (the web IDE's
//! `Math.divide`, Python's `//`), for profiles and fault injection.

/// Reduce an integer to a Jack word (mod 2^16, signed).
#[inline]
pub const fn wrap(x: i32) -> i16 {
    x as i16
}

/// `a + b` wrapping at 16 bits.
#[inline]
pub const fn add(a: i16, b: i16) -> i16 {
    a.wrapping_add(b)
}

/// `a - b` wrapping at 16 bits.
#[inline]
pub const fn sub(a: i16, b: i16) -> i16 {
    a.wrapping_sub(b)
}

/// Unary minus wrapping at 16 bits (`neg(-32768) = -32768`).
#[inline]
pub const fn neg(a: i16) -> i16 {
    a.wrapping_neg()
}

/// `Math.multiply`: the low 16 bits of the exact product.
#[inline]
pub const fn mul(a: i16, b: i16) -> i16 {
    a.wrapping_mul(b)
}

/// Division truncating toward zero, as the desktop emulator's
/// `Math.divide` (and Rust's `/`) does: `-47 / 2 = -23`.
/// `None` for a zero divisor (Jack: `Sys.error(3)`).
/// `-32768 / -1` wraps to `-32768`.
#[inline]
pub const fn div(a: i16, b: i16) -> Option<i16> {
    if b == 0 {
        None
    } else {
        Some(a.wrapping_div(b))
    }
}

/// Division rounding toward minus infinity, as the web IDE's `Math.divide`
/// and Python's `//` do: `-47 // 2 = -24`. `None` for a zero divisor.
#[inline]
pub const fn div_floor(a: i16, b: i16) -> Option<i16> {
    if b == 0 {
        return None;
    }
    let q = a.wrapping_div(b);
    if (a.wrapping_rem(b) != 0) && ((a < 0) != (b < 0)) {
        Some(q.wrapping_sub(1))
    } else {
        Some(q)
    }
}

/// "Halve" in the spec: integer division by 2, truncating toward zero.
#[inline]
pub const fn halve(a: i16) -> i16 {
    a / 2
}

/// Bitwise and, as Jack's `&`.
#[inline]
pub const fn and(a: i16, b: i16) -> i16 {
    a & b
}

/// Jack's `true` is -1 and `false` is 0.
#[inline]
pub const fn from_bool(b: bool) -> i16 {
    if b {
        -1
    } else {
        0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn truncating_division_of_negative_numbers() {
        assert_eq!(div(-47, 2), Some(-23));
        assert_eq!(div(-7, 2), Some(-3));
        assert_eq!(div(7, -2), Some(-3));
        assert_eq!(div(-32768, -1), Some(-32768));
        assert_eq!(div(5, 0), None);
    }

    #[test]
    fn floor_division_of_negative_numbers() {
        assert_eq!(div_floor(-47, 2), Some(-24));
        assert_eq!(div_floor(-7, 2), Some(-4));
        assert_eq!(div_floor(7, -2), Some(-4));
        assert_eq!(div_floor(-8, 2), Some(-4));
        assert_eq!(div_floor(-32768, -1), Some(-32768));
        assert_eq!(div_floor(1, 0), None);
    }

    #[test]
    fn wrap_around() {
        assert_eq!(add(32767, 1), -32768);
        assert_eq!(sub(-32768, 1), 32767);
        assert_eq!(neg(-32768), -32768);
        assert_eq!(mul(300, 300), 24464);
        assert_eq!(wrap(65535), -1);
        assert_eq!(wrap(40000), -25536);
        assert_eq!(halve(-1), 0);
        assert_eq!(halve(-3), -1);
        assert_eq!(from_bool(true), -1);
        assert_eq!(and(-1, 127), 127);
    }

    proptest! {
        #[test]
        fn division_agrees_with_i32_arithmetic(a in any::<i16>(), b in any::<i16>()) {
            prop_assume!(b != 0);
            let (a32, b32) = (a as i32, b as i32);
            prop_assert_eq!(div(a, b), Some(wrap(a32 / b32)));
            prop_assert_eq!(div_floor(a, b), Some(wrap(a32.div_euclid(b32) - if b32 < 0 && a32.rem_euclid(b32) != 0 { 1 } else { 0 })));
        }

        #[test]
        fn truncation_and_floor_differ_only_on_inexact_negative_quotients(a in any::<i16>(), b in any::<i16>()) {
            prop_assume!(b != 0);
            let inexact_negative = (a as i32) % (b as i32) != 0 && ((a < 0) != (b < 0));
            prop_assert_eq!(div(a, b) != div_floor(a, b), inexact_negative);
        }

        #[test]
        fn ring_operations_wrap(a in any::<i16>(), b in any::<i16>()) {
            prop_assert_eq!(add(a, b), wrap(a as i32 + b as i32));
            prop_assert_eq!(sub(a, b), wrap(a as i32 - b as i32));
            prop_assert_eq!(mul(a, b), wrap(a as i32 * b as i32));
        }
    }
}
