//! Inputs found by hostile runs (issue 20) that once panicked.

use common::{Outcome, F316};
use reference::{RefImpl, Reference};

/// A legal SDF point whose x (exponent 255) exceeds f32's range: the float
/// implementations answer out of domain (as ref-f316 does: its squares
/// leave Float316's range), where they panicked.
#[test]
fn an_sdf_point_beyond_the_float_range_is_out_of_domain() {
    let p = [F316::new(0, 255, 8192), F316::ZERO, F316::ZERO];
    assert_eq!(Reference::seed(RefImpl::F32).sdf(p), Outcome::OutOfDomain);
    assert_eq!(Reference::seed(RefImpl::F316).sdf(p), Outcome::OutOfDomain);
    // f64 holds 2^(255-140) but not 2^(1151-140+13).
    assert!(matches!(
        Reference::seed(RefImpl::F64).sdf(p),
        Outcome::Value(_)
    ));
    let huge = [F316::new(1, 1151, 16383), F316::ZERO, F316::ZERO];
    assert_eq!(
        Reference::seed(RefImpl::F64).sdf(huge),
        Outcome::OutOfDomain
    );
    assert_eq!(
        Reference::seed(RefImpl::F32).sdf(huge),
        Outcome::OutOfDomain
    );
}

/// The value reported beside a Float316 answer (what the error figures
/// against ref-f64 use) is its triple's value, for distances and shades
/// alike (mutation testing found `to_f64 -> 1.0` uncaught).
#[test]
fn a_float316_answer_reports_its_own_value() {
    let r = Reference::seed(RefImpl::F316);
    let p = [
        F316::new(0, 128, 8192),
        F316::new(1, 126, 12000),
        F316::ZERO,
    ];
    let Outcome::Value(s) = r.sdf(p) else {
        panic!("the seed scene answers at {p:?}");
    };
    for scalar in [s.sd, s.col] {
        let t = scalar.triple.expect("ref-f316 gives triples");
        assert_eq!(scalar.value, t.to_f64(), "{t:?}");
    }
    assert_ne!(s.sd.value, s.col.value);
    let Outcome::Value(px) = r.pixel(312, 87) else {
        panic!("pixel (312,87) has a shade");
    };
    assert_eq!(px.value.value, px.value.triple.unwrap().to_f64());
}

/// `gt` of operands with different signs, one of them not 0 or 1, is
/// Jack's `(s = 0) & (bs = 1)`: false unless exactly 0 against 1
/// (mutation testing found `&&` -> `||` uncaught).
#[test]
fn gt_with_a_non_canonical_sign_follows_jack() {
    let gt = |a: F316, b: F316| reference::op(common::Op::Gt, &[a, b], Default::default()).unwrap();
    let yes = Outcome::Value(common::OpValue::Bool(true));
    let no = Outcome::Value(common::OpValue::Bool(false));
    let one = |s| F316::new(s, 128, 8192);
    assert_eq!(gt(one(0), one(1)), yes);
    assert_eq!(gt(one(1), one(0)), no);
    assert_eq!(gt(one(0), one(2)), no);
    assert_eq!(gt(one(2), one(1)), no);
    assert_eq!(gt(one(-1), one(1)), no);
}
