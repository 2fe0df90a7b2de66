//! `harness nightly --steps scenes --scene NAME`: a described scene on the
//! reference implementations, with what it uses, what it never reaches and
//! its cost per pixel in the report; gpu-f316 made from the description,
//! compared with ref-f316 bit for bit (needs a wgpu adapter: lavapipe will
//! do; F316_SKIP_GPU skips it); a bad scene file fails the night with its
//! field named; an unknown scene name is refused before the run.

use crate::binary;

use binary::{assert_says, harness, text};
use std::path::Path;
use std::process::Output;

fn night(out: &Path, scene: &str) -> Output {
    night_of("ref-f64,ref-f32,ref-f316", out, scene)
}

fn night_of(impls: &str, out: &Path, scene: &str) -> Output {
    harness(&[
        "nightly",
        "--impls",
        impls,
        "--steps",
        "scenes",
        "--scene",
        scene,
        "--out",
        out.to_str().unwrap(),
    ])
}

#[test]
fn the_scene_step_reports_use_reach_and_cost() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("nightly");
    let o = night(&out, "rtdemo");
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    let scenes = report["scenes"].as_array().unwrap();
    assert_eq!(scenes.len(), 1);
    let s = &scenes[0];
    assert_eq!(s["name"], "rtdemo");
    assert_eq!(s["shapes"], serde_json::json!(["sphere", "union"]));
    // The BBC demo normalises by a square root and a division: it never
    // calls inv_sqrt, and its sqrt never sees a negative operand.
    assert!(s["reached"]["sqrt"].as_u64().unwrap() > 0, "{s}");
    assert!(s["never_reached"]
        .as_array()
        .unwrap()
        .contains(&"inv_sqrt".into()));
    assert!(s["domains_never_reached"]
        .as_array()
        .unwrap()
        .contains(&"sqrt(negative)".into()));
    assert_eq!(s["traced_pixels"], 40 * 30);
    let costs = s["costs"].as_array().unwrap();
    let names: Vec<&str> = costs
        .iter()
        .map(|c| c["implementation"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["ref-f64", "ref-f32", "ref-f316"]);
    for c in costs {
        assert_eq!(c["pixels"], 320 * 240);
        assert!(c["per_pixel_s"].as_f64().unwrap() > 0.0, "{c}");
    }
    // Without the jack kind in the night, no Jack leg and no refusal.
    assert_eq!(s["unsupported"], serde_json::json!([]));
    assert!(s["jack"].is_null(), "{s}");
    let f32 = report["comparisons"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["scope"] == "scene rtdemo" && c["b"] == "ref-f32")
        .expect("ref-f32 against ref-f64 on rtdemo");
    assert_eq!(f32["policy"], "error figures");
    assert_eq!(f32["cases"], 320 * 240);
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(html.contains("<section id=scenes>") && html.contains("rtdemo"));
}

/// The generated Jack program of the scene with carved shapes, through
/// its bindings: ops, SDF, every pixel and `Main.main`'s whole screen
/// bit-exact with ref-f316, its cost figures (every pixel measured, the
/// whole program timed), its outcomes, and the scene's pictures.
#[test]
fn the_scene_step_compares_the_generated_jack_program_and_shows_its_pictures() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("nightly");
    // A relative path, from the package's folder where the test runs.
    let o = night_of("ref-f316,jack", &out, "../vectors/scenes/tests/carved.json");
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let report = report(&out);
    assert_eq!(report["problems"], serde_json::json!([]), "{report}");
    let rows: Vec<&serde_json::Value> = report["comparisons"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|c| {
            c["b"]
                .as_str()
                .is_some_and(|b| b.starts_with("jack-generated"))
        })
        .collect();
    let levels: Vec<&str> = rows.iter().map(|c| c["level"].as_str().unwrap()).collect();
    assert_eq!(levels, ["ops", "sdf", "pixels", "screen"]);
    for c in &rows {
        assert_eq!(
            (&c["a"], &c["policy"]),
            (&"ref-f316".into(), &"bit-exact".into())
        );
        assert_eq!(c["divergences"], 0, "{c}");
        assert!(c["cases"].as_u64().unwrap() > 100, "{c}");
    }
    assert_eq!(
        rows[2]["cases"],
        160 * 96,
        "every pixel of the 160x96 scene"
    );
    assert_eq!(rows[3]["cases"], 512 * 256, "every pixel of the screen");
    let s = &report["scenes"][0];
    let jack = &s["jack"];
    assert_eq!(
        (&jack["step"], &jack["pixels_measured"]),
        (&1.into(), &(160 * 96).into())
    );
    // docs/scenes.md's figure over every pixel is 287 411.
    let mean = jack["mean"].as_f64().unwrap();
    assert!((200_000.0..400_000.0).contains(&mean), "{jack}");
    assert!(jack["desktop_s"].as_f64().unwrap() > 0.0);
    assert!(jack["main_s"].as_f64().unwrap() > 0.0, "{jack}");
    assert!(s["cpu_s"].as_f64().unwrap() > 0.0, "{s}");
    let outcomes: Vec<String> = s["outcomes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|o| format!("{} {} {}", o["implementation"], o["level"], o["cases"]))
        .collect();
    assert!(
        outcomes.contains(&"\"jack-generated\" \"pixels\" 15360".to_string()),
        "{outcomes:?}"
    );
    assert!(jack["rom_shared"].as_u64().unwrap() < jack["rom_words"].as_u64().unwrap());
    let pictures: Vec<&str> = s["pictures"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["image"].as_str().unwrap())
        .collect();
    for p in &pictures {
        assert!(out.join(p).is_file(), "{p}");
    }
    for want in [
        "images/scene-carved-ref-f316.png",
        "images/scene-carved-jack-generated.png",
        "images/scene-carved-jack-generated-vs-ref-f316.png",
        "images/scene-carved-jack-generated-cost.png",
        "images/scene-carved-jack-generated-main.png",
    ] {
        assert!(pictures.contains(&want), "{want} in {pictures:?}");
    }
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(
        html.contains("Generated Jack program")
            && html.contains("scene-carved-jack-generated-cost.png")
    );
}

fn report(out: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap()
}

#[test]
fn the_scene_step_compares_gpu_f316_with_ref_f316_bit_for_bit() {
    if std::env::var_os(gpu::SKIP_ENV).is_some() {
        gpu::report_skipped("the scene step on gpu-f316");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("nightly");
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("../vectors/scenes/tests/carved.json");
    let o = night_of("ref-f316,gpu-f316", &out, scene.to_str().unwrap());
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let report = report(&out);
    assert_eq!(report["problems"], serde_json::json!([]), "{report}");
    let row = |level: &str| {
        report["comparisons"]
            .as_array()
            .unwrap()
            .iter()
            .find(|c| c["scope"] == "scene carved" && c["level"] == level)
            .unwrap_or_else(|| panic!("no {level} row: {report}"))
            .clone()
    };
    let (pixels, sdf) = (row("pixels"), row("sdf"));
    for c in [&pixels, &sdf] {
        assert_eq!(
            (&c["a"], &c["b"]),
            (&"ref-f316".into(), &"gpu-f316".into()),
            "{c}"
        );
        assert_eq!(c["policy"], "bit-exact", "{c}");
        assert_eq!(c["divergences"], 0, "{c}");
    }
    assert_eq!(pixels["cases"], 160 * 96, "every pixel of the 160x96 scene");
    assert!(
        sdf["cases"].as_u64().unwrap() > 512,
        "uniform and derived points: {sdf}"
    );
    let costs = report["scenes"][0]["costs"].to_string();
    assert!(costs.contains("gpu-f316"), "{costs}");
}

#[test]
fn a_bad_scene_file_fails_the_night_naming_the_field() {
    let dir = tempfile::tempdir().unwrap();
    let shipped = Path::new(env!("CARGO_MANIFEST_DIR")).join("../vectors/scenes/rtdemo.json");
    let text_of = std::fs::read_to_string(shipped).unwrap();
    let bad = text_of.replacen("\"radius\": 1.0", "\"radius\": -1.0", 1);
    assert_ne!(bad, text_of, "the shipped rtdemo has a sphere of radius 1");
    let file = dir.path().join("bad.json");
    std::fs::write(&file, bad).unwrap();
    let out = dir.path().join("nightly");
    let o = night(&out, file.to_str().unwrap());
    assert_eq!(o.status.code(), Some(3), "not compared: {}", text(&o));
    assert_says(&o, "failed: scene ");
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    let problems = report["problems"].to_string();
    assert!(
        problems.contains("radius: must be positive, is -1"),
        "{problems}"
    );
}

#[test]
fn an_unknown_scene_is_refused_before_the_run() {
    let dir = tempfile::tempdir().unwrap();
    let o = night(&dir.path().join("nightly"), "no-such-scene");
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert_says(
        &o,
        "neither a shipped scene (rtdemo, sdf-engine, seed, toon) nor a file",
    );
    assert!(!text(&o).contains("nightly: open"), "{}", text(&o));
}
