//! Command-line definition (stable: scripts and reports rely on it) and
//! dispatch to one module per subcommand under `commands/`.

use crate::commands;
use clap::{Parser, Subcommand};
use harness::cast::Cast;
use std::process::ExitCode;

/// Differential verification harness for the Float316 raymarcher ports.
#[derive(Debug, Parser)]
#[command(name = "harness", version, about)]
pub struct Cli {
    /// The project file declaring more implementations (default:
    /// harness.toml in the current directory, when there is one).
    #[arg(long, global = true, value_name = "FILE")]
    pub cast: Option<std::path::PathBuf>,
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// List every implementation of the cast: kind, numbers, levels, availability.
    Cast(commands::cast::CastArgs),
    /// Render the 512x256 dithered image with one implementation.
    Render(commands::render::RenderArgs),
    /// Jack toolchain: compile Jack to VM code, run a VM program.
    #[command(subcommand)]
    Jack(commands::jack::JackCommand),
    /// Compare implementations on vector sets; exit 1 on a divergence.
    Diff(commands::diff::DiffArgs),
    /// Print the first Float316 operation on which two implementations differ.
    Localize(commands::localize::LocalizeArgs),
    /// Why a lower-precision implementation differs from ref-f64: class and root cause.
    Explain(commands::explain::ExplainArgs),
    /// Inject each fault of the catalogue and check that it is detected and localized.
    Selftest(commands::selftest::SelftestArgs),
    /// For `git bisect run`: exit 0 when the comparison holds, 1 when it fails, 125 when undecidable.
    Check(commands::check::CheckArgs),
    /// Speed and error table: every implementation renders the whole image.
    Bench(commands::bench::BenchArgs),
    /// Everything: levels, unary checks, self-test, renders, speed and error; HTML + JSON report.
    Nightly(commands::nightly::NightlyArgs),
    /// Join the reports of `diff --shard K/N` runs into the whole campaign's report.
    Merge(commands::merge::MergeArgs),
    /// A binary operation over every equivalence class of its operands, bit for bit.
    Sweep(commands::sweep::SweepArgs),
    /// Cheaper variants per call site of a scene that keep its picture: delta debugging, checked on Jack.
    Tune(commands::tune::TuneArgs),
    /// Vector sets: regenerate the committed ones, check a file, TestFloat-style cases.
    #[command(subcommand)]
    Vectors(commands::vectors::VectorsCommand),
}

/// Run a parsed command line; the exit code follows the design's contract
/// (errors of usage or input are reported by the caller as exit 2).
pub fn run(cli: Cli) -> anyhow::Result<ExitCode> {
    let cast = || Cast::load(cli.cast.as_deref());
    match cli.command {
        Command::Cast(args) => commands::cast::run(args, &cast()?),
        Command::Render(args) => commands::render::run(args, &cast()?),
        Command::Jack(cmd) => commands::jack::run(cmd),
        Command::Diff(args) => commands::diff::run(args, &cast()?),
        Command::Localize(args) => commands::localize::run(args, &cast()?),
        Command::Explain(args) => commands::explain::run(args, &cast()?),
        Command::Selftest(args) => commands::selftest::run(args, &cast()?),
        Command::Merge(args) => commands::merge::run(args),
        Command::Sweep(args) => commands::sweep::run(args, &cast()?),
        Command::Vectors(cmd) => commands::vectors::run(cmd),
        Command::Tune(args) => commands::tune::run(args),
        Command::Check(args) => commands::check::run(args, cast()),
        Command::Bench(args) => commands::bench::run(args, &cast()?),
        Command::Nightly(args) => commands::nightly::run(args, cast()?),
    }
}
