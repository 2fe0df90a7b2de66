//! Pixels of the Jack program against the committed Float316 render
//! (`vectors/images/seed-float316-512x256.png`, 255 = white), through the
//! entry point and through the image loop drawing on the Hack screen.

use common::image_consts::WIDTH;
use jack::{Budgets, Profile, Raymarcher};
use std::sync::OnceLock;

fn jack() -> &'static Raymarcher {
    static R: OnceLock<Raymarcher> = OnceLock::new();
    R.get_or_init(|| {
        Raymarcher::new(Profile::Desktop, Budgets::default()).expect("the raymarcher builds")
    })
}

fn reference_white(x: usize, y: usize) -> bool {
    static IMG: OnceLock<image::GrayImage> = OnceLock::new();
    let img = IMG.get_or_init(|| {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../vectors/images/seed-float316-512x256.png"
        );
        image::open(path)
            .expect("the committed reference image")
            .to_luma8()
    });
    img.get_pixel(x as u32, y as u32)[0] == 255
}

#[test]
fn a_spread_of_pixels_matches_the_reference_image() {
    let pixels: Vec<(usize, usize)> = (0..600)
        .map(|i| ((i * 97 + 13) % 512, (i * 53 + 7) % 256))
        .collect();
    let differing: Vec<_> = pixels
        .iter()
        .filter(|&&(x, y)| {
            let p = jack().pixel(x, y).expect("the pixel runs");
            let white = p.outcome.value().expect("a pixel has a value").white;
            white != reference_white(x, y)
        })
        .collect();
    assert!(
        differing.is_empty(),
        "pixels differing from the reference: {differing:?}"
    );
}

#[test]
fn the_image_loop_on_screen_equals_the_entry_point() {
    // Two rows through the sphere, the torus, their shadows and the floor.
    let rows = 150..152;
    let screen = jack()
        .render_band_on_screen(rows.clone(), 1_000_000_000)
        .unwrap()
        .value()
        .expect("the band renders");
    let fast = jack().render_rows(rows.clone()).unwrap();
    let fast_white: Vec<bool> = fast
        .pixels
        .iter()
        .map(|p| p.outcome.value().unwrap().white)
        .collect();
    assert_eq!(screen.white, fast_white);
    for (i, &w) in screen.white.iter().enumerate() {
        let (x, y) = (i % WIDTH, rows.start + i / WIDTH);
        assert_eq!(w, reference_white(x, y), "pixel ({x},{y})");
    }
}

#[test]
fn pixels_outside_the_image_are_refused() {
    let err = jack().pixel(512, 0).unwrap_err();
    assert!(
        err.to_string().contains("outside the 512x256 image"),
        "{err}"
    );
}

/// The whole image through the entry points (about 21.8 billion VM
/// instructions: about 5 s on two cores once the engine compiles the
/// program), every pixel against the committed render.
#[test]
fn the_whole_image_matches_the_reference() {
    let render = jack().render().unwrap();
    let differing: Vec<(usize, usize)> = render
        .pixels
        .iter()
        .enumerate()
        .map(|(i, p)| (i % WIDTH, i / WIDTH, p.outcome.value().map(|s| s.white)))
        .filter(|&(x, y, w)| w != Some(reference_white(x, y)))
        .map(|(x, y, _)| (x, y))
        .collect();
    assert!(
        differing.is_empty(),
        "{} pixels differ, first {:?}",
        differing.len(),
        differing.first()
    );
}

/// `Main.main` run unattended (SPACE scripted), read from screen memory:
/// the slow path of `harness jack run impls/jack/raymarcher --keys SPACE`,
/// against the committed render of the original program. 21.8 G VM
/// instructions on one thread, about 9 s compiled (the auto engine tiers up
/// to it), so every `cargo test` compares the whole image the program
/// itself draws, not only its pixels through the entry points.
#[test]
fn the_whole_program_draws_the_reference() {
    let screen = jack::run_main(Profile::Desktop, 200_000_000_000, &mut |_| {})
        .unwrap()
        .value()
        .expect("Main.main returns");
    for (i, &w) in screen.white.iter().enumerate() {
        let (x, y) = (i % WIDTH, i / WIDTH);
        assert_eq!(w, reference_white(x, y), "pixel ({x},{y})");
    }
}
