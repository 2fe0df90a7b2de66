//! The public face of the reference: the three implementations by name, and
//! what each answers (an SDF query, a pixel, the whole image, a Float316
//! operation), plus op traces for the Float316 one.

use crate::consts::Consts;
use crate::engine::{outcome, Engine};
use crate::float::FloatEngine;
use crate::float316::F316Engine;
use crate::formulation::Formulated;
use crate::pipeline::{self, Shaded};
use crate::scene::{Scene, SceneError};
use crate::settings::{Arith, Settings};
use crate::shadow::{OutputValue, Sh, ShadowEngine, ShadowOptions, ShadowOutput, ShadowRun};
use crate::tracer::Tracer;
use crate::vec3::V3;
use common::image_consts::{HEIGHT, WIDTH};
use common::{Op, OpValue, Outcome, TraceRecord, F316};
use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

/// One of the reference implementations.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum RefImpl {
    /// `ref-f316`: Float316, bit-exact with the Jack program.
    #[serde(rename = "ref-f316")]
    F316,
    /// `ref-f64`: the float formulation in f64 (the oracle for error figures).
    #[serde(rename = "ref-f64")]
    F64,
    /// `ref-f32`: the float formulation in f32.
    #[serde(rename = "ref-f32")]
    F32,
}

impl RefImpl {
    /// All three.
    pub const ALL: [RefImpl; 3] = [RefImpl::F316, RefImpl::F64, RefImpl::F32];

    /// The command-line name (`ref-f316`, `ref-f64`, `ref-f32`).
    pub const fn name(self) -> &'static str {
        match self {
            RefImpl::F316 => "ref-f316",
            RefImpl::F64 => "ref-f64",
            RefImpl::F32 => "ref-f32",
        }
    }
}

impl fmt::Display for RefImpl {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A name that is not one of the reference implementations.
#[derive(Debug, thiserror::Error)]
#[error("unknown reference implementation `{0}` (expected ref-f316, ref-f64 or ref-f32)")]
pub struct UnknownImpl(pub String);

impl FromStr for RefImpl {
    type Err = UnknownImpl;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        RefImpl::ALL
            .into_iter()
            .find(|i| i.name() == s)
            .ok_or_else(|| UnknownImpl(s.to_string()))
    }
}

/// A number produced by an implementation: its value as f64 and, for
/// Float316, the triple itself.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Scalar {
    pub value: f64,
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub triple: Option<F316>,
}

impl Scalar {
    fn of<E: Engine>(v: E::N) -> Scalar {
        Scalar {
            value: E::to_f64(v),
            triple: E::triple(v),
        }
    }
}

/// The scene's answer at a point: signed distance and colour.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SdfValue {
    pub sd: Scalar,
    pub col: Scalar,
}

/// A pixel: the clamped shade before dithering, and the dithered bit.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PixelValue {
    pub value: Scalar,
    pub white: bool,
}

/// A whole 512x256 image, row by row.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RenderedImage {
    pub width: usize,
    pub height: usize,
    /// `pixels[y * width + x]`.
    pub pixels: Vec<Outcome<PixelValue>>,
}

impl RenderedImage {
    /// Whether pixel (x, y) is white. A pixel whose computation trapped is
    /// white: the Jack program never draws it (the Hack screen starts white).
    pub fn is_white(&self, x: usize, y: usize) -> bool {
        match self.pixels[y * self.width + x] {
            Outcome::Value(p) => p.white,
            _ => true,
        }
    }

    /// 8-bit grayscale samples, row by row: 255 white, 0 black.
    pub fn gray8(&self) -> Vec<u8> {
        (0..self.height)
            .flat_map(|y| (0..self.width).map(move |x| (x, y)))
            .map(|(x, y)| if self.is_white(x, y) { 255 } else { 0 })
            .collect()
    }

    /// How many pixels are white.
    pub fn white_count(&self) -> usize {
        self.gray8().iter().filter(|&&g| g == 255).count()
    }
}

/// An outcome together with the Float316 operations that produced it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Trace<T> {
    pub outcome: Outcome<T>,
    pub records: Vec<TraceRecord>,
}

/// A request the reference cannot answer.
#[derive(Debug, thiserror::Error)]
pub enum RequestError {
    /// Only `ref-f316` records op traces.
    #[error("{0} has no Float316 operations to trace (only ref-f316 does)")]
    NotTraceable(RefImpl),
    /// An operation was given the wrong number of operands.
    #[error("{op} takes {expected} operand(s), {given} given")]
    Arity {
        op: Op,
        expected: usize,
        given: usize,
    },
}

/// The scene's constants, prepared for one implementation's number type.
#[derive(Clone, Debug)]
enum Prepared {
    F316(Box<Consts<F316>>),
    F64(Box<Consts<f64>>),
    F32(Box<Consts<f32>>),
}

/// One reference implementation with a scene and settings, ready to answer.
#[derive(Clone, Debug)]
pub struct Reference {
    implementation: RefImpl,
    settings: Settings,
    consts: Prepared,
    /// The scene, for the shadowed runs' constants.
    scene: Scene,
}

/// The float engine of `settings` (contracting under `fma`).
fn float_engine<T>(settings: Settings) -> FloatEngine<T> {
    FloatEngine::contracting(settings.contract_multiply_add)
}

fn sdf_at<E: Engine>(e: &mut E, k: &Consts<E::N>, p: [F316; 3]) -> Outcome<SdfValue> {
    let point = || {
        Ok(V3::new(
            E::from_triple(p[0])?,
            E::from_triple(p[1])?,
            E::from_triple(p[2])?,
        ))
    };
    outcome(point().and_then(|p| pipeline::sdf(e, k, p))).map(|s| SdfValue {
        sd: Scalar::of::<E>(s.sd),
        col: Scalar::of::<E>(s.col),
    })
}

fn pixel_value<E: Engine>(s: Shaded<E::N>) -> PixelValue {
    PixelValue {
        value: Scalar::of::<E>(s.value),
        white: s.white,
    }
}

fn pixel_at<E: Engine>(e: &mut E, k: &Consts<E::N>, x: usize, y: usize) -> Outcome<PixelValue> {
    let r = pipeline::counter(e, k, x)
        .and_then(|xc| Ok((xc, pipeline::counter(e, k, y)?)))
        .and_then(|c| pipeline::pixel(e, k, (x, y), c));
    outcome(r).map(pixel_value::<E>)
}

fn coords_at<E: Engine>(e: &mut E, k: &Consts<E::N>, x: usize, y: usize) -> Outcome<[Scalar; 2]> {
    let r = pipeline::counter(e, k, x)
        .and_then(|xc| Ok((xc, pipeline::counter(e, k, y)?)))
        .and_then(|c| pipeline::coords(e, k, c));
    outcome(r).map(|(u, v)| [Scalar::of::<E>(u), Scalar::of::<E>(v)])
}

fn image_of<E: Engine>(engine: impl Fn() -> E + Sync, k: &Consts<E::N>) -> RenderedImage {
    let pixels = pipeline::image(engine, k)
        .into_iter()
        .map(|r| outcome(r).map(pixel_value::<E>))
        .collect();
    RenderedImage {
        width: WIDTH,
        height: HEIGHT,
        pixels,
    }
}

impl Reference {
    /// Prepare `implementation` for `scene` under `settings`. Fails when a
    /// scene constant cannot be encoded (the error names the field) or the
    /// camera basis traps.
    pub fn new(
        implementation: RefImpl,
        scene: &Scene,
        settings: Settings,
    ) -> Result<Self, SceneError> {
        scene.check()?;
        let fault = settings.dither_threshold;
        let consts = match implementation {
            RefImpl::F316 => {
                let mut e = F316Engine::new(settings.arith);
                Prepared::F316(Box::new(Consts::build(scene, &mut e, fault)?))
            }
            RefImpl::F64 => Prepared::F64(Box::new(Consts::build(
                scene,
                &mut float_engine(settings),
                fault,
            )?)),
            RefImpl::F32 => Prepared::F32(Box::new(Consts::build(
                scene,
                &mut float_engine(settings),
                fault,
            )?)),
        };
        Ok(Reference {
            implementation,
            settings,
            consts,
            scene: scene.clone(),
        })
    }

    /// The seed scene with the spec's settings.
    pub fn seed(implementation: RefImpl) -> Self {
        Reference::new(implementation, &Scene::default(), Settings::default())
            .expect("the seed scene is valid in every implementation")
    }

    /// Which implementation this is.
    pub fn implementation(&self) -> RefImpl {
        self.implementation
    }

    /// The float engine of the settings (contracting with `fma`).
    fn float<T>(&self) -> FloatEngine<T> {
        float_engine(self.settings)
    }

    /// The scene's distance and colour at `p` (the float implementations
    /// take the f64 value of each triple).
    pub fn sdf(&self, p: [F316; 3]) -> Outcome<SdfValue> {
        match &self.consts {
            Prepared::F316(k) => sdf_at(&mut F316Engine::new(self.settings.arith), k, p),
            Prepared::F64(k) => sdf_at(&mut self.float(), k, p),
            Prepared::F32(k) => sdf_at(&mut self.float(), k, p),
        }
    }

    /// Pixel (x, y): x counts columns from the left, y rows from the top.
    /// Coordinates outside 512x256 are computed the same way.
    pub fn pixel(&self, x: usize, y: usize) -> Outcome<PixelValue> {
        match &self.consts {
            Prepared::F316(k) if self.settings.arith == Arith::SPEC => {
                pixel_at(&mut F316Engine::spec(), k, x, y)
            }
            Prepared::F316(k) => pixel_at(&mut F316Engine::new(self.settings.arith), k, x, y),
            Prepared::F64(k) => pixel_at(&mut self.float(), k, x, y),
            Prepared::F32(k) => pixel_at(&mut self.float(), k, x, y),
        }
    }

    /// The normalized coordinates `[u, v]` of pixel (x, y), the arguments
    /// of the spec's `pixel(u, v)`, computed as [`Reference::pixel`] does.
    pub fn pixel_coords(&self, x: usize, y: usize) -> Outcome<[Scalar; 2]> {
        match &self.consts {
            Prepared::F316(k) => coords_at(&mut F316Engine::new(self.settings.arith), k, x, y),
            Prepared::F64(k) => coords_at(&mut self.float(), k, x, y),
            Prepared::F32(k) => coords_at(&mut self.float(), k, x, y),
        }
    }

    /// The whole image, rows in parallel.
    pub fn render(&self) -> RenderedImage {
        match &self.consts {
            Prepared::F316(k) if self.settings.arith == Arith::SPEC => {
                image_of(F316Engine::spec, k)
            }
            Prepared::F316(k) => image_of(|| F316Engine::new(self.settings.arith), k),
            Prepared::F64(k) => image_of(|| self.float(), k),
            Prepared::F32(k) => image_of(|| self.float(), k),
        }
    }

    fn f316_consts(&self) -> Result<&Consts<F316>, RequestError> {
        match &self.consts {
            Prepared::F316(k) => Ok(k),
            _ => Err(RequestError::NotTraceable(self.implementation)),
        }
    }

    fn traced<T>(
        &self,
        root: Option<String>,
        run: impl FnOnce(&mut F316Engine<&mut Tracer>, &Consts<F316>) -> Outcome<T>,
    ) -> Result<Trace<T>, RequestError> {
        let k = self.f316_consts()?;
        let mut tracer = Tracer::new(root);
        let outcome = run(
            &mut F316Engine::with_tracer(self.settings.arith, &mut tracer),
            k,
        );
        Ok(Trace {
            outcome,
            records: tracer.into_records(),
        })
    }

    /// Every Float316 operation of pixel (x, y), from its coordinates to its
    /// dithered bit (the image loop's pixel counters are not part of it).
    /// `ref-f316` only.
    pub fn trace_pixel(&self, x: usize, y: usize) -> Result<Trace<PixelValue>, RequestError> {
        let k = self.f316_consts()?;
        let mut e = F316Engine::new(self.settings.arith);
        let counters = pipeline::counter(&mut e, k, x)
            .and_then(|xc| Ok((xc, pipeline::counter(&mut e, k, y)?)));
        self.traced(None, |e, k| {
            outcome(counters.and_then(|c| pipeline::pixel(e, k, (x, y), c)))
                .map(pixel_value::<F316Engine>)
        })
    }

    /// The Float316 operations of pixel (x, y)'s coordinates: the records
    /// that open [`Reference::trace_pixel`]. `ref-f316` only.
    pub fn trace_pixel_coords(
        &self,
        x: usize,
        y: usize,
    ) -> Result<Trace<[Scalar; 2]>, RequestError> {
        let k = self.f316_consts()?;
        let mut e = F316Engine::new(self.settings.arith);
        let counters = pipeline::counter(&mut e, k, x)
            .and_then(|xc| Ok((xc, pipeline::counter(&mut e, k, y)?)));
        self.traced(None, |e, k| {
            let coords = counters
                .and_then(|c| e.frame(|| format!("pixel({x},{y})"), |e| pipeline::coords(e, k, c)));
            outcome(coords).map(|(u, v)| [Scalar::of::<F316Engine>(u), Scalar::of::<F316Engine>(v)])
        })
    }

    /// Pixel (x, y) of ref-f316 from its normalized coordinates `[u, v]`
    /// (as [`Reference::pixel_coords`] gives them): what a port's pixel
    /// function computes from its arguments. `ref-f316` only.
    pub fn pixel_from_coords(
        &self,
        x: usize,
        y: usize,
        [u, v]: [F316; 2],
    ) -> Result<Outcome<PixelValue>, RequestError> {
        let k = self.f316_consts()?;
        let mut e = F316Engine::new(self.settings.arith);
        Ok(outcome(pipeline::shaded(&mut e, k, (x, y), (u, v))).map(pixel_value::<F316Engine>))
    }

    /// Every Float316 operation of [`Reference::pixel_from_coords`], under
    /// the same path as in [`Reference::trace_pixel`]. `ref-f316` only.
    pub fn trace_pixel_from_coords(
        &self,
        x: usize,
        y: usize,
        [u, v]: [F316; 2],
    ) -> Result<Trace<PixelValue>, RequestError> {
        self.traced(None, |e, k| {
            let r = e.frame(
                || format!("pixel({x},{y})"),
                |e| pipeline::shaded(e, k, (x, y), (u, v)),
            );
            outcome(r).map(pixel_value::<F316Engine>)
        })
    }

    /// Every Float316 operation of one SDF query. `ref-f316` only.
    pub fn trace_sdf(&self, p: [F316; 3]) -> Result<Trace<SdfValue>, RequestError> {
        self.traced(
            Some(format!("sdf({:?},{:?},{:?})", p[0], p[1], p[2])),
            |e, k| sdf_at(e, k, p),
        )
    }
}

/// Run `body` on a shadow of `inner` with the scene's constants (built by
/// the same engine, so the camera basis is shadowed and correctable too).
fn shadowed<E: Formulated>(
    inner: E,
    scene: &Scene,
    settings: Settings,
    options: &ShadowOptions,
    body: impl FnOnce(&mut ShadowEngine<E>, &Consts<Sh<E::N>>) -> crate::engine::R<ShadowOutput>,
) -> ShadowRun {
    let mut e = ShadowEngine::new(inner, options.clone());
    // The scene was accepted by `Reference::new` with the same low
    // precision encoding and camera computation, so it is accepted here.
    let k = Consts::build(scene, &mut e, settings.dither_threshold)
        .expect("the scene was checked when the reference was made");
    let r = body(&mut e, &k);
    e.finish(outcome(r))
}

pub(crate) fn output<E: Engine>(name: &'static str, v: Sh<E::N>) -> OutputValue {
    OutputValue {
        name,
        lo: E::to_f64(v.lo),
        hi: v.hi,
    }
}

fn shadow_pixel_of<E: Formulated>(
    inner: E,
    r: &Reference,
    (x, y): (usize, usize),
    options: &ShadowOptions,
) -> ShadowRun {
    shadowed(inner, &r.scene, r.settings, options, |e, k| {
        // The image loop's counters are exact integers in every precision.
        let counter = |n: usize| {
            ShadowEngine::<E>::constant(n as f64).ok_or(crate::engine::Trap::OutOfDomain)
        };
        let s = pipeline::pixel(e, k, (x, y), (counter(x)?, counter(y)?))?;
        Ok(ShadowOutput {
            values: vec![output::<E>("shade", s.value)],
            white: Some(s.white),
        })
    })
}

fn shadow_sdf_of<E: Formulated>(
    inner: E,
    r: &Reference,
    p: [F316; 3],
    options: &ShadowOptions,
) -> ShadowRun {
    shadowed(inner, &r.scene, r.settings, options, |e, k| {
        let point = V3::new(
            ShadowEngine::<E>::from_triple(p[0])?,
            ShadowEngine::<E>::from_triple(p[1])?,
            ShadowEngine::<E>::from_triple(p[2])?,
        );
        let s = e.frame(|| "sdf".into(), |e| pipeline::sdf(e, k, point))?;
        Ok(ShadowOutput {
            values: vec![output::<E>("sd", s.sd), output::<E>("col", s.col)],
            white: None,
        })
    })
}

impl Reference {
    /// Pixel (x, y) with every value shadowed in f64 (see
    /// [`crate::ShadowEngine`]): its decisions, and its operations when
    /// `options.record_ops`. The low-precision answer is this
    /// implementation's, bit for bit, except under the `fma` variant: the
    /// shadow engine rounds products and sums apart, so a contracting
    /// reference is shadowed as the spec's (`harness explain` refuses it).
    pub fn shadow_pixel(&self, x: usize, y: usize, options: &ShadowOptions) -> ShadowRun {
        let arith = self.settings.arith;
        match &self.consts {
            Prepared::F316(_) => shadow_pixel_of(F316Engine::new(arith), self, (x, y), options),
            Prepared::F64(_) => shadow_pixel_of(FloatEngine::<f64>::new(), self, (x, y), options),
            Prepared::F32(_) => shadow_pixel_of(FloatEngine::<f32>::new(), self, (x, y), options),
        }
    }

    /// One SDF query, shadowed (see [`Reference::shadow_pixel`]).
    pub fn shadow_sdf(&self, p: [F316; 3], options: &ShadowOptions) -> ShadowRun {
        let arith = self.settings.arith;
        match &self.consts {
            Prepared::F316(_) => shadow_sdf_of(F316Engine::new(arith), self, p, options),
            Prepared::F64(_) => shadow_sdf_of(FloatEngine::<f64>::new(), self, p, options),
            Prepared::F32(_) => shadow_sdf_of(FloatEngine::<f32>::new(), self, p, options),
        }
    }
}

fn check_arity(op: Op, args: &[F316]) -> Result<(), RequestError> {
    if args.len() == op.arity() {
        Ok(())
    } else {
        Err(RequestError::Arity {
            op,
            expected: op.arity(),
            given: args.len(),
        })
    }
}

/// One Float316 operation on `args` under `arith` (`gt` gives a boolean).
pub fn op(op: Op, args: &[F316], arith: Arith) -> Result<Outcome<OpValue>, RequestError> {
    check_arity(op, args)?;
    Ok(outcome(F316Engine::new(arith).apply(op, args)))
}

/// One Float316 operation with the operations it calls, in pre-order.
pub fn trace_op(op: Op, args: &[F316], arith: Arith) -> Result<Trace<OpValue>, RequestError> {
    check_arity(op, args)?;
    let mut tracer = Tracer::default();
    let r = F316Engine::with_tracer(arith, &mut tracer).apply(op, args);
    Ok(Trace {
        outcome: outcome(r),
        records: tracer.into_records(),
    })
}
