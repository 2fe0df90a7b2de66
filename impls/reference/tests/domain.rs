//! A scene that drives Float316's `floor` and `mod2` outside their modelled
//! domain (`vectors/scenes/tests/domain.json`: a checker plane scaled by
//! 0.001, so that its texture coordinates are 1000 times the point's):
//! ref-f316 answers "out of domain" there, at the SDF and at the pixel
//! level, naming the operation in its trace, and a value elsewhere; ref-f64
//! answers values everywhere.

use common::{Op, Outcome, F316};
use reference::{Described, RefImpl, Settings};

fn scene() -> scene::Checked {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../vectors/scenes/tests/domain.json"
    );
    scene::load(std::path::Path::new(path)).unwrap_or_else(|e| panic!("{e}"))
}

fn p(x: f64, y: f64, z: f64) -> [F316; 3] {
    [x, y, z].map(|c| F316::from_f64_truncating(c).unwrap())
}

/// The operation that failed: the trace's last record, out of domain.
fn failing_op(d: &Described, q: [F316; 3]) -> Op {
    let trace = d.trace_sdf(q).unwrap();
    assert_eq!(trace.outcome, Outcome::OutOfDomain, "{q:?}");
    let last = trace.records.last().expect("operations ran");
    assert_eq!(last.result, Outcome::OutOfDomain, "{last:?}");
    last.op
}

#[test]
fn floor_and_mod2_outside_their_domain_are_out_of_domain_in_the_sdf() {
    let c = scene();
    let f316 = Described::new(RefImpl::F316, &c, Settings::default()).unwrap();
    let f64 = Described::new(RefImpl::F64, &c, Settings::default()).unwrap();
    // floor(16500) and floor(20000): |x| >= 2^14.
    assert_eq!(failing_op(&f316, p(16.5, 0.0, 0.0)), Op::Floor);
    assert_eq!(failing_op(&f316, p(-20.0, 0.0, 0.0)), Op::Floor);
    // floor(10000) + floor(10000) = 20000: mod2 out of its domain.
    assert_eq!(failing_op(&f316, p(10.0, -1.0, 10.0)), Op::Mod2);
    // 16 * 1000 and 0.3 * 1000 are in the domain.
    for q in [p(0.0, 0.0, 0.0), p(16.0, 0.0, 0.3), p(-3.0, 2.0, 5.0)] {
        assert!(matches!(f316.sdf(q), Outcome::Value(_)), "{q:?}");
    }
    for q in [p(16.5, 0.0, 0.0), p(10.0, -1.0, 10.0)] {
        assert!(matches!(f64.sdf(q), Outcome::Value(_)), "{q:?}");
    }
}

#[test]
fn far_pixels_are_out_of_domain_near_ones_are_values() {
    let c = scene();
    let image = Described::new(RefImpl::F316, &c, Settings::default())
        .unwrap()
        .render();
    let count = |f: fn(&Outcome<reference::ScenePixel>) -> bool| {
        image.pixels.iter().filter(|p| f(p)).count()
    };
    let ood = count(|p| matches!(p, Outcome::OutOfDomain));
    let values = count(|p| matches!(p, Outcome::Value(_)));
    assert_eq!(ood + values, image.pixels.len(), "no other trap");
    assert!(
        ood > 300 && values > 1000,
        "{ood} out of domain, {values} values"
    );
    // The sky and the far floor (the top rows) are out of domain; the
    // floor in front of the camera (the bottom row) is not.
    let w = image.width;
    assert!(matches!(image.pixels[w * 4 + w / 2], Outcome::OutOfDomain));
    let last = &image.pixels[image.pixels.len() - w..];
    assert!(last.iter().all(|p| matches!(p, Outcome::Value(_))));
    let f64_image = Described::new(RefImpl::F64, &c, Settings::default())
        .unwrap()
        .render();
    assert!(f64_image
        .pixels
        .iter()
        .all(|p| matches!(p, Outcome::Value(_))));
}
