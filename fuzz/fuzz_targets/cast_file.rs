//! cargo-fuzz target `cast_file`: the property is `fuzz_checks::cast_file`
//! (see docs/fuzzing.md).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| fuzz_checks::cast_file(data));
