//! A reference implementation made from a scene description: the scene is
//! lowered to the intermediate form in the implementation's formulation
//! and interpreted on its engine (see `interp.rs`). Answers the image, a
//! pixel, an SDF query, and Float316 op traces of the last two.

use crate::api::{output, RefImpl, Scalar, SdfValue, Trace};
use crate::counter::{Counter, OpCounts};
use crate::engine::{outcome, Engine, R};
use crate::float::FloatEngine;
use crate::float316::F316Engine;
use crate::formulation::Formulated;
use crate::interp::{self, Hoisted, Machine, PrepareError, Prepared};
use crate::recorder::{Decided, Recorder};
use crate::settings::{Arith, Settings};
use crate::shadow::{Sh, ShadowEngine, ShadowOptions, ShadowOutput, ShadowRun};
use crate::tracer::Tracer;
use common::{Outcome, F316};
use rayon::prelude::*;
use scene::{Checked, Formulation, Program};
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// A pixel of a described scene: its shade before the output step and its
/// output level (0 or 1 for one bit; 0..=3 for four grey levels).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ScenePixel {
    pub value: Scalar,
    pub level: u8,
}

/// A whole image of a described scene, row by row.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SceneImage {
    pub width: usize,
    pub height: usize,
    /// Output levels: 2 or 4.
    pub levels: u8,
    /// `pixels[y * width + x]`.
    pub pixels: Vec<Outcome<ScenePixel>>,
}

impl SceneImage {
    /// 8-bit grey samples, row by row: level 0 is 0, the top level 255. A
    /// pixel whose computation trapped is white (never drawn on a screen
    /// that starts white), as for the seed render.
    pub fn gray8(&self) -> Vec<u8> {
        let top = u16::from(self.levels - 1);
        self.pixels
            .iter()
            .map(|p| match p {
                Outcome::Value(p) => (u16::from(p.level) * 255 / top) as u8,
                _ => 255,
            })
            .collect()
    }
}

/// Why a described scene cannot be prepared.
#[derive(Debug, thiserror::Error)]
pub enum DescribedError {
    #[error(transparent)]
    Prepare(#[from] PrepareError),
    #[error("the dither-threshold fault exists for the hand-written seed scene only")]
    Fault,
    #[error(
        "the fma variant (contracted multiply-adds) exists for the hand-written seed scene only"
    )]
    Contraction,
    #[error("{0} has no Float316 operations to trace (only ref-f316 does)")]
    NotTraceable(RefImpl),
}

#[derive(Clone, Debug)]
enum Encoded {
    F316(Box<Prepared<F316>>),
    F64(Box<Prepared<f64>>),
    F32(Box<Prepared<f32>>),
}

/// One reference implementation of a described scene.
#[derive(Clone, Debug)]
pub struct Described {
    implementation: RefImpl,
    arith: Arith,
    program: Arc<Program>,
    /// The program without frames and with its constants hoisted, for
    /// runs that record nothing.
    fast: Arc<(Program, Hoisted)>,
    encoded: Encoded,
}

/// Pixel (x, y): its row counter, matrix index and the pixel function; a
/// row the camera does not draw is level 0.
fn pixel_of<E: Engine>(
    e: &mut E,
    p: &Program,
    k: &Prepared<E::N>,
    m: &mut Machine<E::N>,
    (x, y): (u32, u32),
) -> R<(E::N, u8)> {
    let px = &p.pixels;
    let n = match px.row_origin {
        Some(origin) => i64::from(origin) - i64::from(y),
        None => i64::from(y),
    };
    if n < i64::from(px.rows[0]) || n > i64::from(px.rows[1]) {
        return Ok((k.zero, 0));
    }
    let n = n as u32;
    let index = interp::matrix_index(px.dither, x, n);
    let exact = |v: u32| E::constant(f64::from(v)).expect("a pixel coordinate is exact");
    let r = e.frame(
        || format!("pixel({x},{y})"),
        |e| interp::run(e, p, k, m, p.pixel, &[exact(x), exact(n)], index),
    )?;
    let level = E::to_f64(r.results.get(1)) as i64;
    Ok((
        r.results.get(0),
        level.rem_euclid(i64::from(px.levels)) as u8,
    ))
}

fn scene_pixel<E: Engine>(r: R<(E::N, u8)>) -> Outcome<ScenePixel> {
    outcome(r).map(|(v, level)| ScenePixel {
        value: Scalar {
            value: E::to_f64(v),
            triple: E::triple(v),
        },
        level,
    })
}

fn image_of<E: Engine>(
    engine: impl Fn() -> E + Sync,
    p: &(Program, Hoisted),
    k: &Prepared<E::N>,
) -> SceneImage
where
    E::N: Send + Sync,
{
    image_with(engine, p, k, drop).0
}

/// The whole image, rows in parallel, each row on a fresh engine from
/// `engine`, which `finish` takes when the row is done (what it recorded),
/// one result per row.
fn image_with<E: Engine, T: Send>(
    engine: impl Fn() -> E + Sync,
    (p, hoisted): &(Program, Hoisted),
    k: &Prepared<E::N>,
    finish: impl Fn(E) -> T + Sync,
) -> (SceneImage, Vec<T>)
where
    E::N: Send + Sync,
{
    let (w, h) = (p.pixels.width, p.pixels.height);
    let rows: Vec<(Vec<Outcome<ScenePixel>>, T)> = (0..h)
        .into_par_iter()
        .map(|y| {
            let mut e = engine();
            let mut m = Machine::preloaded(p, k, hoisted);
            let row = (0..w)
                .map(|x| scene_pixel::<E>(pixel_of(&mut e, p, k, &mut m, (x, y))))
                .collect();
            (row, finish(e))
        })
        .collect();
    let mut pixels = Vec::with_capacity(w as usize * h as usize);
    let mut finished = Vec::with_capacity(rows.len());
    for (row, t) in rows {
        pixels.extend(row);
        finished.push(t);
    }
    let image = SceneImage {
        width: w as usize,
        height: h as usize,
        levels: p.pixels.levels,
        pixels,
    };
    (image, finished)
}

fn sdf_of<E: Engine>(
    e: &mut E,
    p: &Program,
    k: &Prepared<E::N>,
    q: [F316; 3],
) -> Outcome<SdfValue> {
    let run = |e: &mut E| {
        let args = [
            E::from_triple(q[0])?,
            E::from_triple(q[1])?,
            E::from_triple(q[2])?,
        ];
        let mut m = Machine::new(p, k.zero);
        interp::run(e, p, k, &mut m, p.sdf, &args, 0)
    };
    outcome(run(e)).map(|r| SdfValue {
        sd: scalar::<E>(r.results.get(0)),
        col: scalar::<E>(r.results.get(1)),
    })
}

/// Run `body` on a shadow of `inner` with `p`'s constants and camera
/// set-up made by the same engine (so they are shadowed too).
fn shadowed<E: Formulated>(
    inner: E,
    p: &Program,
    options: &ShadowOptions,
    body: impl FnOnce(&mut ShadowEngine<E>, &Prepared<Sh<E::N>>) -> R<ShadowOutput>,
) -> ShadowRun {
    let mut e = ShadowEngine::new(inner, options.clone());
    // `Described::new` accepted the same constants and set-up in the low
    // precision, which the shadow computes in.
    let k = Prepared::new(p, &mut e).expect("the scene was prepared when the reference was made");
    let r = body(&mut e, &k);
    e.finish(outcome(r))
}

fn shadow_pixel_of<E: Formulated>(
    inner: E,
    p: &Program,
    xy: (u32, u32),
    options: &ShadowOptions,
) -> ShadowRun {
    shadowed(inner, p, options, |e, k| {
        let mut m = Machine::new(p, k.zero);
        let (value, level) = pixel_of(e, p, k, &mut m, xy)?;
        Ok(ShadowOutput {
            values: vec![output::<E>("shade", value)],
            white: (p.pixels.levels == 2).then_some(level == 1),
        })
    })
}

fn shadow_sdf_of<E: Formulated>(
    inner: E,
    p: &Program,
    q: [F316; 3],
    options: &ShadowOptions,
) -> ShadowRun {
    shadowed(inner, p, options, |e, k| {
        let args = [
            ShadowEngine::<E>::from_triple(q[0])?,
            ShadowEngine::<E>::from_triple(q[1])?,
            ShadowEngine::<E>::from_triple(q[2])?,
        ];
        let mut m = Machine::new(p, k.zero);
        let r = e.frame(
            || "sdf".into(),
            |e| interp::run(e, p, k, &mut m, p.sdf, &args, 0),
        )?;
        Ok(ShadowOutput {
            values: vec![
                output::<E>("sd", r.results.get(0)),
                output::<E>("col", r.results.get(1)),
            ],
            white: None,
        })
    })
}

fn decided_pixel_of<E: Engine>(
    inner: E,
    p: &Program,
    k: &Prepared<E::N>,
    xy: (u32, u32),
) -> (Outcome<ScenePixel>, Vec<Decided>) {
    let mut log = Vec::new();
    let mut e = Recorder {
        inner,
        log: &mut log,
    };
    let mut m = Machine::new(p, k.zero);
    let pixel = scene_pixel::<E>(pixel_of(&mut e, p, k, &mut m, xy));
    (pixel, log)
}

fn scalar<E: Engine>(v: E::N) -> Scalar {
    Scalar {
        value: E::to_f64(v),
        triple: E::triple(v),
    }
}

impl Described {
    /// Lower `scene` for `implementation` and encode it; fails when a
    /// constant cannot be encoded (the error names its field), the camera
    /// set-up traps, or `settings` holds the dither-threshold fault.
    pub fn new(
        implementation: RefImpl,
        scene: &Checked,
        settings: Settings,
    ) -> Result<Self, DescribedError> {
        if settings.dither_threshold {
            return Err(DescribedError::Fault);
        }
        if settings.contract_multiply_add {
            return Err(DescribedError::Contraction);
        }
        let form = match implementation {
            RefImpl::F316 => Formulation::Float316,
            RefImpl::F64 | RefImpl::F32 => Formulation::Ieee,
        };
        let program = scene::lower(scene, form);
        debug_assert_eq!(program.validate(), Ok(()));
        let encoded = match implementation {
            RefImpl::F316 => Encoded::F316(Box::new(Prepared::new(
                &program,
                &mut F316Engine::new(settings.arith),
            )?)),
            RefImpl::F64 => {
                Encoded::F64(Box::new(Prepared::new(&program, &mut FloatEngine::new())?))
            }
            RefImpl::F32 => {
                Encoded::F32(Box::new(Prepared::new(&program, &mut FloatEngine::new())?))
            }
        };
        Ok(Described {
            implementation,
            arith: settings.arith,
            fast: Arc::new(interp::untraced(&program)),
            program: Arc::new(program),
            encoded,
        })
    }

    /// Which implementation this is.
    pub fn implementation(&self) -> RefImpl {
        self.implementation
    }

    /// The lowered program.
    pub fn program(&self) -> &Program {
        &self.program
    }

    /// The whole image, rows in parallel.
    pub fn render(&self) -> SceneImage {
        let p = &*self.fast;
        match &self.encoded {
            Encoded::F316(k) if self.arith == Arith::SPEC => image_of(F316Engine::spec, p, k),
            Encoded::F316(k) => image_of(|| F316Engine::new(self.arith), p, k),
            Encoded::F64(k) => image_of(FloatEngine::new, p, k),
            Encoded::F32(k) => image_of(FloatEngine::new, p, k),
        }
    }

    /// The whole image with the Float316 operations it made (the set-up's
    /// once and every pixel's), rows in parallel. `ref-f316` only.
    pub fn render_counted(&self) -> Result<(SceneImage, OpCounts), DescribedError> {
        let k = self.f316()?;
        let engine = || F316Engine::recording(self.arith, Counter::default());
        let (image, rows) = image_with(engine, &self.fast, k, |e| e.into_recorder().counts);
        let mut counts = self.setup_counted()?;
        rows.iter().for_each(|c| counts.add(c));
        Ok((image, counts))
    }

    /// The Float316 operations of the set-up (the camera, once per image).
    /// `ref-f316` only.
    pub fn setup_counted(&self) -> Result<OpCounts, DescribedError> {
        self.f316()?;
        let mut e = F316Engine::recording(self.arith, Counter::default());
        Prepared::new(&self.program, &mut e)?;
        Ok(e.into_recorder().counts)
    }

    /// Pixel (x, y) with the Float316 operations it made. `ref-f316` only.
    pub fn pixel_counted(
        &self,
        x: u32,
        y: u32,
    ) -> Result<(Outcome<ScenePixel>, OpCounts), DescribedError> {
        let k = self.f316()?;
        let (p, hoisted) = &*self.fast;
        let mut m = Machine::preloaded(p, k, hoisted);
        let mut e = F316Engine::recording(self.arith, Counter::default());
        let pixel = scene_pixel::<F316Engine<Counter>>(pixel_of(&mut e, p, k, &mut m, (x, y)));
        Ok((pixel, e.into_recorder().counts))
    }

    /// Pixel (x, y), x from the left, y from the top.
    pub fn pixel(&self, x: u32, y: u32) -> Outcome<ScenePixel> {
        let (p, hoisted) = &*self.fast;
        match &self.encoded {
            Encoded::F316(k) => {
                let mut m = Machine::preloaded(p, k, hoisted);
                let mut e = F316Engine::new(self.arith);
                scene_pixel::<F316Engine>(pixel_of(&mut e, p, k, &mut m, (x, y)))
            }
            Encoded::F64(k) => {
                let mut m = Machine::preloaded(p, k, hoisted);
                scene_pixel::<FloatEngine<f64>>(pixel_of(
                    &mut FloatEngine::new(),
                    p,
                    k,
                    &mut m,
                    (x, y),
                ))
            }
            Encoded::F32(k) => {
                let mut m = Machine::preloaded(p, k, hoisted);
                scene_pixel::<FloatEngine<f32>>(pixel_of(
                    &mut FloatEngine::new(),
                    p,
                    k,
                    &mut m,
                    (x, y),
                ))
            }
        }
    }

    /// The scene's distance and colour at `q` (floats take each triple's
    /// value).
    pub fn sdf(&self, q: [F316; 3]) -> Outcome<SdfValue> {
        let p = &self.program;
        match &self.encoded {
            Encoded::F316(k) => sdf_of(&mut F316Engine::new(self.arith), p, k, q),
            Encoded::F64(k) => sdf_of(&mut FloatEngine::new(), p, k, q),
            Encoded::F32(k) => sdf_of(&mut FloatEngine::new(), p, k, q),
        }
    }

    /// Pixel (x, y) with every value shadowed in f64, its decisions
    /// recorded (see `Reference::shadow_pixel`, the same for the
    /// hand-written seed scene).
    pub fn shadow_pixel(&self, x: u32, y: u32, options: &ShadowOptions) -> ShadowRun {
        let p = &self.program;
        match &self.encoded {
            Encoded::F316(_) => shadow_pixel_of(F316Engine::new(self.arith), p, (x, y), options),
            Encoded::F64(_) => shadow_pixel_of(FloatEngine::<f64>::new(), p, (x, y), options),
            Encoded::F32(_) => shadow_pixel_of(FloatEngine::<f32>::new(), p, (x, y), options),
        }
    }

    /// One SDF query, shadowed (see [`Described::shadow_pixel`]).
    pub fn shadow_sdf(&self, q: [F316; 3], options: &ShadowOptions) -> ShadowRun {
        let p = &self.program;
        match &self.encoded {
            Encoded::F316(_) => shadow_sdf_of(F316Engine::new(self.arith), p, q, options),
            Encoded::F64(_) => shadow_sdf_of(FloatEngine::<f64>::new(), p, q, options),
            Encoded::F32(_) => shadow_sdf_of(FloatEngine::<f32>::new(), p, q, options),
        }
    }

    /// Pixel (x, y) and the branch decisions its run takes, in order.
    pub fn decided_pixel(&self, x: u32, y: u32) -> (Outcome<ScenePixel>, Vec<Decided>) {
        let p = &self.program;
        match &self.encoded {
            Encoded::F316(k) => decided_pixel_of(F316Engine::new(self.arith), p, k, (x, y)),
            Encoded::F64(k) => decided_pixel_of(FloatEngine::<f64>::new(), p, k, (x, y)),
            Encoded::F32(k) => decided_pixel_of(FloatEngine::<f32>::new(), p, k, (x, y)),
        }
    }

    fn f316(&self) -> Result<&Prepared<F316>, DescribedError> {
        match &self.encoded {
            Encoded::F316(k) => Ok(k),
            _ => Err(DescribedError::NotTraceable(self.implementation)),
        }
    }

    /// Every Float316 operation of pixel (x, y). `ref-f316` only.
    pub fn trace_pixel(&self, x: u32, y: u32) -> Result<Trace<ScenePixel>, DescribedError> {
        let k = self.f316()?;
        let mut tracer = Tracer::default();
        let mut m = Machine::new(&self.program, k.zero);
        let r = pixel_of(
            &mut F316Engine::with_tracer(self.arith, &mut tracer),
            &self.program,
            k,
            &mut m,
            (x, y),
        );
        Ok(Trace {
            outcome: scene_pixel::<F316Engine>(r),
            records: tracer.into_records(),
        })
    }

    /// Every Float316 operation of one SDF query. `ref-f316` only.
    pub fn trace_sdf(&self, q: [F316; 3]) -> Result<Trace<SdfValue>, DescribedError> {
        let k = self.f316()?;
        let mut tracer = Tracer::new(Some(format!("sdf({:?},{:?},{:?})", q[0], q[1], q[2])));
        let outcome = sdf_of(
            &mut F316Engine::with_tracer(self.arith, &mut tracer),
            &self.program,
            k,
            q,
        );
        Ok(Trace {
            outcome,
            records: tracer.into_records(),
        })
    }
}
