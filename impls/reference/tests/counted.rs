//! Counting a described scene's Float316 operations: the counted render is
//! the plain render, and its counts are the sum of its pixels' counts.

use common::Op;
use reference::{Described, RefImpl, Settings};
use std::path::Path;

/// The small test scene of `harness tune` (64x32) in `implementation`.
fn small(implementation: RefImpl) -> Described {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../vectors/scenes/tests/tune-small.json");
    let checked = scene::load(&path).unwrap();
    Described::new(implementation, &checked, Settings::default()).unwrap()
}

#[test]
fn the_counted_render_is_the_render_and_sums_its_pixels() {
    let d = small(RefImpl::F316);
    let (image, counts) = d.render_counted().unwrap();
    assert_eq!(image, d.render());
    // The set-up's operations once, then every pixel's.
    let mut sum = d.setup_counted().unwrap();
    assert!(sum.of(Op::InvSqrt) > 0, "the camera normalizes");
    for y in 0..image.height as u32 {
        for x in 0..image.width as u32 {
            let (pixel, c) = d.pixel_counted(x, y).unwrap();
            assert_eq!(pixel, image.pixels[y as usize * image.width + x as usize]);
            sum.add(&c);
        }
    }
    assert_eq!(sum, counts);
    // `sqrt` calls `div`, so some divisions are made inside another
    // operation and are not the program's own.
    assert!(counts.of(Op::InvSqrt) > 0 && counts.of(Op::Div) > 0);
    for op in Op::ALL {
        assert!(counts.outer[op as usize] <= counts.of(op), "{op}");
    }
    assert!(counts.outer_total() < counts.all.iter().sum::<u64>());
}

#[test]
fn only_ref_f316_counts() {
    let f64 = small(RefImpl::F64);
    assert!(f64.render_counted().is_err());
    assert!(f64.pixel_counted(0, 0).is_err());
    assert!(f64.setup_counted().is_err());
}
