//! The one verdict of every command that compares (`diff`, `check`,
//! `merge`, `nightly`, `render`, `bench`): what was compared and whether it
//! diverged beyond its policy, and what the user asked for that could not
//! be compared, with the reason. Each command fills a [`Verdict`] and takes
//! its exit status from it, so the gates cannot drift apart.
//!
//! | status | exit | when |
//! |---|---|---|
//! | [`Status::Agreed`] | 0 | something was compared, nothing diverged, nothing asked for is missing |
//! | [`Status::Diverged`] | 1 | anything compared diverges beyond its policy (bit-exact or error figures, flip fractions, traps against values) |
//! | [`Status::Incomplete`] | 3 | nothing diverged, but something asked for was not compared: a crash, a hang, a failed open, an unsupported level asked for, a failed or missing shard, a built-in that cannot run here (unless allowed), or nothing at all |
//!
//! Exit 2 stays the command's own: a usage or input error before anything
//! ran. `harness check` maps the same verdict to `git bisect`'s codes.

use crate::implementation::ImplError;
use crate::runner::LevelReport;
use serde::{Deserialize, Serialize};
use std::fmt;
use std::process::ExitCode;

/// The exit status of a run whose verdict is [`Status::Incomplete`].
pub const INCOMPLETE_EXIT: u8 = 3;

/// How a run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// Everything asked for was compared and agreed.
    Agreed,
    /// Something compared diverged beyond its policy.
    Diverged,
    /// Something asked for could not be compared.
    Incomplete,
}

impl Status {
    /// The process exit status: 0, 1 or [`INCOMPLETE_EXIT`].
    pub fn code(self) -> u8 {
        match self {
            Status::Agreed => 0,
            Status::Diverged => 1,
            Status::Incomplete => INCOMPLETE_EXIT,
        }
    }

    /// The status as a process exit code.
    pub fn exit_code(self) -> ExitCode {
        ExitCode::from(self.code())
    }
}

/// Why something was not compared.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Missing {
    /// It cannot run on this machine (no Vulkan adapter for a GPU or shader entry):
    /// skipped, a failure unless the user allows it.
    Unavailable,
    /// It ran and failed: a crash, a hang of a batch, a broken protocol, a
    /// failed open or render.
    Failed,
    /// It has no entry point for a level the user asked for.
    Unsupported,
    /// A shard of the campaign is not there.
    Shard,
}

impl Missing {
    /// What an implementation's error leaves uncompared.
    pub fn of(error: &ImplError) -> Missing {
        match error {
            ImplError::Unavailable(_) => Missing::Unavailable,
            ImplError::Unsupported(_) => Missing::Unsupported,
            ImplError::Failed(_) | ImplError::Contained(_) => Missing::Failed,
        }
    }
}

impl fmt::Display for Missing {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Missing::Unavailable => "skipped",
            Missing::Failed => "failed",
            Missing::Unsupported => "unsupported",
            Missing::Shard => "missing",
        })
    }
}

/// One thing the user asked for that was not compared.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct NotCompared {
    /// What (an implementation on a set, a render, a shard).
    pub what: String,
    pub missing: Missing,
    /// Why, in the implementation's or the harness's words.
    pub why: String,
}

/// One comparison made.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Compared {
    /// What was compared (`A vs B on SET`).
    pub what: String,
    /// Cases compared (vectors, pixels).
    pub cases: u64,
    /// How it diverged beyond its policy, if it did.
    pub beyond_policy: Option<String>,
}

/// What a run compared and what it could not.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Verdict {
    pub compared: Vec<Compared>,
    pub not_compared: Vec<NotCompared>,
    /// Unavailable implementations do not fail the run (the user said so).
    #[serde(default)]
    pub allow_unavailable: bool,
}

impl Verdict {
    /// An empty verdict; `allow_unavailable` as the user asked.
    pub fn new(allow_unavailable: bool) -> Self {
        Verdict {
            allow_unavailable,
            ..Verdict::default()
        }
    }

    /// Record a comparison of `cases` cases, diverging when `beyond_policy`
    /// says how.
    pub fn compared(&mut self, what: impl Into<String>, cases: u64, beyond_policy: Option<String>) {
        self.compared.push(Compared {
            what: what.into(),
            cases,
            beyond_policy,
        });
    }

    /// Record something asked for that was not compared.
    pub fn not_compared(
        &mut self,
        what: impl Into<String>,
        missing: Missing,
        why: impl Into<String>,
    ) {
        self.not_compared.push(NotCompared {
            what: what.into(),
            missing,
            why: why.into(),
        });
    }

    /// Record an implementation's error on `what`, by its kind.
    pub fn failed(&mut self, what: impl Into<String>, error: &ImplError) {
        self.not_compared(what, Missing::of(error), one_line(&error.to_string()));
    }

    /// Record a level report: every comparison, and every implementation
    /// that gave no answers (or stopped before the end). A level the
    /// implementation does not answer counts only when `asked` says the
    /// user named that level.
    pub fn add_level(&mut self, report: &LevelReport, asked: bool) {
        self.add_comparisons(report);
        for (label, e) in report.failures() {
            if matches!(e, ImplError::Unsupported(_)) && !asked {
                continue;
            }
            self.failed(format!("{label} on {}", report.set), e);
        }
    }

    /// Record the comparisons of a level report, each diverging when its
    /// policy says so (differences beyond it, or a finding such as the flip
    /// fraction).
    pub fn add_comparisons(&mut self, report: &LevelReport) {
        for c in &report.comparisons {
            let beyond = c.diverged.then(|| {
                let differences: usize = c
                    .groups
                    .iter()
                    .filter(|g| !g.tolerated)
                    .map(|g| g.count)
                    .sum();
                let mut why = vec![format!("{differences} differences beyond policy")];
                why.extend(c.findings.iter().cloned());
                why.join("; ")
            });
            self.compared(
                format!("{} vs {} on {}", c.a, c.b, report.set),
                c.vectors as u64,
                beyond,
            );
        }
    }

    /// Whether `n` counts against the run.
    fn counts(&self, n: &NotCompared) -> bool {
        !(self.allow_unavailable && n.missing == Missing::Unavailable)
    }

    /// The status: diverged if anything compared diverged, else incomplete
    /// if anything asked for is missing or nothing was compared at all (no
    /// comparison, or comparisons of no case: an empty shard).
    pub fn status(&self) -> Status {
        if self.compared.iter().any(|c| c.beyond_policy.is_some()) {
            Status::Diverged
        } else if self.cases() == 0 || self.not_compared.iter().any(|n| self.counts(n)) {
            Status::Incomplete
        } else {
            Status::Agreed
        }
    }

    /// How many comparisons diverged beyond their policy.
    pub fn beyond_policy(&self) -> usize {
        self.compared
            .iter()
            .filter(|c| c.beyond_policy.is_some())
            .count()
    }

    /// Cases compared, over every comparison.
    pub fn cases(&self) -> u64 {
        self.compared.iter().map(|c| c.cases).sum()
    }

    /// The lines printed at the end of a run: what diverged, what was not
    /// compared (skipped ones in red on a terminal), and the verdict.
    pub fn lines(&self, colour: bool) -> Vec<String> {
        let red = |s: String| {
            if colour {
                format!("\x1b[31m{s}\x1b[0m")
            } else {
                s
            }
        };
        let mut lines: Vec<String> = self
            .compared
            .iter()
            .filter_map(|c| {
                c.beyond_policy
                    .as_ref()
                    .map(|why| format!("diverged: {}: {why}", c.what))
            })
            .collect();
        for n in &self.not_compared {
            let allowed = if self.counts(n) {
                ""
            } else {
                " (allowed by --allow-unavailable)"
            };
            lines.push(red(format!(
                "{}: {}: {}{allowed}",
                n.missing, n.what, n.why
            )));
        }
        let failing = self.not_compared.iter().filter(|n| self.counts(n)).count();
        let diverged = self.beyond_policy();
        let summary = format!(
            "{} comparisons on {} cases, {diverged} beyond policy; {failing} not compared",
            self.compared.len(),
            self.cases()
        );
        lines.push(match self.status() {
            Status::Agreed => format!("verdict: agreed ({summary})"),
            Status::Diverged => format!("verdict: DIVERGED ({summary})"),
            Status::Incomplete if self.cases() == 0 => red(format!(
                "verdict: INCOMPLETE, nothing was compared ({summary})"
            )),
            Status::Incomplete => red(format!("verdict: INCOMPLETE ({summary})")),
        });
        lines
    }

    /// Print [`Verdict::lines`] to standard output (red only on a
    /// terminal) and return the exit status.
    pub fn report(&self) -> ExitCode {
        use std::io::IsTerminal;
        for line in self.lines(std::io::stdout().is_terminal()) {
            println!("{line}");
        }
        self.status().exit_code()
    }
}

/// The implementation's own failure behind an error (a failed open, a
/// crash or hang while answering), if that is what it is, as opposed to a
/// usage or input error of the command.
pub fn implementation_failure(e: &anyhow::Error) -> Option<&ImplError> {
    e.chain().find_map(|cause| {
        cause.downcast_ref::<ImplError>().or_else(|| {
            cause
                .downcast_ref::<crate::cast::OpenError>()
                .and_then(|o| match o {
                    crate::cast::OpenError::Impl(i) => Some(i),
                    _ => None,
                })
        })
    })
}

/// A multi-line message (a failure with its stderr lines) on one line.
pub fn one_line(text: &str) -> String {
    text.lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn agreed() -> Verdict {
        let mut v = Verdict::new(false);
        v.compared("a vs b on s", 10, None);
        v
    }

    #[test]
    fn nothing_compared_is_never_agreement() {
        assert_eq!(Verdict::new(false).status(), Status::Incomplete);
        assert_eq!(Verdict::new(true).status(), Status::Incomplete);
        assert_eq!(agreed().status(), Status::Agreed);
        assert_eq!(agreed().status().code(), 0);
        let mut empty = Verdict::new(false);
        empty.compared("a vs b on shard 0/4294967295", 0, None);
        assert_eq!(empty.status(), Status::Incomplete, "0 cases compared");
    }

    #[test]
    fn a_divergence_wins_over_a_missing_part() {
        let mut v = agreed();
        v.not_compared("c on s", Missing::Failed, "crashed");
        assert_eq!(v.status(), Status::Incomplete);
        assert_eq!(v.status().code(), INCOMPLETE_EXIT);
        v.compared("a vs c on s", 3, Some("2 differences beyond policy".into()));
        assert_eq!(v.status(), Status::Diverged);
        assert_eq!(v.status().code(), 1);
        let text = v.lines(false).join("\n");
        assert!(
            text.contains("diverged: a vs c on s: 2 differences"),
            "{text}"
        );
        assert!(text.contains("failed: c on s: crashed"), "{text}");
        assert!(text.contains("2 comparisons on 13 cases, 1 beyond policy; 1 not compared"));
    }

    /// A divergence's reason counts only the differences its policy does
    /// not tolerate one by one.
    #[test]
    fn a_divergence_counts_only_the_untolerated_differences() {
        use crate::compare::{Comparison, DiffKind, Group, Policy};
        let group = |count, tolerated| Group {
            level: vectors::Level::Sdf,
            op: None,
            category: "random".into(),
            kind: DiffKind::Value,
            count,
            tolerated,
            first: 0,
        };
        let report = LevelReport {
            set: "sdf-small".into(),
            level: vectors::Level::Sdf,
            vectors: 10,
            runs: Vec::new(),
            comparisons: vec![Comparison {
                a: "a".into(),
                b: "b".into(),
                level: vectors::Level::Sdf,
                set: "sdf-small".into(),
                policy: Policy::Exact,
                vectors: 10,
                divergences: Vec::new(),
                omitted: 0,
                groups: vec![group(3, false), group(5, true)],
                stats: None,
                findings: vec!["a finding".into()],
                outside_domain: Default::default(),
                unsupported: Default::default(),
                diverged: true,
            }],
            shard: None,
        };
        let mut v = Verdict::new(false);
        v.add_comparisons(&report);
        assert_eq!(
            v.lines(false)[0],
            "diverged: a vs b on sdf-small: 3 differences beyond policy; a finding"
        );
    }

    /// "Nothing was compared" only when no case was.
    #[test]
    fn an_incomplete_run_says_nothing_was_compared_only_when_nothing_was() {
        let mut v = agreed();
        v.not_compared("c on s", Missing::Failed, "crashed");
        assert_eq!(
            v.lines(false).last().unwrap(),
            "verdict: INCOMPLETE (1 comparisons on 10 cases, 0 beyond policy; 1 not compared)"
        );
        let mut none = Verdict::new(false);
        none.not_compared("c on s", Missing::Failed, "crashed");
        assert!(none
            .lines(false)
            .last()
            .unwrap()
            .starts_with("verdict: INCOMPLETE, nothing was compared"));
    }

    #[test]
    fn only_unavailable_ones_may_be_allowed() {
        for (missing, allowed) in [
            (Missing::Unavailable, true),
            (Missing::Failed, false),
            (Missing::Unsupported, false),
            (Missing::Shard, false),
        ] {
            let mut v = agreed();
            v.not_compared("gpu-f32", missing, "no adapter");
            assert_eq!(v.status(), Status::Incomplete, "{missing}");
            v.allow_unavailable = true;
            let expected = if allowed {
                Status::Agreed
            } else {
                Status::Incomplete
            };
            assert_eq!(v.status(), expected, "{missing}");
        }
    }

    #[test]
    fn skipped_ones_are_red_on_a_terminal() {
        let mut v = agreed();
        v.not_compared("gpu-f32", Missing::Unavailable, "no Vulkan adapter");
        let lines = v.lines(true);
        assert_eq!(
            lines[0],
            "\x1b[31mskipped: gpu-f32: no Vulkan adapter\x1b[0m"
        );
        assert!(v.lines(false)[0].starts_with("skipped: gpu-f32"));
        v.allow_unavailable = true;
        assert!(v.lines(false)[0].ends_with("(allowed by --allow-unavailable)"));
        assert_eq!(
            v.lines(false)[1],
            "verdict: agreed (1 comparisons on 10 cases, 0 beyond policy; 0 not compared)"
        );
    }
}
