//! cargo-fuzz target `pipe_reader`: the property is
//! `fuzz_checks::pipe_reader` (see docs/fuzzing.md).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| fuzz_checks::pipe_reader(data));
