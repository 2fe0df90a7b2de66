//! The nightly's steps, in the order they run ([`all`]); the explain and
//! scenes steps have files of their own, and every step implements
//! [`Step`](super::step::Step).

use super::pairs::{self, PlannedPair};
use super::step::Step;
use super::{Night, Opened, Rendered};
use anyhow::{Context, Result};
use common::image_consts::{HEIGHT, WIDTH};
use common::Op;
use harness::cast::{OpenError, VariantRole};
use harness::compare::{Comparison as LevelComparison, Divergence, Policy, Thresholds};
use harness::exhaustive;
use harness::implementation::{ImplError, Implementation, Numbers};
use harness::localize::{localizable, localize};
use harness::progress;
use harness::runner::{self, ImplRun, RunOptions};
use harness::selftest;
use harness::verdict::{self, Missing};
use harness_report::images::Grid;
use harness_report::measure::{self, FullRender};
use harness_report::model::{
    BenchRow, CaseCount, Comparison, DivergenceExample, ErrorFigures, ImplStatus, Render, SelfTest,
};
use harness_report::stability;
use harness_report::{RenderImages, BIT_EXACT, ERROR_FIGURES};
use std::time::Instant;
use vectors::gen::testfloat::{self, CaseLevel};
use vectors::VectorSet;

/// Every step, in order.
pub fn all() -> Vec<Box<dyn Step>> {
    vec![
        Box::new(Open),
        Box::new(Levels { set: "ops-nightly" }),
        Box::new(Levels { set: "sdf-nightly" }),
        Box::new(Levels {
            set: "pixels-nightly",
        }),
        Box::new(Unary),
        Box::new(TestFloat),
        Box::new(SelfTestStep),
        Box::new(Renders),
        Box::new(Screens),
        Box::new(Pairs),
        Box::new(super::explain::Explain),
        Box::new(super::scenes::Scenes),
        Box::new(super::tuned::Tuned),
        Box::new(Speed),
    ]
}

/// The keys `--steps` accepts.
pub fn keys() -> Vec<&'static str> {
    let mut keys: Vec<&'static str> = all()
        .iter()
        .filter(|s| !s.always())
        .map(|s| s.key())
        .collect();
    keys.dedup();
    keys
}

/// Examples of divergences kept per comparison in the report.
const EXAMPLES: usize = 5;

/// The night's shard of `set`, its name saying which shard it is.
fn sharded(night: &Night<'_>, set: VectorSet) -> VectorSet {
    let shard = night.options.shard;
    if shard == vectors::Shard::WHOLE {
        return set;
    }
    let name = format!("{} (shard {shard})", set.name);
    VectorSet {
        name,
        ..shard.of_set(&set)
    }
}

fn run_options(night: &Night<'_>) -> RunOptions {
    RunOptions {
        progress: night.options.progress,
    }
}

/// Open every implementation of the cast (or those asked for, with the
/// oracle and the tracer); those that cannot run here are listed with the
/// reason, never faked.
struct Open;

impl Step for Open {
    fn key(&self) -> &'static str {
        "open"
    }

    fn name(&self) -> String {
        "open implementations".into()
    }

    fn always(&self) -> bool {
        true
    }

    fn run(&self, night: &mut Night<'_>) -> Result<()> {
        let cast = night.cast;
        let (oracle, tracer) = (&cast.oracle().name, &cast.tracer().name);
        let wanted: Vec<_> = cast
            .entries()
            .iter()
            .filter(|e| {
                night.options.implementations.as_ref().is_none_or(|names| {
                    names.contains(&e.name) || &e.name == oracle || &e.name == tracer
                })
            })
            .collect();
        let bar = progress::show(
            progress::items(wanted.len() as u64, "open", "implementations"),
            night.options.progress,
        );
        for entry in wanted {
            bar.set_message(entry.name.clone());
            let start = Instant::now();
            let opened = cast.open(&entry.name);
            let open_s = start.elapsed().as_secs_f64();
            let mut status = ImplStatus {
                name: entry.name.clone(),
                available: opened.is_ok(),
                open_s,
                ..ImplStatus::default()
            };
            let failed = match opened {
                Ok(imp) => {
                    night.opened.push(Opened { entry, imp, open_s });
                    None
                }
                Err(e) => {
                    status.note = Some(e.to_string());
                    Some(e)
                }
            };
            night.builder.report_mut().implementations.push(status);
            if let Some(e) = failed {
                let missing = match &e {
                    OpenError::Impl(ImplError::Unavailable(_)) => Missing::Unavailable,
                    _ => Missing::Failed,
                };
                night.not_compared(
                    format!("{} (open)", entry.name),
                    missing,
                    verdict::one_line(&e.to_string()),
                );
            }
            bar.inc(1);
        }
        bar.finish_and_clear();
        Ok(())
    }
}

/// One committed nightly set through every opened implementation: the
/// bit-exact group compared bit for bit with the tracer, the float group
/// against the oracle (SDF points and pixels), the examples of bit-exact
/// divergences localized, and the stability rows of the set's categories.
struct Levels {
    set: &'static str,
}

impl Step for Levels {
    fn key(&self) -> &'static str {
        "levels"
    }

    fn name(&self) -> String {
        self.set.into()
    }

    fn run(&self, night: &mut Night<'_>) -> Result<()> {
        let set = vectors::load_named(self.set)
            .with_context(|| format!("the committed set {}", self.set))?;
        let set = sharded(night, set);
        let cast = night.cast;
        let oracle = cast.oracle().name.as_str();
        let tracer = cast.tracer().name.as_str();
        let everyone: Vec<&dyn Implementation> = night
            .opened
            .iter()
            .map(|o| o.imp.as_ref())
            .filter(|i| i.supports(set.level))
            .collect();
        let runs = runner::run(&everyone, &set, run_options(night));
        let runs_of = |names: &[&str]| -> Vec<ImplRun> {
            names
                .iter()
                .filter_map(|n| runs.iter().find(|r| r.label == *n).cloned())
                .collect()
        };
        let bit_exact: Vec<&str> = cast
            .bit_exact_group()
            .iter()
            .map(|e| e.name.as_str())
            .collect();
        let mut groups = vec![runs_of(&bit_exact)];
        if set.level != vectors::Level::Ops {
            groups.push(runs_of(&float_group(night)));
        }
        let mut exact = Vec::new();
        for group_runs in groups {
            if group_runs.len() < 2 {
                continue;
            }
            let level = runner::level_report(&set, &group_runs);
            record_failures(night, &level);
            let rows: Vec<Comparison> = level
                .comparisons
                .iter()
                .map(|c| summarise(night, c, &set.name))
                .collect();
            night.builder.report_mut().comparisons.extend(rows);
            exact.extend(
                level
                    .comparisons
                    .into_iter()
                    .filter(|c| c.policy == Policy::Exact),
            );
        }
        let mut unwritten = Vec::new();
        let builder = &night.builder;
        let bases = stability::Bases {
            oracle,
            bit_exact: tracer,
        };
        let rows = stability::rows(&set, &runs, &exact, bases, |imp, vector| {
            match builder.write_repro(vector) {
                Ok(file) => Some(format!("harness diff {imp} {oracle} --vectors {file}")),
                Err(e) => {
                    unwritten.push(format!("repro file for {vector}: {e:#}"));
                    None
                }
            }
        });
        let report = night.builder.report_mut();
        report.stability.extend(rows);
        report.problems.extend(unwritten);
        Ok(())
    }
}

/// The float group: the oracle first, every opened implementation that
/// does not compute with Float316, then the tracer.
fn float_group<'c>(night: &Night<'c>) -> Vec<&'c str> {
    let cast = night.cast;
    let oracle = cast.oracle().name.as_str();
    std::iter::once(oracle)
        .chain(night.names_where(|e| !e.bit_exact() && e.name != oracle))
        .chain([cast.tracer().name.as_str()])
        .collect()
}

/// The unary operations over every normalised input, the tracer against
/// each other opened Float316 implementation (a slow one takes every N-th
/// input).
struct Unary;

impl Step for Unary {
    fn key(&self) -> &'static str {
        "unary"
    }

    fn name(&self) -> String {
        "unary checks".into()
    }

    fn run(&self, night: &mut Night<'_>) -> Result<()> {
        let tracer = night.cast.tracer().name.as_str();
        let slow_step = night.options.slow_unary_step.max(1);
        let others: Vec<(&str, usize)> = night
            .opened
            .iter()
            .filter(|o| {
                o.entry.bit_exact()
                    && o.entry.name != tracer
                    && o.entry.answers(vectors::Level::Ops)
            })
            .map(|o| {
                (
                    o.entry.name.as_str(),
                    if o.entry.slow { slow_step } else { 1 },
                )
            })
            .collect();
        for (other, step) in others {
            let pair = night.opened_of(&[tracer, other]);
            if pair.len() < 2 {
                continue;
            }
            for level in exhaustive::unary(&pair, step, run_options(night)) {
                record_failures(night, &level);
                for c in &level.comparisons {
                    let mut row = summarise(night, c, &level.set);
                    row.level = "unary-exhaustive".into();
                    row.scope = match step {
                        1 => format!("{} (every input)", level.set),
                        n => format!("{} (one input in {n})", level.set),
                    };
                    night.builder.report_mut().comparisons.push(row);
                }
            }
        }
        Ok(())
    }
}

/// The TestFloat-style cases of every operation (docs/coverage.md), levels
/// 1 and 2, through the tracer and every other opened Float316
/// implementation, compared bit for bit with the tracer; the count of
/// cases per operation and level goes into the report whether or not a
/// second implementation opened.
struct TestFloat;

impl Step for TestFloat {
    fn key(&self) -> &'static str {
        "testfloat"
    }

    fn name(&self) -> String {
        "testfloat levels 1 and 2".into()
    }

    fn run(&self, night: &mut Night<'_>) -> Result<()> {
        let tracer = night.cast.tracer().name.as_str();
        let names: Vec<&str> = std::iter::once(tracer)
            .chain(night.names_where(|e| {
                e.bit_exact() && e.name != tracer && e.answers(vectors::Level::Ops)
            }))
            .collect();
        for level in CaseLevel::ALL {
            for op in Op::ALL {
                let set = sharded(night, testfloat::set(&[op], level, testfloat::DEFAULT_SEED));
                let impls = night.opened_of(&names);
                let report = runner::diff_set(&impls, &set, run_options(night));
                record_failures(night, &report);
                let rows: Vec<Comparison> = report
                    .comparisons
                    .iter()
                    .map(|c| Comparison {
                        level: level.table_category().into(),
                        ..summarise(night, c, &set.name)
                    })
                    .collect();
                let answered = report
                    .runs
                    .iter()
                    .filter(|r| r.error.is_none())
                    .map(|r| r.label.clone())
                    .collect();
                let built = night.builder.report_mut();
                built.testfloat.push(CaseCount {
                    op: op.to_string(),
                    level: level.number(),
                    cases: set.vectors.len() as u64,
                    implementations: answered,
                    divergences: rows.iter().map(|r| r.divergences).sum(),
                });
                built.comparisons.extend(rows);
            }
        }
        Ok(())
    }
}

/// The fault self-test (`harness selftest`).
struct SelfTestStep;

impl Step for SelfTestStep {
    fn key(&self) -> &'static str {
        "selftest"
    }

    fn name(&self) -> String {
        "self-test".into()
    }

    fn run(&self, night: &mut Night<'_>) -> Result<()> {
        let results = selftest::run_all(night.cast);
        night.builder.report_mut().selftest = Some(SelfTest {
            passed: results.iter().all(|r| r.passed),
            lines: results.iter().map(|r| r.to_string()).collect(),
        });
        Ok(())
    }
}

/// The whole image with every opened implementation and the tracer's
/// precision variants; a render that fails fails the night.
struct Renders;

impl Step for Renders {
    fn key(&self) -> &'static str {
        "renders"
    }

    fn name(&self) -> String {
        "renders".into()
    }

    fn run(&self, night: &mut Night<'_>) -> Result<()> {
        let spec = measure::spec_image()?;
        let tracer = night.cast.tracer();
        let variant_labels: Vec<String> = tracer
            .variants
            .iter()
            .filter(|v| v.role == VariantRole::Precision)
            .map(|v| format!("{}+{}", tracer.name, v.name))
            .collect();
        let progress = night.options.progress;
        let entries: Vec<(String, bool, f64, Option<f64>)> = night
            .opened
            .iter()
            .map(|o| {
                // Float316 renders are judged bit for bit against the
                // tracer's; their distance from the oracle is measured.
                let numbers = o.imp.numbers();
                let limit = (numbers != Numbers::Float316)
                    .then(|| Thresholds::for_subject(numbers).max_flip_fraction);
                (o.entry.name.clone(), o.entry.bit_exact(), o.open_s, limit)
            })
            .collect();
        for (label, bit_exact, open_s, limit) in entries {
            let imp = night.find(&label).context("an opened implementation")?;
            let result = measure::render_with(imp, open_s, progress);
            add(
                night,
                &label,
                result.map(|(full, _)| full),
                &spec,
                bit_exact,
                limit,
            );
        }
        for label in variant_labels {
            let start = Instant::now();
            let result = night
                .cast
                .open(&label)
                .map_err(anyhow::Error::from)
                .and_then(|imp| {
                    let full = measure::render_with(
                        imp.as_ref(),
                        start.elapsed().as_secs_f64(),
                        progress,
                    )?
                    .0;
                    night.variants.push(imp);
                    Ok(full)
                });
            add(night, &label, result, &spec, false, None);
        }
        Ok(())
    }
}

/// Add a render, or record it as failed. `flip_limit` is the fraction of
/// pixels it may flip against the oracle (`None`: not judged).
fn add(
    night: &mut Night<'_>,
    label: &str,
    result: Result<FullRender>,
    spec: &Grid<bool>,
    bit_exact: bool,
    flip_limit: Option<f64>,
) {
    let added = result.and_then(|full| {
        add_render(night, &full, spec)?;
        if let Some(costs) = &full.costs {
            if night.builder.report().cost_map.is_none() {
                night.builder.set_cost_map(costs)?;
            }
        }
        Ok(())
    });
    match added {
        Ok(()) => night.rendered.push(Rendered {
            label: label.to_string(),
            bit_exact,
            screen_of: None,
            flip_limit,
        }),
        Err(e) => night.not_compared(format!("render {label}"), Missing::Failed, format!("{e:#}")),
    }
}

/// The slow path: the screen each opened implementation that can run its
/// whole program draws (the Jack program from `Main.main`, SPACE scripted,
/// with its Float316 counters) must equal the image its entry points
/// computed.
struct Screens;

/// The label of the screen of `label`'s whole program.
pub fn screen_label(label: &str) -> String {
    format!("{label}-main")
}

impl Step for Screens {
    fn key(&self) -> &'static str {
        "screens"
    }

    fn name(&self) -> String {
        "program screens".into()
    }

    fn run(&self, night: &mut Night<'_>) -> Result<()> {
        let spec = measure::spec_image()?;
        let progress = night.options.progress;
        let labels: Vec<(String, bool)> = night
            .opened
            .iter()
            .map(|o| (o.entry.name.clone(), o.entry.bit_exact()))
            .collect();
        for (label, bit_exact) in labels {
            let expected = night
                .builder
                .report()
                .renders
                .iter()
                .find(|r| r.label == label)
                .and_then(|r| r.vm_instructions);
            let imp = night.find(&label).context("an opened implementation")?;
            let start = Instant::now();
            let Some(screen) = imp.program_screen(expected, progress) else {
                continue;
            };
            let screen_label = screen_label(&label);
            let result = screen.map_err(anyhow::Error::from).and_then(|bitmap| {
                Ok(FullRender {
                    label: screen_label.clone(),
                    setup_s: 0.0,
                    render_s: start.elapsed().as_secs_f64(),
                    images: RenderImages {
                        bits: Grid::new(WIDTH, HEIGHT, bitmap.white)?,
                        shades: None,
                        traps: None,
                    },
                    costs: None,
                })
            });
            add(night, &screen_label, result, &spec, bit_exact, None);
            if let Some(r) = night
                .rendered
                .last_mut()
                .filter(|r| r.label == screen_label)
            {
                r.screen_of = Some(label.clone());
            }
        }
        Ok(())
    }
}

/// Every render against the tracer and against the oracle, each program
/// screen against its entry points' image; the listed divergent pixels of
/// two Float316 sides are localized. A difference between two bit-exact
/// renders fails the night.
struct Pairs;

impl Step for Pairs {
    fn key(&self) -> &'static str {
        "pairs"
    }

    fn name(&self) -> String {
        "pairs".into()
    }

    fn run(&self, night: &mut Night<'_>) -> Result<()> {
        let cast = night.cast;
        let planned = pairs::plan(&night.rendered, &cast.tracer().name, &cast.oracle().name);
        let bar = progress::show(
            progress::items(planned.len() as u64, "pairs", "image pairs compared"),
            night.options.progress,
        );
        for pair in &planned {
            bar.set_message(format!("{} against {}", pair.a, pair.b));
            compare_pair(night, pair)?;
            bar.inc(1);
        }
        bar.finish_and_clear();
        Ok(())
    }
}

/// One planned pair into the report.
fn compare_pair(night: &mut Night<'_>, pair: &PlannedPair) -> Result<()> {
    // The localizer borrows the implementations while the builder is
    // borrowed mutably: split the night.
    let Night {
        cast,
        opened,
        variants,
        builder,
        rendered,
        ..
    } = night;
    let find = |label: &str| super::lookup(opened, variants, label);
    let tracer = cast.tracer().name.as_str();
    let (a, b) = (pair.a.as_str(), pair.b.as_str());
    let screen_of = |label: &str| {
        rendered
            .iter()
            .find(|r| r.label == label)
            .and_then(|r| r.screen_of.as_deref())
    };
    // A pixel of a screen is reproduced through its entry points (against
    // the tracer when the pair is the screen's own).
    let (ra, rb) = (screen_of(a).unwrap_or(a), screen_of(b).unwrap_or(b));
    let ra = if ra == rb { tracer } else { ra };
    let by_localize = matches!(
        (find(ra), find(rb)),
        (Some(x), Some(y)) if localizable(x, y).is_ok()
    );
    let localizer = pairs::pixel_localizer(
        [find(a), find(b)],
        find(tracer),
        [(a, screen_of(a)), (b, screen_of(b))],
    );
    let repro = |x: usize, y: usize| pairs::pixel_repro(ra, rb, by_localize, x, y);
    let listed: Vec<(usize, usize)> = builder
        .add_pair(a, b, pair.gate, localizer, repro)?
        .divergences
        .iter()
        .map(|d| (d.x as usize, d.y as usize))
        .collect();
    if !by_localize {
        for (x, y) in listed {
            builder.write_repro(&pairs::pixel(x, y))?;
        }
    }
    Ok(())
}

/// Speed against error of every render, against the oracle's.
struct Speed;

impl Step for Speed {
    fn key(&self) -> &'static str {
        "speed"
    }

    fn name(&self) -> String {
        "speed".into()
    }

    fn run(&self, night: &mut Night<'_>) -> Result<()> {
        let oracle = night.cast.oracle().name.as_str();
        if !night.rendered.iter().any(|r| r.label == oracle) {
            return Ok(());
        }
        let labels: Vec<String> = night.rendered.iter().map(|r| r.label.clone()).collect();
        for label in &labels {
            let builder = &mut night.builder;
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
                trapped: render.trapped,
            });
            builder.report_mut().speed_error.points.push(point);
        }
        Ok(())
    }
}

/// Implementations that gave no answers (or stopped before the end) on a
/// set fail the night; each is a problem of the report too.
pub(super) fn record_failures(night: &mut Night<'_>, level: &runner::LevelReport) {
    let failures: Vec<(String, ImplError)> = level
        .failures()
        .map(|(label, e)| (format!("{label} on {}", level.set), e.clone()))
        .collect();
    for (what, e) in failures {
        night.not_compared(what, Missing::of(&e), verdict::one_line(&e.to_string()));
    }
}

/// A runner comparison as a report row, its examples localized when both
/// sides are opened Float316 implementations. A Float316 subject's error
/// figures against the oracle are measured, not judged: Float316 is judged
/// bit for bit against the tracer, and its distance from f64 is what the
/// explain step accounts for.
pub(super) fn summarise(night: &Night<'_>, c: &LevelComparison, set: &str) -> Comparison {
    let tracer = night.find(&night.cast.tracer().name);
    let judged = c.policy == Policy::Exact
        || night
            .find(&c.a)
            .is_some_and(|a| a.numbers() != Numbers::Float316);
    let first_op = |d: &Divergence| {
        let (a, b, t) = (night.find(&c.a)?, night.find(&c.b)?, tracer?);
        (c.policy == Policy::Exact).then(|| match localize(a, b, t, &d.input) {
            Ok(found) => found.one_line(),
            Err(e) => format!("not localized: {e}"),
        })
    };
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
        beyond_policy: c.diverged && judged,
        findings: c.findings.clone(),
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
                first_op: first_op(d),
                repro: d.localize.clone(),
            })
            .collect(),
    }
}

/// Add one full render to the report.
fn add_render(night: &mut Night<'_>, full: &FullRender, spec: &Grid<bool>) -> Result<()> {
    let label: harness::cast::Label = full.label.parse()?;
    let identical = full
        .images
        .bits
        .positions_where(spec, |p, q| p != q)
        .map(|d| d.is_empty())
        .ok();
    let vm_instructions = full.costs.as_ref().map(|c| c.data().iter().sum());
    night.builder.add_render(
        Render {
            label: full.label.clone(),
            implementation: label.name.clone(),
            variant: (!label.variants.is_empty()).then(|| label.variants.join("+")),
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
