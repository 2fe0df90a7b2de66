//! The kinds of implementation, one module each: a [`Kind`] that gives its
//! built-in entries of the cast and reads its `[impl.NAME]` tables, and the
//! adapter that makes it an [`Implementation`](crate::implementation::Implementation).
//!
//! To add a kind: write its module here and add it to [`KINDS`] (see
//! [`crate::cast`] for the contract). Nothing else changes.

#[cfg(feature = "jack")]
pub mod jack;
pub mod pipe;
pub mod reference;
#[cfg(feature = "shader")]
pub mod shader;

use crate::cast::entry::Kind;

/// Every kind, by its `kind = "..."` name; their built-in entries come in
/// this order.
pub const KINDS: &[&dyn Kind] = &[
    &reference::ReferenceKind,
    #[cfg(feature = "jack")]
    &jack::JackKind,
    #[cfg(feature = "shader")]
    &shader::ShaderKind,
    &pipe::PipeKind,
];
