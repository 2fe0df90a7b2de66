//! The interpreter of the scene crate's intermediate form, generic over the
//! [`Engine`]: any scene, in any number type the reference has (and any
//! shadow type an engine wraps), with op traces from the Float316 engine's
//! recorder. Statements map one to one onto engine operations, in order.

use crate::engine::{outcome, Engine, Trap, R};
use crate::vec3::{self, V3};
use scene::ir::{Binary, Dither, FuncId, Logic, Program, Stmt, Taken, Unary, VecOp};

/// A program's constants, matrices and uniforms encoded for one engine.
#[derive(Clone, Debug)]
pub struct Prepared<N> {
    pub consts: Vec<N>,
    pub tables: Vec<Vec<N>>,
    pub uniforms: Vec<N>,
    pub zero: N,
    pub one: N,
}

/// A constant the engine cannot encode, or a set-up that trapped.
#[derive(Debug, thiserror::Error)]
pub enum PrepareError {
    #[error("{origin} = {value}: cannot be encoded in this implementation's number type")]
    Constant { origin: String, value: f64 },
    #[error("the camera set-up stopped: {0}")]
    Setup(String),
}

fn encode<E: Engine>(value: f64, origin: &str) -> Result<E::N, PrepareError> {
    E::constant(value).ok_or_else(|| PrepareError::Constant {
        origin: origin.to_string(),
        value,
    })
}

impl<N: Copy> Prepared<N> {
    /// Encode `p`'s constants for `E` and run its set-up with `engine`.
    pub fn new<E: Engine<N = N>>(p: &Program, engine: &mut E) -> Result<Self, PrepareError> {
        let consts = p
            .consts
            .iter()
            .map(|c| encode::<E>(c.value, &c.origin))
            .collect::<Result<Vec<_>, _>>()?;
        let tables = p
            .tables
            .iter()
            .map(|t| {
                t.iter()
                    .map(|&v| encode::<E>(v, "a dither matrix"))
                    .collect()
            })
            .collect::<Result<Vec<_>, _>>()?;
        let mut k = Prepared {
            consts,
            tables,
            uniforms: Vec::new(),
            zero: encode::<E>(0.0, "zero")?,
            one: encode::<E>(1.0, "one")?,
        };
        let mut m = Machine::new(p, k.zero);
        let setup = run(engine, p, &k, &mut m, p.setup, &[], 0);
        k.uniforms = outcome(setup)
            .value()
            .ok_or_else(|| PrepareError::Setup(format!("{:?}", outcome(setup).kind())))?
            .results
            .to_vec();
        Ok(k)
    }
}

/// `p` for runs that record nothing: frames spliced into their blocks
/// (they only name trace paths), decisions left out (only engines that
/// explain runs take another side), and every constant whose register
/// nothing else writes hoisted out of the statements into [`Hoisted`]
/// preloads.
pub fn untraced(p: &Program) -> (Program, Hoisted) {
    let mut q = p.clone();
    let mut hoisted = Vec::new();
    for (fi, f) in q.functions.iter_mut().enumerate() {
        let mut writes = vec![0u32; usize::from(f.scalars)];
        count_writes(&f.body, &mut writes);
        f.body = flatten(std::mem::take(&mut f.body), &writes, fi, &mut hoisted);
    }
    (q, Hoisted(hoisted))
}

/// Constants loaded once into a [`Machine`]: (function, register, index).
#[derive(Clone, Debug, Default)]
pub struct Hoisted(Vec<(usize, u16, u16)>);

fn count_writes(block: &[Stmt], writes: &mut [u32]) {
    for s in block {
        let mut one = |r: u16, width: u16| {
            for i in 0..width {
                writes[usize::from(r + i)] += 1;
            }
        };
        match s {
            Stmt::Const { dst, .. }
            | Stmt::Uniform { dst, .. }
            | Stmt::Table { dst, .. }
            | Stmt::Copy { dst, .. }
            | Stmt::Unary { dst, .. }
            | Stmt::Binary { dst, .. }
            | Stmt::Dot { dst, .. }
            | Stmt::Length { dst, .. }
            | Stmt::Select { dst, .. } => one(*dst, 1),
            Stmt::Vector { dst, .. } => one(*dst, 3),
            Stmt::Decide {
                taken: Taken::Parity(r),
                ..
            } => one(*r, 1),
            Stmt::Call { results, .. } => results.iter().for_each(|&r| one(r, 1)),
            Stmt::If {
                then, otherwise, ..
            } => {
                count_writes(then, writes);
                count_writes(otherwise, writes);
            }
            Stmt::Switch { cases, .. } => cases.iter().for_each(|c| count_writes(c, writes)),
            Stmt::Loop { body, .. } | Stmt::Frame { body, .. } | Stmt::Tuned { body, .. } => {
                count_writes(body, writes)
            }
            _ => {}
        }
    }
    // A function's parameters are written by its callers.
}

fn flatten(
    block: Vec<Stmt>,
    writes: &[u32],
    fi: usize,
    hoisted: &mut Vec<(usize, u16, u16)>,
) -> Vec<Stmt> {
    let mut out = Vec::with_capacity(block.len());
    for s in block {
        match s {
            Stmt::Frame { body, .. } => out.extend(flatten(body, writes, fi, hoisted)),
            Stmt::Decide { .. } => {}
            Stmt::Const { dst, index } if writes[usize::from(dst)] == 1 => {
                hoisted.push((fi, dst, index))
            }
            Stmt::If {
                cond,
                then,
                otherwise,
            } => out.push(Stmt::If {
                cond,
                then: flatten(then, writes, fi, hoisted),
                otherwise: flatten(otherwise, writes, fi, hoisted),
            }),
            Stmt::Switch { tag, cases } => out.push(Stmt::Switch {
                tag,
                cases: cases
                    .into_iter()
                    .map(|c| flatten(c, writes, fi, hoisted))
                    .collect(),
            }),
            Stmt::Loop { count, body, .. } => out.push(Stmt::Loop {
                count,
                name: None,
                body: flatten(body, writes, fi, hoisted),
            }),
            Stmt::Tuned { variant, body } => out.push(Stmt::Tuned {
                variant,
                body: flatten(body, writes, fi, hoisted),
            }),
            other => out.push(other),
        }
    }
    out
}

/// The registers of every function (calls never recurse, so one window per
/// function). Made once per thread and reused for every pixel.
#[derive(Clone, Debug)]
pub struct Machine<N> {
    windows: Vec<Window<N>>,
}

#[derive(Clone, Debug)]
struct Window<N> {
    s: Vec<N>,
    b: Vec<bool>,
    t: Vec<u16>,
}

impl<N: Copy> Machine<N> {
    /// Registers for the untraced form of a program, its hoisted constants
    /// loaded.
    pub fn preloaded(p: &Program, k: &Prepared<N>, hoisted: &Hoisted) -> Self {
        let mut m = Machine::new(p, k.zero);
        for &(f, r, i) in &hoisted.0 {
            m.windows[f].s[usize::from(r)] = k.consts[usize::from(i)];
        }
        m
    }

    /// Registers for every function of `p`, filled with `zero`.
    pub fn new(p: &Program, zero: N) -> Self {
        Machine {
            windows: p
                .functions
                .iter()
                .map(|f| Window {
                    s: vec![zero; usize::from(f.scalars)],
                    b: vec![false; usize::from(f.bools)],
                    t: vec![0; usize::from(f.tags)],
                })
                .collect(),
        }
    }
}

/// What a call returns: its scalar results.
#[derive(Clone, Copy, Debug)]
pub struct Results<N> {
    pub results: ResultList<N>,
}

/// A short list of scalars.
#[derive(Clone, Copy, Debug)]
pub struct ResultList<N> {
    items: [Option<N>; 9],
    len: usize,
}

impl<N: Copy> ResultList<N> {
    /// The scalars, in order.
    pub fn to_vec(self) -> Vec<N> {
        self.items[..self.len].iter().flatten().copied().collect()
    }

    /// Result `i`.
    pub fn get(&self, i: usize) -> N {
        self.items[i].expect("a result of the function")
    }
}

/// Run function `f` of `p` on `args` with the matrix index `index`.
pub fn run<E: Engine>(
    e: &mut E,
    p: &Program,
    k: &Prepared<E::N>,
    m: &mut Machine<E::N>,
    f: FuncId,
    args: &[E::N],
    index: usize,
) -> R<Results<E::N>> {
    let func = p.function(f);
    let w = &mut m.windows[usize::from(f)];
    for (&r, &a) in func.params.iter().zip(args) {
        w.s[usize::from(r)] = a;
    }
    let cx = Cx { p, k, index };
    exec(e, &cx, m, f, &func.body)?;
    let w = &m.windows[usize::from(f)];
    let mut results = ResultList {
        items: [None; 9],
        len: func.results.len(),
    };
    for (slot, &r) in results.items.iter_mut().zip(&func.results) {
        *slot = Some(w.s[usize::from(r)]);
    }
    Ok(Results { results })
}

/// The matrix index of pixel column `x`, row counter `n`.
pub fn matrix_index(dither: Dither, x: u32, n: u32) -> usize {
    let (x, n) = (x as usize, n as usize);
    match dither {
        Dither::None => 0,
        Dither::Bayer8 => (n % 8) * 8 + x % 8,
        Dither::Bayer4 => (n % 4) * 4 + x % 4,
    }
}

struct Cx<'a, N> {
    p: &'a Program,
    k: &'a Prepared<N>,
    index: usize,
}

/// How a block ended.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Flow {
    Next,
    Break,
}

fn v3<N: Copy>(s: &[N], r: u16) -> V3<N> {
    let r = usize::from(r);
    V3::new(s[r], s[r + 1], s[r + 2])
}

fn set3<N: Copy>(s: &mut [N], r: u16, v: V3<N>) {
    let r = usize::from(r);
    s[r] = v.x;
    s[r + 1] = v.y;
    s[r + 2] = v.z;
}

fn unary<E: Engine>(e: &mut E, k: &Prepared<E::N>, op: Unary, a: E::N) -> R<E::N> {
    match op {
        Unary::Sqrt => e.sqrt(a),
        Unary::Floor => e.floor(a),
        Unary::Mod2 => e.mod2(a),
        Unary::Double => e.double(a),
        Unary::Quarter => e.quarter(a),
        Unary::Neg => Ok(E::negate(a)),
        Unary::Abs => Ok(if E::sign_bit(a) { E::negate(a) } else { a }),
        Unary::Fract => {
            let f = e.floor(a)?;
            e.sub(a, f)
        }
        Unary::Clamp01 => {
            if E::sign_bit(a) {
                Ok(k.zero)
            } else if e.gt(a, k.one)? {
                Ok(k.one)
            } else {
                Ok(a)
            }
        }
    }
}

fn binary<E: Engine>(e: &mut E, op: Binary, a: E::N, b: E::N) -> R<E::N> {
    match op {
        Binary::Add => e.add(a, b),
        Binary::Sub => e.sub(a, b),
        Binary::Mul => e.mul(a, b),
        Binary::Div => e.div(a, b),
        Binary::Max => Ok(if e.gt(a, b)? { a } else { b }),
        Binary::Min => Ok(if e.gt(b, a)? { a } else { b }),
        Binary::Pow => e.pow(a, b),
    }
}

fn vector<E: Engine>(e: &mut E, op: VecOp, a: V3<E::N>, b: &[E::N], rb: u16) -> R<V3<E::N>> {
    match op {
        VecOp::Add => vec3::add(e, a, v3(b, rb)),
        VecOp::Sub => vec3::sub(e, a, v3(b, rb)),
        VecOp::Scale => vec3::scale(e, a, b[usize::from(rb)]),
        VecOp::Cross => vec3::cross(e, a, v3(b, rb)),
        VecOp::Normalize => vec3::normalize(e, a),
    }
}

fn exec<E: Engine>(
    e: &mut E,
    cx: &Cx<'_, E::N>,
    m: &mut Machine<E::N>,
    f: FuncId,
    block: &[Stmt],
) -> R<Flow> {
    let fi = usize::from(f);
    for s in block {
        let w = &mut m.windows[fi];
        match s {
            Stmt::Const { dst, index } => w.s[usize::from(*dst)] = cx.k.consts[usize::from(*index)],
            Stmt::Uniform { dst, index } => {
                w.s[usize::from(*dst)] = cx.k.uniforms[usize::from(*index)]
            }
            Stmt::Table { dst, table } => {
                w.s[usize::from(*dst)] = cx.k.tables[usize::from(*table)][cx.index]
            }
            Stmt::Copy { dst, src } => w.s[usize::from(*dst)] = w.s[usize::from(*src)],
            Stmt::Unary { dst, op, a } => {
                w.s[usize::from(*dst)] = unary(e, cx.k, *op, w.s[usize::from(*a)])?
            }
            Stmt::Binary { dst, op, a, b } => {
                w.s[usize::from(*dst)] = binary(e, *op, w.s[usize::from(*a)], w.s[usize::from(*b)])?
            }
            Stmt::Vector { dst, op, a, b } => {
                let r = vector(e, *op, v3(&w.s, *a), &w.s, *b)?;
                set3(&mut w.s, *dst, r);
            }
            Stmt::Dot { dst, a, b } => {
                w.s[usize::from(*dst)] = vec3::dot(e, v3(&w.s, *a), v3(&w.s, *b))?
            }
            Stmt::Length { dst, a } => w.s[usize::from(*dst)] = vec3::length(e, v3(&w.s, *a))?,
            Stmt::Gt { dst, a, b } => {
                w.b[usize::from(*dst)] = e.gt(w.s[usize::from(*a)], w.s[usize::from(*b)])?
            }
            Stmt::SignBit { dst, a } => w.b[usize::from(*dst)] = E::sign_bit(w.s[usize::from(*a)]),
            Stmt::Bool { dst, value } => w.b[usize::from(*dst)] = *value,
            Stmt::Logic { dst, op, a, b } => {
                let (a, b) = (w.b[usize::from(*a)], w.b[usize::from(*b)]);
                w.b[usize::from(*dst)] = match op {
                    Logic::And => a & b,
                    Logic::Or => a | b,
                    Logic::Not => !a,
                }
            }
            Stmt::Select { dst, cond, a, b } => {
                let pick = if w.b[usize::from(*cond)] { *a } else { *b };
                w.s[usize::from(*dst)] = w.s[usize::from(pick)];
            }
            Stmt::SetTag { dst, value } => w.t[usize::from(*dst)] = *value,
            Stmt::TagIs { dst, tag, value } => {
                w.b[usize::from(*dst)] = w.t[usize::from(*tag)] == *value
            }
            Stmt::SelectTag { dst, cond, a, b } => {
                let pick = if w.b[usize::from(*cond)] { *a } else { *b };
                w.t[usize::from(*dst)] = w.t[usize::from(pick)];
            }
            Stmt::If {
                cond,
                then,
                otherwise,
            } => {
                let branch = if w.b[usize::from(*cond)] {
                    then
                } else {
                    otherwise
                };
                if exec(e, cx, m, f, branch)? == Flow::Break {
                    return Ok(Flow::Break);
                }
            }
            Stmt::Switch { tag, cases } => {
                let case = cases
                    .get(usize::from(w.t[usize::from(*tag)]))
                    .ok_or(Trap::OutOfDomain)?;
                if exec(e, cx, m, f, case)? == Flow::Break {
                    return Ok(Flow::Break);
                }
            }
            Stmt::Loop { count, name, body } => {
                for i in 0..*count {
                    let flow = match name {
                        Some(n) => e.frame(|| format!("{n} {i}"), |e| exec(e, cx, m, f, body))?,
                        None => exec(e, cx, m, f, body)?,
                    };
                    if flow == Flow::Break {
                        break;
                    }
                }
            }
            Stmt::Break { cond } => {
                if w.b[usize::from(*cond)] {
                    return Ok(Flow::Break);
                }
            }
            Stmt::Frame { name, body } => {
                if e.frame(|| name.clone(), |e| exec(e, cx, m, f, body))? == Flow::Break {
                    return Ok(Flow::Break);
                }
            }
            Stmt::Tuned { variant, body } => {
                let before = e.set_tuning(Some(*variant));
                let flow = exec(e, cx, m, f, body);
                e.set_tuning(before);
                if flow? == Flow::Break {
                    return Ok(Flow::Break);
                }
            }
            Stmt::Decide {
                decision,
                taken,
                a,
                b,
            } => {
                let operands = [w.s[usize::from(*a)], w.s[usize::from(*b)]];
                let decision = *decision;
                match *taken {
                    Taken::Bool(c) => {
                        let c = usize::from(c);
                        w.b[c] = e.decide(decision, operands, w.b[c]);
                    }
                    Taken::Parity(r) => {
                        let r = usize::from(r);
                        let odd = E::to_f64(w.s[r]) != 0.0;
                        let now = e.decide(decision, operands, odd);
                        if now != odd {
                            w.s[r] = if now { cx.k.one } else { cx.k.zero };
                        }
                    }
                }
            }
            Stmt::Call {
                func,
                args,
                results,
                tags,
            } => {
                let mut buf = [cx.k.zero; 8];
                for (slot, &a) in buf.iter_mut().zip(args) {
                    *slot = w.s[usize::from(a)];
                }
                let callee = cx.p.function(*func);
                let g = usize::from(*func);
                for (&r, &a) in callee.params.iter().zip(&buf) {
                    m.windows[g].s[usize::from(r)] = a;
                }
                exec(e, cx, m, *func, &callee.body)?;
                for (i, &r) in callee.results.iter().enumerate() {
                    buf[i] = m.windows[g].s[usize::from(r)];
                }
                let mut tag_buf = [0u16; 2];
                for (slot, &t) in tag_buf.iter_mut().zip(&callee.tag_results) {
                    *slot = m.windows[g].t[usize::from(t)];
                }
                let w = &mut m.windows[fi];
                for (&r, &v) in results.iter().zip(&buf) {
                    w.s[usize::from(r)] = v;
                }
                for (&t, &v) in tags.iter().zip(&tag_buf) {
                    w.t[usize::from(t)] = v;
                }
            }
        }
    }
    Ok(Flow::Next)
}
