//! `harness selftest [--fault NAME] [--json]`: inject each fault of the
//! catalogue, check that the harness detects it and localizes it to the
//! right operation, and that the clean pair shows no divergence.
//! Exit 0: every fault passed; 1: one did not; 2: usage error.

use anyhow::bail;
use harness::cast::Cast;
use harness::selftest::{catalogue, run_fault};
use std::process::ExitCode;

/// Arguments of `harness selftest`.
#[derive(Debug, clap::Args)]
pub struct SelftestArgs {
    /// Run only this fault (sqrt-floor-div, add-align-off-by-one,
    /// mul-keep-low, dither-threshold, jack-web-divide, f32-oracle).
    #[arg(long)]
    pub fault: Option<String>,
    /// Print the results as JSON.
    #[arg(long)]
    pub json: bool,
}

/// Run `harness selftest`.
pub fn run(args: SelftestArgs, cast: &Cast) -> anyhow::Result<ExitCode> {
    let faults: Vec<_> = catalogue()
        .into_iter()
        .filter(|f| args.fault.as_deref().is_none_or(|n| n == f.name))
        .collect();
    if faults.is_empty() {
        let names: Vec<&str> = catalogue().iter().map(|f| f.name).collect();
        bail!(
            "unknown fault `{}` (expected one of {})",
            args.fault.unwrap_or_default(),
            names.join(", ")
        );
    }
    let mut results = Vec::new();
    for fault in &faults {
        let r = run_fault(cast, fault);
        if !args.json {
            println!("{r}");
        }
        results.push(r);
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&results)?);
    }
    Ok(if results.iter().all(|r| r.passed) {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}
