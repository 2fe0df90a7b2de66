//! `gpu-f316`: Float316 as WGSL integer arithmetic (shaders/f316.wgsl, a
//! Float316 shader of the convention), bit-exact with the reference.
//! Single operations, scene distances and pixel shades, and the word
//! encoding every Float316 kernel shares.

use crate::context::Gpu;
use crate::error::GpuError;
use crate::image::all_pixels;
use crate::shader::{sdf_words, ShaderNum, ShaderNumbers};
use common::{Op, OpValue, Outcome, F316};

/// The op code the kernel switches on: the index in [`Op::ALL`].
pub(crate) fn op_code(op: Op) -> u32 {
    Op::ALL
        .iter()
        .position(|&o| o == op)
        .expect("Op::ALL lists every op") as u32
}

/// Append a triple as three input words (each field sign-extended).
pub(crate) fn push_triple(words: &mut Vec<u32>, v: F316) {
    words.extend([v.s, v.e, v.m].map(|field| field as i32 as u32));
}

/// A triple from three output words (each a sign-extended Jack word).
pub(crate) fn triple(words: &[u32]) -> F316 {
    F316::new(words[0] as i16, words[1] as i16, words[2] as i16)
}

/// Decode a status word (`kind | code << 4`, see f316.wgsl) around `value`.
pub(crate) fn outcome<T>(status: u32, value: impl FnOnce() -> T) -> Outcome<T> {
    let status = status as i32;
    match status & 15 {
        0 => Outcome::Value(value()),
        1 => Outcome::SysError((status >> 4) as i16),
        2 => Outcome::Hang,
        _ => Outcome::OutOfDomain,
    }
}

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
