//! gpu-f316 agrees bit for bit with ref-f316 on the small sets, and a
//! divergence against it is localized by replaying ref-f316's trace through
//! its ops kernel (it cannot trace). Needs a wgpu adapter (lavapipe will
//! do); set F316_SKIP_GPU to skip where there is none.

mod support;

use common::{Op, F316};
use harness::cast::{Cast, OpenError};
use harness::implementation::{ImplError, Implementation};
use harness::localize::{localize, replay};
use harness::runner::RunOptions;
use vectors::{OpVector, Vector};

fn gpu_f316() -> Option<Box<dyn Implementation>> {
    match Cast::builtin().open("gpu-f316") {
        Ok(g) => Some(g),
        Err(OpenError::Impl(ImplError::Unavailable(why)))
            if std::env::var_os(gpu::SKIP_ENV).is_some() =>
        {
            gpu::report_skipped(&why);
            None
        }
        Err(e) => panic!("gpu-f316: {e} (set {} to skip)", gpu::SKIP_ENV),
    }
}

#[test]
fn gpu_f316_agrees_with_ref_f316_on_the_small_sets() {
    let Some(gpu) = gpu_f316() else { return };
    support::assert_agrees_with_ref_f316_on_the_small_sets(gpu.as_ref());
}

#[test]
fn a_divergence_with_gpu_f316_is_localized_against_ref_f316s_trace() {
    let Some(gpu) = gpu_f316() else { return };
    let clean = Cast::builtin().open("ref-f316").unwrap();
    let faulty = Cast::builtin().open("ref-f316+sqrt-floor-div").unwrap();
    let input = Vector::Op(OpVector {
        category: "t".into(),
        op: Op::Sqrt,
        a: F316::new(0, 120, 15576),
        b: None,
    });
    let l = localize(faulty.as_ref(), gpu.as_ref(), clean.as_ref(), &input).unwrap();
    assert!(l.differs());
    assert!(
        l.method.contains("gpu-f316: agrees with ref-f316"),
        "{}",
        l.method
    );
    assert_eq!(l.blamed_op(), Some(Op::Sqrt), "{l}");
}

#[test]
fn replaying_a_pixel_trace_through_gpu_f316_reproduces_every_operation() {
    let Some(gpu) = gpu_f316() else { return };
    let clean = Cast::builtin().open("ref-f316").unwrap();
    let pixel = Vector::Pixel(vectors::PixelVector {
        category: "t".into(),
        x: 312,
        y: 87,
    });
    let trace = clean.trace(&pixel).unwrap();
    assert!(trace.len() > 100);
    assert_eq!(replay(gpu.as_ref(), &trace).unwrap(), trace);
}

#[test]
fn a_slice_of_the_exhaustive_unary_check_agrees() {
    let Some(gpu) = gpu_f316() else { return };
    let reference = Cast::builtin().open("ref-f316").unwrap();
    // Every 997th input: about 4,200 per operation, both signs, all exponents.
    for report in harness::exhaustive::unary(
        &[reference.as_ref(), gpu.as_ref()],
        997,
        RunOptions::default(),
    ) {
        assert!(report.vectors > 4000);
        assert!(
            !report.diverged(),
            "{}",
            harness::text::level_report(&report)
        );
    }
}
