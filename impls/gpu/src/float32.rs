//! `gpu-f32`: the float formulation of the scene (spec section 7) in WGSL
//! f32 (shaders/f32.wgsl). Kernels for scene distances and pixel shades.

use crate::context::Gpu;
use crate::error::GpuError;
use crate::image::{all_pixels, pixel_words};
use crate::kernel::KernelSpec;

const SOURCE: &str = include_str!("shaders/f32.wgsl");

/// Scene query: p -> sd, col.
pub(crate) const SDF: KernelSpec = KernelSpec::new("f32 sdf", SOURCE, "sdf_main", 3, 2);

/// Pixel shade: x, y -> value, white.
pub(crate) const PIXELS: KernelSpec = KernelSpec::new("f32 pixels", SOURCE, "pixels_main", 2, 2);

impl Gpu {
    /// The scene at f32 points: `(sd, col)` per point.
    pub fn f32_sdf(&self, points: &[[f32; 3]]) -> Result<Vec<(f32, f32)>, GpuError> {
        let words: Vec<u32> = points.iter().flatten().map(|c| c.to_bits()).collect();
        let out = self.f32_sdf.run(&self.dev, &words)?;
        Ok(out
            .chunks(SDF.out_words)
            .map(|o| (f32::from_bits(o[0]), f32::from_bits(o[1])))
            .collect())
    }

    /// Pixel shades: the value clamped to [0, 1] before dithering and
    /// whether the dithered pixel is white, per `(x, y)`.
    pub fn f32_pixels(&self, pixels: &[(u16, u16)]) -> Result<Vec<(f32, bool)>, GpuError> {
        let out = self.f32_pixels.run(&self.dev, &pixel_words(pixels)?)?;
        Ok(out
            .chunks(PIXELS.out_words)
            .map(|o| (f32::from_bits(o[0]), o[1] == 1))
            .collect())
    }

    /// The whole image, row by row ([`all_pixels`] order).
    pub fn render_f32(&self) -> Result<Vec<(f32, bool)>, GpuError> {
        self.f32_pixels(&all_pixels())
    }
}
