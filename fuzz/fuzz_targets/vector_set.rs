//! cargo-fuzz target `vector_set`: the property is `fuzz_checks::vector_set` (see
//! docs/fuzzing.md).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| fuzz_checks::vector_set(data));
