//! cargo-fuzz target `f316_vs_jack`: the property is `fuzz_checks::f316_vs_jack` (see
//! docs/fuzzing.md).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| fuzz_checks::f316_vs_jack(data));
