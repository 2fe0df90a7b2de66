//! cargo-fuzz target `vm_source`: the property is `fuzz_checks::vm_source` (see
//! docs/fuzzing.md).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| fuzz_checks::vm_source(data));
