//! The runner and its text output on small fixed sets (insta snapshots:
//! stable ordering, no timings), and the localizer on a known fault.

use common::Op;
use harness::cast::Cast;
use harness::localize::localize;
use harness::runner::{diff_set, RunOptions};
use harness::text;
use vectors::{Level, Vector, VectorSet};

fn ops_of(set: &VectorSet, ops: &[Op]) -> VectorSet {
    let vectors = set
        .vectors
        .iter()
        .filter(|v| matches!(v, Vector::Op(o) if ops.contains(&o.op)))
        .cloned()
        .collect();
    VectorSet::new(
        &format!("{}-{:?}", set.name, ops),
        set.level,
        "",
        None,
        vectors,
    )
}

fn ops_small() -> VectorSet {
    vectors::load_named("ops-small").unwrap()
}

#[test]
fn a_faulty_sqrt_is_reported_grouped_and_with_localize_commands() {
    let set = ops_of(&ops_small(), &[Op::Sqrt, Op::InvSqrt]);
    let faulty = Cast::builtin().open("ref-f316+sqrt-floor-div").unwrap();
    let clean = Cast::builtin().open("ref-f316").unwrap();
    let report = diff_set(
        &[faulty.as_ref(), clean.as_ref()],
        &set,
        RunOptions::default(),
    );
    assert!(report.diverged());
    insta::assert_snapshot!(text::level_report(&report));
}

#[test]
fn three_implementations_name_the_odd_one_out() {
    let set = ops_of(&ops_small(), &[Op::Mul]);
    let faulty = Cast::builtin().open("ref-f316+mul-keep-low").unwrap();
    let (x, y) = (
        Cast::builtin().open("ref-f316").unwrap(),
        Cast::builtin().open("ref-f316").unwrap(),
    );
    let report = diff_set(
        &[x.as_ref(), faulty.as_ref(), y.as_ref()],
        &set,
        RunOptions::default(),
    );
    let c = &report.comparisons[0];
    assert!(c.diverged);
    assert!(c
        .divergences
        .iter()
        .all(|d| d.odd_one_out.as_deref() == Some("ref-f316+mul-keep-low")));
    // The clean pair agrees.
    assert!(!report.comparisons[1].diverged);
}

#[test]
fn float_policy_figures_on_sdf_small() {
    let set = vectors::load_named("sdf-small").unwrap();
    let (f32, f64) = (
        Cast::builtin().open("ref-f32").unwrap(),
        Cast::builtin().open("ref-f64").unwrap(),
    );
    let report = diff_set(&[f32.as_ref(), f64.as_ref()], &set, RunOptions::default());
    assert!(!report.diverged(), "{}", text::level_report(&report));
    insta::assert_snapshot!(text::level_report(&report));
    // The oracle is always the f64 side, whichever order they are given in.
    let swapped = diff_set(&[f64.as_ref(), f32.as_ref()], &set, RunOptions::default());
    assert_eq!(swapped.comparisons[0].a, "ref-f32");
}

#[test]
fn localize_names_the_sqrt_with_its_operands() {
    let faulty = Cast::builtin().open("ref-f316+sqrt-floor-div").unwrap();
    let clean = Cast::builtin().open("ref-f316").unwrap();
    // sqrt with an even exponent below 127: the start exponents differ.
    let input = Vector::Op(vectors::OpVector {
        category: "t".into(),
        op: Op::Sqrt,
        a: common::F316::new(0, 120, 15576),
        b: None,
    });
    let l = localize(faulty.as_ref(), clean.as_ref(), clean.as_ref(), &input).unwrap();
    assert_eq!(l.blamed_op(), Some(Op::Sqrt));
    insta::assert_snapshot!(l.to_string());
}

#[test]
fn localize_descends_to_the_operation_at_fault() {
    // sub calls add; with add's alignment fault the origin is the add.
    let faulty = Cast::builtin()
        .open("ref-f316+add-align-off-by-one")
        .unwrap();
    let clean = Cast::builtin().open("ref-f316").unwrap();
    let input = Vector::Op(vectors::OpVector {
        category: "t".into(),
        op: Op::Sub,
        a: common::F316::new(0, 128, 12345),
        b: Some(common::F316::new(0, 126, 9999)),
    });
    let l = localize(faulty.as_ref(), clean.as_ref(), clean.as_ref(), &input).unwrap();
    assert_eq!(l.first.as_ref().unwrap().a.as_ref().unwrap().op, Op::Sub);
    assert_eq!(l.blamed_op(), Some(Op::Add));
    // Every implementation given here answers every level.
    assert!(faulty.supports(Level::Image));
}
