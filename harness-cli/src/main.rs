//! The `harness` command line: a thin layer over the `harness` library.

use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    // Before any thread exists: setting the environment is only sound then.
    #[cfg(target_os = "linux")]
    runtime_dir::give_the_driver_one();
    let cli = match harness_cli::cli::Cli::try_parse() {
        Ok(cli) => cli,
        // `check` runs under `git bisect run`: bad input there means
        // "cannot decide" (125), not a usage error.
        Err(err) if err.use_stderr() && subcommand().as_deref() == Some("check") => {
            eprintln!("{err}");
            println!("skip: bad arguments to check");
            return ExitCode::from(harness_cli::commands::check::UNDECIDABLE);
        }
        Err(err) => err.exit(),
    };
    match harness_cli::cli::run(cli) {
        Ok(code) => code,
        Err(err) => {
            eprintln!("error: {}", error_text(&err));
            ExitCode::from(2)
        }
    }
}

/// The subcommand named on the command line: the first argument that is
/// not a global option (`--cast FILE`).
fn subcommand() -> Option<String> {
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--cast" => {
                args.next();
            }
            a if a.starts_with("--cast=") => {}
            _ => return Some(arg),
        }
    }
    None
}

/// The error and its causes, joined by `: `; a cause whose text the error
/// before it already ends with (a message that prints its source) is not
/// repeated.
fn error_text(err: &anyhow::Error) -> String {
    let mut text = String::new();
    for cause in err.chain() {
        let message = cause.to_string();
        if text.ends_with(&message) {
            continue;
        }
        if !text.is_empty() {
            text.push_str(": ");
        }
        text.push_str(&message);
    }
    text
}

/// Mesa's Vulkan driver asks for `XDG_RUNTIME_DIR` at every device it
/// opens, and on a headless machine (none set) prints "error:
/// XDG_RUNTIME_DIR is invalid or not set in the environment." for each: an
/// error that is not the user's. The binary gives it a private one.
#[cfg(target_os = "linux")]
mod runtime_dir {
    use std::os::unix::fs::{DirBuilderExt, MetadataExt, PermissionsExt};
    use std::path::{Path, PathBuf};

    /// Set `XDG_RUNTIME_DIR` to `$TMPDIR/f316-harness-runtime-UID` (made
    /// with mode 0700) when it is unset or not an absolute path to a
    /// directory. A directory of that name that is not ours alone (another
    /// owner, other permissions, a link) is not used, and the variable is
    /// left as it was.
    pub fn give_the_driver_one() {
        let current = std::env::var_os("XDG_RUNTIME_DIR").map(PathBuf::from);
        if current.is_some_and(|d| d.is_absolute() && d.is_dir()) {
            return;
        }
        let uid = rustix::process::getuid().as_raw();
        let dir = std::env::temp_dir().join(format!("f316-harness-runtime-{uid}"));
        if ours_alone(&dir, uid) {
            std::env::set_var("XDG_RUNTIME_DIR", &dir);
        }
    }

    /// Whether `dir` is (or has just been made) a directory owned by `uid`
    /// that nobody else may enter.
    fn ours_alone(dir: &Path, uid: u32) -> bool {
        // An existing directory is checked below, like any other.
        let _ = std::fs::DirBuilder::new().mode(0o700).create(dir);
        std::fs::symlink_metadata(dir)
            .is_ok_and(|m| m.is_dir() && m.uid() == uid && m.permissions().mode() & 0o777 == 0o700)
    }
}
