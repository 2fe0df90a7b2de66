//! The project's ports, verified by the harness from `cargo test`.

use harness::testkit::Project;
use vectors::Level;

fn project() -> Project {
    Project::load(concat!(env!("CARGO_MANIFEST_DIR"), "/harness.toml")).unwrap()
}

#[test]
fn the_python_port_agrees_with_the_reference() {
    project()
        .diff_level("ref-f316", "py-port", Level::Ops)
        .unwrap()
        .assert_agrees();
}

#[test]
fn the_rounding_bug_is_found_and_localized_to_mul() {
    let verdict = project()
        .diff_level("ref-f316", "py-port-rounding", Level::Ops)
        .unwrap();
    assert!(!verdict.agrees());
    let localized = verdict.localized.as_ref().expect("localized");
    let blamed = localized.blamed_op().map(|op| op.to_string());
    assert_eq!(blamed.as_deref(), Some("mul"), "{}", verdict.text());
    insta::assert_snapshot!(verdict.text());
}
