//! The `harness` command line: a thin layer over the `harness` library.

use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = match harness::cli::Cli::try_parse() {
        Ok(cli) => cli,
        // `check` runs under `git bisect run`: bad input there means
        // "cannot decide" (125), not a usage error.
        Err(err) if err.use_stderr() && subcommand().as_deref() == Some("check") => {
            eprintln!("{err}");
            println!("skip: bad arguments to check");
            return ExitCode::from(harness::commands::check::UNDECIDABLE);
        }
        Err(err) => err.exit(),
    };
    match harness::cli::run(cli) {
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
