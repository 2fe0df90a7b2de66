//! [`BoundProgram`]: a user's Jack program with its bindings checked,
//! brought to its ready point, its query objects made, and snapshotted;
//! every query runs on a clone of the snapshot (independent, parallel).

use super::error::BindError;
use super::layout::{Kind, ObjectLayout};
use super::ready;
use super::spec::{Bindings, PixelShade, Statements};
use super::statement::{compile, Call, Classes, Context, Ty};
use super::vm::{run_all, Regs};
use super::JackProgram;
use crate::{Budgets, Counted, JackError, Shaded};
use common::image_consts::{HEIGHT, WIDTH};
use common::{Op, OpValue, F316};
use hack_vm::{Config, Machine};

/// Where an operation's value is, once its statement has run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum OpResult {
    /// `gt`: the return value.
    Bool,
    /// `result = f(...)`: the returned object.
    Returned,
    /// `f(result, ...)`: the object passed as `result`.
    Argument,
    /// `a.halve()`: the operand object, changed in place.
    InPlace,
}

/// One bound operation.
#[derive(Clone, Debug)]
pub(crate) struct BoundOp {
    pub op: Op,
    pub call: Call,
    /// Registers of `a`, `b` (binary) and `result` in the call's context.
    pub a: usize,
    pub b: Option<usize>,
    pub result: OpResult,
}

/// The variables of an operation statement.
fn op_context(op: Op) -> Context {
    let result = if op == Op::Gt { Ty::Bool } else { Ty::Float };
    let mut vars = vec![("a", Ty::Float)];
    if op.arity() == 2 {
        vars.push(("b", Ty::Float));
    }
    vars.push(("result", result));
    Context { vars, skip: false }
}

/// Registers of the SDF context.
pub(crate) mod sdf_reg {
    pub const P: usize = 0;
    pub const X: usize = 1;
    pub const Y: usize = 2;
    pub const Z: usize = 3;
    pub const DISTANCE: usize = 4;
    pub const COLOUR: usize = 5;
    pub const HIT: usize = 6;
}

fn sdf_context() -> Context {
    Context {
        vars: vec![
            ("p", Ty::Vec3),
            ("x", Ty::Float),
            ("y", Ty::Float),
            ("z", Ty::Float),
            ("distance", Ty::Float),
            ("colour", Ty::Float),
            ("hit", Ty::Hit),
        ],
        skip: false,
    }
}

/// Registers of the pixel context (and of capture statements).
pub(crate) mod pixel_reg {
    pub const X: usize = 0;
    pub const Y: usize = 1;
    pub const U: usize = 2;
    pub const V: usize = 3;
    pub const SHADE: usize = 4;
    pub const WHITE: usize = 5;
}

pub(crate) fn pixel_context(skip: bool) -> Context {
    Context {
        vars: vec![
            ("x", Ty::Int),
            ("y", Ty::Int),
            ("u", Ty::Float),
            ("v", Ty::Float),
            ("shade", Ty::Float),
            ("white", Ty::Bool),
        ],
        skip,
    }
}

/// Statements of a query and the registers they start from.
#[derive(Clone, Debug)]
pub(crate) struct Query {
    pub calls: Vec<Call>,
    /// Object pointers made at the ready point (0 for the others).
    pub regs: Regs,
}

impl Query {
    fn uses(&self, var: usize) -> bool {
        self.calls.iter().any(|c| c.uses(var))
    }

    /// Whether `var` is passed to a call before any call assigns it: then
    /// it needs an object made in advance.
    fn needs_object(&self, var: usize) -> bool {
        for c in &self.calls {
            if c.arg_position(var).is_some() {
                return true;
            }
            if c.target == Some(var) {
                return false;
            }
        }
        false
    }
}

/// The normalised coordinates of pixel (x, y) as the reference computes
/// them: u = (x - 256) / 256 and v = -((y - 128) / 256), both exact in
/// Float316 (v's sign flipped even at zero).
pub fn normalized_coords(x: usize, y: usize) -> (F316, F316) {
    let exact = |n: f64| F316::from_f64_truncating(n).expect("pixel coordinates fit Float316");
    let u = exact((x as f64 - 256.0) / 256.0);
    let v = exact((y as f64 - 128.0) / 256.0).negated();
    (u, v)
}

/// One pixel as the pixel statements give it: the shade (clamped to
/// [0, 1] or not, as `pixel_shade` declares) and the dithered bit when a
/// statement gives `white`. A program whose clamp and dither are inline in
/// its render loop gives the shade alone; the harness then clamps and
/// dithers it exactly as the reference does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BoundPixel {
    /// The shade before dithering.
    pub shade: F316,
    /// Whether `shade` is clamped to [0, 1] already.
    pub clamped: bool,
    /// True when the dithered pixel is white; `None` when no statement
    /// gives `white`.
    pub white: Option<bool>,
}

impl From<Shaded> for BoundPixel {
    fn from(s: Shaded) -> BoundPixel {
        BoundPixel {
            shade: s.value,
            clamped: true,
            white: Some(s.white),
        }
    }
}

/// A bound Jack program, ready to answer queries.
#[derive(Clone, Debug)]
pub struct BoundProgram {
    pub(crate) snapshot: Machine,
    pub(crate) budgets: Budgets,
    pub(crate) float: ObjectLayout,
    vec3: Option<ObjectLayout>,
    hit: Option<ObjectLayout>,
    pub(crate) ops: Vec<BoundOp>,
    /// Registers of the operation statements: `a`, `b`, `result` objects.
    op_objects: [i16; 3],
    sdf: Option<Query>,
    pixel: Option<Query>,
    /// What the pixel statements' `shade` is.
    pixel_shade: PixelShade,
    pub(crate) out_of_domain: Option<i16>,
    /// The start of whole-program runs (the program's entry, its keys).
    pub(crate) whole: super::whole::WholeSetup,
}

/// Values the round-trip check makes and reads back.
const PROBES: [F316; 3] = [
    F316::new(0, 127, 8192),
    F316::new(1, 128, 10240),
    F316::new(0, 131, 16383),
];

impl BoundProgram {
    /// Check `bindings` against `program`, reach the ready point, check
    /// that objects round-trip, make the query objects and snapshot.
    /// `budgets` are the defaults; the bindings' `budget` replaces those
    /// it names.
    pub fn open(
        program: &JackProgram,
        bindings: &Bindings,
        budgets: Budgets,
    ) -> Result<BoundProgram, JackError> {
        let prog = &program.program;
        let sigs = &program.signatures;
        let classes = Classes {
            float: &bindings.float.class,
            vec3: bindings.vec3.as_ref().map(|l| l.class.as_str()),
            hit: bindings.sdf_result.as_ref().map(|l| l.class.as_str()),
        };
        let float = ObjectLayout::new("float", Kind::Float, &bindings.float, &classes, prog, sigs)?;
        let layout = |field, kind, l: &Option<super::spec::Layout>| {
            l.as_ref()
                .map(|l| ObjectLayout::new(field, kind, l, &classes, prog, sigs))
                .transpose()
        };
        let vec3 = layout("vec3", Kind::Vec3, &bindings.vec3)?;
        let hit = layout("sdf_result", Kind::Hit, &bindings.sdf_result)?;
        let ops = bindings
            .ops
            .iter()
            .map(|(name, text)| bind_op(name, text, &classes, program))
            .collect::<Result<Vec<_>, _>>()?;
        let statements = |field: &str, s: &Statements, context: &Context| {
            s.list()
                .into_iter()
                .enumerate()
                .map(|(i, text)| {
                    let f = if matches!(s, Statements::One(_)) {
                        field.to_string()
                    } else {
                        format!("{field}[{i}]")
                    };
                    compile(&f, text, context, &classes, prog, sigs)
                })
                .collect::<Result<Vec<Call>, BindError>>()
        };
        let sdf_calls = bindings
            .sdf
            .as_ref()
            .map(|s| statements("sdf", s, &sdf_context()))
            .transpose()?;
        let pixel_calls = bindings
            .pixel
            .as_ref()
            .map(|s| statements("pixel", s, &pixel_context(false)))
            .transpose()?;
        if bindings.pixel.is_none() && bindings.pixel_shade != PixelShade::Clamped {
            return Err(BindError::new(
                "pixel_shade",
                "says what the `pixel` statements' shade is, but `pixel` is not bound",
            )
            .into());
        }
        let whole = super::whole::WholeSetup::new(program, bindings, &classes)?;

        let mut m = ready::reach(program, &bindings.ready, &classes)?;
        round_trip(&mut m, &float, vec3.as_ref(), hit.as_ref())?;
        let zero = F316::ZERO;
        let op_objects = [
            float.make_float(&mut m, zero)?,
            float.make_float(&mut m, zero)?,
            float.make_float(&mut m, zero)?,
        ];
        let sdf = sdf_calls
            .map(|calls| sdf_query(&mut m, calls, &float, vec3.as_ref(), hit.as_ref()))
            .transpose()?;
        let pixel = pixel_calls
            .map(|calls| pixel_query(&mut m, calls, &float))
            .transpose()?;
        Ok(BoundProgram {
            snapshot: m,
            budgets: bindings.budget.over(budgets),
            float,
            vec3,
            hit,
            ops,
            op_objects,
            sdf,
            pixel,
            pixel_shade: bindings.pixel_shade,
            out_of_domain: bindings.out_of_domain,
            whole,
        })
    }

    /// The budgets in use.
    pub fn budgets(&self) -> Budgets {
        self.budgets
    }

    /// Whether the program checks the modelled domain itself: its bindings
    /// name the `Sys.error` code it calls for an operand out of domain.
    pub fn checks_domain(&self) -> bool {
        self.out_of_domain.is_some()
    }

    /// Whether `op` is bound.
    pub fn has_op(&self, op: Op) -> bool {
        self.bound_op(op).is_some()
    }

    /// Whether an SDF query is bound.
    pub fn has_sdf(&self) -> bool {
        self.sdf.is_some()
    }

    /// Whether a pixel query is bound.
    pub fn has_pixel(&self) -> bool {
        self.pixel.is_some()
    }

    /// Whether the pixel statements give the dithered bit (`white`), not
    /// the shade alone.
    pub fn pixel_gives_white(&self) -> bool {
        self.pixel
            .as_ref()
            .is_some_and(|q| q.uses(pixel_reg::WHITE))
    }

    pub(crate) fn bound_op(&self, op: Op) -> Option<&BoundOp> {
        self.ops.iter().find(|b| b.op == op)
    }

    /// A machine at the snapshot.
    pub(crate) fn machine(&self) -> Machine {
        self.snapshot.clone()
    }

    /// The machine configuration queries run under.
    pub fn config(&self) -> Config {
        self.whole.config.clone()
    }

    /// Prepare `m` for `op` on `args`: the bound operation and registers.
    pub(crate) fn prepare_op(
        &self,
        m: &mut Machine,
        op: Op,
        args: &[F316],
    ) -> Result<(&BoundOp, Regs), JackError> {
        let bound = self
            .bound_op(op)
            .ok_or_else(|| JackError::Unsupported(format!("`ops.{op}` is not bound")))?;
        if args.len() != op.arity() {
            return Err(JackError::BadArgument(format!(
                "{op} takes {} operand(s), got {}",
                op.arity(),
                args.len()
            )));
        }
        let ram = m.ram_mut();
        self.float.write_float(ram, self.op_objects[0], args[0]);
        let mut regs = vec![self.op_objects[0]];
        if let Some(&b) = args.get(1) {
            self.float.write_float(ram, self.op_objects[1], b);
            regs.push(self.op_objects[1]);
        }
        regs.push(self.op_objects[2]);
        Ok((bound, regs))
    }

    /// The value of `bound` after its statement ran with `regs`.
    pub(crate) fn op_value(&self, m: &Machine, bound: &BoundOp, regs: &[i16], ret: i16) -> OpValue {
        let ram = m.ram();
        match bound.result {
            OpResult::Bool => OpValue::Bool(ret != 0),
            OpResult::Returned => OpValue::Num(self.float.read_float(ram, ret)),
            OpResult::Argument => OpValue::Num(self.float.read_float(ram, regs[regs.len() - 1])),
            OpResult::InPlace => OpValue::Num(self.float.read_float(ram, regs[bound.a])),
        }
    }

    /// One Float316 operation on `args` through its bound statement.
    pub fn op(&self, op: Op, args: &[F316]) -> Result<Counted<OpValue>, JackError> {
        let mut m = self.machine();
        let (bound, mut regs) = self.prepare_op(&mut m, op, args)?;
        let (outcome, instructions) = run_all(
            &mut m,
            std::slice::from_ref(&bound.call),
            &mut regs,
            self.budgets.op,
            self.out_of_domain,
        )?;
        Ok(Counted {
            outcome: outcome.map(|ret| self.op_value(&m, bound, &regs, ret)),
            instructions,
        })
    }

    fn sdf_query(&self) -> Result<&Query, JackError> {
        self.sdf
            .as_ref()
            .ok_or_else(|| JackError::Unsupported("`sdf` is not bound".into()))
    }

    /// Write point `p` into `m`'s SDF input objects; the registers.
    pub(crate) fn prepare_sdf(
        &self,
        m: &mut Machine,
        p: [F316; 3],
    ) -> Result<(&Query, Regs), JackError> {
        let q = self.sdf_query()?;
        let regs = q.regs.clone();
        let ram = m.ram_mut();
        if let (Some(vec3), true) = (&self.vec3, q.uses(sdf_reg::P)) {
            for (i, &v) in p.iter().enumerate() {
                let part = vec3.get(ram, regs[sdf_reg::P], i);
                self.float.write_float(ram, part, v);
            }
        }
        for (reg, &v) in [sdf_reg::X, sdf_reg::Y, sdf_reg::Z].into_iter().zip(&p) {
            if q.uses(reg) {
                self.float.write_float(ram, regs[reg], v);
            }
        }
        Ok((q, regs))
    }

    /// The distance and colour the SDF statements left in `regs`.
    pub(crate) fn sdf_value(&self, m: &Machine, q: &Query, regs: &[i16]) -> (F316, F316) {
        let ram = m.ram();
        if q.uses(sdf_reg::DISTANCE) {
            (
                self.float.read_float(ram, regs[sdf_reg::DISTANCE]),
                self.float.read_float(ram, regs[sdf_reg::COLOUR]),
            )
        } else {
            let hit = self.hit.as_ref().expect("checked when bound");
            let parts = hit.read_compound(ram, &self.float, regs[sdf_reg::HIT]);
            (parts[0], parts[1])
        }
    }

    /// The scene at point `p`: (signed distance, colour).
    pub fn sdf(&self, p: [F316; 3]) -> Result<Counted<(F316, F316)>, JackError> {
        let mut m = self.machine();
        let (q, mut regs) = self.prepare_sdf(&mut m, p)?;
        let (outcome, instructions) = run_all(
            &mut m,
            &q.calls,
            &mut regs,
            self.budgets.sdf,
            self.out_of_domain,
        )?;
        Ok(Counted {
            outcome: outcome.map(|_| self.sdf_value(&m, q, &regs)),
            instructions,
        })
    }

    /// Write pixel (x, y)'s inputs into `m`; the statements and registers.
    pub(crate) fn prepare_pixel(
        &self,
        m: &mut Machine,
        x: usize,
        y: usize,
    ) -> Result<(&Query, Regs), JackError> {
        let q = self
            .pixel
            .as_ref()
            .ok_or_else(|| JackError::Unsupported("`pixel` is not bound".into()))?;
        if x >= WIDTH || y >= HEIGHT {
            return Err(JackError::BadArgument(format!(
                "pixel ({x},{y}) is outside the {WIDTH}x{HEIGHT} image"
            )));
        }
        let mut regs = q.regs.clone();
        regs[pixel_reg::X] = x as i16;
        regs[pixel_reg::Y] = y as i16;
        let (u, v) = normalized_coords(x, y);
        let ram = m.ram_mut();
        if q.uses(pixel_reg::U) {
            self.float.write_float(ram, regs[pixel_reg::U], u);
        }
        if q.uses(pixel_reg::V) {
            self.float.write_float(ram, regs[pixel_reg::V], v);
        }
        Ok((q, regs))
    }

    /// Pixel (x, y): its shade and, when the statements give it, its
    /// dithered bit.
    pub fn pixel(&self, x: usize, y: usize) -> Result<Counted<BoundPixel>, JackError> {
        let mut m = self.machine();
        let (q, mut regs) = self.prepare_pixel(&mut m, x, y)?;
        let (outcome, instructions) = run_all(
            &mut m,
            &q.calls,
            &mut regs,
            self.budgets.pixel,
            self.out_of_domain,
        )?;
        Ok(Counted {
            outcome: outcome.map(|_| BoundPixel {
                shade: self.float.read_float(m.ram(), regs[pixel_reg::SHADE]),
                clamped: self.pixel_shade == PixelShade::Clamped,
                white: q
                    .uses(pixel_reg::WHITE)
                    .then(|| regs[pixel_reg::WHITE] != 0),
            }),
            instructions,
        })
    }

    /// The rows `rows` of the image through the pixel statements, pixels in
    /// parallel, calling `done` as each finishes.
    pub fn render_rows_observed(
        &self,
        rows: std::ops::Range<usize>,
        done: &(dyn Fn() + Sync),
    ) -> Result<Vec<Counted<BoundPixel>>, JackError> {
        use rayon::prelude::*;
        let coords: Vec<(usize, usize)> =
            rows.flat_map(|y| (0..WIDTH).map(move |x| (x, y))).collect();
        coords
            .par_iter()
            .map(|&(x, y)| {
                let p = self.pixel(x, y)?;
                done();
                Ok(p)
            })
            .collect()
    }

    /// The whole image through the pixel statements, row by row.
    pub fn render(&self) -> Result<Vec<Counted<BoundPixel>>, JackError> {
        self.render_rows_observed(0..HEIGHT, &|| {})
    }
}

/// Check and resolve `ops.NAME`.
fn bind_op(
    name: &str,
    text: &str,
    classes: &Classes,
    program: &JackProgram,
) -> Result<BoundOp, BindError> {
    let field = format!("ops.{name}");
    // The exact names only (the vector files' parser also takes `invsqrt`
    // and other spellings, which the bindings do not document).
    let op = Op::ALL
        .into_iter()
        .find(|op| op.name() == name)
        .ok_or_else(|| {
            BindError::new(&field, common::op::UnknownOp(name.to_string()).to_string())
        })?;
    let context = op_context(op);
    let call = compile(
        &field,
        text,
        &context,
        classes,
        &program.program,
        &program.signatures,
    )?;
    let a = context.var("a").expect("every op has a");
    let b = context.var("b");
    let r = context.var("result").expect("every op has a result");
    for (var, name) in [(Some(a), "a"), (b, "b")] {
        if let Some(v) = var {
            if call.arg_position(v).is_none() {
                return Err(BindError::new(
                    &field,
                    format!("the statement does not pass the operand `{name}`"),
                ));
            }
        }
    }
    let result = if op == Op::Gt {
        if call.arg_position(r).is_some() {
            return Err(BindError::new(
                &field,
                "gt gives a boolean: its result is the return value, not an argument",
            ));
        }
        OpResult::Bool
    } else if call.target == Some(r) {
        OpResult::Returned
    } else if call.arg_position(r).is_some() {
        OpResult::Argument
    } else if call.target.is_some() {
        return Err(BindError::new(
            &field,
            "the return value can only go to `result`",
        ));
    } else {
        OpResult::InPlace
    };
    Ok(BoundOp {
        op,
        call,
        a,
        b,
        result,
    })
}

/// Make and read back the probe values through every layout.
fn round_trip(
    m: &mut Machine,
    float: &ObjectLayout,
    vec3: Option<&ObjectLayout>,
    hit: Option<&ObjectLayout>,
) -> Result<(), JackError> {
    let show = |vs: &[F316]| {
        let parts: Vec<String> = vs.iter().map(|v| format!("{v:?}")).collect();
        parts.join(", ")
    };
    for v in PROBES {
        let p = float.make_float(m, v)?;
        let back = float.read_float(m.ram(), p);
        if back != v {
            return Err(float.round_trip_error(show(&[v]), show(&[back])).into());
        }
    }
    for (layout, values) in [(vec3, &PROBES[..]), (hit, &PROBES[..2])] {
        if let Some(layout) = layout {
            let p = layout.make_compound(m, float, values)?;
            let back = layout.read_compound(m.ram(), float, p);
            if back != values {
                return Err(layout.round_trip_error(show(values), show(&back)).into());
            }
        }
    }
    Ok(())
}

/// Check the SDF statements give a distance and a colour, and make their
/// input and output objects.
fn sdf_query(
    m: &mut Machine,
    calls: Vec<Call>,
    float: &ObjectLayout,
    vec3: Option<&ObjectLayout>,
    hit: Option<&ObjectLayout>,
) -> Result<Query, JackError> {
    use sdf_reg::*;
    let mut q = Query {
        calls,
        regs: vec![0; 7],
    };
    let direct = q.uses(DISTANCE) && q.uses(COLOUR);
    if !(direct || q.uses(HIT) && hit.is_some()) {
        return Err(BindError::new(
            "sdf",
            "no statement gives `distance` and `colour` (assign or pass both, or give `hit` \
             with an `sdf_result` layout)",
        )
        .into());
    }
    if q.uses(P) && vec3.is_none() {
        return Err(BindError::new("sdf", "`p` is used but no `vec3` layout is bound").into());
    }
    if !(q.uses(P) || q.uses(X) && q.uses(Y) && q.uses(Z)) {
        return Err(BindError::new(
            "sdf",
            "the statements pass neither the point `p` nor all of `x`, `y`, `z`",
        )
        .into());
    }
    let zero = [F316::ZERO; 3];
    if q.needs_object(P) {
        q.regs[P] = vec3.expect("checked").make_compound(m, float, &zero)?;
    }
    for reg in [X, Y, Z, DISTANCE, COLOUR] {
        if q.needs_object(reg) {
            q.regs[reg] = float.make_float(m, F316::ZERO)?;
        }
    }
    if q.needs_object(HIT) {
        let hit = hit.ok_or_else(|| {
            BindError::new("sdf", "`hit` is passed but no `sdf_result` layout is bound")
        })?;
        q.regs[HIT] = hit.make_compound(m, float, &zero[..2])?;
    }
    Ok(q)
}

/// Check the pixel statements give a shade (and, if any, a white bit that
/// is assigned), and make their objects.
fn pixel_query(
    m: &mut Machine,
    calls: Vec<Call>,
    float: &ObjectLayout,
) -> Result<Query, JackError> {
    use pixel_reg::*;
    let mut q = Query {
        calls,
        regs: vec![0; 6],
    };
    if !q.uses(SHADE) {
        return Err(BindError::new(
            "pixel",
            "no statement gives `shade` (the shade before dithering; `white` is optional)",
        )
        .into());
    }
    if q.needs_object(WHITE) {
        return Err(
            BindError::new("pixel", "`white` is a boolean: assign it, do not pass it").into(),
        );
    }
    for reg in [U, V, SHADE] {
        if q.needs_object(reg) {
            q.regs[reg] = float.make_float(m, F316::ZERO)?;
        }
    }
    Ok(q)
}
