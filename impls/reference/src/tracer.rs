//! The op tracer: collects a [`TraceRecord`] for every Float316 operation in
//! pre-order (an operation is recorded when it is called, its result filled
//! in when it returns), with the call path of named frames.

use crate::engine::{outcome, R};
use common::{Op, OpValue, Outcome, TraceRecord, F316};

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
