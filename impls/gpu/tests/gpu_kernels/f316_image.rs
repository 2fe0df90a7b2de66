//! The full Float316 render against the committed seed image (the original
//! Jack program's output): zero differing pixels.

use crate::support::gpu;
use common::image_consts::{HEIGHT, WIDTH};
use common::Outcome;

fn seed_image() -> image::GrayImage {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../vectors/images/seed-float316-512x256.png"
    );
    image::open(path).expect("seed image").to_luma8()
}

#[test]
fn f316_render_matches_the_seed_image() {
    let Some(gpu) = gpu() else { return };
    let seed = seed_image();
    assert_eq!(
        (seed.width() as usize, seed.height() as usize),
        (WIDTH, HEIGHT)
    );
    let pixels = gpu.render_f316().expect("render");
    assert_eq!(pixels.len(), WIDTH * HEIGHT);
    let mut differing = Vec::new();
    for (i, outcome) in pixels.iter().enumerate() {
        let (x, y) = (i % WIDTH, i / WIDTH);
        let Outcome::Value((_, white)) = outcome else {
            panic!("pixel ({x},{y}) gave {outcome:?}");
        };
        let seed_white = seed.get_pixel(x as u32, y as u32).0[0] > 127;
        if *white != seed_white {
            differing.push((x, y));
        }
    }
    assert!(
        differing.is_empty(),
        "{} differing pixels, first {:?}",
        differing.len(),
        &differing[..differing.len().min(10)]
    );
}
