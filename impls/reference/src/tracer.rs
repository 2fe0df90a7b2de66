//! The op tracer: collects a [`TraceRecord`] for every Float316 operation in
//! pre-order (an operation is recorded when it is called, its result filled
//! in when it returns), with the call path of named frames.
//!
//! The Float316 engine is generic over a [`Recorder`]: [`Untraced`] records
//! nothing and compiles away entirely (the operations inline into the scene
//! code), `&mut Tracer` records everything.

use crate::engine::{outcome, R};
use common::{Op, OpValue, Outcome, TraceRecord, F316};

/// Where the Float316 engine reports operations and frames.
pub trait Recorder {
    /// Whether anything is recorded (`false`: every call is a no-op).
    const ON: bool;
    /// Record a call of `op` on `args`; returns the record's index.
    fn open(&mut self, op: Op, args: &[F316]) -> usize;
    /// Fill in the result of the record `index`.
    fn close(&mut self, index: usize, result: R<OpValue>);
    /// The call of `op` just opened runs as the variant `variant` of a
    /// tuned call site.
    #[inline(always)]
    fn variant(&mut self, _op: Op, _variant: scene::ir::Tuning) {}
    /// Enter a named frame.
    fn push(&mut self, frame: String);
    /// Leave the innermost frame.
    fn pop(&mut self);
}

/// The recorder of untraced runs: records nothing, costs nothing.
#[derive(Clone, Copy, Debug, Default)]
pub struct Untraced;

impl Recorder for Untraced {
    const ON: bool = false;
    #[inline(always)]
    fn open(&mut self, _: Op, _: &[F316]) -> usize {
        0
    }
    #[inline(always)]
    fn close(&mut self, _: usize, _: R<OpValue>) {}
    #[inline(always)]
    fn push(&mut self, _: String) {}
    #[inline(always)]
    fn pop(&mut self) {}
}

impl Recorder for &mut Tracer {
    const ON: bool = true;
    fn open(&mut self, op: Op, args: &[F316]) -> usize {
        Tracer::open(self, op, args)
    }
    fn close(&mut self, index: usize, result: R<OpValue>) {
        Tracer::close(self, index, result)
    }
    fn push(&mut self, frame: String) {
        Tracer::push(self, frame)
    }
    fn pop(&mut self) {
        Tracer::pop(self)
    }
}

/// Records operations and the current call path.
#[derive(Debug, Default)]
pub struct Tracer {
    records: Vec<TraceRecord>,
    path: Vec<String>,
}

impl Tracer {
    /// An empty tracer whose paths start with `root` frames.
    pub fn new(root: impl IntoIterator<Item = String>) -> Self {
        Tracer {
            records: Vec::new(),
            path: root.into_iter().collect(),
        }
    }

    /// Enter a named frame.
    pub fn push(&mut self, frame: String) {
        self.path.push(frame);
    }

    /// Leave the innermost frame.
    pub fn pop(&mut self) {
        self.path.pop();
    }

    /// Record a call of `op`; its own frame is entered so that nested
    /// operations carry it in their path. Returns the record's index.
    pub fn open(&mut self, op: Op, args: &[F316]) -> usize {
        self.records.push(TraceRecord {
            op,
            args: args.to_vec(),
            // Replaced by `close`; a record left open would read as a hang.
            result: Outcome::Hang,
            path: self.path.clone(),
        });
        self.path.push(op.name().to_string());
        self.records.len() - 1
    }

    /// Fill in the result of the record `index` and leave its frame.
    pub fn close(&mut self, index: usize, result: R<OpValue>) {
        self.records[index].result = outcome(result);
        self.path.pop();
    }

    /// The records so far.
    pub fn into_records(self) -> Vec<TraceRecord> {
        self.records
    }
}
