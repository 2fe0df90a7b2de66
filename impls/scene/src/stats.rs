//! What a program uses, read from its statements: the Float316 operations
//! (by the names of `common::Op`) a back end must provide.

use crate::ir::{Binary, Formulation, Program, Stmt, Unary, VecOp};
use std::collections::BTreeSet;

/// The arithmetic operations the program's statements call, by the names
/// of `common::Op` (`add`, `invSqrt`, ...), plus `pow` for IEEE programs.
pub fn operations(p: &Program) -> BTreeSet<&'static str> {
    let mut out = BTreeSet::new();
    let f316 = p.formulation == Formulation::Float316;
    for s in p.statements() {
        match s {
            Stmt::Unary { op, .. } => out.extend(match op {
                Unary::Sqrt => &["sqrt"][..],
                Unary::Floor => &["floor"],
                Unary::Mod2 => &["mod2"],
                Unary::Double => &["double"],
                Unary::Quarter => &["quarter"],
                Unary::Neg | Unary::Abs => &[],
                Unary::Fract => &["floor", "sub"],
                Unary::Clamp01 => &["gt"],
            }),
            Stmt::Binary { op, .. } => out.extend(match op {
                Binary::Add => &["add"][..],
                Binary::Sub => &["sub"],
                Binary::Mul => &["mul"],
                Binary::Div => &["div"],
                Binary::Max | Binary::Min => &["gt"],
                Binary::Pow => &["pow"],
            }),
            Stmt::Vector { op, .. } => out.extend(match op {
                VecOp::Add => &["add"][..],
                VecOp::Sub => &["sub"],
                VecOp::Scale => &["mul"],
                VecOp::Cross => &["mul", "sub"],
                VecOp::Normalize if f316 => &["mul", "add", "invSqrt"],
                VecOp::Normalize => &["mul", "add", "sqrt", "div"],
            }),
            Stmt::Dot { .. } => out.extend(["mul", "add"]),
            Stmt::Length { .. } => out.extend(["mul", "add", "sqrt"]),
            Stmt::Gt { .. } => {
                out.insert("gt");
            }
            _ => {}
        }
    }
    if f316 && out.contains("sqrt") {
        // sqrt's Newton steps divide, add and halve.
        out.extend(["div", "add", "halve"]);
    }
    if f316 && out.contains("invSqrt") {
        out.extend(["mul", "sub"]);
    }
    if f316 && out.contains("floor") {
        out.insert("add");
    }
    out
}
