//! Exhaustive sweeps of a binary Float316 operation over its equivalence
//! classes (`vectors::gen::classes`): every class of the operation (or the
//! classes of one shard) is evaluated by every implementation, in chunks,
//! and compared bit for bit. A sweep keeps the first divergences it meets
//! with their operands, so each reproduces from a one-vector file.

use crate::compare::Divergence;
use crate::implementation::Implementation;
use crate::runner::{diff_set, RunOptions};
use common::Op;
use serde::{Deserialize, Serialize};
use std::time::Instant;
use vectors::gen::classes::{class_count, in_shard, representative};
use vectors::{Level, Shard, Vector, VectorSet};

/// Classes evaluated per chunk: large enough for the GPU to batch well,
/// small enough to keep memory and progress steps modest.
pub const CHUNK: usize = 1 << 18;

/// Divergences kept in a sweep's result.
pub const KEPT: usize = 20;

/// What a sweep found.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SweepResult {
    /// The operation.
    pub op: Op,
    /// The implementations, the first compared with each other one.
    pub impls: Vec<String>,
    /// The shard swept (`0/1`: every class).
    pub shard: String,
    /// Classes of the operation in all.
    pub classes: u64,
    /// Classes swept (those of the shard, up to the limit).
    pub swept: u64,
    /// Whether a `--limit` stopped the sweep before the shard's end.
    pub limited: bool,
    /// Cases (classes) that diverged, over all comparisons.
    pub divergent: u64,
    /// The first divergences, with their operands.
    pub divergences: Vec<Divergence>,
    /// Implementations that failed (no answers), with why.
    pub failures: Vec<String>,
    /// Wall-clock seconds.
    pub seconds: f64,
}

impl SweepResult {
    /// Cases swept per second (every implementation answered each).
    pub fn cases_per_second(&self) -> f64 {
        self.swept as f64 / self.seconds.max(1e-9)
    }

    /// Seconds a full sweep of every class would take on `machines`
    /// machines like this one, projected from this sweep's rate.
    pub fn projected_full_seconds(&self, machines: u32) -> f64 {
        self.classes as f64 / self.cases_per_second() / f64::from(machines.max(1))
    }

    /// Whether the sweep found a divergence or an implementation failed.
    pub fn failed(&self) -> bool {
        self.divergent > 0 || !self.failures.is_empty()
    }
}

/// Sweep `op`'s classes in `shard` through `impls`, at most `limit`
/// classes; `on_chunk` is told how many classes each finished chunk held.
pub fn sweep(
    impls: &[&dyn Implementation],
    op: Op,
    shard: Shard,
    limit: Option<u64>,
    mut on_chunk: impl FnMut(u64),
) -> Result<SweepResult, String> {
    let classes = class_count(op).ok_or_else(|| {
        format!("`{op}` has no sweep (only add, sub, mul, div and gt have equivalence classes)")
    })?;
    let start = Instant::now();
    let mut result = SweepResult {
        op,
        impls: impls.iter().map(|i| i.label()).collect(),
        shard: shard.to_string(),
        classes,
        swept: 0,
        limited: false,
        divergent: 0,
        divergences: Vec::new(),
        failures: Vec::new(),
        seconds: 0.0,
    };
    let limit = limit.unwrap_or(u64::MAX);
    let mut next = 0u64;
    while next < classes && result.swept < limit && result.failures.is_empty() {
        let room = (limit - result.swept).min(CHUNK as u64) as usize;
        let mut vectors = Vec::with_capacity(room);
        while next < classes && vectors.len() < room {
            if in_shard(next, shard.index, shard.count) {
                vectors.push(Vector::Op(representative(op, next)));
            }
            next += 1;
        }
        if vectors.is_empty() {
            break;
        }
        let set = VectorSet::new(
            &format!("sweep-{op}"),
            Level::Ops,
            "equivalence classes",
            None,
            vectors,
        );
        let report = diff_set(impls, &set, RunOptions::default());
        result.swept += set.vectors.len() as u64;
        result
            .failures
            .extend(report.failures().map(|(label, e)| format!("{label}: {e}")));
        for c in report.comparisons {
            result.divergent += (c.divergences.len() + c.omitted) as u64;
            let room = KEPT.saturating_sub(result.divergences.len());
            result
                .divergences
                .extend(c.divergences.into_iter().take(room));
        }
        on_chunk(set.vectors.len() as u64);
    }
    result.limited = next < classes && result.swept >= limit;
    result.seconds = start.elapsed().as_secs_f64();
    Ok(result)
}
