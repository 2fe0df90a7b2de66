//! Bring your own Jack program: bindings say how to reach a program's
//! numbers and functions, so that the harness can query it without entry
//! points written for it (syntax and walkthrough: `docs/bindings.md`).
//!
//! - [`Bindings`] (module `spec`): what the user writes; deserializable.
//! - [`JackProgram`]: the program's folder compiled or loaded, with what
//!   its sources tell of each subroutine ([`Signatures`]).
//! - [`BoundProgram::open`]: every binding checked against the program
//!   (a [`BindError`] names the field), the ready point reached, objects
//!   round-tripped through their layouts, one snapshot taken.
//! - Queries from clones of it: [`BoundProgram::op`], `sdf`, `pixel`,
//!   `render`, their op traces (`trace_op`, `trace_sdf`, `trace_pixel`),
//!   and whole-program mode ([`BoundProgram::run_whole`]).
//!
//! Only what is bound is used: a query whose binding is absent is
//! [`crate::JackError::Unsupported`], never guessed.

mod bound;
mod error;
mod layout;
mod program;
mod ready;
mod record;
mod signatures;
mod spec;
mod statement;
mod vm;
pub use vm::outcome_of;
mod whole;

pub use bound::{normalized_coords, BoundPixel, BoundProgram};
pub use error::BindError;
pub use program::JackProgram;
pub use ready::DEFAULT_READY_BUDGET;
pub use signatures::Signatures;
pub use spec::{Bindings, BudgetFields, Capture, Layout, PixelShade, Ready, Statements};
pub use whole::WholeRun;
