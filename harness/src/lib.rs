//! The differential verification harness: runs the same inputs through the
//! Rust reference, the Jack program on the Hack VM emulator and the GPU
//! kernels, compares them under the right policy and says where they
//! diverge. See ARCHITECTURE.md for the map.

pub mod cli;
pub mod commands;
