//! Every injected fault of the catalogue is detected and localized to the
//! right operation, and the clean pairs show no divergence.

/// The whole catalogue, exactly, in order: each fault detected, passed, and
/// localized to exactly its own operation (not to one of several). One run
/// of the catalogue serves every check: the level-2 faults run on the
/// TestFloat sets, with the Jack program as their control.
#[test]
fn every_fault_is_detected_and_localized_to_its_own_operation() {
    use common::Op;
    let expected = [
        ("sqrt-floor-div", Some(Op::Sqrt)),
        ("jack-web-divide", Some(Op::Sqrt)),
        ("add-align-off-by-one", Some(Op::Add)),
        ("mul-keep-low", Some(Op::Mul)),
        ("dither-threshold", Some(Op::Gt)),
        ("add-carry-bit", Some(Op::Add)),
        ("add-drop-far", Some(Op::Add)),
        ("div-normalise-once", Some(Op::Div)),
        ("f32-oracle", None),
    ];
    let results = harness::selftest::run_all(&harness::cast::Cast::builtin());
    let names: Vec<&str> = results.iter().map(|r| r.fault.as_str()).collect();
    let expected_names: Vec<&str> = expected.iter().map(|(name, _)| *name).collect();
    assert_eq!(names, expected_names);
    for (r, (_, op)) in results.iter().zip(expected) {
        assert!(r.passed, "{r}");
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
