//! What a generated program costs: VM instructions per pixel, measured by
//! running `Image.pixel` on the emulator ([`Runner`]; per function with
//! [`Runner::profiled`]), and its size in VM
//! commands with an estimate of Hack ROM words ([`Size`]).
//!
//! Two ROM estimates, per VM command. *Textbook*: the translator of
//! nand2tetris chapters 7 and 8 writing every command in line. *Shared*:
//! the same, with `call`, `return` and the comparisons jumping to one
//! routine each (the routines, about 150 words together, counted once):
//!
//! | command | textbook | shared |
//! |---|---:|---:|
//! | `push constant` | 7 | 7 |
//! | `push local/argument/this/that` | 10 | 10 |
//! | `push static/temp/pointer` | 7 | 7 |
//! | `pop local/argument/this/that` | 12 | 12 |
//! | `pop static/temp/pointer` | 5 | 5 |
//! | `add`, `sub`, `and`, `or` | 5 | 5 |
//! | `neg`, `not` | 3 | 3 |
//! | `eq`, `gt`, `lt` | 13 | 4 |
//! | `label` | 0 | 0 |
//! | `goto` | 2 | 2 |
//! | `if-goto` | 5 | 5 |
//! | `function f k` | 7 k | 7 k |
//! | `call f n` | 49 | 10 |
//! | `return` | 45 | 2 |
//!
//! The OS is not counted (the emulator's is native; the official OS in VM
//! code is a program of its own).

use crate::JackSources;
use common::F316;
use hack_vm::{Config, Exit, Machine, Profile, Program};
use std::collections::HashMap;

/// Hack ROM words.
pub const ROM_WORDS: usize = 32768;

/// Why a program could not be run.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    #[error("compile: {0}")]
    Compile(#[from] jack_compiler::CompileErrors),
    #[error("load: {0}")]
    Load(#[from] hack_vm::LoadError),
    #[error("{call}: {exit:?}")]
    Stopped { call: String, exit: Box<Exit> },
}

/// The VM text of `j` compiled under `profile`: (file name, VM code).
pub fn compile(j: &JackSources, profile: Profile) -> Result<Vec<(String, String)>, RunError> {
    Ok(jack_compiler::compile_sources(&j.sources(), profile)?
        .into_iter()
        .map(jack_compiler::VmClass::into_file)
        .collect())
}

/// How a query ended: the value, or the `Sys.error` code / other stop.
pub type Answer<T> = Result<T, Box<Exit>>;

/// One pixel as `Image.pixel` gives it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Pixel {
    /// The output level.
    pub level: i16,
    /// The shade (`Image.shade()`).
    pub shade: F316,
}

/// A result with the VM instructions it took.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Counted<T> {
    pub answer: Answer<T>,
    pub instructions: u64,
}

/// A generated program on the emulator after `Main.init`; each query runs
/// on a copy of that machine.
#[derive(Clone)]
pub struct Runner {
    ready: Machine,
    /// Instructions `Main.init` took.
    pub init_instructions: u64,
    /// Budget of one query.
    pub budget: u64,
}

fn float_at(m: &Machine, addr: i16) -> F316 {
    let r = m.ram();
    let a = i32::from(addr);
    F316::new(r.read(a), r.read(a + 1), r.read(a + 2))
}

impl Runner {
    /// Compile `j` under `profile`, load it and run `Main.init`.
    pub fn new(j: &JackSources, profile: Profile) -> Result<Runner, RunError> {
        Runner::with_config(
            j,
            Config {
                profile,
                ..Config::default()
            },
        )
    }

    /// Like [`Runner::new`], counting instructions per function for
    /// [`Runner::pixel_profile`].
    pub fn profiled(j: &JackSources, profile: Profile) -> Result<Runner, RunError> {
        Runner::with_config(
            j,
            Config {
                profile,
                profile_functions: true,
                ..Config::default()
            },
        )
    }

    fn with_config(j: &JackSources, config: Config) -> Result<Runner, RunError> {
        let mut m = machine(j, config)?;
        let budget = 200_000_000;
        match m.call("Main.init", &[], Some(budget)) {
            Ok(Exit::Returned(_)) => {}
            Ok(exit) => {
                return Err(RunError::Stopped {
                    call: "Main.init".into(),
                    exit: Box::new(exit),
                })
            }
            Err(e) => unreachable!("Main.init is generated: {e:?}"),
        }
        Ok(Runner {
            init_instructions: m.steps(),
            ready: m,
            budget: 50_000_000,
        })
    }

    /// Call `name` on `m`; its return value and the instructions it took.
    fn call(&self, m: &mut Machine, name: &str, args: &[i16]) -> (Answer<i16>, u64) {
        let before = m.steps();
        let exit = m
            .call(name, args, Some(self.budget))
            .unwrap_or_else(|e| unreachable!("{name} is generated: {e:?}"));
        let n = m.steps() - before;
        match exit {
            Exit::Returned(v) => (Ok(v), n),
            other => (Err(Box::new(other)), n),
        }
    }

    /// Pixel (x, y) through `Image.pixel`.
    pub fn pixel(&self, x: u32, y: u32) -> Counted<Pixel> {
        let mut m = self.ready.clone();
        let (level, instructions) = self.call(&mut m, "Image.pixel", &[x as i16, y as i16]);
        let answer = level.map(|level| {
            let (shade, _) = self.call(&mut m, "Image.shade", &[]);
            let shade = shade.expect("a getter returns");
            Pixel {
                level,
                shade: float_at(&m, shade),
            }
        });
        Counted {
            answer,
            instructions,
        }
    }

    /// The VM instructions `Image.pixel` takes at (x, y) in each function
    /// (exclusive of its callees), by name, on a runner made by
    /// [`Runner::profiled`] (empty on any other).
    pub fn pixel_profile(&self, x: u32, y: u32) -> Vec<(String, u64)> {
        let mut m = self.ready.clone();
        let before: HashMap<String, u64> = m.function_profile().into_iter().collect();
        let _ = self.call(&mut m, "Image.pixel", &[x as i16, y as i16]);
        m.function_profile()
            .into_iter()
            .map(|(f, n)| {
                let n = n - before.get(&f).copied().unwrap_or(0);
                (f, n)
            })
            .filter(|(_, n)| *n > 0)
            .collect()
    }

    /// The SDF at `p` through `Scene.sdf`: (distance, colour).
    pub fn sdf(&self, p: [F316; 3]) -> Counted<(F316, F316)> {
        let mut m = self.ready.clone();
        // The point and the two results, made by the program's constructor.
        let mut objects = [0i16; 5];
        for (i, o) in objects.iter_mut().enumerate() {
            let v = p.get(i).copied().unwrap_or(F316::ZERO);
            let (ptr, _) = self.call(&mut m, "Float316.new", &[v.s, v.e, v.m]);
            *o = ptr.expect("the constructor returns");
        }
        let (tag, instructions) = self.call(&mut m, "Scene.sdf", &objects);
        Counted {
            answer: tag.map(|_| (float_at(&m, objects[3]), float_at(&m, objects[4]))),
            instructions,
        }
    }
}

/// A fresh machine for `j` under `config`.
fn machine(j: &JackSources, config: Config) -> Result<Machine, RunError> {
    let program = Program::from_sources(&compile(j, config.profile)?)?;
    Ok(Machine::new(program, config))
}

/// Run `Main.main` (set-up and the whole image) for at most `budget`
/// instructions: the screen and the instructions it took.
pub fn run_main(j: &JackSources, profile: Profile, budget: u64) -> Result<Screen, RunError> {
    let mut m = machine(
        j,
        Config {
            profile,
            ..Config::default()
        },
    )?;
    match m.run(Some(budget)) {
        Exit::Halted | Exit::Returned(_) => {}
        exit => {
            return Err(RunError::Stopped {
                call: "Main.main".into(),
                exit: Box::new(exit),
            })
        }
    }
    let (w, h) = (crate::SCREEN.0 as usize, crate::SCREEN.1 as usize);
    Ok(Screen {
        white: (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .map(|(x, y)| !m.ram().pixel(x, y))
            .collect(),
        instructions: m.steps(),
    })
}
/// The Hack screen after a run.
#[derive(Clone, Debug)]
pub struct Screen {
    /// 512 x 256, row by row, `true` = white.
    pub white: Vec<bool>,
    pub instructions: u64,
}

/// VM instructions per pixel over a sample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PixelCost {
    pub pixels: usize,
    pub mean: f64,
    pub max: u64,
    /// The pixel that took `max`.
    pub worst: (u32, u32),
}

/// The cost of `pixels` through `runner`.
pub fn pixel_cost(runner: &Runner, pixels: &[(u32, u32)]) -> PixelCost {
    let counts: Vec<((u32, u32), u64)> = pixels
        .iter()
        .map(|&(x, y)| ((x, y), runner.pixel(x, y).instructions))
        .collect();
    let total: u64 = counts.iter().map(|c| c.1).sum();
    let (worst, max) = counts
        .iter()
        .copied()
        .max_by_key(|c| c.1)
        .unwrap_or(((0, 0), 0));
    PixelCost {
        pixels: counts.len(),
        mean: total as f64 / counts.len().max(1) as f64,
        max,
        worst,
    }
}

/// A program's size.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Size {
    /// VM commands (labels included).
    pub vm_commands: usize,
    /// Hack instructions, every command in line (see the module).
    pub rom_textbook: usize,
    /// Hack instructions with shared call, return and comparison routines.
    pub rom_shared: usize,
}

/// The words of the shared routines (call, return, eq, gt, lt).
const SHARED_ROUTINES: usize = 150;

/// Hack instructions of one VM command in line (the module's table).
fn rom_words(command: &str) -> usize {
    let w: Vec<&str> = command.split_whitespace().collect();
    let pointer_like = |seg: &str| matches!(seg, "static" | "temp" | "pointer");
    match w.as_slice() {
        ["push", "constant", _] => 7,
        ["push", seg, _] if pointer_like(seg) => 7,
        ["push", _, _] => 10,
        ["pop", seg, _] if pointer_like(seg) => 5,
        ["pop", _, _] => 12,
        ["add" | "sub" | "and" | "or"] => 5,
        ["neg" | "not"] => 3,
        ["eq" | "gt" | "lt"] => 13,
        ["label", _] => 0,
        ["goto", _] => 2,
        ["if-goto", _] => 5,
        ["function", _, k] => 7 * k.parse::<usize>().unwrap_or(0),
        ["call", _, _] => 49,
        ["return"] => 45,
        _ => 0,
    }
}

/// Hack instructions of one VM command with the shared routines.
fn rom_words_shared(command: &str) -> usize {
    match command.split_whitespace().next() {
        Some("eq" | "gt" | "lt") => 4,
        Some("call") => 10,
        Some("return") => 2,
        _ => rom_words(command),
    }
}

/// The size of VM text `vm` (file name, code).
pub fn size(vm: &[(String, String)]) -> Size {
    let commands: Vec<&str> = vm
        .iter()
        .flat_map(|(_, code)| code.lines())
        .map(|l| l.split("//").next().unwrap_or("").trim())
        .filter(|l| !l.is_empty())
        .collect();
    Size {
        vm_commands: commands.len(),
        rom_textbook: commands.iter().map(|c| rom_words(c)).sum(),
        rom_shared: SHARED_ROUTINES + commands.iter().map(|c| rom_words_shared(c)).sum::<usize>(),
    }
}
