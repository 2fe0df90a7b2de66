//! Pixel coordinates as kernel input: validation against the image size and
//! the full image in row-major order.

use crate::error::GpuError;
use common::image_consts::{bayer, BAYER, HEIGHT, WIDTH};

/// Every pixel of the 512x256 image, row by row (the order of the renders).
pub fn all_pixels() -> Vec<(u16, u16)> {
    (0..HEIGHT as u16)
        .flat_map(|y| (0..WIDTH as u16).map(move |x| (x, y)))
        .collect()
}

/// The dither matrix as WGSL generated from [`BAYER`] (so there is one
/// copy of it): the array `table` and `function(x, y)`, the entry of pixel
/// (x, y). The kernels' prelude names them `BAYER` and `bayer`, the
/// Float316 shader wrapper `harness_bayer_matrix` and `harness_bayer`.
pub(crate) fn bayer_wgsl(table: &str, function: &str) -> String {
    let entries: Vec<String> = BAYER.iter().map(u8::to_string).collect();
    format!(
        "var<private> {table}: array<i32, 64> = array<i32, 64>({});\n\n\
         // The Bayer entry of pixel (x, y): {table}[(y mod 8) * 8 + (x mod 8)].\n\
         fn {function}(x: u32, y: u32) -> i32 {{\n    return {table}[(y % 8u) * 8u + (x % 8u)];\n}}\n",
        entries.join(", ")
    )
}

/// Pixel coordinates as kernel input words (x, y per item).
pub(crate) fn pixel_words(pixels: &[(u16, u16)]) -> Result<Vec<u32>, GpuError> {
    let mut words = Vec::with_capacity(2 * pixels.len());
    for &(x, y) in pixels {
        if x as usize >= WIDTH || y as usize >= HEIGHT {
            return Err(GpuError::PixelOutsideImage {
                x,
                y,
                width: WIDTH,
                height: HEIGHT,
            });
        }
        words.extend([x as u32, y as u32]);
    }
    Ok(words)
}

/// The spec's dithering of a clamped f32 shade at pixel (x, y): white when
/// `(value + B/64) - 0.5 > 0.5`, in f32 (the same IEEE operations as the
/// f32 kernel's WGSL and the float reference).
pub(crate) fn dither_f32(value: f32, x: u16, y: u16) -> bool {
    let b = f32::from(bayer(x as usize, y as usize));
    (value + b / 64.0) - 0.5 > 0.5
}
