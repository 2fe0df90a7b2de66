//! Op traces of a bound program: the emulator reports every call and
//! return; a call of a bound operation's function (with the statement's
//! constant arguments, if it has any) becomes a [`TraceRecord`]: its
//! operands read through the float layout at the call, its result at the
//! return, its path the Jack call stack. Records are in pre-order, nested
//! operations included, in the program's own order and nesting.

use super::bound::{BoundOp, BoundProgram, OpResult};
use super::statement::Slot;
use super::vm::{arguments, outcome_of};
use crate::JackError;
use common::{Op, OpValue, Outcome, TraceRecord, F316};
use hack_vm::{FnId, Machine, Program, Ram, Watcher};

/// Where a record's result is read at the return.
#[derive(Clone, Copy)]
enum ResultAt {
    Bool,
    Returned,
    Object(i16),
}

/// A record before its path is named.
struct Raw {
    op: Op,
    args: Vec<F316>,
    result: Outcome<OpValue>,
    path: Vec<FnId>,
}

/// Builds records while a machine runs; `active` says whether calls are
/// recorded now (whole-program mode records some pixels only).
pub(crate) struct Recorder<'a> {
    bound: &'a BoundProgram,
    /// The bound operations of each function id.
    by_fn: Vec<Vec<usize>>,
    raw: Vec<Raw>,
    stack: Vec<FnId>,
    open: Vec<Option<(usize, ResultAt)>>,
    pub active: bool,
}

/// The bound operation `args` are a call of, if any.
fn matches(bound: &BoundOp, args: &[i16]) -> bool {
    bound.call.args.len() == args.len()
        && bound
            .call
            .args
            .iter()
            .zip(args)
            .all(|(s, &a)| !matches!(*s, Slot::Lit(n) if n != a))
}

impl<'a> Recorder<'a> {
    pub fn new(bound: &'a BoundProgram, program: &Program) -> Recorder<'a> {
        let mut by_fn = vec![Vec::new(); program.functions().len()];
        for (i, b) in bound.ops.iter().enumerate() {
            by_fn[b.call.function as usize].push(i);
        }
        Recorder {
            bound,
            by_fn,
            raw: Vec::new(),
            stack: Vec::new(),
            open: Vec::new(),
            active: true,
        }
    }

    /// The functions to watch: all (the path needs every frame).
    pub fn watch_all(program: &Program) -> Vec<bool> {
        vec![true; program.functions().len()]
    }

    /// Fill in the result of every open record (a trap ended the run).
    pub fn close_all(&mut self, outcome: Outcome<OpValue>) {
        for (index, _) in self.open.drain(..).flatten() {
            self.raw[index].result = outcome;
        }
    }

    /// Take the records so far, paths named under `root`.
    pub fn take(&mut self, program: &Program, root: &str) -> Vec<TraceRecord> {
        self.raw
            .drain(..)
            .map(|r| {
                let mut path = vec![root.to_string()];
                path.extend(r.path.iter().map(|&f| program.function_name(f).to_string()));
                TraceRecord {
                    op: r.op,
                    args: r.args,
                    result: r.result,
                    path,
                }
            })
            .collect()
    }

    /// Drop the records so far.
    pub fn clear(&mut self) {
        self.raw.clear();
        for o in &mut self.open {
            *o = None;
        }
    }

    fn record(&mut self, ram: &Ram, bound: &BoundOp, args: &[i16]) -> (usize, ResultAt) {
        let float = &self.bound.float;
        let read = |reg: usize| {
            let pos = bound.call.arg_position(reg).expect("operands are passed");
            float.read_float(ram, args[pos])
        };
        let mut operands = vec![read(bound.a)];
        if let Some(b) = bound.b {
            operands.push(read(b));
        }
        let result_reg = if bound.b.is_some() { 2 } else { 1 };
        let at = match bound.result {
            OpResult::Bool => ResultAt::Bool,
            OpResult::Returned => ResultAt::Returned,
            OpResult::Argument => {
                ResultAt::Object(args[bound.call.arg_position(result_reg).expect("passed")])
            }
            OpResult::InPlace => {
                ResultAt::Object(args[bound.call.arg_position(bound.a).expect("passed")])
            }
        };
        self.raw.push(Raw {
            op: bound.op,
            args: operands,
            result: Outcome::Hang,
            path: self.stack.clone(),
        });
        (self.raw.len() - 1, at)
    }
}

impl Watcher for Recorder<'_> {
    fn on_call(&mut self, _program: &Program, function: FnId, args: &[i16], ram: &Ram) {
        let mut open = None;
        if self.active {
            let bound = self.by_fn[function as usize]
                .iter()
                .map(|&i| &self.bound.ops[i])
                .find(|b| matches(b, args));
            if let Some(b) = bound {
                open = Some(self.record(ram, b, args));
            }
        }
        self.stack.push(function);
        self.open.push(open);
    }

    fn on_return(&mut self, _program: &Program, _function: FnId, value: i16, ram: &Ram) {
        self.stack.pop();
        if let Some(Some((index, at))) = self.open.pop() {
            let float = &self.bound.float;
            self.raw[index].result = Outcome::Value(match at {
                ResultAt::Bool => OpValue::Bool(value != 0),
                ResultAt::Returned => OpValue::Num(float.read_float(ram, value)),
                ResultAt::Object(p) => OpValue::Num(float.read_float(ram, p)),
            });
        }
    }
}

impl BoundProgram {
    /// Run `calls` on `m` with a recorder; the records under `root`.
    fn traced(
        &self,
        m: &mut Machine,
        calls: &[super::statement::Call],
        regs: &mut [i16],
        budget: u64,
        root: &str,
    ) -> Result<Vec<TraceRecord>, JackError> {
        let program = std::sync::Arc::clone(m.program());
        let watch = Recorder::watch_all(&program);
        let mut rec = Recorder::new(self, &program);
        let start = m.steps();
        for call in calls {
            let left = budget.saturating_sub(m.steps() - start).max(1);
            let args = arguments(call, regs);
            let exit = m.call_watched(&call.name, &args, Some(left), &watch, &mut rec)?;
            let outcome = outcome_of(exit, self.out_of_domain, || call.name.clone())?;
            match outcome {
                Outcome::Value(v) => {
                    if let Some(t) = call.target {
                        regs[t] = v;
                    }
                }
                Outcome::SysError(c) => {
                    rec.close_all(Outcome::SysError(c));
                    break;
                }
                Outcome::Hang => {
                    rec.close_all(Outcome::Hang);
                    break;
                }
                Outcome::OutOfDomain => {
                    rec.close_all(Outcome::OutOfDomain);
                    break;
                }
            }
        }
        Ok(rec.take(&program, root))
    }

    /// The op trace of one operation (itself first, then what it calls).
    pub fn trace_op(&self, op: Op, args: &[F316]) -> Result<Vec<TraceRecord>, JackError> {
        let mut m = self.machine();
        let (bound, mut regs) = self.prepare_op(&mut m, op, args)?;
        let call = bound.call.clone();
        self.traced(
            &mut m,
            std::slice::from_ref(&call),
            &mut regs,
            self.budgets.op,
            &op.to_string(),
        )
    }

    /// The op trace of one SDF query at `p`.
    pub fn trace_sdf(&self, p: [F316; 3]) -> Result<Vec<TraceRecord>, JackError> {
        let mut m = self.machine();
        let (q, mut regs) = self.prepare_sdf(&mut m, p)?;
        let calls = q.calls.clone();
        let root = format!("sdf({:?},{:?},{:?})", p[0], p[1], p[2]);
        self.traced(&mut m, &calls, &mut regs, self.budgets.sdf, &root)
    }

    /// The op trace of pixel (x, y).
    pub fn trace_pixel(&self, x: usize, y: usize) -> Result<Vec<TraceRecord>, JackError> {
        let mut m = self.machine();
        let (q, mut regs) = self.prepare_pixel(&mut m, x, y)?;
        let calls = q.calls.clone();
        self.traced(
            &mut m,
            &calls,
            &mut regs,
            self.budgets.pixel,
            &format!("pixel({x},{y})"),
        )
    }
}
