//! The most important property of the reference: its Float316 render of the
//! seed scene is the original Jack render, pixel for pixel.

use reference::{RefImpl, Reference, RenderedImage};
use std::path::PathBuf;

fn target() -> Vec<u8> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../vectors/images/seed-float316-512x256.png");
    let img = image::open(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let g = img.to_luma8();
    assert_eq!((g.width(), g.height()), (512, 256));
    g.into_raw()
}

fn differing(img: &RenderedImage, target: &[u8]) -> Vec<(usize, usize)> {
    img.gray8()
        .iter()
        .zip(target)
        .enumerate()
        .filter(|(_, (a, b))| a != b)
        .map(|(i, _)| (i % 512, i / 512))
        .collect()
}

#[test]
fn ref_f316_reproduces_the_jack_render_exactly() {
    let target = target();
    let img = Reference::seed(RefImpl::F316).render();
    let diff = differing(&img, &target);
    assert!(
        diff.is_empty(),
        "{} pixels differ; first ones: {:?}",
        diff.len(),
        &diff[..diff.len().min(20)]
    );
}
