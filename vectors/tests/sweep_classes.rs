//! The equivalence-class argument of `gen::classes`, tested on random full
//! inputs against ref-f316: every pair of normalised operands gives the
//! result of its class's representative, with the exponent shifted by the
//! amount the argument says (and the same outcome kind).

use common::{Op, OpValue, Outcome, F316};
use proptest::prelude::*;
use reference::Arith;
use vectors::gen::classes::{class_of, representative, SWEPT};

fn eval(op: Op, a: F316, b: F316) -> Outcome<OpValue> {
    reference::op(op, &[a, b], Arith::SPEC).expect("a binary op with two operands")
}

/// How far the result's exponent moves between the representative and the
/// pair, by the argument of `gen::classes`.
fn exponent_shift(op: Op, a: F316, b: F316, ra: F316, rb: F316) -> i16 {
    match op {
        Op::Add | Op::Sub => a.e.max(b.e) - ra.e.max(rb.e),
        Op::Mul => (a.e + b.e) - (ra.e + rb.e),
        Op::Div => (a.e - b.e) - (ra.e - rb.e),
        _ => 0,
    }
}

fn normalised(e: std::ops::RangeInclusive<i16>) -> impl Strategy<Value = F316> {
    (0..=1i16, e, 8192..=16383i16).prop_map(|(s, e, m)| F316::new(s, e, m))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(20_000))]

    #[test]
    fn a_pair_answers_as_its_class(op in proptest::sample::select(SWEPT.to_vec()),
                                   a in normalised(-200..=400), b in normalised(-200..=400)) {
        let rep = representative(op, class_of(op, a, b));
        let (ra, rb) = (rep.a, rep.b.unwrap());
        let shift = exponent_shift(op, a, b, ra, rb);
        let want = match eval(op, ra, rb) {
            Outcome::Value(OpValue::Num(r)) => Outcome::Value(OpValue::Num(F316::new(r.s, r.e + shift, r.m))),
            other => other,
        };
        prop_assert_eq!(eval(op, a, b), want, "{} {:?} {:?} (class rep {:?} {:?})", op, a, b, ra, rb);
    }
}
