//! `rtdemo` on ref-f64 is the BBC BASIC program's arithmetic: the BBC
//! BASIC ray tracer demo's listing (its lines 10-340, numbered as in the
//! listing) transcribed line by line below, recursion and all, gives every drawn pixel's colour
//! and shade; the scene description must give the same, including pixels
//! whose ray reflects twice.

use common::Outcome;
use reference::{Described, RefImpl, Settings};
use std::path::PathBuf;

/// Line 10: the ordered dither pattern A().
const A: [f64; 16] = [
    0.0, 24.0, 6.0, 30.0, 36.0, 12.0, 42.0, 18.0, 9.0, 33.0, 3.0, 27.0, 45.0, 21.0, 39.0, 15.0,
];

/// Lines 310-340: DEFFNc.
fn fn_c(x: f64, y: f64, z: f64, u: f64, v: f64, w: f64) -> f64 {
    if v >= 0.0 {
        return v;
    }
    let p = (y + 2.0) / v;
    let parity = (((x - u * p).floor() as i64 + (z - w * p).floor() as i64) & 1) as f64;
    -v * (parity / 2.0 + 0.3) + 0.2
}

/// Lines 190-300: DEFFNray; `bounces` counts the reflections.
#[allow(clippy::too_many_arguments)]
fn fn_ray(x: f64, y: f64, z: f64, u: f64, v: f64, w: f64, i: f64, bounces: &mut u32) -> f64 {
    let (e, f, g) = (x - i, y - i, z);
    let p = u * e + v * f - w * g;
    let d = p * p - e * e - f * f - g * g + 1.0;
    if d <= 0.0 {
        return fn_c(x, y, z, u, v, w);
    }
    let t = -p - d.sqrt();
    if t <= 0.0 {
        return fn_c(x, y, z, u, v, w);
    }
    let (x, y, z) = (x + t * u, y + t * v, z - t * w);
    let (e, f, g) = (x - i, y - i, z);
    let p = 2.0 * (u * e + v * f - w * g);
    let (u, v, w) = (u - p * e, v - p * f, w + p * g);
    *bounces += 1;
    fn_ray(x, y, z, u, v, w, -i, bounces)
}

/// Lines 80-150 for column m, row n: (shade C, GCOL colour, reflections).
fn bbc_pixel(m: u32, n: u32) -> (f64, u8, u32) {
    let (mf, nf) = (f64::from(m), f64::from(n));
    let u = (mf - 159.5) / 160.0;
    let v = (nf - 127.5) / 160.0;
    let w = 1.0 / (u * u + v * v + 1.0).sqrt();
    let (u, v) = (u * w, v * w);
    let i = u.signum();
    let mut bounces = 0;
    let c = fn_ray(0.0, -0.1, 3.0, u, v, w, i, &mut bounces);
    // BBC DIV truncates its operand to an integer first.
    let t = (48.0 * c.sqrt() + A[(m % 4 + (n % 4) * 4) as usize] / 3.0) as i64;
    (c, (3 - t / 16) as u8, bounces)
}

#[test]
fn rtdemo_on_ref_f64_is_the_bbc_listing_pixel_for_pixel() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../vectors/scenes/rtdemo.json");
    let scene = scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
    let image = Described::new(RefImpl::F64, &scene, Settings::default())
        .unwrap()
        .render();
    assert_eq!((image.width, image.height, image.levels), (320, 240, 4));
    let mut twice = Vec::new();
    for n in 8..=238 {
        for m in 0..320 {
            let (c, colour, bounces) = bbc_pixel(m, n);
            // Line 150: PLOT 69, M, 247 - N.
            let y = 247 - n;
            let Outcome::Value(p) = image.pixels[(y * 320 + m) as usize] else {
                panic!("pixel ({m},{y}) did not render");
            };
            assert_eq!(p.value.value.to_bits(), c.to_bits(), "shade at M={m} N={n}");
            assert_eq!(p.level, colour, "colour at M={m} N={n}");
            if bounces >= 2 {
                twice.push((m, n));
            }
        }
    }
    assert!(!twice.is_empty(), "no pixel reflects twice");
    // One of them by hand: its ray meets both spheres before the floor.
    let (m, n) = twice[twice.len() / 2];
    assert!(bbc_pixel(m, n).2 >= 2);
    // Rows 0..=8 are never plotted: the cleared screen, colour 0.
    for y in 0..9 {
        for m in 0..320 {
            assert!(matches!(image.pixels[y * 320 + m], Outcome::Value(p) if p.level == 0));
        }
    }
}
