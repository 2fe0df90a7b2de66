//! Op traces: the list of every Float316 operation a computation performed,
//! in a form every Float316 implementation can produce and the localizer
//! can diff.
//!
//! Convention (all implementations follow it so that traces line up):
//! records are in *pre-order*: an operation is recorded when it is called
//! and its result is filled in when it returns, and operations called by
//! other operations are recorded too, after their caller. The spec's
//! structure decides the nesting: `sub` calls `add`; `floor` calls `add`
//! for a negative non-integer; `sqrt` calls `div`, `add`, `halve` twice;
//! `invSqrt` calls `mul`, `mul`, `sub` (and so `add`), `mul` twice. Vector
//! helpers (dot, length, normalize, ...) are not operations; they appear in
//! the call path only.

use crate::{Op, Outcome, F316};
use serde::{Deserialize, Serialize};
use std::fmt;

/// The value an operation returns: a Float316 triple, or a boolean for `gt`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(untagged)]
pub enum OpValue {
    Num(F316),
    Bool(bool),
}

impl fmt::Display for OpValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            OpValue::Num(v) => write!(f, "{v}"),
            OpValue::Bool(b) => write!(f, "{b}"),
        }
    }
}

/// One traced operation.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct TraceRecord {
    /// Which operation.
    pub op: Op,
    /// Its operands, as they were when it was called.
    pub args: Vec<F316>,
    /// What it produced.
    pub result: Outcome<OpValue>,
    /// The call path, outermost first, e.g. `["pixel(312,87)", "march step
    /// 14", "scene", "torus", "sqrt"]`. Informative only: two
    /// implementations may name frames differently; records are compared on
    /// `op`, `args` and `result`.
    pub path: Vec<String>,
}

impl TraceRecord {
    /// Whether two records describe the same operation with the same
    /// operands and the same result (paths are not compared).
    pub fn same_computation(&self, other: &TraceRecord) -> bool {
        self.op == other.op && self.args == other.args && self.result == other.result
    }
}

impl fmt::Display for TraceRecord {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}(", self.op)?;
        for (i, a) in self.args.iter().enumerate() {
            if i > 0 {
                write!(f, ", ")?;
            }
            write!(f, "{a}")?;
        }
        write!(f, ") = {}  [{}]", self.result, self.path.join(" > "))
    }
}
