//! `harness merge DIR... [--out DIR]`: join the reports of `harness diff
//! --shard K/N --report DIR` runs into the report of the whole campaign
//! (identical to the unsharded run's, timings apart), say which shards are
//! missing, and with `--out` write it with its repro files.
//! Exit 0: every shard present and no divergence; 1: a divergence or a
//! missing shard; 2: the reports cannot be merged.

use crate::commands::diff::write_report;
use crate::merge::merge;
use crate::runner::LevelReport;
use crate::text;
use anyhow::Context;
use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `harness merge`.
#[derive(Debug, clap::Args)]
pub struct MergeArgs {
    /// Report directories of the shards (each holds a report.json).
    #[arg(required = true)]
    pub dirs: Vec<PathBuf>,
    /// Write the merged report.json and repro/ here.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// Run `harness merge`.
pub fn run(args: MergeArgs) -> anyhow::Result<ExitCode> {
    if let Some(dir) = &args.out {
        crate::output::check_dir(dir, "--out")?;
    }
    let parts = args
        .dirs
        .iter()
        .map(|dir| {
            let path = dir.join("report.json");
            let text = common::input::read_text(&path)
                .with_context(|| format!("reading {}", path.display()))?;
            serde_json::from_str::<Vec<LevelReport>>(&text)
                .with_context(|| format!("{} is not a harness diff report", path.display()))
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    let mut merged = merge(&parts)?;
    if let Some(dir) = &args.out {
        write_report(dir, &mut merged.reports)?;
    }
    for r in &merged.reports {
        print!("{}", text::level_report(r));
    }
    let present = merged.count as usize - merged.missing.len();
    println!("shards: {present} of {}", merged.count);
    if !merged.missing.is_empty() {
        let list: Vec<String> = merged
            .missing
            .iter()
            .map(|k| format!("{k}/{}", merged.count))
            .collect();
        println!("missing shards: {}", list.join(", "));
    }
    if let Some(dir) = &args.out {
        println!("report: {}", dir.join("report.json").display());
    }
    let diverged = merged.reports.iter().any(LevelReport::diverged);
    Ok(if diverged || !merged.missing.is_empty() {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}
