//! `scripts/gpu-check.sh`, the prepared check of the GPU legs, so that it
//! cannot rot: its reduced form (`--quick`) runs on this machine's adapter
//! (lavapipe in CI, hence `--allow-software`) with the binary under test,
//! and must pass with a summary that names the adapter and holds every
//! step's verdict and the whole-image times; on a software adapter it
//! refuses to run without `--allow-software`. Its gates are checked with a
//! stand-in for the binary whose steps fail on request (no GPU needed): a
//! failing diff, scenes step or bench fails the check, and a bench without
//! the GPU legs' rows too. Set F316_SKIP_GPU to skip the GPU runs where
//! there is no adapter.

#![cfg(target_os = "linux")]

use std::os::unix::fs::PermissionsExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn script() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../scripts/gpu-check.sh")
}

/// The check with `args` and the binary `bin`.
fn gpu_check(bin: &Path, args: &[&str]) -> Output {
    Command::new("bash")
        .arg(script())
        .args(args)
        .env("HARNESS_BIN", bin)
        .env_remove("GPU_CHECK_ALLOW_SOFTWARE")
        .env_remove("GPU_CHECK_QUICK")
        .output()
        .expect("bash runs")
}

fn log(o: &Output, out: &Path) -> String {
    format!(
        "{}{}\n--- summary.md ---\n{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr),
        std::fs::read_to_string(out.join("summary.md")).unwrap_or_default()
    )
}

/// Whether the run found no adapter where F316_SKIP_GPU allows it.
fn skipped(o: &Output, out: &Path) -> bool {
    let summary = std::fs::read_to_string(out.join("summary.md")).unwrap_or_default();
    if summary.contains("**no GPU adapter**") && std::env::var_os(gpu::SKIP_ENV).is_some() {
        gpu::report_skipped(&log(o, out));
        return true;
    }
    false
}

#[test]
fn the_quick_check_passes_here_and_reports_adapter_verdicts_and_times() {
    let out = tempfile::tempdir().unwrap();
    let dir = out.path().join("report");
    let bin = Path::new(env!("CARGO_BIN_EXE_harness"));
    let o = gpu_check(bin, &["--allow-software", "--quick", dir.to_str().unwrap()]);
    if skipped(&o, &dir) {
        return;
    }
    let text = log(&o, &dir);
    assert_eq!(o.status.code(), Some(0), "{text}");
    let summary = std::fs::read_to_string(dir.join("summary.md")).unwrap();
    assert!(summary.contains("\nadapter: "), "{summary}");
    for step in [
        "diff-ref-f316-gpu-f316",
        "diff-ref-f32-gpu-f32",
        "diff-ref-f64-gpu-f32",
        "diff-ref-f32+fma-gpu-f32",
        "shaders",
        "scenes",
        "bench",
    ] {
        assert!(
            summary.contains(&format!("- `{step}`: ok")),
            "{step}: {summary}"
        );
    }
    // gpu-f316 bit for bit at each level the quick form runs.
    let f316 = std::fs::read_to_string(dir.join("logs/diff-ref-f316-gpu-f316.log")).unwrap();
    assert_eq!(f316.matches("no divergence on").count(), 3, "{f316}");
    // The reading of gpu-f32 against ref-f32 and ref-f32+fma, per level.
    assert!(summary.contains("| sdf | "), "{summary}");
    assert!(summary.contains("| pixels | "), "{summary}");
    assert!(!summary.contains("not measured"), "{summary}");
    // The whole-image times of both GPU legs, and the scene's.
    for leg in ["gpu-f32 ", "gpu-f316 "] {
        assert!(
            summary.lines().any(|l| l.starts_with(leg)),
            "{leg}: {summary}"
        );
    }
    assert!(summary.contains("| rtdemo | gpu-f316 |"), "{summary}");
    assert!(dir.join("scenes/index.html").is_file());
    assert!(summary.contains("**passed**"), "{summary}");
}

#[test]
fn a_software_adapter_is_refused_without_allow_software() {
    let out = tempfile::tempdir().unwrap();
    let bin = Path::new(env!("CARGO_BIN_EXE_harness"));
    let o = gpu_check(bin, &["--quick", out.path().to_str().unwrap()]);
    if skipped(&o, out.path()) {
        return;
    }
    let summary = std::fs::read_to_string(out.path().join("summary.md")).unwrap();
    let adapter = summary
        .lines()
        .find_map(|l| l.strip_prefix("adapter: "))
        .unwrap_or_else(|| panic!("no adapter line: {}", log(&o, out.path())));
    if adapter.ends_with("[software]") {
        assert_eq!(o.status.code(), Some(3), "{}", log(&o, out.path()));
        assert!(summary.contains("**refused**"), "{summary}");
        assert!(!summary.contains("diff-ref-f316"), "ran on: {summary}");
    } else {
        eprintln!("a hardware adapter ({adapter}): the refusal is not tested here");
    }
}

/// A stand-in for the binary: `cast` names a hardware adapter; `bench`
/// prints the rows of both GPU legs; the subcommand named by `fail` exits
/// 1, and `bench` prints no rows when `fail` is `bench-rows`.
fn stand_in(dir: &Path, fail: &str) -> PathBuf {
    let path = dir.join("harness");
    std::fs::write(
        &path,
        format!(
            r#"#!/bin/sh
[ "$1" = --cast ] && shift 2
case "$1" in
  cast) echo "gpu-f32 runs on Stand-in GPU (Vulkan, DiscreteGpu, driver stand-in 1)"
        echo "gpu-f316 runs on Stand-in GPU (Vulkan, DiscreteGpu, driver stand-in 1)" ;;
  bench) [ {fail} = bench-rows ] || printf 'implementation x\ngpu-f32 1\ngpu-f316 1\n' ;;
esac
[ "$1" = {fail} ] && exit 1
exit 0
"#
        ),
    )
    .unwrap();
    std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o755)).unwrap();
    path
}

#[test]
fn a_failing_step_fails_the_check_and_is_named() {
    for (fail, named) in [
        ("diff", "- `diff-ref-f316-gpu-f316`: **failed (exit 1)**"),
        ("nightly", "- `scenes`: **failed (exit 1)**"),
        ("bench", "- `bench`: **failed (exit 1)**"),
        ("bench-rows", "**bench has no row for gpu-f32**"),
    ] {
        let tmp = tempfile::tempdir().unwrap();
        let bin = stand_in(tmp.path(), fail);
        let out = tmp.path().join("out");
        let o = gpu_check(&bin, &["--quick", out.to_str().unwrap()]);
        let text = log(&o, &out);
        assert_eq!(o.status.code(), Some(1), "{fail}: {text}");
        assert!(text.contains(named), "{fail}: {text}");
        assert!(text.contains("**FAILED**"), "{fail}: {text}");
    }
    // The same stand-in with nothing failing passes: the failures above are
    // the steps', not the stand-in's.
    let tmp = tempfile::tempdir().unwrap();
    let bin = stand_in(tmp.path(), "none");
    let out = tmp.path().join("out");
    let o = gpu_check(&bin, &["--quick", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", log(&o, &out));
}
