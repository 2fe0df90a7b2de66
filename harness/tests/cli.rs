//! The command-line contract of diff, localize, selftest and bench: exit codes,
//! repro files that reproduce, errors that name the field.

use std::path::Path;
use std::process::{Command, Output};

fn harness(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_harness"))
        .args(args)
        .output()
        .expect("the binary runs")
}

fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

fn ops_small() -> String {
    vectors::sets_dir()
        .join("ops-small.json")
        .display()
        .to_string()
}

#[test]
fn a_bad_vector_file_is_an_input_error_naming_the_field() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("bad.json");
    std::fs::write(
        &file,
        r#"{"format_version":1,"name":"bad","level":"ops","vectors":[{"category":"c","op":"sqrt","a":[0,1]}]}"#,
    )
    .unwrap();
    let o = harness(&[
        "diff",
        "ref-f316",
        "ref-f316",
        "--vectors",
        file.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("bad.json: vectors[0].a: expected [s,e,m]"),
        "{}",
        text(&o)
    );
    let o = harness(&["diff", "ref-f99", "ref-f316"]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("unknown implementation `ref-f99`"),
        "{}",
        text(&o)
    );
}

#[test]
fn a_divergence_exits_1_and_its_repro_file_reproduces_it() {
    let dir = tempfile::tempdir().unwrap();
    let report = dir.path().join("report");
    let o = harness(&[
        "diff",
        "ref-f316+sqrt-floor-div",
        "ref-f316",
        "--vectors",
        &ops_small(),
        "--report",
        report.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    let out = text(&o);
    assert!(
        out.contains("localize: harness localize ref-f316+sqrt-floor-div ref-f316 --op sqrt"),
        "{out}"
    );
    assert!(report.join("report.json").exists());
    let repro = std::fs::read_dir(report.join("repro"))
        .unwrap()
        .next()
        .unwrap()
        .unwrap()
        .path();
    assert_eq!(std::fs::read_to_string(&repro).unwrap().lines().count(), 1);
    let again = harness(&[
        "diff",
        "ref-f316+sqrt-floor-div",
        "ref-f316",
        "--vectors",
        repro.to_str().unwrap(),
    ]);
    assert_eq!(again.status.code(), Some(1), "{}", text(&again));
    let clean = harness(&[
        "diff",
        "ref-f316",
        "ref-f316",
        "--vectors",
        repro.to_str().unwrap(),
    ]);
    assert_eq!(clean.status.code(), Some(0), "{}", text(&clean));
}

#[test]
fn localize_prints_the_first_divergent_operation() {
    let o = harness(&[
        "localize",
        "ref-f316+sqrt-floor-div",
        "ref-f316",
        "--op",
        "sqrt",
        "--a",
        "0,120,15576",
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    assert!(
        text(&o).contains("origin: sqrt((0,120,15576)"),
        "{}",
        text(&o)
    );
    let same = harness(&["localize", "ref-f316", "ref-f316", "--pixel", "312,87"]);
    assert_eq!(same.status.code(), Some(0), "{}", text(&same));
    let bad = harness(&["localize", "ref-f316", "ref-f316", "--pixel", "600,1"]);
    assert_eq!(bad.status.code(), Some(2), "{}", text(&bad));
    // A float implementation has no Float316 operations to compare.
    let float = harness(&["localize", "ref-f316", "ref-f64", "--pixel", "312,87"]);
    assert_eq!(float.status.code(), Some(2), "{}", text(&float));
    assert!(
        text(&float).contains("ref-f64 computes with f64"),
        "{}",
        text(&float)
    );
    assert!(Path::new(env!("CARGO_BIN_EXE_harness")).exists());
}

#[test]
fn bench_prints_and_writes_the_speed_and_error_table() {
    let dir = tempfile::tempdir().unwrap();
    let json = dir.path().join("bench.json");
    let o = harness(&[
        "bench",
        "ref-f64",
        "ref-f32",
        "--json",
        json.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", text(&o));
    assert!(text(&o).contains("ref-f32"), "{}", text(&o));
    let rows: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let rows = rows.as_array().unwrap();
    assert_eq!(rows.len(), 2);
    assert_eq!(rows[0]["implementation"], "ref-f64");
    assert_eq!(rows[0]["pixel_flips"], 0);
    assert_eq!(rows[1]["pixels"], 131072);
}
