//! The example adapters through the harness: the clean one agrees with
//! ref-f316 at every level it declares; the faulty one is detected and
//! localized to `mul` through its own op trace.

use common::Op;
use harness::cast::Cast;
use harness::localize::localize;
use harness::pipe::{Pipe, PipeConfig};
use harness::runner::{diff_set, RunOptions};
use vectors::{Level, Vector};

fn adapter(label: &str, args: &[&str]) -> Pipe {
    Pipe::open(&PipeConfig::new(
        label,
        env!("CARGO_BIN_EXE_ref-pipe"),
        args,
    ))
    .unwrap()
}

fn small_set(level: Level) -> vectors::VectorSet {
    vectors::load_named(vectors::named::small_set_name(level)).unwrap()
}

#[test]
fn the_clean_adapter_agrees_with_ref_f316_at_every_level_it_declares() {
    let pipe = adapter("ref-pipe", &[]);
    assert_eq!(pipe.handshake().levels, Level::ALL.to_vec());
    let reference = Cast::builtin().open("ref-f316").unwrap();
    for level in Level::ALL {
        let set = small_set(level);
        let report = diff_set(&[reference.as_ref(), &pipe], &set, RunOptions::default());
        assert_eq!(
            report.failures().count(),
            0,
            "{}",
            harness::text::level_report(&report)
        );
        assert_eq!(report.comparisons.len(), 1);
        assert!(
            !report.diverged(),
            "{}",
            harness::text::level_report(&report)
        );
    }
}

#[test]
fn the_faulty_adapter_is_detected_and_localized_to_mul_through_its_trace() {
    let pipe = adapter("ref-pipe+mul-keep-low", &["--fault", "mul-keep-low"]);
    let reference = Cast::builtin().open("ref-f316").unwrap();
    let set = small_set(Level::Pixels);
    let report = diff_set(&[reference.as_ref(), &pipe], &set, RunOptions::default());
    assert!(
        report.diverged(),
        "{}",
        harness::text::level_report(&report)
    );
    let first = &report.comparisons[0].divergences[0];
    assert!(matches!(first.input, Vector::Pixel(_)));
    let found = localize(reference.as_ref(), &pipe, reference.as_ref(), &first.input).unwrap();
    assert_eq!(found.method, "op traces of both", "{found}");
    let origin = found.origin.as_ref().expect("an operation at fault");
    assert_eq!(origin.op, Op::Mul, "{found}");
    // One unit in the last place of the product before normalising (two
    // after a normalising doubling).
    let (a, b) = (origin.a.value().unwrap(), origin.b.value().unwrap());
    let (common::OpValue::Num(a), common::OpValue::Num(b)) = (a, b) else {
        panic!("mul gives triples: {found}");
    };
    assert_eq!((a.s, a.e), (b.s, b.e), "{found}");
    assert!(matches!((a.m - b.m).abs(), 1 | 2), "{found}");
    // The ops level finds it too: in mul, and in inv_sqrt, which calls mul
    // and is localized to it.
    let ops = diff_set(
        &[reference.as_ref(), &pipe],
        &small_set(Level::Ops),
        RunOptions::default(),
    );
    let c = &ops.comparisons[0];
    assert!(c.diverged);
    for d in &c.divergences {
        let Vector::Op(o) = &d.input else {
            panic!("an ops vector")
        };
        assert!(
            matches!(o.op, Op::Mul | Op::InvSqrt),
            "{}",
            harness::text::level_report(&ops)
        );
        let found = localize(reference.as_ref(), &pipe, reference.as_ref(), &d.input).unwrap();
        assert_eq!(found.origin.map(|o| o.op), Some(Op::Mul), "{}", d.input);
    }
}
