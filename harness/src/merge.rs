//! Campaigns split across machines: running one shard of a set
//! ([`run_shard`]: the shard's vectors, with every index reported as the
//! vector's index in the whole set) and joining shard reports again
//! ([`merge`]) into the report the unsharded run gives, timings apart.
//!
//! Merged error figures of the error policy take each shard's mean
//! weighted by its values, so a merged mean can differ from the unsharded
//! one in its last bits; every other field is reproduced exactly.

use crate::compare::{Comparison, Group, MAX_KEPT};
use crate::implementation::{ImplError, Implementation};
use crate::runner::{diff_set, LevelReport, RunOptions};
use std::collections::BTreeMap;
use vectors::{Shard, VectorSet};

/// Run shard `shard` of `set` through `impls`: the report counts only the
/// shard's vectors, but every divergence and group names the vector's
/// index in the whole set, and the report says which shard it is.
pub fn run_shard(
    impls: &[&dyn Implementation],
    set: &VectorSet,
    shard: Shard,
    options: RunOptions,
) -> LevelReport {
    if shard == Shard::WHOLE {
        return diff_set(impls, set, options);
    }
    let whole_index: Vec<usize> = set
        .vectors
        .iter()
        .enumerate()
        .filter(|(_, v)| shard.contains(v))
        .map(|(i, _)| i)
        .collect();
    let part = shard.of_set(set);
    let mut report = diff_set(impls, &part, options);
    for c in &mut report.comparisons {
        for d in &mut c.divergences {
            d.index = whole_index[d.index];
        }
        for g in &mut c.groups {
            g.first = whole_index[g.first];
        }
    }
    report.shard = Some(shard);
    report
}

/// Why shard reports could not be merged.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum MergeError {
    #[error("no shard reports to merge")]
    Empty,
    #[error("report {0} has a set without a shard (it was not run with --shard)")]
    NotSharded(usize),
    #[error("shards of different campaigns: {0} and {1} shards")]
    Counts(u32, u32),
    #[error("shard {0} is given twice")]
    Duplicate(Shard),
    #[error("the shards ran different sets or implementations ({0})")]
    Mismatch(String),
    #[error("report {0} names shard {1}, which no campaign has (K/N needs N >= 1 and K < N)")]
    BadShard(usize, Shard),
    #[error("the shards' {0} add up to more than {max}", max = usize::MAX)]
    Overflow(&'static str),
}

/// The sum of shard counts, refused when it does not fit (a hand-edited
/// report must not wrap to a small number).
fn total(what: &'static str, counts: impl IntoIterator<Item = usize>) -> Result<usize, MergeError> {
    counts
        .into_iter()
        .try_fold(0usize, usize::checked_add)
        .ok_or(MergeError::Overflow(what))
}

/// Shard reports joined into one.
#[derive(Debug, PartialEq)]
pub struct Merged {
    /// One report per set, as the unsharded run gives it.
    pub reports: Vec<LevelReport>,
    /// How many shards the campaign has.
    pub count: u32,
    /// The shards not given (K of K/N).
    pub missing: Vec<u32>,
    /// Every implementation that gave no answers (or stopped early) in a
    /// shard: the shard, the implementation's label, the set and why.
    pub failures: Vec<ShardFailure>,
}

/// An implementation's failure in one shard.
#[derive(Clone, Debug, PartialEq)]
pub struct ShardFailure {
    pub shard: Shard,
    pub label: String,
    pub set: String,
    pub error: ImplError,
}

/// Join shard reports (each the reports of one `diff --shard K/N` run, its
/// sets in the same order) into the reports of the whole campaign.
pub fn merge(parts: &[Vec<LevelReport>]) -> Result<Merged, MergeError> {
    let first = parts.first().ok_or(MergeError::Empty)?;
    let mut seen = BTreeMap::new();
    let mut count = None;
    for (i, part) in parts.iter().enumerate() {
        let shard = part
            .first()
            .and_then(|r| r.shard)
            .ok_or(MergeError::NotSharded(i))?;
        if part.iter().any(|r| r.shard != Some(shard)) {
            return Err(MergeError::NotSharded(i));
        }
        if shard.count == 0 || shard.index >= shard.count {
            return Err(MergeError::BadShard(i, shard));
        }
        match count {
            Some(n) if n != shard.count => return Err(MergeError::Counts(n, shard.count)),
            _ => count = Some(shard.count),
        }
        if seen.insert(shard.index, i).is_some() {
            return Err(MergeError::Duplicate(shard));
        }
        let shape = |p: &[LevelReport]| -> Vec<(String, Vec<String>)> {
            p.iter()
                .map(|r| {
                    (
                        r.set.clone(),
                        r.runs.iter().map(|s| s.label.clone()).collect(),
                    )
                })
                .collect()
        };
        if shape(part) != shape(first) {
            return Err(MergeError::Mismatch(format!("report {i} against report 0")));
        }
    }
    let count = count.expect("at least one part");
    let missing = (0..count).filter(|k| !seen.contains_key(k)).collect();
    let failures = parts
        .iter()
        .flatten()
        .flat_map(|r| {
            r.failures().map(|(label, e)| ShardFailure {
                shard: r.shard.unwrap_or(Shard::WHOLE),
                label: label.to_string(),
                set: r.set.clone(),
                error: e.clone(),
            })
        })
        .collect();
    let reports = (0..first.len())
        .map(|s| merge_set(parts.iter().map(|p| &p[s])))
        .collect::<Result<_, _>>()?;
    Ok(Merged {
        reports,
        count,
        missing,
        failures,
    })
}

fn merge_set<'a>(parts: impl Iterator<Item = &'a LevelReport>) -> Result<LevelReport, MergeError> {
    let parts: Vec<&LevelReport> = parts.collect();
    let mut out = parts[0].clone();
    out.shard = None;
    out.vectors = total("vectors", parts.iter().map(|p| p.vectors))?;
    for (i, run) in out.runs.iter_mut().enumerate() {
        run.seconds = parts.iter().map(|p| p.runs[i].seconds).sum();
        run.error = parts.iter().find_map(|p| p.runs[i].error.clone());
    }
    // A pair is missing from a shard where one side gave no answer at all:
    // each pair is merged over the shards that compared it.
    let mut pairs: Vec<(String, String)> = Vec::new();
    for c in parts.iter().flat_map(|p| &p.comparisons) {
        let pair = (c.a.clone(), c.b.clone());
        if !pairs.contains(&pair) {
            pairs.push(pair);
        }
    }
    out.comparisons = pairs
        .iter()
        .map(|(a, b)| {
            merge_comparison(
                parts
                    .iter()
                    .flat_map(|p| &p.comparisons)
                    .filter(|c| (&c.a, &c.b) == (a, b)),
            )
        })
        .collect::<Result<_, _>>()?;
    Ok(out)
}

/// Counts per key, summed over the shards.
fn summed<'a>(
    parts: impl Iterator<Item = &'a BTreeMap<String, usize>>,
) -> Result<BTreeMap<String, usize>, MergeError> {
    let mut sum: BTreeMap<String, usize> = BTreeMap::new();
    for (key, n) in parts.flatten() {
        let count = sum.entry(key.clone()).or_insert(0);
        *count = total("inputs not compared", [*count, *n])?;
    }
    Ok(sum)
}

/// One pair's comparisons in several shards as one: the vectors each
/// actually compared are summed (a shard whose implementation stopped early
/// compared fewer than it holds).
fn merge_comparison<'a>(
    parts: impl Iterator<Item = &'a Comparison>,
) -> Result<Comparison, MergeError> {
    let parts: Vec<&Comparison> = parts.collect();
    let mut out = parts[0].clone();
    out.vectors = total("compared vectors", parts.iter().map(|c| c.vectors))?;
    let found = total(
        "divergences",
        parts.iter().flat_map(|c| [c.divergences.len(), c.omitted]),
    )?;
    let mut divergences: Vec<_> = parts.iter().flat_map(|c| c.divergences.clone()).collect();
    divergences.sort_by_key(|d| d.index);
    divergences.truncate(MAX_KEPT);
    out.omitted = found - divergences.len();
    out.divergences = divergences;
    let mut groups: BTreeMap<_, Group> = BTreeMap::new();
    for g in parts.iter().flat_map(|c| &c.groups) {
        let key = (g.op, g.category.clone(), g.kind, g.tolerated);
        match groups.get_mut(&key) {
            Some(m) => {
                m.count = total("group counts", [m.count, g.count])?;
                m.first = m.first.min(g.first);
            }
            None => {
                groups.insert(key, g.clone());
            }
        }
    }
    out.groups = groups.into_values().collect();
    out.outside_domain = summed(parts.iter().map(|c| &c.outside_domain))?;
    out.unsupported = summed(parts.iter().map(|c| &c.unsupported))?;
    if let Some(s) = &mut out.stats {
        let stats: Vec<_> = parts.iter().filter_map(|c| c.stats.as_ref()).collect();
        s.values = total("values", stats.iter().map(|t| t.values))?;
        s.pixels = total("pixels", stats.iter().map(|t| t.pixels))?;
        s.flips = total("flips", stats.iter().map(|t| t.flips))?;
        s.max_abs = stats.iter().map(|t| t.max_abs).fold(0.0, f64::max);
        s.max_rel = stats.iter().map(|t| t.max_rel).fold(0.0, f64::max);
        s.max_ulps_f32 = stats.iter().filter_map(|t| t.max_ulps_f32).reduce(f64::max);
        s.mean_abs = if s.values == 0 {
            0.0
        } else {
            stats
                .iter()
                .map(|t| t.mean_abs * t.values as f64)
                .sum::<f64>()
                / s.values as f64
        };
    }
    let mut findings: Vec<String> = parts.iter().flat_map(|c| c.findings.clone()).collect();
    findings.dedup();
    out.findings = findings;
    out.diverged = parts.iter().any(|c| c.diverged);
    Ok(out)
}
