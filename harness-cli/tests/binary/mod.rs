//! Running the `harness` binary from the integration tests.

use std::path::Path;
use std::process::{Command, Output};

/// The harness run with `args` in the test's working directory.
#[allow(dead_code)] // not every test crate that includes this module runs it so
pub fn harness(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_harness"))
        .args(args)
        .output()
        .expect("the binary runs")
}

/// The harness run with `args` in `dir`, where a project file lies.
#[allow(dead_code)] // not every test crate that includes this module runs it so
pub fn harness_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_harness"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the binary runs")
}

/// A run's standard output and error, as text.
pub fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}
