//! `harness tune --scene FILE [--max-flips N | --max-error E] [--out
//! TUNED.json] [--state STATE.json] [--exhaustive] [--jack-step N]
//! [--json]`: which call sites of a scene can compute a cheaper variant
//! (one Newton step, a truncated product, a floor without its nested
//! `add`, fewer march steps) without changing the picture.
//!
//! Each configuration is rendered whole by ref-f316 (`evaluate`), its cost
//! estimated from the Float316 operations it counts at costs measured on
//! the scene's generated Jack program (`cost_model`), and judged against
//! the constraint: by default no pixel whose output level differs from the
//! untuned image (the dithered picture the user sees). The search is delta
//! debugging, or every configuration with `--exhaustive` (`search`). Every
//! site left untuned comes with the pixel that forbids it, explained
//! (`reasons`). The tuned and untuned programs are then generated, run on
//! the emulator and compared with their references bit for bit
//! (`jack_check`). The tuned description and a Pareto plot of every
//! configuration tried are written; `--state` records every evaluation so
//! that a rerun skips them (`state`). The results are printed as text or
//! JSON (`report`).

mod cost_model;
mod evaluate;
mod jack_check;
mod reasons;
mod report;
mod search;
mod space;
mod state;

use anyhow::{bail, Context};
use cost_model::CostModel;
use evaluate::{Constraint, Evaluation, Evaluator};
use harness::progress;
use harness_report::plot::ParetoPoint;
use report::{RejectedSite, Report, Saving, Tuned};
use search::{Found, Judged, Rejection};
use space::Config;
use state::State;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

/// Arguments of `harness tune`.
#[derive(Debug, clap::Args)]
pub struct TuneArgs {
    /// The scene description (docs/scenes.md); its own `variants` are left
    /// out: the search starts from the untuned scene.
    #[arg(long)]
    pub scene: PathBuf,
    /// Allow at most N pixels whose output level differs from the untuned
    /// image (default 0).
    #[arg(long, value_name = "N", conflicts_with = "max_error")]
    pub max_flips: Option<u64>,
    /// Instead, allow |shade - ref-f64| up to E at every pixel.
    #[arg(long, value_name = "E")]
    pub max_error: Option<f64>,
    /// The tuned description to write, named after the file (default:
    /// STEM-tuned.json in the current directory); the Pareto plot goes
    /// beside it (STEM-tuned-pareto.svg).
    #[arg(long, value_name = "TUNED.json")]
    pub out: Option<PathBuf>,
    /// Record every evaluated configuration in this file, and skip those it
    /// already holds (a rerun, or a run stopped half way).
    #[arg(long, value_name = "STATE.json")]
    pub state: Option<PathBuf>,
    /// Try every configuration instead of delta debugging (refused above
    /// 20 000 configurations).
    #[arg(long)]
    pub exhaustive: bool,
    /// Check the generated Jack programs on every N-th pixel of every N-th
    /// row (1: every pixel).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=256))]
    pub jack_step: u32,
    /// Measure the per-operation costs on every N-th pixel of every N-th row.
    #[arg(long, default_value_t = 8, value_parser = clap::value_parser!(u32).range(1..=256))]
    pub calibration_step: u32,
    /// Print the results as JSON.
    #[arg(long)]
    pub json: bool,
}

/// The most configurations `--exhaustive` enumerates.
pub const EXHAUSTIVE_LIMIT: u64 = 20_000;

/// The constraint the arguments ask for.
fn constraint(args: &TuneArgs) -> anyhow::Result<Constraint> {
    Ok(match (args.max_flips, args.max_error) {
        (_, Some(e)) if !(e.is_finite() && e >= 0.0) => {
            bail!("--max-error: {e} is not a finite number of 0 or more")
        }
        (_, Some(e)) => Constraint::MaxError(e),
        (n, None) => Constraint::Flips(n.unwrap_or(0)),
    })
}

/// `DIR/STEM-tuned.json` for `--out`'s default: STEM-tuned.json here.
fn default_out(scene: &Path) -> PathBuf {
    let stem = scene.file_stem().unwrap_or_default().to_string_lossy();
    PathBuf::from(format!("{stem}-tuned.json"))
}

/// The Pareto plot beside `out`: `STEM-pareto.svg`.
fn plot_path(out: &Path) -> PathBuf {
    let stem = out.file_stem().unwrap_or_default().to_string_lossy();
    out.with_file_name(format!("{stem}-pareto.svg"))
}

/// Run `harness tune`. Exit 0; 1 when a generated program's image differs
/// from its reference's; 2 on bad input.
pub fn run(args: TuneArgs) -> anyhow::Result<ExitCode> {
    let constraint = constraint(&args)?;
    let out = args.out.clone().unwrap_or_else(|| default_out(&args.scene));
    let plot = plot_path(&out);
    crate::output::check_file(&out, "--out")?;
    crate::output::check_file(&plot, "--out (its Pareto plot)")?;
    if let Some(s) = &args.state {
        crate::output::check_file(s, "--state")?;
    }
    // Checked first, so that a bad file is refused naming its field.
    scene::load(&args.scene)?;
    let mut untuned_description: serde_json::Value =
        serde_json::from_str(&scene::read(&args.scene)?)
            .with_context(|| args.scene.display().to_string())?;
    if let Some(top) = untuned_description.as_object_mut() {
        top.remove("variants");
    }
    let untuned_checked = scene::parse(&untuned_description.to_string())?;
    let sites = space::searched(&scene::lower(
        &untuned_checked,
        scene::Formulation::Float316,
    ));
    let configurations = space::size(&sites);
    if args.exhaustive && configurations > EXHAUSTIVE_LIMIT {
        bail!(
            "--exhaustive: {} has {configurations} configurations over {} sites, more than \
             {EXHAUSTIVE_LIMIT}; leave --exhaustive out to search by delta debugging",
            args.scene.display(),
            sites.len()
        );
    }
    let untuned = Config::new();
    let mut state = State::open(
        args.state.as_deref(),
        state::scene_hash(&untuned_description),
    )?;
    let shown = progress::wanted();
    let stage = |what: &str| {
        if shown {
            eprintln!("{what}");
        }
    };
    stage("rendering the untuned scene on ref-f316 and ref-f64");
    let evaluator = Evaluator::new(untuned_description.clone(), &untuned_checked)?;
    let (base_ref, _, base_counts) = evaluator.base();
    let base_sources = scene_jack::emit(base_ref.program())
        .with_context(|| format!("{}: generating its Jack program", args.scene.display()))?;
    stage("measuring per-operation costs on the generated Jack programs");
    let every_variant: Config = sites
        .iter()
        .filter(|s| !s.is_loop)
        .map(|s| (s.name.clone(), s.options[0]))
        .collect();
    let variants_ref = evaluator.reference(&every_variant)?;
    let variants_sources = scene_jack::emit(variants_ref.program()).with_context(|| {
        format!(
            "{}: generating its Jack program with every operation site tuned",
            args.scene.display()
        )
    })?;
    let model = CostModel::calibrate(
        (base_ref, &base_sources),
        (&variants_ref, &variants_sources),
        args.calibration_step,
    )?;
    if state.get(&untuned).is_none() {
        state.insert(untuned.clone(), evaluator.base_evaluation())?;
    }
    let base_cost = model.whole_image(base_counts);

    let start = Instant::now();
    let (found, rendered) = search(
        &args, &sites, &evaluator, &model, constraint, base_cost, &mut state,
    )?;
    let search_s = start.elapsed().as_secs_f64();

    let rejected = explain_rejections(&found, &evaluator, &model, constraint, &state, shown)?;
    stage("checking the untuned and tuned Jack programs against ref-f316");
    let jack_untuned = jack_check::check(
        &args.scene,
        evaluator.checked(&untuned)?,
        base_ref,
        evaluator.base().1,
        args.jack_step,
    )?;
    let jack_tuned = if found.best.is_empty() {
        None
    } else {
        let (d, image) = evaluator.image(&found.best)?;
        Some(jack_check::check(
            &args.scene,
            evaluator.checked(&found.best)?,
            &d,
            &image,
            args.jack_step,
        )?)
    };

    let tuned_eval = state
        .get(&found.best)
        .cloned()
        .context("the best configuration was evaluated")?;
    // Named after its file, so that it does not pass for the untuned scene.
    let mut tuned_description = evaluator.description(&found.best);
    tuned_description["name"] = out
        .file_stem()
        .unwrap_or_default()
        .to_string_lossy()
        .into_owned()
        .into();
    let points = pareto_points(&state, &model, &found.best, constraint);
    let svg = harness_report::plot::pareto(&points)?;
    harness_report::atomic::write_files(&[
        (
            out.clone(),
            format!("{}\n", serde_json::to_string_pretty(&tuned_description)?).into_bytes(),
        ),
        (plot.clone(), svg.into_bytes()),
    ])?;

    let jack = report::jack_figures(&jack_untuned, jack_tuned.as_ref());
    let report = Report {
        scene: args.scene.display().to_string(),
        name: untuned_description["name"]
            .as_str()
            .unwrap_or_default()
            .to_string(),
        constraint: constraint.describe(),
        search: if args.exhaustive {
            "exhaustive"
        } else {
            "delta debugging"
        },
        sites: sites.len(),
        configurations,
        judged: found.judged,
        rendered,
        known: found.judged - rendered,
        search_s,
        tuned: found
            .best
            .iter()
            .map(|(site, choice)| Tuned {
                site: site.clone(),
                variant: choice.to_string(),
            })
            .collect(),
        flips: tuned_eval.flips,
        shades: tuned_eval.shades,
        max_error: tuned_eval.max_error,
        untuned_max_error: evaluator.base_evaluation().max_error,
        estimated: Saving::new(
            (model.per_pixel(base_counts), base_cost),
            (model.per_pixel(&tuned_eval.counts), found.cost),
        ),
        model,
        jack,
        rejected,
        out: out.display().to_string(),
        plot: plot.display().to_string(),
    };
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print!("{}", report::text(&report));
    }
    let bad = report.jack.tuned_mismatches + report.jack.untuned_mismatches;
    Ok(if bad > 0 {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}

/// Run the search the arguments ask for; also how many configurations were
/// rendered (not found in the state).
fn search(
    args: &TuneArgs,
    sites: &[space::Site],
    evaluator: &Evaluator,
    model: &CostModel,
    constraint: Constraint,
    base_cost: f64,
    state: &mut State,
) -> anyhow::Result<(Found, usize)> {
    let shown = progress::wanted();
    let length = if args.exhaustive {
        space::size(sites)
    } else {
        sites.iter().map(|s| s.options.len().min(4) as u64).sum()
    };
    let bar = progress::show(progress::items(length, "tune", "configurations"), shown);
    let mut rendered = 0;
    let mut judge = |c: &Config| -> anyhow::Result<Judged> {
        if bar.position() >= bar.length().unwrap_or(0) {
            bar.inc_length(1);
        }
        let e = match state.get(c) {
            Some(e) => e.clone(),
            None => {
                bar.set_message(space::key(c));
                let e = evaluator.evaluate(c)?;
                state.insert(c.clone(), e.clone())?;
                rendered += 1;
                e
            }
        };
        bar.inc(1);
        Ok(Judged {
            passes: constraint.holds(&e),
            cost: model.whole_image(&e.counts),
        })
    };
    let found = if args.exhaustive {
        search::exhaustive(sites, base_cost, &mut judge)?
    } else {
        let budget = constraint != Constraint::Flips(0);
        search::delta_debug(sites, base_cost, budget, &mut judge)?
    };
    bar.finish_and_clear();
    Ok((found, rendered))
}

/// Each rejected site with the pixel that forbids it, explained.
fn explain_rejections(
    found: &Found,
    evaluator: &Evaluator,
    model: &CostModel,
    constraint: Constraint,
    state: &State,
    shown: bool,
) -> anyhow::Result<Vec<RejectedSite>> {
    let bar = progress::show(
        progress::items(found.rejected.len() as u64, "explain", "rejected sites"),
        shown,
    );
    let evaluation = |c: &Config| -> anyhow::Result<Evaluation> {
        state
            .get(c)
            .cloned()
            .with_context(|| format!("{} was judged", space::key(c)))
    };
    let mut out = Vec::new();
    for r in &found.rejected {
        let (config, reason) = match &r.why {
            Rejection::Fails { config } => (config, "fails"),
            Rejection::NoSaving { config, .. } => (config, "no saving"),
        };
        let e = evaluation(config)?;
        let pixel = match (&r.why, constraint.forbidding_pixel(&e)) {
            (Rejection::Fails { .. }, Some(p)) => Some(reasons::forbidding(evaluator, config, p)?),
            _ => None,
        };
        let mut others = config.clone();
        let variant = others
            .remove(&r.site)
            .map_or_else(String::new, |c| c.to_string());
        out.push(RejectedSite {
            site: r.site.clone(),
            variant,
            on: (!others.is_empty()).then(|| space::key(&others)),
            reason,
            flips: e.flips,
            max_error: e.max_error,
            per_pixel: model.per_pixel(&e.counts),
            pixel,
        });
        bar.inc(1);
    }
    bar.finish_and_clear();
    Ok(out)
}

/// Every configuration of the state as a point of the Pareto plot.
fn pareto_points(
    state: &State,
    model: &CostModel,
    best: &Config,
    constraint: Constraint,
) -> Vec<ParetoPoint> {
    state
        .records()
        .iter()
        .map(|r| ParetoPoint {
            per_pixel: model.per_pixel(&r.evaluation.counts),
            flips: r.evaluation.flips,
            max_error: r.evaluation.max_error,
            passes: constraint.holds(&r.evaluation),
            chosen: &r.config == best,
            untuned: r.config.is_empty(),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_outputs_default_beside_the_current_directory() {
        let out = default_out(Path::new("vectors/scenes/seed.json"));
        assert_eq!(out, PathBuf::from("seed-tuned.json"));
        assert_eq!(plot_path(&out), PathBuf::from("seed-tuned-pareto.svg"));
        assert_eq!(
            plot_path(Path::new("/tmp/x/a.json")),
            PathBuf::from("/tmp/x/a-pareto.svg")
        );
    }
}
