//! The compiling engine: each VM function translated to native code with
//! Cranelift (module `translate`, blocks from module `blocks`), run by a
//! dispatcher that hands every instruction compiled code does not take to
//! the interpreter (`exec.rs`), one at a time, until compiled code can take
//! over again at the start of a block. The interpreter stays the oracle:
//! compiled code changes the machine exactly as the interpreter would,
//! counting steps per block and leaving before any stretch of blocks that
//! could cross the stop (budget or key change), so every stop falls on the
//! same instruction.
//!
//! Calls and returns between VM functions run in compiled code (a compiled
//! function calls its callee's directly), except a call to a watched
//! function and the return from a watched call, which the interpreter runs
//! with the watcher's callbacks, and every call and return while the
//! function profile is on. Small callees, and chains of small callees
//! calling each other, run inline in their caller's code: their frames go
//! to RAM as the calls write them, and onto the frame stack only where
//! compiled code leaves inside them.

mod blocks;
mod builtin;
mod code_map;
mod translate;

use crate::exec::{Flow, Halt};
use crate::machine::{Frame, Machine, Watcher, MAX_DEPTH, THAT_ZERO};
use crate::program::{Code, FnId, Op, Program};
use crate::timing::{self, Timing};
use cranelift_codegen::ir::{types, AbiParam, UserFuncName};
use cranelift_codegen::settings::{self, Configurable};
use cranelift_frontend::FunctionBuilderContext;
use cranelift_jit::{JITBuilder, JITModule};
use cranelift_module::{default_libcall_names, FuncId, Linkage, Module};
use jack_os::{Os, Profile, Ram, RAM_SIZE};
use std::time::{Duration, Instant};

/// Which engine runs a [`Machine`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
// The hidden variant is a test switch, not a reserved future variant.
#[allow(clippy::manual_non_exhaustive)]
pub enum Engine {
    /// The interpreter first, then compiled code once the program's
    /// machines have run [`AUTO_THRESHOLD`] steps on the interpreter
    /// between them (see [`crate::Machine::engine`]): short runs never pay
    /// for compiling, long ones run compiled. The interpreter alone where
    /// Cranelift cannot target the host.
    Auto,
    /// The interpreter (`exec.rs`) alone.
    Interp,
    /// VM functions compiled to native code with Cranelift, with the
    /// interpreter for what compiled code leaves to it; the interpreter
    /// alone where Cranelift cannot target the host.
    Native,
    /// `Native` with `sub` translated wrongly (operands swapped), so that
    /// tests can show the differential tests catch a broken translation.
    #[doc(hidden)]
    NativeBrokenSub,
}

impl Default for Engine {
    /// `HACK_VM_ENGINE=auto|native|interp` if set (how the test suites run
    /// on each engine), else `Auto`.
    fn default() -> Engine {
        match std::env::var("HACK_VM_ENGINE").as_deref() {
            Ok("native") => Engine::Native,
            Ok("interp") => Engine::Interp,
            _ => Engine::Auto,
        }
    }
}

/// The interpreted steps after which [`Engine::Auto`] compiles: 100 M, about
/// what the interpreter runs (0.66-0.75 G VM instructions per CPU second on
/// the raymarcher) in the time compiling the seed program takes (0.13-0.18 s,
/// docs/performance.md). A run that stops below it never compiles; one that
/// goes on has spent at most about as long interpreting as compiling would
/// have cost, so Auto is never much more than twice as slow as the better of
/// the two engines, and on long runs (the whole `Main.main`, 21 G steps) the
/// compile time is under 2% of the run.
pub const AUTO_THRESHOLD: u64 = 100_000_000;

impl std::str::FromStr for Engine {
    type Err = String;

    fn from_str(s: &str) -> Result<Engine, String> {
        match s {
            "auto" => Ok(Engine::Auto),
            "interp" => Ok(Engine::Interp),
            "native" => Ok(Engine::Native),
            _ => Err(format!("unknown engine {s:?} (auto, interp or native)")),
        }
    }
}

/// A deliberate translation error (see [`Engine::NativeBrokenSub`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Fault {
    SubSwapped,
}

/// Code a compiled function returns: it returned into its compiled caller.
pub(crate) const RETURNED: i32 = -1;
/// Code: continue in compiled code at `Ctx::pc` of function `Ctx::cur`.
pub(crate) const CONTINUE: i32 = -2;
/// Code: a built-in called from compiled code ended the run, with
/// `Ctx::stopped`.
pub(crate) const STOPPED: i32 = -3;
/// The bit that marks a compiled call in place of a block index, beside
/// the RET word it wrote in the low 16 bits: the registers come as the
/// entry's other arguments, not in the context, and the call's frame stack
/// entry is written only if the callee leaves compiled code.
pub(crate) const CALLED: u32 = 1 << 31;
/// Compiled functions nested deeper than this leave calls to the
/// interpreter, which bounds the host stack compiled code uses.
pub(crate) const NATIVE_DEPTH: u32 = 256;

/// The machine state compiled code works on (layout shared with
/// `translate`, which reads fields by offset).
#[repr(C)]
pub(crate) struct Ctx {
    pub ram: *mut i16,
    pub frames: *mut Frame,
    pub frames_len: u64,
    /// The frame stack's capacity, at most [`MAX_DEPTH`]; 0 where calls and
    /// returns must not run compiled (the function profile is on), which
    /// fails compiled code's room test for both.
    pub frames_cap: u64,
    /// Compiled calls run while `frames_len` is below this: the capacity,
    /// and at most [`NATIVE_DEPTH`] frames above its length on entering
    /// compiled code (0 where `frames_cap` is).
    pub frames_limit: u64,
    /// One byte per function, nonzero where the watcher wants its calls:
    /// a compiled call to it leaves for the interpreter (a frame the
    /// interpreter pushed for a watched call is marked `Frame::watched`,
    /// and compiled code does not return through it).
    pub watch: *const u8,
    /// Nonzero where the watch set names some function: the outermost call
    /// of an inline run then tests the functions its nested runs call.
    pub any_watched: u8,
    pub steps: u64,
    pub stop_at: u64,
    pub sp: u16,
    pub lcl: u16,
    pub arg: u16,
    pub this: u16,
    pub that: u16,
    pub nargs: u16,
    pub flags: u8,
    pub cur: u32,
    pub pc: u32,
    /// The OS and the RAM, for built-ins called from compiled code
    /// (`builtin::call`); `ram` points into `ram_obj`'s words.
    pub os: *mut Os,
    pub ram_obj: *mut Ram,
    /// What a built-in called from compiled code stopped the run with
    /// (with the code [`STOPPED`]).
    pub stopped: Option<Halt>,
}

/// A compiled function: (context, block index or [`CALLED`] | RET word,
/// and for a call the caller's SP, THIS | THAT << 16, the argument count |
/// the entry flags << 16, the step count) -> (code, step count). The
/// dispatcher enters at a block with the registers in the context, and
/// finds them there on the way out; a compiled call gets them as
/// arguments, and on [`RETURNED`] reads the caller's from the frame it
/// wrote to RAM.
type Entry = unsafe extern "C" fn(*mut Ctx, i32, u32, u32, u32, u64) -> Exit;

/// What a compiled function returns (two registers).
#[repr(C)]
struct Exit {
    code: i32,
    steps: u64,
}

/// A program's compiled code: one native function per VM function, and for
/// each instruction the function it belongs to and the index of the block
/// starting there (`NO_BLOCK` if none), which is where compiled code of
/// that function can be entered.
pub(crate) struct Native {
    module: Option<JITModule>,
    entries: Vec<Entry>,
    block_at: Vec<(FnId, u32)>,
    /// A watch set naming no function (one byte per function).
    unwatched: Vec<bool>,
    compile_time: Duration,
}

const NO_BLOCK: u32 = u32::MAX;

// SAFETY: after `finalize_definitions` the module is only kept to own the
// code's memory (freed in `Drop`, with exclusive access); the entries point
// into that memory, which is never written again. Running the code from
// several threads at once is sound: it only touches the `Ctx` it is given.
unsafe impl Send for Native {}
unsafe impl Sync for Native {}

impl Drop for Native {
    fn drop(&mut self) {
        if let Some(module) = self.module.take() {
            // SAFETY: the last owner of the code is going; no entry is
            // running (a running machine holds an `Arc` to this).
            unsafe { module.free_memory() }
        }
    }
}

impl std::fmt::Debug for Native {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Native")
            .field("functions", &self.entries.len())
            .field("compile_time", &self.compile_time)
            .finish()
    }
}

impl Native {
    /// Compile every function of `program` for this host, `Err` naming
    /// why not (a host Cranelift cannot target, or a translation error);
    /// with the code map written where `HACK_VM_CODE_MAP` names a file.
    pub(crate) fn compile(
        program: &Program,
        profile: Profile,
        divide: jack_os::DivideRule,
        fault: Option<Fault>,
    ) -> Result<Native, String> {
        let Some(path) = code_map::wanted() else {
            return Native::compile_mapped(program, profile, divide, fault, None);
        };
        let mut map = String::new();
        let native = Native::compile_mapped(program, profile, divide, fault, Some(&mut map))?;
        std::fs::write(&path, map).map_err(|e| format!("code map {}: {e}", path.display()))?;
        Ok(native)
    }

    /// [`Native::compile`], with the code map appended to `map` if given.
    fn compile_mapped(
        program: &Program,
        profile: Profile,
        divide: jack_os::DivideRule,
        fault: Option<Fault>,
        mut map: Option<&mut String>,
    ) -> Result<Native, String> {
        let started = Instant::now();
        let mut flags = settings::builder();
        let set = |f: &mut settings::Builder, k: &str, v: &str| {
            f.set(k, v).map_err(|e| format!("cranelift flag {k}: {e}"))
        };
        set(&mut flags, "opt_level", "speed")?;
        set(&mut flags, "use_colocated_libcalls", "false")?;
        set(&mut flags, "is_pic", "false")?;
        set(
            &mut flags,
            "enable_verifier",
            if cfg!(debug_assertions) {
                "true"
            } else {
                "false"
            },
        )?;
        let isa = cranelift_native::builder()
            .map_err(|e| format!("host not supported by Cranelift: {e}"))?
            .finish(settings::Flags::new(flags))
            .map_err(|e| format!("cranelift: {e}"))?;
        let mut module = JITModule::new(JITBuilder::with_isa(isa, default_libcall_names()));
        let mut sig = module.make_signature();
        for t in [
            types::I64,
            types::I32,
            types::I32,
            types::I32,
            types::I32,
            types::I64,
        ] {
            sig.params.push(AbiParam::new(t));
        }
        sig.returns.push(AbiParam::new(types::I32));
        sig.returns.push(AbiParam::new(types::I64));
        // Named for the VM functions, which is how Cranelift's perf map
        // (written when `perf record` runs the process) names their code.
        let ids: Vec<FuncId> = program
            .functions
            .iter()
            .map(|f| {
                module
                    .declare_function(&f.name, Linkage::Local, &sig)
                    .map_err(|e| format!("cranelift: {e}"))
            })
            .collect::<Result<_, _>>()?;
        let target = module.target_config();
        let timing = Timing::of(profile);
        let code = &program.code[timing::index(profile)].plain;
        let mut block_at = vec![(0, NO_BLOCK); code.len()];
        let plans: Vec<Plan> = program
            .functions
            .iter()
            .map(|f| Plan::of(code, f, timing))
            .collect();
        let frames_intact = frames_intact(code, &plans, profile);
        let mut ctx = module.make_context();
        let mut fctx = FunctionBuilderContext::new();
        for (i, &id) in ids.iter().enumerate() {
            ctx.func.signature = sig.clone();
            ctx.func.name = UserFuncName::user(0, id.as_u32());
            let f = &program.functions[i];
            let Plan {
                start,
                blocks: ref vm_blocks,
                ref starts,
                ref depths,
            } = plans[i];
            for (k, b) in starts.iter().enumerate() {
                block_at[start as usize + k] = (i as FnId, b.unwrap_or(NO_BLOCK));
            }
            let mut callee = |func: &mut cranelift_codegen::ir::Function, callee: FnId| {
                module.declare_func_in_func(ids[callee as usize], func)
            };
            translate::translate(
                cranelift_frontend::FunctionBuilder::new(&mut ctx.func, &mut fctx),
                translate::Env {
                    program,
                    code,
                    start,
                    timing,
                    id: i as FnId,
                    blocks: vm_blocks,
                    block_at: starts,
                    depths: depths.as_deref(),
                    frames_intact,
                    profile,
                    divide,
                    fault,
                    target,
                    callee: &mut callee,
                },
            );
            module
                .define_function(id, &mut ctx)
                .map_err(|e| format!("cranelift, function {}: {e:?}", f.name))?;
            if let Some(map) = map.as_deref_mut() {
                let compiled = ctx.compiled_code().expect("just compiled");
                code_map::record(map, &f.name, code, compiled);
            }
            module.clear_context(&mut ctx);
        }
        module
            .finalize_definitions()
            .map_err(|e| format!("cranelift: {e}"))?;
        let entries = ids
            .iter()
            .map(|&id| {
                let p = module.get_finalized_function(id);
                // SAFETY: every function was defined with `sig`, which is
                // this type under the host's default calling convention.
                unsafe { std::mem::transmute::<*const u8, Entry>(p) }
            })
            .collect();
        Ok(Native {
            module: Some(module),
            entries,
            block_at,
            unwatched: vec![false; program.functions.len()],
            compile_time: started.elapsed(),
        })
    }

    /// How long compiling took.
    pub(crate) fn compile_time(&self) -> Duration {
        self.compile_time
    }
}

/// One function's code as the translator takes it: its first
/// instruction, its blocks and the block at each instruction
/// ([`blocks::blocks`]), and its static stack depths, if it has them
/// ([`blocks::static_depths`]).
struct Plan {
    start: u32,
    blocks: Vec<blocks::Block>,
    starts: Vec<Option<u32>>,
    depths: Option<Vec<Option<i32>>>,
}

impl Plan {
    fn of(code: &[Op], f: &crate::program::Function, timing: Timing) -> Plan {
        let (start, end) = extent(code, f, timing);
        // Where a run may stand in this function other than at a block
        // that compiled code reaches: the body of a function without a
        // `function` line (the start of `__implicit`).
        let entries: &[u32] = if start == f.start || f.headed {
            &[]
        } else {
            std::slice::from_ref(&f.start)
        };
        let (blocks, starts) = blocks::blocks(code, start, end, entries);
        let end = blocks::code_end(&blocks, start);
        // A call lands on the `function` line (SP = LCL) or on the body.
        let entry_depth = match code[start as usize] {
            Op::Function { .. } => 0,
            _ => i32::from(f.n_vars),
        };
        let depths = f
            .headed
            .then(|| blocks::static_depths(code, start, end, entry_depth))
            .flatten();
        Plan {
            start,
            blocks,
            starts,
            depths,
        }
    }
}

/// Whether no code that runs compiled can write a word of a saved frame
/// (RET, LCL, ARG, THIS, THAT of a call in progress), so that a compiled
/// call's return may keep the caller's registers instead of reading them
/// back: on the desktop (whose `this`, `that`, `Memory.poke` and built-in
/// writes lie in the heap and the screen, above the stack, or leave
/// compiled code), where every function's stack depths are static and
/// never pop below its LCL (its saved frame), and no `pop constant`
/// writes into the stack. A callee's `local` and `argument` words lie
/// above and below the frame its call wrote, and a deeper callee's above.
fn frames_intact(code: &[Op], plans: &[Plan], profile: Profile) -> bool {
    profile == Profile::Desktop
        && !code.iter().any(|&op| blocks::pops_into_stack(op))
        && plans.iter().all(|p| {
            p.depths
                .as_deref()
                .is_some_and(|d| blocks::pops_stay_above(code, p.start, d, 0))
        })
}

/// The instructions `start..end` of function `f` in `code` that compiled
/// code runs: from the instruction a call lands on (its `function` line
/// where that is a step, crate::timing, else its body), through its
/// `Halt` and the wasted-step jumps after it.
fn extent(code: &[Op], f: &crate::program::Function, timing: Timing) -> (u32, u32) {
    let start = f.start - u32::from(timing.function_step);
    let halt = f.start as usize
        + code[f.start as usize..]
            .iter()
            .position(|op| *op == Op::Halt)
            .expect("every function ends in Halt");
    let jumps = code[halt + 1..]
        .iter()
        .take_while(|op| matches!(op, Op::Goto(_)))
        .count();
    (start, (halt + 1 + jumps) as u32)
}

/// Whether `a` is an ordinary word (not a register, inside RAM).
pub(crate) fn plain_address(a: u16) -> bool {
    (5..RAM_SIZE).contains(&usize::from(a))
}

impl Machine {
    /// Run until the step count reaches `stop_at` or the run ends: compiled
    /// code where a block starts, the interpreter for one instruction
    /// wherever compiled code stops.
    pub(crate) fn exec_native<const W: bool>(
        &mut self,
        program: &Program,
        code: &Code,
        native: &Native,
        stop_at: u64,
        watch: &mut Option<(&[bool], &mut dyn Watcher)>,
    ) -> Flow {
        // The watch set as compiled code reads it: a byte per function
        // (a shorter set leaves the rest unwatched).
        let padded: Vec<bool>;
        let set: Option<&[bool]> = watch.as_ref().map(|(set, _)| *set).filter(|_| W);
        let n = native.unwatched.len();
        let watched: &[bool] = match set.map(|set| (set, set.get(..n))) {
            Some((_, Some(prefix))) => prefix,
            Some((set, None)) => {
                padded = (0..n)
                    .map(|i| set.get(i).copied().unwrap_or(false))
                    .collect();
                &padded
            }
            None => &native.unwatched,
        };
        let any_watched = set.is_some_and(|set| set.contains(&true));
        loop {
            if self.steps >= stop_at {
                return Flow::Limit;
            }
            // (A host call's return leaves PC in the callee: no block then.)
            let (owner, block) = native.block_at[self.pc as usize];
            // (Compiled code leaves the desktop's `that` from word 0 to
            // the interpreter: it never runs with THAT_ZERO set.)
            if block != NO_BLOCK && owner == self.cur && self.flags & THAT_ZERO == 0 {
                let before = self.steps;
                let entered = self.enter_native(native, block, stop_at, watched, any_watched);
                self.compiled_steps += self.steps - before;
                match entered {
                    Err(halt) => return self.end_at(halt),
                    Ok(CONTINUE) => continue,
                    Ok(_) => {}
                }
            }
            if self.steps >= stop_at {
                return Flow::Limit;
            }
            if let Flow::End(exit) = self.exec::<W>(program, code, false, self.steps + 1, watch) {
                return Flow::End(exit);
            }
        }
    }

    /// Run compiled code from block `block` of the current function, with
    /// `watched` (a flag per function) the functions whose calls it leaves
    /// to the interpreter (`any_watched`: whether it names any).
    /// Its code (`Err`: a built-in it called ended the run).
    fn enter_native(
        &mut self,
        native: &Native,
        block: u32,
        stop_at: u64,
        watched: &[bool],
        any_watched: bool,
    ) -> Result<i32, Halt> {
        let ram_obj: *mut Ram = &mut self.ram;
        // SAFETY: `ram_obj` was just made from `self.ram`, which nothing
        // else borrows while compiled code runs.
        let w = unsafe { (*ram_obj).words_mut() };
        let reg = |i: usize| w[i] as u16;
        let mut ctx = Ctx {
            ram: std::ptr::null_mut(),
            frames: self.frames.as_mut_ptr(),
            frames_len: self.frames.len() as u64,
            frames_cap: if self.profile.is_none() {
                self.frames.capacity().min(MAX_DEPTH) as u64
            } else {
                0
            },
            steps: self.steps,
            stop_at,
            sp: reg(0),
            lcl: reg(1),
            arg: reg(2),
            this: reg(3),
            that: reg(4),
            nargs: self.nargs,
            flags: self.flags,
            cur: self.cur,
            pc: self.pc,
            frames_limit: 0,
            watch: watched.as_ptr().cast(),
            any_watched: u8::from(any_watched),
            os: &mut self.os,
            ram_obj,
            stopped: None,
        };
        ctx.frames_limit = ctx.frames_cap.min(ctx.frames_len + u64::from(NATIVE_DEPTH));
        ctx.ram = w.as_mut_ptr();
        let entered_len = ctx.frames_len;
        // SAFETY: the entry was compiled for this program and function; it
        // reads and writes RAM words 5..RAM_SIZE only (all it checks), and
        // frame slots below `frames_cap`, setting `frames_len` to cover
        // exactly the slots it filled.
        let exit = unsafe { native.entries[self.cur as usize](&mut ctx, block as i32, 0, 0, 0, 0) };
        // Compiled code pushes frames only below the limit its calls test
        // (a broken test would write past the frame stack's capacity).
        assert!(
            ctx.frames_len <= ctx.frames_limit.max(entered_len),
            "compiled code left {} frames, past its limit {}",
            ctx.frames_len,
            ctx.frames_limit
        );
        // SAFETY: see above: slots 0..frames_len are initialised.
        unsafe { self.frames.set_len(ctx.frames_len as usize) };
        let w = self.ram.words_mut();
        for (i, r) in [ctx.sp, ctx.lcl, ctx.arg, ctx.this, ctx.that]
            .into_iter()
            .enumerate()
        {
            w[i] = r as i16;
        }
        // Whatever code leaves compiled code with, the state is in the
        // context (the step count also comes back in a register).
        debug_assert_eq!(exit.steps, ctx.steps);
        self.steps = ctx.steps;
        self.pc = ctx.pc;
        self.cur = ctx.cur;
        self.nargs = ctx.nargs;
        self.flags = ctx.flags;
        match ctx.stopped {
            Some(halt) => Err(halt),
            None => Ok(exit.code),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{frames_intact, Plan};
    use crate::program::Program;
    use crate::timing::{self, Timing};
    use jack_os::Profile;

    fn intact(src: &str, profile: Profile) -> bool {
        let program = Program::from_sources(&[("Main.vm", src)]).expect("it loads");
        let timing = Timing::of(profile);
        let code = &program.code[timing::index(profile)].plain;
        let plans: Vec<Plan> = program
            .functions
            .iter()
            .map(|f| Plan::of(code, f, timing))
            .collect();
        frames_intact(code, &plans, profile)
    }

    /// A compiled call's return keeps the caller's registers only on the
    /// desktop, and only where no function pops below its LCL (onto its
    /// saved frame), every function's depths are static, and no `pop
    /// constant` writes into the stack.
    #[test]
    fn frames_stay_intact_only_where_no_code_can_write_them() {
        let program = "function Main.main 1\npush constant 3\ncall Main.g 1\npop local 0\n\
                       push constant 0\nreturn\nfunction Main.g 0\npush argument 0\nreturn\n";
        assert!(intact(program, Profile::Desktop));
        assert!(!intact(program, Profile::Web));
        let edits = [
            // Main.g pops the saved THAT (its stack is empty).
            (
                "push argument 0\nreturn",
                "pop temp 0\npush constant 1\nreturn",
            ),
            // Two paths reach `return` with different depths.
            (
                "push argument 0\nreturn",
                "push argument 0\nif-goto A\npush constant 2\nlabel A\npush constant 1\nreturn",
            ),
            ("pop local 0", "pop constant 300"),
        ];
        for (from, to) in edits {
            let edited = program.replace(from, to);
            assert_ne!(edited, program);
            assert!(!intact(&edited, Profile::Desktop), "{to}");
        }
        // A `pop constant` below the stack writes no frame.
        assert!(intact(
            &program.replace("pop local 0", "pop constant 200"),
            Profile::Desktop
        ));
    }
}
