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
    let r = Runner::new(&j, jack::Profile::Desktop).expect("compiles and sets up");
    let points = grid(6);
    let bad: Vec<String> = points
        .iter()
        .filter_map(|&p| sdf_mismatch(&r, &d, p))
        .collect();
    assert!(
        bad.is_empty(),
        "{} SDF answers differ: {:?}",
        bad.len(),
        &bad[..bad.len().min(5)]
    );
    let changed = points.iter().filter(|&&p| d.sdf(p) != plain.sdf(p)).count();
    assert!(
        changed > 0,
        "the torus's sqrt with newton-1 changes some SDF answer"
    );
    let bad: Vec<String> = [40u32, 100, 128, 150, 200]
        .iter()
        .flat_map(|&y| (0..512).step_by(7).map(move |x| (x, y)))
        .filter_map(|(x, y)| pixel_mismatch(&r, &d, x, y))
        .collect();
    assert!(
        bad.is_empty(),
        "{} pixels differ: {:?}",
        bad.len(),
        &bad[..bad.len().min(5)]
    );
}
