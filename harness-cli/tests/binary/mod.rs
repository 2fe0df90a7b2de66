//! Running the `harness` binary from the integration tests.

use std::path::Path;
use std::process::{Command, Output};

/// The harness run with `args` in the test's working directory.
pub fn harness(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_harness"))
        .args(args)
        .output()
        .expect("the binary runs")
}

/// The harness run with `args` in `dir`, where a project file lies.
pub fn harness_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_harness"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the binary runs")
}

/// Fail the test, showing the whole run, unless its output says `needle`.
#[track_caller]
pub fn assert_says(o: &Output, needle: &str) {
    let t = text(o);
    assert!(
        t.contains(needle),
        "expected {needle:?} in the output:\n{t}"
    );
}

/// Fail the test, showing the whole run, unless it exited with `code`,
/// without a panic, and its output says every one of `names`.
#[track_caller]
pub fn assert_status(o: &Output, code: i32, names: &[&str]) {
    let t = text(o);
    assert_eq!(o.status.code(), Some(code), "{t}");
    assert!(!t.contains("panicked"), "{t}");
    for name in names {
        assert!(t.contains(name), "`{name}` is not named: {t}");
    }
}

/// A run's standard output and error, as text.
pub fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}
