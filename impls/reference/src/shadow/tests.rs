use super::*;
use crate::{RefImpl, Reference};
use common::Outcome;

fn recorded() -> ShadowOptions {
    ShadowOptions {
        record_ops: true,
        flip: None,
        follow: None,
    }
}

/// The shadowed run's low-precision answer is the plain run's, bit for
/// bit, in every formulation, and ref-f64's shadow is its own value.
#[test]
fn the_low_precision_side_is_the_plain_implementation() {
    for imp in RefImpl::ALL {
        let r = Reference::seed(imp);
        for y in [0, 40, 87, 130, 200, 255] {
            for x in (0..512).step_by(37) {
                let run = r.shadow_pixel(x, y, &ShadowOptions::default());
                let Outcome::Value(plain) = r.pixel(x, y) else {
                    panic!("{imp} ({x},{y}) trapped");
                };
                let out = run.outcome.value().expect("no trap");
                assert_eq!(out.values[0].lo, plain.value.value, "{imp} ({x},{y})");
                assert_eq!(out.white, Some(plain.white), "{imp} ({x},{y})");
                if imp == RefImpl::F64 {
                    assert_eq!(out.values[0].hi, out.values[0].lo, "({x},{y})");
                }
            }
        }
    }
}

/// A run records operations with their local and accumulated errors and
/// call paths, and the pipeline's decisions with both sides' operands.
#[test]
fn operations_and_decisions_are_recorded_with_their_paths() {
    let r = Reference::seed(RefImpl::F316);
    let run = r.shadow_pixel(120, 100, &recorded());
    assert!(run.ops.len() > 1000, "{} operations", run.ops.len());
    let inv = run
        .ops
        .iter()
        .find(|o| o.op == "inv_sqrt" && run.site_path(o.site) != "camera > normalize")
        .expect("normalize calls inv_sqrt");
    assert_eq!(run.path(inv.path), "pixel(120,100) > normalize");
    assert_eq!(run.site_path(inv.site), "pixel(*,*) > normalize");
    assert!(run.ops.iter().any(|o| o.local_error > 0.0));
    assert!(run.ops.iter().any(|o| o.accumulated_error() > 0.0));
    let kinds: Vec<Decision> = run.decisions.iter().map(|d| d.decision).collect();
    for d in [
        Decision::Union,
        Decision::Checker,
        Decision::MarchHit,
        Decision::MarchFar,
        Decision::Miss,
        Decision::Dither,
    ] {
        assert!(kinds.contains(&d), "{d} missing");
    }
    let last = run.decisions.last().unwrap();
    assert_eq!(last.decision, Decision::Dither);
    assert_eq!(run.path(last.path), "pixel(120,100)");
}

/// A small pipeline over the engine: two nearly equal large terms, one
/// at a power of two (8192) and one just below it (8191.5), subtracted.
/// Both terms are exact (doublings); Float316's `add` has no guard bit, so
/// aligning the smaller term drops its last bit and the difference comes
/// out as 1 instead of 0.5: the root cause is that `sub`.
fn cancelling<E: Engine>(e: &mut E, a: E::N, b: E::N, c: E::N) -> R<E::N> {
    e.frame(
        || "test".into(),
        |e| {
            let big = e.add(a, a)?;
            let other = e.add(b, b)?;
            let d = e.frame(|| "difference".into(), |e| e.sub(big, other))?;
            let scaled = e.mul(d, c)?;
            e.add(scaled, c)
        },
    )
}

fn run_cancelling(options: &ShadowOptions) -> ShadowRun {
    type F = crate::float316::F316Engine;
    let mut e = ShadowEngine::new(F::new(crate::Arith::SPEC), options.clone());
    let k = |x: f64| ShadowEngine::<F>::constant(x).expect("exact in Float316");
    let r = cancelling(&mut e, k(4096.0), k(4095.75), k(3.0));
    let out = r.map(|v| ShadowOutput {
        values: vec![OutputValue {
            name: "out",
            lo: v.lo.to_f64(),
            hi: v.hi,
        }],
        white: None,
    });
    e.finish(crate::engine::outcome(out))
}

#[test]
fn a_cancellation_is_blamed_on_its_sub() {
    let base = run_cancelling(&recorded());
    let error = |r: &ShadowRun| r.output("out").map(|o| o.lo - o.hi);
    assert_eq!(
        error(&base),
        Some(1.5),
        "the difference is off by 0.5, times 3"
    );
    let flipped = |site: &SiteKey| {
        run_cancelling(&ShadowOptions {
            record_ops: false,
            flip: Some(site.clone()),
            follow: None,
        })
    };
    let blamed = blame(&base, usize::MAX, flipped, error);
    let top = &blamed[0];
    assert_eq!(top.site.op, "sub", "{blamed:#?}");
    assert_eq!(top.site.path, "test > difference");
    assert_eq!(top.share, 1.0, "{blamed:#?}");
    assert_eq!(top.worst.operands(), [(8192.0, 8192.0), (8191.5, 8191.5)]);
    assert_eq!(top.worst.result, (1.0, 0.5));
    assert_eq!(top.worst.local_error, 0.5);
    assert!(top.worst.cancelled_bits() >= 13.0, "{:?}", top.worst);
    // Nothing else contributes: the other operations are exact.
    assert!(
        blamed[1..].iter().all(|b| b.contribution == 0.0),
        "{blamed:#?}"
    );
}

#[test]
fn digits_collapse_to_stars() {
    assert_eq!(collapse_digits("pixel(312,87)"), "pixel(*,*)");
    assert_eq!(
        collapse_digits("shadow march step 14"),
        "shadow march step *"
    );
    assert_eq!(collapse_digits("scene"), "scene");
}

/// Blaming one seed pixel reruns it once per site that makes a local
/// error; the flipped run of the top site changes the error.
#[test]
fn blaming_a_seed_pixel_reruns_each_site() {
    let r = Reference::seed(RefImpl::F316);
    let (x, y) = (120, 100);
    let base = r.shadow_pixel(x, y, &recorded());
    let error = |run: &ShadowRun| run.output("shade").map(|o| o.lo - o.hi);
    let flipped = |site: &SiteKey| {
        r.shadow_pixel(
            x,
            y,
            &ShadowOptions {
                record_ops: false,
                flip: Some(site.clone()),
                follow: None,
            },
        )
    };
    let blamed = blame(&base, usize::MAX, flipped, error);
    assert_eq!(blamed.len(), candidate_sites(&base).len());
    assert!(blamed[0].contribution > 0.0);
}
