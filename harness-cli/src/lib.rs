//! The `harness` command line on top of the core (`harness`) and the
//! report (`harness-report`): the argument parser ([`cli`]), one module per
//! command ([`commands`]), the nightly job ([`nightly`]) and the output
//! paths checked before a long run ([`output`]).

pub mod cli;
pub mod commands;
pub mod nightly;
pub mod output;
