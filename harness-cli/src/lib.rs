//! The `harness` command line on top of the core (`harness`) and the
//! report (`harness-report`): the argument parser ([`cli`]), one module per
//! command ([`commands`]), the nightly job ([`nightly`]), the output
//! paths checked before a long run ([`output`]) and the process's CPU time
//! ([`cpu`]).

pub mod cli;
pub mod commands;
pub mod cpu;
pub mod nightly;
pub mod output;
