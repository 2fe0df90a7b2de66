//! Command-line definition (stable: scripts and reports rely on it) and
//! dispatch to one module per subcommand under `commands/`.

use crate::commands;
use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// Differential verification harness for the Float316 raymarcher ports.
#[derive(Debug, Parser)]
#[command(name = "harness", version, about)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Render the 512x256 dithered image with one implementation.
    Render(commands::render::RenderArgs),
    /// Jack toolchain: compile Jack to VM code, run a VM program.
    #[command(subcommand)]
    Jack(commands::jack::JackCommand),
}

/// Run a parsed command line; the exit code follows the design's contract
/// (errors of usage or input are reported by the caller as exit 2).
pub fn run(cli: Cli) -> anyhow::Result<ExitCode> {
    match cli.command {
        Command::Render(args) => commands::render::run(args),
        Command::Jack(cmd) => commands::jack::run(cmd),
    }
}
