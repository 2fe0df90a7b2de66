//! `harness jack`: the Jack toolchain. One module per subcommand under
//! `commands/jack/`.

mod compile;
pub mod cost;
mod emit;
mod run;
mod test;

/// Jack subcommands.
#[derive(Debug, clap::Subcommand)]
pub enum JackCommand {
    /// Compile every .jack file of SRC_DIR to one .vm file per class.
    Compile(compile::CompileArgs),
    /// Run a VM program on the Hack VM emulator (compiling .jack files first).
    Run(run::RunArgs),
    /// Run a course VM emulator test script (.tst), compared with its .cmp.
    Test(test::TestArgs),
    /// Write the Jack program generated from a scene description, with its bindings.toml.
    Emit(emit::EmitArgs),
    /// What the Jack program generated from a scene costs: VM instructions per pixel, time, ROM.
    Cost(cost::CostArgs),
}

/// Run a Jack subcommand.
pub fn run(cmd: JackCommand) -> anyhow::Result<std::process::ExitCode> {
    match cmd {
        JackCommand::Compile(args) => compile::run(args),
        JackCommand::Run(args) => run::run(args),
        JackCommand::Test(args) => test::run(args),
        JackCommand::Emit(args) => emit::run(args),
        JackCommand::Cost(args) => cost::run(args),
    }
}
