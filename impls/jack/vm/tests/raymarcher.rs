//! The real workload: the Jack raymarcher (impls/jack/raymarcher), compiled
//! with jack-compiler, initialised once and then asked for pixels from
//! clones of the snapshot. Fused and plain execution must agree on it.

use crate::raymarcher_support as support;
use hack_vm::{Engine, Exit};
use support::raymarcher;

/// The committed render of the seed scene (255 white, 0 black).
fn seed_image() -> image::GrayImage {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../../vectors/images/seed-float316-512x256.png"
    );
    image::open(path).unwrap().to_luma8()
}

#[test]
fn raymarcher_pixels_run_and_fusion_changes_nothing() {
    let snapshot = support::initialised(&raymarcher(), Engine::default());
    for (x, y) in [(256, 128), (10, 10)] {
        let mut a = snapshot.clone();
        let e = a.call("Image.pixel", &[x, y], Some(50_000_000)).unwrap();
        // true (-1) exactly where the committed render is white.
        let white = seed_image().get_pixel(x as u32, y as u32).0[0] == 255;
        assert_eq!(e, Exit::Returned(-i16::from(white)), "pixel ({x},{y})");
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
