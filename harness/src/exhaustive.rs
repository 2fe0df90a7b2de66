//! Exhaustive checks of the unary Float316 operations (sqrt, invsqrt,
//! floor, mod2, halve, double, quarter) over every normalised input of both
//! signs plus the zeros (about 4.2 million per operation), across Float316
//! implementations. `step` takes every n-th input, for the small slice
//! `cargo test` runs; the nightly job runs step 1.

use crate::implementation::Implementation;
use crate::runner::{diff_set, LevelReport, RunOptions};
use common::Op;
use vectors::gen::ops::all_normalised;
use vectors::{Level, OpVector, Vector, VectorSet};

/// The set of every `step`-th normalised input for one unary operation.
pub fn unary_set(op: Op, step: usize) -> VectorSet {
    let vectors = all_normalised(step)
        .map(|a| {
            Vector::Op(OpVector {
                category: "exhaustive".into(),
                op,
                a,
                b: None,
            })
        })
        .collect();
    VectorSet::new(
        &format!("exhaustive-{op}-step-{step}"),
        Level::Ops,
        "every normalised input of both signs plus the zeros",
        None,
        vectors,
    )
}

/// Run every unary operation's exhaustive set through `impls` (the first
/// compared with each other), one report per operation.
pub fn unary(impls: &[&dyn Implementation], step: usize, options: RunOptions) -> Vec<LevelReport> {
    Op::UNARY
        .into_iter()
        .map(|op| diff_set(impls, &unary_set(op, step), options))
        .collect()
}
