//! The nightly job: a list of typed steps ([`steps::all`]) run in order
//! over the cast. Each step reads what the steps before it left in the
//! [`Night`] (the opened implementations, the renders) and adds its
//! results to the report being built; the [`Verdict`] inside the
//! [`Summary`] decides the exit status: every bit-exact divergence (at any level, and
//! between the images of Float316 implementations, a program's own screen
//! included), every render that failed and a failed self-test fail the
//! night.
//!
//! # Adding a step
//! Write a unit struct implementing [`step::Step`] (its `key` selects it
//! with `--steps`, its `name` is its line in the log and the report's
//! timings, `run` does the work through the [`Night`]) and add it to
//! [`steps::all`] where it belongs in the order. A step that can find a
//! failure must make it count in the night's [`Verdict`]: a bit-exact
//! comparison row, a gated image pair, or `Night::not_compared`.

mod explain;
mod pairs;
mod scene_jack;
mod scene_pictures;
pub mod scenes;
pub mod step;
pub mod steps;
mod tuned;

use anyhow::Result;
use harness::cast::{Cast, Entry};
use harness::implementation::Implementation;
use harness::verdict::{Missing, Status, Verdict};
use harness_report::model::{RunMeta, StepTiming};
use harness_report::ReportBuilder;
use std::path::PathBuf;
use std::time::Instant;

/// What the night is asked to do.
#[derive(Clone, Debug)]
pub struct Options {
    /// The report directory (replaced atomically when the run completes).
    pub out: PathBuf,
    /// The exhaustive unary checks give a slow implementation (an
    /// emulator) every N-th input.
    pub slow_unary_step: usize,
    /// The steps to run, by key (`None`: all).
    pub steps: Option<Vec<String>>,
    /// The implementations to open, by name (`None`: the whole cast); the
    /// oracle and the tracer are always opened.
    pub implementations: Option<Vec<String>>,
    /// Progress bars on a terminal.
    pub progress: bool,
    /// The described scenes of the scene step (files).
    pub scenes: Vec<PathBuf>,
    /// The shard of the committed sets and TestFloat sets to run (K/N, K
    /// from 0, by the vectors' identity hash); [`vectors::Shard::WHOLE`]
    /// runs them whole.
    pub shard: vectors::Shard,
    /// An implementation that cannot run here is skipped without failing
    /// the night.
    pub allow_unavailable: bool,
}

/// An implementation of the cast, opened for the night.
pub struct Opened<'c> {
    pub entry: &'c Entry,
    pub imp: Box<dyn Implementation>,
    /// Seconds it took to open.
    pub open_s: f64,
}

/// A render in the report, and what it may be compared with.
#[derive(Clone, Debug, PartialEq)]
pub struct Rendered {
    pub label: String,
    /// It belongs to the bit-exact group (a Float316 entry with no variant
    /// in its label): a difference from another such render fails the
    /// night.
    pub bit_exact: bool,
    /// For the screen of a whole-program run, the label of the
    /// implementation whose entry points answer for its pixels.
    pub screen_of: Option<String>,
    /// The most dithered pixels it may flip against the oracle's render,
    /// as a fraction (its number type's policy); `None` for a render that
    /// is measured, not judged (a precision variant, a program screen).
    pub flip_limit: Option<f64>,
}

/// What the steps share.
pub struct Night<'c> {
    pub cast: &'c Cast,
    pub options: &'c Options,
    /// The implementations that opened, in the cast's order.
    pub opened: Vec<Opened<'c>>,
    /// Variants opened by a step (the tracer's precision variants).
    pub variants: Vec<Box<dyn Implementation>>,
    pub builder: ReportBuilder,
    pub rendered: Vec<Rendered>,
    /// What could not be compared so far (an implementation that did not
    /// open, failed on a set, or whose render failed); the report's
    /// comparisons join it at the end.
    pub verdict: Verdict,
}

impl<'c> Night<'c> {
    /// The opened implementation or variant labelled `label`.
    pub fn find(&self, label: &str) -> Option<&dyn Implementation> {
        lookup(&self.opened, &self.variants, label)
    }

    /// The opened ones among `names`, in that order.
    pub fn opened_of(&self, names: &[&str]) -> Vec<&dyn Implementation> {
        names.iter().filter_map(|n| self.find(n)).collect()
    }

    /// The names of the opened entries that satisfy `which`.
    pub fn names_where(&self, which: impl Fn(&Entry) -> bool) -> Vec<&'c str> {
        self.opened
            .iter()
            .filter(|o| which(o.entry))
            .map(|o| o.entry.name.as_str())
            .collect()
    }

    /// Record a problem of the report.
    pub fn problem(&mut self, line: String) {
        self.builder.report_mut().problems.push(line);
    }

    /// Record something that could not be compared: it fails the night
    /// (an unavailable one unless allowed), and is a problem of the report.
    pub fn not_compared(&mut self, what: String, missing: Missing, why: String) {
        self.problem(format!("{what}: {why}"));
        self.verdict.not_compared(what, missing, why);
    }
}

/// The implementation labelled `label` among `opened` and `variants`.
fn lookup<'a>(
    opened: &'a [Opened<'_>],
    variants: &'a [Box<dyn Implementation>],
    label: &str,
) -> Option<&'a dyn Implementation> {
    opened
        .iter()
        .map(|o| o.imp.as_ref())
        .chain(variants.iter().map(|v| v.as_ref()))
        .find(|i| i.label() == label)
}

/// How the night ended.
#[derive(Clone, Debug, PartialEq)]
pub struct Summary {
    /// Every comparison of the night and what could not be compared.
    pub verdict: Verdict,
    pub problems: usize,
    pub duration_s: f64,
}

impl Summary {
    /// The night's status (its exit status is [`Status::code`]).
    pub fn status(&self) -> Status {
        self.verdict.status()
    }

    /// The one line printed at the end.
    pub fn line(&self) -> String {
        let v = &self.verdict;
        let beyond = v.beyond_policy();
        let missing = v.not_compared.len();
        format!(
            "{}: {} comparisons on {} cases, {beyond} beyond policy, {missing} not compared, {} problems, {:.0} s",
            match self.status() {
                Status::Agreed => "passed",
                Status::Diverged => "DIVERGED",
                Status::Incomplete => "INCOMPLETE",
            },
            v.compared.len(),
            v.cases(),
            self.problems,
            self.duration_s
        )
    }
}

/// Times the steps of the run.
struct Timer {
    list: Vec<StepTiming>,
    last: Instant,
}

impl Timer {
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

/// Run the night's steps over the cast, write the report and the history
/// line; returns the summary and the report directory.
pub fn run(cast: &Cast, options: &Options) -> Result<(Summary, PathBuf)> {
    let started = Instant::now();
    let mut timer = Timer {
        list: Vec::new(),
        last: Instant::now(),
    };
    let builder = ReportBuilder::new(&options.out, RunMeta::collect(), cast.role_names())?;
    let mut night = Night {
        cast,
        options,
        opened: Vec::new(),
        variants: Vec::new(),
        builder,
        rendered: Vec::new(),
        verdict: Verdict::new(options.allow_unavailable),
    };
    for step in steps::all() {
        let wanted = options
            .steps
            .as_ref()
            .is_none_or(|keys| keys.iter().any(|k| k == step.key()));
        if step.always() || wanted {
            step.run(&mut night)?;
            timer.done(&step.name());
        }
    }
    let mut verdict = std::mem::take(&mut night.verdict);
    let report = night.builder.report_mut();
    report.add_comparisons_to(&mut verdict);
    report.verdict = verdict.clone();
    let mut summary = Summary {
        verdict,
        problems: report.problems.len(),
        duration_s: 0.0,
    };
    timer.done("summary");
    report.meta.steps = timer.list;
    report.meta.duration_s = started.elapsed().as_secs_f64();
    summary.duration_s = report.meta.duration_s;
    let history = options
        .out
        .parent()
        .unwrap_or_else(|| std::path::Path::new("."))
        .join("history.jsonl");
    let dir = night.builder.finish(&history)?;
    Ok((summary, dir))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_line_says_the_status_and_what_was_not_compared() {
        let mut verdict = Verdict::new(false);
        verdict.compared("a vs b on s", 5, None);
        let summary = |verdict: &Verdict| Summary {
            verdict: verdict.clone(),
            problems: 1,
            duration_s: 2.0,
        };
        assert_eq!(
            summary(&verdict).line(),
            "passed: 1 comparisons on 5 cases, 0 beyond policy, 0 not compared, 1 problems, 2 s"
        );
        verdict.not_compared("port (open)", Missing::Failed, "exit 3");
        assert!(summary(&verdict).line().starts_with("INCOMPLETE: "));
        verdict.compared("a vs c on s", 5, Some("flips".into()));
        assert_eq!(summary(&verdict).status(), Status::Diverged);
    }
}
