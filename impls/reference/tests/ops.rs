//! Float316 operations: hand-worked cases from the spec, agreement with an
//! f64 evaluation within stated bounds, and algebraic facts.

use common::{Op, OpValue, Outcome, F316};
use proptest::prelude::*;
use reference::{op, trace_op, Arith, Settings, Variant};

fn t(s: i16, e: i16, m: i16) -> F316 {
    F316::new(s, e, m)
}

fn f(x: f64) -> F316 {
    F316::from_f64_truncating(x).unwrap()
}

fn run(o: Op, args: &[F316]) -> Outcome<OpValue> {
    op(o, args, Arith::default()).unwrap()
}

fn num(o: Op, args: &[F316]) -> F316 {
    match run(o, args) {
        Outcome::Value(OpValue::Num(v)) => v,
        other => panic!("{o}{args:?} gave {other:?}"),
    }
}

fn gt(a: F316, b: F316) -> bool {
    match run(Op::Gt, &[a, b]) {
        Outcome::Value(OpValue::Bool(v)) => v,
        other => panic!("gt gave {other:?}"),
    }
}

const ZERO: F316 = F316::ZERO;
const NEG_ZERO: F316 = F316::NEG_ZERO;

#[test]
fn add_and_sub_by_hand() {
    assert_eq!(num(Op::Add, &[f(1.0), f(1.0)]), t(0, 128, 8192));
    assert_eq!(num(Op::Add, &[f(1.0), f(0.5)]), f(1.5));
    assert_eq!(num(Op::Add, &[f(124.0), f(-25.75)]), f(98.25));
    assert_eq!(num(Op::Add, &[f(1.0), f(-1.0)]), ZERO);
    assert_eq!(num(Op::Sub, &[f(-1.0), f(-1.0)]), ZERO);
    // Zero operands: `big` is returned unchanged, so signed zeros survive.
    assert_eq!(num(Op::Add, &[NEG_ZERO, ZERO]), NEG_ZERO);
    assert_eq!(num(Op::Add, &[ZERO, NEG_ZERO]), ZERO);
    assert_eq!(num(Op::Add, &[NEG_ZERO, f(2.0)]), f(2.0));
    // The smaller operand is truncated when aligned: 1 + 2^-14 is 1.
    assert_eq!(num(Op::Add, &[f(1.0), t(0, 113, 8192)]), f(1.0));
    // Cancellation renormalises: (1 + 2^-13) - 1 = 2^-13.
    assert_eq!(num(Op::Sub, &[t(0, 127, 8193), f(1.0)]), t(0, 114, 8192));
    // 2^-14 + 2^-14 + ... the counter of the image loop stays exact.
    let mut c = ZERO;
    for n in 1..=512 {
        c = num(Op::Add, &[c, f(1.0)]);
        assert_eq!(c, f(n as f64));
    }
}

#[test]
fn add_hangs_when_the_difference_is_zero() {
    // Non-canonical (0,62,0) minus (0,61,0): m reaches 0 in the loop.
    assert_eq!(run(Op::Sub, &[t(0, 62, 0), t(0, 61, 0)]), Outcome::Hang);
    // A non-normalised mantissa aligned onto an equal one.
    assert_eq!(
        run(Op::Add, &[t(0, 128, 8192), t(1, 127, 16384)]),
        Outcome::Hang
    );
}

#[test]
fn mul_by_hand() {
    assert_eq!(num(Op::Mul, &[f(1.5), f(2.0)]), f(3.0));
    assert_eq!(num(Op::Mul, &[f(-0.5), f(0.5)]), f(-0.25));
    assert_eq!(num(Op::Mul, &[NEG_ZERO, f(3.0)]), NEG_ZERO);
    assert_eq!(num(Op::Mul, &[f(-2.0), ZERO]), NEG_ZERO);
    assert_eq!(num(Op::Mul, &[f(-2.0), NEG_ZERO]), ZERO);
    // No special case for 1.0: the low*low product of 1.0001220703125 is lost.
    assert_eq!(num(Op::Mul, &[f(1.0), t(0, 127, 8193)]), f(1.0));
    let keep = Arith {
        mul_keeps_low_product: true,
        ..Arith::default()
    };
    // 0.01 * 0.01: the low product (117*117/128 = 106) does not carry.
    let plain = num(Op::Mul, &[f(0.01), f(0.01)]);
    let kept = op(Op::Mul, &[f(0.01), f(0.01)], keep).unwrap();
    assert_eq!(plain, t(0, 113, 13418));
    assert_eq!(kept, Outcome::Value(OpValue::Num(plain)));
    // (2 - 2^-13)^2: here it does.
    let a = t(0, 127, 16383);
    assert_eq!(num(Op::Mul, &[a, a]), t(0, 128, 16381));
    assert_eq!(
        op(Op::Mul, &[a, a], keep).unwrap(),
        Outcome::Value(OpValue::Num(t(0, 128, 16382)))
    );
}

#[test]
fn div_by_hand() {
    assert_eq!(num(Op::Div, &[f(1.0), f(2.0)]), f(0.5));
    assert_eq!(num(Op::Div, &[f(-3.0), f(1.5)]), f(-2.0));
    assert_eq!(num(Op::Div, &[f(1.0), f(3.0)]), t(0, 125, 10922));
    assert_eq!(num(Op::Div, &[NEG_ZERO, f(2.0)]), NEG_ZERO);
    assert_eq!(num(Op::Div, &[ZERO, f(-2.0)]), NEG_ZERO);
    assert_eq!(num(Op::Div, &[ZERO, ZERO]), ZERO);
    assert_eq!(run(Op::Div, &[f(1.0), ZERO]), Outcome::SysError(1));
    assert_eq!(run(Op::Div, &[f(1.0), NEG_ZERO]), Outcome::SysError(1));
    // A non-canonical dividend with m = 0: q stays 0, Jack loops forever.
    assert_eq!(run(Op::Div, &[t(0, 61, 0), f(1.0)]), Outcome::Hang);
}

#[test]
fn halve_double_quarter_touch_only_non_zero_exponents() {
    assert_eq!(num(Op::Halve, &[f(1.0)]), f(0.5));
    assert_eq!(num(Op::Double, &[f(-1.0)]), f(-2.0));
    assert_eq!(num(Op::Quarter, &[f(0.835)]), t(0, 124, 13680));
    for o in [Op::Halve, Op::Double, Op::Quarter] {
        assert_eq!(num(o, &[ZERO]), ZERO);
        assert_eq!(num(o, &[NEG_ZERO]), NEG_ZERO);
    }
    assert_eq!(num(Op::Quarter, &[t(0, 1, 8192)]), t(0, -1, 8192));
}

#[test]
fn gt_by_hand() {
    assert!(gt(ZERO, NEG_ZERO));
    assert!(!gt(NEG_ZERO, ZERO));
    assert!(!gt(ZERO, ZERO));
    assert!(gt(f(-1.0), f(-2.0)));
    assert!(gt(f(1.0001220703125), f(1.0)));
    assert!(gt(f(0.01), NEG_ZERO));
    assert!(!gt(f(-0.01), ZERO));
}

#[test]
fn floor_by_hand() {
    assert_eq!(num(Op::Floor, &[NEG_ZERO]), f(-1.0));
    assert_eq!(num(Op::Floor, &[ZERO]), ZERO);
    assert_eq!(num(Op::Floor, &[f(0.7)]), ZERO);
    assert_eq!(num(Op::Floor, &[f(-0.7)]), f(-1.0));
    assert_eq!(num(Op::Floor, &[f(2.5)]), f(2.0));
    assert_eq!(num(Op::Floor, &[f(-1.5)]), f(-2.0));
    assert_eq!(num(Op::Floor, &[f(-1.0)]), f(-1.0));
    assert_eq!(num(Op::Floor, &[f(-25.75)]), f(-26.0));
    assert_eq!(num(Op::Floor, &[f(16383.5)]), f(16383.0));
    assert_eq!(run(Op::Floor, &[f(16384.0)]), Outcome::OutOfDomain);
    assert_eq!(run(Op::Floor, &[f(-20000.0)]), Outcome::OutOfDomain);
}

#[test]
fn mod2_by_hand() {
    assert_eq!(num(Op::Mod2, &[f(-1.0)]), f(1.0));
    assert_eq!(num(Op::Mod2, &[f(-2.0)]), ZERO);
    assert_eq!(num(Op::Mod2, &[f(3.0)]), f(1.0));
    assert_eq!(num(Op::Mod2, &[ZERO]), ZERO);
    assert_eq!(num(Op::Mod2, &[t(0, 300, 0)]), ZERO);
    assert_eq!(run(Op::Mod2, &[f(0.5)]), Outcome::OutOfDomain);
    assert_eq!(run(Op::Mod2, &[f(16384.0)]), Outcome::OutOfDomain);
}

#[test]
fn sqrt_and_inv_sqrt_by_hand() {
    assert_eq!(num(Op::Sqrt, &[ZERO]), t(0, 61, 0));
    assert_eq!(run(Op::Sqrt, &[NEG_ZERO]), Outcome::SysError(2));
    assert_eq!(run(Op::Sqrt, &[f(-4.0)]), Outcome::SysError(2));
    assert_eq!(num(Op::Sqrt, &[f(4.0)]), f(2.0));
    assert_eq!(num(Op::Sqrt, &[f(1.0)]), f(1.0));
    assert_eq!(run(Op::InvSqrt, &[f(-4.0)]), Outcome::SysError(3));
    assert_eq!(run(Op::InvSqrt, &[NEG_ZERO]), Outcome::SysError(3));
    let r = num(Op::InvSqrt, &[f(4.0)]).to_f64();
    assert!((r - 0.5).abs() < 1e-3, "{r}");
}

/// The first div of sqrt shows the start value, whose exponent uses Jack's
/// truncating division: for e = -47, e/2 = -23 (a floor division gives -24).
#[test]
fn sqrt_start_value_truncates_toward_zero() {
    let x = t(0, -47, 8192);
    let trace = trace_op(Op::Sqrt, &[x], Arith::default()).unwrap();
    assert_eq!(trace.records[1].op, Op::Div);
    assert_eq!(trace.records[1].args, vec![x, t(0, 41, 8192)]);
    // e = 100: even, 100/2 + 63 = 113.
    let trace = trace_op(Op::Sqrt, &[t(0, 100, 9000)], Arith::default()).unwrap();
    assert_eq!(trace.records[1].args[1], t(0, 113, 9000));
}

#[test]
fn sqrt_fault_differs_exactly_for_odd_differences_below_127() {
    let fault = Variant::SqrtFloorDiv.apply(Settings::default()).arith;
    for e in 1..=300 {
        let x = t(0, e, 9000);
        let guess = |a| trace_op(Op::Sqrt, &[x], a).unwrap().records[1].args[1];
        let differs = e < 127 && (e - 127) % 2 != 0;
        assert_eq!(guess(fault) != guess(Arith::default()), differs, "e = {e}");
    }
}

#[test]
fn trace_nesting_follows_the_convention() {
    let ops = |o: Op, args: &[F316]| -> Vec<Op> {
        let tr = trace_op(o, args, Arith::default()).unwrap();
        assert_eq!(tr.outcome, run(o, args));
        tr.records.iter().map(|r| r.op).collect()
    };
    use Op::*;
    assert_eq!(ops(Sub, &[f(1.0), f(0.5)]), [Sub, Add]);
    assert_eq!(
        ops(Sqrt, &[f(2.0)]),
        [Sqrt, Div, Add, Halve, Div, Add, Halve]
    );
    assert_eq!(
        ops(InvSqrt, &[f(2.0)]),
        [InvSqrt, Mul, Mul, Sub, Add, Mul, Mul, Mul, Sub, Add, Mul]
    );
    assert_eq!(ops(Floor, &[f(-1.5)]), [Floor, Add]);
    assert_eq!(ops(Floor, &[f(1.5)]), [Floor]);
    let tr = trace_op(Sqrt, &[f(2.0)], Arith::default()).unwrap();
    assert_eq!(tr.records[0].path, Vec::<String>::new());
    assert_eq!(tr.records[1].path, ["sqrt"]);
}

/// sqrt and invSqrt depend on the exponent only through its parity and a
/// scale, so every mantissa at one odd and one even exponent covers them.
#[test]
fn sqrt_and_inv_sqrt_error_bounds_hold_for_every_mantissa() {
    for e in [126, 127] {
        for m in 8192..=16383 {
            let x = t(0, e, m);
            let exact = x.to_f64().sqrt();
            assert!(rel(num(Op::Sqrt, &[x]), exact) < 2f64.powi(-8), "sqrt{x:?}");
            assert!(
                rel(num(Op::InvSqrt, &[x]), 1.0 / exact) < 0.125,
                "invSqrt{x:?}"
            );
        }
    }
}

#[test]
fn wrong_arity_is_an_error() {
    assert!(op(Op::Add, &[f(1.0)], Arith::default()).is_err());
    assert!(op(Op::Sqrt, &[f(1.0), f(2.0)], Arith::default()).is_err());
}

/// A normalised triple with an exponent well inside the safe range.
fn normalised() -> impl Strategy<Value = F316> {
    (0i16..=1, 100i16..=154, 8192i16..=16383).prop_map(|(s, e, m)| t(s, e, m))
}

fn positive() -> impl Strategy<Value = F316> {
    (100i16..=154, 8192i16..=16383).prop_map(|(e, m)| t(0, e, m))
}

fn ulp(e: i16) -> f64 {
    2f64.powi(e as i32 - 140)
}

fn rel(got: F316, want: f64) -> f64 {
    ((got.to_f64() - want) / want).abs()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    /// Alignment truncates the smaller operand (less than one unit of the
    /// larger's last place) and a carry may drop one more unit.
    #[test]
    fn add_is_within_two_units_of_the_larger_operand(a in normalised(), b in normalised()) {
        let got = num(Op::Add, &[a, b]).to_f64();
        let exact = a.to_f64() + b.to_f64();
        prop_assert!((got - exact).abs() < 2.0 * ulp(a.e.max(b.e)), "{a:?} + {b:?} = {got}, exact {exact}");
    }

    /// The partial products drop less than two units of a mantissa of at
    /// least 4096 before normalisation.
    #[test]
    fn mul_relative_error_below_2_pow_minus_11(a in normalised(), b in normalised()) {
        let got = num(Op::Mul, &[a, b]);
        prop_assert!(rel(got, a.to_f64() * b.to_f64()) < 2f64.powi(-11), "{a:?} * {b:?} = {got:?}");
        prop_assert!(got.is_normalised());
    }

    /// Long division with a truncated, shrinking divisor: the halved
    /// divisor loses its low bits, so the quotient keeps only about 10 bits
    /// (measured worst case about 2^-9.9).
    #[test]
    fn div_relative_error_below_2_pow_minus_9(a in normalised(), b in normalised()) {
        let got = num(Op::Div, &[a, b]);
        prop_assert!(rel(got, a.to_f64() / b.to_f64()) < 2f64.powi(-9), "{a:?} / {b:?} = {got:?}");
    }

    /// Two Newton steps from the exponent-halving start value (the bound is
    /// also checked exhaustively below).
    #[test]
    fn sqrt_relative_error_below_2_pow_minus_8(x in positive()) {
        let got = num(Op::Sqrt, &[x]);
        prop_assert!(rel(got, x.to_f64().sqrt()) < 2f64.powi(-8), "sqrt{x:?} = {got:?}");
    }

    /// Two Newton steps from a start value that ignores the mantissa: the
    /// error stays large (measured worst case about 0.116).
    #[test]
    fn inv_sqrt_relative_error_below_one_eighth(x in positive()) {
        let got = num(Op::InvSqrt, &[x]);
        prop_assert!(rel(got, 1.0 / x.to_f64().sqrt()) < 0.125, "invSqrt{x:?} = {got:?}");
    }

    #[test]
    fn add_and_mul_commute(a in normalised(), b in normalised()) {
        prop_assert_eq!(run(Op::Add, &[a, b]), run(Op::Add, &[b, a]));
        prop_assert_eq!(run(Op::Mul, &[a, b]), run(Op::Mul, &[b, a]));
    }

    #[test]
    fn sub_is_add_of_the_negation(a in normalised(), b in normalised()) {
        prop_assert_eq!(run(Op::Sub, &[a, b]), run(Op::Add, &[a, b.negated()]));
    }

    /// gt is a strict total order on normalised triples that agrees with
    /// the values.
    #[test]
    fn gt_is_antisymmetric_and_agrees_with_f64(a in normalised(), b in normalised()) {
        let (ab, ba) = (gt(a, b), gt(b, a));
        prop_assert!(!(ab && ba));
        prop_assert_eq!(ab || ba, a != b);
        prop_assert_eq!(ab, a.to_f64() > b.to_f64());
    }

    #[test]
    fn floor_and_mod2_on_integers(n in -16383i32..=16383) {
        let x = f(n as f64);
        prop_assert_eq!(num(Op::Floor, &[x]), x);
        prop_assert_eq!(num(Op::Mod2, &[x]), f(n.rem_euclid(2) as f64));
    }

    #[test]
    fn floor_agrees_with_f64(x in normalised().prop_filter("|x| < 2^13", |x| x.e < 140)) {
        prop_assert_eq!(num(Op::Floor, &[x]), f(x.to_f64().floor()));
    }

    /// Any triple at all: every operation ends (a value or a trap) and the
    /// traced run agrees with the untraced one.
    #[test]
    fn every_triple_gives_an_outcome(a in any::<[i16; 3]>(), b in any::<[i16; 3]>(), i in 0usize..12) {
        let o = Op::ALL[i];
        let args = &[F316::from(a), F316::from(b)][..o.arity()];
        let traced = trace_op(o, args, Arith::default()).unwrap();
        prop_assert_eq!(traced.outcome, run(o, args));
        prop_assert_eq!(traced.records[0].result, traced.outcome);
    }
}
