//! The seed scene's parameter files are checked before a render: every
//! run is bounded and a camera without a direction is an error (issue 20,
//! findings 2 and 8).

use reference::{RefImpl, Reference, Scene, Settings};

fn load(name: &str, text: &str) -> Result<Scene, String> {
    let path =
        std::env::temp_dir().join(format!("scene-limits-{}-{name}.json", std::process::id()));
    std::fs::write(&path, text).unwrap();
    let r = Scene::from_file(&path).map_err(|e| e.to_string());
    std::fs::remove_file(&path).unwrap();
    r
}

#[test]
fn unbounded_marches_are_refused() {
    let e = load("a", r#"{"march":{"precision":0.0,"view_steps":100000}}"#).unwrap_err();
    assert!(
        e.contains("march.view_steps") && e.contains("1..=1024"),
        "{e}"
    );
    let e = load("b", r#"{"march":{"view_steps":4294967295}}"#).unwrap_err();
    assert!(e.contains("march.view_steps"), "{e}");
    let e = load("c", r#"{"march":{"shadow_steps":0}}"#).unwrap_err();
    assert!(e.contains("march.shadow_steps"), "{e}");
    assert!(load("d", r#"{"march":{"view_steps":1024}}"#).is_ok());
}

#[test]
fn a_file_that_is_not_an_object_is_refused() {
    for text in ["[]", "3", "\"seed\""] {
        let e = load("e", text).unwrap_err();
        assert!(e.contains("a scene is a JSON object"), "{text}: {e}");
    }
}

/// `{}` sets nothing (the seed scene needs no file); a NaN or a file cut
/// short is a JSON error at its line, not the first field the parameters
/// do not know.
#[test]
fn an_empty_object_and_broken_json_are_refused_where_they_are() {
    let e = load("g", "{}").unwrap_err();
    assert!(e.contains("sets no field"), "{e}");
    let e = load("h", "{\"version\": 1,\n \"radius\": NaN}").unwrap_err();
    assert!(e.contains("line 2"), "{e}");
    assert!(!e.contains("unknown field"), "{e}");
    let e = load("i", "{\"version\": 1, \"nodes\": [").unwrap_err();
    assert!(e.contains("EOF") && !e.contains("unknown field"), "{e}");
}

#[test]
fn a_camera_without_direction_is_refused() {
    let e = load("f", r#"{"camera":{"position":[0,0,0],"look_at":[0,0,0]}}"#).unwrap_err();
    assert!(e.contains("camera.look_at"), "{e}");
    let e = load("j", r#"{"camera":{"up":[0,1.5,4]}}"#).unwrap_err();
    assert!(e.contains("camera.up"), "{e}");
    let mut s = Scene::default();
    s.camera.look_at = s.camera.position;
    assert!(Reference::new(RefImpl::F316, &s, Settings::default()).is_err());
}

/// Every error of a scene file names the file, and the field where one is
/// at fault: the checks' errors named no file (issue 35 item 11).
#[test]
fn every_error_names_the_file_and_the_field() {
    let dir = std::env::temp_dir().join(format!("scene-limits-files-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("my-scene.json");
    let shown = path.display().to_string();
    for (text, field) in [
        (
            r#"{"march":{"view_steps":100000}}"#,
            Some("march.view_steps"),
        ),
        (
            r#"{"camera":{"position":[0,0,0],"look_at":[0,0,0]}}"#,
            Some("camera.look_at"),
        ),
        (
            r#"{"camera":{"position":[0,1e300,0],"look_at":[0,0,0],"up":[0,1e300,0]}}"#,
            Some("camera.up"),
        ),
        (r#"{"torus":{"tube":0.5}}"#, Some("tube")),
        ("{\"radius\": NaN}", None),
        ("[]", None),
        ("{}", None),
    ] {
        std::fs::write(&path, text).unwrap();
        let e = Scene::from_file(&path).unwrap_err().to_string();
        assert!(e.contains(&shown), "{text}: {e}");
        if let Some(field) = field {
            assert!(e.contains(field), "{text}: {e}");
        }
    }
    let e = Scene::from_file(&dir.join("missing.json"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("missing.json"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A huge value is shown as `1e300`, not its 301 digits (issue 35 item 11).
#[test]
fn a_huge_value_is_shown_compactly() {
    let e = load(
        "k",
        r#"{"camera":{"position":[0,1e300,0],"look_at":[0,0,0],"up":[0,1e300,0]}}"#,
    )
    .unwrap_err();
    assert!(e.contains("`camera.up` = 1e300: "), "{e}");
    assert!(!e.contains("000000"), "{e}");
}
