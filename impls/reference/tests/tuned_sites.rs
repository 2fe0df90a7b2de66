//! A call site tuned in the description (`variants`) runs with its variant
//! on ref-f316, and only there: the shadow ray's `normalize` with one
//! Newton step computes `invSqrt` as the global `newton-1` does, every
//! other `invSqrt` as the spec does.

use common::{Op, TraceRecord};
use reference::{op, Arith, Described, RefImpl, Settings, Variant};

fn seed(variants: &str) -> scene::Checked {
    let mut v: serde_json::Value = serde_json::from_str(scene::SEED).unwrap();
    v["variants"] = serde_json::from_str(variants).unwrap();
    scene::parse(&v.to_string()).unwrap_or_else(|e| panic!("{e}"))
}

/// The `invSqrt` records of a trace, with whether they are in the shadow
/// frame.
fn inv_sqrts(records: &[TraceRecord]) -> Vec<(bool, &TraceRecord)> {
    records
        .iter()
        .filter(|r| r.op == Op::InvSqrt)
        .map(|r| (r.path.iter().any(|f| f == "shadow"), r))
        .collect()
}

#[test]
fn a_tuned_site_computes_with_its_variant_and_no_other_site_does() {
    let tuned = Described::new(
        RefImpl::F316,
        &seed(r#"[{"site": "pixel/shadow/normalize", "variant": "newton-1"}]"#),
        Settings::default(),
    )
    .unwrap();
    let newton1 = Variant::Newton1.apply(Settings::default()).arith;
    let (mut tuned_seen, mut changed) = (0, 0);
    for (x, y) in (0..512)
        .step_by(37)
        .flat_map(|x| (0..256).step_by(23).map(move |y| (x, y)))
    {
        let t = tuned.trace_pixel(x, y).unwrap();
        for (in_shadow, r) in inv_sqrts(&t.records) {
            let arith = if in_shadow { newton1 } else { Arith::SPEC };
            let expected = op(Op::InvSqrt, &r.args, arith).unwrap();
            assert_eq!(r.result, expected, "({x},{y}) {r}");
            if in_shadow {
                tuned_seen += 1;
                let spec = op(Op::InvSqrt, &r.args, Arith::SPEC).unwrap();
                changed += usize::from(spec != r.result);
            }
        }
    }
    assert!(tuned_seen > 0, "the sample reaches the tuned site");
    assert!(
        changed > 0,
        "one Newton step fewer changes some answer of the site"
    );
}

#[test]
fn the_float_references_ignore_the_variants() {
    let tuned = seed(r#"[{"site": "pixel/shadow/normalize", "variant": "newton-1"}]"#);
    let plain = scene::parse(scene::SEED).unwrap();
    let a = Described::new(RefImpl::F64, &tuned, Settings::default()).unwrap();
    let b = Described::new(RefImpl::F64, &plain, Settings::default()).unwrap();
    assert_eq!(a.program(), b.program());
}
