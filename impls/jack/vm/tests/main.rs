//! The emulator's integration tests, one module per file, in a single test
//! binary: one link of the crate's dependencies instead of one per file,
//! and every file's tests run side by side. `code_map.rs` and
//! `script_cwd.rs` stay binaries of their own: one sets an environment
//! variable that every compile in its process reads, the other the
//! working directory.

#[path = "support/corpus.rs"]
mod corpus_programs;
#[macro_use]
#[path = "support/fib.rs"]
mod fib;
#[path = "support/jack_main.rs"]
mod jack_main;
#[path = "support/raymarcher.rs"]
mod raymarcher_support;

mod corpus;
mod desktop;
mod projects;
mod proptests;
mod raymarcher;
mod scripts;
mod semantics;
mod tier;
mod timing;
mod trace_diff;
mod workload;
