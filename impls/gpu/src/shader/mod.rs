//! Bring your own shader: a user's WGSL or Shadertoy-style GLSL file,
//! unmodified, wrapped into the harness's compute kernels (conventions in
//! docs/shaders.md and [`convention`]).
//!
//! [`UserShader::check`] runs the front end alone (naga parses the file,
//! the convention is checked, the wrapper added, every loop guarded, the
//! module validated; errors name the user's file, line and column).
//! [`UserShader::open`] also opens a device on any adapter (lavapipe
//! included), compiles the kernels and dispatches each once. A shader that
//! loops for ever answers [`Outcome::Hang`] (the loop guard); a dispatch
//! that still outruns its time limit is a [`GpuError::Timeout`] and the
//! shader's device is abandoned, never waited for.

mod convention;
mod diagnostic;
mod frontend;
mod guard;

pub use convention::{Language, Provides, Shade, ShaderNumbers};

use crate::device::Device;
use crate::error::GpuError;
use crate::image::{all_pixels, dither_f32, pixel_words};
use crate::kernel::{compile_source, Kernel};
use crate::words::{outcome, push_triple, triple};
use common::{AdapterDescription, Op, OpValue, Outcome, F316};
use convention::Entry;
use std::borrow::Cow;
use std::path::Path;
use std::time::Duration;

/// A shader's text, the name its messages use, and its language.
#[derive(Clone, Debug)]
pub struct ShaderSource {
    name: String,
    text: String,
    language: Language,
}

impl ShaderSource {
    /// Read `path`; the language is `language`, else the file's extension
    /// says it (`.wgsl`; `.glsl`, `.frag`, `.fs`).
    pub fn read(path: &Path, language: Option<Language>) -> Result<ShaderSource, GpuError> {
        let name = path.display().to_string();
        let language = language
            .or_else(|| Language::from_extension(path))
            .ok_or_else(|| GpuError::Shader {
                diagnostic: format!(
                    "{name}: error: the language is not declared and the extension does not \
                     say it (.wgsl, .glsl, .frag, .fs): declare `language = \"glsl\"` or \"wgsl\""
                ),
            })?;
        let text =
            common::input::read_text(path).map_err(|source| GpuError::ShaderFile { source })?;
        Ok(ShaderSource {
            name,
            text,
            language,
        })
    }

    /// A shader from text; `name` is what its messages call the file.
    pub fn from_text(name: &str, text: &str, language: Language) -> ShaderSource {
        ShaderSource {
            name: name.to_string(),
            text: text.to_string(),
            language,
        }
    }

    /// The name messages use for the file.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Our own seed-scene kernels, shaders of the convention compiled into
    /// the crate: the WGSL of `gpu-f32` (f32) or of `gpu-f316` (Float316).
    pub fn ours(numbers: ShaderNumbers) -> ShaderSource {
        let (name, text) = match numbers {
            ShaderNumbers::F32 => (
                "impls/gpu/src/shaders/f32.wgsl",
                include_str!("../shaders/f32.wgsl"),
            ),
            ShaderNumbers::Float316 => (
                "impls/gpu/src/shaders/f316.wgsl",
                include_str!("../shaders/f316.wgsl"),
            ),
        };
        ShaderSource::from_text(name, text, Language::Wgsl)
    }
}

/// How a shader is run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShaderOptions {
    /// The numbers it computes with.
    pub numbers: ShaderNumbers,
    /// Where a GLSL shader's shade comes from (`fragColor`'s channel or luminance).
    pub shade: Shade,
    /// Loop iterations one invocation may run, all loops together, before
    /// its answer is a hang (`None`: no loop guard, for a shader whose
    /// every loop has a constant bound).
    pub loop_limit: Option<u32>,
    /// How long one batch may run on the device before it is abandoned
    /// (`None`: no limit).
    pub time_limit: Option<Duration>,
}

impl ShaderOptions {
    /// The default loop limit: far above a raymarcher's few hundred steps
    /// (times its inner loops), and below lavapipe's own silent cut of any
    /// one loop after 65535 iterations (which would give a wrong answer,
    /// not a hang); a whole image of endless loops ends in seconds there.
    pub const LOOP_LIMIT: u32 = 1 << 15;
    /// The default time limit of one batch.
    pub const TIME_LIMIT: Duration = Duration::from_secs(120);
    /// What the first dispatch of each kernel may take beyond the time
    /// limit: the driver may compile the kernel's machine code then
    /// (lavapipe does, 13 s for our Float316 kernel with a cold cache).
    pub const COMPILE_ALLOWANCE: Duration = Duration::from_secs(300);

    /// How our own kernels ([`ShaderSource::ours`]) run: no loop guard and
    /// no time limit. Every loop of theirs has a constant bound, and the
    /// guard's count would add work to every iteration of the Float316
    /// arithmetic's loops (docs/shaders.md, "Our own kernels").
    pub fn ours(numbers: ShaderNumbers) -> ShaderOptions {
        ShaderOptions {
            numbers,
            loop_limit: None,
            time_limit: None,
            ..ShaderOptions::default()
        }
    }
}

impl Default for ShaderOptions {
    fn default() -> Self {
        ShaderOptions {
            numbers: ShaderNumbers::F32,
            shade: Shade::Luminance,
            loop_limit: Some(ShaderOptions::LOOP_LIMIT),
            time_limit: Some(ShaderOptions::TIME_LIMIT),
        }
    }
}

/// A number a shader answered: f32, or a Float316 triple.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ShaderNum {
    /// From an f32 shader.
    F32(f32),
    /// From a Float316 shader.
    F316(F316),
}

impl ShaderNum {
    /// The value of an f32 shader's answer.
    pub fn f32(self) -> Option<f32> {
        match self {
            ShaderNum::F32(v) => Some(v),
            ShaderNum::F316(_) => None,
        }
    }

    /// The triple of a Float316 shader's answer.
    pub fn f316(self) -> Option<F316> {
        match self {
            ShaderNum::F316(t) => Some(t),
            ShaderNum::F32(_) => None,
        }
    }
}

/// A shader's kernels compiled on a device (the device is the caller's:
/// [`UserShader`] opens one per shader, [`crate::Gpu`] shares one between
/// our two kernels and the scene kernels).
pub(crate) struct Compiled {
    name: String,
    language: Language,
    options: ShaderOptions,
    provides: Provides,
    pixels: Kernel,
    sdf: Option<Kernel>,
    ops: Option<Kernel>,
}

impl Compiled {
    /// Run the front end on `source`, compile its kernels on `dev` and
    /// dispatch each once (a driver may compile machine code at the first
    /// dispatch: that is set-up, not image time, and has
    /// [`ShaderOptions::COMPILE_ALLOWANCE`] beyond the time limit).
    pub(crate) fn new(
        dev: &Device,
        source: &ShaderSource,
        options: &ShaderOptions,
    ) -> Result<Compiled, GpuError> {
        let front = frontend::front(source, options.numbers, options.loop_limit)?;
        Compiled::from_front(dev, source, options, front)
    }

    /// [`Compiled::new`] after the front end.
    fn from_front(
        dev: &Device,
        source: &ShaderSource,
        options: &ShaderOptions,
        front: frontend::Front,
    ) -> Result<Compiled, GpuError> {
        let first_limit = options
            .time_limit
            .map(|limit| limit + ShaderOptions::COMPILE_ALLOWANCE);
        let mut kernels: [Option<Kernel>; 3] = [None, None, None];
        for kernel in front.kernels {
            let label = format!("{} {}", source.name, kernel.entry.name());
            let pipeline = compile_source(
                &dev.device,
                &dev.health,
                &dev.layout,
                &label,
                wgpu::ShaderSource::Naga(Cow::Owned(kernel.module)),
                kernel.entry.entry_point(source.language),
            )?;
            let (in_words, out_words) = kernel.entry.words(source.language, options.numbers);
            kernels[kernel.entry as usize] = Some(Kernel::from_pipeline(
                label,
                pipeline,
                in_words,
                out_words,
                first_limit,
            ));
        }
        let [pixels, sdf, ops] = kernels;
        let mut compiled = Compiled {
            name: source.name.clone(),
            language: source.language,
            options: *options,
            provides: front.provides,
            pixels: pixels.expect("every convention has a pixel entry"),
            sdf,
            ops,
        };
        compiled.warm_up(dev)?;
        for kernel in [
            Some(&mut compiled.pixels),
            compiled.sdf.as_mut(),
            compiled.ops.as_mut(),
        ]
        .into_iter()
        .flatten()
        {
            kernel.set_time_limit(options.time_limit);
        }
        Ok(compiled)
    }

    fn warm_up(&self, dev: &Device) -> Result<(), GpuError> {
        self.pixels(dev, &[(256, 128)])?;
        if self.sdf.is_some() {
            self.sdf(dev, &sdf_words(self.options.numbers, &[[F316::ONE; 3]]))?;
        }
        if self.ops.is_some() {
            self.ops(dev, &[(Op::Add, F316::ONE, F316::ONE)])?;
        }
        Ok(())
    }

    fn number(&self, words: &[u32]) -> ShaderNum {
        match self.options.numbers {
            ShaderNumbers::F32 => ShaderNum::F32(f32::from_bits(words[0])),
            ShaderNumbers::Float316 => ShaderNum::F316(triple(words)),
        }
    }

    /// See [`UserShader::pixels`].
    pub(crate) fn pixels(
        &self,
        dev: &Device,
        pixels: &[(u16, u16)],
    ) -> Result<Vec<Outcome<(ShaderNum, bool)>>, GpuError> {
        let out = self.pixels.run(dev, &pixel_words(pixels)?)?;
        let (_, stride) = Entry::Pixels.words(self.language, self.options.numbers);
        Ok(out
            .chunks(stride)
            .zip(pixels)
            .map(|(o, &(x, y))| {
                outcome(o[0], || match self.options.numbers {
                    ShaderNumbers::Float316 => (ShaderNum::F316(triple(&o[1..4])), o[4] == 1),
                    ShaderNumbers::F32 => {
                        let channels = o[1..].iter().map(|&w| f32::from_bits(w));
                        let shade = match self.language {
                            Language::Wgsl => f32::from_bits(o[1]),
                            Language::Glsl => {
                                let rgba: Vec<f32> = channels.collect();
                                self.options.shade.of([rgba[0], rgba[1], rgba[2], rgba[3]])
                            }
                        };
                        let value = shade.clamp(0.0, 1.0);
                        (ShaderNum::F32(value), dither_f32(value, x, y))
                    }
                })
            })
            .collect())
    }

    /// The distance and colour at the points `words` holds ([`sdf_words`]).
    pub(crate) fn sdf(
        &self,
        dev: &Device,
        words: &[u32],
    ) -> Result<Vec<Outcome<(ShaderNum, ShaderNum)>>, GpuError> {
        let kernel = self
            .sdf
            .as_ref()
            .ok_or_else(|| self.not_provided("sdf(p)"))?;
        let out = kernel.run(dev, words)?;
        let (_, stride) = Entry::Sdf.words(self.language, self.options.numbers);
        let half = (stride - 1) / 2;
        Ok(out
            .chunks(stride)
            .map(|o| {
                outcome(o[0], || {
                    (self.number(&o[1..1 + half]), self.number(&o[1 + half..]))
                })
            })
            .collect())
    }

    /// See [`UserShader::ops`].
    pub(crate) fn ops(
        &self,
        dev: &Device,
        cases: &[(Op, F316, F316)],
    ) -> Result<Vec<Outcome<OpValue>>, GpuError> {
        let kernel = self
            .ops
            .as_ref()
            .ok_or_else(|| self.not_provided("op(code, a, b)"))?;
        let mut words = Vec::with_capacity(7 * cases.len());
        for &(op, a, b) in cases {
            words.push(crate::words::op_code(op));
            push_triple(&mut words, a);
            push_triple(&mut words, b);
        }
        let out = kernel.run(dev, &words)?;
        Ok(out
            .chunks(4)
            .zip(cases)
            .map(|(o, &(op, _, _))| {
                outcome(o[0], || match op {
                    Op::Gt => OpValue::Bool(o[3] == 1),
                    _ => OpValue::Num(triple(&o[1..4])),
                })
            })
            .collect())
    }

    fn not_provided(&self, what: &str) -> GpuError {
        GpuError::NotProvided {
            shader: self.name.clone(),
            what: what.to_string(),
        }
    }
}

/// Float316 points as an sdf kernel's input words: triples, or for an f32
/// shader each coordinate's value rounded to f32.
pub(crate) fn sdf_words(numbers: ShaderNumbers, points: &[[F316; 3]]) -> Vec<u32> {
    let mut words = Vec::with_capacity(9 * points.len());
    for p in points {
        for c in p {
            match numbers {
                ShaderNumbers::F32 => words.push((c.to_f64() as f32).to_bits()),
                ShaderNumbers::Float316 => push_triple(&mut words, *c),
            }
        }
    }
    words
}

/// A user's shader compiled on a device of its own, ready to answer.
pub struct UserShader {
    dev: Device,
    compiled: Compiled,
}

impl UserShader {
    /// Run the front end only (no device): what the shader provides, or
    /// the diagnostic that says why it cannot run.
    pub fn check(source: &ShaderSource, options: &ShaderOptions) -> Result<Provides, GpuError> {
        frontend::front(source, options.numbers, options.loop_limit).map(|f| f.provides)
    }

    /// Compile `source` on the preferred adapter and dispatch each kernel
    /// once (see [`ShaderOptions::COMPILE_ALLOWANCE`]).
    pub fn open(source: &ShaderSource, options: &ShaderOptions) -> Result<UserShader, GpuError> {
        // The front end first: a shader that does not compile needs no device.
        let front = frontend::front(source, options.numbers, options.loop_limit)?;
        let dev = Device::open()?;
        let compiled = Compiled::from_front(&dev, source, options, front)?;
        Ok(UserShader { dev, compiled })
    }

    /// The shader's file name.
    pub fn name(&self) -> &str {
        &self.compiled.name
    }

    /// The numbers it computes with.
    pub fn numbers(&self) -> ShaderNumbers {
        self.compiled.options.numbers
    }

    /// The levels beyond pixels and image it answers.
    pub fn provides(&self) -> &Provides {
        &self.compiled.provides
    }

    /// The adapter it runs on.
    pub fn adapter_info(&self) -> &AdapterDescription {
        &self.dev.adapter
    }

    /// Pixel shades: the value before dithering (clamped to [0, 1] for
    /// f32, where the harness dithers as the spec says) and whether the
    /// dithered pixel is white, per `(x, y)` of the 512x256 image (row 0 at
    /// the top).
    pub fn pixels(
        &self,
        pixels: &[(u16, u16)],
    ) -> Result<Vec<Outcome<(ShaderNum, bool)>>, GpuError> {
        self.compiled.pixels(&self.dev, pixels)
    }

    /// The whole image, row by row ([`all_pixels`] order).
    pub fn render(&self) -> Result<Vec<Outcome<(ShaderNum, bool)>>, GpuError> {
        self.pixels(&all_pixels())
    }

    /// The scene's distance and colour at Float316 points (an f32 shader
    /// gets each coordinate's value rounded to f32).
    pub fn sdf(
        &self,
        points: &[[F316; 3]],
    ) -> Result<Vec<Outcome<(ShaderNum, ShaderNum)>>, GpuError> {
        let words = sdf_words(self.compiled.options.numbers, points);
        self.compiled.sdf(&self.dev, &words)
    }

    /// Float316 operations `(op, a, b)`; the op code is the index in
    /// [`Op::ALL`], unary operations ignore `b`, and `gt` answers in the
    /// result's `m` (0 or 1).
    pub fn ops(&self, cases: &[(Op, F316, F316)]) -> Result<Vec<Outcome<OpValue>>, GpuError> {
        self.compiled.ops(&self.dev, cases)
    }

    /// Release the device now; every later call fails with
    /// [`GpuError::DeviceLost`], as after a driver reset.
    pub fn destroy(&self) {
        self.dev.destroy();
    }
}
