//! How many Float316 operations a run makes, for an estimate of what it
//! costs on another machine: every call of each operation, and the calls
//! the program makes itself rather than an operation does (`sub` calls
//! `add`; `sqrt` calls `div`, `add` and `halve`), and the calls run as a
//! tuned call site's variant (`sqrtNewton1`, `mulTruncated`).

use crate::engine::R;
use crate::tracer::Recorder;
use common::{Op, OpValue, F316};
use scene::ir::Tuning;
use serde::{Deserialize, Serialize};

/// Operation counts, each array indexed as [`Op::ALL`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct OpCounts {
    /// Every call of each operation, those made inside another included.
    pub all: [u64; Op::ALL.len()],
    /// The calls made outside any operation: by the program itself.
    pub outer: [u64; Op::ALL.len()],
    /// The calls of each operation run as each variant (indexed as
    /// [`Tuning::ALL`], then [`Op::ALL`]); counted in `all` too.
    pub variant: [[u64; Op::ALL.len()]; Tuning::ALL.len()],
}

impl OpCounts {
    /// Every call of `op`.
    pub fn of(&self, op: Op) -> u64 {
        self.all[op as usize]
    }

    /// The calls of `op` run as `variant`.
    pub fn of_variant(&self, op: Op, variant: Tuning) -> u64 {
        self.variant[variant as usize][op as usize]
    }

    /// The calls of `op` run as the spec computes it.
    pub fn of_spec(&self, op: Op) -> u64 {
        self.of(op)
            - Tuning::ALL
                .iter()
                .map(|&t| self.of_variant(op, t))
                .sum::<u64>()
    }

    /// The calls the program makes itself, all operations together.
    pub fn outer_total(&self) -> u64 {
        self.outer.iter().sum()
    }

    /// Add `other`'s counts to these.
    pub fn add(&mut self, other: &OpCounts) {
        for (a, b) in self.all.iter_mut().zip(other.all) {
            *a += b;
        }
        for (a, b) in self.outer.iter_mut().zip(other.outer) {
            *a += b;
        }
        for (mine, theirs) in self.variant.iter_mut().zip(other.variant) {
            for (a, b) in mine.iter_mut().zip(theirs) {
                *a += b;
            }
        }
    }
}

/// The recorder that counts: operations into [`OpCounts`], frames not at
/// all.
#[derive(Debug, Default)]
pub(crate) struct Counter {
    pub(crate) counts: OpCounts,
    /// Operations open now.
    depth: usize,
}

impl Recorder for Counter {
    const ON: bool = true;

    #[inline(always)]
    fn open(&mut self, op: Op, _: &[F316]) -> usize {
        let i = op as usize;
        self.counts.all[i] += 1;
        if self.depth == 0 {
            self.counts.outer[i] += 1;
        }
        self.depth += 1;
        0
    }

    #[inline(always)]
    fn close(&mut self, _: usize, _: R<OpValue>) {
        self.depth -= 1;
    }

    #[inline(always)]
    fn variant(&mut self, op: Op, variant: Tuning) {
        self.counts.variant[variant as usize][op as usize] += 1;
    }

    #[inline(always)]
    fn push(&mut self, _: String) {}

    #[inline(always)]
    fn pop(&mut self) {}
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_operation_counts_at_its_place_in_op_all() {
        for (i, op) in Op::ALL.iter().enumerate() {
            assert_eq!(*op as usize, i, "{op}");
        }
    }

    #[test]
    fn nested_calls_count_in_all_but_not_in_outer() {
        let mut c = Counter::default();
        let sub = c.open(Op::Sub, &[]);
        let add = c.open(Op::Add, &[]);
        c.close(add, Ok(OpValue::Bool(true)));
        c.close(sub, Ok(OpValue::Bool(true)));
        c.open(Op::Add, &[]);
        assert_eq!(c.counts.of(Op::Add), 2);
        assert_eq!(c.counts.of(Op::Sub), 1);
        assert_eq!(c.counts.outer_total(), 2);
        assert_eq!(c.counts.outer[Op::Add as usize], 1);
        c.open(Op::Sqrt, &[]);
        c.variant(Op::Sqrt, Tuning::Newton1);
        assert_eq!(c.counts.of(Op::Sqrt), 1);
        assert_eq!(c.counts.of_variant(Op::Sqrt, Tuning::Newton1), 1);
        assert_eq!(c.counts.of_spec(Op::Sqrt), 0);
        assert_eq!(c.counts.of_spec(Op::Add), 2);
        let mut sum = c.counts;
        sum.add(&c.counts);
        assert_eq!(sum.of(Op::Add), 4);
        assert_eq!(sum.of_variant(Op::Sqrt, Tuning::Newton1), 2);
    }
}
