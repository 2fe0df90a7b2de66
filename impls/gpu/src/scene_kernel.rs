//! Kernels generated from a scene ([`crate::scene_wgsl`]): `gpu-f316` from
//! the scene's Float316 program, `gpu-f32` from its IEEE one. Compiled on
//! the shared device; every call batches like the hand-written kernels.

use crate::context::Gpu;
use crate::error::GpuError;
use crate::kernel::{compile, Kernel};
use crate::scene_wgsl::{generate, strides};
use crate::words::{outcome, push_triple, triple};
use common::{Outcome, F316};
use scene::{Formulation, Program};

/// A number a generated kernel returned: its value and, for Float316, the
/// triple.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GpuNum {
    pub value: f64,
    pub triple: Option<F316>,
}

/// A pixel of a generated kernel: the shade before the output step and
/// the output level.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GpuPixel {
    pub value: GpuNum,
    pub level: u8,
}

/// The compiled kernels of one scene in one formulation.
pub struct SceneKernel {
    formulation: Formulation,
    width: u32,
    height: u32,
    source: String,
    pixels: Kernel,
    sdf: Kernel,
}

fn num(form: Formulation, words: &[u32]) -> GpuNum {
    match form {
        Formulation::Float316 => {
            let t = triple(words);
            GpuNum {
                value: t.to_f64(),
                triple: Some(t),
            }
        }
        Formulation::Ieee => GpuNum {
            value: f64::from(f32::from_bits(words[0])),
            triple: None,
        },
    }
}

impl Gpu {
    /// Generate and compile the kernels of `program`.
    pub fn scene_kernel(&self, program: &Program) -> Result<SceneKernel, GpuError> {
        let source = generate(program);
        let (pin, pout, sin, sout) = strides(program.formulation);
        let label = match program.formulation {
            Formulation::Float316 => "scene f316",
            Formulation::Ieee => "scene f32",
        };
        let dev = &self.dev;
        let kernel = |entry, in_words, out_words| -> Result<Kernel, GpuError> {
            let pipeline = compile(&dev.device, &dev.health, &dev.layout, label, &source, entry)?;
            Ok(Kernel::from_pipeline(
                label.to_string(),
                pipeline,
                in_words,
                out_words,
                None,
            ))
        };
        let kernel = SceneKernel {
            formulation: program.formulation,
            width: program.pixels.width,
            height: program.pixels.height,
            pixels: kernel("pixels_main", pin, pout)?,
            sdf: kernel("sdf_main", sin, sout)?,
            source,
        };
        // Lavapipe compiles machine code at the first dispatch: set-up.
        kernel.pixels(self, &[(0, 0)])?;
        Ok(kernel)
    }
}

impl SceneKernel {
    /// The generated WGSL (without the prelude).
    pub fn source(&self) -> &str {
        &self.source
    }

    /// Pixels `(x, y)` of the scene's image.
    pub fn pixels(
        &self,
        gpu: &Gpu,
        pixels: &[(u32, u32)],
    ) -> Result<Vec<Outcome<GpuPixel>>, GpuError> {
        let mut words = Vec::with_capacity(2 * pixels.len());
        for &(x, y) in pixels {
            if x >= self.width || y >= self.height {
                return Err(GpuError::PixelOutsideImage {
                    x: x.min(u32::from(u16::MAX)) as u16,
                    y: y.min(u32::from(u16::MAX)) as u16,
                    width: self.width as usize,
                    height: self.height as usize,
                });
            }
            words.extend([x, y]);
        }
        let out = self.pixels.run(&gpu.dev, &words)?;
        let form = self.formulation;
        Ok(match form {
            Formulation::Float316 => out
                .chunks(5)
                .map(|o| {
                    outcome(o[0], || GpuPixel {
                        value: num(form, &o[1..4]),
                        level: o[4] as u8,
                    })
                })
                .collect(),
            Formulation::Ieee => out
                .chunks(2)
                .map(|o| {
                    Outcome::Value(GpuPixel {
                        value: num(form, &o[..1]),
                        level: o[1] as u8,
                    })
                })
                .collect(),
        })
    }

    /// The whole image, row by row.
    pub fn render(&self, gpu: &Gpu) -> Result<Vec<Outcome<GpuPixel>>, GpuError> {
        let all: Vec<(u32, u32)> = (0..self.height)
            .flat_map(|y| (0..self.width).map(move |x| (x, y)))
            .collect();
        self.pixels(gpu, &all)
    }

    /// The scene's (sd, col) at Float316 points (f32 kernels take each
    /// triple's value rounded to f32).
    pub fn sdf(
        &self,
        gpu: &Gpu,
        points: &[[F316; 3]],
    ) -> Result<Vec<Outcome<(GpuNum, GpuNum)>>, GpuError> {
        let form = self.formulation;
        let mut words = Vec::new();
        for p in points {
            for &c in p {
                match form {
                    Formulation::Float316 => push_triple(&mut words, c),
                    Formulation::Ieee => words.push((c.to_f64() as f32).to_bits()),
                }
            }
        }
        let out = self.sdf.run(&gpu.dev, &words)?;
        Ok(match form {
            Formulation::Float316 => out
                .chunks(7)
                .map(|o| outcome(o[0], || (num(form, &o[1..4]), num(form, &o[4..7]))))
                .collect(),
            Formulation::Ieee => out
                .chunks(2)
                .map(|o| Outcome::Value((num(form, &o[..1]), num(form, &o[1..2]))))
                .collect(),
        })
    }
}
