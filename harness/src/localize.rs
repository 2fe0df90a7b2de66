//! Localization: given two implementations and one input on which they
//! differ, find the first Float316 operation that differs. The answers are
//! compared first: traces that differ on the way to the same answer are a
//! difference that does not reach it. Both op traces are then diffed,
//! records paired by what they compute (operation and operands; paths are
//! informative), whatever order each side computes them in
//! ([`diff_traces`]); the answer is the first divergent record with the
//! last matching one before it (Gameboy-Doctor style), and its *origin*:
//! the innermost operation that was given identical operands and still
//! produced a different result (the operation at fault).
//!
//! An implementation that cannot trace (gpu-f316) is localized by replay:
//! after checking against `ref-f316` which side differs, every operation of
//! ref-f316's trace is run through it alone, and the first one whose result
//! differs from the trace is the divergent operation.
//!
//! A side whose call nesting and operation order differ from the
//! reference's (a user's Jack program) is localized without assuming our
//! structure: when the record-by-record diff finds no operation at fault,
//! every record of that side's own trace is replayed through the tracer
//! ([`Replayed`]: the first operation whose result differs from ref-f316's
//! on the same operands, with its call path), and its operands are looked
//! up in the tracer's trace of the same input ([`StrayInputs`]: the first
//! operation whose inputs ref-f316 never sees, when the inputs already
//! differ).

use crate::implementation::{Answer, ImplError, Implementation, Numbers};
use common::{Op, OpValue, Outcome, TraceRecord};
use serde::{Deserialize, Serialize};
use std::collections::{HashMap, VecDeque};
use std::fmt;
use vectors::{OpVector, Vector};

/// The first point where two traces part.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FirstDivergence {
    /// Index of the first differing record (in A's trace).
    pub index: usize,
    /// Index of B's record, where it is not `index`: the traces run in
    /// different orders, and B's record is the one computing the same
    /// operation on the same operands (or B's first record with no equal).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub b_index: Option<usize>,
    /// The last record on which both agree, for context.
    pub previous: Option<TraceRecord>,
    /// A's record there (`None`: every record of A has its equal in B).
    pub a: Option<TraceRecord>,
    /// B's record there (`None`: B has no record on the same operands, and
    /// every record it has is paired).
    pub b: Option<TraceRecord>,
}

/// The operation at fault: identical operands, different results.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Origin {
    /// Index of its record.
    pub index: usize,
    pub op: Op,
    pub args: Vec<common::F316>,
    /// A's result.
    pub a: Outcome<OpValue>,
    /// B's result.
    pub b: Outcome<OpValue>,
    /// Its call path (from the trace that has one).
    pub path: Vec<String>,
}

/// The answer of `harness localize`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Localization {
    pub input: Vector,
    pub a: String,
    pub b: String,
    /// A's and B's answers to the input.
    pub a_answer: Outcome<Answer>,
    pub b_answer: Outcome<Answer>,
    /// How the traces were obtained and compared.
    pub method: String,
    /// Lengths of the two traces compared.
    pub trace_lengths: (usize, usize),
    /// Where the traces part (`None`: they agree throughout).
    pub first: Option<FirstDivergence>,
    /// The operation at fault, when one has identical operands.
    pub origin: Option<Origin>,
    /// When the answers differ but the traces agree throughout: the last
    /// operation, after which the logic that uses its result differs.
    pub after_last: Option<TraceRecord>,
    /// When the diff finds no operation at fault: the first operation of a
    /// side's own trace whose result differs from the tracer's on the same
    /// operands.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub replayed: Option<Replayed>,
    /// The first operation of a side's own trace whose operands the
    /// tracer's trace of the input never has (the inputs already differ),
    /// when it comes before any operation at fault.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inputs_differ: Option<StrayInputs>,
}

/// An operation of one side's own trace that the tracer computes
/// differently from the same operands: the operation at fault, whatever the
/// side's call nesting and operation order.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Replayed {
    /// The side (its label).
    pub side: String,
    /// The tracer (its label).
    pub tracer: String,
    /// Index of the record in the side's trace.
    pub index: usize,
    /// The record: operands, the side's result and its call path.
    pub record: TraceRecord,
    /// The tracer's result on the same operands.
    pub expected: Outcome<OpValue>,
}

/// An operation of one side whose operands appear in no operation of the
/// tracer's trace of the same input: the inputs already differ there.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StrayInputs {
    /// The side (its label).
    pub side: String,
    /// The tracer (its label).
    pub tracer: String,
    /// Index of the record in the side's trace.
    pub index: usize,
    /// The record.
    pub record: TraceRecord,
}

impl Localization {
    /// Whether the two answers differ at all.
    pub fn differs(&self) -> bool {
        self.a_answer != self.b_answer
    }

    /// The finding in one line, for tables: the operation at fault with its
    /// operands, both results and call path; else the first divergent
    /// record of each side; else where the answers part after the traces.
    pub fn one_line(&self) -> String {
        if let (None, Some(r)) = (&self.origin, &self.replayed) {
            return format!(
                "{} = {} ({}) vs {} ({}), record {} of {}'s own trace",
                r.record, r.record.result, r.side, r.expected, r.tracer, r.index, r.side
            );
        }
        if let Some(o) = &self.origin {
            let args: Vec<String> = o.args.iter().map(ToString::to_string).collect();
            return format!(
                "{}({}) = {} ({}) vs {} ({}), record {} [{}]",
                o.op,
                args.join(", "),
                o.a,
                self.a,
                o.b,
                self.b,
                o.index,
                o.path.join(" > ")
            );
        }
        let record = |r: &Option<TraceRecord>| {
            r.as_ref()
                .map_or_else(|| "(no such record)".to_string(), ToString::to_string)
        };
        match (&self.first, &self.after_last) {
            (Some(first), _) => format!(
                "record {}, the operands differ first: {}: {} | {}: {}",
                first.index,
                self.a,
                record(&first.a),
                self.b,
                record(&first.b)
            ),
            (None, Some(last)) => {
                format!("every operation agrees; the answers differ after the last one: {last}")
            }
            (None, None) => "the answers and traces agree".to_string(),
        }
    }

    /// The operation the divergence is blamed on: the origin, else the
    /// first divergent record's operation.
    pub fn blamed_op(&self) -> Option<Op> {
        let replayed = self.replayed.as_ref().map(|r| r.record.op);
        self.origin.as_ref().map(|o| o.op).or(replayed).or_else(|| {
            self.first
                .as_ref()
                .and_then(|f| f.a.as_ref().or(f.b.as_ref()).map(|r| r.op))
        })
    }
}

/// Why localization could not be done.
#[derive(Debug, thiserror::Error)]
pub enum LocalizeError {
    #[error("{0}: {1}")]
    Impl(String, ImplError),
    #[error("{0}")]
    Unsupported(String),
}

fn nested(outer: &TraceRecord, inner: &TraceRecord) -> bool {
    inner.path.len() > outer.path.len() && inner.path.starts_with(&outer.path)
}

/// Diff two traces: the first divergent record and the origin.
///
/// Records are paired by what they compute, not by position: each record
/// of A is paired with B's earliest unpaired record of the same operation
/// on the same operands (`add` and `mul` in either order), so a port that
/// computes a dot product's products before its sums pairs its `mul`s with
/// the reference's. The first divergence is A's first record whose
/// partner gives another result; it is also where the origin search
/// starts, descending into the operations that record calls while one of
/// them differs too. Where no record has such a partner, it is A's first
/// record that B never computes, beside B's first that A never computes:
/// the operands differ there. A record only one side traces (a port that
/// traces fewer operations) is not a divergence by itself. Where both
/// traces run in the same order this is the record-by-record diff.
pub fn diff_traces(
    a: &[TraceRecord],
    b: &[TraceRecord],
) -> (Option<FirstDivergence>, Option<Origin>) {
    let a_partner = pair_by_operands(a, b);
    let b_partner = pair_by_operands(b, a);
    let differs = |i: usize| a_partner[i].is_some_and(|j| a[i].result != b[j].result);
    let b_unpaired = b_partner.iter().position(Option::is_none);
    let origin_start = (0..a.len()).find(|&i| differs(i));
    let (index, b_index) = match origin_start {
        Some(i) => (i, a_partner[i]),
        None => match (a_partner.iter().position(Option::is_none), b_unpaired) {
            (None, None) => return (None, None),
            (Some(i), j) => (i, j),
            // Every record of A has its equal in B: B computes more.
            (None, Some(j)) => (a.len(), Some(j)),
        },
    };
    let first = FirstDivergence {
        index,
        b_index: b_index.filter(|&j| j != index),
        previous: (0..index)
            .rev()
            .find(|&i| a_partner[i].is_some())
            .map(|i| a[i].clone()),
        a: a.get(index).cloned(),
        b: b_index.map(|j| b[j].clone()),
    };
    // Whether record `inner` runs inside `outer`, by either side's paths.
    let inside = |outer: usize, inner: usize| {
        nested(&a[outer], &a[inner])
            || matches!((a_partner[outer], a_partner[inner]),
                (Some(o), Some(n)) if nested(&b[o], &b[n]))
    };
    let origin = origin_start.map(|mut at| {
        loop {
            let deeper = (at + 1..a.len())
                .take_while(|&k| inside(at, k))
                .find(|&k| differs(k));
            match deeper {
                Some(k) => at = k,
                None => break,
            }
        }
        let partner = &b[a_partner[at].unwrap_or_default()];
        Origin {
            index: at,
            op: a[at].op,
            args: a[at].args.clone(),
            a: a[at].result,
            b: partner.result,
            path: if a[at].path.is_empty() {
                partner.path.clone()
            } else {
                a[at].path.clone()
            },
        }
    });
    (Some(first), origin)
}

/// The key of an operation for looking up its operands: `add` and `mul`
/// take theirs in either order.
fn operands_key(r: &TraceRecord) -> (Op, Vec<common::F316>) {
    let mut args = r.args.clone();
    if matches!(r.op, Op::Add | Op::Mul) {
        args.sort_by_key(|v| (v.s, v.e, v.m));
    }
    (r.op, args)
}

/// For each record of `a`, the earliest record of `b` not yet taken that
/// computes the same operation on the same operands.
fn pair_by_operands(a: &[TraceRecord], b: &[TraceRecord]) -> Vec<Option<usize>> {
    let mut by_key: HashMap<(Op, Vec<common::F316>), VecDeque<usize>> = HashMap::new();
    for (j, r) in b.iter().enumerate() {
        by_key.entry(operands_key(r)).or_default().push_back(j);
    }
    a.iter()
        .map(|r| {
            by_key
                .get_mut(&operands_key(r))
                .and_then(VecDeque::pop_front)
        })
        .collect()
}

/// Replay `own` (a side's trace) through `tracer`: the first record whose
/// result differs, descending into the operations it calls while one of
/// them differs too (the innermost operation at fault).
fn replay_search(
    side: &dyn Implementation,
    tracer: &dyn Implementation,
    own: &[TraceRecord],
) -> Result<Option<Replayed>, LocalizeError> {
    let expected = replay(tracer, own)?;
    let differs = |i: usize| own[i].result != expected[i].result;
    let Some(mut at) = (0..own.len()).find(|&i| differs(i)) else {
        return Ok(None);
    };
    loop {
        let deeper = (at + 1..own.len())
            .take_while(|&j| nested(&own[at], &own[j]))
            .find(|&j| differs(j));
        match deeper {
            Some(j) => at = j,
            None => break,
        }
    }
    Ok(Some(Replayed {
        side: side.label(),
        tracer: tracer.label(),
        index: at,
        record: own[at].clone(),
        expected: expected[at].result,
    }))
}

/// The first record of `own` whose operands no record of `reference` has.
fn stray_inputs(
    side: &dyn Implementation,
    tracer: &dyn Implementation,
    own: &[TraceRecord],
    reference: &[TraceRecord],
) -> Option<StrayInputs> {
    let known: std::collections::HashSet<(Op, Vec<common::F316>)> =
        reference.iter().map(operands_key).collect();
    own.iter()
        .position(|r| !known.contains(&operands_key(r)))
        .map(|index| StrayInputs {
            side: side.label(),
            tracer: tracer.label(),
            index,
            record: own[index].clone(),
        })
}

fn eval_one(imp: &dyn Implementation, input: &Vector) -> Result<Outcome<Answer>, LocalizeError> {
    let answer = imp
        .eval(std::slice::from_ref(input))
        .map_err(|e| LocalizeError::Impl(imp.label(), e))?
        .pop()
        .ok_or_else(|| LocalizeError::Impl(imp.label(), ImplError::Failed("no answer".into())))?;
    match answer {
        Outcome::Value(Answer::Unsupported) => Err(LocalizeError::Unsupported(format!(
            "{} has no such operation: {input}",
            imp.label()
        ))),
        answer => Ok(answer),
    }
}

fn to_op_answer(r: &Outcome<OpValue>) -> Outcome<Answer> {
    r.map(Answer::from)
}

fn from_op_answer(r: Outcome<Answer>) -> Outcome<OpValue> {
    match r {
        Outcome::Value(Answer::Bool { value }) => Outcome::Value(OpValue::Bool(value)),
        Outcome::Value(Answer::Num {
            value: crate::implementation::Num::F316(t),
        }) => Outcome::Value(OpValue::Num(t)),
        // Any other kind of answer is out of place for an operation.
        Outcome::Value(_) => Outcome::OutOfDomain,
        Outcome::SysError(c) => Outcome::SysError(c),
        Outcome::Hang => Outcome::Hang,
        Outcome::OutOfDomain => Outcome::OutOfDomain,
    }
}

/// Replay every operation of `trace` through `imp` (ops level) and build
/// the trace `imp` would have produced with the same operands: the same
/// records with `imp`'s results (the trace's own, for an operation `imp`
/// answers unsupported).
pub fn replay(
    imp: &dyn Implementation,
    trace: &[TraceRecord],
) -> Result<Vec<TraceRecord>, LocalizeError> {
    let batch: Vec<Vector> = trace
        .iter()
        .map(|r| {
            Vector::Op(OpVector {
                category: "replay".into(),
                op: r.op,
                a: r.args[0],
                b: r.args.get(1).copied(),
            })
        })
        .collect();
    let answers = imp
        .eval(&batch)
        .map_err(|e| LocalizeError::Impl(imp.label(), e))?;
    Ok(trace
        .iter()
        .zip(answers)
        .map(|(r, answer)| TraceRecord {
            // An operation `imp` does not have (it computes it inline)
            // cannot be replayed: its record is taken as it is.
            result: match answer {
                Outcome::Value(Answer::Unsupported) => r.result,
                answer => from_op_answer(answer),
            },
            ..r.clone()
        })
        .collect())
}

/// Whether `a` and `b` can be localized op by op: both must compute with
/// Float316 (a float implementation has no Float316 operations, and
/// replaying Float316 operands through it would compare nothing).
pub fn localizable(a: &dyn Implementation, b: &dyn Implementation) -> Result<(), LocalizeError> {
    for imp in [a, b] {
        let numbers = match imp.numbers() {
            Numbers::Float316 => continue,
            other => other.name(),
        };
        return Err(LocalizeError::Unsupported(format!(
            "{} computes with {numbers}: it has no Float316 operations to compare op by op \
             (`harness diff` gives its error figures)",
            imp.label()
        )));
    }
    Ok(())
}

/// Localize the difference between `a` and `b` at `input`. `tracer` is a
/// clean Float316 implementation that traces (ref-f316), used when one side
/// cannot trace. Both sides must compute with Float316 ([`localizable`]).
pub fn localize(
    a: &dyn Implementation,
    b: &dyn Implementation,
    tracer: &dyn Implementation,
    input: &Vector,
) -> Result<Localization, LocalizeError> {
    localizable(a, b)?;
    let a_answer = eval_one(a, input)?;
    let b_answer = eval_one(b, input)?;
    let trace_of = |imp: &dyn Implementation| match imp.trace(input) {
        Ok(t) => Ok(Some(t)),
        Err(ImplError::Unsupported(_)) => Ok(None),
        Err(e) => Err(LocalizeError::Impl(imp.label(), e)),
    };
    let (ta, tb) = (trace_of(a)?, trace_of(b)?);
    let own = [(a, ta.clone()), (b, tb.clone())];
    let (method, ta, tb) = match (ta, tb) {
        (Some(ta), Some(tb)) => ("op traces of both".to_string(), ta, tb),
        (ta, tb) => {
            // One side (at least) cannot trace: find out which side differs
            // from the clean tracer, and replay its trace through it.
            let reference_trace = tracer
                .trace(input)
                .map_err(|e| LocalizeError::Impl(tracer.label(), e))?;
            let reference_answer = eval_one(tracer, input)?;
            let side = |imp: &dyn Implementation,
                        own: Option<Vec<TraceRecord>>,
                        answer: &Outcome<Answer>| {
                match own {
                    Some(t) => Ok::<_, LocalizeError>((t, "own trace".to_string())),
                    None if *answer == reference_answer => Ok((
                        reference_trace.clone(),
                        format!("agrees with {}: its trace", tracer.label()),
                    )),
                    None => Ok((
                        replay(imp, &reference_trace)?,
                        format!("{}'s trace replayed op by op", tracer.label()),
                    )),
                }
            };
            let (ta, ma) = side(a, ta, &a_answer)?;
            let (tb, mb) = side(b, tb, &b_answer)?;
            (format!("{}: {ma}; {}: {mb}", a.label(), b.label()), ta, tb)
        }
    };
    let (first, origin) = diff_traces(&ta, &tb);
    let after_last = match (&first, a_answer != b_answer) {
        (None, true) => ta.last().cloned(),
        _ => None,
    };
    let (mut replayed, mut inputs_differ) = (None, None);
    if origin.is_none() && a_answer != b_answer {
        let tracer_label = tracer.label();
        let mut reference_trace = None;
        for (side, trace) in own {
            let Some(trace) = trace.filter(|_| side.label() != tracer_label) else {
                continue;
            };
            if replayed.is_none() {
                replayed = replay_search(side, tracer, &trace)?;
            }
            if inputs_differ.is_none() {
                if reference_trace.is_none() {
                    reference_trace = Some(
                        tracer
                            .trace(input)
                            .map_err(|e| LocalizeError::Impl(tracer_label.clone(), e))?,
                    );
                }
                let reference = reference_trace.as_deref().unwrap_or_default();
                inputs_differ = stray_inputs(side, tracer, &trace, reference)
                    .filter(|s| replayed.as_ref().is_none_or(|r| s.index < r.index));
            }
        }
    }
    Ok(Localization {
        input: input.clone(),
        a: a.label(),
        b: b.label(),
        a_answer,
        b_answer,
        method,
        trace_lengths: (ta.len(), tb.len()),
        first,
        origin,
        after_last,
        replayed,
        inputs_differ,
    })
}

/// The answer of an operation record as an `Answer`, for printing.
pub fn record_answer(r: &TraceRecord) -> Outcome<Answer> {
    to_op_answer(&r.result)
}

impl fmt::Display for Localization {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let w = self.a.len().max(self.b.len());
        writeln!(f, "input: {}", self.input)?;
        writeln!(f, "  {:w$}  {}", self.a, self.a_answer)?;
        writeln!(f, "  {:w$}  {}", self.b, self.b_answer)?;
        writeln!(
            f,
            "traces: {} ({} and {} records)",
            self.method, self.trace_lengths.0, self.trace_lengths.1
        )?;
        let Some(first) = &self.first else {
            writeln!(f, "the traces agree on every operation")?;
            if let Some(last) = &self.after_last {
                writeln!(f, "the answers differ after the last operation, in the logic that uses its result:")?;
                writeln!(f, "  last operation  {last}")?;
            }
            return Ok(());
        };
        if !self.differs() {
            writeln!(
                f,
                "the answers agree: the traces differ, but the difference does not reach the answer"
            )?;
        }
        match first.b_index {
            None => writeln!(f, "first divergent operation: record {}", first.index)?,
            Some(j) => writeln!(
                f,
                "first divergent operation: record {} of {}, record {j} of {} \
                 (records are paired by operation and operands)",
                first.index, self.a, self.b
            )?,
        }
        match &first.previous {
            Some(p) => writeln!(f, "  last match  {p}")?,
            None => writeln!(f, "  (it is the first record)")?,
        }
        for (label, r) in [(&self.a, &first.a), (&self.b, &first.b)] {
            match r {
                Some(r) => writeln!(f, "  {label:w$}  {r}")?,
                None => writeln!(f, "  {label:w$}  (no such record)")?,
            }
        }
        if let (None, Some(r)) = (&self.origin, &self.replayed) {
            writeln!(
                f,
                "origin (replayed through {}): {}({}) at record {} of {}'s own trace [{}]",
                r.tracer,
                r.record.op,
                r.record
                    .args
                    .iter()
                    .map(ToString::to_string)
                    .collect::<Vec<_>>()
                    .join(", "),
                r.index,
                r.side,
                r.record.path.join(" > ")
            )?;
            writeln!(f, "  {:w$}  = {}", r.side, r.record.result)?;
            return writeln!(f, "  {:w$}  = {}", r.tracer, r.expected);
        }
        if let Some(s) = &self.inputs_differ {
            writeln!(
                f,
                "the inputs already differ: {}'s record {}, {}, has operands no {} operation has",
                s.side, s.index, s.record, s.tracer
            )?;
        }
        match &self.origin {
            Some(o) => {
                let args: Vec<String> = o.args.iter().map(ToString::to_string).collect();
                writeln!(
                    f,
                    "origin: {}({}) at record {} [{}]",
                    o.op,
                    args.join(", "),
                    o.index,
                    o.path.join(" > ")
                )?;
                writeln!(f, "  {:w$}  = {}", self.a, o.a)?;
                writeln!(f, "  {:w$}  = {}", self.b, o.b)
            }
            None => writeln!(
                f,
                "origin: no operation differs on identical operands (the operands differ first)"
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use common::F316;

    fn n(m: i16) -> F316 {
        F316::new(0, 127, m)
    }

    fn rec(op: Op, args: &[i16], result: i16, path: &[&str]) -> TraceRecord {
        TraceRecord {
            op,
            args: args.iter().map(|&m| n(m)).collect(),
            result: Outcome::Value(OpValue::Num(n(result))),
            path: path.iter().map(ToString::to_string).collect(),
        }
    }

    /// A dot product of (1, 2, 3) and (4, 5, 6), the reference's way: each
    /// product summed as it comes.
    fn interleaved(fault: Option<i16>) -> Vec<TraceRecord> {
        let sum = fault.unwrap_or(14);
        vec![
            rec(Op::Mul, &[1, 4], 4, &["dot"]),
            rec(Op::Mul, &[2, 5], 10, &["dot"]),
            rec(Op::Add, &[4, 10], sum, &["dot"]),
            rec(Op::Mul, &[3, 6], 18, &["dot"]),
            rec(Op::Add, &[sum, 18], sum + 18, &["dot"]),
        ]
    }

    /// The same dot product with the three products first, as a user's
    /// port wrote it.
    fn products_first(fault: Option<i16>) -> Vec<TraceRecord> {
        let sum = fault.unwrap_or(14);
        vec![
            rec(Op::Mul, &[1, 4], 4, &["Vec.dot"]),
            rec(Op::Mul, &[2, 5], 10, &["Vec.dot"]),
            rec(Op::Mul, &[3, 6], 18, &["Vec.dot"]),
            rec(Op::Add, &[10, 4], sum, &["Vec.dot"]),
            rec(Op::Add, &[18, sum], sum + 18, &["Vec.dot"]),
        ]
    }

    #[test]
    fn traces_in_different_orders_with_the_same_operations_agree() {
        assert_eq!(
            diff_traces(&interleaved(None), &products_first(None)),
            (None, None)
        );
        assert_eq!(
            diff_traces(&products_first(None), &interleaved(None)),
            (None, None)
        );
    }

    #[test]
    fn a_fault_is_paired_with_the_same_operation_whatever_the_order() {
        let (first, origin) = diff_traces(&interleaved(None), &products_first(Some(15)));
        let first = first.expect("a divergence");
        // The reference's first add, paired with the port's first add (its
        // record 3), not with the port's third mul at the same position.
        assert_eq!((first.index, first.b_index), (2, Some(3)));
        assert_eq!(first.a.as_ref().map(|r| r.op), Some(Op::Add));
        assert_eq!(first.b.as_ref().map(|r| r.op), Some(Op::Add));
        let origin = origin.expect("an origin");
        assert_eq!((origin.op, origin.index), (Op::Add, 2));
        assert_eq!(origin.b, Outcome::Value(OpValue::Num(n(15))));
    }

    #[test]
    fn traces_in_the_same_order_diff_record_by_record() {
        let (first, origin) = diff_traces(&interleaved(None), &interleaved(Some(15)));
        let first = first.expect("a divergence");
        assert_eq!((first.index, first.b_index), (2, None));
        assert_eq!(first.previous, Some(interleaved(None)[1].clone()));
        assert_eq!(origin.map(|o| o.index), Some(2));
    }

    #[test]
    fn a_longer_trace_diverges_where_the_shorter_ends() {
        let long = interleaved(None);
        let (first, origin) = diff_traces(&long[..3], &long);
        let first = first.expect("a divergence");
        assert_eq!((first.index, first.b_index, first.a), (3, None, None));
        assert_eq!(first.b, Some(long[3].clone()));
        assert_eq!(origin, None);
    }

    #[test]
    fn an_operation_only_one_side_traces_is_not_the_divergence() {
        // The port traces its invSqrt and the sub inside it, not the muls,
        // and its sub answers -1 where the reference's answers 2 (its
        // result aliases an operand).
        let reference = vec![
            rec(Op::InvSqrt, &[1], 1, &[]),
            rec(Op::Mul, &[1, 1], 1, &["inv_sqrt"]),
            rec(Op::Sub, &[3, 1], 2, &["inv_sqrt"]),
        ];
        let mut port = vec![reference[0].clone(), reference[2].clone()];
        port[1].result = Outcome::Value(OpValue::Num(F316::new(1, 127, 2)));
        let (first, origin) = diff_traces(&reference, &port);
        let first = first.expect("a divergence");
        assert_eq!((first.index, first.b_index), (2, Some(1)));
        assert_eq!(first.previous, Some(reference[0].clone()));
        assert_eq!(origin.map(|o| (o.op, o.index)), Some((Op::Sub, 2)));
        // With the port's sub right, what is left is the mul the port does
        // not trace: shown, with nothing on the port's side, and no origin.
        port[1] = reference[2].clone();
        let (first, origin) = diff_traces(&reference, &port);
        let first = first.expect("the untraced mul");
        assert_eq!((first.index, first.b_index, first.b), (1, None, None));
        assert_eq!(origin, None);
    }

    #[test]
    fn the_origin_is_the_innermost_operation_at_fault() {
        let outer = |r: i16| rec(Op::InvSqrt, &[1], r, &["pixel"]);
        let a = vec![
            outer(1),
            rec(Op::Mul, &[1, 1], 1, &["pixel", "inv_sqrt"]),
            rec(Op::Sub, &[3, 1], 2, &["pixel", "inv_sqrt"]),
        ];
        let mut b = a.clone();
        b[0] = outer(5);
        b[2] = rec(Op::Sub, &[3, 1], 6, &["pixel", "inv_sqrt"]);
        let (first, origin) = diff_traces(&a, &b);
        assert_eq!(first.map(|f| f.index), Some(0));
        let origin = origin.expect("an origin");
        assert_eq!((origin.op, origin.index), (Op::Sub, 2));
    }
}
