//! `harness nightly`: everything in one run. Every level on the committed
//! nightly sets, every implementation available here, the unary checks
//! over every normalised input, the self-test, full-image renders (with the
//! reference's precision variants) and their speed and error, written as
//! one report directory (`report.json`, `index.html`, images) that replaces
//! the previous one atomically, plus a line in the history file.

use crate::compare::{Comparison as LevelComparison, Policy};
use crate::exhaustive;
use crate::implementation::{ImplName, Implementation};
use crate::impls;
use crate::report::images::Grid;
use crate::report::measure::{self, FullRender};
use crate::report::model::{
    BenchRow, Comparison, DivergenceExample, ErrorFigures, ImplStatus, Render, RunMeta, SelfTest,
    StepTiming,
};
use crate::report::{RenderImages, ReportBuilder, BIT_EXACT, ERROR_FIGURES};
use crate::runner::{self, RunOptions};
use crate::selftest;
use anyhow::{Context, Result};
use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

/// Arguments of `harness nightly`.
#[derive(Debug, clap::Args)]
pub struct NightlyArgs {
    /// Report directory (replaced atomically when the run completes).
    #[arg(long, default_value = "reports/nightly")]
    pub out: PathBuf,
    /// The unary checks against the Jack emulator take every N-th input
    /// (the reference and gpu-f316 always take every input).
    #[arg(long, default_value_t = 16)]
    pub jack_unary_step: usize,
}

/// Precision variants of ref-f316 rendered for the speed-against-error plot.
const VARIANTS: [&str; 3] = ["mul-low-product", "newton-1", "newton-3"];

/// Label of the Jack program's own run from `Main.main` (the slow path).
const JACK_MAIN: &str = "jack-main";

/// Instruction budget of that run (the image takes about 21 billion).
const JACK_MAIN_BUDGET: u64 = 60_000_000_000;

/// Examples of divergences kept per comparison in the report.
const EXAMPLES: usize = 5;

/// The nightly sets, one per level.
const NIGHTLY_SETS: [&str; 3] = ["ops-nightly", "sdf-nightly", "pixels-nightly"];

/// Times the steps of the run.
struct Steps {
    list: Vec<StepTiming>,
    last: Instant,
}

impl Steps {
    fn done(&mut self, step: &str) {
        self.list.push(StepTiming {
            step: step.into(),
            seconds: self.last.elapsed().as_secs_f64(),
        });
        self.last = Instant::now();
    }
}

/// Run the nightly job.
pub fn run(args: NightlyArgs) -> Result<ExitCode> {
    let started = Instant::now();
    let progress = RunOptions {
        progress: std::io::stderr().is_terminal(),
    };
    let mut steps = Steps {
        list: Vec::new(),
        last: Instant::now(),
    };
    let mut builder = ReportBuilder::new(&args.out, RunMeta::collect())?;

    // Which implementations can run here.
    let mut open: Vec<Box<dyn Implementation>> = Vec::new();
    for name in ImplName::ALL {
        let status = match impls::open(name) {
            Ok(imp) => {
                open.push(imp);
                ImplStatus {
                    name: name.as_str().into(),
                    available: true,
                    note: None,
                }
            }
            Err(e) => ImplStatus {
                name: name.as_str().into(),
                available: false,
                note: Some(e.to_string()),
            },
        };
        builder.report_mut().implementations.push(status);
    }
    let by_name = |n: ImplName| open.iter().find(|i| i.label() == n.as_str());
    let group = |names: &[ImplName]| -> Vec<&dyn Implementation> {
        names
            .iter()
            .filter_map(|n| by_name(*n))
            .map(|b| b.as_ref())
            .collect()
    };
    let float316 = group(&[ImplName::RefF316, ImplName::Jack, ImplName::GpuF316]);
    let floats = group(&[
        ImplName::RefF64,
        ImplName::RefF32,
        ImplName::GpuF32,
        ImplName::RefF316,
    ]);
    steps.done("open implementations");

    // Levels on the nightly sets.
    for set_name in NIGHTLY_SETS {
        let set = vectors::load_named(set_name)
            .with_context(|| format!("the committed set {set_name}"))?;
        let mut groups = vec![&float316];
        if set.level != vectors::Level::Ops {
            groups.push(&floats);
        }
        for impls in groups {
            if impls.len() < 2 {
                continue;
            }
            let level = runner::diff_set(impls, &set, progress);
            record_failures(&mut builder, &level);
            for c in &level.comparisons {
                builder
                    .report_mut()
                    .comparisons
                    .push(summarise(c, &set.name));
            }
        }
        steps.done(set_name);
    }

    // Unary operations over every normalised input.
    let unary_pairs: [(Vec<&dyn Implementation>, usize); 2] = [
        (group(&[ImplName::RefF316, ImplName::GpuF316]), 1),
        (
            group(&[ImplName::RefF316, ImplName::Jack]),
            args.jack_unary_step.max(1),
        ),
    ];
    for (impls, step) in unary_pairs {
        if impls.len() < 2 {
            continue;
        }
        for level in exhaustive::unary(&impls, step, progress) {
            record_failures(&mut builder, &level);
            for c in &level.comparisons {
                let mut row = summarise(c, &level.set);
                row.level = "unary-exhaustive".into();
                row.scope = format!("{} (every {step}. input)", level.set);
                builder.report_mut().comparisons.push(row);
            }
        }
    }
    steps.done("unary checks");

    // The self-test.
    let results = selftest::run_all();
    builder.report_mut().selftest = Some(SelfTest {
        passed: results.iter().all(|r| r.passed),
        lines: results.iter().map(|r| r.to_string()).collect(),
    });
    steps.done("self-test");

    // Full-image renders, with the reference's precision variants.
    let spec = measure::spec_image()?;
    let set = measure::full_image_set();
    let mut labels: Vec<String> = open.iter().map(|i| i.label().to_string()).collect();
    labels.extend(VARIANTS.iter().map(|v| format!("ref-f316+{v}")));
    let mut rendered = Vec::new();
    for label in &labels {
        let result = if label == "jack" {
            // Through the crate directly: the same pixels, with the VM
            // instructions each took.
            jack_render().and_then(|(full, costs)| {
                let total = costs.data().iter().sum();
                add_render(&mut builder, &full, &spec, Some(total))?;
                builder.set_cost_map(&costs)?;
                Ok(full)
            })
        } else {
            measure::render(label, &set, progress.progress)
                .and_then(|full| add_render(&mut builder, &full, &spec, None).map(|()| full))
        };
        match result {
            Ok(full) => rendered.push(full.label),
            Err(e) => builder
                .report_mut()
                .problems
                .push(format!("render {label}: {e:#}")),
        }
    }
    steps.done("renders");

    // The slow path: the whole Jack program from Main.main, drawing on the
    // Hack screen with its Float316 counters, must draw what the entry
    // points computed.
    if rendered.iter().any(|r| r == "jack") {
        match jack_main_screen() {
            Ok(full) => {
                add_render(&mut builder, &full, &spec, None)?;
                rendered.push(full.label);
            }
            Err(e) => builder
                .report_mut()
                .problems
                .push(format!("jack Main.main: {e:#}")),
        }
        steps.done("jack Main.main");
    }

    // Every render against ref-f316 and the float ones against ref-f64.
    if rendered.iter().any(|r| r == JACK_MAIN) {
        builder.add_pair(
            "jack",
            JACK_MAIN,
            |_, _| None,
            |x, y| format!("harness localize ref-f316 jack --pixel {x},{y}"),
        )?;
    }
    for label in &rendered {
        for base in ["ref-f316", "ref-f64"] {
            if label != base && rendered.iter().any(|r| r == base) {
                let (a, b) = (base.to_string(), label.clone());
                builder.add_pair(
                    &a,
                    &b,
                    |_, _| None,
                    |x, y| format!("harness localize {a} {b} --pixel {x},{y}"),
                )?;
            }
        }
    }
    if rendered.iter().any(|r| r == "ref-f64") {
        for label in &rendered {
            let point = builder.speed_point(label)?;
            let render = builder
                .report()
                .renders
                .iter()
                .find(|r| &r.label == label)
                .context("render just added")?
                .clone();
            builder.report_mut().bench.push(BenchRow {
                implementation: label.clone(),
                setup_s: render.setup_s,
                image_s: render.render_s,
                pixels: render.pixels,
                per_pixel_s: point.time_per_pixel_s,
                vm_instructions_per_pixel: point.vm_instructions_per_pixel,
                mean_shade_error: point.mean_shade_error,
                max_shade_error: point.max_shade_error,
                pixel_flips: point.pixel_flips,
            });
            builder.report_mut().speed_error.points.push(point);
        }
    }
    steps.done("pairs and speed");

    let report = builder.report_mut();
    let bit_exact = report.bit_exact_divergences();
    let problems = report.problems.len();
    let selftest_ok = report.selftest.as_ref().is_some_and(|s| s.passed);
    steps.done("summary");
    report.meta.steps = steps.list;
    report.meta.duration_s = started.elapsed().as_secs_f64();
    let duration = report.meta.duration_s;
    let history = args
        .out
        .parent()
        .unwrap_or_else(|| std::path::Path::new("."))
        .join("history.jsonl");
    let dir = builder.finish(&history)?;
    println!(
        "nightly: {bit_exact} bit-exact divergences, self-test {}, {problems} problems, {duration:.0} s; report {}",
        if selftest_ok { "passed" } else { "FAILED" },
        dir.join("index.html").display()
    );
    Ok(if bit_exact == 0 && selftest_ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

/// Implementations that gave no answers become problems of the report.
fn record_failures(builder: &mut ReportBuilder, level: &runner::LevelReport) {
    let lines: Vec<String> = level
        .failures()
        .map(|(label, e)| format!("{} on {}: {e}", label, level.set))
        .collect();
    builder.report_mut().problems.extend(lines);
}

/// A runner comparison as a report row.
fn summarise(c: &LevelComparison, set: &str) -> Comparison {
    Comparison {
        level: c.level.to_string(),
        scope: set.into(),
        a: c.a.clone(),
        b: c.b.clone(),
        policy: match c.policy {
            Policy::Exact => BIT_EXACT,
            Policy::Error { .. } => ERROR_FIGURES,
        }
        .into(),
        cases: c.vectors as u64,
        divergences: (c.divergences.iter().filter(|d| !d.tolerated).count() + c.omitted) as u64,
        error: c.stats.as_ref().map(|s| ErrorFigures {
            mean_abs: s.mean_abs,
            max_abs: s.max_abs,
        }),
        examples: c
            .divergences
            .iter()
            .filter(|d| !d.tolerated)
            .take(EXAMPLES)
            .map(|d| DivergenceExample {
                case: d.input.to_string(),
                a: d.a.to_string(),
                b: d.b.to_string(),
                first_op: None,
                repro: d.localize.clone(),
            })
            .collect(),
    }
}

/// Add one full render to the report.
fn add_render(
    builder: &mut ReportBuilder,
    full: &FullRender,
    spec: &Grid<bool>,
    vm_instructions: Option<u64>,
) -> Result<()> {
    let (implementation, variant) = match full.label.split_once('+') {
        Some((i, v)) => (i.to_string(), Some(v.to_string())),
        None => (full.label.clone(), None),
    };
    let identical = full
        .images
        .bits
        .positions_where(spec, |p, q| p != q)
        .map(|d| d.is_empty())
        .ok();
    builder.add_render(
        Render {
            label: full.label.clone(),
            implementation,
            variant,
            setup_s: full.setup_s,
            render_s: full.render_s,
            pixels: full.pixels(),
            identical_to_spec: identical,
            vm_instructions,
            ..Render::default()
        },
        full.images.clone(),
    )
}

/// The Jack program's whole image through its pixel entry point, with the
/// per-pixel VM instruction counts (the cost map).
fn jack_render() -> Result<(FullRender, Grid<u64>)> {
    use common::image_consts::{HEIGHT, WIDTH};
    let start = Instant::now();
    let raymarcher = jack::Raymarcher::new(jack::Profile::Desktop, jack::Budgets::default())?;
    let setup_s = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let render = raymarcher.render()?;
    let render_s = start.elapsed().as_secs_f64();
    let pixels = render
        .pixels
        .iter()
        .map(|p| p.outcome.value().map(|s| (s.white, s.value.to_f64())));
    let full = FullRender::from_pixels("jack", setup_s, render_s, pixels)?;
    let costs = render.pixels.iter().map(|p| p.instructions).collect();
    Ok((full, Grid::new(WIDTH, HEIGHT, costs)?))
}

/// The Hack screen after `Main.main` ran to its end with SPACE pressed.
fn jack_main_screen() -> Result<FullRender> {
    use common::image_consts::{HEIGHT, WIDTH};
    let start = Instant::now();
    let screen = match jack::run_main(jack::Profile::Desktop, JACK_MAIN_BUDGET)? {
        common::Outcome::Value(screen) => screen,
        other => anyhow::bail!("Main.main did not finish: {}", other.map(|_| "screen")),
    };
    Ok(FullRender {
        label: JACK_MAIN.into(),
        setup_s: 0.0,
        render_s: start.elapsed().as_secs_f64(),
        images: RenderImages {
            bits: Grid::new(WIDTH, HEIGHT, screen.white)?,
            shades: None,
        },
        trapped: 0,
    })
}
