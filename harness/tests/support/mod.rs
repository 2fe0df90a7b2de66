//! Helpers shared by the integration tests.

use harness::cast::Cast;
use harness::implementation::Implementation;
use harness::runner::{diff_set, LevelReport, RunOptions};
use vectors::Level;

/// Assert that `subject` agrees with ref-f316 on the committed small set of
/// every level it answers (ops, sdf, pixels): every vector answered by
/// both (a failure of either keeps only the answers before it) and none
/// diverging.
pub fn assert_agrees_with_ref_f316_on_the_small_sets(subject: &dyn Implementation) {
    let reference = Cast::builtin().open("ref-f316").unwrap();
    for level in [Level::Ops, Level::Sdf, Level::Pixels] {
        let set = vectors::load_named(vectors::named::small_set_name(level)).unwrap();
        let report = diff_set(&[reference.as_ref(), subject], &set, RunOptions::default());
        let failures: Vec<String> = report
            .failures()
            .map(|(label, e)| format!("{label}: {e}"))
            .collect();
        assert!(failures.is_empty(), "{}: {failures:?}", set.name);
        assert!(
            !report.diverged(),
            "{}",
            harness::text::level_report(&report)
        );
        assert_eq!(report.comparisons.len(), 1);
    }
}

/// `a` against `b` on the committed small ops set, asserted to diverge.
pub fn assert_diverges_on_the_small_ops_set(
    a: &dyn Implementation,
    b: &dyn Implementation,
) -> LevelReport {
    let set = vectors::load_named(vectors::named::small_set_name(Level::Ops)).unwrap();
    let report = diff_set(&[a, b], &set, RunOptions::default());
    assert!(
        report.diverged(),
        "{}",
        harness::text::level_report(&report)
    );
    report
}
