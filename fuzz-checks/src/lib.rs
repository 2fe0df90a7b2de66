//! The properties every fuzz target checks, one function per target, each
//! taking the fuzzer's bytes and panicking when a property fails. The
//! cargo-fuzz targets in `fuzz/fuzz_targets` call them with libFuzzer's
//! inputs; `tests/bounded.rs` calls them under `cargo test` with the
//! checked-in corpus, the committed regression inputs and a bounded number
//! of proptest mutations of the corpus. See docs/fuzzing.md.

mod cast_file;
mod differential;
mod jack_source;
mod pipe_reader;
mod sets;
mod tst_script;

pub use cast_file::{cast_file, project_file};
pub use differential::f316_vs_jack;
pub use jack_source::{jack_source, vm_source};
pub use pipe_reader::pipe_reader;
pub use sets::{scene, vector_set};
pub use tst_script::tst_script;

/// A target's property: panics when the input breaks it.
pub type Check = fn(&[u8]);

/// The targets by name, as `fuzz/fuzz_targets/NAME.rs` and the corpus
/// folders `fuzz/corpus/NAME` call them.
pub const TARGETS: [(&str, Check); 8] = [
    ("jack_source", jack_source),
    ("vm_source", vm_source),
    ("vector_set", vector_set),
    ("scene", scene),
    ("cast_file", cast_file),
    ("f316_vs_jack", f316_vs_jack),
    ("pipe_reader", pipe_reader),
    ("tst_script", tst_script),
];
