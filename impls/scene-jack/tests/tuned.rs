//! A seed scene with tuned call sites (`variants`): its generated program
//! calls the variants' subroutines, and only it has them, and it answers
//! as ref-f316 of the same description, bit for bit, at both levels,
//! where the untuned scene answers otherwise.

mod support;

use reference::{Described, RefImpl, Settings};
use scene::{Checked, Formulation};
use scene_jack::cost::Runner;
use support::*;

/// The seed with the shadow ray's `normalize`, the shadow's `length` and
/// the torus's second `sqrt` at one Newton step, and the shadow march at
/// 16 steps (`vectors/scenes/tests/seed-tuned.json`, as gpu-f316's test
/// uses it).
fn tuned_seed() -> Checked {
    let c = checked("tests/seed-tuned");
    assert_eq!(c.description.variants.len(), 4);
    c
}

fn f316(c: &Checked) -> Described {
    Described::new(RefImpl::F316, c, Settings::default()).unwrap()
}

#[test]
fn the_variants_subroutines_are_in_the_tuned_program_only() {
    let tuned = tuned_seed();
    let text = |c: &Checked| -> String {
        let p = scene::lower(c, Formulation::Float316);
        let j = scene_jack::emit(&p).unwrap();
        j.classes.iter().map(|c| c.text.clone()).collect()
    };
    let t = text(&tuned);
    for sub in [
        "method void invSqrtNewton1",
        "method void sqrtNewton1",
        "Ops.normalize3Newton1(",
    ] {
        assert!(t.contains(sub), "{sub}");
    }
    let plain = text(&checked("seed"));
    assert!(!plain.contains("Newton1"));
    // The hand-written class is unchanged: the plain program's Float316
    // subroutines are its own.
    assert!(!include_str!("../../jack/raymarcher/Float316.jack").contains("Newton1"));
}

#[test]
fn the_tuned_program_equals_the_tuned_reference_at_sdf_and_pixels() {
    let tuned = tuned_seed();
    let d = f316(&tuned);
    let plain = f316(&checked("seed"));
    let j = scene_jack::emit(d.program()).unwrap();
    agrees_with_its_reference(
        &j,
        &d,
        &plain,
        "the torus's sqrt with newton-1 changes some SDF answer",
    );
}

/// The seed with both floors at `floor-direct` and four products
/// truncated, two of them in the torus's distance
/// (`vectors/scenes/tests/seed-tuned-ops.json`, as gpu-f316's test uses
/// it).
fn ops_seed() -> Checked {
    let c = checked("tests/seed-tuned-ops");
    assert_eq!(c.description.variants.len(), 6);
    c
}

#[test]
fn the_operation_variants_program_equals_its_reference_at_sdf_and_pixels() {
    let tuned = ops_seed();
    let d = f316(&tuned);
    let plain = f316(&checked("seed"));
    let j = scene_jack::emit(d.program()).unwrap();
    let text: String = j.classes.iter().map(|c| c.text.clone()).collect();
    for sub in ["method void mulTruncated", "method void floorDirect"] {
        assert!(text.contains(sub), "{sub}");
    }
    agrees_with_its_reference(
        &j,
        &d,
        &plain,
        "the torus's truncated products change some SDF answer",
    );
}

/// Each operation variant costs fewer VM instructions per call on the
/// generated program than the spec's subroutine it replaces, the calls
/// counted by ref-f316 on the same pixels: `mulTruncated` against `mul`,
/// and `floorDirect` against `floor` with the `add` a negative
/// non-integer's `floor` calls.
#[test]
fn each_operation_variant_is_cheaper_per_call_than_the_spec() {
    use common::Op;
    use scene::ir::Tuning;
    let d = f316(&ops_seed());
    let plain = f316(&checked("seed"));
    let pixels: Vec<(u32, u32)> = (100..180)
        .step_by(20)
        .flat_map(|y| (0..512).step_by(32).map(move |x| (x, y)))
        .collect();
    let spent = |d: &Described| {
        let j = scene_jack::emit(d.program()).unwrap();
        let r = Runner::profiled(&j, jack::Profile::Desktop).unwrap();
        let mut by_function = std::collections::HashMap::<String, u64>::new();
        let mut counts = reference::OpCounts::default();
        for &(x, y) in &pixels {
            for (f, n) in r.pixel_profile(x, y) {
                *by_function.entry(f).or_default() += n;
            }
            counts.add(&d.pixel_counted(x, y).unwrap().1);
        }
        (by_function, counts)
    };
    let (tuned, tc) = spent(&d);
    let per_call = |f: &str, calls: u64| tuned[f] as f64 / calls as f64;
    let truncated = per_call(
        "Float316.mulTruncated",
        tc.of_variant(Op::Mul, Tuning::TruncatedProduct),
    );
    let mul = per_call("Float316.mul", tc.of_spec(Op::Mul));
    assert!(
        truncated < mul,
        "mulTruncated {truncated:.1} against mul {mul:.1}"
    );

    // The seed with its floors alone tuned computes the same values, so
    // its only missing operations are the adds floor called.
    let seed = scene::SEED.trim_end().strip_suffix('}').unwrap();
    let floors_only = format!(
        r#"{seed}, "variants": [
            {{"site": "sdf/scene/floor/floor", "variant": "floor-direct"}},
            {{"site": "sdf/scene/floor/floor#2", "variant": "floor-direct"}}]}}"#
    );
    let floors_only = f316(&scene::parse(&floors_only).unwrap());
    let (direct, dc) = spent(&floors_only);
    let (untuned, uc) = spent(&plain);
    let floors = uc.of(Op::Floor);
    assert_eq!(floors, dc.of_variant(Op::Floor, Tuning::FloorDirect));
    let nested_adds = uc.of(Op::Add) - dc.of(Op::Add);
    assert!(
        nested_adds > 0,
        "some floor steps a negative non-integer down"
    );
    let add = untuned["Float316.add"] as f64 / uc.of(Op::Add) as f64;
    let spec_floor = (untuned["Float316.floor"] as f64 + add * nested_adds as f64) / floors as f64;
    let per_floor = direct["Float316.floorDirect"] as f64 / floors as f64;
    assert!(
        per_floor < spec_floor,
        "floorDirect {per_floor:.1} against floor {spec_floor:.1}"
    );
    let total = |m: &std::collections::HashMap<String, u64>| m.values().sum::<u64>();
    assert!(total(&direct) < total(&untuned));
}

/// The generated program `j` answers as `d`, ref-f316 of the tuned
/// description, on a grid of SDF points and a sample of pixels, and some
/// SDF answer differs from the untuned `plain`'s (`changes` says which).
fn agrees_with_its_reference(
    j: &scene_jack::JackSources,
    d: &Described,
    plain: &Described,
    changes: &str,
) {
    let r = Runner::new(j, jack::Profile::Desktop).expect("compiles and sets up");
    let points = grid(6);
    let bad: Vec<String> = points
        .iter()
        .filter_map(|&p| sdf_mismatch(&r, d, p))
        .collect();
    assert!(
        bad.is_empty(),
        "{} SDF answers differ: {:?}",
        bad.len(),
        &bad[..bad.len().min(5)]
    );
    let changed = points.iter().filter(|&&p| d.sdf(p) != plain.sdf(p)).count();
    assert!(changed > 0, "{changes}");
    let bad: Vec<String> = [40u32, 100, 128, 150, 200]
        .iter()
        .flat_map(|&y| (0..512).step_by(7).map(move |x| (x, y)))
        .filter_map(|(x, y)| pixel_mismatch(&r, d, x, y))
        .collect();
    assert!(
        bad.is_empty(),
        "{} pixels differ: {:?}",
        bad.len(),
        &bad[..bad.len().min(5)]
    );
}
