//! `gpu-f316`: Float316 as WGSL integer arithmetic (shaders/f316.wgsl),
//! bit-exact with the reference. Kernels for single operations, scene
//! distances and pixel shades.

use crate::context::Gpu;
use crate::error::GpuError;
use crate::image::{all_pixels, pixel_words};
use crate::kernel::KernelSpec;
use common::{Op, OpValue, Outcome, F316};

const SOURCE: &str = include_str!("shaders/f316.wgsl");

/// One operation: op code, a, b -> status, result.
pub(crate) const OPS: KernelSpec = KernelSpec::new("f316 ops", SOURCE, "ops_main", 7, 4);

/// Scene query: p -> status, sd, col.
pub(crate) const SDF: KernelSpec = KernelSpec::new("f316 sdf", SOURCE, "sdf_main", 9, 7);

/// Pixel shade: x, y -> status, value, white.
pub(crate) const PIXELS: KernelSpec = KernelSpec::new("f316 pixels", SOURCE, "pixels_main", 2, 5);

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

impl Gpu {
    /// Apply Float316 operations: `(op, a, b)` per case; unary operations
    /// ignore `b`. `gt` gives [`OpValue::Bool`], every other op a triple.
    pub fn f316_ops(&self, cases: &[(Op, F316, F316)]) -> Result<Vec<Outcome<OpValue>>, GpuError> {
        let mut words = Vec::with_capacity(OPS.in_words * cases.len());
        for &(op, a, b) in cases {
            words.push(op_code(op));
            push_triple(&mut words, a);
            push_triple(&mut words, b);
        }
        let out = self.f316_ops.run(&self.dev, &words)?;
        Ok(out
            .chunks(OPS.out_words)
            .zip(cases)
            .map(|(o, &(op, _, _))| {
                outcome(o[0], || match op {
                    Op::Gt => OpValue::Bool(o[3] == 1),
                    _ => OpValue::Num(triple(&o[1..4])),
                })
            })
            .collect())
    }

    /// The scene at Float316 points: `(sd, col)` per point.
    pub fn f316_sdf(&self, points: &[[F316; 3]]) -> Result<Vec<Outcome<(F316, F316)>>, GpuError> {
        let mut words = Vec::with_capacity(SDF.in_words * points.len());
        for p in points {
            p.iter().for_each(|&c| push_triple(&mut words, c));
        }
        let out = self.f316_sdf.run(&self.dev, &words)?;
        Ok(out
            .chunks(SDF.out_words)
            .map(|o| outcome(o[0], || (triple(&o[1..4]), triple(&o[4..7]))))
            .collect())
    }

    /// Pixel shades: the clamped value before dithering and whether the
    /// dithered pixel is white, per `(x, y)` of the 512x256 image.
    pub fn f316_pixels(
        &self,
        pixels: &[(u16, u16)],
    ) -> Result<Vec<Outcome<(F316, bool)>>, GpuError> {
        let out = self.f316_pixels.run(&self.dev, &pixel_words(pixels)?)?;
        Ok(out
            .chunks(PIXELS.out_words)
            .map(|o| outcome(o[0], || (triple(&o[1..4]), o[4] == 1)))
            .collect())
    }

    /// The whole image, row by row ([`all_pixels`] order).
    pub fn render_f316(&self) -> Result<Vec<Outcome<(F316, bool)>>, GpuError> {
        self.f316_pixels(&all_pixels())
    }
}
