//! `harness check`: one yes/no question about the tree, for `git bisect
//! run`. Exit 0 when the comparison holds, 1 when it fails, 125 when it
//! cannot be decided (an implementation unavailable, bad input); always one
//! line saying why. An implementation under test that panics, hangs,
//! crashes or breaks its protocol fails the check (1): that is the commit
//! to blame, never one to skip. See `scripts/bisect-check.sh`, which maps a
//! build failure to 125 too.
//!
//! - `--no-divergence A B [--level L]`: the runner's policy finds no
//!   divergence between A and B on the level's small set (default: all).
//! - `--max-error IMPL THRESHOLD [--metric max|mean|flips]`: IMPL's whole
//!   image against the cast's oracle (`ref-f64`) stays within THRESHOLD.
//! - `--min-speed IMPL PIXELS_PER_SEC`: IMPL renders the whole image at
//!   least that fast (wall clock, this machine).

use crate::commands::diff::{sets_for, LevelArg};
use anyhow::{Context, Result};
use harness::cast::{Cast, CastError};
use harness::implementation::Failure;
use harness::implementation::{ImplError, Implementation};
use harness::runner::{diff_set, RunOptions};
use harness::verdict::{self, one_line};
use harness_report::measure::{self, ImageError};
use std::process::ExitCode;
use vectors::VectorSet;

/// Exit status of `check` when the question cannot be decided.
pub const UNDECIDABLE: u8 = 125;

/// Arguments of `harness check`.
#[derive(Debug, clap::Args)]
pub struct CheckArgs {
    /// A and B agree under the comparison policy.
    #[arg(long, num_args = 2, value_names = ["A", "B"], conflicts_with_all = ["max_error", "min_speed"])]
    pub no_divergence: Option<Vec<String>>,
    /// IMPL's error against ref-f64 is at most THRESHOLD.
    #[arg(long, num_args = 2, value_names = ["IMPL", "THRESHOLD"], conflicts_with = "min_speed")]
    pub max_error: Option<Vec<String>>,
    /// IMPL renders at least PIXELS_PER_SEC pixels per second.
    #[arg(long, num_args = 2, value_names = ["IMPL", "PIXELS_PER_SEC"])]
    pub min_speed: Option<Vec<String>>,
    /// Level for --no-divergence (its small committed set); default all.
    #[arg(long, value_enum)]
    pub level: Option<LevelArg>,
    /// Error figure for --max-error.
    #[arg(long, value_enum, default_value = "max")]
    pub metric: Metric,
}

/// Which error figure `--max-error` bounds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Metric {
    /// Largest absolute shade error.
    Max,
    /// Mean absolute shade error.
    Mean,
    /// Dithered pixels that differ.
    Flips,
}

/// The answer to a check, in `git bisect run`'s terms.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Bisect {
    /// The comparison holds.
    Good(String),
    /// It fails.
    Bad(String),
    /// It cannot be decided here.
    Undecidable(String),
}

impl Bisect {
    /// The exit status for `git bisect run`: 0, 1 or 125.
    pub fn exit_code(&self) -> u8 {
        match self {
            Bisect::Good(_) => 0,
            Bisect::Bad(_) => 1,
            Bisect::Undecidable(_) => UNDECIDABLE,
        }
    }

    /// The one line printed.
    pub fn line(&self) -> String {
        match self {
            Bisect::Good(why) => format!("good: {why}"),
            Bisect::Bad(why) => format!("bad: {why}"),
            Bisect::Undecidable(why) => format!("skip: {why}"),
        }
    }
}

fn parse_number(what: &str, text: &str) -> Result<f64> {
    let v: f64 = text
        .parse()
        .with_context(|| format!("{what} `{text}` is not a number"))?;
    anyhow::ensure!(
        v.is_finite() && v >= 0.0,
        "{what} must be a non-negative number, got {text}"
    );
    Ok(v)
}

/// Decide the question; every failure to decide is [`Bisect::Undecidable`].
pub fn decide(args: &CheckArgs, cast: &Cast) -> Bisect {
    let result = if let Some(ab) = &args.no_divergence {
        no_divergence(cast, &ab[0], &ab[1], args.level)
    } else if let Some(v) = &args.max_error {
        parse_number("threshold", &v[1]).and_then(|t| max_error(cast, &v[0], t, args.metric))
    } else if let Some(v) = &args.min_speed {
        parse_number("pixels per second", &v[1]).and_then(|t| min_speed(cast, &v[0], t))
    } else {
        Err(anyhow::anyhow!("no question given"))
    };
    result.unwrap_or_else(|e| match contained_failure(&e) {
        Some(f) => Bisect::Bad(one_line(&f.to_string())),
        None => Bisect::Undecidable(format!("{e:#}")),
    })
}

/// The contained failure of an implementation of its own (not a batch
/// left unrun) behind an error, if that is what it is.
fn contained_failure(e: &anyhow::Error) -> Option<&Failure> {
    match verdict::implementation_failure(e) {
        Some(ImplError::Contained(f)) if f.is_own() => Some(f.as_ref()),
        _ => None,
    }
}

fn no_divergence(cast: &Cast, a: &str, b: &str, level: Option<LevelArg>) -> Result<Bisect> {
    let sets = sets_for(level, None)?;
    let ia = cast
        .open(a)
        .with_context(|| format!("implementation `{a}`"))?;
    let ib = cast
        .open(b)
        .with_context(|| format!("implementation `{b}`"))?;
    no_divergence_between(ia.as_ref(), ib.as_ref(), &sets)
}

/// The `--no-divergence` question for two opened implementations on
/// `sets`: bad on a divergence or on a contained failure of either.
pub fn no_divergence_between(
    ia: &dyn Implementation,
    ib: &dyn Implementation,
    sets: &[VectorSet],
) -> Result<Bisect> {
    let (a, b) = (ia.label(), ib.label());
    let mut compared = 0;
    for set in sets {
        let report = diff_set(&[ia, ib], set, RunOptions { progress: false });
        if let Some((label, e)) = report.failures().next() {
            match e {
                ImplError::Unsupported(_) => continue,
                ImplError::Contained(f) if f.is_own() => {
                    return Ok(Bisect::Bad(one_line(&format!("on {}: {f}", set.name))));
                }
                _ => anyhow::bail!("{label} on {}: {e}", set.name),
            }
        }
        for c in &report.comparisons {
            compared += c.vectors;
            if c.diverged {
                let first = c
                    .divergences
                    .iter()
                    .find(|d| !d.tolerated)
                    .or(c.divergences.first());
                let at = first
                    .map(|d| format!(", first at {}", d.input))
                    .unwrap_or_default();
                return Ok(Bisect::Bad(format!(
                    "{a} and {b} diverge on {} ({} level){at}",
                    set.name, set.level
                )));
            }
        }
    }
    anyhow::ensure!(compared > 0, "{a} and {b} share no level to compare");
    Ok(Bisect::Good(format!(
        "{a} and {b} agree on {compared} vectors"
    )))
}

fn max_error(cast: &Cast, imp: &str, threshold: f64, metric: Metric) -> Result<Bisect> {
    let oracle_name = &cast.oracle().name;
    let (subject, _) = measure::render(cast, imp, false)?;
    let (oracle, _) = measure::render(cast, oracle_name, false)?;
    let figures = ImageError::of(&subject.images, &oracle.images)?;
    // A trap is an answer that no error figure can bound.
    if figures.traps > 0 {
        return Ok(Bisect::Bad(format!(
            "{imp}: {} of {} pixels trapped where {oracle_name} answered",
            figures.traps, figures.pixels
        )));
    }
    let no_shades = || {
        format!(
            "no shades to compare: {imp} gives its image's bits alone (it does not answer the \
             pixels level); --metric flips compares them"
        )
    };
    let value = match metric {
        Metric::Flips => figures.flips as f64,
        Metric::Max => figures.shade.with_context(no_shades)?.1,
        Metric::Mean => figures.shade.with_context(no_shades)?.0,
    };
    let what =
        format!("{imp}: {metric:?} error against {oracle_name} {value:e}, threshold {threshold:e}")
            .to_lowercase();
    Ok(if value <= threshold {
        Bisect::Good(what)
    } else {
        Bisect::Bad(what)
    })
}

fn min_speed(cast: &Cast, imp: &str, threshold: f64) -> Result<Bisect> {
    let (r, _) = measure::render(cast, imp, false)?;
    Ok(speed_answer(imp, r.pixels(), r.render_s, threshold))
}

/// The `--min-speed` answer for `pixels` rendered in `seconds`: good at
/// the threshold's speed or above.
fn speed_answer(imp: &str, pixels: u64, seconds: f64, threshold: f64) -> Bisect {
    let speed = pixels as f64 / seconds.max(1e-9);
    let what = format!("{imp}: {speed:.0} pixels/s, threshold {threshold:.0}");
    if speed >= threshold {
        Bisect::Good(what)
    } else {
        Bisect::Bad(what)
    }
}

/// Run `harness check`: print the verdict's line and exit with its code
/// (a project file that cannot be read makes the question undecidable).
pub fn run(args: CheckArgs, cast: Result<Cast, CastError>) -> Result<ExitCode> {
    let answer = match cast {
        Ok(cast) => decide(&args, &cast),
        Err(e) => Bisect::Undecidable(e.to_string()),
    };
    println!("{}", answer.line());
    Ok(ExitCode::from(answer.exit_code()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use common::Outcome;
    use harness::implementation::Answer;

    #[test]
    fn exit_codes_follow_git_bisect() {
        assert_eq!(Bisect::Good("x".into()).exit_code(), 0);
        assert_eq!(Bisect::Bad("x".into()).exit_code(), 1);
        assert_eq!(Bisect::Undecidable("x".into()).exit_code(), 125);
        assert_eq!(Bisect::Undecidable("no GPU".into()).line(), "skip: no GPU");
    }

    #[test]
    fn the_speed_is_pixels_over_seconds_and_good_from_the_threshold_up() {
        assert_eq!(
            speed_answer("x", 131_072, 2.0, 65_536.0),
            Bisect::Good("x: 65536 pixels/s, threshold 65536".into())
        );
        assert!(matches!(
            speed_answer("x", 131_072, 2.0, 65_537.0),
            Bisect::Bad(_)
        ));
    }

    /// A contained failure of the implementation's own is an answer
    /// (bad); a batch it was never asked, or another error, is not.
    #[test]
    fn only_an_implementations_own_contained_failure_decides() {
        use harness::implementation::{Failure, FailureKind};
        let contained = |kind| {
            anyhow::Error::new(ImplError::Contained(Box::new(Failure::new(
                "port",
                kind,
                "boom".into(),
                &[],
            ))))
            .context("rendering")
        };
        let own = contained(FailureKind::Panic);
        assert_eq!(
            contained_failure(&own).map(|f| f.label.as_str()),
            Some("port")
        );
        assert!(contained_failure(&contained(FailureKind::NotRun)).is_none());
        assert!(contained_failure(&anyhow::anyhow!("no such file")).is_none());
    }

    /// Answers a white pixel of shade 0.5 to every input, except `changed`.
    struct Pixels {
        changed: Vec<(vectors::Vector, Outcome<Answer>)>,
    }

    impl Implementation for Pixels {
        fn label(&self) -> String {
            format!("pixels{}", self.changed.len())
        }
        fn numbers(&self) -> harness::implementation::Numbers {
            harness::implementation::Numbers::F64
        }
        fn supports(&self, level: vectors::Level) -> bool {
            level == vectors::Level::Pixels
        }
        fn eval(&self, batch: &[vectors::Vector]) -> Result<Vec<Outcome<Answer>>, ImplError> {
            Ok(batch
                .iter()
                .map(|v| {
                    self.changed
                        .iter()
                        .find(|(k, _)| k == v)
                        .map_or_else(|| pixel(true), |(_, a)| a.clone())
                })
                .collect())
        }
    }

    fn pixel(white: bool) -> Outcome<Answer> {
        Outcome::Value(Answer::Pixel {
            shade: harness::implementation::Num::F64(0.5),
            white,
        })
    }

    /// The bad answer names the first difference beyond the policy (a
    /// pixel answered out of domain), not the tolerated flip before it.
    #[test]
    fn a_divergence_is_named_by_its_first_untolerated_difference() {
        let set = measure::full_image_set();
        let a = Pixels { changed: vec![] };
        let b = Pixels {
            changed: vec![
                (set.vectors[0].clone(), pixel(false)),
                (set.vectors[3].clone(), Outcome::OutOfDomain),
            ],
        };
        let report = diff_set(&[&a, &b], &set, RunOptions { progress: false });
        let d = &report.comparisons[0].divergences;
        assert!(d.len() == 2 && d[0].tolerated && !d[1].tolerated, "{d:?}");
        assert_ne!(d[0].input, d[1].input);
        let Bisect::Bad(line) = no_divergence_between(&a, &b, std::slice::from_ref(&set)).unwrap()
        else {
            panic!("a divergence beyond policy is bad")
        };
        assert!(
            line.ends_with(&format!("first at {}", d[1].input)),
            "{line}"
        );
    }

    #[test]
    fn numbers_are_checked() {
        assert!(parse_number("t", "1e-3").is_ok());
        assert!(parse_number("t", "-1").is_err());
        assert!(parse_number("t", "fast").is_err());
        assert!(parse_number("t", "NaN").is_err());
    }
}
