//! `harness jack test FILE.tst [--profile desktop|web]`: run one of the
//! course's VM emulator test scripts (hack-vm's `run_script`), write its
//! `.out` file and compare it with its `.cmp` file as the official tools do.

use hack_vm::Profile;
use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `harness jack test`.
#[derive(Debug, clap::Args)]
pub struct TestArgs {
    /// The test script (e.g. `BasicTestVME.tst`); paths in it are relative to its folder.
    pub script: PathBuf,
    /// Which official tool's VM emulator to follow.
    #[arg(long, default_value = "desktop")]
    pub profile: Profile,
}

/// Exit 0 when every output line matches the compare file (or the script
/// names none, or a breakpoint or `!` stopped it first), 1 at the first
/// differing line, 2 when the script cannot be read, parsed or run.
pub fn run(args: TestArgs) -> anyhow::Result<ExitCode> {
    let report = match hack_vm::run_script(&args.script, args.profile) {
        Ok(report) => report,
        Err(e) => {
            eprintln!("{e}");
            return Ok(ExitCode::from(2));
        }
    };
    if let Some(echo) = &report.echo {
        println!("{echo}");
    }
    if let Some(out) = &report.output_file {
        println!("output: {} ({} lines)", out.display(), report.lines);
    }
    println!("steps: {}", report.steps);
    if let Some(m) = &report.mismatch {
        println!("{m}");
        return Ok(ExitCode::from(1));
    }
    // A breakpoint or a `!` stops the script, as in the desktop tool: no
    // failure, and no end-of-script verdict.
    if let Some(stop) = &report.stopped {
        println!("{stop}");
        return Ok(ExitCode::SUCCESS);
    }
    match &report.compare_file {
        Some(cmp) => println!(
            "End of script - Comparison ended successfully ({})",
            cmp.display()
        ),
        None => println!("End of script"),
    }
    Ok(ExitCode::SUCCESS)
}
