//! The intermediate form every back end reads: a small structured program
//! over one number type. A scene lowers to one [`Program`] per number
//! formulation ([`Formulation::Float316`] for ref-f316 and gpu-f316,
//! [`Formulation::Ieee`] for ref-f64, ref-f32 and gpu-f32). Back ends
//! (the reference's interpreter, the WGSL generator) map each statement to
//! their target one for one; none of them knows scenes.
//!
//! Registers are per function: scalar numbers, booleans and small integer
//! tags (which instance a surface belongs to). A vector is three
//! consecutive scalar registers. Calls never recurse ([`Program::validate`]
//! checks it), so each function's registers can live in one fixed window.

use serde::Serialize;

/// A scalar register of the enclosing function.
pub type Reg = u16;
/// A boolean register.
pub type BReg = u16;
/// A tag register.
pub type TReg = u16;
/// A function of the program.
pub type FuncId = u16;

/// Which formulation of the arithmetic the program is written in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub enum Formulation {
    /// Float316 as the Jack program computes: normalize by invSqrt, factor
    /// products truncated once, powers by repeated multiplication.
    Float316,
    /// IEEE floats: normalize divides by the length, factors multiply at
    /// run time, powers by `pow`.
    Ieee,
}

/// Operations on one scalar.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub enum Unary {
    Sqrt,
    Floor,
    /// `a mod 2` of an integral value: 0 or 1, also for negative `a`.
    Mod2,
    Double,
    Quarter,
    /// Sign flipped (not an arithmetic operation).
    Neg,
    /// Sign cleared when set (not an arithmetic operation).
    Abs,
    /// `a - floor(a)`.
    Fract,
    /// The angle clamp: 0 when the sign bit is set, 1 when above 1.
    Clamp01,
}

/// Operations on two scalars.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub enum Binary {
    Add,
    Sub,
    Mul,
    Div,
    /// `a` when `a > b`, else `b`.
    Max,
    /// `a` when `b > a`, else `b`.
    Min,
    /// `a` to the power `b` (IEEE programs only).
    Pow,
}

/// Operations on 3-vectors (three consecutive registers).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub enum VecOp {
    /// Component-wise `a + b`.
    Add,
    /// Component-wise `a - b`.
    Sub,
    /// Each component of `a` times the scalar `b`.
    Scale,
    Cross,
    /// As the formulation defines it (see [`Formulation`]); `b` unused.
    Normalize,
}

/// A variant of an operation chosen for one call site (a [`Stmt::Tuned`]
/// statement); the spec's arithmetic elsewhere.
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, serde::Deserialize,
)]
pub enum Tuning {
    /// One Newton step in `sqrt` and `invSqrt` (the spec takes two): for
    /// `sqrt`, `length` and `normalize`.
    #[serde(rename = "newton-1")]
    Newton1,
    /// `mul` with the product of the mantissas' high halves only (the spec
    /// adds the two mixed products, divided by 128): for `mul`.
    #[serde(rename = "truncated-product")]
    TruncatedProduct,
    /// `floor` with a negative non-integer's step down done on the
    /// mantissa, where the spec calls `add(r, -1.0)`: the spec's value at
    /// every input, without the nested `add`. For `floor`.
    #[serde(rename = "floor-direct")]
    FloorDirect,
}

impl Tuning {
    /// Every variant a site can take.
    pub const ALL: [Tuning; 3] = [
        Tuning::Newton1,
        Tuning::TruncatedProduct,
        Tuning::FloorDirect,
    ];

    /// Its name in a description (`newton-1`).
    pub const fn name(self) -> &'static str {
        match self {
            Tuning::Newton1 => "newton-1",
            Tuning::TruncatedProduct => "truncated-product",
            Tuning::FloorDirect => "floor-direct",
        }
    }

    /// What the back ends append to the name of the subroutine that
    /// computes the variant (`sqrtNewton1`, `mulTruncated`, `floorDirect`;
    /// lower case in WGSL: `sqrt316_newton1`).
    pub const fn suffix(self) -> &'static str {
        match self {
            Tuning::Newton1 => "Newton1",
            Tuning::TruncatedProduct => "Truncated",
            Tuning::FloorDirect => "Direct",
        }
    }

    /// Whether this variant changes how the Float316 operation `op` is
    /// computed (`newton-1`: `sqrt` and `invSqrt`).
    pub fn changes(self, op: common::Op) -> bool {
        use common::Op;
        match self {
            Tuning::Newton1 => matches!(op, Op::Sqrt | Op::InvSqrt),
            Tuning::TruncatedProduct => op == Op::Mul,
            Tuning::FloorDirect => op == Op::Floor,
        }
    }

    /// Newton steps in `sqrt` and `invSqrt` under this variant, if it
    /// changes them.
    pub const fn newton_steps(self) -> Option<u8> {
        match self {
            Tuning::Newton1 => Some(1),
            Tuning::TruncatedProduct | Tuning::FloorDirect => None,
        }
    }
}

impl std::fmt::Display for Tuning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// A statement.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum Stmt {
    /// `dst = consts[index]`.
    Const {
        dst: Reg,
        index: u16,
    },
    /// `dst = ` the setup function's result `index`.
    Uniform {
        dst: Reg,
        index: u16,
    },
    /// `dst = tables[table]` at the pixel's matrix index (see [`Dither`]).
    Table {
        dst: Reg,
        table: u16,
    },
    Copy {
        dst: Reg,
        src: Reg,
    },
    Unary {
        dst: Reg,
        op: Unary,
        a: Reg,
    },
    Binary {
        dst: Reg,
        op: Binary,
        a: Reg,
        b: Reg,
    },
    /// A vector result at `dst..dst+3`.
    Vector {
        dst: Reg,
        op: VecOp,
        a: Reg,
        b: Reg,
    },
    /// `add(add(mul(ax,bx), mul(ay,by)), mul(az,bz))`.
    Dot {
        dst: Reg,
        a: Reg,
        b: Reg,
    },
    /// `sqrt(dot(a, a))`.
    Length {
        dst: Reg,
        a: Reg,
    },
    /// `dst = a > b`.
    Gt {
        dst: BReg,
        a: Reg,
        b: Reg,
    },
    /// `dst = ` the sign bit of `a` (set for negative values and -0).
    SignBit {
        dst: BReg,
        a: Reg,
    },
    /// `dst = value`.
    Bool {
        dst: BReg,
        value: bool,
    },
    /// Boolean logic; `Not` ignores `b`.
    Logic {
        dst: BReg,
        op: Logic,
        a: BReg,
        b: BReg,
    },
    /// `dst = cond ? a : b`.
    Select {
        dst: Reg,
        cond: BReg,
        a: Reg,
        b: Reg,
    },
    SetTag {
        dst: TReg,
        value: u16,
    },
    /// `dst = tag == value`.
    TagIs {
        dst: BReg,
        tag: TReg,
        value: u16,
    },
    SelectTag {
        dst: TReg,
        cond: BReg,
        a: TReg,
        b: TReg,
    },
    If {
        cond: BReg,
        then: Vec<Stmt>,
        otherwise: Vec<Stmt>,
    },
    /// Run `cases[tag]`.
    Switch {
        tag: TReg,
        cases: Vec<Vec<Stmt>>,
    },
    /// Run `body` at most `count` times; a `Break` leaves it. A traced run
    /// names each iteration `"{name} {i}"` when `name` is given.
    Loop {
        count: u32,
        name: Option<String>,
        body: Vec<Stmt>,
    },
    /// Leave the innermost loop when `cond` holds.
    Break {
        cond: BReg,
    },
    /// Call `func`: copy `args` into its parameters, run it, copy its
    /// results into `results` and its tag results into `tags`.
    Call {
        func: FuncId,
        args: Vec<Reg>,
        results: Vec<Reg>,
        tags: Vec<TReg>,
    },
    /// A named frame of a trace's call path (no effect on values).
    Frame {
        name: String,
        body: Vec<Stmt>,
    },
    /// Run `body` (one `sqrt`, `length`, `normalize`, `mul` or `floor`
    /// statement, see [`crate::sites`]) with the operation variant
    /// `variant`.
    Tuned {
        variant: Tuning,
        body: Vec<Stmt>,
    },
    /// The pipeline takes the branch `decision` here, as `taken` holds it,
    /// on the operands `a`, `b` (for `gt(a, b)`: `a`, `b`). An engine that
    /// explains runs records it and may take the other side: `taken` is
    /// then rewritten. Back ends that only compute emit nothing for it.
    Decide {
        decision: Decision,
        taken: Taken,
        a: Reg,
        b: Reg,
    },
}

/// A branch decision of the pipeline, marked by [`Stmt::Decide`] and
/// reported to the reference's engines (`Engine::decide`). These are where
/// two precisions' runs of one pixel can part.
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize, serde::Deserialize,
)]
#[serde(rename_all = "kebab-case")]
pub enum Decision {
    /// `union(a, b)`: `a` kept when `gt(b.sd, a.sd)`.
    Union,
    /// The floor's checker parity: `mod2(floor(x) + floor(z))` is 1.
    Checker,
    /// A march step hits: `gt(precision, sd)`.
    MarchHit,
    /// A march step is past the far limit: `gt(depth, max_distance)`.
    MarchFar,
    /// The view ray misses (background): `gt(depth, max_distance)`.
    Miss,
    /// The point is in shadow: `gt(distance to light, shadow depth)`.
    Shadow,
    /// `angle`: the dot product's sign bit is set (clamped to 0).
    AngleLow,
    /// `angle`: the dot product is above 1 (clamped to 1).
    AngleHigh,
    /// The shade is above 1 (clamped to 1).
    ClampHigh,
    /// The shade's sign bit is set (clamped to 0).
    ClampLow,
    /// The dithered value is above the threshold (the pixel is white).
    Dither,
    /// A reflected ray meets a sphere and bounces (described scenes with
    /// analytic spheres): `found` on `[nearest t, 0]`.
    Bounce,
}

impl Decision {
    /// Its name in reports (`march-hit`, `shadow`, ...).
    pub const fn name(self) -> &'static str {
        match self {
            Decision::Union => "union",
            Decision::Checker => "checker",
            Decision::MarchHit => "march-hit",
            Decision::MarchFar => "march-far",
            Decision::Miss => "miss",
            Decision::Shadow => "shadow",
            Decision::AngleLow => "angle-low",
            Decision::AngleHigh => "angle-high",
            Decision::ClampHigh => "clamp-high",
            Decision::ClampLow => "clamp-low",
            Decision::Dither => "dither",
            Decision::Bounce => "bounce",
        }
    }
}

impl std::fmt::Display for Decision {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Where a [`Stmt::Decide`] finds the side taken.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub enum Taken {
    /// A boolean register.
    Bool(BReg),
    /// A parity register (0 or 1, from `mod2`): taken when it is not 0;
    /// the other side sets it to exactly 1 or 0.
    Parity(Reg),
}

/// Boolean operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub enum Logic {
    And,
    Or,
    Not,
}

/// A function.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Function {
    pub name: String,
    /// Scalar parameters, in order.
    pub params: Vec<Reg>,
    /// Scalar results, in order.
    pub results: Vec<Reg>,
    /// Tag results, in order.
    pub tag_results: Vec<TReg>,
    /// How many registers of each class the function uses.
    pub scalars: u16,
    pub bools: u16,
    pub tags: u16,
    pub body: Vec<Stmt>,
}

/// A constant with the description field it comes from (for errors when a
/// number type cannot encode it).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Constant {
    pub value: f64,
    pub origin: String,
}

/// How a pixel's matrix index is computed (for [`Stmt::Table`]); `n` is
/// the pixel's row as the camera counts it (see [`Pixels`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Dither {
    /// No matrix.
    None,
    /// `(n mod 8) * 8 + (x mod 8)`.
    Bayer8,
    /// `(n mod 4) * 4 + (x mod 4)`.
    Bayer4,
}

/// How pixel coordinates reach the pixel function.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Pixels {
    pub width: u32,
    pub height: u32,
    /// `Some(origin)`: the row counter is `n = origin - y` (the BBC demo);
    /// `None`: `n = y`.
    pub row_origin: Option<u32>,
    /// Rows whose `n` is outside this range are not drawn (level 0).
    pub rows: [u32; 2],
    pub dither: Dither,
    /// Grey levels of the output: 2 (one bit) or 4.
    pub levels: u8,
}

/// A lowered scene.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Program {
    pub formulation: Formulation,
    pub consts: Vec<Constant>,
    /// Matrices read by [`Stmt::Table`].
    pub tables: Vec<Vec<f64>>,
    pub functions: Vec<Function>,
    /// Run once per image; its results are the uniforms.
    pub setup: FuncId,
    /// `sdf(px, py, pz) -> (sd, col; tag)`.
    pub sdf: FuncId,
    /// `pixel(x, n) -> (value, level)`: the clamped shade before the output
    /// step, and the output level (0 or 1 for one bit, 0..=3 for four).
    pub pixel: FuncId,
    pub pixels: Pixels,
}

/// A program that breaks the form's rules.
#[derive(Debug, thiserror::Error, PartialEq)]
#[error("invalid program: {0}")]
pub struct InvalidProgram(pub String);

impl Program {
    /// The function `id`.
    pub fn function(&self, id: FuncId) -> &Function {
        &self.functions[usize::from(id)]
    }

    /// Check the rules back ends rely on: calls go to earlier functions
    /// only (so nothing recurses), arities match, registers are in range,
    /// `Break` is inside a loop.
    pub fn validate(&self) -> Result<(), InvalidProgram> {
        for (i, f) in self.functions.iter().enumerate() {
            check_block(self, i, f, &f.body, false)?;
        }
        for id in [self.setup, self.sdf, self.pixel] {
            if usize::from(id) >= self.functions.len() {
                return Err(InvalidProgram(format!("no function {id}")));
            }
        }
        Ok(())
    }

    /// The program with no names: frames spliced into their blocks, loops
    /// unnamed, constants without origins. Two scenes whose programs are
    /// equal this way compute the same thing.
    pub fn without_names(&self) -> Program {
        let mut p = self.clone();
        for c in &mut p.consts {
            c.origin.clear();
        }
        for f in &mut p.functions {
            f.name.clear();
            f.body = unnamed(std::mem::take(&mut f.body));
        }
        p
    }

    /// Every statement of every function, depth first.
    pub fn statements(&self) -> Vec<&Stmt> {
        let mut out = Vec::new();
        for f in &self.functions {
            walk(&f.body, &mut out);
        }
        out
    }
}

fn unnamed(block: Vec<Stmt>) -> Vec<Stmt> {
    let mut out = Vec::with_capacity(block.len());
    for s in block {
        match s {
            Stmt::Frame { body, .. } => out.extend(unnamed(body)),
            Stmt::If {
                cond,
                then,
                otherwise,
            } => out.push(Stmt::If {
                cond,
                then: unnamed(then),
                otherwise: unnamed(otherwise),
            }),
            Stmt::Switch { tag, cases } => out.push(Stmt::Switch {
                tag,
                cases: cases.into_iter().map(unnamed).collect(),
            }),
            Stmt::Loop { count, body, .. } => out.push(Stmt::Loop {
                count,
                name: None,
                body: unnamed(body),
            }),
            Stmt::Tuned { variant, body } => out.push(Stmt::Tuned {
                variant,
                body: unnamed(body),
            }),
            other => out.push(other),
        }
    }
    out
}

impl Stmt {
    /// The blocks nested in the statement: an `if`'s two, a `switch`'s
    /// cases, a loop's or a frame's body.
    pub fn blocks(&self) -> Vec<&[Stmt]> {
        match self {
            Stmt::If {
                then, otherwise, ..
            } => vec![then, otherwise],
            Stmt::Switch { cases, .. } => cases.iter().map(Vec::as_slice).collect(),
            Stmt::Loop { body, .. } | Stmt::Frame { body, .. } | Stmt::Tuned { body, .. } => {
                vec![body]
            }
            _ => Vec::new(),
        }
    }
}

fn walk<'a>(block: &'a [Stmt], out: &mut Vec<&'a Stmt>) {
    for s in block {
        out.push(s);
        s.blocks().into_iter().for_each(|b| walk(b, out));
    }
}

fn check_block(
    p: &Program,
    index: usize,
    f: &Function,
    block: &[Stmt],
    in_loop: bool,
) -> Result<(), InvalidProgram> {
    let bad = |what: String| Err(InvalidProgram(format!("{}: {what}", f.name)));
    let s_ok = |r: Reg, width: u16| r.checked_add(width).is_some_and(|end| end <= f.scalars);
    for s in block {
        let fine = match s {
            Stmt::Const { dst, index } => s_ok(*dst, 1) && usize::from(*index) < p.consts.len(),
            Stmt::Uniform { dst, .. } => s_ok(*dst, 1),
            Stmt::Table { dst, table } => s_ok(*dst, 1) && usize::from(*table) < p.tables.len(),
            Stmt::Copy { dst, src } => s_ok(*dst, 1) && s_ok(*src, 1),
            Stmt::Unary { dst, a, .. } => s_ok(*dst, 1) && s_ok(*a, 1),
            Stmt::Binary { dst, a, b, .. } => s_ok(*dst, 1) && s_ok(*a, 1) && s_ok(*b, 1),
            Stmt::Vector { dst, op, a, b } => {
                let bw = if *op == VecOp::Scale { 1 } else { 3 };
                s_ok(*dst, 3) && s_ok(*a, 3) && (*op == VecOp::Normalize || s_ok(*b, bw))
            }
            Stmt::Dot { dst, a, b } => s_ok(*dst, 1) && s_ok(*a, 3) && s_ok(*b, 3),
            Stmt::Length { dst, a } => s_ok(*dst, 1) && s_ok(*a, 3),
            Stmt::Gt { dst, a, b } => *dst < f.bools && s_ok(*a, 1) && s_ok(*b, 1),
            Stmt::SignBit { dst, a } => *dst < f.bools && s_ok(*a, 1),
            Stmt::Bool { dst, .. } => *dst < f.bools,
            Stmt::Logic { dst, a, b, .. } => *dst < f.bools && *a < f.bools && *b < f.bools,
            Stmt::Select { dst, cond, a, b } => {
                s_ok(*dst, 1) && *cond < f.bools && s_ok(*a, 1) && s_ok(*b, 1)
            }
            Stmt::SetTag { dst, .. } => *dst < f.tags,
            Stmt::TagIs { dst, tag, .. } => *dst < f.bools && *tag < f.tags,
            Stmt::SelectTag { dst, cond, a, b } => {
                *dst < f.tags && *cond < f.bools && *a < f.tags && *b < f.tags
            }
            Stmt::If {
                cond,
                then,
                otherwise,
            } => {
                check_block(p, index, f, then, in_loop)?;
                check_block(p, index, f, otherwise, in_loop)?;
                *cond < f.bools
            }
            Stmt::Switch { tag, cases } => {
                for c in cases {
                    check_block(p, index, f, c, in_loop)?;
                }
                *tag < f.tags && !cases.is_empty()
            }
            Stmt::Loop { body, .. } => {
                check_block(p, index, f, body, true)?;
                true
            }
            Stmt::Break { cond } => in_loop && *cond < f.bools,
            Stmt::Frame { body, .. } => {
                check_block(p, index, f, body, in_loop)?;
                true
            }
            Stmt::Tuned { body, .. } => {
                check_block(p, index, f, body, in_loop)?;
                body.len() == 1 && crate::sites::op_of(&body[0]).is_some()
            }
            Stmt::Decide { taken, a, b, .. } => {
                let taken_ok = match taken {
                    Taken::Bool(c) => *c < f.bools,
                    Taken::Parity(r) => s_ok(*r, 1),
                };
                taken_ok && s_ok(*a, 1) && s_ok(*b, 1)
            }
            Stmt::Call {
                func,
                args,
                results,
                tags,
            } => {
                let Some(g) = p.functions.get(usize::from(*func)) else {
                    return bad(format!("calls missing function {func}"));
                };
                if usize::from(*func) >= index {
                    return bad(format!("calls {} (not an earlier function)", g.name));
                }
                args.len() == g.params.len()
                    && results.len() == g.results.len()
                    && tags.len() == g.tag_results.len()
                    && args.iter().chain(results).all(|&r| s_ok(r, 1))
                    && tags.iter().all(|&t| t < f.tags)
            }
        };
        if !fine {
            return bad(format!("malformed statement {s:?}"));
        }
    }
    Ok(())
}
