//! cargo-fuzz target `jack_source`: the property is `fuzz_checks::jack_source` (see
//! docs/fuzzing.md).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| fuzz_checks::jack_source(data));
