//! The differential runner: feeds a vector set to several implementations
//! in parallel (one job per batch, on the runner's own thread pool), with a progress bar per
//! implementation on long work (hidden when stderr is not a terminal),
//! then compares the first implementation with each of the others and,
//! when three or more answered, names the odd one out of each divergence.

use crate::compare::{compare, odd_one_out, Comparison, Policy, Sides};
use crate::implementation::{
    Answer, BatchAnswers, Failure, FailureKind, ImplError, Implementation, Numbers,
};
use crate::progress;
use common::Outcome;
use indicatif::ProgressBar;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::OnceLock;
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
    /// Wall-clock seconds from its first batch's start to its last one's
    /// end.
    pub seconds: f64,
    /// Whether it checks the reference's modelled domain itself
    /// ([`Implementation::checks_domain`]).
    pub checks_domain: bool,
    /// The levels it answers ([`Implementation::supports`]).
    pub levels: Vec<Level>,
}

/// How an implementation fared on a set, without its answers.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunSummary {
    pub label: String,
    pub numbers: Numbers,
    /// Why it gave no answers (unavailable, unsupported, failed).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub error: Option<ImplError>,
    /// Wall-clock seconds from its first batch's start to its last one's
    /// end.
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

/// One batch's answers checked for their count.
fn counted(answers: BatchAnswers, chunk: &[Vector]) -> BatchAnswers {
    answers.and_then(|a| {
        if a.len() == chunk.len() {
            Ok(a)
        } else {
            Err(ImplError::Failed(format!(
                "answered {} of {} vectors",
                a.len(),
                chunk.len()
            )))
        }
    })
}

/// The runner's unit of parallel work.
enum Job<'a> {
    /// One batch of implementation `i`, from `start` in the set.
    Batch {
        i: usize,
        start: usize,
        chunk: &'a [Vector],
    },
    /// Every batch of an implementation that answers in order, with
    /// their starts.
    InOrder {
        i: usize,
        batches: Vec<(usize, &'a [Vector])>,
    },
}

/// One batch's result: the implementation, the batch's start, its answers
/// and the seconds it took.
/// A batch's implementation, its start in the set, its answers, and when
/// it began and ended.
type Done = (usize, usize, BatchAnswers, (Instant, Instant));

/// Join one implementation's batches, in set order, into its answers. At
/// the first batch that failed, a contained failure keeps every answer
/// before its input (earlier batches and its own) and names the input in
/// the set; the batches after it count as not run.
fn joined(batches: Vec<(usize, BatchAnswers)>) -> Answers {
    let mut answers = Vec::new();
    for (start, batch) in batches {
        match batch {
            Ok(a) => answers.extend(a),
            Err(ImplError::Contained(mut failure)) => {
                answers.append(&mut failure.answered);
                let mut placed = failure.placed(start);
                placed.answered = answers;
                return Err(ImplError::Contained(Box::new(placed)));
            }
            Err(e) => return Err(e),
        }
    }
    Ok(answers)
}

/// Answer every vector of `set` with every implementation, in parallel.
/// The runner's threads, one per core. A batch job blocks while its
/// contained worker or its pipe answers; on threads of its own it cannot
/// starve an implementation that parallelises on the global rayon pool
/// inside a batch (the reference renders an image's rows in parallel).
/// `None` when no thread could be started: the global pool runs the jobs.
fn runner_pool() -> Option<&'static rayon::ThreadPool> {
    static POOL: OnceLock<Option<rayon::ThreadPool>> = OnceLock::new();
    POOL.get_or_init(|| {
        rayon::ThreadPoolBuilder::new()
            .thread_name(|i| format!("harness-runner-{i}"))
            .build()
            .ok()
    })
    .as_ref()
}

/// An implementation's failure is contained to it: once one of its batches
/// failed, its later batches are not run, and the other implementations go
/// on.
pub fn run(impls: &[&dyn Implementation], set: &VectorSet, options: RunOptions) -> Vec<ImplRun> {
    let bars = bars(impls, set, options);
    // The start of each implementation's earliest failed batch.
    let failed: Vec<AtomicUsize> = impls.iter().map(|_| AtomicUsize::new(usize::MAX)).collect();
    // One job per (implementation, batch), or per implementation that
    // answers in order; rayon spreads them over cores.
    let jobs: Vec<Job> = impls
        .iter()
        .enumerate()
        .filter(|(_, imp)| imp.supports(set.level))
        .flat_map(|(i, imp)| {
            let size = imp.batch_size(set.level).max(1);
            let batches = set
                .vectors
                .chunks(size)
                .enumerate()
                .map(move |(k, chunk)| (k * size, chunk));
            if imp.in_order() {
                vec![Job::InOrder {
                    i,
                    batches: batches.collect(),
                }]
            } else {
                batches
                    .map(|(start, chunk)| Job::Batch { i, start, chunk })
                    .collect()
            }
        })
        .collect();
    let one_batch = |i: usize, start: usize, chunk: &[Vector]| -> Done {
        let begin = Instant::now();
        let answers = if start > failed[i].load(Ordering::Relaxed) {
            Err(Failure::new(
                &impls[i].label(),
                FailureKind::NotRun,
                "an earlier batch failed".into(),
                chunk,
            )
            .into())
        } else {
            counted(impls[i].eval(chunk), chunk)
        };
        if answers.is_err() {
            failed[i].fetch_min(start, Ordering::Relaxed);
        }
        bars[i].inc(chunk.len() as u64);
        (i, start, answers, (begin, Instant::now()))
    };
    let in_order = |i: usize, batches: &[(usize, &[Vector])]| -> Vec<Done> {
        let chunks: Vec<&[Vector]> = batches.iter().map(|(_, c)| *c).collect();
        let mut done: Vec<Option<Done>> = batches.iter().map(|_| None).collect();
        let mut begin = Instant::now();
        impls[i].eval_in_order(&chunks, &mut |k, answers| {
            let Some(&(start, chunk)) = batches.get(k) else {
                return;
            };
            bars[i].inc(chunk.len() as u64);
            let end = Instant::now();
            done[k].get_or_insert((i, start, counted(answers, chunk), (begin, end)));
            begin = end;
        });
        // A batch it never reported is a failure, not a gap in the answers.
        done.into_iter()
            .zip(batches)
            .map(|(d, &(start, _))| {
                d.unwrap_or_else(|| {
                    let why = "its in-order evaluation gave this batch no answers".into();
                    let now = Instant::now();
                    (i, start, Err(ImplError::Failed(why)), (now, now))
                })
            })
            .collect()
    };
    let work = || -> Vec<Done> {
        jobs.into_par_iter()
            .flat_map_iter(|job| match job {
                Job::Batch { i, start, chunk } => vec![one_batch(i, start, chunk)],
                Job::InOrder { i, batches } => in_order(i, &batches),
            })
            .collect()
    };
    let results = match runner_pool() {
        Some(pool) => pool.install(work),
        None => work(),
    };
    let mut per_impl: Vec<Vec<(usize, BatchAnswers)>> = impls.iter().map(|_| Vec::new()).collect();
    // Each implementation's span, from its first batch's start to its last
    // one's end: its batches run side by side, so their sum overstates it.
    let mut spans: Vec<Option<(Instant, Instant)>> = impls.iter().map(|_| None).collect();
    for (i, start, answers, (begin, end)) in results {
        per_impl[i].push((start, answers));
        let span = spans[i].get_or_insert((begin, end));
        *span = (span.0.min(begin), span.1.max(end));
    }
    let seconds = spans
        .into_iter()
        .map(|s| s.map_or(0.0, |(begin, end)| (end - begin).as_secs_f64()));
    impls
        .iter()
        .zip(per_impl)
        .zip(seconds)
        .enumerate()
        .map(|(i, ((imp, mut batches), seconds))| {
            bars[i].finish_and_clear();
            let answers = if imp.supports(set.level) {
                batches.sort_by_key(|(start, _)| *start);
                joined(batches)
            } else {
                Err(ImplError::Unsupported(format!("the {} level", set.level)))
            };
            ImplRun {
                label: imp.label(),
                numbers: imp.numbers(),
                answers,
                seconds,
                checks_domain: imp.checks_domain(),
                levels: Level::ALL
                    .into_iter()
                    .filter(|&l| imp.supports(l))
                    .collect(),
            }
        })
        .collect()
}

/// The answers a run has to compare: all of them, or those kept before a
/// contained failure.
pub fn kept_answers(run: &ImplRun) -> Option<&[Outcome<Answer>]> {
    match &run.answers {
        Ok(a) => Some(a),
        Err(ImplError::Contained(f)) if !f.answered.is_empty() => Some(&f.answered),
        Err(_) => None,
    }
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
    let answered: Vec<(&ImplRun, &[Outcome<Answer>])> = runs
        .iter()
        .filter_map(|r| kept_answers(r).map(|a| (r, a)))
        .collect();
    let Some((&(first, first_answers), others)) = answered.split_first() else {
        return Vec::new();
    };
    if first.label != runs[0].label {
        return Vec::new();
    }
    let exact_runs: Vec<&(&ImplRun, &[Outcome<Answer>])> = answered
        .iter()
        .filter(|(r, _)| r.numbers == Numbers::Float316)
        .collect();
    others
        .iter()
        .map(|&(other, other_answers)| {
            // The f64 side, if any, is the oracle.
            let swap = first.numbers == Numbers::F64 && other.numbers != Numbers::F64;
            let ((sa, aa), (sb, ab)) = if swap {
                ((other, other_answers), (first, first_answers))
            } else {
                ((first, first_answers), (other, other_answers))
            };
            // After a contained failure, the answers kept before it.
            let n = aa.len().min(ab.len());
            let prefix;
            let compared = if n < set.vectors.len() {
                prefix = VectorSet {
                    vectors: set.vectors[..n].to_vec(),
                    ..set.clone()
                };
                &prefix
            } else {
                set
            };
            let mut comparison = compare(
                compared,
                &Sides {
                    a_label: &sa.label,
                    a_numbers: sa.numbers,
                    a_checks_domain: sa.checks_domain,
                    a: &aa[..n],
                    b_label: &sb.label,
                    b_numbers: sb.numbers,
                    b_checks_domain: sb.checks_domain,
                    b: &ab[..n],
                },
            );
            // An input a side cannot be asked for on its own (a pixel of
            // an image that comes from its whole program) has no repro and
            // no localize command.
            for d in &mut comparison.divergences {
                let level = d.input.level();
                d.reproducible = sa.levels.contains(&level) && sb.levels.contains(&level);
            }
            if comparison.policy == Policy::Exact {
                for d in &mut comparison.divergences {
                    if d.reproducible {
                        d.localize = localize_command(&sa.label, &sb.label, &d.input);
                    }
                    let voters: Vec<&&(&ImplRun, &[Outcome<Answer>])> = exact_runs
                        .iter()
                        .filter(|(_, a)| set.level == Level::Image || d.index < a.len())
                        .collect();
                    let answers: Vec<Outcome<Answer>> = voters
                        .iter()
                        .map(|(_, a)| answer_at(a, d.index, set.level))
                        .collect();
                    let refs: Vec<&Outcome<Answer>> = answers.iter().collect();
                    d.odd_one_out = odd_one_out(&refs).map(|i| voters[i].0.label.clone());
                }
            }
            comparison
        })
        .collect()
}

/// An error as a summary keeps it: a contained failure without the
/// answers it kept.
fn without_answers(e: &ImplError) -> ImplError {
    match e {
        ImplError::Contained(f) => ImplError::Contained(Box::new(Failure {
            answered: Vec::new(),
            ..(**f).clone()
        })),
        other => other.clone(),
    }
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
                error: r.answers.as_ref().err().map(without_answers),
                seconds: r.seconds,
            })
            .collect(),
        comparisons,
        shard: None,
    }
}
