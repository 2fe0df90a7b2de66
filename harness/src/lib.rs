//! The differential verification harness: runs the same inputs through the
//! Rust reference, the Jack program on the Hack VM emulator and the GPU
//! kernels, compares them under the right policy and says where they
//! diverge. See ARCHITECTURE.md for the map.
//!
//! Library entry points: [`cast::Cast`] (the registry of implementations,
//! with the project file), [`implementation::Implementation`] (the trait),
//! [`runner::diff_set`] (run and compare a set), [`compare`] (policies and
//! the result types).

pub mod cast;
pub mod compare;
pub mod contain;
pub mod dither;
pub mod exhaustive;
pub mod explain;
pub mod implementation;
pub mod impls;
pub mod localize;
pub mod merge;
pub mod pipe;
pub mod progress;
pub mod runner;
pub mod selftest;
pub mod sweep;
pub mod testkit;
pub mod text;
pub mod verdict;
