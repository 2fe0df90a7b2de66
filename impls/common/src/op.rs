//! Names of the Float316 operations of the spec (section 2), shared by
//! vector files, traces and every implementation.

use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

/// One Float316 operation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Op {
    Gt,
    Add,
    Sub,
    Mul,
    Div,
    Floor,
    Mod2,
    Sqrt,
    InvSqrt,
    Halve,
    Double,
    Quarter,
}

impl Op {
    /// Every operation, in a fixed order.
    pub const ALL: [Op; 12] = [
        Op::Gt,
        Op::Add,
        Op::Sub,
        Op::Mul,
        Op::Div,
        Op::Floor,
        Op::Mod2,
        Op::Sqrt,
        Op::InvSqrt,
        Op::Halve,
        Op::Double,
        Op::Quarter,
    ];

    /// The unary operations (arity one), in the order of [`Op::ALL`].
    pub const UNARY: [Op; 7] = {
        let mut unary = [Op::Gt; 7];
        let (mut i, mut n) = (0, 0);
        while i < Op::ALL.len() {
            if Op::ALL[i].arity() == 1 {
                unary[n] = Op::ALL[i];
                n += 1;
            }
            i += 1;
        }
        assert!(n == unary.len(), "UNARY holds every unary op");
        unary
    };

    /// How many Float316 operands the operation takes.
    pub const fn arity(self) -> usize {
        match self {
            Op::Gt | Op::Add | Op::Sub | Op::Mul | Op::Div => 2,
            _ => 1,
        }
    }

    /// The name used on the command line and in files (`inv_sqrt`, ...).
    pub const fn name(self) -> &'static str {
        match self {
            Op::Gt => "gt",
            Op::Add => "add",
            Op::Sub => "sub",
            Op::Mul => "mul",
            Op::Div => "div",
            Op::Floor => "floor",
            Op::Mod2 => "mod2",
            Op::Sqrt => "sqrt",
            Op::InvSqrt => "inv_sqrt",
            Op::Halve => "halve",
            Op::Double => "double",
            Op::Quarter => "quarter",
        }
    }
}

impl fmt::Display for Op {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// An unknown operation name.
#[derive(Debug, thiserror::Error)]
#[error("unknown Float316 operation `{0}` (expected one of gt, add, sub, mul, div, floor, mod2, sqrt, inv_sqrt, halve, double, quarter)")]
pub struct UnknownOp(pub String);

impl FromStr for Op {
    type Err = UnknownOp;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let s_norm = s.to_ascii_lowercase().replace('-', "_");
        let s_norm = if s_norm == "invsqrt" {
            "inv_sqrt".to_string()
        } else {
            s_norm
        };
        Op::ALL
            .into_iter()
            .find(|op| op.name() == s_norm)
            .ok_or_else(|| UnknownOp(s.to_string()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for op in Op::ALL {
            assert_eq!(op.name().parse::<Op>().unwrap(), op);
        }
        assert_eq!("invSqrt".parse::<Op>().unwrap(), Op::InvSqrt);
        assert!("pow".parse::<Op>().is_err());
        assert_eq!(Op::UNARY.len() + 5, Op::ALL.len());
    }
}
