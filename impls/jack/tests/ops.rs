//! Float316 operations of the Jack program on hand-checked hard cases
//! (spec section 2): signed zeros, cancellation, traps, hangs, domains.

use common::{Op, OpValue, Outcome, F316};
use jack::{Budgets, Profile, Raymarcher};
use std::sync::OnceLock;

fn jack() -> &'static Raymarcher {
    static R: OnceLock<Raymarcher> = OnceLock::new();
    R.get_or_init(|| {
        Raymarcher::new(Profile::Desktop, Budgets::default()).expect("the raymarcher builds")
    })
}

const fn f(s: i16, e: i16, m: i16) -> F316 {
    F316::new(s, e, m)
}

const ZERO: F316 = f(0, 0, 0);
const NEG_ZERO: F316 = f(1, 0, 0);
const ONE: F316 = f(0, 127, 8192);
const MINUS_ONE: F316 = f(1, 127, 8192);
const TWO: F316 = f(0, 128, 8192);
const HALF: F316 = f(0, 126, 8192);

fn num(v: F316) -> Outcome<OpValue> {
    Outcome::Value(OpValue::Num(v))
}

fn yes(b: bool) -> Outcome<OpValue> {
    Outcome::Value(OpValue::Bool(b))
}

#[test]
fn hard_cases_agree_with_the_spec() {
    let table: Vec<(Op, Vec<F316>, Outcome<OpValue>)> = vec![
        // gt: signs first, +0 > -0.
        (Op::Gt, vec![ZERO, NEG_ZERO], yes(true)),
        (Op::Gt, vec![NEG_ZERO, ZERO], yes(false)),
        (Op::Gt, vec![ONE, ONE], yes(false)),
        (Op::Gt, vec![MINUS_ONE, f(1, 127, 8193)], yes(true)),
        (Op::Gt, vec![TWO, ONE], yes(true)),
        // add: signed zeros are kept, exact cancellation gives +0.
        (Op::Add, vec![ONE, ONE], num(TWO)),
        (Op::Add, vec![NEG_ZERO, ZERO], num(NEG_ZERO)),
        (Op::Add, vec![ZERO, NEG_ZERO], num(ZERO)),
        (Op::Add, vec![MINUS_ONE, ONE], num(ZERO)),
        (Op::Add, vec![f(1, 131, 13184), f(0, 131, 13184)], num(ZERO)),
        // Catastrophic cancellation: 1.0001220703125 - 1 = 2^-13.
        (
            Op::Add,
            vec![f(0, 127, 8193), MINUS_ONE],
            num(f(0, 114, 8192)),
        ),
        // The small operand's bits are shifted out entirely.
        (Op::Add, vec![ONE, f(0, 100, 8192)], num(ONE)),
        // A carry: 1.5 + 1.5 = 3.
        (
            Op::Add,
            vec![f(0, 127, 12288), f(0, 127, 12288)],
            num(f(0, 128, 12288)),
        ),
        // The difference's mantissa reaches 0 without equal operands: a hang.
        (Op::Add, vec![TWO, f(1, 127, 16384)], Outcome::Hang),
        (Op::Sub, vec![ONE, ONE], num(ZERO)),
        (Op::Sub, vec![ZERO, ZERO], num(ZERO)),
        (Op::Sub, vec![f(0, 130, 12288), HALF], num(f(0, 130, 11776))),
        // mul: the sign of a zero product, 1.0 * 1.0 renormalised.
        (Op::Mul, vec![NEG_ZERO, f(0, 129, 10240)], num(NEG_ZERO)),
        (Op::Mul, vec![ONE, ONE], num(ONE)),
        (Op::Mul, vec![MINUS_ONE, TWO], num(f(1, 128, 8192))),
        // div: by zero is Sys.error(1), a zero dividend wins.
        (Op::Div, vec![ONE, ZERO], Outcome::SysError(1)),
        (Op::Div, vec![ZERO, ZERO], num(ZERO)),
        (Op::Div, vec![NEG_ZERO, ONE], num(NEG_ZERO)),
        (Op::Div, vec![ONE, TWO], num(HALF)),
        (
            Op::Div,
            vec![f(0, 129, 10240), MINUS_ONE],
            num(f(1, 129, 10240)),
        ),
        // A non-canonical dividend with m = 0: the quotient stays 0.
        (Op::Div, vec![f(0, 130, 0), ONE], Outcome::Hang),
        // sqrt: negatives (and -0) are Sys.error(2), sqrt(0) is (0,61,0).
        (Op::Sqrt, vec![MINUS_ONE], Outcome::SysError(2)),
        (Op::Sqrt, vec![NEG_ZERO], Outcome::SysError(2)),
        (Op::Sqrt, vec![ZERO], num(f(0, 61, 0))),
        (Op::Sqrt, vec![f(0, 129, 8192)], num(TWO)),
        (Op::InvSqrt, vec![MINUS_ONE], Outcome::SysError(3)),
        // floor: -0 and small negatives go to -1; 2^14 is out of domain.
        (Op::Floor, vec![NEG_ZERO], num(MINUS_ONE)),
        (Op::Floor, vec![f(1, 126, 8192)], num(MINUS_ONE)),
        (Op::Floor, vec![HALF], num(ZERO)),
        (Op::Floor, vec![f(0, 128, 12288)], num(f(0, 128, 12288))),
        (Op::Floor, vec![f(1, 131, 13184)], num(f(1, 131, 13312))),
        (Op::Floor, vec![f(0, 141, 8192)], Outcome::OutOfDomain),
        // mod2: the units bit, sign ignored; fractions are out of domain.
        (Op::Mod2, vec![f(0, 128, 12288)], num(ONE)),
        (Op::Mod2, vec![f(1, 127, 8192)], num(ONE)),
        (Op::Mod2, vec![TWO], num(ZERO)),
        (Op::Mod2, vec![f(0, 45, 0)], num(ZERO)),
        (Op::Mod2, vec![HALF], Outcome::OutOfDomain),
        (Op::Mod2, vec![f(0, 141, 8192)], Outcome::OutOfDomain),
        // halve/double/quarter touch positive exponents only.
        (Op::Halve, vec![ONE], num(HALF)),
        (Op::Halve, vec![NEG_ZERO], num(NEG_ZERO)),
        (Op::Double, vec![ONE], num(TWO)),
        (Op::Quarter, vec![ONE], num(f(0, 125, 8192))),
        (Op::Quarter, vec![f(0, 1, 8192)], num(f(0, -1, 8192))),
    ];
    let mut failures = Vec::new();
    for (op, args, want) in &table {
        let got = jack().op(*op, args).expect("the call runs").outcome;
        if got != *want {
            failures.push(format!("{op}{args:?}: jack {got}, expected {want}"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn wrong_operand_count_is_an_error() {
    let err = jack().op(Op::Add, &[ONE]).unwrap_err();
    assert!(
        err.to_string().contains("add takes 2 operand(s), got 1"),
        "{err}"
    );
}

#[test]
fn operations_are_counted_and_a_hang_stops_at_the_budget() {
    let small = Budgets {
        op: 10_000,
        ..Budgets::default()
    };
    let jack = Raymarcher::new(Profile::Desktop, small).unwrap();
    let add = jack.op(Op::Add, &[ONE, HALF]).unwrap();
    assert_eq!(add.outcome, num(f(0, 127, 12288)));
    assert!(
        (20..1_000).contains(&add.instructions),
        "{}",
        add.instructions
    );
    let hang = jack.op(Op::Div, &[f(0, 130, 0), ONE]).unwrap();
    assert_eq!(hang.outcome, Outcome::Hang);
    assert!(hang.instructions >= 10_000);
}

#[test]
fn the_web_profile_rounds_a_negative_halving_down() {
    // A non-normalised small operand with a negative mantissa: halving -3
    // gives -1 with the desktop's truncating Math.divide, -2 on the web IDE.
    let args = [ONE, f(0, 126, -3)];
    let web = Raymarcher::new(Profile::Web, Budgets::default()).unwrap();
    assert_eq!(
        jack().op(Op::Add, &args).unwrap().outcome,
        num(f(0, 127, 8191))
    );
    assert_eq!(
        web.op(Op::Add, &args).unwrap().outcome,
        num(f(0, 127, 8190))
    );
}
