//! `harness diff A B [C...] [--level ops|sdf|pixels|image|all] [--vectors
//! FILE] [--report DIR] [--shard K/N]`: run vector sets through the implementations,
//! compare the first with each other one, print the divergences (each with
//! the localize command that reproduces it) and, with `--report`, write a
//! JSON report and a one-line repro file per divergence.
//! Every implementation that opens runs; one that does not is reported
//! with the reason. The exit status is the run's [`Verdict`]: 0 agreed, 1 a
//! divergence beyond policy, 3 something asked for was not compared (a
//! failed open, a crash or hang, a level asked for and not answered); 2 a
//! usage or input error.

use anyhow::{bail, Context};
use harness::cast::{Cast, OpenError};
use harness::merge::run_shard;
use harness::runner::{LevelReport, RunOptions};
use harness::text;
use harness::verdict::Verdict;
use harness_report::atomic::StagingDir;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use vectors::{Level, Shard, Vector, VectorSet};

/// Levels selectable with `--level`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum LevelArg {
    Ops,
    Sdf,
    Pixels,
    Image,
    All,
}

impl LevelArg {
    fn levels(self) -> Vec<Level> {
        match self {
            LevelArg::Ops => vec![Level::Ops],
            LevelArg::Sdf => vec![Level::Sdf],
            LevelArg::Pixels => vec![Level::Pixels],
            LevelArg::Image => vec![Level::Image],
            LevelArg::All => Level::ALL.to_vec(),
        }
    }
}

/// Arguments of `harness diff`.
#[derive(Debug, clap::Args)]
pub struct DiffArgs {
    /// The implementation under test: a label of the cast (`harness cast`
    /// lists them; `NAME+FAULT` injects a fault, e.g.
    /// ref-f316+sqrt-floor-div, jack+web-divide, ref-f64+f32-oracle).
    pub a: String,
    /// The implementation it is compared with.
    pub b: String,
    /// More implementations: each is compared with A too, and with three
    /// or more the odd one out of each divergence is named.
    pub more: Vec<String>,
    /// Which level(s); without --vectors each level uses its small set.
    #[arg(long, value_enum)]
    pub level: Option<LevelArg>,
    /// A vector set file (its level is used).
    #[arg(long)]
    pub vectors: Option<PathBuf>,
    /// Write report.json and repro/*.json into this directory.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Run only shard K/N of each set (K counts from 0; a vector's shard
    /// is a stable hash of its identity); `harness merge` joins the
    /// shards' reports.
    #[arg(long)]
    pub shard: Option<Shard>,
    /// An implementation that cannot run on this machine (no Vulkan
    /// adapter) is reported as skipped without failing the
    /// run.
    #[arg(long)]
    pub allow_unavailable: bool,
}

/// The sets a diff runs: the file given, or each level's small set.
pub fn sets_for(level: Option<LevelArg>, file: Option<&Path>) -> anyhow::Result<Vec<VectorSet>> {
    match file {
        Some(path) => {
            let set = VectorSet::load(path)?;
            if let Some(l) = level {
                if l != LevelArg::All && l.levels() != [set.level] {
                    bail!(
                        "--level {l:?} does not match the level `{}` of {}",
                        set.level,
                        path.display()
                    );
                }
            }
            Ok(vec![set])
        }
        None => level
            .unwrap_or(LevelArg::All)
            .levels()
            .into_iter()
            .map(|l| {
                let name = vectors::named::small_set_name(l);
                vectors::load_named(name).with_context(|| format!("the committed set {name}"))
            })
            .collect(),
    }
}

/// Write `report.json` and a one-line repro file per kept divergence,
/// recording the repro paths in the report. The directory is replaced
/// whole, in one step: both are written into a staging directory beside it
/// that is then exchanged with it, so a run killed at any point leaves the
/// previous report and its repro files, or the new ones, never a mix.
pub fn write_report(dir: &Path, reports: &mut [LevelReport]) -> anyhow::Result<()> {
    let stage = StagingDir::new(dir)?;
    let repro_dir = dir.join("repro");
    let staged_repro = stage.path().join("repro");
    std::fs::create_dir(&staged_repro)
        .with_context(|| format!("creating {}", staged_repro.display()))?;
    for report in reports.iter_mut() {
        for c in &mut report.comparisons {
            for d in &mut c.divergences {
                if matches!(d.input, Vector::Image(_)) || !d.reproducible {
                    continue;
                }
                let name = format!("{}.json", d.input.slug());
                VectorSet::repro(d.input.clone()).save(&staged_repro.join(&name))?;
                d.repro = Some(repro_dir.join(name).display().to_string());
            }
        }
    }
    let json = serde_json::to_string_pretty(reports).context("serialising the report")?;
    std::fs::write(stage.path().join("report.json"), json)
        .with_context(|| format!("writing {}", stage.path().join("report.json").display()))?;
    stage.commit()?;
    Ok(())
}

/// Run `harness diff`.
pub fn run(args: DiffArgs, cast: &Cast) -> anyhow::Result<ExitCode> {
    if let Some(dir) = &args.report {
        crate::output::check_dir(dir, "--report")?;
    }
    let sets = sets_for(args.level, args.vectors.as_deref())?;
    let labels: Vec<String> = [args.a, args.b].into_iter().chain(args.more).collect();
    let mut verdict = Verdict::new(args.allow_unavailable);
    let mut opened = Vec::new();
    for label in &labels {
        match cast.open(label) {
            Ok(imp) => opened.push(imp),
            Err(OpenError::Impl(e)) => verdict.failed(format!("{label} (open)"), &e),
            Err(e) => return Err(e).with_context(|| format!("implementation `{label}`")),
        }
    }
    // Every comparison is the first implementation against another one.
    let first_opened = opened.first().is_some_and(|i| i.label() == labels[0]);
    let refs: Vec<&dyn harness::implementation::Implementation> = if first_opened {
        opened.iter().map(|b| b.as_ref()).collect()
    } else {
        Vec::new()
    };
    let options = RunOptions {
        progress: harness::progress::wanted(),
    };
    let mut reports: Vec<LevelReport> = if refs.len() >= 2 {
        sets.iter()
            .map(|set| run_shard(&refs, set, args.shard.unwrap_or(Shard::WHOLE), options))
            .collect()
    } else {
        Vec::new()
    };
    if let Some(dir) = &args.report {
        write_report(dir, &mut reports)?;
    }
    let asked = args.vectors.is_some() || args.level.is_some_and(|l| l != LevelArg::All);
    for r in &reports {
        print!("{}", text::level_report(r));
        let timings: Vec<String> = r
            .runs
            .iter()
            .map(|s| format!("{} {:.2}s", s.label, s.seconds))
            .collect();
        println!("  time: {}", timings.join(", "));
        verdict.add_level(r, asked);
    }
    if let Some(dir) = &args.report {
        println!("report: {}", dir.join("report.json").display());
    }
    Ok(verdict.report())
}
