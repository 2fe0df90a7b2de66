//! The kinds of implementation, one module each: a [`Kind`] that gives its
//! built-in entries of the cast and reads its `[impl.NAME]` tables, and the
//! adapter that makes it an [`Implementation`](crate::implementation::Implementation).
//!
//! To add a kind: write its module here and add it to [`KINDS`] (see
//! [`crate::cast`] for the contract). Nothing else changes.

pub mod jack;
pub mod pipe;
pub mod reference;
pub mod shader;

use crate::cast::Kind;

/// Every kind, by its `kind = "..."` name; their built-in entries come in
/// this order.
pub const KINDS: &[&dyn Kind] = &[
    &reference::ReferenceKind,
    &jack::JackKind,
    &shader::ShaderKind,
    &pipe::PipeKind,
];

/// The operation cases of an ops-level batch, as the GPU kernels take them
/// (a unary operation's second operand is zero).
pub(crate) fn op_cases(batch: &[vectors::Vector]) -> Vec<(common::Op, common::F316, common::F316)> {
    batch
        .iter()
        .filter_map(|v| match v {
            vectors::Vector::Op(o) => Some((o.op, o.a, o.b.unwrap_or(common::F316::ZERO))),
            _ => None,
        })
        .collect()
}

/// The points of an sdf-level batch.
pub(crate) fn sdf_points(batch: &[vectors::Vector]) -> Vec<[common::F316; 3]> {
    batch
        .iter()
        .filter_map(|v| match v {
            vectors::Vector::Sdf(s) => Some(s.p),
            _ => None,
        })
        .collect()
}

/// The pixels `(x, y)` of a pixel-level batch.
pub(crate) fn pixel_coords(batch: &[vectors::Vector]) -> Vec<(u16, u16)> {
    batch
        .iter()
        .filter_map(|v| match v {
            vectors::Vector::Pixel(p) => Some((p.x, p.y)),
            _ => None,
        })
        .collect()
}
