//! The Jack program against the Rust reference (`ref-f316`), bit for bit:
//! operations on generated operands (normalised and arbitrary triples),
//! SDF queries, pixels, and whole op traces.

use common::{Op, Outcome, F316};
use jack::{Budgets, Profile, Raymarcher};
use proptest::prelude::*;
use reference::{Arith, RefImpl, Reference};
use std::sync::OnceLock;
use vectors::gen::{self, Draw};

fn jack() -> &'static Raymarcher {
    static R: OnceLock<Raymarcher> = OnceLock::new();
    // Hangs are the common trap among arbitrary triples: a budget far
    // above any finishing operation (under 40 000) keeps them cheap.
    let budgets = Budgets {
        op: 200_000,
        ..Budgets::default()
    };
    R.get_or_init(|| Raymarcher::new(Profile::Desktop, budgets).expect("the raymarcher builds"))
}

fn seed() -> &'static Reference {
    static R: OnceLock<Reference> = OnceLock::new();
    R.get_or_init(|| Reference::seed(RefImpl::F316))
}

/// Mostly normalised values near the scene's range, some zeros, some
/// arbitrary triples, some values with few mantissa bits.
fn operand() -> impl Strategy<Value = F316> {
    prop_oneof![
        1 => (0..=1i16).prop_map(|s| F316::new(s, 0, 0)),
        1 => (0..=1i16, -200..=400i16, any::<i16>()).prop_map(|(s, e, m)| F316::new(s, e, m)),
        1 => (0..=1i16, 127..=141i16, 8192..=16383i16).prop_map(|(s, e, m)| F316::new(s, e, m & !127)),
        7 => gen::ops::normalised(110..=145),
    ]
}

fn operands(draw: &mut Draw, op: Op) -> Vec<F316> {
    (0..op.arity()).map(|_| draw.one(&operand())).collect()
}

#[test]
fn operations_agree_on_generated_operands() {
    let mut draw = Draw::new(0x0f31_6d1f);
    let mut failures = Vec::new();
    for op in Op::ALL {
        for _ in 0..400 {
            let args = operands(&mut draw, op);
            let want = reference::op(op, &args, Arith::default()).unwrap();
            let got = jack().op(op, &args).unwrap().outcome;
            if got != want {
                failures.push(format!("{op}{args:?}: jack {got}, ref-f316 {want}"));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} differences:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn operation_traces_agree() {
    let mut draw = Draw::new(0x7ace);
    for op in [Op::Sub, Op::Floor, Op::Sqrt, Op::InvSqrt] {
        for _ in 0..50 {
            let args = operands(&mut draw, op);
            let want = reference::trace_op(op, &args, Arith::default())
                .unwrap()
                .records;
            let got = jack().trace_op(op, &args).unwrap();
            assert_eq!(got.len(), want.len(), "{op}{args:?}");
            for (g, w) in got.iter().zip(&want) {
                assert!(
                    g.same_computation(w),
                    "{op}{args:?}: jack {g} vs ref-f316 {w}"
                );
            }
        }
    }
}

#[test]
fn sdf_queries_agree() {
    let mut draw = Draw::new(0x5df);
    let coord =
        (-4000..=4000i32).prop_map(|v| F316::from_f64_truncating(f64::from(v) / 1000.0).unwrap());
    for _ in 0..300 {
        let p = [draw.one(&coord), draw.one(&coord), draw.one(&coord)];
        let want = seed()
            .sdf(p)
            .map(|v| (v.sd.triple.unwrap(), v.col.triple.unwrap()));
        let got = jack().sdf(p).unwrap().outcome;
        assert_eq!(got, want, "sdf at {p:?}");
    }
}

#[test]
fn pixels_agree() {
    for i in 0..150 {
        let (x, y) = ((i * 173 + 5) % 512, (i * 71 + 3) % 256);
        let want = seed()
            .pixel(x, y)
            .map(|p| (p.value.triple.unwrap(), p.white));
        let got = jack()
            .pixel(x, y)
            .unwrap()
            .outcome
            .map(|p| (p.value, p.white));
        assert_eq!(got, want, "pixel ({x},{y})");
    }
}

#[test]
fn pixel_traces_agree_op_by_op() {
    // Sky, sphere (lit and shadowed side), torus, floor in shadow.
    for (x, y) in [(10, 10), (160, 120), (130, 150), (330, 150), (300, 230)] {
        let want = seed().trace_pixel(x, y).unwrap().records;
        let got = jack().trace_pixel(x, y).unwrap();
        let first = got
            .iter()
            .zip(&want)
            .position(|(g, w)| !g.same_computation(w));
        assert_eq!(
            first, None,
            "pixel ({x},{y}): first difference at record {first:?}"
        );
        assert_eq!(got.len(), want.len(), "pixel ({x},{y})");
    }
    assert!(matches!(
        seed().trace_pixel(0, 0).unwrap().outcome,
        Outcome::Value(_)
    ));
}
