//! The look-at camera's handedness: a left-handed scene renders as the
//! right-handed one mirrored, and `toon`, written left-handed as its source
//! (I<3IQ's figure 6.2), draws the diffuse torus on the left and the toon
//! torus on the right.

use common::Outcome;
use reference::{Described, RefImpl, SceneImage, Settings};
use serde_json::{json, Value};
use std::collections::BTreeSet;

fn toon_json() -> Value {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../vectors/scenes/toon.json"
    );
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn render(v: &Value, imp: RefImpl) -> SceneImage {
    let checked = scene::parse(&v.to_string()).unwrap_or_else(|e| panic!("{e}"));
    Described::new(imp, &checked, Settings::default())
        .unwrap()
        .render()
}

/// The shade of pixel (x, y) as bits (traps as `None`).
fn shade(image: &SceneImage, x: usize, y: usize) -> Option<u64> {
    match image.pixels[y * image.width + x] {
        Outcome::Value(p) => Some(p.value.value.to_bits()),
        _ => None,
    }
}

/// u = (x - w/2) / scale, so the mirror of column x is column w - x: a
/// left-handed render's column x shades exactly as the right-handed
/// render's column w - x, in f64 and in Float316 alike.
#[test]
fn left_handed_is_the_right_handed_image_mirrored() {
    let mut left = toon_json();
    left["image"]["camera"]["look_at"]["handedness"] = json!("left");
    let mut right = toon_json();
    right["image"]["camera"]["look_at"]["handedness"] = json!("right");
    for imp in [RefImpl::F64, RefImpl::F316] {
        let (l, r) = (render(&left, imp), render(&right, imp));
        let w = l.width;
        let mut differ = Vec::new();
        let mut hits = 0;
        for y in 0..l.height {
            for x in 1..w {
                let (a, b) = (shade(&l, x, y), shade(&r, w - x, y));
                hits += usize::from(a != shade(&l, 0, 0));
                if a != b {
                    differ.push((x, y));
                }
            }
        }
        assert!(hits > 1000, "{imp}: the tori are in the picture");
        assert!(
            differ.is_empty(),
            "{imp}: {} pixels are not mirrored, first {:?}",
            differ.len(),
            &differ[..differ.len().min(5)]
        );
    }
}

/// Distinct shades of the pixels in columns `cols` that are not background.
fn shades(image: &SceneImage, cols: std::ops::Range<usize>) -> BTreeSet<u64> {
    let background = shade(image, 0, 0);
    (0..image.height)
        .flat_map(|y| cols.clone().map(move |x| (x, y)))
        .filter_map(|(x, y)| shade(image, x, y).filter(|s| Some(*s) != background))
        .collect()
}

/// The toon material has 4 bands (5 shades, the darkest the background's);
/// the diffuse one shades continuously. In the shipped `toon` the diffuse
/// torus is in the left half, the toon one in the right half.
#[test]
fn toon_draws_the_diffuse_torus_on_the_left() {
    let image = render(&toon_json(), RefImpl::F64);
    let half = image.width / 2;
    let left = shades(&image, 0..half);
    let right = shades(&image, half..image.width);
    assert!(left.len() > 50, "left: {} shades", left.len());
    assert!(
        !right.is_empty() && right.len() <= 4,
        "right: {} shades",
        right.len()
    );
}
