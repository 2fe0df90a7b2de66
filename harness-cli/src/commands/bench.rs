//! `harness bench`: the speed and error table. Every implementation
//! of the cast available here (or the ones named) renders the whole image;
//! each row has its set-up time, image time, time per pixel, pixels per
//! second and its error against the oracle, `ref-f64` (mean and max shade
//! error, dithered flips, trapped pixels).
//! Printed as a table, and as JSON with `--json FILE`. The exit status is
//! the run's [`Verdict`]: 1 when a render diverges from the oracle beyond
//! its policy (more flips than its number type allows, a trap where the
//! oracle answered), 3 when one could not render (a built-in unavailable
//! here counts unless `--allow-unavailable`).

use anyhow::{Context, Result};
use harness::cast::Cast;
use harness::verdict::{self, Verdict};
use harness_report::measure::{self, ImageError};
use harness_report::model::BenchRow;
use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `harness bench`.
#[derive(Debug, clap::Args)]
pub struct BenchArgs {
    /// Implementations (labels, faults allowed); default: every one of the
    /// cast, the unavailable ones reported and skipped.
    pub implementations: Vec<String>,
    /// Also write the rows as JSON.
    #[arg(long, value_name = "FILE.json")]
    pub json: Option<PathBuf>,
    /// An implementation that cannot run on this machine (no Vulkan
    /// adapter) is reported as skipped without failing the run.
    #[arg(long)]
    pub allow_unavailable: bool,
}

/// Run the benchmark table.
pub fn run(args: BenchArgs, cast: &Cast) -> Result<ExitCode> {
    let labels: Vec<String> = if args.implementations.is_empty() {
        cast.names().into_iter().map(String::from).collect()
    } else {
        args.implementations.clone()
    };
    let progress = harness::progress::wanted();
    let oracle_name = &cast.oracle().name;
    let (oracle, _) = measure::render(cast, oracle_name, progress)
        .with_context(|| format!("the oracle {oracle_name}"))?;
    let mut verdict = Verdict::new(args.allow_unavailable);
    let mut rows = Vec::new();
    for label in &labels {
        let (full, numbers) = if label == oracle_name {
            (oracle.clone(), harness::implementation::Numbers::F64)
        } else {
            match measure::render(cast, label, progress) {
                Ok(rendered) => rendered,
                Err(e) => {
                    match verdict::implementation_failure(&e) {
                        Some(failure) => verdict.failed(label.clone(), failure),
                        None => return Err(e),
                    }
                    continue;
                }
            }
        };
        let figures = ImageError::of(&full.images, &oracle.images)?;
        if label != oracle_name {
            verdict.compared(
                format!("{label} vs {oracle_name} image"),
                figures.pixels,
                figures.beyond_policy(numbers),
            );
        }
        let errors = figures.shade;
        let pixels = full.pixels();
        rows.push(BenchRow {
            implementation: label.clone(),
            setup_s: full.setup_s,
            image_s: full.render_s,
            pixels,
            per_pixel_s: full.render_s / pixels.max(1) as f64,
            vm_instructions_per_pixel: None,
            mean_shade_error: errors.map(|e| e.0),
            max_shade_error: errors.map(|e| e.1),
            pixel_flips: figures.flips,
            trapped: figures.traps,
        });
    }
    println!(
        "{:<28} {:>9} {:>9} {:>11} {:>12} {:>10} {:>10} {:>6} {:>7}",
        "implementation",
        "set-up s",
        "image s",
        "per pixel",
        "pixels/s",
        "mean|err|",
        "max|err|",
        "flips",
        "trapped"
    );
    let fmt = |e: Option<f64>| e.map_or("-".to_string(), |v| format!("{v:.2e}"));
    for r in &rows {
        println!(
            "{:<28} {:>9.3} {:>9.3} {:>9.2}µs {:>12.0} {:>10} {:>10} {:>6} {:>7}",
            r.implementation,
            r.setup_s,
            r.image_s,
            r.per_pixel_s * 1e6,
            r.pixels_per_s(),
            fmt(r.mean_shade_error),
            fmt(r.max_shade_error),
            r.pixel_flips,
            r.trapped
        );
    }
    if let Some(path) = &args.json {
        let text = serde_json::to_string_pretty(&rows)?;
        harness_report::atomic::write_file(path, text.as_bytes())
            .with_context(|| format!("writing {}", path.display()))?;
    }
    Ok(verdict.report())
}
