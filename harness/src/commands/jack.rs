//! `harness jack`: placeholder until the Jack toolchain lands.

/// Jack subcommands.
#[derive(Debug, clap::Subcommand)]
pub enum JackCommand {}

/// Run a Jack subcommand.
pub fn run(cmd: JackCommand) -> anyhow::Result<std::process::ExitCode> {
    match cmd {}
}
