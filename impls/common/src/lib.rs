//! Types shared by every implementation and by the harness: the Float316
//! triple, the outcome of a computation, Jack's 16-bit integer semantics,
//! the names of the Float316 operations, the image constants and the
//! deterministic generator of fixed point sets.
//!
//! Dependency direction: `harness -> impls/* -> common`. Nothing here knows
//! about any particular implementation.

pub mod adapter;
pub mod f316;
pub mod hash;
pub mod image_consts;
pub mod input;
pub mod jack_int;
pub mod op;
pub mod outcome;
pub mod shown;
pub mod splitmix;
pub mod trace;

pub use adapter::AdapterDescription;
pub use f316::F316;
pub use op::Op;
pub use outcome::{Outcome, OutcomeKind};
pub use shown::{shown, shown_f32, Shown};
pub use splitmix::SplitMix64;
pub use trace::{OpValue, TraceRecord};
