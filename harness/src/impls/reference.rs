//! The `reference` kind: the Rust reference's `ref-f316` (bit-exact
//! Float316, traces natively, the tracer), `ref-f64` (the oracle) and
//! `ref-f32`, with the reference's variants and faults, plus the "f32
//! oracle" fault (ref-f32 posing as ref-f64).
//!
//! Ops on the float implementations are the real operation on the exact
//! values of the operands, in that float type; a non-finite result is out
//! of domain.

use crate::cast::entry::{Entry, Kind, Opener, Request, Roles, VariantInfo, VariantRole};
use crate::cast::file::{FieldError, Fields};
use crate::implementation::{
    Answer, Bitmap, ImageAnswers, ImplError, Implementation, Num, Numbers,
};
use common::{Op, OpValue, Outcome, TraceRecord, F316};
use reference::{PixelValue, RefImpl, Reference, Scalar, SdfValue, Settings, Variant, VariantKind};
use vectors::{Level, OpVector, Vector};

/// The `reference` kind: the three built-in formulations, and declared
/// entries `numbers = "float316" | "f64" | "f32"` with `variants = [...]`
/// of the reference applied.
pub struct ReferenceKind;

/// The fault that makes ref-f32 answer where ref-f64 is expected.
const F32_ORACLE: &str = "f32-oracle";

impl Kind for ReferenceKind {
    fn name(&self) -> &'static str {
        "reference"
    }

    fn builtins(&self) -> Vec<Entry> {
        let oracle = Roles {
            oracle: true,
            tracer: false,
        };
        let tracer = Roles {
            oracle: false,
            tracer: true,
        };
        let mut f64_variants = variants_of(RefImpl::F64);
        f64_variants.push(VariantInfo {
            name: F32_ORACLE.into(),
            role: VariantRole::Fault,
        });
        vec![
            entry(RefImpl::F64, Vec::new())
                .about("the float formulation in f64 (the oracle of the error figures)")
                .roles(oracle)
                .variants(f64_variants),
            entry(RefImpl::F32, Vec::new()).about("the float formulation in f32"),
            entry(RefImpl::F316, Vec::new())
                .about("Float316 in Rust, bit-exact with the Jack program; traces natively")
                .roles(tracer),
        ]
    }

    fn declare(&self, _name: &str, fields: &mut Fields<'_>) -> Result<Entry, FieldError> {
        let formulation = match fields.required_string("numbers")? {
            "float316" => RefImpl::F316,
            "f64" => RefImpl::F64,
            "f32" => RefImpl::F32,
            other => {
                return Err(fields.error(
                    "numbers",
                    format!("the reference computes with float316, f64 or f32, not `{other}`"),
                ))
            }
        };
        let accepted = variants_of(formulation);
        let mut base = Vec::new();
        for v in fields.strings("variants")? {
            let variant: Variant = v
                .parse()
                .map_err(|e: reference::UnknownVariant| fields.error("variants", e.to_string()))?;
            if !accepted.iter().any(|a| a.name == v) {
                return Err(fields.error(
                    "variants",
                    format!("`{v}` does not apply to the {formulation} formulation"),
                ));
            }
            base.push(variant);
        }
        let about = match base.as_slice() {
            [] => format!("the reference's {formulation}"),
            _ => format!(
                "the reference's {formulation} with {}",
                base.iter().map(|v| v.name()).collect::<Vec<_>>().join(", ")
            ),
        };
        Ok(entry(formulation, base).about(about).variants(accepted))
    }
}

/// The variants of the reference that change `formulation`'s answers: the
/// Float316 arithmetic's apply to ref-f316 only, `fma` (multiply-adds
/// contracted) to the float formulations, the dithering fault to all.
fn variants_of(formulation: RefImpl) -> Vec<VariantInfo> {
    Variant::ALL
        .into_iter()
        .filter(|v| v.applies_to(formulation))
        .map(|v| VariantInfo {
            name: v.name().into(),
            role: match v.kind() {
                VariantKind::Precision => VariantRole::Precision,
                VariantKind::Fault => VariantRole::Fault,
            },
        })
        .collect()
}

/// The entry of `formulation` with `base` variants always applied.
fn entry(formulation: RefImpl, base: Vec<Variant>) -> Entry {
    let numbers = match formulation {
        RefImpl::F316 => Numbers::Float316,
        RefImpl::F64 => Numbers::F64,
        RefImpl::F32 => Numbers::F32,
    };
    let e = Entry::new(
        formulation.name(),
        "reference",
        numbers,
        RefOpener { formulation, base },
    )
    .variants(variants_of(formulation));
    if formulation == RefImpl::F316 {
        e.traces()
    } else {
        e
    }
}

/// Opens one formulation with its base variants and the label's.
struct RefOpener {
    formulation: RefImpl,
    base: Vec<Variant>,
}

impl Opener for RefOpener {
    fn open(&self, request: &Request<'_>) -> Result<Box<dyn Implementation>, ImplError> {
        let mut settings = self
            .base
            .iter()
            .fold(Settings::default(), |s, v| v.apply(s));
        let mut posing_as_f64 = false;
        for v in &request.label.variants {
            if v == F32_ORACLE {
                posing_as_f64 = true;
            } else {
                let variant: Variant = v
                    .parse()
                    .map_err(|e: reference::UnknownVariant| ImplError::Failed(e.to_string()))?;
                settings = variant.apply(settings);
            }
        }
        let formulation = if posing_as_f64 {
            RefImpl::F32
        } else {
            self.formulation
        };
        let scene = request.scene.cloned().unwrap_or_default();
        let reference = Reference::new(formulation, &scene, settings)
            .map_err(|e| ImplError::Failed(format!("the scene: {e}")))?;
        Ok(Box::new(RefAdapter {
            label: request.label.to_string(),
            reference,
            settings,
            posing_as_f64,
        }))
    }
}

/// One reference implementation, possibly with variants or faults.
pub struct RefAdapter {
    label: String,
    reference: Reference,
    settings: Settings,
    /// Answers are widened to f64 and presented as `ref-f64`'s (the
    /// "f32 oracle" fault).
    posing_as_f64: bool,
}

impl RefAdapter {
    fn num(&self, s: Scalar) -> Num {
        match (s.triple, self.reference.implementation()) {
            (Some(t), _) => Num::F316(t),
            (None, RefImpl::F32) if !self.posing_as_f64 => Num::F32(s.value as f32),
            _ => Num::F64(s.value),
        }
    }

    fn op(&self, v: &OpVector) -> Outcome<Answer> {
        let args = v.args();
        match self.reference.implementation() {
            RefImpl::F316 => match reference::op(v.op, &args, self.settings.arith) {
                Ok(outcome) => outcome.map(|r| match r {
                    OpValue::Bool(value) => Answer::Bool { value },
                    OpValue::Num(t) => Answer::Num {
                        value: Num::F316(t),
                    },
                }),
                // The set validation guarantees the arity.
                Err(e) => unreachable!("a validated vector has the right arity: {e}"),
            },
            RefImpl::F64 => float_op(v.op, &args, |x| x, |x| self.wrap(x)),
            RefImpl::F32 => float_op(v.op, &args, |x| f64::from(x as f32), |x| self.wrap_f32(x)),
        }
    }

    fn wrap(&self, x: f64) -> Num {
        Num::F64(x)
    }

    fn wrap_f32(&self, x: f64) -> Num {
        if self.posing_as_f64 {
            Num::F64(f64::from(x as f32))
        } else {
            Num::F32(x as f32)
        }
    }

    fn sdf(&self, p: [F316; 3]) -> Outcome<Answer> {
        self.reference
            .sdf(p)
            .map(|SdfValue { sd, col }| Answer::Sdf {
                sd: self.num(sd),
                col: self.num(col),
            })
    }

    fn pixel(&self, x: u16, y: u16) -> Outcome<Answer> {
        self.answer(self.reference.pixel(usize::from(x), usize::from(y)))
    }

    fn answer(&self, pixel: Outcome<PixelValue>) -> Outcome<Answer> {
        pixel.map(|PixelValue { value, white }| Answer::Pixel {
            shade: self.num(value),
            white,
        })
    }

    fn image(&self) -> Outcome<Answer> {
        let image = self.reference.render();
        let white = (0..image.height)
            .flat_map(|y| (0..image.width).map(move |x| (x, y)))
            .map(|(x, y)| image.is_white(x, y))
            .collect();
        Outcome::Value(Answer::Image {
            bitmap: Bitmap {
                width: image.width,
                height: image.height,
                white,
            },
        })
    }
}

/// The operation on exact operand values in a float type: `round` rounds an
/// f64 to that type, `num` wraps a result of it.
fn float_op(
    op: Op,
    args: &[F316],
    round: impl Fn(f64) -> f64,
    num: impl Fn(f64) -> Num,
) -> Outcome<Answer> {
    let a = round(args[0].to_f64());
    let b = args.get(1).map(|b| round(b.to_f64())).unwrap_or(0.0);
    let r = |x: f64| round(x);
    let value = match op {
        Op::Gt => return Outcome::Value(Answer::Bool { value: a > b }),
        Op::Add => r(a + b),
        Op::Sub => r(a - b),
        Op::Mul => r(a * b),
        Op::Div => r(a / b),
        Op::Floor => a.floor(),
        Op::Mod2 => a.rem_euclid(2.0),
        Op::Sqrt => r(a.sqrt()),
        Op::InvSqrt => r(1.0 / r(a.sqrt())),
        Op::Halve => a / 2.0,
        Op::Double => r(a * 2.0),
        Op::Quarter => a / 4.0,
    };
    if value.is_finite() {
        Outcome::Value(Answer::Num { value: num(value) })
    } else {
        Outcome::OutOfDomain
    }
}

impl Implementation for RefAdapter {
    fn label(&self) -> String {
        self.label.clone()
    }

    fn numbers(&self) -> Numbers {
        match self.reference.implementation() {
            RefImpl::F316 => Numbers::Float316,
            RefImpl::F64 => Numbers::F64,
            RefImpl::F32 if self.posing_as_f64 => Numbers::F64,
            RefImpl::F32 => Numbers::F32,
        }
    }

    fn supports(&self, _level: Level) -> bool {
        true
    }

    fn batch_size(&self, level: Level) -> usize {
        match level {
            // A pixel takes a few microseconds here: batches of the default
            // four would cost more in hand-overs to the contained worker
            // than in tracing.
            Level::Pixels => 256,
            _ => crate::implementation::default_batch_size(level),
        }
    }

    fn eval(&self, batch: &[Vector]) -> Result<Vec<Outcome<Answer>>, ImplError> {
        Ok(batch
            .iter()
            .map(|v| match v {
                Vector::Op(o) => self.op(o),
                Vector::Sdf(s) => self.sdf(s.p),
                Vector::Pixel(p) => self.pixel(p.x, p.y),
                Vector::Image(_) => self.image(),
            })
            .collect())
    }

    /// The whole image through the reference's own image loop, which
    /// counts each row's and column's Float316 counter once; pixel by pixel,
    /// every pixel would count its counters up from 0 (a fifth more time
    /// for `harness render`).
    fn render_image(&self, _progress: bool) -> Option<Result<ImageAnswers, ImplError>> {
        let image = self.reference.render();
        Some(Ok(ImageAnswers {
            pixels: image.pixels.into_iter().map(|p| self.answer(p)).collect(),
            costs: None,
        }))
    }

    fn trace(&self, input: &Vector) -> Result<Vec<TraceRecord>, ImplError> {
        let unsupported = |e: reference::RequestError| ImplError::Unsupported(e.to_string());
        match input {
            Vector::Op(o) => reference::trace_op(o.op, &o.args(), self.settings.arith)
                .map(|t| t.records)
                .map_err(unsupported),
            Vector::Sdf(s) => self
                .reference
                .trace_sdf(s.p)
                .map(|t| t.records)
                .map_err(unsupported),
            Vector::Pixel(p) => self
                .reference
                .trace_pixel(usize::from(p.x), usize::from(p.y))
                .map(|t| t.records)
                .map_err(unsupported),
            Vector::Image(_) => Err(ImplError::Unsupported("a trace of the whole image".into())),
        }
    }
}
