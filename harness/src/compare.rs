//! Comparison policies and their results. One function per policy, each
//! treating a trap (`Sys.error`, hang, out of domain) as an answer to
//! compare:
//! - [`Policy::Exact`] for two Float316 implementations: bit-exact triples
//!   and the same outcome kind; any difference is a divergence.
//! - [`Policy::Error`] when a float implementation takes part: error
//!   figures (absolute, relative, f32 ULPs, dithered-pixel flips) of the
//!   subject against the oracle, with thresholds that are reported.
//!
//! Every difference is classified ([`DiffKind`]) and identical ones are
//! grouped ([`Group`]: same level, operation, category and kind).

use crate::implementation::{Answer, Bitmap, Num, Numbers};
use common::{Outcome, OutcomeKind};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::fmt;
use vectors::{Level, PixelVector, Vector};

/// At most this many divergences are kept per comparison (all are counted
/// in the groups).
pub const MAX_KEPT: usize = 1000;

/// The thresholds of the error policy: a value differs beyond policy when
/// both its absolute and its relative error exceed them; a set of pixels
/// diverges when more than `max_flip_fraction` of them flip.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Thresholds {
    pub max_abs: f64,
    pub max_rel: f64,
    pub max_flip_fraction: f64,
}

impl Thresholds {
    /// The thresholds for a subject computing with `numbers` against f64.
    pub fn for_subject(numbers: Numbers) -> Self {
        match numbers {
            Numbers::F32 | Numbers::F64 | Numbers::Ieee { bits: 32.. } => Thresholds {
                max_abs: 1e-4,
                max_rel: 1e-4,
                max_flip_fraction: 0.01,
            },
            // binary16 holds about 3 decimal digits.
            Numbers::Ieee { .. } => Thresholds {
                max_abs: 1e-2,
                max_rel: 1e-2,
                max_flip_fraction: 0.02,
            },
            Numbers::Float316 => Thresholds {
                max_abs: 1e-3,
                max_rel: 1e-3,
                max_flip_fraction: 0.01,
            },
        }
    }
}

/// How two implementations are compared.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "policy", rename_all = "snake_case")]
pub enum Policy {
    /// Bit-exact Float316 triples and the same outcome kind.
    Exact,
    /// Error figures of the subject against the oracle.
    Error { thresholds: Thresholds },
}

impl Policy {
    /// The policy for a subject and an oracle computing with these numbers.
    pub fn for_pair(subject: Numbers, oracle: Numbers) -> Self {
        if subject == Numbers::Float316 && oracle == Numbers::Float316 {
            Policy::Exact
        } else {
            Policy::Error {
                thresholds: Thresholds::for_subject(subject),
            }
        }
    }
}

/// What kind of difference one vector shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DiffKind {
    /// Both answered values, and the values differ (bits, or error beyond
    /// the thresholds).
    Value,
    /// One answered a value, `Sys.error` or out of domain, the other
    /// something of another kind (hangs are [`DiffKind::Hang`]).
    OutcomeKind,
    /// Both called `Sys.error`, with different codes.
    ErrorCode,
    /// One side hung, the other did not.
    Hang,
    /// A dithered pixel flipped.
    Flip,
}

impl fmt::Display for DiffKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            DiffKind::Value => "value",
            DiffKind::OutcomeKind => "outcome kind",
            DiffKind::ErrorCode => "error code",
            DiffKind::Hang => "hang",
            DiffKind::Flip => "pixel flip",
        })
    }
}

/// The error of one value against the oracle.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PointError {
    pub abs: f64,
    pub rel: f64,
    /// Units in the last place of f32, when the subject computes in f32.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ulps_f32: Option<f64>,
}

/// One vector on which two implementations differ.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Divergence {
    /// Index of the vector in its set (for the image level: of the pixel,
    /// `y * 512 + x`).
    pub index: usize,
    /// The input.
    pub input: Vector,
    /// The kind of difference.
    pub kind: DiffKind,
    /// The answer of the first implementation (the subject).
    pub a: Outcome<Answer>,
    /// The answer of the second implementation (the oracle).
    pub b: Outcome<Answer>,
    /// Error figures (error policy only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub error: Option<PointError>,
    /// Whether the policy tolerates this difference on its own (pixel flips
    /// and shade errors under the error policy count only in aggregate).
    pub tolerated: bool,
    /// When three or more implementations answered and exactly one
    /// disagrees with all the others, its label.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub odd_one_out: Option<String>,
    /// The `harness localize` command that reproduces and localizes it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub localize: Option<String>,
    /// The one-vector repro file, once written.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub repro: Option<String>,
    /// Whether both sides answer the input on its own, at its level, so
    /// that a repro file and a localize command can replay it: an image
    /// divergence of a program whose image comes only from its whole run
    /// (no pixel binding) has a pixel neither can be asked for.
    #[serde(default = "yes", skip_serializing_if = "is_yes")]
    pub reproducible: bool,
}

fn yes() -> bool {
    true
}

fn is_yes(b: &bool) -> bool {
    *b
}

/// Identical divergences: same level, operation, category and kind.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
pub struct Group {
    pub level: Level,
    /// The operation (ops level only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub op: Option<common::Op>,
    pub category: String,
    pub kind: DiffKind,
    /// How many vectors.
    pub count: usize,
    /// Whether the policy tolerates them one by one.
    pub tolerated: bool,
    /// The index of the first one.
    pub first: usize,
}

/// Aggregate error figures of the error policy.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ErrorStats {
    /// Values compared (both sides answered values).
    pub values: usize,
    pub max_abs: f64,
    pub mean_abs: f64,
    pub max_rel: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_ulps_f32: Option<f64>,
    /// Dithered pixels compared and how many flipped.
    pub pixels: usize,
    pub flips: usize,
}

/// The result of comparing two implementations on one set.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Comparison {
    /// Label of the subject.
    pub a: String,
    /// Label of the oracle.
    pub b: String,
    pub level: Level,
    /// The set's name.
    pub set: String,
    pub policy: Policy,
    /// Vectors compared.
    pub vectors: usize,
    /// The divergences, in set order (at most [`MAX_KEPT`]).
    pub divergences: Vec<Divergence>,
    /// Divergences not kept (beyond [`MAX_KEPT`]).
    pub omitted: usize,
    /// Identical divergences grouped, in a stable order.
    pub groups: Vec<Group>,
    /// Error figures (error policy only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stats: Option<ErrorStats>,
    /// Set-level findings beyond policy (flip fraction, oracle precision).
    pub findings: Vec<String>,
    /// Inputs outside the reference's modelled domain that were not
    /// compared, per operation (or level): one side answered out of domain
    /// and the other declares no domain check of its own.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub outside_domain: BTreeMap<String, usize>,
    /// Inputs not compared because a side has no such operation (it
    /// answered `unsupported`), per operation.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub unsupported: BTreeMap<String, usize>,
    /// The verdict: a divergence under the policy.
    pub diverged: bool,
}

fn kind_difference(a: &Outcome<Answer>, b: &Outcome<Answer>) -> Option<DiffKind> {
    match (a, b) {
        (Outcome::SysError(x), Outcome::SysError(y)) if x != y => Some(DiffKind::ErrorCode),
        _ if a.kind() == b.kind() => None,
        _ if a.kind() == OutcomeKind::Hang || b.kind() == OutcomeKind::Hang => Some(DiffKind::Hang),
        _ => Some(DiffKind::OutcomeKind),
    }
}

fn numbers_of(answer: &Answer) -> Vec<Num> {
    match answer {
        Answer::Num { value } => vec![*value],
        Answer::Sdf { sd, col } => vec![*sd, *col],
        Answer::Pixel { shade, .. } => vec![*shade],
        Answer::Bool { .. } | Answer::Image { .. } | Answer::Dot { .. } | Answer::Unsupported => {
            Vec::new()
        }
    }
}

/// The distance from `oracle` to `x` in units in the last place of f32, the
/// unit taken at the larger of the two magnitudes: finite at an oracle of
/// 0 (where the unit at 0 itself would make any error astronomical), and 0
/// when both are 0.
fn ulps_f32(x: f64, oracle: f64) -> f64 {
    let at = x.abs().max(oracle.abs()) as f32;
    if at == 0.0 {
        return 0.0;
    }
    let ulp = if at.is_finite() {
        f64::from(f32::from_bits(at.to_bits() + 1)) - f64::from(at)
    } else {
        f64::from(f32::MAX) - f64::from(f32::from_bits(f32::MAX.to_bits() - 1))
    };
    (x - oracle).abs() / ulp
}

/// The error of one answer against the oracle's answer to the same input:
/// the worst (by relative error) over the numbers it carries; `None` when
/// it carries none (`gt`, dithered bits).
pub fn answer_error(
    subject: &Answer,
    oracle: &Answer,
    subject_numbers: Numbers,
) -> Option<PointError> {
    point_error(&numbers_of(subject), &numbers_of(oracle), subject_numbers)
}

fn point_error(subject: &[Num], oracle: &[Num], subject_numbers: Numbers) -> Option<PointError> {
    let mut worst: Option<PointError> = None;
    for (s, o) in subject.iter().zip(oracle) {
        let (s, o) = (s.to_f64(), o.to_f64());
        let abs = if s.is_nan() && o.is_nan() {
            0.0
        } else {
            (s - o).abs()
        };
        let abs = if abs.is_nan() { f64::INFINITY } else { abs };
        let rel = if o == 0.0 { abs } else { abs / o.abs() };
        let ulps_f32 = (subject_numbers == Numbers::F32).then(|| ulps_f32(s, o));
        if worst.is_none_or(|w| rel > w.rel) {
            worst = Some(PointError { abs, rel, ulps_f32 });
        }
    }
    worst
}

fn pixel_flips(a: &Bitmap, b: &Bitmap) -> Vec<(usize, bool, bool)> {
    a.white
        .iter()
        .zip(&b.white)
        .enumerate()
        .filter(|(_, (x, y))| x != y)
        .map(|(i, (x, y))| (i, *x, *y))
        .collect()
}

/// One difference found on one vector, before bookkeeping.
struct Found {
    index: usize,
    input: Vector,
    kind: DiffKind,
    a: Outcome<Answer>,
    b: Outcome<Answer>,
    error: Option<PointError>,
    tolerated: bool,
}

fn image_differences(
    a: &Bitmap,
    b: &Bitmap,
    kind: DiffKind,
    tolerated: bool,
    stats: Option<&mut ErrorStats>,
) -> Vec<Found> {
    let flips = pixel_flips(a, b);
    if let Some(stats) = stats {
        stats.pixels += a.white.len();
        stats.flips += flips.len();
    }
    flips
        .into_iter()
        .map(|(i, x, y)| Found {
            index: i,
            input: Vector::Pixel(PixelVector {
                category: "image".to_string(),
                x: (i % a.width) as u16,
                y: (i / a.width) as u16,
            }),
            kind,
            a: Outcome::Value(Answer::Dot { white: x }),
            b: Outcome::Value(Answer::Dot { white: y }),
            error: None,
            tolerated,
        })
        .collect()
}

/// The exact policy on one vector.
fn exact(index: usize, input: &Vector, a: &Outcome<Answer>, b: &Outcome<Answer>) -> Vec<Found> {
    let found = |kind| {
        vec![Found {
            index,
            input: input.clone(),
            kind,
            a: a.clone(),
            b: b.clone(),
            error: None,
            tolerated: false,
        }]
    };
    if let Some(kind) = kind_difference(a, b) {
        return found(kind);
    }
    match (a, b) {
        (
            Outcome::Value(Answer::Image { bitmap: x }),
            Outcome::Value(Answer::Image { bitmap: y }),
        ) => image_differences(x, y, DiffKind::Value, false, None),
        _ if a != b => found(DiffKind::Value),
        _ => Vec::new(),
    }
}

/// The error policy on one vector; updates the aggregate figures.
fn error(
    index: usize,
    input: &Vector,
    a: &Outcome<Answer>,
    b: &Outcome<Answer>,
    subject_numbers: Numbers,
    t: &Thresholds,
    stats: &mut ErrorStats,
) -> Vec<Found> {
    let found = |kind, error, tolerated| Found {
        index,
        input: input.clone(),
        kind,
        a: a.clone(),
        b: b.clone(),
        error,
        tolerated,
    };
    if let Some(kind) = kind_difference(a, b) {
        return vec![found(kind, None, false)];
    }
    let (Outcome::Value(x), Outcome::Value(y)) = (a, b) else {
        return Vec::new();
    };
    if let (Answer::Image { bitmap: x }, Answer::Image { bitmap: y }) = (x, y) {
        return image_differences(x, y, DiffKind::Flip, true, Some(stats));
    }
    let mut out = Vec::new();
    if let (Answer::Bool { value: p }, Answer::Bool { value: q }) = (x, y) {
        if p != q {
            out.push(found(DiffKind::Value, None, false));
        }
    }
    if let (Answer::Pixel { white: p, .. }, Answer::Pixel { white: q, .. }) = (x, y) {
        stats.pixels += 1;
        if p != q {
            stats.flips += 1;
            out.push(found(DiffKind::Flip, None, true));
        }
    }
    if let Some(e) = answer_error(x, y, subject_numbers) {
        stats.values += 1;
        stats.max_abs = stats.max_abs.max(e.abs);
        stats.mean_abs += e.abs;
        stats.max_rel = stats.max_rel.max(e.rel);
        if let Some(u) = e.ulps_f32 {
            stats.max_ulps_f32 = Some(stats.max_ulps_f32.unwrap_or(0.0).max(u));
        }
        if e.abs > t.max_abs && e.rel > t.max_rel {
            // A shade error matters only through the pixel flips.
            let tolerated = matches!(x, Answer::Pixel { .. });
            if !out.iter().any(|f| f.kind == DiffKind::Flip) || !tolerated {
                out.push(found(DiffKind::Value, Some(e), tolerated));
            }
        }
    }
    out
}

/// Whether every value of an answer fits in f32 exactly: the tell-tale of
/// an oracle that computes in f32 while claiming f64.
fn exact_in_f32(answers: &[Outcome<Answer>]) -> (usize, usize) {
    let values: Vec<f64> = answers
        .iter()
        .filter_map(|o| match o {
            Outcome::Value(a) => Some(numbers_of(a)),
            _ => None,
        })
        .flatten()
        .map(Num::to_f64)
        .filter(|v| v.is_finite())
        .collect();
    let exact = values
        .iter()
        .filter(|v| f64::from(**v as f32) == **v)
        .count();
    (exact, values.len())
}

/// The sides of one comparison: the subject's and the oracle's answers.
pub struct Sides<'a> {
    pub a_label: &'a str,
    pub a_numbers: Numbers,
    /// Whether A checks the modelled domain itself.
    pub a_checks_domain: bool,
    pub a: &'a [Outcome<Answer>],
    pub b_label: &'a str,
    pub b_numbers: Numbers,
    pub b_checks_domain: bool,
    pub b: &'a [Outcome<Answer>],
}

impl Sides<'_> {
    /// Whether the answers to one input are left out as outside the
    /// modelled domain: one side answered out of domain and the other,
    /// which answered anything else, declares no domain check. (Two sides
    /// that both check, or a port answering out of domain where the
    /// reference answers a value, are compared.)
    fn outside_domain(&self, a: &Outcome<Answer>, b: &Outcome<Answer>) -> bool {
        let ood = |o: &Outcome<Answer>| matches!(o, Outcome::OutOfDomain);
        (ood(a) && !ood(b) && self.a_checks_domain && !self.b_checks_domain)
            || (ood(b) && !ood(a) && self.b_checks_domain && !self.a_checks_domain)
    }
}

/// What an input left out of a comparison is counted under: its
/// operation, or its level.
fn domain_key(input: &Vector, level: Level) -> String {
    match input {
        Vector::Op(v) => v.op.to_string(),
        _ => level.to_string(),
    }
}

/// Compare the answers of two implementations to the vectors of `set`
/// (same order) under the policy their numbers call for.
pub fn compare(set: &vectors::VectorSet, sides: &Sides) -> Comparison {
    let policy = Policy::for_pair(sides.a_numbers, sides.b_numbers);
    let mut stats = ErrorStats::default();
    let mut found = Vec::new();
    let mut outside_domain = BTreeMap::new();
    let mut unsupported = BTreeMap::new();
    let unsupported_by = |o: &Outcome<Answer>| matches!(o, Outcome::Value(Answer::Unsupported));
    for (i, input) in set.vectors.iter().enumerate() {
        let (a, b) = (&sides.a[i], &sides.b[i]);
        let skipped = if unsupported_by(a) || unsupported_by(b) {
            Some(&mut unsupported)
        } else if sides.outside_domain(a, b) {
            Some(&mut outside_domain)
        } else {
            None
        };
        if let Some(counts) = skipped {
            *counts.entry(domain_key(input, set.level)).or_insert(0) += 1;
            continue;
        }
        found.extend(match &policy {
            Policy::Exact => exact(i, input, a, b),
            Policy::Error { thresholds } => {
                error(i, input, a, b, sides.a_numbers, thresholds, &mut stats)
            }
        });
    }
    let mut findings = Vec::new();
    let stats = match &policy {
        Policy::Exact => None,
        Policy::Error { thresholds } => {
            if stats.values > 0 {
                stats.mean_abs /= stats.values as f64;
            }
            if stats.pixels > 0 {
                let fraction = stats.flips as f64 / stats.pixels as f64;
                if fraction > thresholds.max_flip_fraction {
                    findings.push(format!(
                        "{} of {} dithered pixels flip ({:.3}%), over the policy's {:.3}%",
                        stats.flips,
                        stats.pixels,
                        100.0 * fraction,
                        100.0 * thresholds.max_flip_fraction
                    ));
                }
            }
            if sides.b_numbers == Numbers::F64 {
                let (exact, total) = exact_in_f32(sides.b);
                // A genuine f64 oracle rounds most quotients and roots to
                // values f32 cannot hold; an f32 one never does.
                if total >= 16 && exact == total {
                    findings.push(format!(
                        "the oracle {} is not f64: all {total} of its values are exact f32 values",
                        sides.b_label
                    ));
                }
            }
            Some(stats)
        }
    };
    let diverged = !findings.is_empty() || found.iter().any(|f| !f.tolerated);
    let groups = group(set.level, &found);
    let omitted = found.len().saturating_sub(MAX_KEPT);
    let divergences = found
        .into_iter()
        .take(MAX_KEPT)
        .map(|f| Divergence {
            index: f.index,
            input: f.input,
            kind: f.kind,
            a: f.a,
            b: f.b,
            error: f.error,
            tolerated: f.tolerated,
            odd_one_out: None,
            localize: None,
            repro: None,
            reproducible: true,
        })
        .collect();
    Comparison {
        a: sides.a_label.to_string(),
        b: sides.b_label.to_string(),
        level: set.level,
        set: set.name.clone(),
        policy,
        vectors: set.vectors.len()
            - outside_domain.values().sum::<usize>()
            - unsupported.values().sum::<usize>(),
        divergences,
        omitted,
        groups,
        stats,
        findings,
        outside_domain,
        unsupported,
        diverged,
    }
}

fn group(level: Level, found: &[Found]) -> Vec<Group> {
    let mut groups: BTreeMap<(Option<common::Op>, String, DiffKind, bool), Group> = BTreeMap::new();
    for f in found {
        let op = match &f.input {
            Vector::Op(v) => Some(v.op),
            _ => None,
        };
        let key = (op, f.input.category().to_string(), f.kind, f.tolerated);
        groups
            .entry(key)
            .or_insert_with(|| Group {
                level,
                op,
                category: f.input.category().to_string(),
                kind: f.kind,
                count: 0,
                tolerated: f.tolerated,
                first: f.index,
            })
            .count += 1;
    }
    groups.into_values().collect()
}

/// When three or more answers are given and exactly one differs from all
/// the others (which agree), the index of that one.
pub fn odd_one_out(answers: &[&Outcome<Answer>]) -> Option<usize> {
    if answers.len() < 3 {
        return None;
    }
    let differs = |i: usize| {
        let others: Vec<_> = (0..answers.len()).filter(|&j| j != i).collect();
        others.iter().all(|&j| answers[j] == answers[others[0]]) && answers[i] != answers[others[0]]
    };
    (0..answers.len()).find(|&i| differs(i))
}

#[cfg(test)]
mod tests {
    use super::*;
    use common::{Op, F316};
    use vectors::{OpVector, VectorSet};

    fn ops_set(n: usize) -> VectorSet {
        let vectors = (0..n)
            .map(|i| {
                Vector::Op(OpVector {
                    category: if i % 2 == 0 { "even" } else { "odd" }.into(),
                    op: Op::Sqrt,
                    a: F316::new(0, 127 + i as i16, 8192),
                    b: None,
                })
            })
            .collect();
        VectorSet::new("t", Level::Ops, "", None, vectors)
    }

    fn num(t: F316) -> Outcome<Answer> {
        Outcome::Value(Answer::Num {
            value: Num::F316(t),
        })
    }

    fn f64_answer(x: f64) -> Outcome<Answer> {
        Outcome::Value(Answer::Num { value: Num::F64(x) })
    }

    fn pixel_vector(category: &str, x: u16, y: u16) -> Vector {
        Vector::Pixel(PixelVector {
            category: category.into(),
            x,
            y,
        })
    }

    fn sides<'a>(
        a: &'a [Outcome<Answer>],
        b: &'a [Outcome<Answer>],
        na: Numbers,
        nb: Numbers,
    ) -> Sides<'a> {
        Sides {
            a_label: "A",
            a_numbers: na,
            a_checks_domain: true,
            a,
            b_label: "B",
            b_numbers: nb,
            b_checks_domain: true,
            b,
        }
    }

    #[test]
    fn inputs_outside_the_modelled_domain_are_counted_unless_both_sides_check_it() {
        let set = ops_set(4);
        let reference = vec![
            Outcome::OutOfDomain,
            Outcome::OutOfDomain,
            num(F316::ONE),
            num(F316::ONE),
        ];
        // A port without a domain check of its own: a value where the
        // reference models none, and one wrong value.
        let port = vec![
            num(F316::ONE),
            Outcome::OutOfDomain,
            Outcome::OutOfDomain,
            num(F316::ZERO),
        ];
        let mut s = sides(&reference, &port, Numbers::Float316, Numbers::Float316);
        s.b_checks_domain = false;
        let c = compare(&set, &s);
        assert_eq!(c.outside_domain, BTreeMap::from([("sqrt".to_string(), 1)]));
        // The port's own out of domain where the reference answers, and
        // its wrong value, are divergences still.
        let diverging: Vec<usize> = c.divergences.iter().map(|d| d.index).collect();
        assert_eq!(diverging, [2, 3]);
        // Either side may be the one without the check.
        let mut s = sides(&port, &reference, Numbers::Float316, Numbers::Float316);
        s.a_checks_domain = false;
        assert_eq!(compare(&set, &s).outside_domain.values().sum::<usize>(), 1);
        // Declared checks on both sides: compared as before.
        let c = compare(
            &set,
            &sides(&reference, &port, Numbers::Float316, Numbers::Float316),
        );
        assert!(c.outside_domain.is_empty());
        assert_eq!(c.divergences.len(), 3);
    }

    #[test]
    fn exact_policy_classifies_every_kind_of_difference() {
        let set = ops_set(6);
        let a = vec![
            num(F316::ONE),
            num(F316::ONE),
            Outcome::SysError(2),
            Outcome::SysError(2),
            Outcome::Hang,
            Outcome::OutOfDomain,
        ];
        let b = vec![
            num(F316::ONE),
            num(F316::new(0, 127, 8193)),
            Outcome::SysError(3),
            num(F316::ZERO),
            num(F316::ZERO),
            Outcome::OutOfDomain,
        ];
        let c = compare(&set, &sides(&a, &b, Numbers::Float316, Numbers::Float316));
        assert!(c.diverged);
        let kinds: Vec<(usize, DiffKind)> =
            c.divergences.iter().map(|d| (d.index, d.kind)).collect();
        assert_eq!(
            kinds,
            [
                (1, DiffKind::Value),
                (2, DiffKind::ErrorCode),
                (3, DiffKind::OutcomeKind),
                (4, DiffKind::Hang)
            ]
        );
        // Groups: same op, category and kind together, in a stable order.
        let g: Vec<(String, DiffKind, usize)> = c
            .groups
            .iter()
            .map(|g| (g.category.clone(), g.kind, g.count))
            .collect();
        assert!(c.groups.iter().all(|g| g.op == Some(Op::Sqrt)));
        assert_eq!(
            g,
            [
                ("even".to_string(), DiffKind::ErrorCode, 1),
                ("even".to_string(), DiffKind::Hang, 1),
                ("odd".to_string(), DiffKind::Value, 1),
                ("odd".to_string(), DiffKind::OutcomeKind, 1),
            ]
        );
        let same = compare(&set, &sides(&a, &a, Numbers::Float316, Numbers::Float316));
        assert!(!same.diverged && same.divergences.is_empty());
    }

    #[test]
    fn error_policy_reports_figures_and_thresholds() {
        let set = ops_set(2);
        let f = f64_answer;
        let g = |x: f32| Outcome::Value(Answer::Num { value: Num::F32(x) });
        let oracle = vec![f(1.0 + 1e-9), f(2.0)];
        let close = vec![g(1.0), g(2.0)];
        let c = compare(&set, &sides(&close, &oracle, Numbers::F32, Numbers::F64));
        assert!(!c.diverged, "{c:?}");
        let s = c.stats.unwrap();
        assert_eq!(s.values, 2);
        assert!((s.max_abs - 1e-9).abs() < 1e-12);
        assert!(s.max_ulps_f32.unwrap() < 0.1);
        let far = vec![g(1.5), g(2.0)];
        let c = compare(&set, &sides(&far, &oracle, Numbers::F32, Numbers::F64));
        assert!(c.diverged);
        assert_eq!(c.divergences.len(), 1);
        assert_eq!(c.divergences[0].kind, DiffKind::Value);
    }

    #[test]
    fn the_mean_error_is_over_the_values_compared() {
        let set = ops_set(4);
        let f = f64_answer;
        let g = |x: f32| Outcome::Value(Answer::Num { value: Num::F32(x) });
        let oracle = vec![f(1.0), f(2.5), f(3.0), f(4.0)];
        let subject = vec![g(1.0), g(2.0), g(3.0), g(4.0)];
        let c = compare(&set, &sides(&subject, &oracle, Numbers::F32, Numbers::F64));
        assert_eq!(c.stats.unwrap().mean_abs, 0.125);
        // No value compared: no mean to take.
        let traps = vec![Outcome::SysError(1); 4];
        let c = compare(&set, &sides(&traps, &traps, Numbers::F32, Numbers::F64));
        assert_eq!(c.stats.unwrap().mean_abs, 0.0);
    }

    #[test]
    fn flips_diverge_only_beyond_the_policy_fraction() {
        // (A shade f32 cannot hold, so that the oracle passes for f64.)
        let pixel = |white| {
            Outcome::Value(Answer::Pixel {
                shade: Num::F64(0.1),
                white,
            })
        };
        // f32 against f64 allows 1% of the pixels to flip.
        let findings = |n: usize, flips: usize| {
            let oracle = vec![pixel(true); n];
            let subject: Vec<_> = (0..n).map(|i| pixel(i >= flips)).collect();
            compare(
                &ops_set(n),
                &sides(&subject, &oracle, Numbers::F32, Numbers::F64),
            )
            .findings
        };
        assert_eq!(
            findings(4, 1),
            ["1 of 4 dithered pixels flip (25.000%), over the policy's 1.000%"]
        );
        assert!(findings(100, 1).is_empty());
        assert!(findings(4, 0).is_empty());
    }

    #[test]
    fn an_f32_oracle_posing_as_f64_is_found() {
        let set = ops_set(20);
        let thirds: Vec<f64> = (0..20).map(|i| (i as f64 + 1.0) / 3.0).collect();
        let f64s: Vec<_> = thirds.iter().map(|&x| f64_answer(x)).collect();
        let f32s: Vec<_> = thirds
            .iter()
            .map(|&x| {
                Outcome::Value(Answer::Num {
                    value: Num::F64(f64::from(x as f32)),
                })
            })
            .collect();
        let honest = compare(&set, &sides(&f32s, &f64s, Numbers::F32, Numbers::F64));
        assert!(honest.findings.is_empty());
        let fooled = compare(&set, &sides(&f64s, &f32s, Numbers::F32, Numbers::F64));
        assert!(fooled.diverged);
        assert!(
            fooled.findings[0].contains("is not f64"),
            "{:?}",
            fooled.findings
        );
    }

    #[test]
    fn odd_one_out_needs_a_clear_majority() {
        let (x, y, z) = (num(F316::ONE), num(F316::ZERO), Outcome::Hang);
        assert_eq!(odd_one_out(&[&x, &x, &y]), Some(2));
        assert_eq!(odd_one_out(&[&y, &x, &x]), Some(0));
        assert_eq!(odd_one_out(&[&x, &y, &z]), None);
        assert_eq!(odd_one_out(&[&x, &y]), None);
        assert_eq!(odd_one_out(&[&x, &x, &x]), None);
    }

    /// Only two Float316 sides are compared bit for bit (mutation testing
    /// found `&&` -> `||` uncaught by the unit tests).
    #[test]
    fn only_float316_pairs_get_the_exact_policy() {
        use crate::implementation::Numbers::{Float316, F32, F64};
        assert!(matches!(
            Policy::for_pair(Float316, Float316),
            Policy::Exact
        ));
        for (subject, oracle) in [(Float316, F64), (F64, Float316), (F32, F64), (F64, F64)] {
            assert!(
                matches!(Policy::for_pair(subject, oracle), Policy::Error { .. }),
                "{subject:?} against {oracle:?}"
            );
        }
    }

    #[test]
    fn difference_kinds_have_their_names() {
        let names: Vec<String> = [
            DiffKind::Value,
            DiffKind::OutcomeKind,
            DiffKind::ErrorCode,
            DiffKind::Hang,
            DiffKind::Flip,
        ]
        .iter()
        .map(ToString::to_string)
        .collect();
        assert_eq!(
            names,
            ["value", "outcome kind", "error code", "hang", "pixel flip"]
        );
    }

    /// Distances in f32 units in the last place, at 1, at a power of two
    /// (the ulp above it), and at zero (the unit at the subject's value).
    #[test]
    fn f32_ulps_are_exact() {
        let ulp_at_one = f64::from(f32::EPSILON);
        assert_eq!(ulps_f32(1.0 + ulp_at_one, 1.0), 1.0);
        assert_eq!(ulps_f32(1.0 - 3.0 * ulp_at_one, 1.0), 3.0);
        // At an oracle of 0 the unit is the subject's own: finite, at most
        // 2^23 or so, never the 1e38 of the unit at 0.
        let at_zero = ulps_f32(1e-7, 0.0);
        assert!(at_zero > 1e6 && at_zero < 2f64.powi(24), "{at_zero}");
        assert_eq!(ulps_f32(0.0, 0.0), 0.0);
        assert_eq!(ulps_f32(-4.0 - 8.0 * ulp_at_one, -4.0), 2.0);
    }

    #[test]
    fn the_worst_number_is_the_first_of_the_largest_relative_error() {
        let error = |s: &[f64], o: &[f64]| {
            let nums = |v: &[f64]| v.iter().map(|&x| Num::F64(x)).collect::<Vec<_>>();
            point_error(&nums(s), &nums(o), Numbers::F64).unwrap()
        };
        // 2 against 1 is the larger error, wherever it stands.
        assert_eq!(error(&[1.0, 2.0], &[1.0, 1.0]).rel, 1.0);
        assert_eq!(error(&[2.0, 1.0], &[1.0, 1.0]).rel, 1.0);
        // Equal relative errors: the first number's is kept.
        assert_eq!(error(&[2.0, 4.0], &[1.0, 2.0]).abs, 1.0);
    }

    #[test]
    fn every_flipped_pixel_is_found_with_its_position_and_both_bits() {
        let bitmap = |white: [bool; 6]| Bitmap {
            width: 3,
            height: 2,
            white: white.to_vec(),
        };
        let a = bitmap([false, true, false, false, true, true]);
        let b = bitmap([false, false, false, true, true, true]);
        let mut stats = ErrorStats::default();
        let found = image_differences(&a, &b, DiffKind::Flip, true, Some(&mut stats));
        let seen: Vec<_> = found
            .iter()
            .map(|f| (f.index, f.input.clone(), f.a.clone(), f.b.clone()))
            .collect();
        let pixel = |x, y| pixel_vector("image", x, y);
        let dot = |white| Outcome::Value(Answer::Dot { white });
        assert_eq!(
            seen,
            [
                (1, pixel(1, 0), dot(true), dot(false)),
                (3, pixel(0, 1), dot(false), dot(true)),
            ]
        );
        assert!(found
            .iter()
            .all(|f| f.kind == DiffKind::Flip && f.tolerated));
        assert_eq!((stats.pixels, stats.flips), (6, 2));
    }

    #[test]
    fn the_exact_policy_compares_images_pixel_by_pixel() {
        let image = |white: Vec<bool>| {
            Outcome::Value(Answer::Image {
                bitmap: Bitmap {
                    width: 2,
                    height: 1,
                    white,
                },
            })
        };
        let input = pixel_vector("image", 0, 0);
        let found = exact(
            7,
            &input,
            &image(vec![true, true]),
            &image(vec![true, false]),
        );
        let seen: Vec<_> = found
            .iter()
            .map(|f| (f.index, f.kind, f.tolerated))
            .collect();
        assert_eq!(seen, [(1, DiffKind::Value, false)]);
    }

    #[test]
    fn the_error_policy_counts_flips_and_reports_a_shade_error_only_without_a_flip() {
        let input = pixel_vector("c", 0, 0);
        let t = Thresholds {
            max_abs: 0.01,
            max_rel: 0.01,
            max_flip_fraction: 0.0,
        };
        let mut stats = ErrorStats::default();
        let mut run = |a: Outcome<Answer>, b: Outcome<Answer>| {
            error(0, &input, &a, &b, Numbers::F64, &t, &mut stats)
                .into_iter()
                .map(|f| (f.kind, f.error.is_some(), f.tolerated))
                .collect::<Vec<_>>()
        };
        let pixel = |shade, white| {
            Outcome::Value(Answer::Pixel {
                shade: Num::F64(shade),
                white,
            })
        };
        // Within the thresholds, or over only one of them: no difference.
        assert_eq!(run(pixel(0.5, true), pixel(0.5001, true)), []);
        assert_eq!(run(pixel(100.5, true), pixel(100.0, true)), []);
        assert_eq!(run(pixel(0.002, true), pixel(0.001, true)), []);
        // A flip with a large shade error: the flip alone, tolerated.
        let flip = (DiffKind::Flip, false, true);
        assert_eq!(run(pixel(0.9, true), pixel(0.1, false)), [flip]);
        // A large shade error without a flip: a tolerated value difference.
        let shade = (DiffKind::Value, true, true);
        assert_eq!(run(pixel(0.9, true), pixel(0.1, true)), [shade]);
        // gt's answers: another bool is a value difference, not tolerated.
        let bool = |value| Outcome::Value(Answer::Bool { value });
        assert_eq!(
            run(bool(true), bool(false)),
            [(DiffKind::Value, false, false)]
        );
        assert_eq!(run(bool(false), bool(false)), []);
        assert_eq!((stats.pixels, stats.flips, stats.values), (5, 1, 5));
    }

    #[test]
    fn a_value_differs_only_beyond_both_thresholds() {
        let input = pixel_vector("c", 0, 0);
        let value = f64_answer;
        // 1.25 against 1 is an absolute and a relative error of 0.25.
        let differs = |max_abs, max_rel| {
            let t = Thresholds {
                max_abs,
                max_rel,
                max_flip_fraction: 0.0,
            };
            let mut stats = ErrorStats::default();
            let found = error(
                0,
                &input,
                &value(1.25),
                &value(1.0),
                Numbers::F64,
                &t,
                &mut stats,
            );
            !found.is_empty()
        };
        assert!(differs(0.125, 0.125));
        assert!(!differs(0.25, 0.125));
        assert!(!differs(0.125, 0.25));
    }

    #[test]
    fn a_nan_is_no_error_only_against_a_nan() {
        let error = |s: f64, o: f64| point_error(&[Num::F64(s)], &[Num::F64(o)], Numbers::F64);
        assert_eq!(error(f64::NAN, f64::NAN).unwrap().abs, 0.0);
        for (s, o) in [(f64::NAN, 1.0), (2.0, f64::NAN)] {
            let one = error(s, o).unwrap();
            assert_eq!(one.abs, f64::INFINITY, "{s} against {o}");
        }
    }
}
