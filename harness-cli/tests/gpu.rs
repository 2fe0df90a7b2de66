//! gpu-f316 agrees bit for bit with ref-f316 on the small sets, and a
//! divergence against it is localized by replaying ref-f316's trace through
//! its ops kernel (it cannot trace). A user's Float316 WGSL file does the
//! same through the shader kind, and one wrong operation in it is an ops
//! divergence. The nightly runs the seed scene's Shadertoy port. Needs a
//! wgpu adapter (lavapipe will do); set F316_SKIP_GPU to skip where there
//! is none.

use crate::support;

use common::{Op, F316};
use harness::cast::{Cast, OpenError};
use harness::implementation::{ImplError, Implementation};
use harness::localize::{localize, replay};
use harness::runner::RunOptions;
use std::path::Path;
use vectors::{Level, OpVector, Vector};

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

/// Our Float316 WGSL (impls/gpu/src/shaders/f316.wgsl: `pixel`, `sdf`
/// and `op` of the convention), or `edit` of it, as a user's file declared
/// with `kind = "shader"` and `numbers = "float316"` in a project file.
fn user_float316(dir: &Path, edit: impl Fn(&str) -> String) -> Option<Box<dyn Implementation>> {
    let ours = Path::new(env!("CARGO_MANIFEST_DIR")).join("../impls/gpu/src/shaders/f316.wgsl");
    let text = edit(&std::fs::read_to_string(ours).unwrap());
    std::fs::write(dir.join("mine.wgsl"), text).unwrap();
    let project = dir.join("harness.toml");
    let cast = Cast::with_project(
        &project,
        "[impl.mine]\nkind = \"shader\"\npath = \"mine.wgsl\"\nnumbers = \"float316\"\n",
    )
    .unwrap();
    let entry = cast.get("mine").unwrap();
    assert_eq!(
        (entry.kind, entry.levels.as_slice()),
        ("shader", Level::ALL.as_slice())
    );
    match cast.open("mine") {
        Ok(imp) => Some(imp),
        Err(OpenError::Impl(ImplError::Unavailable(why)))
            if std::env::var_os(gpu::SKIP_ENV).is_some() =>
        {
            gpu::report_skipped(&why);
            None
        }
        Err(e) => panic!("mine.wgsl: {e}"),
    }
}

#[test]
fn a_users_float316_wgsl_agrees_bit_for_bit_with_ref_f316_at_every_level() {
    let dir = tempfile::tempdir().unwrap();
    let Some(mine) = user_float316(dir.path(), str::to_string) else {
        return;
    };
    support::assert_agrees_with_ref_f316_on_the_small_sets(mine.as_ref());
    let image = Vector::Image(vectors::ImageVector {
        category: "t".into(),
    });
    let reference = Cast::builtin().open("ref-f316").unwrap();
    assert_eq!(
        mine.eval(std::slice::from_ref(&image)).unwrap(),
        reference.eval(&[image]).unwrap(),
        "the whole image"
    );
}

/// A user's Float316 file whose sqrt runs one Newton step instead of two:
/// the ops level reports divergences, every one of them a sqrt.
#[test]
fn a_wrong_float316_op_in_a_users_wgsl_is_an_ops_divergence() {
    let dir = tempfile::tempdir().unwrap();
    let one_step = |text: &str| {
        let two = "fn sqrt316(x: F) -> F {\n    return sqrt316_steps(x, 2);";
        assert!(text.contains(two), "sqrt316's two Newton steps");
        text.replace(
            two,
            "fn sqrt316(x: F) -> F {\n    return sqrt316_steps(x, 1);",
        )
    };
    let Some(mine) = user_float316(dir.path(), one_step) else {
        return;
    };
    let reference = Cast::builtin().open("ref-f316").unwrap();
    let report = support::assert_diverges_on_the_small_ops_set(reference.as_ref(), mine.as_ref());
    let divergences = &report.comparisons[0].divergences;
    assert!(!divergences.is_empty());
    for d in divergences {
        assert!(
            matches!(&d.input, Vector::Op(o) if o.op == Op::Sqrt),
            "{}",
            d.input
        );
    }
}

/// `harness nightly` runs the seed scene's Shadertoy port by default
/// (`seed-shadertoy`): the report has its pixels row against ref-f64 with
/// error figures, its image pair with ref-f64 and its speed row with the
/// dithered-pixel flips.
#[test]
fn the_nightly_reports_the_shadertoy_port_against_ref_f64() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("nightly");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_harness"))
        .args(["nightly", "--impls", "seed-shadertoy", "--steps"])
        .arg("levels,renders,pairs,speed")
        .arg("--out")
        .arg(&out)
        .current_dir(dir.path())
        .output()
        .unwrap();
    let log = format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    let status = report["implementations"]
        .as_array()
        .unwrap()
        .iter()
        .find(|i| i["name"] == "seed-shadertoy")
        .unwrap_or_else(|| panic!("seed-shadertoy in the report: {log}"))
        .clone();
    if status["available"] == false && std::env::var_os(gpu::SKIP_ENV).is_some() {
        gpu::report_skipped(status["note"].as_str().unwrap_or("unavailable"));
        return;
    }
    assert_eq!(o.status.code(), Some(0), "{log}");
    let row = report["comparisons"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["level"] == "pixels" && c["a"] == "seed-shadertoy")
        .unwrap_or_else(|| panic!("a pixels row of seed-shadertoy: {log}"))
        .clone();
    assert_eq!(
        (row["b"].as_str(), row["policy"].as_str()),
        (Some("ref-f64"), Some("error figures"))
    );
    let max = row["error"]["max_abs"].as_f64().unwrap();
    assert!(max > 0.0 && max < 1e-3, "{row}");
    let pair = report["image_pairs"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["a"] == "ref-f64" && p["b"] == "seed-shadertoy")
        .unwrap_or_else(|| panic!("an image pair ref-f64 / seed-shadertoy: {log}"))
        .clone();
    assert_eq!(pair["bit_exact"], false);
    let bench = report["bench"]
        .as_array()
        .unwrap()
        .iter()
        .find(|b| b["implementation"] == "seed-shadertoy")
        .unwrap_or_else(|| panic!("a speed row of seed-shadertoy: {log}"))
        .clone();
    let flips = bench["pixel_flips"].as_u64().unwrap();
    assert_eq!(Some(flips), pair["differing_pixels"].as_u64(), "{pair}");
    assert!(flips <= 131, "{bench}");
    assert!(bench["max_shade_error"].as_f64().unwrap() < 1e-3, "{bench}");
}
