//! A scene that drives Float316's `floor` and `mod2` outside their modelled
//! domain (`vectors/scenes/tests/domain.json`), through the harness: the
//! renders of ref-f316 and gpu-f316 give the same outcome for every pixel,
//! out of domain on the same ones; the nightly's scenes step compares them
//! with no divergence, and its coverage sees both operations' traps reached
//! (needs a wgpu adapter: lavapipe will do; F316_SKIP_GPU skips it).

mod binary;

use binary::{harness, text};
use serde_json::Value;
use std::path::{Path, PathBuf};

fn scene() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../vectors/scenes/tests/domain.json")
}

/// The `--values` file of `harness render --impl IMPL --scene domain.json`.
fn values(dir: &Path, imp: &str) -> Value {
    let (png, json) = (
        dir.join(format!("{imp}.png")),
        dir.join(format!("{imp}.json")),
    );
    let o = harness(&[
        "render",
        "--impl",
        imp,
        "--scene",
        scene().to_str().unwrap(),
        "--out",
        png.to_str().unwrap(),
        "--values",
        json.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    serde_json::from_str(&std::fs::read_to_string(json).unwrap()).unwrap()
}

#[test]
fn ref_f316_and_gpu_f316_are_out_of_domain_on_the_same_pixels() {
    if std::env::var_os(gpu::SKIP_ENV).is_some() {
        gpu::report_skipped("the out-of-domain scene on gpu-f316");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let (r, g) = (
        values(dir.path(), "ref-f316"),
        values(dir.path(), "gpu-f316"),
    );
    let kinds = |v: &Value| -> Vec<String> {
        v["pixels"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| p["kind"].as_str().unwrap().to_string())
            .collect()
    };
    let (kr, kg) = (kinds(&r), kinds(&g));
    assert_eq!(kr, kg, "the same outcome on every pixel");
    let ood = kr.iter().filter(|k| *k == "out_of_domain").count();
    assert!(ood > 300 && ood < kr.len() - 1000, "{ood} of {}", kr.len());

    let out = dir.path().join("nightly");
    let o = harness(&[
        "nightly",
        "--impls",
        "ref-f316,gpu-f316",
        "--steps",
        "scenes",
        "--scene",
        scene().to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let report: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    assert_eq!(report["problems"], serde_json::json!([]), "{report}");
    let rows: Vec<&Value> = report["comparisons"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|c| c["scope"] == "scene domain")
        .collect();
    assert_eq!(rows.len(), 2, "pixels and sdf: {report}");
    for c in rows {
        assert_eq!(c["divergences"], 0, "{c}");
    }
    let never = report["scenes"][0]["domains_never_reached"].to_string();
    for trap in ["floor -> trap", "mod2 -> trap"] {
        assert!(!never.contains(trap), "{trap} is reached: {never}");
    }
}
