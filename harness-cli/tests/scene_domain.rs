//! A scene that drives Float316's `floor` and `mod2` outside their modelled
//! domain (`vectors/scenes/tests/domain.json`), through the harness: the
//! renders of ref-f316 and gpu-f316 give the same outcome for every pixel,
//! out of domain on the same ones; the nightly's scenes step compares them
//! and the generated Jack program with no divergence, counts as many
//! answers out of domain on each, and its coverage sees both operations'
//! traps reached (gpu-f316 needs a wgpu adapter: lavapipe will do;
//! F316_SKIP_GPU skips it).

use crate::binary;

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
}

/// The nightly's scenes step on the scene: ref-f316, the generated Jack
/// program and (where a wgpu adapter is found) gpu-f316 compared with no
/// divergence, the same number of answers out of domain on each at both
/// levels in the report's outcomes (632 pixels), `Main.main` stopping where the
/// reference stops, and coverage seeing both operations' traps reached.
#[test]
fn the_nightly_counts_the_same_answers_out_of_domain_on_every_float316_implementation() {
    let gpu = std::env::var_os(gpu::SKIP_ENV).is_none();
    if !gpu {
        gpu::report_skipped("gpu-f316 in the nightly's out-of-domain counts");
    }
    let impls = if gpu {
        "ref-f316,gpu-f316,jack"
    } else {
        "ref-f316,jack"
    };
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("nightly");
    let o = harness(&[
        "nightly",
        "--impls",
        impls,
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
    let compared: Vec<String> = rows
        .iter()
        .map(|c| format!("{} {} {}", c["level"], c["a"], c["b"]))
        .collect();
    for c in &rows {
        assert_eq!(c["divergences"], 0, "{c}");
    }
    let stops = rows
        .iter()
        .find(|c| c["level"] == "screen" && c["a"] == "ref-f316")
        .unwrap_or_else(|| panic!("a screen row: {compared:?}"));
    assert!(
        stops["findings"]
            .to_string()
            .contains("Main.main stops too"),
        "{stops}"
    );
    let scene = &report["scenes"][0];
    let outcomes = scene["outcomes"].as_array().unwrap();
    let legs = if gpu { 3 } else { 2 };
    for level in ["pixels", "sdf"] {
        let counts: Vec<(&str, u64)> = outcomes
            .iter()
            // The oracle ref-f64, always opened, answers values there.
            .filter(|o| o["level"] == level && o["implementation"] != "ref-f64")
            .map(|o| {
                (
                    o["implementation"].as_str().unwrap(),
                    o["out_of_domain"].as_u64().unwrap(),
                )
            })
            .collect();
        assert_eq!(counts.len(), legs, "{level}: {counts:?}");
        // The step's SDF points lie near the surfaces, where the scene is
        // in domain; its sky and far floor are not.
        let least = if level == "pixels" { 300 } else { 0 };
        assert!(counts[0].1 >= least, "{level}: {counts:?}");
        assert!(
            counts.iter().all(|c| c.1 == counts[0].1),
            "{level}: {counts:?}"
        );
    }
    let never = scene["domains_never_reached"].to_string();
    for trap in ["floor -> trap", "mod2 -> trap"] {
        assert!(!never.contains(trap), "{trap} is reached: {never}");
    }
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(html.contains("out of domain") && !html.contains("disagree on how many"));
}
