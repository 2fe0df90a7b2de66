//! Why a lower-precision implementation differs from the f64 oracle: for
//! one pixel (or SDF query), its class and root cause.
//!
//! The pixel runs twice through the reference's pipeline: in the low
//! precision with every value shadowed in f64 ([`reference::ShadowEngine`]:
//! operations with their local and accumulated errors and call paths), and
//! in f64 as `ref-f64` computes it. Both runs record every branch decision
//! ([`reference::Decision`]); the first one where they part classifies the
//! pixel:
//! - a decision before the dither comparison (march hit or step count,
//!   miss, shadow, checker parity, `union`, the clamps): a *control-flow
//!   divergence*;
//! - only the dither comparison, the shades within [`THRESHOLD_MARGIN`] of
//!   each other (so both lie that close to the pixel's threshold): a
//!   *threshold flip*;
//! - only the dither comparison with shades further apart, or no decision
//!   at all: *accumulated error*.
//!
//! The root causes are the sites whose own rounding contributes most of the
//! error that matters ([`reference::blame`]): at a changed decision, the
//! error of its operands (the margin of the comparison); without one, the
//! error of the shade.
//!
//! An explanation is that of a reference implementation (`ref-f316` with
//! its variants, `ref-f32`); it holds for any implementation that agrees
//! with it bit for bit, which [`holds_for`] checks.

mod story;

use crate::implementation::{Implementation, Numbers};
use anyhow::{bail, Context, Result};
use common::{Outcome, F316};
use rayon::prelude::*;
use reference::{
    blame, Decision, DecisionRecord, Described, Follow, RefImpl, Reference, Settings,
    ShadowOptions, ShadowRun, SiteKey, Variant,
};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

pub use story::{story, summary_text};

/// Two shades closer than this (one dither level, 1/64) whose dithered
/// bits differ only at the dither comparison are a threshold flip.
pub const THRESHOLD_MARGIN: f64 = 1.0 / 64.0;

/// Root causes kept per explanation.
pub const ROOT_CAUSES: usize = 3;

/// The label of the oracle explanations are against.
pub const ORACLE: &str = "ref-f64";

/// What kind of difference a pixel shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Class {
    /// Only the dither comparison changed, the shades being close.
    ThresholdFlip,
    /// A branch decision before the dither comparison changed.
    ControlFlow,
    /// No decision changed before the output, which differs by more than
    /// the threshold margin (or without a flip).
    Accumulated,
    /// The two runs agree.
    Agree,
    /// A run trapped, or the decision sequences part without a decision
    /// changing (never expected: reported, not hidden).
    Unexplained,
}

impl Class {
    /// Every class, in report order.
    pub const ALL: [Class; 5] = [
        Class::ThresholdFlip,
        Class::ControlFlow,
        Class::Accumulated,
        Class::Agree,
        Class::Unexplained,
    ];

    /// Its name in reports.
    pub const fn name(self) -> &'static str {
        match self {
            Class::ThresholdFlip => "threshold flip",
            Class::ControlFlow => "control-flow divergence",
            Class::Accumulated => "accumulated error",
            Class::Agree => "agree",
            Class::Unexplained => "unexplained",
        }
    }
}

impl std::fmt::Display for Class {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// One side of a decision.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct DecisionSide {
    pub taken: bool,
    /// Its operands (`gt(a, b)`: `[a, b]`).
    pub operands: [f64; 2],
}

/// The first decision where the two runs part.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DecisionChange {
    pub decision: Decision,
    /// Its call path (`pixel(3,4) > shadow`).
    pub path: String,
    /// The march step, when it lies in one.
    pub step: Option<u32>,
    /// Its position among the run's decisions.
    pub index: usize,
    /// The low precision's side, and the shadows of its operands.
    pub low: DecisionSide,
    pub low_shadows: [f64; 2],
    /// The oracle's side.
    pub oracle: DecisionSide,
}

/// A root cause: a site and its worst operation.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RootCause {
    /// The operation and its collapsed call path.
    pub site: SiteKey,
    /// How many operations the site ran.
    pub count: usize,
    /// Its share of the error (first order; 1 = all of it).
    pub share: f64,
    /// Its worst operation's full call path.
    pub path: String,
    /// Operands and result of that operation: (low precision, shadow).
    pub operands: Vec<(f64, f64)>,
    pub result: (f64, f64),
    /// Its local error (against the f64 operation on the same operands).
    pub local_error: f64,
    /// Its accumulated error (against its shadow).
    pub accumulated_error: f64,
    /// Leading bits that cancel in it (`add`, `sub`).
    pub cancelled_bits: f64,
}

/// The answers of the two sides.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Answers {
    /// The output's name (`shade`, `sd`).
    pub output: String,
    pub low: f64,
    /// The low precision run's shadow of it.
    pub low_shadow: f64,
    pub oracle: f64,
    /// Dithered bits, for a pixel.
    pub low_white: Option<bool>,
    pub oracle_white: Option<bool>,
    /// The pixel's dither threshold (white above it), for a pixel.
    pub threshold: Option<f64>,
}

/// Why one input differs between a lower precision and the oracle.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Explanation {
    /// `pixel(x,y)` or `sdf(x,y,z)`.
    pub input: String,
    /// The reference implementation explained (`ref-f316+newton-1`).
    pub low: String,
    pub oracle: String,
    pub class: Class,
    /// Why, in one sentence.
    pub why: String,
    pub answers: Option<Answers>,
    /// The first decision where the runs part (for a threshold flip, the
    /// dither comparison itself).
    pub decision: Option<DecisionChange>,
    /// The error the root causes are ranked by: the decision's margin, or
    /// the output's error (low minus oracle).
    pub error: f64,
    /// What that error is of.
    pub error_of: String,
    /// The largest contributors to it, largest first.
    pub causes: Vec<RootCause>,
    /// Sites flipped to find them, and how many of those runs could not
    /// measure the error (they trapped, or no longer reached the decision).
    pub sites: usize,
    pub unmeasured: usize,
}

impl Explanation {
    /// Class and top root cause in one line, for report tables.
    pub fn one_line(&self) -> String {
        let cause = self.causes.first().map_or_else(
            || "no operation contributes".to_string(),
            |c| format!("root cause {} ({:.0}%)", c.site, 100.0 * c.share),
        );
        match (&self.decision, self.class) {
            (Some(d), Class::ControlFlow) => {
                format!("{} at {} ({}); {cause}", self.class, d.decision, d.path)
            }
            (_, Class::Unexplained) => format!("{}: {}", self.class, self.why),
            _ => format!("{}; {cause}", self.class),
        }
    }

    /// The absolute shade (or distance) error, when both sides answered.
    pub fn output_error(&self) -> Option<f64> {
        self.answers.as_ref().map(|a| (a.low - a.oracle).abs())
    }
}

/// Explains inputs of one reference implementation against ref-f64.
#[derive(Clone, Debug)]
pub struct Explainer {
    label: String,
    low: Subject,
    oracle: Subject,
}

/// What an explainer runs: the hand-written seed scene, or a scene made
/// from its description (the interpreter reports the same decisions).
#[derive(Clone, Debug)]
enum Subject {
    Seed(Box<Reference>),
    Scene(Box<Described>),
}

impl Subject {
    fn shadow_pixel(&self, x: usize, y: usize, options: &ShadowOptions) -> ShadowRun {
        match self {
            Subject::Seed(r) => r.shadow_pixel(x, y, options),
            Subject::Scene(d) => d.shadow_pixel(x as u32, y as u32, options),
        }
    }

    fn shadow_sdf(&self, p: [F316; 3], options: &ShadowOptions) -> ShadowRun {
        match self {
            Subject::Seed(r) => r.shadow_sdf(p, options),
            Subject::Scene(d) => d.shadow_sdf(p, options),
        }
    }
}

/// The implementation and settings of a reference label.
fn parse_label(label: &str) -> Result<(RefImpl, Settings)> {
    let mut parts = label.split('+');
    let name = parts.next().unwrap_or_default();
    let implementation: RefImpl = name.parse()?;
    if implementation == RefImpl::F64 {
        bail!("{label} is the oracle itself");
    }
    let settings = parts.try_fold(Settings::default(), |s, v| {
        let variant: Variant = v.parse()?;
        if variant == Variant::Fma {
            bail!(
                "{label}: the shadow engine rounds every product and sum apart, so it cannot \
                 explain contracted multiply-adds; compare {label} with `harness diff` instead"
            );
        }
        anyhow::Ok(variant.apply(s))
    })?;
    Ok((implementation, settings))
}

/// The reference implementation whose explanation holds for `imp` (when
/// `imp` agrees with it bit for bit): the implementation itself for
/// `ref-f316[+variants]` and `ref-f32`, else `ref-f316` for a Float316
/// implementation and `ref-f32` for an f32 one.
pub fn reference_label(imp: &dyn Implementation) -> Result<String> {
    let label = imp.label();
    let name = label.split('+').next().unwrap_or_default();
    if name == "ref-f316" || label == "ref-f32" {
        return Ok(label);
    }
    match imp.numbers() {
        Numbers::Float316 => Ok("ref-f316".into()),
        Numbers::F32 => Ok("ref-f32".into()),
        Numbers::F64 => bail!(
            "{label} computes with f64, as the oracle does: there is no lower precision to explain"
        ),
        Numbers::Ieee { bits } => bail!(
            "{label} computes with a {bits}-bit IEEE type: explanations are made by the \
        reference's Float316 and f32 pipelines only"
        ),
    }
}

impl Explainer {
    /// The explainer of a reference label (`ref-f316`, `ref-f316+newton-1`,
    /// `ref-f32`) on the seed scene.
    pub fn new(label: &str) -> Result<Self> {
        let (implementation, settings) = parse_label(label)?;
        let scene = reference::Scene::default();
        let low = Reference::new(implementation, &scene, settings)
            .with_context(|| format!("opening {label}"))?;
        Ok(Explainer {
            label: label.to_string(),
            low: Subject::Seed(Box::new(low)),
            oracle: Subject::Seed(Box::new(Reference::seed(RefImpl::F64))),
        })
    }

    /// The explainer of a reference label on a described scene: both
    /// sides made from the description.
    pub fn for_scene(label: &str, scene: &scene::Checked) -> Result<Self> {
        let (implementation, settings) = parse_label(label)?;
        let low = Described::new(implementation, scene, settings)
            .with_context(|| format!("opening {label} on scene {}", scene.description.name))?;
        let oracle = Described::new(RefImpl::F64, scene, Settings::default())
            .with_context(|| format!("opening {ORACLE} on scene {}", scene.description.name))?;
        Ok(Explainer {
            label: label.to_string(),
            low: Subject::Scene(Box::new(low)),
            oracle: Subject::Scene(Box::new(oracle)),
        })
    }

    /// The label explained.
    pub fn label(&self) -> &str {
        &self.label
    }

    /// Why pixel (x, y) differs.
    pub fn pixel(&self, x: usize, y: usize) -> Explanation {
        let run = |o: &ShadowOptions| self.low.shadow_pixel(x, y, o);
        let oracle = self.oracle.shadow_pixel(x, y, &ShadowOptions::default());
        // The seed's threshold; a described scene's output differs.
        let threshold = matches!(self.low, Subject::Seed(_))
            .then(|| 1.0 - f64::from(common::image_consts::BAYER[(y % 8) * 8 + (x % 8)]) / 64.0);
        self.explain(format!("pixel({x},{y})"), "shade", threshold, &oracle, run)
    }

    /// Why the SDF query at `p` differs.
    pub fn point(&self, p: [F316; 3]) -> Explanation {
        let run = |o: &ShadowOptions| self.low.shadow_sdf(p, o);
        let oracle = self.oracle.shadow_sdf(p, &ShadowOptions::default());
        let input = format!("sdf({},{},{})", p[0].to_f64(), p[1].to_f64(), p[2].to_f64());
        self.explain(input, "sd", None, &oracle, run)
    }

    /// The pixels of the image worth explaining: those whose dithered bit
    /// differs from the oracle's (`true`), or, when none does, the
    /// `largest` whose shades differ most (`false`).
    pub fn image_pixels(&self, largest: usize) -> Result<(Vec<(usize, usize)>, bool)> {
        let (Subject::Seed(low), Subject::Seed(oracle)) = (&self.low, &self.oracle) else {
            bail!("--image explains the seed scene only; name pixels with --pixel on a described scene");
        };
        let (low, oracle) = (low.render(), oracle.render());
        let differing = differing_pixels(&low, &oracle);
        Ok(if differing.is_empty() {
            (largest_differences(&low, &oracle, largest), false)
        } else {
            (differing, true)
        })
    }

    /// Every pixel of `pixels`, in parallel, in order.
    pub fn pixels(&self, pixels: &[(usize, usize)]) -> Vec<Explanation> {
        pixels.par_iter().map(|&(x, y)| self.pixel(x, y)).collect()
    }

    /// Explain one input: `run` runs the low precision under options,
    /// `oracle` is the oracle's run, `output` the answer compared.
    fn explain(
        &self,
        input: String,
        output: &str,
        threshold: Option<f64>,
        oracle: &ShadowRun,
        run: impl Fn(&ShadowOptions) -> ShadowRun,
    ) -> Explanation {
        let base = run(&ShadowOptions {
            record_ops: true,
            ..ShadowOptions::default()
        });
        let mut e = Explanation {
            input,
            low: self.label.clone(),
            oracle: ORACLE.into(),
            class: Class::Unexplained,
            why: String::new(),
            answers: None,
            decision: None,
            error: 0.0,
            error_of: output.to_string(),
            causes: Vec::new(),
            sites: 0,
            unmeasured: 0,
        };
        let (Some(lo), Some(or)) = (base.output(output), oracle.output(output)) else {
            e.why = format!(
                "a run trapped: {} {}, {ORACLE} {}",
                self.label,
                base.outcome.kind(),
                oracle.outcome.kind()
            );
            return e;
        };
        let white = |r: &ShadowRun| match &r.outcome {
            Outcome::Value(o) => o.white,
            _ => None,
        };
        e.answers = Some(Answers {
            output: output.into(),
            low: lo.lo,
            low_shadow: lo.hi,
            oracle: or.lo,
            low_white: white(&base),
            oracle_white: white(oracle),
            threshold,
        });
        let changes = match changed_decisions(&base, oracle) {
            Ok(changes) => changes,
            Err(why) => {
                e.why = why;
                return e;
            }
        };
        // Take the oracle's branches from a changed decision on: the
        // first changed decision whose own branch, left to the low
        // precision, moves the answer by more than the margin is the one
        // that matters; the others change nothing that reaches it.
        let oracle_decisions: Vec<(Decision, String, bool)> = oracle
            .decisions
            .iter()
            .map(|d| (d.decision, oracle.path(d.path), d.taken))
            .collect();
        let following = |from: usize| {
            run(&ShadowOptions {
                follow: Some(Follow {
                    from,
                    decisions: oracle_decisions.clone(),
                }),
                ..ShadowOptions::default()
            })
            .output(output)
            .map_or(lo.lo, |v| v.lo)
        };
        let branches: Vec<&DecisionChange> = changes
            .iter()
            .filter(|c| c.decision != Decision::Dither)
            .collect();
        let all_followed = branches.first().map(|c| following(c.index));
        let harmless = branches
            .iter()
            .enumerate()
            .take_while(|(j, _)| {
                let rest = branches.get(j + 1).map_or(lo.lo, |n| following(n.index));
                all_followed.is_some_and(|f| (rest - f).abs() <= THRESHOLD_MARGIN)
            })
            .count();
        let difference = (lo.lo - or.lo).abs();
        let also = match changes.first() {
            Some(c) if harmless > 0 => format!(
                "; {harmless} earlier decision(s) changed without moving the {output} (first: {} at {})",
        c.decision, c.path
            ),
            _ => String::new(),
        };
        let parted = branches
            .get(harmless)
            .copied()
            .or(changes.last().filter(|c| c.decision == Decision::Dither))
            .cloned();
        match &parted {
            Some(d) if d.decision != Decision::Dither => {
                e.class = Class::ControlFlow;
                e.why = format!(
                    "{} at {} changed, and taking {ORACLE}'s branch there moves the {output} \
                     towards {ORACLE}'s{also}",
                    d.decision, d.path
                );
            }
            Some(_) if difference <= THRESHOLD_MARGIN => {
                e.class = Class::ThresholdFlip;
                e.why = format!(
                    "only the dither comparison changed; the shades differ by {difference:.6}, \
                     within {THRESHOLD_MARGIN} of each other and of the threshold{also}"
                );
            }
            Some(_) => {
                e.class = Class::Accumulated;
                e.why = format!(
                    "only the dither comparison changed; the shades differ by {difference:.6}, \
                     more than {THRESHOLD_MARGIN}: accumulated error{also}"
                );
            }
            None if difference == 0.0 && harmless == 0 => {
                e.class = Class::Agree;
                e.why = "every decision and the answer agree".into();
            }
            None => {
                e.class = Class::Accumulated;
                e.why = format!(
                    "no decision that reaches the {output} changed; it differs by \
                     {difference:.3e}: accumulated error{also}"
                );
            }
        }
        let error = |r: &ShadowRun| match &parted {
            Some(d) => margin_error(r, d, &base),
            None => r.output(output).map(|v| v.lo - or.lo),
        };
        e.error = error(&base).unwrap_or(0.0);
        if let Some(d) = &parted {
            e.error_of = format!("the margin of {} ({})", d.decision, d.path);
        }
        // A flipped run keeps the base run's branches, so that the error
        // it changes is the rounding's own, through the same operations:
        // a flip that changed a decision on its way would measure that
        // decision's jump, or miss the decision whose margin is measured.
        let own_branches = Follow {
            from: 0,
            decisions: base
                .decisions
                .iter()
                .map(|d| (d.decision, base.path(d.path), d.taken))
                .collect(),
        };
        let flipped = |site: &SiteKey| {
            run(&ShadowOptions {
                flip: Some(site.clone()),
                follow: Some(own_branches.clone()),
                ..ShadowOptions::default()
            })
        };
        let blamed = blame(&base, usize::MAX, flipped, error);
        e.unmeasured = blamed.iter().filter(|b| !b.measured).count();
        e.sites = blamed.len();
        e.causes = blamed
            .into_iter()
            .filter(|b| b.contribution > 0.0)
            .take(ROOT_CAUSES)
            .map(|b| RootCause {
                operands: b.worst.operands().to_vec(),
                result: b.worst.result,
                local_error: b.worst.local_error,
                accumulated_error: b.worst.accumulated_error(),
                cancelled_bits: b.worst.cancelled_bits(),
                path: b.worst_path,
                share: b.share,
                count: b.count,
                site: b.site,
            })
            .collect();
        e.decision = parted;
        e
    }
}

/// The margin of a comparison on `operands`: what must cross 0 for it to
/// change (`a - b` of `gt(a, b)`; for the checker parity, the coordinate
/// nearest to a square's edge on the oracle's side, `oracle`).
fn margin(decision: Decision, operands: [f64; 2], oracle: [f64; 2]) -> f64 {
    if decision == Decision::Checker {
        let edge = |v: f64| (v - v.round()).abs();
        return operands[usize::from(edge(oracle[1]) < edge(oracle[0]))];
    }
    operands[0] - operands[1]
}

/// The error of the changed decision's margin in run `r` (low minus
/// oracle), `None` when `r` no longer reaches that decision.
fn margin_error(r: &ShadowRun, change: &DecisionChange, base: &ShadowRun) -> Option<f64> {
    let here = if change.decision == Decision::Dither {
        r.decisions.last()
    } else {
        r.decisions.get(change.index)
    };
    let same = |d: &&reference::DecisionRecord| {
        d.decision == change.decision && (std::ptr::eq(r, base) || r.path(d.path) == change.path)
    };
    // Where the run's earlier decisions went otherwise, the same decision
    // (kind and call path) further on or before.
    let d = here.filter(same).or_else(|| {
        r.decisions
            .iter()
            .filter(|d| d.decision == change.decision)
            .find(|d| r.path(d.path) == change.path)
    })?;
    let oracle = change.oracle.operands;
    Some(margin(d.decision, d.operands, oracle) - margin(d.decision, oracle, oracle))
}

fn change(index: usize, path: String, l: &DecisionRecord, o: &DecisionRecord) -> DecisionChange {
    DecisionChange {
        decision: l.decision,
        step: march_step(&path),
        path,
        index,
        low: DecisionSide {
            taken: l.taken,
            operands: l.operands,
        },
        low_shadows: l.shadows,
        oracle: DecisionSide {
            taken: o.taken,
            operands: o.operands,
        },
    }
}

/// The decisions where the low run and the oracle's take different
/// branches, in order, while both runs make the same decisions; then the
/// final dither comparison, when it differs and was not reached in step.
/// An error when the sequences part before any decision changes.
fn changed_decisions(low: &ShadowRun, oracle: &ShadowRun) -> Result<Vec<DecisionChange>, String> {
    let mut changes = Vec::new();
    let mut in_step = true;
    for (index, (l, o)) in low.decisions.iter().zip(&oracle.decisions).enumerate() {
        let path = low.path(l.path);
        if l.decision != o.decision || path != oracle.path(o.path) {
            if changes.is_empty() {
                return Err(format!(
                    "the decision sequences part without a decision changing: {} at {path} \
        against {} at {}",
                    l.decision,
                    o.decision,
                    oracle.path(o.path)
                ));
            }
            in_step = false;
            break;
        }
        if l.taken != o.taken {
            changes.push(change(index, path, l, o));
        }
    }
    if in_step && changes.is_empty() && low.decisions.len() != oracle.decisions.len() {
        return Err(format!(
            "one run makes more decisions ({} against {}) without a decision changing",
            low.decisions.len(),
            oracle.decisions.len()
        ));
    }
    let reached = changes.iter().any(|c| c.decision == Decision::Dither);
    if let (false, Some(l), Some(o)) = (reached, low.decisions.last(), oracle.decisions.last()) {
        if l.decision == Decision::Dither && o.decision == Decision::Dither && l.taken != o.taken {
            changes.push(change(low.decisions.len() - 1, low.path(l.path), l, o));
        }
    }
    Ok(changes)
}

/// The step number of the innermost `... step N` frame of a path.
fn march_step(path: &str) -> Option<u32> {
    path.split(" > ")
        .filter_map(|f| f.rsplit_once("step ").and_then(|(_, n)| n.parse().ok()))
        .last()
}

/// Whether `imp` agrees with the explained reference `reference` bit for
/// bit on each of `inputs`: the explanations hold for it exactly there.
/// `Ok(None)`: it agrees on all of them; `Ok(Some(..))`: the first input
/// where it does not, with both answers.
pub fn holds_for(
    imp: &dyn Implementation,
    reference: &dyn Implementation,
    inputs: &[vectors::Vector],
) -> Result<Option<String>> {
    let mine = imp.eval(inputs)?;
    let theirs = reference.eval(inputs)?;
    Ok(inputs
        .iter()
        .zip(mine.iter().zip(&theirs))
        .find(|(_, (a, b))| a != b)
        .map(|(v, (a, b))| {
            format!(
                "{} does not agree with {} on {v} ({a} against {b}): the explanation is {}'s, \
        not {}'s",
                imp.label(),
                reference.label(),
                reference.label(),
                imp.label()
            )
        }))
}

/// Class counts and root causes over many explanations.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Summary {
    /// Pixels per class, in [`Class::ALL`] order (classes with none left
    /// out).
    pub classes: Vec<(Class, u64)>,
    /// The top root cause of each explanation, grouped by site: pixels
    /// whose top cause it is, and their mean share, most pixels first.
    pub causes: Vec<CauseCount>,
    /// Control-flow divergences by decision.
    pub decisions: Vec<(Decision, u64)>,
}

/// One site as a top root cause.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CauseCount {
    pub site: SiteKey,
    pub pixels: u64,
    pub mean_share: f64,
}

impl Summary {
    /// The summary of `explanations`.
    pub fn of(explanations: &[Explanation]) -> Summary {
        let mut classes: BTreeMap<Class, u64> = BTreeMap::new();
        let mut decisions: BTreeMap<Decision, u64> = BTreeMap::new();
        let mut causes: BTreeMap<SiteKey, (u64, f64)> = BTreeMap::new();
        for e in explanations {
            *classes.entry(e.class).or_default() += 1;
            if let (Class::ControlFlow, Some(d)) = (e.class, &e.decision) {
                *decisions.entry(d.decision).or_default() += 1;
            }
            if let Some(c) = e.causes.first() {
                let entry = causes.entry(c.site.clone()).or_default();
                entry.0 += 1;
                entry.1 += c.share;
            }
        }
        let mut causes: Vec<CauseCount> = causes
            .into_iter()
            .map(|(site, (pixels, share))| CauseCount {
                site,
                pixels,
                mean_share: share / pixels as f64,
            })
            .collect();
        causes.sort_by(|a, b| b.pixels.cmp(&a.pixels).then(a.site.cmp(&b.site)));
        let mut decisions: Vec<(Decision, u64)> = decisions.into_iter().collect();
        decisions.sort_by_key(|d| std::cmp::Reverse(d.1));
        Summary {
            classes: Class::ALL
                .iter()
                .filter_map(|c| classes.get(c).map(|n| (*c, *n)))
                .collect(),
            causes,
            decisions,
        }
    }

    /// How many explanations fell in `class`.
    pub fn count(&self, class: Class) -> u64 {
        self.classes
            .iter()
            .find(|(c, _)| *c == class)
            .map_or(0, |(_, n)| *n)
    }
}

/// The pixels whose dithered bits differ between two renders, row by row.
pub fn differing_pixels(
    a: &reference::RenderedImage,
    b: &reference::RenderedImage,
) -> Vec<(usize, usize)> {
    (0..a.height)
        .flat_map(|y| (0..a.width).map(move |x| (x, y)))
        .filter(|&(x, y)| a.is_white(x, y) != b.is_white(x, y))
        .collect()
}

/// The `n` pixels whose shades differ most between two renders, largest
/// first (ties row by row).
pub fn largest_differences(
    a: &reference::RenderedImage,
    b: &reference::RenderedImage,
    n: usize,
) -> Vec<(usize, usize)> {
    let shade = |r: &reference::RenderedImage, i: usize| match r.pixels[i] {
        Outcome::Value(p) => Some(p.value.value),
        _ => None,
    };
    let mut diffs: Vec<(f64, usize)> = (0..a.pixels.len())
        .filter_map(|i| Some(((shade(a, i)? - shade(b, i)?).abs(), i)))
        .filter(|(d, _)| *d > 0.0)
        .collect();
    diffs.sort_by(|p, q| q.0.total_cmp(&p.0).then(p.1.cmp(&q.1)));
    diffs
        .into_iter()
        .take(n)
        .map(|(_, i)| (i % a.width, i / a.width))
        .collect()
}

#[cfg(test)]
mod tests;
