//! Run-time variants of the reference: precision variants (used by the
//! speed-against-error report) and injected faults (used by the harness's
//! self-test to prove it detects and localizes them). The default settings
//! are the spec, and cost nothing: a variant is a field test at the point
//! where it changes the algorithm.

use crate::api::RefImpl;
use std::fmt;
use std::str::FromStr;

/// How the Float316 operations compute. `Arith::default()` is the spec.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Arith {
    /// Newton steps in `sqrt` and `invSqrt` (spec: 2).
    pub newton_steps: u8,
    /// `mul` keeps the low*low partial product instead of dropping it.
    pub mul_keeps_low_product: bool,
    /// `sqrt`'s start exponent computed as `(e - 127)/2 + 127` (the
    /// original Python port's formula) in Jack's truncating division. It
    /// differs from the spec exactly when `e < 127` and `e - 127` is odd.
    /// (With a floor division that formula equals the spec's for every
    /// `e >= -1`, so the fault that shows is the truncating one.)
    pub sqrt_guess_from_biased_difference: bool,
    /// `add` halves the smaller mantissa once more than the exponent
    /// difference (when the exponents differ).
    pub add_alignment_off_by_one: bool,
    /// `add` tests its carry by the sum's bit 14 instead of `m > 16383`:
    /// the same for normalised operands, not when an operand's carry or
    /// overflow-detector bits are set and the sum wraps.
    pub add_carry_by_bit_test: bool,
    /// `add` returns the larger operand alone when the exponents are 14 or
    /// more apart, as if the smaller were always shifted out: true only
    /// for mantissas below 16384.
    pub add_drops_operand_at_gap_14: bool,
    /// `div` normalises its quotient with one doubling instead of a loop:
    /// enough when both mantissas are normalised, not when the divisor has
    /// its carry or overflow-detector bits set.
    pub div_normalises_once: bool,
}

impl Arith {
    /// The spec's arithmetic (also `Arith::default()`).
    pub const SPEC: Arith = Arith {
        newton_steps: 2,
        mul_keeps_low_product: false,
        sqrt_guess_from_biased_difference: false,
        add_alignment_off_by_one: false,
        add_carry_by_bit_test: false,
        add_drops_operand_at_gap_14: false,
        div_normalises_once: false,
    };
}

impl Default for Arith {
    fn default() -> Self {
        Arith::SPEC
    }
}

/// Where a Float316 engine gets its [`Arith`]: a run-time value, or
/// [`SpecArith`], the spec's arithmetic as a compile-time constant that the
/// compiler folds into the operations (no variant tests in the hot path).
pub trait ArithSource: Copy {
    /// The arithmetic.
    fn arith(&self) -> Arith;
}

impl ArithSource for Arith {
    #[inline(always)]
    fn arith(&self) -> Arith {
        *self
    }
}

/// [`Arith::SPEC`], known at compile time.
#[derive(Clone, Copy, Debug, Default)]
pub struct SpecArith;

impl ArithSource for SpecArith {
    #[inline(always)]
    fn arith(&self) -> Arith {
        Arith::SPEC
    }
}

/// The arithmetic plus scene-level faults.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Settings {
    pub arith: Arith,
    /// A pixel is white when its dithered value is not below 0.5 (spec:
    /// strictly above 0.5).
    pub dither_threshold: bool,
    /// The float formulation computes each multiply-add of the scene as
    /// one fused operation, rounded once (`mul_add`), as a GPU driver may
    /// contract `a * b + c` (see [`crate::Engine::contracts`]). The spec
    /// rounds the product and the sum apart.
    pub contract_multiply_add: bool,
}

/// Whether a variant is a precision trade-off or a deliberate fault.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VariantKind {
    Precision,
    Fault,
}

/// A named variant, as given to `--variant NAME`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Variant {
    /// `mul-low-product`: mul keeps the low*low product (more precise).
    MulLowProduct,
    /// `newton-1`: one Newton step in sqrt and invSqrt.
    Newton1,
    /// `newton-3`: three Newton steps.
    Newton3,
    /// `sqrt-floor-div` (fault): sqrt's start exponent by the Python
    /// port's `(e - 127)/2 + 127` (see [`Arith`]).
    SqrtFloorDiv,
    /// `add-align-off-by-one` (fault): add over-shifts the smaller operand.
    AddAlignOffByOne,
    /// `add-carry-bit` (fault): add's carry tested by bit 14.
    AddCarryBit,
    /// `add-drop-far` (fault): add drops an operand 14 exponents below.
    AddDropFar,
    /// `div-normalise-once` (fault): div's quotient normalised by one step.
    DivNormaliseOnce,
    /// `mul-keep-low` (fault): the arithmetic of `mul-low-product`, used as
    /// an injected fault against the spec.
    MulKeepLow,
    /// `dither-threshold` (fault): `>=` instead of `>` against 0.5.
    DitherThreshold,
    /// `fma` (float formulations only): multiply-adds contracted into
    /// fused operations, as a GPU driver may compile them.
    Fma,
}

impl Variant {
    /// Every variant.
    pub const ALL: [Variant; 11] = [
        Variant::MulLowProduct,
        Variant::Newton1,
        Variant::Newton3,
        Variant::SqrtFloorDiv,
        Variant::AddAlignOffByOne,
        Variant::AddCarryBit,
        Variant::AddDropFar,
        Variant::DivNormaliseOnce,
        Variant::MulKeepLow,
        Variant::DitherThreshold,
        Variant::Fma,
    ];

    /// The command-line name.
    pub const fn name(self) -> &'static str {
        match self {
            Variant::MulLowProduct => "mul-low-product",
            Variant::Newton1 => "newton-1",
            Variant::Newton3 => "newton-3",
            Variant::SqrtFloorDiv => "sqrt-floor-div",
            Variant::AddAlignOffByOne => "add-align-off-by-one",
            Variant::AddCarryBit => "add-carry-bit",
            Variant::AddDropFar => "add-drop-far",
            Variant::DivNormaliseOnce => "div-normalise-once",
            Variant::MulKeepLow => "mul-keep-low",
            Variant::DitherThreshold => "dither-threshold",
            Variant::Fma => "fma",
        }
    }

    /// Whether it changes `implementation`'s answers: the Float316
    /// arithmetic's variants apply to `ref-f316` only, `fma` to the float
    /// formulations only, the dithering fault to all three.
    pub fn applies_to(self, implementation: RefImpl) -> bool {
        match self {
            Variant::DitherThreshold => true,
            Variant::Fma => implementation != RefImpl::F316,
            _ => implementation == RefImpl::F316,
        }
    }

    /// Precision variant or fault.
    pub const fn kind(self) -> VariantKind {
        match self {
            Variant::MulLowProduct | Variant::Newton1 | Variant::Newton3 | Variant::Fma => {
                VariantKind::Precision
            }
            _ => VariantKind::Fault,
        }
    }

    /// The settings with this variant applied on top of `base`.
    pub fn apply(self, base: Settings) -> Settings {
        let mut s = base;
        match self {
            Variant::MulLowProduct | Variant::MulKeepLow => s.arith.mul_keeps_low_product = true,
            Variant::Newton1 => s.arith.newton_steps = 1,
            Variant::Newton3 => s.arith.newton_steps = 3,
            Variant::SqrtFloorDiv => s.arith.sqrt_guess_from_biased_difference = true,
            Variant::AddAlignOffByOne => s.arith.add_alignment_off_by_one = true,
            Variant::AddCarryBit => s.arith.add_carry_by_bit_test = true,
            Variant::AddDropFar => s.arith.add_drops_operand_at_gap_14 = true,
            Variant::DivNormaliseOnce => s.arith.div_normalises_once = true,
            Variant::DitherThreshold => s.dither_threshold = true,
            Variant::Fma => s.contract_multiply_add = true,
        }
        s
    }
}

impl fmt::Display for Variant {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// An unknown variant name.
#[derive(Debug, thiserror::Error)]
#[error("unknown variant `{0}` (expected one of mul-low-product, newton-1, newton-3, sqrt-floor-div, add-align-off-by-one, add-carry-bit, add-drop-far, div-normalise-once, mul-keep-low, dither-threshold, fma)")]
pub struct UnknownVariant(pub String);

impl FromStr for Variant {
    type Err = UnknownVariant;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Variant::ALL
            .into_iter()
            .find(|v| v.name() == s)
            .ok_or_else(|| UnknownVariant(s.to_string()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_each_changes_the_settings() {
        for v in Variant::ALL {
            assert_eq!(v.name().parse::<Variant>().unwrap(), v);
            assert_ne!(v.apply(Settings::default()), Settings::default(), "{v}");
        }
        assert!("newton-7".parse::<Variant>().is_err());
    }
}
