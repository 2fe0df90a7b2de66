//! The real workload: the Jack raymarcher (impls/jack/raymarcher), compiled
//! with jack-compiler, initialised once and then asked for pixels from
//! clones of the snapshot. Fused and plain execution must agree on it.

#[path = "support/raymarcher.rs"]
mod support;

use hack_vm::{Config, Exit, Machine};
use support::raymarcher;

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
