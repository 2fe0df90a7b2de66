//! Op traces of the Jack program: the emulator reports every call and
//! return; calls of the Float316 operation subroutines become
//! [`TraceRecord`]s (operands read from their objects when called, the
//! result when they return), in pre-order, with the Jack call stack as the
//! path. Nested operations (sub's add, sqrt's div/add/halve, ...) are
//! recorded because the Jack program really calls them.

use crate::raymarcher::{function_op, outcome_of, read_f316, OpShape, Raymarcher};
use crate::JackError;
use common::{Op, OpValue, Outcome, TraceRecord, F316};
use hack_vm::{FnId, Machine, Program, Ram, Watcher};

/// A call in progress: the record of an operation, or a plain frame.
struct Open {
    /// The record index and how to read the result, for an operation.
    op: Option<(usize, OpShape, i16)>,
}

/// Builds the records while the machine runs.
struct Recorder {
    /// The operation of each function id, if it is one.
    ops: Vec<Option<(Op, OpShape)>>,
    records: Vec<TraceRecord>,
    /// Path of frame names (the root label, then Jack functions).
    path: Vec<String>,
    open: Vec<Open>,
}

impl Recorder {
    fn new(program: &Program, root: String) -> Recorder {
        let ops = (0..program.functions().len())
            .map(|id| function_op(program.function_name(id as FnId)))
            .collect();
        Recorder {
            ops,
            records: Vec::new(),
            path: vec![root],
            open: Vec::new(),
        }
    }

    /// Fill in the result of every operation still open (a trap ended the
    /// run inside them).
    fn close_all(&mut self, outcome: Outcome<OpValue>) {
        for open in self.open.drain(..) {
            if let Some((index, _, _)) = open.op {
                self.records[index].result = outcome;
            }
        }
    }
}

impl Watcher for Recorder {
    fn on_call(&mut self, program: &Program, function: FnId, args: &[i16], ram: &Ram) {
        let name = program.function_name(function).to_string();
        let op = self.ops[function as usize].map(|(op, shape)| {
            let operands: Vec<F316> = args
                .iter()
                .take(op.arity())
                .map(|&a| read_f316(ram, a))
                .collect();
            let result_addr = match shape {
                OpShape::Binary => args[2],
                OpShape::Unary => args[1],
                OpShape::InPlace | OpShape::Compare => args[0],
            };
            self.records.push(TraceRecord {
                op,
                args: operands,
                result: Outcome::Hang,
                path: self.path.clone(),
            });
            (self.records.len() - 1, shape, result_addr)
        });
        self.path.push(name);
        self.open.push(Open { op });
    }

    fn on_return(&mut self, _program: &Program, _function: FnId, value: i16, ram: &Ram) {
        self.path.pop();
        if let Some(Open {
            op: Some((index, shape, addr)),
        }) = self.open.pop()
        {
            self.records[index].result = Outcome::Value(match shape {
                OpShape::Compare => OpValue::Bool(value != 0),
                _ => OpValue::Num(read_f316(ram, addr)),
            });
        }
    }
}

impl Raymarcher {
    /// Run `name(args)` on `machine` watching every function; returns the
    /// call's outcome and the records.
    fn traced(
        &self,
        machine: &mut Machine,
        name: &str,
        args: &[i16],
        budget: u64,
        root: String,
    ) -> Result<(Outcome<i16>, Vec<TraceRecord>), JackError> {
        let program = std::sync::Arc::clone(machine.program());
        let watch = vec![true; program.functions().len()];
        let mut recorder = Recorder::new(&program, root);
        let exit = machine.call_watched(name, args, Some(budget), &watch, &mut recorder)?;
        let outcome = outcome_of(exit, || format!("{name}{args:?}"))?;
        match outcome {
            Outcome::Value(_) => {}
            Outcome::SysError(c) => recorder.close_all(Outcome::SysError(c)),
            Outcome::Hang => recorder.close_all(Outcome::Hang),
            Outcome::OutOfDomain => recorder.close_all(Outcome::OutOfDomain),
        }
        Ok((outcome, recorder.records))
    }

    /// The op trace of one operation (the operation itself first, then the
    /// operations it calls).
    pub fn trace_op(&self, op: Op, args: &[F316]) -> Result<Vec<TraceRecord>, JackError> {
        let mut m = self.machine();
        let (name, call_args, _) = self.prepare_op(&mut m, op, args)?;
        let root = format!("{op}");
        Ok(self
            .traced(&mut m, name, &call_args, self.budgets().op, root)?
            .1)
    }

    /// The op trace of one SDF evaluation at `p`.
    pub fn trace_sdf(&self, p: [F316; 3]) -> Result<Vec<TraceRecord>, JackError> {
        let mut m = self.machine();
        let arg = self.prepare_sdf(&mut m, p);
        let root = format!("sdf({:?},{:?},{:?})", p[0], p[1], p[2]);
        Ok(self
            .traced(&mut m, "Scene.eval", &[arg], self.budgets().sdf, root)?
            .1)
    }

    /// The op trace of pixel (x, y), from its screen coordinates to its
    /// dithered bit.
    pub fn trace_pixel(&self, x: usize, y: usize) -> Result<Vec<TraceRecord>, JackError> {
        let args = Raymarcher::pixel_args(x, y)?;
        let mut m = self.machine();
        let root = format!("pixel({x},{y})");
        Ok(self
            .traced(&mut m, "Image.pixel", &args, self.budgets().pixel, root)?
            .1)
    }
}
