//! Where each register of an IR function lives in Jack.
//!
//! The Hack VM has 240 static words for the whole program, and the lowered
//! functions have hundreds of registers, so registers share storage: each
//! register gets a *slot* (a Float316 object made once, an int or a
//! boolean), and two registers share a slot when their lifetimes do not
//! overlap. A lifetime is the interval between the register's first and
//! last mention in the function's statements in written order, widened to
//! cover every loop it is mentioned in (a value may cross the back edge).
//! A statement's destination is alive where its operands are read, so it
//! never shares their slot.
//!
//! A scalar register that one statement writes, a `Const` or a `Uniform`,
//! needs no slot: it is the constant (or the uniform) object itself, made
//! once at start-up, as the reference's interpreter hoists such constants.
//! A parameter that the function never writes is the caller's argument.

use scene::ir::{Function, Stmt, Taken};

/// Where an IR scalar register lives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Place {
    /// Never mentioned.
    Unused,
    /// The constant `index` of the program (read only).
    Const(u16),
    /// The uniform `index` (a result of the set-up function; read only).
    Uniform(u16),
    /// The function's parameter `k`, passed by the caller (read only).
    Param(usize),
    /// A Float316 object of the function's own.
    Slot(usize),
}

/// The storage of one function.
#[derive(Clone, Debug)]
pub struct Plan {
    /// Indexed by scalar register.
    pub scalars: Vec<Place>,
    /// Float316 slots.
    pub scalar_slots: usize,
    /// Slot of each boolean register (`None`: unused).
    pub bools: Vec<Option<usize>>,
    pub bool_slots: usize,
    /// Slot of each tag register.
    pub tags: Vec<Option<usize>>,
    pub tag_slots: usize,
    /// Parameters the function writes: (parameter index, slot), copied in
    /// at entry.
    pub copied_params: Vec<(usize, usize)>,
}

/// The register classes of the IR.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Class {
    Scalar,
    Bool,
    Tag,
}

/// Mentions of registers in written order.
#[derive(Default)]
struct Scan {
    /// The next statement's position.
    at: usize,
    /// (class, register, position, written)
    mentions: Vec<(Class, u16, usize, bool)>,
    /// Position ranges of loops, inclusive.
    loops: Vec<(usize, usize)>,
}

impl Scan {
    fn read(&mut self, c: Class, r: u16) {
        self.mentions.push((c, r, self.at, false));
    }

    fn write(&mut self, c: Class, r: u16) {
        self.mentions.push((c, r, self.at, true));
    }

    fn read3(&mut self, r: u16) {
        (r..r + 3).for_each(|r| self.read(Class::Scalar, r));
    }

    fn block(&mut self, stmts: &[Stmt]) {
        use Class::{Bool as B, Scalar as S, Tag as T};
        for s in stmts {
            self.at += 1;
            match s {
                Stmt::Const { dst, .. } | Stmt::Uniform { dst, .. } | Stmt::Table { dst, .. } => {
                    self.write(S, *dst)
                }
                Stmt::Copy { dst, src } => {
                    self.read(S, *src);
                    self.write(S, *dst);
                }
                Stmt::Unary { dst, a, .. } => {
                    self.read(S, *a);
                    self.write(S, *dst);
                }
                Stmt::Binary { dst, a, b, .. } => {
                    self.read(S, *a);
                    self.read(S, *b);
                    self.write(S, *dst);
                }
                Stmt::Vector { dst, op, a, b } => {
                    self.read3(*a);
                    match op {
                        scene::ir::VecOp::Normalize => {}
                        scene::ir::VecOp::Scale => self.read(S, *b),
                        _ => self.read3(*b),
                    }
                    (*dst..dst + 3).for_each(|r| self.write(S, r));
                }
                Stmt::Dot { dst, a, b } => {
                    self.read3(*a);
                    self.read3(*b);
                    self.write(S, *dst);
                }
                Stmt::Length { dst, a } => {
                    self.read3(*a);
                    self.write(S, *dst);
                }
                Stmt::Gt { dst, a, b } => {
                    self.read(S, *a);
                    self.read(S, *b);
                    self.write(B, *dst);
                }
                Stmt::SignBit { dst, a } => {
                    self.read(S, *a);
                    self.write(B, *dst);
                }
                Stmt::Bool { dst, .. } => self.write(B, *dst),
                Stmt::Logic { dst, a, b, op } => {
                    self.read(B, *a);
                    if *op != scene::ir::Logic::Not {
                        self.read(B, *b);
                    }
                    self.write(B, *dst);
                }
                Stmt::Select { dst, cond, a, b } => {
                    self.read(B, *cond);
                    self.read(S, *a);
                    self.read(S, *b);
                    self.write(S, *dst);
                }
                Stmt::SetTag { dst, .. } => self.write(T, *dst),
                Stmt::TagIs { dst, tag, .. } => {
                    self.read(T, *tag);
                    self.write(B, *dst);
                }
                Stmt::SelectTag { dst, cond, a, b } => {
                    self.read(B, *cond);
                    self.read(T, *a);
                    self.read(T, *b);
                    self.write(T, *dst);
                }
                Stmt::If {
                    cond,
                    then,
                    otherwise,
                } => {
                    self.read(B, *cond);
                    self.block(then);
                    self.block(otherwise);
                }
                Stmt::Switch { tag, cases } => {
                    self.read(T, *tag);
                    cases.iter().for_each(|c| self.block(c));
                }
                Stmt::Loop { body, .. } => {
                    let start = self.at;
                    self.block(body);
                    self.loops.push((start, self.at));
                }
                Stmt::Break { cond } => self.read(B, *cond),
                Stmt::Frame { body, .. } | Stmt::Tuned { body, .. } => self.block(body),
                // Back ends that only compute emit nothing for a decision.
                Stmt::Decide { .. } => {}
                Stmt::Call {
                    args,
                    results,
                    tags,
                    ..
                } => {
                    args.iter().for_each(|&r| self.read(S, r));
                    results.iter().for_each(|&r| self.write(S, r));
                    tags.iter().for_each(|&t| self.write(T, t));
                }
            }
        }
    }
}

/// The single statement writing register `r`, when it is a `Const` or a
/// `Uniform` (counted as the interpreter counts writes).
fn read_only_sources(f: &Function) -> Vec<Option<Place>> {
    let mut writes = vec![0u32; usize::from(f.scalars)];
    let mut source = vec![None; usize::from(f.scalars)];
    fn walk(stmts: &[Stmt], writes: &mut [u32], source: &mut [Option<Place>]) {
        for s in stmts {
            let mut one = |r: u16, place: Option<Place>| {
                writes[usize::from(r)] += 1;
                source[usize::from(r)] = place;
            };
            match s {
                Stmt::Const { dst, index } => one(*dst, Some(Place::Const(*index))),
                Stmt::Uniform { dst, index } => one(*dst, Some(Place::Uniform(*index))),
                Stmt::Table { dst, .. }
                | Stmt::Copy { dst, .. }
                | Stmt::Unary { dst, .. }
                | Stmt::Binary { dst, .. }
                | Stmt::Dot { dst, .. }
                | Stmt::Length { dst, .. }
                | Stmt::Select { dst, .. } => one(*dst, None),
                Stmt::Vector { dst, .. } => (*dst..dst + 3).for_each(|r| one(r, None)),
                Stmt::Decide {
                    taken: Taken::Parity(r),
                    ..
                } => one(*r, None),
                Stmt::Call { results, .. } => results.iter().for_each(|&r| one(r, None)),
                _ => s.blocks().into_iter().for_each(|b| walk(b, writes, source)),
            }
        }
    }
    walk(&f.body, &mut writes, &mut source);
    for &p in &f.params {
        // A parameter is written by its callers as well.
        writes[usize::from(p)] += 1;
    }
    source
        .into_iter()
        .zip(writes)
        .map(|(s, w)| if w == 1 { s } else { None })
        .collect()
}

/// Give each register of class `class` among `count` a slot; returns the
/// slots and their number. `pinned` registers are left out (`None`).
fn share(scan: &Scan, class: Class, count: u16, skip: &[bool]) -> (Vec<Option<usize>>, usize) {
    let n = usize::from(count);
    let mut span: Vec<Option<(usize, usize)>> = vec![None; n];
    for &(c, r, at, _) in &scan.mentions {
        let r = usize::from(r);
        if c != class || skip.get(r).copied().unwrap_or(false) {
            continue;
        }
        span[r] = Some(match span[r] {
            None => (at, at),
            Some((a, b)) => (a.min(at), b.max(at)),
        });
    }
    // Inner loops end first and are shorter: widen by them first.
    let mut loops = scan.loops.clone();
    loops.sort_by_key(|&(a, b)| b - a);
    for &(start, end) in &loops {
        for (a, b) in span.iter_mut().flatten() {
            if *a <= end && *b >= start {
                *a = (*a).min(start);
                *b = (*b).max(end);
            }
        }
    }
    // Linear scan: registers by start; a slot is free once its last
    // register's interval has ended before the next one starts.
    let mut order: Vec<usize> = (0..n).filter(|&r| span[r].is_some()).collect();
    order.sort_by_key(|&r| span[r].map(|s| s.0));
    let mut free_at: Vec<usize> = Vec::new();
    let mut slot = vec![None; n];
    for r in order {
        let (a, b) = span[r].expect("filtered");
        let s = match free_at.iter().position(|&end| end < a) {
            Some(s) => s,
            None => {
                free_at.push(0);
                free_at.len() - 1
            }
        };
        free_at[s] = b;
        slot[r] = Some(s);
    }
    (slot, free_at.len())
}

/// The storage plan of `f`.
pub fn plan(f: &Function) -> Plan {
    let mut scan = Scan::default();
    // Parameters are written at entry, results read after the last statement.
    for &p in &f.params {
        scan.write(Class::Scalar, p);
    }
    scan.block(&f.body);
    scan.at += 1;
    for &r in &f.results {
        scan.read(Class::Scalar, r);
    }
    for &t in &f.tag_results {
        scan.read(Class::Tag, t);
    }
    let sources = read_only_sources(f);
    let written: Vec<bool> = {
        let mut w = vec![false; usize::from(f.scalars)];
        for &(c, r, at, write) in &scan.mentions {
            // The entry's own writes of the parameters are at position 0.
            if c == Class::Scalar && write && at > 0 {
                w[usize::from(r)] = true;
            }
        }
        w
    };
    let mut fixed: Vec<Option<Place>> = sources;
    for (k, &p) in f.params.iter().enumerate() {
        let p = usize::from(p);
        fixed[p] = (!written[p]).then_some(Place::Param(k));
    }
    let skip: Vec<bool> = fixed.iter().map(Option::is_some).collect();
    let (slots, scalar_slots) = share(&scan, Class::Scalar, f.scalars, &skip);
    let scalars: Vec<Place> = fixed
        .iter()
        .zip(&slots)
        .map(|(fixed, slot)| match (fixed, slot) {
            (Some(p), _) => *p,
            (None, Some(s)) => Place::Slot(*s),
            (None, None) => Place::Unused,
        })
        .collect();
    let copied_params = f
        .params
        .iter()
        .enumerate()
        .filter_map(|(k, &p)| match scalars[usize::from(p)] {
            Place::Slot(s) => Some((k, s)),
            _ => None,
        })
        .collect();
    let (bools, bool_slots) = share(&scan, Class::Bool, f.bools, &[]);
    let (tags, tag_slots) = share(&scan, Class::Tag, f.tags, &[]);
    Plan {
        scalars,
        scalar_slots,
        bools,
        bool_slots,
        tags,
        tag_slots,
        copied_params,
    }
}
