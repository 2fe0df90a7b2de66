//! Adapter for the Rust reference: `ref-f316` (bit-exact Float316, traces
//! natively), `ref-f64` (the oracle) and `ref-f32`, optionally with one of
//! the reference's injected faults, plus the "f32 oracle" fault (ref-f32
//! posing as ref-f64).
//!
//! Ops on the float implementations are the real operation on the exact
//! values of the operands, in that float type; a non-finite result is out
//! of domain.

use crate::implementation::{Answer, Bitmap, ImplError, ImplName, Implementation, Num};
use common::{Op, OpValue, Outcome, TraceRecord, F316};
use reference::{PixelValue, RefImpl, Reference, Scalar, SdfValue, Settings, Variant};
use vectors::{Level, OpVector, Vector};

/// One reference implementation, possibly with a fault.
pub struct RefAdapter {
    name: ImplName,
    reference: Reference,
    settings: Settings,
    fault: Option<String>,
    /// Answers are widened to f64 and presented as `ref-f64`'s.
    posing_as_f64: bool,
}

impl RefAdapter {
    /// The clean implementation `name` (one of the three `ref-*`).
    pub fn new(name: ImplName) -> Result<Self, ImplError> {
        Self::build(name, Settings::default(), None, false)
    }

    /// `name` with the reference's fault or variant `variant` applied.
    pub fn with_variant(name: ImplName, variant: Variant) -> Result<Self, ImplError> {
        let settings = variant.apply(Settings::default());
        Self::build(name, settings, Some(variant.name().to_string()), false)
    }

    /// The "f32 oracle" fault: ref-f32 answering where ref-f64 is expected,
    /// its values widened to f64 so that nothing but their precision tells.
    pub fn f32_posing_as_f64() -> Result<Self, ImplError> {
        let mut adapter = Self::build(
            ImplName::RefF32,
            Settings::default(),
            Some("f32-oracle".into()),
            true,
        )?;
        adapter.name = ImplName::RefF64;
        Ok(adapter)
    }

    fn build(
        name: ImplName,
        settings: Settings,
        fault: Option<String>,
        posing_as_f64: bool,
    ) -> Result<Self, ImplError> {
        let which = match name {
            ImplName::RefF316 => RefImpl::F316,
            ImplName::RefF64 => RefImpl::F64,
            ImplName::RefF32 => RefImpl::F32,
            other => {
                return Err(ImplError::Failed(format!(
                    "{other} is not a reference implementation"
                )))
            }
        };
        let reference = Reference::new(which, &reference::Scene::default(), settings)
            .map_err(|e| ImplError::Failed(format!("the seed scene: {e}")))?;
        Ok(RefAdapter {
            name,
            reference,
            settings,
            fault,
            posing_as_f64,
        })
    }

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
        self.reference
            .pixel(usize::from(x), usize::from(y))
            .map(|PixelValue { value, white }| Answer::Pixel {
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
        match &self.fault {
            Some(f) => format!("{}+{f}", self.name),
            None => self.name.to_string(),
        }
    }

    fn name(&self) -> ImplName {
        self.name
    }

    fn supports(&self, _level: Level) -> bool {
        true
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
