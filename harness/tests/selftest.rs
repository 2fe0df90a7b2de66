//! Every injected fault of the catalogue is detected and localized to the
//! right operation, and the clean pairs show no divergence.

#[test]
fn every_fault_is_detected_and_localized() {
    let results = harness::selftest::run_all(&harness::cast::Cast::builtin());
    assert!(results.len() >= 5);
    for r in &results {
        assert!(r.passed, "{r}");
    }
}
