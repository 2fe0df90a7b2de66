//! cargo-fuzz target `scene`: the property is `fuzz_checks::scene` (see
//! docs/fuzzing.md).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| fuzz_checks::scene(data));
