//! Every injected fault of the catalogue is detected and localized to the
//! right operation, and the clean pairs show no divergence.

#[test]
fn every_fault_is_detected_and_localized() {
    let results = harness::selftest::run_all(&harness::cast::Cast::builtin());
    let names: Vec<&str> = results.iter().map(|r| r.fault.as_str()).collect();
    assert_eq!(
        names,
        [
            "sqrt-floor-div",
            "jack-web-divide",
            "add-align-off-by-one",
            "mul-keep-low",
            "dither-threshold",
            "f32-oracle"
        ]
    );
    for r in &results {
        assert!(r.passed, "{r}");
    }
}

/// Each fault is localized to exactly its operation (not to one of several).
#[test]
fn each_fault_is_localized_to_its_own_operation() {
    use common::Op;
    let expected = [
        ("sqrt-floor-div", Some(Op::Sqrt)),
        ("jack-web-divide", Some(Op::Sqrt)),
        ("add-align-off-by-one", Some(Op::Add)),
        ("mul-keep-low", Some(Op::Mul)),
        ("dither-threshold", Some(Op::Gt)),
        ("f32-oracle", None),
    ];
    let results = harness::selftest::run_all(&harness::cast::Cast::builtin());
    for (name, op) in expected {
        let r = results.iter().find(|r| r.fault == name).unwrap();
        assert_eq!(r.localized_to, op, "{r}");
    }
}

/// The clean control can raise a false alarm: given a faulty pair as its
/// "clean" pair, the fault fails.
#[test]
fn a_faulty_control_fails_the_fault() {
    let mut fault = harness::selftest::catalogue().remove(0);
    assert_eq!(fault.name, "sqrt-floor-div");
    fault.clean = fault.faulty;
    let r = harness::selftest::run_fault(&harness::cast::Cast::builtin(), &fault);
    assert!(r.detected, "{r}");
    assert!(r.clean_diverged, "{r}");
    assert!(!r.passed, "{r}");
}
