//! `harness tune` on a small scene (`vectors/scenes/tests/tune-small.json`,
//! 64x32): the search keeps the picture, saves VM instructions, says why a
//! site stays untuned, checks the generated programs bit for bit, writes a
//! tuned description that loads, and a rerun on its state renders nothing;
//! bad input exits 2 naming the file or field.

use crate::binary;

use binary::{assert_status, harness_in, text};
use std::path::{Path, PathBuf};

fn small() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../vectors/scenes/tests/tune-small.json")
}

fn tune(dir: &Path, extra: &[&str]) -> (Option<i32>, String, serde_json::Value) {
    let scene = small();
    let mut args = vec![
        "tune",
        "--scene",
        scene.to_str().unwrap(),
        "--out",
        "tuned.json",
        "--state",
        "state.json",
        "--json",
    ];
    args.extend_from_slice(extra);
    let out = harness_in(dir, &args);
    let report = serde_json::from_slice(&out.stdout).unwrap_or(serde_json::Value::Null);
    (out.status.code(), text(&out), report)
}

#[test]
fn tuning_keeps_the_picture_saves_and_says_why_a_site_is_left_out() {
    let dir = tempfile::tempdir().unwrap();
    let (code, out, r) = tune(dir.path(), &[]);
    assert_eq!(code, Some(0), "{out}");
    assert_eq!(r["flips"], 0, "{out}");
    assert_eq!(r["jack"]["tuned_mismatches"], 0, "{out}");
    assert_eq!(r["jack"]["untuned_mismatches"], 0, "{out}");
    assert!(
        r["estimated"]["saved_per_pixel"].as_f64().unwrap() > 0.0,
        "{out}"
    );
    assert!(
        r["jack"]["measured"]["saved_per_pixel"].as_f64().unwrap() > 0.0,
        "{out}"
    );
    let tuned: Vec<&str> = r["tuned"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t["site"].as_str().unwrap())
        .collect();
    assert!(!tuned.is_empty(), "{out}");
    // Every site left out says why; one that fails names its pixel and
    // the decision that changed there.
    let rejected = r["rejected"].as_array().unwrap();
    assert!(!rejected.is_empty(), "{out}");
    let failing = rejected
        .iter()
        .find(|x| x["reason"] == "fails")
        .expect("a site fails");
    assert!(failing["flips"].as_u64().unwrap() > 0, "{out}");
    assert!(failing["pixel"]["explanation"].is_string(), "{out}");
    assert_eq!(
        r["sites"].as_u64().unwrap() as usize,
        tuned.len() + rejected.len(),
        "{out}"
    );
    // The tuned description loads and carries the tuned sites.
    let written = scene::load(&dir.path().join("tuned.json")).unwrap();
    let sites: Vec<&str> = written
        .description
        .variants
        .iter()
        .map(|v| v.site.as_str())
        .collect();
    assert_eq!(sites, tuned);
    assert_eq!(written.description.name, "tuned");
    let svg = std::fs::read_to_string(dir.path().join("tuned-pareto.svg")).unwrap();
    assert!(svg.starts_with("<svg"));
    // The same search again on its state renders nothing new.
    let (code, out, again) = tune(dir.path(), &["--jack-step", "4"]);
    assert_eq!(code, Some(0), "{out}");
    assert_eq!(again["rendered"], 0, "{out}");
    assert_eq!(again["tuned"], r["tuned"], "{out}");
}

#[test]
fn bad_input_exits_2_naming_the_file_or_the_field() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("missing.json");
    let out = harness_in(dir.path(), &["tune", "--scene", missing.to_str().unwrap()]);
    assert_status(&out, 2, &["missing.json"]);

    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(small()).unwrap()).unwrap();
    v["variants"] = serde_json::json!([{"site": "pixel/normalize", "variant": "newton-7"}]);
    let bad = dir.path().join("bad.json");
    std::fs::write(&bad, v.to_string()).unwrap();
    let out = harness_in(dir.path(), &["tune", "--scene", bad.to_str().unwrap()]);
    assert_status(&out, 2, &["variants[0].variant"]);

    let scene = small();
    let out = harness_in(
        dir.path(),
        &["tune", "--scene", scene.to_str().unwrap(), "--max-error=-1"],
    );
    assert_status(&out, 2, &["--max-error"]);

    let seed = Path::new(env!("CARGO_MANIFEST_DIR")).join("../vectors/scenes/seed.json");
    let out = harness_in(
        dir.path(),
        &["tune", "--scene", seed.to_str().unwrap(), "--exhaustive"],
    );
    assert_status(&out, 2, &["--exhaustive: "]);

    std::fs::write(dir.path().join("state.json"), "{}").unwrap();
    let out = harness_in(
        dir.path(),
        &[
            "tune",
            "--scene",
            scene.to_str().unwrap(),
            "--state",
            "state.json",
        ],
    );
    assert_status(&out, 2, &["--state"]);
}
