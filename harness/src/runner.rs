//! The differential runner: feeds a vector set to several implementations
//! in parallel (rayon, one job per batch), with a progress bar per
//! implementation on long work (hidden when stderr is not a terminal),
//! then compares the first implementation with each of the others and,
//! when three or more answered, names the odd one out of each divergence.

use crate::compare::{compare, odd_one_out, Comparison, Policy, Sides};
use crate::implementation::{Answer, ImplError, Implementation, Numbers};
use crate::progress;
use common::Outcome;
use indicatif::ProgressBar;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::time::Instant;
use vectors::{Level, Vector, VectorSet};

/// An implementation's answers in set order, or why it gave none.
pub type Answers = Result<Vec<Outcome<Answer>>, ImplError>;

/// The answers of one implementation to one set.
#[derive(Clone, Debug)]
pub struct ImplRun {
    /// The implementation's label.
    pub label: String,
    /// Its numbers.
    pub numbers: Numbers,
    /// Its answers in set order, or why it gave none.
    pub answers: Answers,
    /// Wall-clock seconds spent (summed over its batches).
    pub seconds: f64,
}

/// How an implementation fared on a set, without its answers.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunSummary {
    pub label: String,
    pub numbers: Numbers,
    /// Why it gave no answers (unavailable, unsupported, failed).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub error: Option<ImplError>,
    /// Wall-clock seconds (CPU time summed over parallel batches).
    pub seconds: f64,
}

/// One set run through several implementations and compared.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LevelReport {
    /// The set's name.
    pub set: String,
    pub level: Level,
    pub vectors: usize,
    /// One per implementation, in the order given.
    pub runs: Vec<RunSummary>,
    /// The first implementation against each other one that answered.
    pub comparisons: Vec<Comparison>,
    /// The shard of the set this report covers (`None`: the whole set);
    /// indices are the vectors' indices in the whole set either way.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shard: Option<vectors::Shard>,
}

impl LevelReport {
    /// Whether some comparison diverged.
    pub fn diverged(&self) -> bool {
        self.comparisons.iter().any(|c| c.diverged)
    }

    /// Implementations that gave no answers, with the reason.
    pub fn failures(&self) -> impl Iterator<Item = (&str, &ImplError)> {
        self.runs
            .iter()
            .filter_map(|r| r.error.as_ref().map(|e| (r.label.as_str(), e)))
    }
}

/// Options of a run.
#[derive(Clone, Copy, Debug, Default)]
pub struct RunOptions {
    /// Draw progress bars (only ever on a terminal).
    pub progress: bool,
}

fn bars(impls: &[&dyn Implementation], set: &VectorSet, options: RunOptions) -> Vec<ProgressBar> {
    let multi = progress::multi(options.progress);
    impls
        .iter()
        .map(|imp| {
            multi.add(progress::items(
                set.vectors.len() as u64,
                &imp.label(),
                &set.name,
            ))
        })
        .collect()
}

/// Answer every vector of `set` with every implementation, in parallel.
pub fn run(impls: &[&dyn Implementation], set: &VectorSet, options: RunOptions) -> Vec<ImplRun> {
    let bars = bars(impls, set, options);
    // One job per (implementation, batch); rayon spreads them over cores.
    let jobs: Vec<(usize, &[Vector])> = impls
        .iter()
        .enumerate()
        .filter(|(_, imp)| imp.supports(set.level))
        .flat_map(|(i, imp)| {
            set.vectors
                .chunks(imp.batch_size(set.level).max(1))
                .map(move |chunk| (i, chunk))
        })
        .collect();
    let results: Vec<(usize, Answers, f64)> = jobs
        .into_par_iter()
        .map(|(i, chunk)| {
            let start = Instant::now();
            let answers = impls[i].eval(chunk).and_then(|a| {
                if a.len() == chunk.len() {
                    Ok(a)
                } else {
                    Err(ImplError::Failed(format!(
                        "answered {} of {} vectors",
                        a.len(),
                        chunk.len()
                    )))
                }
            });
            bars[i].inc(chunk.len() as u64);
            (i, answers, start.elapsed().as_secs_f64())
        })
        .collect();
    impls
        .iter()
        .enumerate()
        .map(|(i, imp)| {
            bars[i].finish_and_clear();
            let mine = results.iter().filter(|(j, _, _)| *j == i);
            let seconds = mine.clone().map(|(_, _, s)| s).sum();
            let answers = if imp.supports(set.level) {
                mine.map(|(_, a, _)| a.clone())
                    .collect::<Result<Vec<Vec<_>>, _>>()
                    .map(|v| v.concat())
            } else {
                Err(ImplError::Unsupported(format!("the {} level", set.level)))
            };
            ImplRun {
                label: imp.label(),
                numbers: imp.numbers(),
                answers,
                seconds,
            }
        })
        .collect()
}

/// The localize command that reproduces a divergence.
pub fn localize_command(a: &str, b: &str, input: &Vector) -> Option<String> {
    input
        .localize_args()
        .map(|args| format!("harness localize {a} {b} {args}"))
}

/// The answer of one run to one divergence's input (for the image level,
/// the pixel's colour).
fn answer_at(run: &[Outcome<Answer>], index: usize, level: Level) -> Outcome<Answer> {
    match (level, run.first()) {
        (Level::Image, Some(Outcome::Value(Answer::Image { bitmap }))) => {
            Outcome::Value(Answer::Dot {
                white: bitmap.white[index],
            })
        }
        (Level::Image, Some(other)) => other.clone(),
        _ => run[index].clone(),
    }
}

/// Compare the first run with each other one that answered; fill in odd
/// ones out and localize commands.
pub fn compare_runs(set: &VectorSet, runs: &[ImplRun]) -> Vec<Comparison> {
    let answered: Vec<(&ImplRun, &Vec<Outcome<Answer>>)> = runs
        .iter()
        .filter_map(|r| r.answers.as_ref().ok().map(|a| (r, a)))
        .collect();
    let Some(((first, first_answers), others)) = answered.split_first() else {
        return Vec::new();
    };
    if first.label != runs[0].label {
        return Vec::new();
    }
    let exact_runs: Vec<&(&ImplRun, &Vec<Outcome<Answer>>)> = answered
        .iter()
        .filter(|(r, _)| r.numbers == Numbers::Float316)
        .collect();
    others
        .iter()
        .map(|(other, other_answers)| {
            // The f64 side, if any, is the oracle.
            let swap = first.numbers == Numbers::F64 && other.numbers != Numbers::F64;
            let ((sa, aa), (sb, ab)) = if swap {
                ((other, other_answers), (first, first_answers))
            } else {
                ((first, first_answers), (other, other_answers))
            };
            let mut comparison = compare(
                set,
                &Sides {
                    a_label: &sa.label,
                    a_numbers: sa.numbers,
                    a: aa,
                    b_label: &sb.label,
                    b_numbers: sb.numbers,
                    b: ab,
                },
            );
            if comparison.policy == Policy::Exact {
                for d in &mut comparison.divergences {
                    d.localize = localize_command(&sa.label, &sb.label, &d.input);
                    let answers: Vec<Outcome<Answer>> = exact_runs
                        .iter()
                        .map(|(_, a)| answer_at(a, d.index, set.level))
                        .collect();
                    let refs: Vec<&Outcome<Answer>> = answers.iter().collect();
                    d.odd_one_out = odd_one_out(&refs).map(|i| exact_runs[i].0.label.clone());
                }
            }
            comparison
        })
        .collect()
}

/// Run a set through the implementations and compare them.
pub fn diff_set(
    impls: &[&dyn Implementation],
    set: &VectorSet,
    options: RunOptions,
) -> LevelReport {
    level_report(set, &run(impls, set, options))
}

/// Compare runs of a set made earlier (see [`compare_runs`]) and summarise
/// them, for callers that keep the answers.
pub fn level_report(set: &VectorSet, runs: &[ImplRun]) -> LevelReport {
    let comparisons = compare_runs(set, runs);
    LevelReport {
        set: set.name.clone(),
        level: set.level,
        vectors: set.vectors.len(),
        runs: runs
            .iter()
            .map(|r| RunSummary {
                label: r.label.clone(),
                numbers: r.numbers,
                error: r.answers.as_ref().err().cloned(),
                seconds: r.seconds,
            })
            .collect(),
        comparisons,
        shard: None,
    }
}
