//! `harness merge DIR... [--out DIR]`: join the reports of `harness diff
//! --shard K/N --report DIR` runs into the report of the whole campaign
//! (identical to the unsharded run's, timings apart), say which shards are
//! missing, and with `--out` write it with its repro files.
//! The exit status is the merged [`Verdict`]: 1 on a divergence in any
//! shard; 3 when a shard is missing or an implementation failed in one
//! (every shard's failures are carried, and the counts are what was
//! actually compared); 2 when the reports cannot be merged.

use crate::commands::diff::write_report;
use anyhow::Context;
use harness::merge::merge;
use harness::runner::LevelReport;
use harness::text;
use harness::verdict::{Missing, Verdict};
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
    /// An implementation that could not run on a shard's machine (no
    /// Vulkan adapter) is reported as skipped without failing the merge.
    #[arg(long)]
    pub allow_unavailable: bool,
}

/// Run `harness merge`.
pub fn run(args: MergeArgs) -> anyhow::Result<ExitCode> {
    if let Some(dir) = &args.out {
        // The merged report replaces its folder whole: written over a
        // shard's report, or over a folder holding one, it would delete
        // that shard.
        if let Ok(out) = dir.canonicalize() {
            for input in &args.dirs {
                let Ok(canonical) = input.canonicalize() else {
                    continue;
                };
                if canonical == out {
                    anyhow::bail!(
                        "--out {} is one of the shard reports being merged ({}); give another folder",
                        dir.display(),
                        input.display()
                    );
                }
                if canonical.starts_with(&out) {
                    anyhow::bail!(
                        "--out {} holds the shard report {} being merged: the merged report \
                         replaces its whole folder, which would delete the shard; give another folder",
                        dir.display(),
                        input.display()
                    );
                }
            }
        }
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
    let mut verdict = Verdict::new(args.allow_unavailable);
    for r in &merged.reports {
        print!("{}", text::level_report(r));
        verdict.add_comparisons(r);
    }
    // A level a shard's implementation does not answer is that shard's
    // own `diff` to judge (it knows whether the level was asked for).
    for f in merged
        .failures
        .iter()
        .filter(|f| !matches!(f.error, harness::implementation::ImplError::Unsupported(_)))
    {
        verdict.failed(
            format!("{} on {} (shard {})", f.label, f.set, f.shard),
            &f.error,
        );
    }
    let present = merged.count as usize - merged.missing.len();
    println!("shards: {present} of {}", merged.count);
    for k in &merged.missing {
        verdict.not_compared(
            format!("shard {k}/{}", merged.count),
            Missing::Shard,
            "no report given",
        );
    }
    if let Some(dir) = &args.out {
        println!("report: {}", dir.join("report.json").display());
    }
    Ok(verdict.report())
}
