//! cargo-fuzz target `tst_script`: the property is `fuzz_checks::tst_script`
//! (see docs/fuzzing.md).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| fuzz_checks::tst_script(data));
