//! `gpu-f32`: the float formulation of the scene (spec section 7) in WGSL
//! f32 (shaders/f32.wgsl, an f32 shader of the convention). Scene
//! distances and pixel shades; the harness clamps and dithers the shade.

use crate::context::Gpu;
use crate::error::GpuError;
use crate::image::all_pixels;
use crate::shader::ShaderNum;
use common::Outcome;

/// The value of an answer of the f32 shader: its loops have constant
/// bounds and it has no `status`, so every answer is a value.
fn value<T>(o: Outcome<T>) -> Result<T, GpuError> {
    let kind = o.kind();
    o.value().ok_or_else(|| GpuError::Execution {
        kernel: "f32".into(),
        message: format!("the f32 kernel answered {kind}, not a value"),
    })
}

/// The number of an answer of the f32 shader.
fn f32_of(n: ShaderNum) -> f32 {
    n.f32().expect("an f32 shader answers f32")
}

impl Gpu {
    /// The scene at f32 points: `(sd, col)` per point.
    pub fn f32_sdf(&self, points: &[[f32; 3]]) -> Result<Vec<(f32, f32)>, GpuError> {
        let words: Vec<u32> = points.iter().flatten().map(|c| c.to_bits()).collect();
        self.f32
            .sdf(&self.dev, &words)?
            .into_iter()
            .map(|o| value(o).map(|(sd, col)| (f32_of(sd), f32_of(col))))
            .collect()
    }

    /// Pixel shades: the value clamped to [0, 1] before dithering and
    /// whether the dithered pixel is white, per `(x, y)`.
    pub fn f32_pixels(&self, pixels: &[(u16, u16)]) -> Result<Vec<(f32, bool)>, GpuError> {
        self.f32
            .pixels(&self.dev, pixels)?
            .into_iter()
            .map(|o| value(o).map(|(v, white)| (f32_of(v), white)))
            .collect()
    }

    /// The whole image, row by row ([`all_pixels`] order).
    pub fn render_f32(&self) -> Result<Vec<(f32, bool)>, GpuError> {
        self.f32_pixels(&all_pixels())
    }
}
