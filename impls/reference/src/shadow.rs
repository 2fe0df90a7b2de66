//! Shadow execution: a number type of the [`Engine`] that pairs a
//! low-precision value (Float316 or f32) with its f64 shadow, computed by
//! the same operations in the same control flow. Every pipeline generic
//! over the engine gets it without a line of its own.
//!
//! Each operation records its *local error* (its result against the f64
//! operation on the same low-precision operands) and its *accumulated
//! error* (its result against its shadow), with its call path; every
//! branch decision the pipeline reports ([`Engine::decide`]) is recorded
//! with both sides' operands. A *site* is an operation at a call path with
//! its step numbers and coordinates collapsed (`sub` at
//! `pixel(*,*) > march step * > scene > torus`). A run can *flip* one
//! site: each of its results is mirrored around the exact result on its
//! operands (`2 * exact - result`, encoded in the low precision), so that
//! its local error changes sign and nothing else does. Half the change of
//! an error that a flip causes is, to first order, the share of that error
//! the site's own rounding contributes; [`blame`] ranks sites by it: the
//! root causes.

use crate::consts::Consts;
use crate::engine::{Decision, Engine, Tuning, R};
use crate::formulation::{self, Formulated, Formulation};
use crate::vec3::V3;
use common::F316;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;

/// A low-precision value and its f64 shadow.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sh<N> {
    /// The value the low-precision engine computes.
    pub lo: N,
    /// The same computation in f64.
    pub hi: f64,
}

/// An operation of a site: its name and collapsed call path.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct SiteKey {
    /// The operation (`add`, `inv_sqrt`, ...).
    pub op: String,
    /// The call path with digits collapsed to `*`, frames joined by ` > `.
    pub path: String,
}

impl std::fmt::Display for SiteKey {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} in {}", self.op, self.path)
    }
}

/// One operation of a shadowed run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadowOp {
    /// The operation's name.
    pub op: &'static str,
    /// Its full call path (an index into [`ShadowRun::path`]).
    pub path: u32,
    /// Its site's collapsed path (an index into [`ShadowRun::site_path`]).
    pub site: u32,
    /// Operands: (low-precision value, shadow), `arity` of them.
    pub args: [(f64, f64); 2],
    pub arity: u8,
    /// Result: (low-precision value, shadow).
    pub result: (f64, f64),
    /// |result - the f64 operation on the low-precision operands|.
    pub local_error: f64,
}

impl ShadowOp {
    /// The operands.
    pub fn operands(&self) -> &[(f64, f64)] {
        &self.args[..usize::from(self.arity)]
    }

    /// |result - its shadow|.
    pub fn accumulated_error(&self) -> f64 {
        (self.result.0 - self.result.1).abs()
    }

    /// For `add` and `sub`: how many leading bits cancel (log2 of the
    /// larger operand's magnitude over the result's, in the low
    /// precision); 0 for other operations or when nothing cancels.
    pub fn cancelled_bits(&self) -> f64 {
        if !matches!(self.op, "add" | "sub") {
            return 0.0;
        }
        let big = self
            .operands()
            .iter()
            .map(|a| a.0.abs())
            .fold(0.0, f64::max);
        let r = self.result.0.abs();
        if r == 0.0 || big == 0.0 {
            return 0.0;
        }
        (big / r).log2().max(0.0)
    }
}

/// One branch decision of a shadowed run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DecisionRecord {
    pub decision: Decision,
    /// Its full call path (an index into [`ShadowRun::path`]).
    pub path: u32,
    /// The branch the low-precision run took.
    pub taken: bool,
    /// The decision's operands in the low precision.
    pub operands: [f64; 2],
    /// Their shadows.
    pub shadows: [f64; 2],
}

/// A named output of a run: the low-precision value and its shadow.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct OutputValue {
    pub name: &'static str,
    pub lo: f64,
    pub hi: f64,
}

/// What a shadowed run produced.
#[derive(Clone, Debug, PartialEq)]
pub struct ShadowOutput {
    /// Its numbers (`shade`; `sd`, `col`; ...).
    pub values: Vec<OutputValue>,
    /// The dithered bit, for a pixel.
    pub white: Option<bool>,
}

/// What to record and correct in a run.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ShadowOptions {
    /// Record every operation (decisions are always recorded).
    pub record_ops: bool,
    /// Flip this site's local errors (see the module documentation).
    pub flip: Option<SiteKey>,
    /// Take another run's branches (see [`Follow`]).
    pub follow: Option<Follow>,
}

/// Another run's decisions, to take its branches from position `from` on
/// (counting from 0) while this run makes the same decisions (kind and
/// full call path) at the same positions; once it does not, it goes its
/// own way.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Follow {
    pub from: usize,
    /// Kind, full call path and branch of each decision of the other run.
    pub decisions: Vec<(Decision, String, bool)>,
}

/// A frame of a full call path.
#[derive(Clone, Debug)]
struct FullNode {
    parent: u32,
    name: String,
    /// Its collapsed path (a site node).
    site: u32,
    children: Vec<u32>,
}

/// A frame of a collapsed call path.
#[derive(Clone, Debug)]
struct SiteNode {
    /// The whole path, joined.
    path: String,
    /// Its own frame's collapsed name.
    name: String,
    children: Vec<u32>,
}

/// The interned call paths of a run: full ones (for decisions and
/// operations) and collapsed ones (sites), as trees.
#[derive(Clone, Debug)]
struct Paths {
    full: Vec<FullNode>,
    sites: Vec<SiteNode>,
    /// The full node of each open frame; the root (0) is never left.
    stack: Vec<u32>,
    /// The collapsed path of the flipped site.
    target_path: Option<String>,
    /// Its site node, once entered.
    target: Option<u32>,
}

impl Paths {
    fn new(target_path: Option<String>) -> Self {
        Paths {
            full: vec![FullNode {
                parent: 0,
                name: String::new(),
                site: 0,
                children: Vec::new(),
            }],
            sites: vec![SiteNode {
                path: String::new(),
                name: String::new(),
                children: Vec::new(),
            }],
            stack: vec![0],
            target: target_path
                .as_deref()
                .and_then(|t| t.is_empty().then_some(0)),
            target_path,
        }
    }

    /// The current (full, site) nodes.
    fn current(&self) -> (u32, u32) {
        let full = *self.stack.last().expect("the root frame is never left");
        (full, self.full[full as usize].site)
    }

    fn push(&mut self, name: String) {
        let parent = self.current().0;
        let known = self.full[parent as usize]
            .children
            .iter()
            .copied()
            .find(|&c| self.full[c as usize].name == name);
        let node = match known {
            Some(c) => c,
            None => {
                let site = self.site_child(self.full[parent as usize].site, &name);
                let id = self.full.len() as u32;
                self.full.push(FullNode {
                    parent,
                    name,
                    site,
                    children: Vec::new(),
                });
                self.full[parent as usize].children.push(id);
                id
            }
        };
        self.stack.push(node);
    }

    /// The site node under `parent` for a frame called `name`.
    fn site_child(&mut self, parent: u32, name: &str) -> u32 {
        let collapsed = collapse_digits(name);
        let known = self.sites[parent as usize]
            .children
            .iter()
            .copied()
            .find(|&c| self.sites[c as usize].name == collapsed);
        if let Some(c) = known {
            return c;
        }
        let above = &self.sites[parent as usize].path;
        let path = if above.is_empty() {
            collapsed.clone()
        } else {
            format!("{above} > {collapsed}")
        };
        let id = self.sites.len() as u32;
        if self.target_path.as_deref() == Some(path.as_str()) {
            self.target = Some(id);
        }
        self.sites.push(SiteNode {
            path,
            name: collapsed,
            children: Vec::new(),
        });
        self.sites[parent as usize].children.push(id);
        id
    }

    fn pop(&mut self) {
        if self.stack.len() > 1 {
            self.stack.pop();
        }
    }

    fn full_path(&self, mut id: u32) -> String {
        let mut names = Vec::new();
        while id != 0 {
            let node = &self.full[id as usize];
            names.push(node.name.as_str());
            id = node.parent;
        }
        names.reverse();
        names.join(" > ")
    }
}

/// `name` with every run of ASCII digits replaced by `*`.
fn collapse_digits(name: &str) -> String {
    let mut out = String::with_capacity(name.len());
    let mut in_digits = false;
    for c in name.chars() {
        if c.is_ascii_digit() {
            if !in_digits {
                out.push('*');
            }
            in_digits = true;
        } else {
            out.push(c);
            in_digits = false;
        }
    }
    out
}

/// The engine over [`Sh`]: each operation runs in the low-precision
/// engine `E` and in f64, in `E`'s formulation.
pub struct ShadowEngine<E> {
    inner: E,
    options: ShadowOptions,
    paths: Paths,
    ops: Vec<ShadowOp>,
    decisions: Vec<DecisionRecord>,
    /// Whether the run still makes the followed run's decisions.
    in_step: bool,
}

/// The records of one shadowed run and what it produced.
#[derive(Clone, Debug)]
pub struct ShadowRun {
    /// The low-precision run's answer with its shadows, or its trap.
    pub outcome: common::Outcome<ShadowOutput>,
    /// Every operation, in order (when recorded).
    pub ops: Vec<ShadowOp>,
    /// Every branch decision, in order.
    pub decisions: Vec<DecisionRecord>,
    paths: Paths,
}

impl ShadowRun {
    /// The full call path of a record.
    pub fn path(&self, id: u32) -> String {
        self.paths.full_path(id)
    }

    /// The collapsed call path of a site.
    pub fn site_path(&self, id: u32) -> &str {
        &self.paths.sites[id as usize].path
    }

    /// The site of an operation record.
    pub fn site_of(&self, op: &ShadowOp) -> SiteKey {
        SiteKey {
            op: op.op.to_string(),
            path: self.site_path(op.site).to_string(),
        }
    }

    /// The output called `name`.
    pub fn output(&self, name: &str) -> Option<OutputValue> {
        let common::Outcome::Value(out) = &self.outcome else {
            return None;
        };
        out.values.iter().find(|v| v.name == name).copied()
    }
}

impl<E: Formulated> ShadowEngine<E> {
    /// A shadow of `inner` under `options`.
    pub fn new(inner: E, options: ShadowOptions) -> Self {
        let paths = Paths::new(options.flip.as_ref().map(|c| c.path.clone()));
        let ops = if options.record_ops {
            Vec::with_capacity(4096)
        } else {
            Vec::new()
        };
        ShadowEngine {
            inner,
            options,
            paths,
            ops,
            decisions: Vec::with_capacity(256),
            in_step: true,
        }
    }

    /// Finish with `outcome`, handing over the records.
    pub fn finish(self, outcome: common::Outcome<ShadowOutput>) -> ShadowRun {
        ShadowRun {
            outcome,
            ops: self.ops,
            decisions: self.decisions,
            paths: self.paths,
        }
    }

    fn flipped(&self, op: &'static str) -> bool {
        match (&self.options.flip, self.paths.target) {
            (Some(c), Some(t)) => self.paths.current().1 == t && c.op == op,
            _ => false,
        }
    }

    /// Record (and possibly flip) an operation whose low-precision
    /// result is `lo`; `exact` is the f64 operation, applied to the
    /// shadows for the result's shadow and to the low-precision operands
    /// for the local error.
    fn op(
        &mut self,
        op: &'static str,
        args: &[Sh<E::N>],
        lo: E::N,
        exact: impl Fn(&[f64]) -> f64,
    ) -> Sh<E::N> {
        let n = args.len();
        let mut his = [0.0; 2];
        for (h, a) in his.iter_mut().zip(args) {
            *h = a.hi;
        }
        let hi = exact(&his[..n]);
        let flip = self.flipped(op);
        if !flip && !self.options.record_ops {
            return Sh { lo, hi };
        }
        let mut los = [0.0; 2];
        for (l, a) in los.iter_mut().zip(args) {
            *l = E::to_f64(a.lo);
        }
        let on_lo = exact(&los[..n]);
        let lo = if flip {
            E::constant(2.0 * on_lo - E::to_f64(lo)).unwrap_or(lo)
        } else {
            lo
        };
        if self.options.record_ops {
            let mut pairs = [(0.0, 0.0); 2];
            for (p, a) in pairs.iter_mut().zip(args) {
                *p = (E::to_f64(a.lo), a.hi);
            }
            let (full, site) = self.paths.current();
            let result = E::to_f64(lo);
            self.ops.push(ShadowOp {
                op,
                path: full,
                site,
                args: pairs,
                arity: args.len() as u8,
                result: (result, hi),
                local_error: (result - on_lo).abs(),
            });
        }
        Sh { lo, hi }
    }
}

impl<E: Formulated> Engine for ShadowEngine<E> {
    type N = Sh<E::N>;

    fn constant(x: f64) -> Option<Sh<E::N>> {
        Some(Sh {
            lo: E::constant(x)?,
            hi: x,
        })
    }

    fn to_f64(v: Sh<E::N>) -> f64 {
        E::to_f64(v.lo)
    }

    fn triple(v: Sh<E::N>) -> Option<F316> {
        E::triple(v.lo)
    }

    fn from_triple(t: F316) -> R<Sh<E::N>> {
        Ok(Sh {
            lo: E::from_triple(t)?,
            hi: t.to_f64(),
        })
    }

    fn gt(&mut self, a: Sh<E::N>, b: Sh<E::N>) -> R<bool> {
        self.inner.gt(a.lo, b.lo)
    }

    fn add(&mut self, a: Sh<E::N>, b: Sh<E::N>) -> R<Sh<E::N>> {
        let lo = self.inner.add(a.lo, b.lo)?;
        Ok(self.op("add", &[a, b], lo, |x| x[0] + x[1]))
    }

    fn sub(&mut self, a: Sh<E::N>, b: Sh<E::N>) -> R<Sh<E::N>> {
        let lo = self.inner.sub(a.lo, b.lo)?;
        Ok(self.op("sub", &[a, b], lo, |x| x[0] - x[1]))
    }

    fn mul(&mut self, a: Sh<E::N>, b: Sh<E::N>) -> R<Sh<E::N>> {
        let lo = self.inner.mul(a.lo, b.lo)?;
        Ok(self.op("mul", &[a, b], lo, |x| x[0] * x[1]))
    }

    fn div(&mut self, a: Sh<E::N>, b: Sh<E::N>) -> R<Sh<E::N>> {
        let lo = self.inner.div(a.lo, b.lo)?;
        Ok(self.op("div", &[a, b], lo, |x| x[0] / x[1]))
    }

    fn sqrt(&mut self, a: Sh<E::N>) -> R<Sh<E::N>> {
        let lo = self.inner.sqrt(a.lo)?;
        Ok(self.op("sqrt", &[a], lo, |x| x[0].sqrt()))
    }

    fn floor(&mut self, a: Sh<E::N>) -> R<Sh<E::N>> {
        let lo = self.inner.floor(a.lo)?;
        Ok(self.op("floor", &[a], lo, |x| x[0].floor()))
    }

    fn mod2(&mut self, a: Sh<E::N>) -> R<Sh<E::N>> {
        let lo = self.inner.mod2(a.lo)?;
        Ok(self.op("mod2", &[a], lo, |x| x[0].rem_euclid(2.0)))
    }

    fn double(&mut self, a: Sh<E::N>) -> R<Sh<E::N>> {
        let lo = self.inner.double(a.lo)?;
        Ok(self.op("double", &[a], lo, |x| 2.0 * x[0]))
    }

    fn quarter(&mut self, a: Sh<E::N>) -> R<Sh<E::N>> {
        let lo = self.inner.quarter(a.lo)?;
        Ok(self.op("quarter", &[a], lo, |x| x[0] * 0.25))
    }

    fn pow(&mut self, x: Sh<E::N>, p: Sh<E::N>) -> R<Sh<E::N>> {
        let lo = self.inner.pow(x.lo, p.lo)?;
        Ok(self.op("pow", &[x, p], lo, |v| v[0].powf(v[1])))
    }

    fn negate(a: Sh<E::N>) -> Sh<E::N> {
        Sh {
            lo: E::negate(a.lo),
            hi: -a.hi,
        }
    }

    fn sign_bit(a: Sh<E::N>) -> bool {
        E::sign_bit(a.lo)
    }

    fn frame<T>(
        &mut self,
        name: impl FnOnce() -> String,
        f: impl FnOnce(&mut Self) -> R<T>,
    ) -> R<T> {
        self.paths.push(name());
        let r = f(self);
        self.paths.pop();
        r
    }

    fn set_tuning(&mut self, tuning: Option<Tuning>) -> Option<Tuning> {
        self.inner.set_tuning(tuning)
    }

    fn decide(&mut self, decision: Decision, operands: [Sh<E::N>; 2], taken: bool) -> bool {
        let mut taken = taken;
        if let (true, Some(follow)) = (self.in_step, &self.options.follow) {
            let at = self.decisions.len();
            match follow.decisions.get(at) {
                Some((d, path, other))
                    if *d == decision && *path == self.paths.full_path(self.paths.current().0) =>
                {
                    if at >= follow.from {
                        taken = *other;
                    }
                }
                _ => self.in_step = false,
            }
        }
        self.decisions.push(DecisionRecord {
            decision,
            path: self.paths.current().0,
            taken,
            operands: operands.map(|o| E::to_f64(o.lo)),
            shadows: operands.map(|o| o.hi),
        });
        taken
    }

    fn normalize(&mut self, v: V3<Sh<E::N>>) -> R<V3<Sh<E::N>>> {
        formulation::normalize(self, v)
    }

    fn diffuse(&mut self, k: &Consts<Sh<E::N>>, a: Sh<E::N>) -> R<Sh<E::N>> {
        formulation::diffuse(self, k, a)
    }

    fn specular(&mut self, k: &Consts<Sh<E::N>>, s: Sh<E::N>) -> R<Sh<E::N>> {
        formulation::specular(self, k, s)
    }

    fn ambient(&mut self, k: &Consts<Sh<E::N>>) -> R<Sh<E::N>> {
        formulation::ambient(self, k)
    }

    fn dither_value(&mut self, k: &Consts<Sh<E::N>>, v: Sh<E::N>, b: usize) -> R<Sh<E::N>> {
        formulation::dither_value(self, k, v, b)
    }
}

impl<E: Formulated> Formulated for ShadowEngine<E> {
    const FORMULATION: Formulation = E::FORMULATION;

    fn inv_sqrt(&mut self, x: Sh<E::N>) -> R<Sh<E::N>> {
        let lo = self.inner.inv_sqrt(x.lo)?;
        Ok(self.op("inv_sqrt", &[x], lo, |v| 1.0 / v[0].sqrt()))
    }
}

/// A root cause: a site, the share of an error its own rounding
/// contributes, and its worst operation in the run.
#[derive(Clone, Debug, PartialEq)]
pub struct Blame {
    pub site: SiteKey,
    /// Half of (the error minus the error with the site flipped): to first
    /// order, the part of the error that the site's rounding causes, with
    /// the error's sign when it pushes the same way.
    pub contribution: f64,
    /// `contribution` over the error (1: all of it).
    pub share: f64,
    /// Whether the flipped run's error could be measured (it may trap, or
    /// no longer reach what the error is of).
    pub measured: bool,
    /// The site's operation with the largest local error.
    pub worst: ShadowOp,
    /// Its full call path.
    pub worst_path: String,
    /// How many operations the site ran.
    pub count: usize,
}

/// The sites of `base` (a run with operations recorded) that make a
/// local error, largest relative local error first, with the operation
/// of largest local error and the number of operations of each.
pub fn candidate_sites(base: &ShadowRun) -> Vec<(SiteKey, ShadowOp, usize)> {
    let relative = |op: &ShadowOp| op.local_error / op.result.1.abs().max(f64::MIN_POSITIVE);
    let mut by_site: HashMap<(u32, &'static str), (ShadowOp, usize)> = HashMap::new();
    for op in base.ops.iter().filter(|op| op.local_error > 0.0) {
        let entry = by_site.entry((op.site, op.op)).or_insert((*op, 0));
        entry.1 += 1;
        if relative(op) > relative(&entry.0) {
            entry.0 = *op;
        }
    }
    let mut sites: Vec<_> = by_site.into_values().collect();
    sites.sort_by(|a, b| {
        relative(&b.0)
            .total_cmp(&relative(&a.0))
            .then(a.0.site.cmp(&b.0.site))
            .then(a.0.op.cmp(b.0.op))
    });
    sites
        .into_iter()
        .map(|(op, n)| (base.site_of(&op), op, n))
        .collect()
}

/// The root causes of the signed error `error(base)`: up to `candidates`
/// sites of `base` (see [`candidate_sites`]) are each flipped alone by
/// `rerun`, and ranked by their contribution, largest first. A rerun whose
/// error cannot be measured (it trapped, or lost the decision measured)
/// contributes nothing.
pub fn blame(
    base: &ShadowRun,
    candidates: usize,
    rerun: impl Fn(&SiteKey) -> ShadowRun,
    error: impl Fn(&ShadowRun) -> Option<f64>,
) -> Vec<Blame> {
    let Some(before) = error(base) else {
        return Vec::new();
    };
    let direction = if before < 0.0 { -1.0 } else { 1.0 };
    let mut blamed: Vec<Blame> = candidate_sites(base)
        .into_iter()
        .take(candidates)
        .map(|(site, worst, count)| {
            let after = error(&rerun(&site));
            let contribution = after.map_or(0.0, |after| direction * (before - after) / 2.0);
            Blame {
                measured: after.is_some(),
                contribution,
                share: if before == 0.0 {
                    0.0
                } else {
                    contribution / before.abs()
                },
                worst_path: base.path(worst.path),
                worst,
                count,
                site,
            }
        })
        .collect();
    blamed.sort_by(|a, b| {
        b.contribution
            .total_cmp(&a.contribution)
            .then(a.site.cmp(&b.site))
    });
    blamed
}

#[cfg(test)]
mod tests;
