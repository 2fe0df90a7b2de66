//! [`Raymarcher`]: the Jack program compiled, loaded and initialised once
//! (`Main.init`), then every computation runs on a clone of that snapshot,
//! so calls are independent and run in parallel.
//!
//! Entry points (see `raymarcher/Main.jack`): an operation is the Float316
//! subroutine itself, called on operand objects whose words the facade
//! writes (`Main.operandA`, `Main.operandB`, result `Main.result`); an SDF
//! query is `Scene.eval` on `Main.point`; a pixel is `Image.pixel(x, y)`.

use crate::{sources, JackError};
use common::image_consts::{HEIGHT, WIDTH};
use common::{Op, OpValue, Outcome, F316};
use hack_vm::{Config, Exit, Machine, Profile, Program, Ram};
use rayon::prelude::*;
use std::sync::Arc;

/// The `Sys.error` code by which `Float316.floor` and `Float316.mod2`
/// signal an input outside their domain (the original program indexed
/// outside its table of powers of two there). Reported as
/// [`Outcome::OutOfDomain`].
pub const OUT_OF_DOMAIN_CODE: i16 = 316;

/// Instruction budgets per call; running out is reported as
/// [`Outcome::Hang`]. The defaults are far above the costliest normal call
/// of any port seen, so that running out means a loop that never ends: our
/// raymarcher's operations end within 33 108 instructions whatever their
/// operands (`sub` at the largest exponent gap; `cargo run -p jack
/// --example op_budget`), a user's bit-serial `add` within 73 580, a pixel
/// under 1 000 000. A hang costs the whole budget, about 4 ms for the
/// operation's 2 000 000 on the compiled engine. A bound program sets its
/// own in its bindings (`budget = { op = N, sdf = N, pixel = N }`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Budgets {
    /// Per Float316 operation.
    pub op: u64,
    /// Per SDF evaluation.
    pub sdf: u64,
    /// Per pixel.
    pub pixel: u64,
}

impl Default for Budgets {
    fn default() -> Self {
        Budgets {
            op: 2_000_000,
            sdf: 5_000_000,
            pixel: 50_000_000,
        }
    }
}

/// A result with the VM instructions it took.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Counted<T> {
    /// The outcome.
    pub outcome: Outcome<T>,
    /// VM instructions executed by the call (labels are free, a call is one).
    pub instructions: u64,
}

/// One pixel: its shade clamped to [0, 1] (before dithering) and its
/// dithered bit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shaded {
    /// The clamped shade.
    pub value: F316,
    /// True when the dithered pixel is white.
    pub white: bool,
}

/// A whole image through the entry points, row by row.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Render {
    /// Pixel `(x, y)` at index `y * WIDTH + x`.
    pub pixels: Vec<Counted<Shaded>>,
}

impl Render {
    /// Total VM instructions of all pixels.
    pub fn instructions(&self) -> u64 {
        self.pixels.iter().map(|p| p.instructions).sum()
    }
}

/// The Jack function of an operation and whether it works in place.
fn op_function(op: Op) -> (&'static str, OpShape) {
    match op {
        Op::Gt => ("Float316.gt", OpShape::Compare),
        Op::Add => ("Float316.add", OpShape::Binary),
        Op::Sub => ("Float316.sub", OpShape::Binary),
        Op::Mul => ("Float316.mul", OpShape::Binary),
        Op::Div => ("Float316.div", OpShape::Binary),
        Op::Floor => ("Float316.floor", OpShape::Unary),
        Op::Mod2 => ("Float316.mod2", OpShape::Unary),
        Op::Sqrt => ("Float316.sqrt", OpShape::Unary),
        Op::InvSqrt => ("Float316.invSqrt", OpShape::Unary),
        Op::Halve => ("Float316.halve", OpShape::InPlace),
        Op::Double => ("Float316.double", OpShape::InPlace),
        Op::Quarter => ("Float316.quarter", OpShape::InPlace),
    }
}

/// How an operation's subroutine takes its operands and gives its result.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum OpShape {
    /// `a.f(b)` returns a boolean.
    Compare,
    /// `a.f(b, r)`.
    Binary,
    /// `a.f(r)`.
    Unary,
    /// `a.f()`, the result in `a`.
    InPlace,
}

/// The Float316 operation a Jack function implements, if any.
pub(crate) fn function_op(name: &str) -> Option<(Op, OpShape)> {
    Op::ALL.into_iter().find_map(|op| {
        let (f, shape) = op_function(op);
        (f == name).then_some((op, shape))
    })
}

/// Read the Float316 object at `addr`.
pub(crate) fn read_f316(ram: &Ram, addr: i16) -> F316 {
    let a = i32::from(addr);
    F316::new(ram.read(a), ram.read(a + 1), ram.read(a + 2))
}

fn write_f316(ram: &mut Ram, addr: i16, v: F316) {
    let a = i32::from(addr);
    ram.write(a, v.s);
    ram.write(a + 1, v.e);
    ram.write(a + 2, v.m);
}

/// The Jack raymarcher on the emulator, initialised and ready to be called.
#[derive(Clone, Debug)]
pub struct Raymarcher {
    snapshot: Machine,
    budgets: Budgets,
    operand_a: i16,
    operand_b: i16,
    result: i16,
    /// The SDF query point (a `Vec`) and its component objects.
    point_vec: i16,
    point: [i16; 3],
}

/// Apply a fallible `f` to a value, keeping traps as they are.
pub(crate) fn and_then<T, U>(
    o: Outcome<T>,
    f: impl FnOnce(T) -> Result<U, JackError>,
) -> Result<Outcome<U>, JackError> {
    Ok(match o {
        Outcome::Value(v) => Outcome::Value(f(v)?),
        Outcome::SysError(c) => Outcome::SysError(c),
        Outcome::Hang => Outcome::Hang,
        Outcome::OutOfDomain => Outcome::OutOfDomain,
    })
}

/// The outcome of a call from its [`Exit`] (`Sys.error` with
/// [`OUT_OF_DOMAIN_CODE`] is out of domain), or an error for an end that is
/// no Float316 outcome.
pub(crate) fn outcome_of(
    exit: Exit,
    what: impl FnOnce() -> String,
) -> Result<Outcome<i16>, JackError> {
    crate::bind::outcome_of(exit, Some(OUT_OF_DOMAIN_CODE), what)
}

impl Raymarcher {
    /// Compile the embedded raymarcher, load it under the OS profile
    /// `profile` (desktop: truncating `Math.divide`, the seed program's),
    /// run `Main.init` and keep the machine as the snapshot every call
    /// starts from.
    pub fn new(profile: Profile, budgets: Budgets) -> Result<Raymarcher, JackError> {
        Raymarcher::with_config(
            Config {
                profile,
                ..Config::default()
            },
            budgets,
        )
    }

    /// [`Raymarcher::new`] with a full machine configuration (for example
    /// with per-function instruction profiling).
    pub fn with_config(config: Config, budgets: Budgets) -> Result<Raymarcher, JackError> {
        let program = sources::program(config.profile)?;
        Raymarcher::from_program(program, config, budgets)
    }

    fn from_program(
        program: Arc<Program>,
        config: Config,
        budgets: Budgets,
    ) -> Result<Raymarcher, JackError> {
        let mut machine = Machine::new(program, config);
        let mut call = |name: &str| -> Result<i16, JackError> {
            let exit = machine.call(name, &[], Some(10_000_000))?;
            match exit {
                Exit::Returned(v) => Ok(v),
                exit => Err(JackError::Unexpected {
                    what: name.to_string(),
                    exit,
                }),
            }
        };
        call("Main.init")?;
        let operand_a = call("Main.operandA")?;
        let operand_b = call("Main.operandB")?;
        let result = call("Main.result")?;
        let point_vec = call("Main.point")?;
        let ram = machine.ram();
        let p = i32::from(point_vec);
        let point = [ram.read(p), ram.read(p + 1), ram.read(p + 2)];
        Ok(Raymarcher {
            snapshot: machine,
            budgets,
            operand_a,
            operand_b,
            result,
            point_vec,
            point,
        })
    }

    /// The budgets in use.
    pub fn budgets(&self) -> Budgets {
        self.budgets
    }

    /// The loaded program (function names, ids).
    pub fn program(&self) -> &Arc<Program> {
        self.snapshot.program()
    }

    /// A fresh machine at the snapshot.
    pub(crate) fn machine(&self) -> Machine {
        self.snapshot.clone()
    }

    /// Run `name(args)` on `machine` and count its instructions.
    pub(crate) fn run_call(
        &self,
        machine: &mut Machine,
        name: &str,
        args: &[i16],
        budget: u64,
    ) -> Result<(Outcome<i16>, u64), JackError> {
        let start = machine.steps();
        let exit = machine.call(name, args, Some(budget))?;
        let outcome = outcome_of(exit, || format!("{name}{args:?}"))?;
        Ok((outcome, machine.steps() - start))
    }

    /// Prepare `machine` for `op` on `args` and return the function name and
    /// its arguments.
    pub(crate) fn prepare_op(
        &self,
        machine: &mut Machine,
        op: Op,
        args: &[F316],
    ) -> Result<(&'static str, Vec<i16>, OpShape), JackError> {
        if args.len() != op.arity() {
            return Err(JackError::BadArgument(format!(
                "{op} takes {} operand(s), got {}",
                op.arity(),
                args.len()
            )));
        }
        let ram = machine.ram_mut();
        write_f316(ram, self.operand_a, args[0]);
        if let Some(&b) = args.get(1) {
            write_f316(ram, self.operand_b, b);
        }
        let (name, shape) = op_function(op);
        let call_args = match shape {
            OpShape::Compare => vec![self.operand_a, self.operand_b],
            OpShape::Binary => vec![self.operand_a, self.operand_b, self.result],
            OpShape::Unary => vec![self.operand_a, self.result],
            OpShape::InPlace => vec![self.operand_a],
        };
        Ok((name, call_args, shape))
    }

    /// The value of an operation that returned `ret` on `machine`.
    pub(crate) fn op_value(&self, machine: &Machine, shape: OpShape, ret: i16) -> OpValue {
        match shape {
            OpShape::Compare => OpValue::Bool(ret != 0),
            OpShape::Binary | OpShape::Unary => OpValue::Num(read_f316(machine.ram(), self.result)),
            OpShape::InPlace => OpValue::Num(read_f316(machine.ram(), self.operand_a)),
        }
    }

    /// One Float316 operation on `args` (`op.arity()` operands).
    pub fn op(&self, op: Op, args: &[F316]) -> Result<Counted<OpValue>, JackError> {
        let mut m = self.machine();
        let (name, call_args, shape) = self.prepare_op(&mut m, op, args)?;
        let (outcome, instructions) = self.run_call(&mut m, name, &call_args, self.budgets.op)?;
        Ok(Counted {
            outcome: outcome.map(|ret| self.op_value(&m, shape, ret)),
            instructions,
        })
    }

    /// Write the SDF query point into `machine`; returns the `Vec` argument.
    pub(crate) fn prepare_sdf(&self, machine: &mut Machine, p: [F316; 3]) -> i16 {
        let ram = machine.ram_mut();
        for (addr, v) in self.point.into_iter().zip(p) {
            write_f316(ram, addr, v);
        }
        self.point_vec
    }

    /// The distance and colour left by `Scene.eval` on `machine`.
    pub(crate) fn sdf_value(&self, machine: &mut Machine) -> Result<(F316, F316), JackError> {
        let sd = self.getter(machine, "Scene.distance")?;
        let col = self.getter(machine, "Scene.colour")?;
        Ok((read_f316(machine.ram(), sd), read_f316(machine.ram(), col)))
    }

    fn getter(&self, machine: &mut Machine, name: &str) -> Result<i16, JackError> {
        match machine.call(name, &[], Some(100))? {
            Exit::Returned(v) => Ok(v),
            exit => Err(JackError::Unexpected {
                what: name.to_string(),
                exit,
            }),
        }
    }

    /// The scene at point `p`: (signed distance, colour).
    pub fn sdf(&self, p: [F316; 3]) -> Result<Counted<(F316, F316)>, JackError> {
        let mut m = self.machine();
        let arg = self.prepare_sdf(&mut m, p);
        let (outcome, instructions) =
            self.run_call(&mut m, "Scene.eval", &[arg], self.budgets.sdf)?;
        let outcome = and_then(outcome, |_| self.sdf_value(&mut m))?;
        Ok(Counted {
            outcome,
            instructions,
        })
    }

    /// Check pixel coordinates and convert them to Jack words.
    pub(crate) fn pixel_args(x: usize, y: usize) -> Result<[i16; 2], JackError> {
        if x >= WIDTH || y >= HEIGHT {
            return Err(JackError::BadArgument(format!(
                "pixel ({x},{y}) is outside the {WIDTH}x{HEIGHT} image"
            )));
        }
        Ok([x as i16, y as i16])
    }

    /// The shade left by `Image.pixel` on `machine`, with its white bit.
    pub(crate) fn shaded(&self, machine: &mut Machine, white: i16) -> Result<Shaded, JackError> {
        let v = self.getter(machine, "Image.shade")?;
        Ok(Shaded {
            value: read_f316(machine.ram(), v),
            white: white != 0,
        })
    }

    /// Pixel (x, y) of the image, through `Image.pixel` (its Float316
    /// coordinates are built directly from the integers; they equal the
    /// image loop's counters).
    pub fn pixel(&self, x: usize, y: usize) -> Result<Counted<Shaded>, JackError> {
        let args = Raymarcher::pixel_args(x, y)?;
        let mut m = self.machine();
        let (outcome, instructions) =
            self.run_call(&mut m, "Image.pixel", &args, self.budgets.pixel)?;
        let outcome = and_then(outcome, |w| self.shaded(&mut m, w))?;
        Ok(Counted {
            outcome,
            instructions,
        })
    }

    /// The rows `rows` of the image, pixels in parallel.
    pub fn render_rows(&self, rows: std::ops::Range<usize>) -> Result<Render, JackError> {
        self.render_rows_observed(rows, &|| {})
    }

    /// Like [`Raymarcher::render_rows`], calling `done` as each pixel
    /// finishes (from any thread, in no particular order: for a progress
    /// bar).
    pub fn render_rows_observed(
        &self,
        rows: std::ops::Range<usize>,
        done: &(dyn Fn() + Sync),
    ) -> Result<Render, JackError> {
        let coords: Vec<(usize, usize)> =
            rows.flat_map(|y| (0..WIDTH).map(move |x| (x, y))).collect();
        let pixels = coords
            .par_iter()
            .map(|&(x, y)| {
                let pixel = self.pixel(x, y)?;
                done();
                Ok(pixel)
            })
            .collect::<Result<Vec<_>, JackError>>()?;
        Ok(Render { pixels })
    }

    /// The whole 512x256 image, pixels in parallel.
    pub fn render(&self) -> Result<Render, JackError> {
        self.render_rows(0..HEIGHT)
    }
}
