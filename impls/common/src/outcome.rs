//! The result of one computation in any implementation. A trap is a result
//! to compare, not a crash: `Sys.error` codes, hangs and out-of-domain
//! inputs are values of this enum.

use serde::{Deserialize, Serialize};
use std::fmt;

/// What a computation produced.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(tag = "kind", content = "value", rename_all = "snake_case")]
pub enum Outcome<T> {
    /// A normal result.
    Value(T),
    /// The Jack program would call `Sys.error(code)`.
    SysError(i16),
    /// A loop that never ends in Jack (or an instruction / iteration budget
    /// that ran out).
    Hang,
    /// The input lies outside the operation's domain (for example floor of
    /// a value of 2^14 or more, where Jack indexes outside its table).
    OutOfDomain,
}

/// The kind of an outcome, without its payload: the first thing compared.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OutcomeKind {
    Value,
    SysError,
    Hang,
    OutOfDomain,
}

impl<T> Outcome<T> {
    /// The kind of this outcome.
    pub fn kind(&self) -> OutcomeKind {
        match self {
            Outcome::Value(_) => OutcomeKind::Value,
            Outcome::SysError(_) => OutcomeKind::SysError,
            Outcome::Hang => OutcomeKind::Hang,
            Outcome::OutOfDomain => OutcomeKind::OutOfDomain,
        }
    }

    /// Apply `f` to a value, keeping traps as they are.
    pub fn map<U>(self, f: impl FnOnce(T) -> U) -> Outcome<U> {
        match self {
            Outcome::Value(v) => Outcome::Value(f(v)),
            Outcome::SysError(c) => Outcome::SysError(c),
            Outcome::Hang => Outcome::Hang,
            Outcome::OutOfDomain => Outcome::OutOfDomain,
        }
    }

    /// Whether `self` and `other` are the same answer: two values that
    /// `values` calls the same, or the same trap (a `Sys.error` with the
    /// same code).
    pub fn same_as<U>(&self, other: &Outcome<U>, values: impl FnOnce(&T, &U) -> bool) -> bool {
        match (self, other) {
            (Outcome::Value(x), Outcome::Value(y)) => values(x, y),
            (Outcome::SysError(x), Outcome::SysError(y)) => x == y,
            (Outcome::Hang, Outcome::Hang) | (Outcome::OutOfDomain, Outcome::OutOfDomain) => true,
            _ => false,
        }
    }

    /// The value, if this is one.
    pub fn value(self) -> Option<T> {
        match self {
            Outcome::Value(v) => Some(v),
            _ => None,
        }
    }
}

impl<T: fmt::Display> fmt::Display for Outcome<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Outcome::Value(v) => write!(f, "{v}"),
            Outcome::SysError(c) => write!(f, "Sys.error({c})"),
            Outcome::Hang => write!(f, "hang"),
            Outcome::OutOfDomain => write!(f, "out of domain"),
        }
    }
}

impl fmt::Display for OutcomeKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            OutcomeKind::Value => "value",
            OutcomeKind::SysError => "Sys.error",
            OutcomeKind::Hang => "hang",
            OutcomeKind::OutOfDomain => "out of domain",
        })
    }
}
