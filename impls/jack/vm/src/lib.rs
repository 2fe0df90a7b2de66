//! A fast emulator of the nand2tetris Hack VM with the native Jack OS
//! (`jack-os`): the VM language of the nand2tetris course (stack
//! arithmetic, the eight memory segments over the Hack RAM map, labels,
//! function calls and returns) as the official VM emulator runs it.
//!
//! - [`Program`]: load a directory of `.vm` files ([`Program::load_dir`]) or
//!   in-memory sources ([`Program::from_sources`]) once, with every
//!   load-time check of the spec; share it as `Arc<Program>`.
//! - [`Machine`]: RAM, registers, OS state and the Jack call stack. `Clone`
//!   is a snapshot; [`Machine::run`] runs from the entry,
//!   [`Machine::call`] calls any function by name; both take an instruction
//!   budget and end with an [`Exit`] (with the Jack call stack where it
//!   matters). [`Machine::run_watched`] reports calls of chosen functions to
//!   a [`Watcher`]; [`compare_call_traces`] runs two machines side by side
//!   and names the first call or return where they differ.
//!
//! Speed: the program is decoded once into compact instructions with
//! resolved jumps and calls, and common command sequences are fused
//! (module `fuse`); the dispatch loop (module `exec`) keeps the VM
//! registers in host registers and allocates nothing.

mod error;
mod exec;
mod exit;
mod fuse;
mod load;
mod machine;
mod native;
mod parse;
mod program;
mod script;
mod tier;
mod timing;
mod trace_diff;

pub use error::LoadError;
pub use exit::{CallStack, Exit};
pub use jack_os::{Builtin, Completion, DivideRule, KeyScript, Profile, Ram, Stop, RAM_SIZE};
pub use load::{in_load_order, IMPLICIT};
pub use machine::{Config, Machine, Register, UnknownFunction, Watcher, MAX_DEPTH};
pub use native::{Engine, AUTO_THRESHOLD};
pub use program::{FnId, Function, Program};
pub use script::{run_script, Mismatch, ScriptError, ScriptReport};
pub use timing::Timing;
pub use trace_diff::{compare_call_traces, CallEvent, TraceComparison, TraceDivergence};
