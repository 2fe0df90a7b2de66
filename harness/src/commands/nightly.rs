//! `harness nightly`: everything in one run. Every level on the committed
//! nightly sets, every implementation available here (with the outcome of
//! every category of those sets, the stability section), the unary checks
//! over every normalised input, the self-test, full-image renders (with the
//! reference's precision variants), their pairs with the divergent pixels
//! of Float316 pairs localized, and their speed and error, written as one
//! report directory (`report.json`, `index.html`, images) that replaces the
//! previous one atomically, plus a line in the history file.

use crate::cast::Cast;
use crate::compare::{Comparison as LevelComparison, Divergence, Policy};
use crate::exhaustive;
use crate::implementation::Implementation;
use crate::localize::{localizable, localize};
use crate::measure::{self, FullRender};
use crate::progress;
use crate::report::images::Grid;
use crate::report::model::{
    BenchRow, Comparison, DivergenceExample, ErrorFigures, ImplStatus, Render, RunMeta, SelfTest,
    StepTiming,
};
use crate::report::{
    stability, PixelLocalizer, RenderImages, ReportBuilder, BIT_EXACT, ERROR_FIGURES,
};
use crate::runner::{self, ImplRun, RunOptions};
use crate::selftest;
use anyhow::{Context, Result};
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;
use vectors::{PixelVector, Vector};

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
    /// Record `step` as finished now, and say so on standard error (the
    /// long steps have progress bars; this line is the log of the run).
    fn done(&mut self, step: &str) {
        let seconds = self.last.elapsed().as_secs_f64();
        eprintln!("nightly: {step}: {seconds:.1} s");
        self.list.push(StepTiming {
            step: step.into(),
            seconds,
        });
        self.last = Instant::now();
    }
}

/// Run the nightly job.
pub fn run(args: NightlyArgs, cast: &Cast) -> Result<ExitCode> {
    let started = Instant::now();
    let progress = RunOptions {
        progress: crate::progress::wanted(),
    };
    let mut steps = Steps {
        list: Vec::new(),
        last: Instant::now(),
    };
    let mut builder = ReportBuilder::new(&args.out, RunMeta::collect())?;

    // Which implementations can run here.
    let mut open: Vec<Box<dyn Implementation>> = Vec::new();
    let bar = progress::show(
        progress::items(cast.entries().len() as u64, "open", "implementations"),
        progress.progress,
    );
    for entry in cast.entries() {
        let name = entry.name.as_str();
        bar.set_message(name.to_string());
        let start = Instant::now();
        let opened = cast.open(name);
        let mut status = ImplStatus {
            name: name.into(),
            available: opened.is_ok(),
            open_s: start.elapsed().as_secs_f64(),
            ..ImplStatus::default()
        };
        match opened {
            Ok(imp) => open.push(imp),
            Err(e) => status.note = Some(e.to_string()),
        }
        builder.report_mut().implementations.push(status);
        bar.inc(1);
    }
    bar.finish_and_clear();
    let by_name = |n: &str| open.iter().find(|i| i.label() == n);
    let group = |names: &[&str]| -> Vec<&dyn Implementation> {
        names
            .iter()
            .filter_map(|n| by_name(n))
            .map(|b| b.as_ref())
            .collect()
    };
    let everyone: Vec<&str> = cast.names();
    let (oracle, tracer_name) = (cast.oracle().name.as_str(), cast.tracer().name.as_str());
    let float316: Vec<&str> = cast
        .bit_exact_group()
        .iter()
        .map(|e| e.name.as_str())
        .collect();
    // The oracle first, then every implementation computing with floats,
    // then the tracer.
    let floats: Vec<&str> = std::iter::once(oracle)
        .chain(
            cast.entries()
                .iter()
                .filter(|e| !e.bit_exact() && e.name != oracle)
                .map(|e| e.name.as_str()),
        )
        .chain([tracer_name])
        .collect();
    // The tracer's precision variants (rendered below), and the tracer,
    // for localizing divergences.
    let variant_labels: Vec<String> = cast
        .tracer()
        .variants
        .iter()
        .filter(|v| v.role == crate::cast::VariantRole::Precision)
        .map(|v| format!("{tracer_name}+{}", v.name))
        .collect();
    let variants: Vec<Box<dyn Implementation>> = variant_labels
        .iter()
        .filter_map(|l| cast.open(l).ok())
        .collect();
    let find = |label: &str| {
        open.iter()
            .chain(&variants)
            .find(|i| i.label() == label)
            .map(|b| b.as_ref())
    };
    let tracer = by_name(tracer_name).map(|b| b.as_ref());
    let first_op = |c: &LevelComparison, d: &Divergence| {
        let (a, b, t) = (find(&c.a)?, find(&c.b)?, tracer?);
        (c.policy == Policy::Exact).then(|| match localize(a, b, t, &d.input) {
            Ok(found) => found.one_line(),
            Err(e) => format!("not localized: {e}"),
        })
    };
    steps.done("open implementations");

    // Levels on the nightly sets: every implementation answers each set
    // once; the Float316 group is compared bit for bit with ref-f316, the
    // float group against ref-f64 (SDF points and pixels), and the answers
    // of all of them give the stability rows of the set's categories.
    for set_name in NIGHTLY_SETS {
        let set = vectors::load_named(set_name)
            .with_context(|| format!("the committed set {set_name}"))?;
        let everyone: Vec<&dyn Implementation> = group(&everyone)
            .into_iter()
            .filter(|i| i.supports(set.level))
            .collect();
        let runs = runner::run(&everyone, &set, progress);
        let runs_of = |names: &[&str]| -> Vec<ImplRun> {
            names
                .iter()
                .filter_map(|n| runs.iter().find(|r| r.label == *n).cloned())
                .collect()
        };
        let mut groups = vec![runs_of(&float316)];
        if set.level != vectors::Level::Ops {
            groups.push(runs_of(&floats));
        }
        let mut exact = Vec::new();
        for group_runs in groups {
            if group_runs.len() < 2 {
                continue;
            }
            let level = runner::level_report(&set, &group_runs);
            record_failures(&mut builder, &level);
            for c in &level.comparisons {
                builder
                    .report_mut()
                    .comparisons
                    .push(summarise(c, &set.name, &first_op));
            }
            exact.extend(
                level
                    .comparisons
                    .into_iter()
                    .filter(|c| c.policy == Policy::Exact),
            );
        }
        let mut unwritten = Vec::new();
        let rows = stability::rows(&set, &runs, &exact, |imp, vector| {
            match builder.write_repro(vector) {
                Ok(file) => Some(format!("harness diff {imp} {oracle} --vectors {file}")),
                Err(e) => {
                    unwritten.push(format!("repro file for {vector}: {e:#}"));
                    None
                }
            }
        });
        let report = builder.report_mut();
        report.stability.extend(rows);
        report.problems.extend(unwritten);
        steps.done(set_name);
    }

    // Unary operations over every normalised input.
    // The tracer against each other Float316 implementation; slow ones
    // (an emulator) take every N-th input.
    let unary_pairs: Vec<(Vec<&dyn Implementation>, usize)> = cast
        .bit_exact_group()
        .iter()
        .skip(1)
        .map(|e| {
            let step = if e.slow {
                args.jack_unary_step.max(1)
            } else {
                1
            };
            (group(&[tracer_name, e.name.as_str()]), step)
        })
        .collect();
    for (impls, step) in unary_pairs {
        if impls.len() < 2 {
            continue;
        }
        for level in exhaustive::unary(&impls, step, progress) {
            record_failures(&mut builder, &level);
            for c in &level.comparisons {
                let mut row = summarise(c, &level.set, &first_op);
                row.level = "unary-exhaustive".into();
                row.scope = match step {
                    1 => format!("{} (every input)", level.set),
                    n => format!("{} (one input in {n})", level.set),
                };
                builder.report_mut().comparisons.push(row);
            }
        }
    }
    steps.done("unary checks");

    // The self-test.
    let results = selftest::run_all(cast);
    builder.report_mut().selftest = Some(SelfTest {
        passed: results.iter().all(|r| r.passed),
        lines: results.iter().map(|r| r.to_string()).collect(),
    });
    steps.done("self-test");

    // Full-image renders, with the reference's precision variants.
    let spec = measure::spec_image()?;
    let mut labels: Vec<String> = open.iter().map(|i| i.label().to_string()).collect();
    labels.extend(variant_labels.iter().cloned());
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
            measure::render(cast, label, progress.progress)
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
    let jack_total = builder
        .report()
        .renders
        .iter()
        .find(|r| r.label == "jack")
        .and_then(|r| r.vm_instructions);
    if let Some(expected) = jack_total {
        match jack_main_screen(expected, progress.progress) {
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

    // Every render against ref-f316 and the float ones against ref-f64;
    // the listed divergent pixels of Float316 pairs are localized.
    let mut pairs = Vec::new();
    if rendered.iter().any(|r| r == JACK_MAIN) {
        pairs.push(("jack".to_string(), JACK_MAIN.to_string()));
    }
    for label in &rendered {
        for base in [tracer_name, oracle] {
            if label != base && rendered.iter().any(|r| r == base) {
                pairs.push((base.to_string(), label.clone()));
            }
        }
    }
    let bar = progress::show(
        progress::items(pairs.len() as u64, "pairs", "image pairs compared"),
        progress.progress,
    );
    for (a, b) in &pairs {
        bar.set_message(format!("{a} against {b}"));
        let localizer = pixel_localizer(find(a), find(b), tracer, [a, b]);
        // A pixel of the Main.main screen is reproduced through jack's
        // entry point (against ref-f316 when the pair is jack's own).
        let (ra, rb) = (entry_point(a), entry_point(b));
        let ra = if ra == rb { tracer_name } else { ra };
        let by_localize = matches!(
            (find(ra), find(rb)),
            (Some(x), Some(y)) if localizable(x, y).is_ok()
        );
        let repro = |x: usize, y: usize| pixel_repro(ra, rb, by_localize, x, y);
        let listed: Vec<(usize, usize)> = builder
            .add_pair(a, b, localizer, repro)?
            .divergences
            .iter()
            .map(|d| (d.x as usize, d.y as usize))
            .collect();
        if !by_localize {
            for (x, y) in listed {
                builder.write_repro(&pixel(x, y))?;
            }
        }
        bar.inc(1);
    }
    bar.finish_and_clear();
    if rendered.iter().any(|r| r == oracle) {
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

/// The pixel vector of `(x, y)`.
fn pixel(x: usize, y: usize) -> Vector {
    Vector::Pixel(PixelVector {
        category: "image".into(),
        x: x as u16,
        y: y as u16,
    })
}

/// How the listed pixels of the pair `labels` are localized: op traces
/// when both are Float316 implementations open here (`a`, `b`), else why
/// not.
fn pixel_localizer<'a>(
    a: Option<&'a dyn Implementation>,
    b: Option<&'a dyn Implementation>,
    tracer: Option<&'a dyn Implementation>,
    labels: [&String; 2],
) -> PixelLocalizer<'a> {
    let missing = |label: &str| {
        if label == JACK_MAIN {
            format!(
                "{JACK_MAIN} is the Hack screen after the whole program ran from Main.main: \
                 it has no per-pixel trace (the repro command localizes the pixel through \
                 jack's entry point)"
            )
        } else {
            format!("{label} is not open here")
        }
    };
    // A float side is the first reason, whatever the other side is.
    for imp in [a, b].into_iter().flatten() {
        if let Err(why) = localizable(imp, imp) {
            return PixelLocalizer::Impossible(why.to_string());
        }
    }
    let (a, b, tracer) = match (a, b, tracer) {
        (None, _, _) => return PixelLocalizer::Impossible(missing(labels[0])),
        (_, None, _) => return PixelLocalizer::Impossible(missing(labels[1])),
        (_, _, None) => {
            return PixelLocalizer::Impossible("ref-f316, the tracer, is not open here".into())
        }
        (Some(a), Some(b), Some(t)) => (a, b, t),
    };
    PixelLocalizer::Traced {
        method: "first divergent Float316 operation from the op traces of both sides \
                 (a side that cannot trace replays ref-f316's trace op by op)"
            .into(),
        first_op: Box::new(move |x, y| match localize(a, b, tracer, &pixel(x, y)) {
            Ok(found) => found.one_line(),
            Err(e) => format!("not localized: {e}"),
        }),
    }
}

/// The implementation that answers for a render label on the command line
/// (the Main.main screen's pixels come from jack's entry point).
fn entry_point(label: &str) -> &str {
    if label == JACK_MAIN {
        "jack"
    } else {
        label
    }
}

/// The command that reproduces a divergent pixel of the implementations
/// `a` and `b`: `harness localize` when both are Float316 (`by_localize`),
/// else `harness diff` on the pixel's repro file (written in the report).
fn pixel_repro(a: &str, b: &str, by_localize: bool, x: usize, y: usize) -> String {
    if by_localize {
        format!("harness localize {a} {b} --pixel {x},{y}")
    } else {
        format!(
            "harness diff {a} {b} --vectors repro/{}.json",
            pixel(x, y).slug()
        )
    }
}

/// Implementations that gave no answers become problems of the report.
fn record_failures(builder: &mut ReportBuilder, level: &runner::LevelReport) {
    let lines: Vec<String> = level
        .failures()
        .map(|(label, e)| format!("{} on {}: {e}", label, level.set))
        .collect();
    builder.report_mut().problems.extend(lines);
}

/// A runner comparison as a report row; `first_op` localizes its examples
/// (bit-exact comparisons of implementations open here).
fn summarise(
    c: &LevelComparison,
    set: &str,
    first_op: &dyn Fn(&LevelComparison, &Divergence) -> Option<String>,
) -> Comparison {
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
                first_op: first_op(c, d),
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

/// The Jack program's whole image through its bound pixel statements, with
/// the per-pixel VM instruction counts (the cost map).
fn jack_render() -> Result<(FullRender, Grid<u64>)> {
    use common::image_consts::{HEIGHT, WIDTH};
    let start = Instant::now();
    let raymarcher = jack::sources::bound(jack::Profile::Desktop, jack::Budgets::default())?;
    let setup_s = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let render = crate::impls::jack::render_with_bar(&raymarcher)?;
    let render_s = start.elapsed().as_secs_f64();
    let pixels = render
        .pixels
        .iter()
        .map(|p| p.outcome.value().map(|s| (s.white, s.value.to_f64())));
    let full = FullRender::from_pixels("jack", setup_s, render_s, pixels)?;
    let costs = render.pixels.iter().map(|p| p.instructions).collect();
    Ok((full, Grid::new(WIDTH, HEIGHT, costs)?))
}

/// The Hack screen after `Main.main` ran to its end with SPACE pressed;
/// a bar of VM instructions, `expected` of them, when `shown`.
fn jack_main_screen(expected: u64, shown: bool) -> Result<FullRender> {
    use common::image_consts::{HEIGHT, WIDTH};
    let start = Instant::now();
    let bar = progress::show(progress::instructions(Some(expected), "Main.main"), shown);
    let run = jack::run_main(jack::Profile::Desktop, JACK_MAIN_BUDGET, &mut |n| {
        bar.set_position(n)
    });
    bar.finish_and_clear();
    let screen = match run? {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::implementation::Answer;
    use common::image_consts::{HEIGHT, WIDTH};

    /// A render of one row of `imp` (the other rows black).
    fn row_render(imp: &dyn Implementation, y: usize) -> RenderImages {
        let row: Vec<Vector> = (0..WIDTH).map(|x| pixel(x, y)).collect();
        let mut bits = vec![false; WIDTH * HEIGHT];
        for (x, answer) in imp.eval(&row).unwrap().into_iter().enumerate() {
            let common::Outcome::Value(Answer::Pixel { white, .. }) = answer else {
                panic!("pixel ({x},{y}): {answer}");
            };
            bits[y * WIDTH + x] = white;
        }
        RenderImages {
            bits: Grid::new(WIDTH, HEIGHT, bits).unwrap(),
            shades: None,
        }
    }

    #[test]
    fn pixels_a_fault_flips_are_localized_to_the_faulty_operation() {
        let cast = Cast::builtin();
        let clean = cast.open("ref-f316").unwrap();
        let faulty = cast.open("ref-f316+mul-keep-low").unwrap();
        let dir = tempfile::tempdir().unwrap();
        let mut builder = ReportBuilder::new(&dir.path().join("r"), RunMeta::default()).unwrap();
        // Row 87 has pixels whose dithered bit the fault flips.
        for imp in [&clean, &faulty] {
            let render = Render {
                label: imp.label(),
                ..Render::default()
            };
            builder
                .add_render(render, row_render(imp.as_ref(), 87))
                .unwrap();
        }
        let (a, b) = (clean.label(), faulty.label());
        let localizer = pixel_localizer(
            Some(clean.as_ref()),
            Some(faulty.as_ref()),
            Some(clean.as_ref()),
            [&a, &b],
        );
        let pair = builder
            .add_pair(&a, &b, localizer, |x, y| pixel_repro(&a, &b, true, x, y))
            .unwrap();
        assert!(!pair.divergences.is_empty());
        assert!(pair
            .localization
            .starts_with("first divergent Float316 operation"));
        for d in &pair.divergences {
            let op = d.first_op.as_deref().unwrap();
            assert!(op.starts_with("mul("), "pixel ({}, {}): {op}", d.x, d.y);
            assert!(op.contains("(ref-f316+mul-keep-low)"), "{op}");
            assert_eq!(
                d.repro,
                format!(
                    "harness localize ref-f316 ref-f316+mul-keep-low --pixel {},{}",
                    d.x, d.y
                )
            );
        }
    }

    #[test]
    fn pairs_with_a_float_side_or_the_main_screen_say_why_they_are_not_localized() {
        let cast = Cast::builtin();
        let f316 = cast.open("ref-f316").unwrap();
        let f64 = cast.open("ref-f64").unwrap();
        let (a, b) = ("ref-f316".to_string(), "ref-f64".to_string());
        let why = |l: PixelLocalizer| match l {
            PixelLocalizer::Impossible(why) => why,
            PixelLocalizer::Traced { .. } => panic!("traced"),
        };
        let float = pixel_localizer(
            Some(f316.as_ref()),
            Some(f64.as_ref()),
            Some(f316.as_ref()),
            [&a, &b],
        );
        assert!(why(float).starts_with("ref-f64 computes with f64"));
        let main = JACK_MAIN.to_string();
        let screen = pixel_localizer(Some(f316.as_ref()), None, Some(f316.as_ref()), [&a, &main]);
        assert!(why(screen).contains("no per-pixel trace"));
        let float_screen =
            pixel_localizer(Some(f64.as_ref()), None, Some(f316.as_ref()), [&b, &main]);
        assert!(why(float_screen).starts_with("ref-f64 computes with f64"));
        assert_eq!(entry_point(JACK_MAIN), "jack");
        assert_eq!(
            pixel_repro("ref-f316", "ref-f64", false, 3, 4),
            "harness diff ref-f316 ref-f64 --vectors repro/pixel-3-4.json"
        );
    }
}
