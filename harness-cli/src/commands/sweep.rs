//! `harness sweep OP [--impl NAME]... [--shard K/N] [--limit N] [--json
//! FILE]`: a binary Float316 operation over every equivalence class of its
//! normalised operands (or one shard of them), compared bit for bit between
//! Float316 implementations (default ref-f316 against gpu-f316). Prints the
//! classes swept, cases per second and the projected time of the full
//! sweep; every divergence kept is written as a one-vector repro file.
//! Exit 0: no divergence; 1: a divergence or a failed implementation;
//! 2: usage or input error.

use anyhow::Context;
use common::Op;
use harness::cast::Cast;
use harness::sweep::{sweep, SweepResult};
use harness_report::atomic::write_file;
use std::path::PathBuf;
use std::process::ExitCode;
use vectors::{Shard, VectorSet};

/// Arguments of `harness sweep`.
#[derive(Debug, clap::Args)]
pub struct SweepArgs {
    /// The operation: add, sub, mul, div or gt.
    pub op: Op,
    /// The implementations (repeatable; the first is compared with each
    /// other one). Default: ref-f316 and gpu-f316.
    #[arg(long = "impl")]
    pub impls: Vec<String>,
    /// Sweep only shard K/N of the classes (K counts from 0).
    #[arg(long)]
    pub shard: Option<Shard>,
    /// Stop after this many classes (a quick look; a shard is the
    /// unbiased way to sweep a fraction).
    #[arg(long)]
    pub limit: Option<u64>,
    /// Write the result as JSON, repro files beside it in `repro/`.
    #[arg(long)]
    pub json: Option<PathBuf>,
}

fn seconds(s: f64) -> String {
    match s {
        s if s < 120.0 => format!("{s:.1} s"),
        s if s < 7200.0 => format!("{:.1} min", s / 60.0),
        s => format!("{:.1} h", s / 3600.0),
    }
}

fn print_result(r: &SweepResult) {
    println!(
        "sweep {}: {} against the rest, shard {}: {} of {} classes{} in {} ({:.3} M cases/s)",
        r.op,
        r.impls.join(", "),
        r.shard,
        r.swept,
        r.classes,
        if r.limited {
            " (stopped at --limit)"
        } else {
            ""
        },
        seconds(r.seconds),
        r.cases_per_second() / 1e6,
    );
    for f in &r.failures {
        println!("  failed: {f}");
    }
    if r.divergent == 0 {
        println!("  no divergence");
    } else {
        println!("  {} divergent cases; the first:", r.divergent);
        for d in &r.divergences {
            println!("    {}: {} against {}", d.input, d.a, d.b);
        }
    }
    println!(
        "  projected full sweep at this rate: {} on 1 machine, {} on 16 shards, {} on 256",
        seconds(r.projected_full_seconds(1)),
        seconds(r.projected_full_seconds(16)),
        seconds(r.projected_full_seconds(256)),
    );
}

/// Run `harness sweep`.
pub fn run(args: SweepArgs, cast: &Cast) -> anyhow::Result<ExitCode> {
    if let Some(path) = &args.json {
        crate::output::check_file(path, "--json")?;
    }
    let labels = if args.impls.is_empty() {
        vec!["ref-f316".to_string(), "gpu-f316".to_string()]
    } else {
        args.impls
    };
    anyhow::ensure!(
        labels.len() >= 2,
        "a sweep compares at least two implementations"
    );
    let opened = labels
        .iter()
        .map(|l| {
            cast.open(l)
                .with_context(|| format!("implementation `{l}`"))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let refs: Vec<&dyn harness::implementation::Implementation> =
        opened.iter().map(|b| b.as_ref()).collect();
    let shard = args.shard.unwrap_or(Shard::WHOLE);
    let total = vectors::gen::classes::class_count(args.op);
    let bar = harness::progress::show(
        harness::progress::items(
            args.limit
                .or(total.map(|t| t / u64::from(shard.count)))
                .unwrap_or(0),
            "sweep",
            "classes",
        ),
        harness::progress::wanted(),
    );
    let result =
        sweep(&refs, args.op, shard, args.limit, |n| bar.inc(n)).map_err(anyhow::Error::msg)?;
    bar.finish_and_clear();
    print_result(&result);
    if let Some(path) = &args.json {
        let dir = path
            .parent()
            .map(|p| p.join("repro"))
            .unwrap_or_else(|| "repro".into());
        if !result.divergences.is_empty() {
            std::fs::create_dir_all(&dir).with_context(|| format!("creating {}", dir.display()))?;
        }
        for d in &result.divergences {
            VectorSet::repro(d.input.clone())
                .save(&dir.join(format!("{}.json", d.input.slug())))?;
        }
        let json = serde_json::to_string_pretty(&result).context("serialising the sweep")?;
        write_file(path, json.as_bytes())?;
    }
    Ok(if result.failed() {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}
