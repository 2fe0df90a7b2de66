//! Adapter for the GPU kernels (wgpu: a real GPU or Mesa's lavapipe):
//! `gpu-f316` (Float316 as i32 arithmetic, every level, no traces: the
//! localizer replays ref-f316's trace through its ops kernel) and `gpu-f32`
//! (the float scene: sdf, pixels, image). Without an adapter the
//! implementation is unavailable, with the reason; nothing is faked.

use crate::cast::file::{FieldError, Fields};
use crate::cast::{Entry, Kind, Opener, Request};
use crate::implementation::{Answer, Bitmap, ImplError, Implementation, Num, Numbers};
use common::image_consts::{HEIGHT, WIDTH};
use common::{Outcome, F316};
use gpu::{Gpu, GpuError};
use vectors::{Level, Vector};

/// The `gpu` kind: the seed scene's WGSL kernels, `gpu-f316` and
/// `gpu-f32`; a declared entry picks one with `numbers = "float316" |
/// "f32"`.
pub struct GpuKind;

fn entry(numbers: Numbers) -> Entry {
    if numbers == Numbers::Float316 {
        Entry::new("gpu-f316", "gpu", numbers, GpuOpener { numbers })
            .about("the Float316 kernels (Float316 as i32 arithmetic), wgpu")
    } else {
        Entry::new("gpu-f32", "gpu", numbers, GpuOpener { numbers })
            .about("the f32 scene kernels, wgpu")
            .levels(&[Level::Sdf, Level::Pixels, Level::Image])
    }
}

impl Kind for GpuKind {
    fn name(&self) -> &'static str {
        "gpu"
    }

    fn builtins(&self) -> Vec<Entry> {
        vec![entry(Numbers::F32), entry(Numbers::Float316)]
    }

    fn declare(&self, _name: &str, fields: &mut Fields<'_>) -> Result<Entry, FieldError> {
        match fields.parsed::<Numbers>("numbers")? {
            Some(n @ (Numbers::Float316 | Numbers::F32)) => Ok(entry(n)),
            Some(n) => Err(fields.error(
                "numbers",
                format!("the gpu kernels compute with float316 or f32, not {n}"),
            )),
            None => Err(fields.error("numbers", "missing (required): float316 or f32")),
        }
    }
}

/// Opens a device and the kernels of one number type.
struct GpuOpener {
    numbers: Numbers,
}

impl Opener for GpuOpener {
    fn open(&self, request: &Request<'_>) -> Result<Box<dyn Implementation>, ImplError> {
        request.seed_scene_only()?;
        Ok(Box::new(GpuAdapter::new(
            self.numbers,
            request.label.to_string(),
        )?))
    }
}

/// One of the two GPU implementations on an opened device.
pub struct GpuAdapter {
    gpu: Gpu,
    numbers: Numbers,
    label: String,
}

fn failed(e: GpuError) -> ImplError {
    ImplError::Failed(e.to_string())
}

impl GpuAdapter {
    /// Open a device and compile the kernels computing with `numbers`
    /// (Float316 or f32).
    pub fn new(numbers: Numbers, label: String) -> Result<Self, ImplError> {
        let gpu = Gpu::new()
            .map_err(|e| ImplError::Unavailable(format!("no usable wgpu adapter: {e}")))?;
        Ok(GpuAdapter {
            gpu,
            numbers,
            label,
        })
    }

    fn f316(&self, batch: &[Vector]) -> Result<Vec<Outcome<Answer>>, ImplError> {
        let bitmap = |pixels: Vec<Outcome<(F316, bool)>>| Bitmap {
            width: WIDTH,
            height: HEIGHT,
            white: pixels
                .iter()
                .map(|p| p.value().is_none_or(|(_, w)| w))
                .collect(),
        };
        Ok(match batch.first() {
            None => Vec::new(),
            Some(Vector::Op(_)) => {
                let out = self.gpu.f316_ops(&super::op_cases(batch)).map_err(failed)?;
                out.into_iter().map(|o| o.map(Answer::from)).collect()
            }
            Some(Vector::Sdf(_)) => {
                let points: Vec<[F316; 3]> = batch
                    .iter()
                    .filter_map(|v| match v {
                        Vector::Sdf(s) => Some(s.p),
                        _ => None,
                    })
                    .collect();
                let out = self.gpu.f316_sdf(&points).map_err(failed)?;
                out.into_iter()
                    .map(|o| {
                        o.map(|(sd, col)| Answer::Sdf {
                            sd: Num::F316(sd),
                            col: Num::F316(col),
                        })
                    })
                    .collect()
            }
            Some(Vector::Pixel(_)) => {
                let out = self.gpu.f316_pixels(&pixels_of(batch)).map_err(failed)?;
                out.into_iter()
                    .map(|o| {
                        o.map(|(v, white)| Answer::Pixel {
                            shade: Num::F316(v),
                            white,
                        })
                    })
                    .collect()
            }
            Some(Vector::Image(_)) => {
                let bitmap = bitmap(self.gpu.render_f316().map_err(failed)?);
                vec![Outcome::Value(Answer::Image { bitmap }); batch.len()]
            }
        })
    }

    fn f32(&self, batch: &[Vector]) -> Result<Vec<Outcome<Answer>>, ImplError> {
        Ok(match batch.first() {
            None => Vec::new(),
            Some(Vector::Op(_)) => {
                return Err(ImplError::Unsupported("Float316 operations".into()))
            }
            Some(Vector::Sdf(_)) => {
                let points: Vec<[f32; 3]> = batch
                    .iter()
                    .filter_map(|v| match v {
                        Vector::Sdf(s) => Some(s.p_f64().map(|c| c as f32)),
                        _ => None,
                    })
                    .collect();
                let out = self.gpu.f32_sdf(&points).map_err(failed)?;
                out.into_iter()
                    .map(|(sd, col)| {
                        Outcome::Value(Answer::Sdf {
                            sd: Num::F32(sd),
                            col: Num::F32(col),
                        })
                    })
                    .collect()
            }
            Some(Vector::Pixel(_)) => {
                let out = self.gpu.f32_pixels(&pixels_of(batch)).map_err(failed)?;
                out.into_iter()
                    .map(|(v, white)| {
                        Outcome::Value(Answer::Pixel {
                            shade: Num::F32(v),
                            white,
                        })
                    })
                    .collect()
            }
            Some(Vector::Image(_)) => {
                let pixels = self.gpu.render_f32().map_err(failed)?;
                let bitmap = Bitmap {
                    width: WIDTH,
                    height: HEIGHT,
                    white: pixels.iter().map(|(_, w)| *w).collect(),
                };
                vec![Outcome::Value(Answer::Image { bitmap }); batch.len()]
            }
        })
    }
}

fn pixels_of(batch: &[Vector]) -> Vec<(u16, u16)> {
    batch
        .iter()
        .filter_map(|v| match v {
            Vector::Pixel(p) => Some((p.x, p.y)),
            _ => None,
        })
        .collect()
}

impl Implementation for GpuAdapter {
    fn label(&self) -> String {
        self.label.clone()
    }

    fn numbers(&self) -> Numbers {
        self.numbers
    }

    fn supports(&self, level: Level) -> bool {
        self.numbers == Numbers::Float316 || level != Level::Ops
    }

    fn batch_size(&self, _level: Level) -> usize {
        // The kernels batch to the device's limits themselves: one call.
        usize::MAX
    }

    fn eval(&self, batch: &[Vector]) -> Result<Vec<Outcome<Answer>>, ImplError> {
        if self.numbers == Numbers::Float316 {
            self.f316(batch)
        } else {
            self.f32(batch)
        }
    }
}
