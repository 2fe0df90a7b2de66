//! `harness check` exits 0, 1 or 125 as `git bisect run` expects.

use std::process::Command;

fn check(args: &[&str]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_harness"))
        .arg("check")
        .args(args)
        .env("WGPU_BACKEND", "metal") // no adapter on this OS: the GPU is unavailable
        .output()
        .expect("harness runs");
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    assert_eq!(stdout.lines().count(), 1, "one line expected: {stdout}");
    (out.status.code().expect("exit code"), stdout)
}

#[test]
fn clean_pair_is_good() {
    let (code, line) = check(&["--no-divergence", "ref-f316", "ref-f316", "--level", "ops"]);
    assert_eq!(code, 0, "{line}");
    assert!(line.starts_with("good: "), "{line}");
}

#[test]
fn injected_fault_is_bad() {
    let (code, line) = check(&[
        "--no-divergence",
        "ref-f316",
        "ref-f316+sqrt-floor-div",
        "--level",
        "ops",
    ]);
    assert_eq!(code, 1, "{line}");
    assert!(
        line.starts_with("bad: ") && line.contains("diverge"),
        "{line}"
    );
}

#[test]
fn unavailable_implementation_is_undecidable() {
    let (code, line) = check(&["--no-divergence", "ref-f316", "gpu-f316", "--level", "ops"]);
    assert_eq!(code, 125, "{line}");
    assert!(
        line.starts_with("skip: ") && line.contains("gpu-f316"),
        "{line}"
    );
}

#[test]
fn bad_input_is_undecidable() {
    assert_eq!(
        check(&["--no-divergence", "ref-f316", "ref-f316+no-such-fault"]).0,
        125
    );
    assert_eq!(check(&["--max-error", "ref-f32", "small"]).0, 125);
    assert_eq!(check(&["--max-error", "ref-f32"]).0, 125);
    assert_eq!(check(&[]).0, 125);
}

#[test]
fn error_threshold_decides() {
    // ref-f316 differs from ref-f64 in a few hundred dithered pixels.
    assert_eq!(
        check(&["--max-error", "ref-f316", "100000", "--metric", "flips"]).0,
        0
    );
    let (code, line) = check(&["--max-error", "ref-f316", "10", "--metric", "flips"]);
    assert_eq!(code, 1, "{line}");
}
