//! The real workload: the Jack raymarcher (impls/jack/raymarcher), compiled
//! with jack-compiler, initialised once and then asked for pixels from
//! clones of the snapshot. Fused and plain execution must agree on it.

use hack_vm::{Config, Exit, Machine, Program};
use std::path::Path;
use std::sync::Arc;

/// The raymarcher compiled under the desktop profile.
fn raymarcher() -> Arc<Program> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../raymarcher");
    let classes = jack_compiler::compile_dir(&dir, jack_compiler::Profile::Desktop)
        .expect("the raymarcher compiles");
    let sources: Vec<(String, String)> = classes
        .into_iter()
        .map(|c| (format!("{}.vm", c.class_name), c.code))
        .collect();
    Program::from_sources(&sources).expect("the raymarcher loads")
}

#[test]
fn raymarcher_pixels_run_and_fusion_changes_nothing() {
    let mut m = Machine::new(raymarcher(), Config::default());
    assert_eq!(
        m.call("Main.init", &[], Some(10_000_000)).unwrap(),
        Exit::Returned(0)
    );
    let snapshot = m.clone();
    for (x, y) in [(256, 128), (10, 10)] {
        let mut a = snapshot.clone();
        let e = a.call("Image.pixel", &[x, y], Some(50_000_000)).unwrap();
        assert!(matches!(e, Exit::Returned(0 | -1)), "pixel ({x},{y}): {e}");
        // The same call, one plain command at a time for its first 20000 steps.
        let mut b = snapshot.clone();
        b.call("Image.pixel", &[x, y], Some(0)).unwrap();
        let mut c = snapshot.clone();
        c.call("Image.pixel", &[x, y], Some(0)).unwrap();
        for _ in 0..20_000 {
            b.run(Some(1));
        }
        c.run(Some(20_000));
        assert_eq!(b.steps(), c.steps());
        assert!(
            b.ram() == c.ram(),
            "fused and plain RAM differ at pixel ({x},{y})"
        );
    }
}
