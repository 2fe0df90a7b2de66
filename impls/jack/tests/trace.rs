//! Op traces read from the emulator: structure, and consistency with the
//! operations run on their own.

use common::{Op, OpValue, Outcome, F316};
use jack::{Budgets, Profile, Raymarcher};
use std::sync::OnceLock;

fn jack() -> &'static Raymarcher {
    static R: OnceLock<Raymarcher> = OnceLock::new();
    R.get_or_init(|| {
        Raymarcher::new(Profile::Desktop, Budgets::default()).expect("the raymarcher builds")
    })
}

#[test]
fn sqrt_calls_div_add_halve_twice() {
    let records = jack()
        .trace_op(Op::Sqrt, &[F316::new(0, 129, 8192)])
        .unwrap();
    let ops: Vec<Op> = records.iter().map(|r| r.op).collect();
    use Op::*;
    assert_eq!(ops, [Sqrt, Div, Add, Halve, Div, Add, Halve]);
    assert_eq!(
        records[0].result,
        Outcome::Value(OpValue::Num(F316::new(0, 128, 8192)))
    );
    // The guess (0,128,8192) divides 4.0.
    assert_eq!(
        records[1].args,
        [F316::new(0, 129, 8192), F316::new(0, 128, 8192)]
    );
    assert!(
        records[1].path.last().is_some_and(|f| f == "Float316.sqrt"),
        "{:?}",
        records[1].path
    );
}

#[test]
fn sub_records_the_add_of_the_negated_operand() {
    let one = F316::ONE;
    let records = jack().trace_op(Op::Sub, &[one, one]).unwrap();
    assert_eq!(records.len(), 2);
    assert_eq!(records[1].op, Op::Add);
    assert_eq!(records[1].args, [one, one.negated()]);
    assert_eq!(records[1].result, Outcome::Value(OpValue::Num(F316::ZERO)));
}

#[test]
fn a_trap_fills_every_open_record() {
    let records = jack()
        .trace_op(Op::Sqrt, &[F316::new(1, 127, 8192)])
        .unwrap();
    assert_eq!(records.len(), 1);
    assert_eq!(records[0].result, Outcome::SysError(2));
}

#[test]
fn every_record_of_a_pixel_replays_to_its_result() {
    // A pixel on the torus: march, normal, light and shadow.
    let (x, y) = (330, 150);
    let records = jack().trace_pixel(x, y).unwrap();
    assert!(records.len() > 1_000, "{} records", records.len());
    for r in &records {
        let alone = jack().op(r.op, &r.args).unwrap().outcome;
        assert_eq!(alone, r.result, "{r}");
    }
    // The last operation decides the dithered bit.
    let last = records.last().unwrap();
    assert_eq!(last.op, Op::Gt);
    let white = jack().pixel(x, y).unwrap().outcome.value().unwrap().white;
    assert_eq!(last.result, Outcome::Value(OpValue::Bool(white)));
}

#[test]
fn an_sdf_trace_starts_with_the_floor() {
    let p = [F316::ONE, F316::ZERO, F316::new(0, 128, 8192)];
    let records = jack().trace_sdf(p).unwrap();
    assert_eq!(records[0].op, Op::Add);
    assert_eq!(records[0].args, [F316::ZERO, F316::ONE]);
    assert!(
        records[0].path.iter().any(|f| f == "Scene.floorPlane"),
        "{:?}",
        records[0].path
    );
    // The distance and colour are ref-f316's, bit for bit.
    let sdf = jack().sdf(p).unwrap();
    let Outcome::Value(want) = reference::Reference::seed(reference::RefImpl::F316).sdf(p) else {
        panic!("ref-f316 answers at {p:?}");
    };
    let triples = (want.sd.triple.unwrap(), want.col.triple.unwrap());
    assert_eq!(sdf.outcome, Outcome::Value(triples));
}
