//! `gpu-f316`: Float316 as WGSL integer arithmetic (shaders/f316.wgsl, a
//! Float316 shader of the convention), bit-exact with the reference.
//! Single operations, scene distances and pixel shades.

use crate::context::Gpu;
use crate::error::GpuError;
use crate::image::all_pixels;
use crate::shader::{sdf_words, ShaderNum, ShaderNumbers};
use common::{Op, OpValue, Outcome, F316};

/// The triple of an answer of the Float316 shader.
fn f316(n: ShaderNum) -> F316 {
    n.f316().expect("a Float316 shader answers triples")
}

impl Gpu {
    /// Apply Float316 operations: `(op, a, b)` per case; unary operations
    /// ignore `b`. `gt` gives [`OpValue::Bool`], every other op a triple.
    pub fn f316_ops(&self, cases: &[(Op, F316, F316)]) -> Result<Vec<Outcome<OpValue>>, GpuError> {
        self.f316.ops(&self.dev, cases)
    }

    /// The scene at Float316 points: `(sd, col)` per point.
    pub fn f316_sdf(&self, points: &[[F316; 3]]) -> Result<Vec<Outcome<(F316, F316)>>, GpuError> {
        let words = sdf_words(ShaderNumbers::Float316, points);
        Ok(self
            .f316
            .sdf(&self.dev, &words)?
            .into_iter()
            .map(|o| o.map(|(sd, col)| (f316(sd), f316(col))))
            .collect())
    }

    /// Pixel shades: the clamped value before dithering and whether the
    /// dithered pixel is white, per `(x, y)` of the 512x256 image.
    pub fn f316_pixels(
        &self,
        pixels: &[(u16, u16)],
    ) -> Result<Vec<Outcome<(F316, bool)>>, GpuError> {
        Ok(self
            .f316
            .pixels(&self.dev, pixels)?
            .into_iter()
            .map(|o| o.map(|(v, white)| (f316(v), white)))
            .collect())
    }

    /// The whole image, row by row ([`all_pixels`] order).
    pub fn render_f316(&self) -> Result<Vec<Outcome<(F316, bool)>>, GpuError> {
        self.f316_pixels(&all_pixels())
    }
}
