//! Float316 operations on the GPU against values worked by hand from the
//! spec (sections 1-2).

use crate::support::gpu;
use common::{Op, OpValue, Outcome, F316};

const fn f(s: i16, e: i16, m: i16) -> F316 {
    F316::new(s, e, m)
}

const ONE: F316 = f(0, 127, 8192);
const NEG_ONE: F316 = f(1, 127, 8192);
const Z: F316 = F316::ZERO;

fn num(v: F316) -> Outcome<OpValue> {
    Outcome::Value(OpValue::Num(v))
}

#[test]
fn hand_worked_operations() {
    let Some(gpu) = gpu() else { return };
    let cases: Vec<((Op, F316, F316), Outcome<OpValue>)> = vec![
        ((Op::Add, ONE, ONE), num(f(0, 128, 8192))),
        ((Op::Sub, ONE, ONE), num(Z)),
        ((Op::Add, ONE, Z), num(ONE)),
        // 1 + (-0.5): the difference is renormalised.
        ((Op::Add, ONE, f(1, 126, 8192)), num(f(0, 126, 8192))),
        (
            (Op::Mul, f(0, 127, 12288), f(0, 128, 8192)),
            num(f(0, 128, 12288)),
        ),
        ((Op::Mul, NEG_ONE, Z), num(F316::NEG_ZERO)),
        ((Op::Div, ONE, f(0, 128, 8192)), num(f(0, 126, 8192))),
        ((Op::Div, Z, NEG_ONE), num(F316::NEG_ZERO)),
        ((Op::Div, ONE, Z), Outcome::SysError(1)),
        ((Op::Sqrt, NEG_ONE, Z), Outcome::SysError(2)),
        ((Op::Sqrt, F316::NEG_ZERO, Z), Outcome::SysError(2)),
        ((Op::InvSqrt, NEG_ONE, Z), Outcome::SysError(3)),
        ((Op::Sqrt, Z, Z), num(f(0, 61, 0))),
        ((Op::Floor, F316::NEG_ZERO, Z), num(NEG_ONE)),
        ((Op::Floor, f(1, 131, 13184), Z), num(f(1, 131, 13312))),
        ((Op::Floor, f(0, 131, 13184), Z), num(f(0, 131, 12800))),
        ((Op::Floor, f(0, 141, 8192), Z), Outcome::OutOfDomain),
        ((Op::Mod2, f(0, 128, 12288), Z), num(ONE)),
        ((Op::Mod2, f(0, 128, 8192), Z), num(Z)),
        ((Op::Mod2, NEG_ONE, Z), num(ONE)),
        ((Op::Mod2, f(0, 200, 0), Z), num(Z)),
        ((Op::Mod2, f(0, 126, 8192), Z), Outcome::OutOfDomain),
        (
            (Op::Gt, Z, F316::NEG_ZERO),
            Outcome::Value(OpValue::Bool(true)),
        ),
        (
            (Op::Gt, NEG_ONE, f(1, 126, 8192)),
            Outcome::Value(OpValue::Bool(false)),
        ),
        (
            (Op::Gt, f(0, 127, 8193), ONE),
            Outcome::Value(OpValue::Bool(true)),
        ),
        ((Op::Halve, ONE, Z), num(f(0, 126, 8192))),
        ((Op::Double, Z, Z), num(Z)),
        ((Op::Quarter, f(0, 129, 8192), Z), num(ONE)),
        // Non-canonical zeros: the normalisation loops of add and div never
        // end in Jack.
        ((Op::Add, f(0, 10, 0), f(1, 5, 0)), Outcome::Hang),
        ((Op::Add, f(0, 128, 8192), f(1, 127, 16384)), Outcome::Hang),
        ((Op::Div, f(0, 61, 0), ONE), Outcome::Hang),
    ];
    let inputs: Vec<_> = cases.iter().map(|c| c.0).collect();
    let got = gpu.f316_ops(&inputs).expect("ops kernel runs");
    for ((input, want), got) in cases.iter().zip(got) {
        assert_eq!(&got, want, "{input:?}");
    }
}

#[test]
fn sqrt_and_inv_sqrt_of_four() {
    let Some(gpu) = gpu() else { return };
    let four = f(0, 129, 8192);
    let got = gpu
        .f316_ops(&[(Op::Sqrt, four, Z), (Op::InvSqrt, four, Z)])
        .expect("ops kernel runs");
    // Exactly 2 and 0.5 (ref-f316 gives the same triples).
    assert_eq!(got[0], Outcome::Value(OpValue::Num(f(0, 128, 8192))));
    assert_eq!(got[1], Outcome::Value(OpValue::Num(f(0, 126, 8192))));
}
