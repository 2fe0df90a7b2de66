//! An implementation declared only in a project file is used by every
//! command, with no change to the harness's code: `harness.toml` in the
//! current directory declares a clean copy of ref-f316 (`my-port`), one
//! with a one-operation fault (`my-bad`: mul keeps the low product) and an
//! f32 one (`my-f32`); each is found by cast, diff, localize, check, bench
//! and nightly, in the group its number type decides.

use crate::binary;

use binary::{assert_says, assert_status, harness_in, text};
use std::path::{Path, PathBuf};
use std::process::Output;

const PROJECT: &str = r#"
[impl.my-port]
kind = "reference"
numbers = "float316"

[impl.my-bad]
kind = "reference"
numbers = "float316"
variants = ["mul-keep-low"]

[impl.my-f32]
kind = "reference"
numbers = "f32"
"#;

fn project() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("harness.toml"), PROJECT).unwrap();
    dir
}

/// The entry `name` of `harness cast --json`'s list.
fn entry(list: &serde_json::Value, name: &str) -> serde_json::Value {
    list.as_array()
        .unwrap()
        .iter()
        .find(|e| e["name"] == name)
        .unwrap_or_else(|| panic!("{name} in {list}"))
        .clone()
}

#[test]
fn cast_lists_the_declared_implementations_with_their_group() {
    let dir = project();
    let o = harness_in(dir.path(), &["cast", "--json"]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let list: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let find = |name: &str| entry(&list, name);
    let port = find("my-port");
    assert_eq!(port["kind"], "reference");
    assert_eq!(port["numbers"], "float316");
    assert_eq!(port["bit_exact_group"], true);
    assert_eq!(port["available"], true);
    assert_eq!(port["origin"], "harness.toml:2");
    assert_eq!(find("my-f32")["bit_exact_group"], false);
    assert_eq!(find("ref-f64")["oracle"], true);
    // --cast names another file; a malformed one names file, line, field.
    let bad = dir.path().join("bad.toml");
    std::fs::write(&bad, "[impl.x]\nkind = \"reference\"\nnumbers = 64\n").unwrap();
    let o = harness_in(dir.path(), &["--cast", "bad.toml", "cast"]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert_says(
        &o,
        "bad.toml:3:11: impl.x.numbers: expected a string, found integer",
    );
    // Under check, an unreadable project file is undecidable.
    let o = harness_in(
        dir.path(),
        &[
            "--cast",
            "bad.toml",
            "check",
            "--no-divergence",
            "ref-f316",
            "my-port",
        ],
    );
    assert_eq!(o.status.code(), Some(125), "{}", text(&o));
}

#[test]
fn diff_localize_and_check_use_a_declared_implementation() {
    let dir = project();
    let d = dir.path();
    let o = harness_in(d, &["diff", "ref-f316", "my-port", "--level", "ops"]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let o = harness_in(d, &["diff", "ref-f316", "my-bad", "--level", "ops"]);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    let out = text(&o);
    let command = out
        .lines()
        .find_map(|l| l.trim().strip_prefix("localize: harness "))
        .unwrap_or_else(|| panic!("a localize command in {out}"));
    assert!(
        command.starts_with("localize ref-f316 my-bad --op mul "),
        "{command}"
    );
    let args: Vec<&str> = command.split_whitespace().collect();
    let o = harness_in(d, &args);
    assert_status(&o, 1, &["origin: mul("]);
    let o = harness_in(
        d,
        &[
            "check",
            "--no-divergence",
            "ref-f316",
            "my-port",
            "--level",
            "ops",
        ],
    );
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let o = harness_in(
        d,
        &[
            "check",
            "--no-divergence",
            "ref-f316",
            "my-bad",
            "--level",
            "ops",
        ],
    );
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    assert!(
        text(&o).starts_with("bad: ref-f316 and my-bad diverge"),
        "{}",
        text(&o)
    );
    // A variant a declared entry does not take is refused.
    let o = harness_in(
        d,
        &["diff", "ref-f316", "my-f32+newton-3", "--level", "ops"],
    );
    assert_status(&o, 2, &["my-f32 has no variant or fault `newton-3`"]);
}

#[test]
fn bench_renders_a_declared_implementation() {
    let dir = project();
    let o = harness_in(dir.path(), &["bench", "my-f32"]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let row = String::from_utf8_lossy(&o.stdout)
        .lines()
        .find(|l| l.starts_with("my-f32 "))
        .map(String::from)
        .unwrap_or_else(|| panic!("a my-f32 row in {}", text(&o)));
    // ref-f32 gives the same dithered image as ref-f64: 0 flips.
    assert!(row.trim_end().ends_with(" 0"), "{row}");
}

/// The nightly's levels, renders and pairs over the implementations
/// `impls` (comma-separated) of the project in `dir`; returns its output
/// and its report directory.
fn nightly(dir: &Path, impls: &str) -> (Output, PathBuf) {
    let out = dir.join("reports/nightly");
    let o = harness_in(
        dir,
        &[
            "nightly",
            "--impls",
            impls,
            "--steps",
            "levels,renders,pairs",
            "--out",
            out.to_str().unwrap(),
        ],
    );
    (o, out)
}

#[test]
fn the_nightly_compares_declared_implementations_in_their_group_and_fails_on_a_bad_image() {
    let dir = project();
    let (o, out) = nightly(dir.path(), "my-port,my-bad,my-f32");
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    let comparison = |level: &str, b: &str| {
        report["comparisons"]
            .as_array()
            .unwrap()
            .iter()
            .find(|c| c["level"] == level && c["b"] == b)
            .unwrap_or_else(|| panic!("a {level} comparison with {b}"))
            .clone()
    };
    let port = comparison("ops", "my-port");
    assert_eq!(
        (port["a"].as_str(), port["policy"].as_str()),
        (Some("ref-f316"), Some("bit-exact"))
    );
    assert_eq!(port["divergences"], 0);
    let bad = comparison("ops", "my-bad");
    assert!(bad["divergences"].as_u64().unwrap() > 0, "{bad}");
    // The float group is compared with the oracle by error figures (the
    // subject first, the oracle second).
    let f32 = report["comparisons"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["level"] == "sdf" && c["a"] == "my-f32")
        .unwrap_or_else(|| panic!("an sdf comparison of my-f32"))
        .clone();
    assert_eq!(
        (f32["b"].as_str(), f32["policy"].as_str()),
        (Some("ref-f64"), Some("error figures"))
    );
    let pair = |b: &str| {
        report["image_pairs"]
            .as_array()
            .unwrap()
            .iter()
            .find(|p| p["a"] == "ref-f316" && p["b"] == b)
            .unwrap_or_else(|| panic!("an image pair ref-f316 / {b}"))
            .clone()
    };
    assert_eq!(pair("my-port")["bit_exact"], true);
    assert_eq!(pair("my-port")["differing_pixels"], 0);
    let bad = pair("my-bad");
    assert_eq!(bad["bit_exact"], true);
    assert!(bad["differing_shades"].as_u64().unwrap() > 0, "{bad}");
    assert_eq!(pair("my-f32")["bit_exact"], false);
    assert_eq!(pair("ref-f316+newton-3")["bit_exact"], false);
    assert!(bad["beyond_policy"]
        .as_str()
        .unwrap()
        .contains("between two bit-exact renders"));
    assert!(pair("my-port")["beyond_policy"].is_null());
    let line = String::from_utf8_lossy(&o.stdout);
    assert!(
        line.contains("diverged: ref-f316 vs my-bad image: ")
            && !line.contains("diverged: ref-f316 vs my-port"),
        "{line}"
    );
}

#[test]
fn the_nightly_passes_with_a_clean_declared_implementation() {
    let dir = project();
    let (o, _) = nightly(dir.path(), "my-port");
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let line = String::from_utf8_lossy(&o.stdout);
    assert!(
        line.contains("nightly: passed: ") && line.contains(" 0 beyond policy, 0 not compared"),
        "{line}"
    );
}

/// Durations from the user are refused out of (0, one day] with the field
/// named, instead of panicking in `Duration::from_secs_f64` (1e300) or in a
/// runner thread's multiply (1e19), and a shader's `timeout_s` of u64::MAX
/// no longer panics inside `harness cast`.
#[test]
fn out_of_range_durations_are_refused_with_the_field_named() {
    let dir = tempfile::tempdir().unwrap();
    for (n, seconds) in ["1e300", "1e19", "86401"].iter().enumerate() {
        let file = dir.path().join(format!("pipe{n}.toml"));
        std::fs::write(
            &file,
            format!(
                "[impl.p]\nkind = \"pipe\"\nnumbers = \"f64\"\nlevels = [\"ops\"]\n\
                 command = \"python3\"\nwatchdog_s = {seconds}\n"
            ),
        )
        .unwrap();
        let o = harness_in(dir.path(), &["--cast", file.to_str().unwrap(), "cast"]);
        assert_eq!(o.status.code(), Some(2), "{seconds}: {}", text(&o));
        assert_says(
            &o,
            "impl.p.watchdog_s: expected a positive number of seconds, at most 86400",
        );
    }
    let shader = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/shaders/seed.glsl");
    let file = dir.path().join("shader.toml");
    std::fs::write(
        &file,
        format!(
            "[impl.s]\nkind = \"shader\"\npath = \"{shader}\"\nshade = \"red\"\n\
             timeout_s = 18446744073709551615\n"
        ),
    )
    .unwrap();
    let o = harness_in(dir.path(), &["--cast", file.to_str().unwrap(), "cast"]);
    assert_status(
        &o,
        2,
        &["impl.s.timeout_s: at most 86400 seconds (one day)"],
    );
}

/// A shader whose compilation outlasts its limit fails its entry, naming
/// the file and the limit, and the rest of the cast is listed: a driver
/// compiling for minutes hung `harness cast` (issue 35 item 5). The limit,
/// 120 s or the entry's larger `timeout_s`, is made tiny here through
/// HARNESS_SHADER_COMPILE_S; a step that came back after it is past it.
#[test]
fn a_shader_compiling_past_its_limit_fails_its_entry_and_the_cast_goes_on() {
    let dir = project();
    let shader = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/shaders/seed.glsl");
    std::fs::write(
        dir.path().join("harness.toml"),
        format!(
            "{PROJECT}\n[impl.slow]\nkind = \"shader\"\npath = \"{shader}\"\nshade = \"red\"\n"
        ),
    )
    .unwrap();
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_harness"))
        .args(["cast", "--json"])
        .current_dir(dir.path())
        .env("HARNESS_SHADER_COMPILE_S", "0.000001")
        .output()
        .expect("the binary runs");
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let list: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let find = |name: &str| entry(&list, name);
    let slow = find("slow");
    assert_eq!(slow["available"], false, "{slow}");
    let why = slow["unavailable"].as_str().unwrap();
    assert!(
        why.contains("seed.glsl: the shader did not compile within its limit of 0.000001 s"),
        "{why}"
    );
    assert_eq!(find("my-port")["available"], true);
    assert_eq!(find("ref-f64")["available"], true);
}
