//! A [`Machine`]: RAM, registers, OS state and the Jack call stack of one
//! running program. `Clone` takes a snapshot; clones run independently
//! (and in parallel: a `Machine` is `Send`).

use crate::exec::Flow;
use crate::exit::{CallStack, Exit};
use crate::native::{Engine, Fault, Native, AUTO_THRESHOLD};
use crate::program::{FnId, Program};
use crate::tier::Tier;
use crate::timing::{self, Timing};
use jack_os::{Builtin, Completion, KeyScript, Os, Profile, Ram, Stop, KBD};
use std::sync::Arc;

/// A register that a test script may preset (`set sp 261`, `set local 300`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Register {
    /// RAM[0].
    Sp,
    /// RAM[1]; presetting it makes `local` usable in the entry function.
    Local,
    /// RAM[2]; presetting it makes `argument` usable in the entry function.
    Argument,
    /// RAM[3]; presetting it counts as `pop pointer 0` for the entry.
    This,
    /// RAM[4]; presetting it counts as `pop pointer 1` for the entry.
    That,
}

/// Per-invocation flags.
pub(crate) const THIS_OK: u8 = 1;
pub(crate) const THAT_OK: u8 = 2;
pub(crate) const LOCAL_OK: u8 = 4;
pub(crate) const ARG_OK: u8 = 8;
/// The invocation has at least `arg_reach` arguments (see [`crate::Function`]).
pub(crate) const ARGS_FIT: u8 = 16;
/// Desktop: the last `pop pointer 1` stored 0, so `that` reaches from word 0
/// (the desktop's `that` range starts at the pointer it was given); a
/// return, or a `pop pointer 1` of any other value, clears it. A callee
/// inherits it, its frame keeps the caller's flags without it, and
/// compiled code never runs while it is set (see [`crate::exec`]).
pub(crate) const THAT_ZERO: u8 = 32;
/// Desktop, inside the interpreter's loop only (never in a machine's or a
/// frame's flags): every `this i` (`that i`) with `i` below [`NEAR`]
/// passes the desktop's address test with the pointer as it is. A fused
/// operand's `need` (desktop code) holds the bit of its pointer.
pub(crate) const NEAR_THIS: u8 = 64;
pub(crate) const NEAR_THAT: u8 = 128;
/// The `this`/`that` offsets that [`NEAR_THIS`] and [`NEAR_THAT`] cover;
/// desktop code fuses no access at a larger one.
pub(crate) const NEAR: u16 = 64;

/// `ret_pc` of the frame below a call made by [`Machine::call`].
pub(crate) const HOST: u32 = u32::MAX;

/// A frame of the internal call stack: what to restore in the caller.
/// `repr(C)`: compiled code reads and writes frames by field offset.
#[derive(Clone, Copy, Debug)]
#[repr(C)]
pub(crate) struct Frame {
    pub caller: FnId,
    pub ret_pc: u32,
    /// The RET word written to RAM; if RAM still holds it, `ret_pc` is right.
    pub ret: i16,
    pub nargs: u16,
    pub flags: u8,
    pub watched: bool,
}

/// Deepest Jack call stack before the run stops with a runtime error
/// (the web IDE has no limit; this keeps a runaway recursion from
/// exhausting host memory before the instruction budget does).
pub const MAX_DEPTH: usize = 1 << 22;

/// Options of a [`Machine`].
#[derive(Clone, Debug, Default)]
pub struct Config {
    /// Which official tool the OS follows.
    pub profile: Profile,
    /// `Math.divide`'s rounding in place of the profile's (`None`: the
    /// profile's own, [`jack_os::DivideRule::of`]); every other rule stays
    /// the profile's.
    pub divide: Option<jack_os::DivideRule>,
    /// Keyboard input over time.
    pub keys: KeyScript,
    /// Count instructions per function (see [`Machine::function_profile`]).
    pub profile_functions: bool,
    /// Interpreter, compiled code, or the first then the second (default:
    /// `HACK_VM_ENGINE`, else [`Engine::Auto`]).
    pub engine: Engine,
    /// [`Engine::Auto`]'s threshold in place of [`crate::AUTO_THRESHOLD`]
    /// (tests set a small one to switch engines inside short runs).
    #[doc(hidden)]
    pub auto_threshold: Option<u64>,
}

/// Observer of calls to chosen functions (see [`Machine::run_watched`]).
pub trait Watcher {
    /// `function` is being called with `args` (VM order: `this` first);
    /// `ram` is the memory at the call, so objects the arguments point to
    /// can be read before the callee changes them.
    fn on_call(&mut self, program: &Program, function: FnId, args: &[i16], ram: &Ram);
    /// `function` returned `value`; `ram` is the memory after the return.
    fn on_return(&mut self, program: &Program, function: FnId, value: i16, ram: &Ram);
}

/// One emulated Hack VM with its OS.
#[derive(Clone, Debug)]
pub struct Machine {
    pub(crate) program: Arc<Program>,
    pub(crate) ram: Ram,
    pub(crate) os: Os,
    pub(crate) steps: u64,
    pub(crate) pc: u32,
    pub(crate) cur: FnId,
    pub(crate) nargs: u16,
    pub(crate) flags: u8,
    pub(crate) frames: Vec<Frame>,
    /// Set once the run has ended for good (halt, error, return from entry).
    pub(crate) ended: Option<Exit>,
    /// Per-function exclusive instruction counts, when profiling.
    pub(crate) profile: Option<Vec<u64>>,
    pub(crate) profile_mark: u64,
    pub(crate) scratch: Vec<i16>,
    /// The step at which the keyboard word is next set from the key script
    /// (0: not yet). Between changes the word keeps whatever the program
    /// stored there, however the run is split into calls.
    pub(crate) next_key_sync: u64,
    /// The desktop's start-up step is still to be taken (by a run from the entry).
    pub(crate) startup_pending: bool,
    /// The program's compiled code, when the compiling engine runs.
    pub(crate) native: Option<Arc<Native>>,
    /// Of `steps`, those compiled code ran (see [`Machine::compiled_steps`]).
    pub(crate) compiled_steps: u64,
    /// An [`Engine::Auto`] machine still on the interpreter.
    pub(crate) tier: Option<Tier>,
    /// The step at which the current run's budget ends (`u64::MAX`: none).
    pub(crate) budget_end: u64,
    /// Web: a blocking built-in whose result was still to be handed back
    /// when the budget ended (see [`Machine::web_blocking_call`]).
    pub(crate) pending: Option<Box<Pending>>,
    /// Web: a return resumed its caller past the caller's last command;
    /// the next step fails with this message, as in the web IDE.
    pub(crate) beyond_end: Option<String>,
}

/// A web blocking call the budget interrupted: the built-in, its argument
/// count, and the machine's memory and OS from before the call (the call
/// is made again from there when the run goes on).
#[derive(Clone, Debug)]
pub(crate) struct Pending {
    builtin: Builtin,
    nargs: u16,
    /// The call's step: the read watches the keys from there.
    at: u64,
    ram: Ram,
    os: Os,
}

impl Machine {
    /// A machine after reset (spec §1), positioned at the entry function
    /// with no frame (§2.6): SP=256, LCL=ARG=THIS=THAT=0. Under the desktop
    /// profile it stands at the entry's `function` line, or, with the
    /// synthetic `Sys.init`, before the desktop's start-up step, which the
    /// first run from the entry takes (see [`crate::timing`]; host calls
    /// do not take it).
    pub fn new(program: Arc<Program>, config: Config) -> Machine {
        let mut ram = Ram::new();
        let timing = Timing::of(config.profile);
        let divide = config
            .divide
            .unwrap_or(jack_os::DivideRule::of(config.profile));
        let mut os = Os::with_divide(config.profile, divide, config.keys);
        os.reset(&mut ram);
        let entry = program.entry;
        let profile = config
            .profile_functions
            .then(|| vec![0; program.functions.len()]);
        let native = match config.engine {
            Engine::Interp | Engine::Auto => None,
            Engine::Native => program.native(config.profile, divide).ok(),
            Engine::NativeBrokenSub => {
                Native::compile(&program, config.profile, divide, Some(Fault::SubSwapped))
                    .ok()
                    .map(Arc::new)
            }
        };
        let f = &program.functions[entry as usize];
        let at_head = timing.function_step && f.headed;
        let mut machine = Machine {
            pc: f.start - u32::from(at_head),
            program,
            ram,
            os,
            steps: 0,
            compiled_steps: 0,
            cur: entry,
            nargs: 0,
            flags: 0,
            frames: Vec::with_capacity(256),
            ended: None,
            profile,
            profile_mark: 0,
            scratch: Vec::new(),
            next_key_sync: 0,
            startup_pending: false,
            native,
            tier: (config.engine == Engine::Auto)
                .then(|| Tier::new(config.auto_threshold.unwrap_or(AUTO_THRESHOLD))),
            budget_end: u64::MAX,
            pending: None,
            beyond_end: None,
        };
        machine.startup_pending = timing.hidden_sys_init && machine.program.synthetic_entry;
        if timing.hidden_sys_init && !machine.program.synthetic_entry {
            // The desktop writes the heap header only in its built-in
            // Memory.init, which a program with its own entry may never call.
            machine.ram.write(2048, 0);
            machine.ram.write(2049, 0);
        }
        machine
    }

    /// The engine that runs this machine now: [`Engine::Interp`] if that
    /// was asked for, the program could not be compiled for this host, or
    /// an [`Engine::Auto`] machine has not switched (yet).
    pub fn engine(&self) -> Engine {
        match &self.native {
            None => Engine::Interp,
            Some(_) => Engine::Native,
        }
    }

    /// The desktop's first step, a hidden `call Sys.init` of its built-in,
    /// which calls the OS inits and then `Main.main` through frames (a call
    /// that `watch` sees like any other).
    fn desktop_startup(&mut self, watch: &mut Option<(&[bool], &mut dyn Watcher)>) {
        let p = Arc::clone(&self.program);
        let size = i16::try_from(p.command_lines + 5).unwrap_or(i16::MAX);
        // The built-in Sys.init's Memory.init writes the heap header (the
        // other OS inits change no RAM).
        let mut clock = self.steps;
        self.os
            .call(Builtin::MemoryInit, &[], &mut self.ram, &mut clock);
        let before = [0, 1, 2, 3, 4].map(|a| self.ram.read(a));
        let (words, regs) = timing::desktop_startup(size, before);
        for (a, v) in (i32::from(before[0])..).zip(words) {
            self.ram.write(a, v);
        }
        for (a, v) in (0..).zip(regs) {
            self.ram.write(a, v);
        }
        let sys_init = &p.functions[p.entry as usize];
        let main = p
            .function_id("Main.main")
            .expect("a synthetic Sys.init calls Main.main");
        let mut watched = false;
        if let Some((set, watcher)) = watch {
            if set.get(main as usize).copied().unwrap_or(false) {
                watcher.on_call(&p, main, &[], &self.ram);
                watched = true;
            }
        }
        self.frames.push(Frame {
            caller: p.entry,
            ret_pc: *sys_init.resume.last().expect("the end of Sys.init"),
            ret: -1,
            nargs: 0,
            flags: 0,
            watched,
        });
        self.steps += 1;
        self.charge_profile();
        self.cur = main;
        self.nargs = 0;
        self.flags = p.functions[main as usize].entry_flags(0);
        self.pc = p.functions[main as usize].start - 1;
    }

    /// The program this machine runs.
    pub fn program(&self) -> &Arc<Program> {
        &self.program
    }

    /// VM instructions executed so far (labels are free, a call is one).
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Of [`Machine::steps`], those run by compiled code (built-ins it
    /// called included); the interpreter ran the rest. 0 on the
    /// interpreter, and before an Auto machine switches.
    pub fn compiled_steps(&self) -> u64 {
        self.compiled_steps
    }

    /// The memory.
    pub fn ram(&self) -> &Ram {
        &self.ram
    }

    /// The memory, for presetting words like a test script's `set RAM[i] v`.
    pub fn ram_mut(&mut self) -> &mut Ram {
        &mut self.ram
    }

    /// The OS state (cursor, heap, profile, keys).
    pub fn os(&self) -> &Os {
        &self.os
    }

    /// Run the OS built-in `builtin` (for example `Memory.alloc`) from the
    /// host with `args` (VM order), on this machine's RAM and OS state, as a
    /// program's call of it would.
    pub fn call_builtin(&mut self, builtin: Builtin, args: &[i16]) -> Completion {
        self.os.call(builtin, args, &mut self.ram, &mut self.steps)
    }

    /// Preset a register like a test script's `set sp|local|argument|this|that`,
    /// which also marks that segment initialised for the entry function.
    pub fn set_register(&mut self, reg: Register, value: i16) {
        let (addr, flag) = match reg {
            Register::Sp => (0, 0),
            Register::Local => (1, LOCAL_OK),
            Register::Argument => (2, ARG_OK),
            Register::This => (3, THIS_OK),
            Register::That => (4, THAT_OK),
        };
        self.ram.write(addr, value);
        self.flags |= flag;
    }

    /// The Jack call stack, outermost first, innermost (running) last,
    /// with a recursion's frames collapsed (see [`CallStack`]).
    pub fn call_stack(&self) -> CallStack {
        let p = &self.program;
        let mut stack = CallStack::default();
        let callers = self
            .frames
            .iter()
            .filter(|f| f.ret_pc != HOST)
            .map(|f| f.caller);
        let mut run: Option<(FnId, u64)> = None;
        for id in callers.chain([self.cur]) {
            match &mut run {
                Some((last, n)) if *last == id => *n += 1,
                _ => {
                    if let Some((last, n)) = run {
                        stack.push_run(p.function_name(last), n);
                    }
                    run = Some((id, 1));
                }
            }
        }
        if let Some((last, n)) = run {
            stack.push_run(p.function_name(last), n);
        }
        stack
    }

    /// The function a test script's `currentFunction` names: the running
    /// one, except where the machine stands at a called function's
    /// `function` line under the desktop profile, whose call stack takes
    /// the callee on only when that line runs (the caller is named then).
    pub fn current_function(&self) -> &str {
        let f = &self.program.functions[self.cur as usize];
        let at_function_line = f.headed && self.pc + 1 == f.start;
        match self.frames.last() {
            Some(fr) if at_function_line && Timing::of(self.os.profile()).function_step => {
                self.program.function_name(fr.caller)
            }
            _ => &f.name,
        }
    }

    /// The index in its function of the command the next step runs, as
    /// the desktop counts it (the `function` line 0, labels not counted):
    /// what a test script's `line` prints, with
    /// [`Machine::current_function`].
    pub fn next_command_index(&self) -> Option<u32> {
        let p = &self.program;
        let k = p.functions.partition_point(|f| f.start <= self.pc + 1);
        let f = p.functions.get(k.checked_sub(1)?)?;
        Some(f.desktop_index(self.pc))
    }

    /// How the run ended, if it has.
    pub fn exit(&self) -> Option<&Exit> {
        self.ended.as_ref()
    }

    /// Instructions per function (exclusive of callees), largest first;
    /// empty unless `Config::profile_functions` was set.
    pub fn function_profile(&self) -> Vec<(String, u64)> {
        let Some(counts) = &self.profile else {
            return Vec::new();
        };
        let mut v: Vec<(String, u64)> = counts
            .iter()
            .enumerate()
            .filter(|(_, &c)| c > 0)
            .map(|(i, &c)| (self.program.function_name(i as FnId).to_string(), c))
            .collect();
        v.sort_by(|a, b| b.1.cmp(&a.1).then_with(|| a.0.cmp(&b.0)));
        v
    }

    /// Run from where the machine stands (at first: the entry) for at most
    /// `budget` more instructions (`None`: no limit). After a
    /// [`Exit::Budget`] a further call continues; after any other end it
    /// returns that end again.
    pub fn run(&mut self, budget: Option<u64>) -> Exit {
        self.drive::<false>(budget, None)
    }

    /// Like [`Machine::run`], in slices of at most `every` instructions,
    /// telling `seen` the instruction count after each slice (for a
    /// progress bar on a long run). Ends as `run(budget)` would: slicing
    /// changes neither the count nor the machine's state.
    pub fn run_observed(
        &mut self,
        budget: Option<u64>,
        every: u64,
        seen: &mut dyn FnMut(u64),
    ) -> Exit {
        let every = every.max(1);
        let start = self.steps;
        loop {
            let left = budget.map(|b| b.saturating_sub(self.steps - start));
            let slice = left.map_or(every, |l| l.min(every));
            let exit = self.run(Some(slice));
            seen(self.steps);
            let more_budget = left.is_none_or(|l| l > slice);
            if !(matches!(exit, Exit::Budget { .. }) && more_budget) {
                return exit;
            }
        }
    }

    /// Like [`Machine::run`], telling `watcher` about every call to and
    /// return from a function whose id is `true` in `watch` (indexed by
    /// [`FnId`]).
    pub fn run_watched(
        &mut self,
        budget: Option<u64>,
        watch: &[bool],
        watcher: &mut dyn Watcher,
    ) -> Exit {
        self.drive::<true>(budget, Some((watch, watcher)))
    }

    /// Call function `name` with `args` (VM order) from the host, as if by
    /// `call name n` at the current stack top, and run it to its return for
    /// at most `budget` instructions. On [`Exit::Returned`] the stack is as
    /// before and the machine can take further calls; after any other end
    /// the machine stays where it stopped (clone a snapshot to retry).
    pub fn call(
        &mut self,
        name: &str,
        args: &[i16],
        budget: Option<u64>,
    ) -> Result<Exit, UnknownFunction> {
        self.call_inner::<false>(name, args, budget, None)
    }

    /// [`Machine::call`] with a watcher (see [`Machine::run_watched`]).
    pub fn call_watched(
        &mut self,
        name: &str,
        args: &[i16],
        budget: Option<u64>,
        watch: &[bool],
        watcher: &mut dyn Watcher,
    ) -> Result<Exit, UnknownFunction> {
        self.call_inner::<true>(name, args, budget, Some((watch, watcher)))
    }

    fn call_inner<const W: bool>(
        &mut self,
        name: &str,
        args: &[i16],
        budget: Option<u64>,
        mut watch: Option<(&[bool], &mut dyn Watcher)>,
    ) -> Result<Exit, UnknownFunction> {
        let callee = self
            .program
            .function_id(name)
            .ok_or_else(|| UnknownFunction(name.to_string()))?;
        if let Some(e) = &self.ended {
            return Ok(e.clone());
        }
        let nargs = u16::try_from(args.len())
            .map_err(|_| UnknownFunction(format!("{name} with {} arguments", args.len())))?;
        let saved = (self.pc, self.cur, self.nargs, self.flags);
        let base_depth = self.frames.len();
        for &a in args {
            let sp = self.ram.read(0);
            self.ram.write(sp as i32, a);
            self.ram.write(0, sp.wrapping_add(1));
        }
        let mut watched = false;
        if let Some((set, watcher)) = &mut watch {
            if set.get(callee as usize).copied().unwrap_or(false) {
                watcher.on_call(&self.program, callee, args, &self.ram);
                watched = true;
            }
        }
        // The frame below the callee: returning into it ends the call.
        self.frames.push(Frame {
            caller: self.cur,
            ret_pc: HOST,
            ret: 0,
            nargs: self.nargs,
            flags: self.flags,
            watched,
        });
        let function = &self.program.functions[callee as usize];
        let (start, n_vars) = (function.start, function.n_vars);
        if Timing::of(self.os.profile()).function_step {
            // The callee's `function` line zeroes its locals, as a step.
            self.enter(callee, nargs, 0, 0);
            self.pc = start - 1;
        } else {
            self.enter(callee, nargs, 0, n_vars);
            self.pc = start;
        }
        let exit = self.drive::<W>(budget, watch);
        if let Exit::Returned(_) = exit {
            debug_assert_eq!(self.frames.len(), base_depth);
            (self.pc, self.cur, self.nargs, self.flags) = saved;
            self.ended = None;
            // The return value sits on the stack top: pop it.
            let sp = self.ram.read(0);
            self.ram.write(0, sp.wrapping_sub(1));
        }
        Ok(exit)
    }

    /// Push a call frame (RET, LCL, ARG, THIS, THAT) in RAM and set up the
    /// callee's registers and zeroed locals; the internal frame is the
    /// caller's business.
    fn enter(&mut self, callee: FnId, nargs: u16, ret: i16, n_vars: u16) {
        let r = &mut self.ram;
        let base = r.read(0);
        let saved = [ret, r.read(1), r.read(2), r.read(3), r.read(4)];
        for (i, v) in saved.into_iter().enumerate() {
            r.write(base.wrapping_add(i as i16) as i32, v);
        }
        let lcl = base.wrapping_add(5);
        r.write(2, base.wrapping_sub(nargs as i16));
        r.write(1, lcl);
        for i in 0..n_vars {
            r.write(lcl.wrapping_add(i as i16) as i32, 0);
        }
        r.write(0, lcl.wrapping_add(n_vars as i16));
        self.cur = callee;
        self.nargs = nargs;
        self.flags = self.program.functions[callee as usize].entry_flags(nargs);
    }

    /// The outer loop: budget, key changes, choice of fused or exact code.
    fn drive<const W: bool>(
        &mut self,
        budget: Option<u64>,
        mut watch: Option<(&[bool], &mut dyn Watcher)>,
    ) -> Exit {
        if let Some(e) = &self.ended {
            return e.clone();
        }
        let budget_end = budget.map_or(u64::MAX, |b| self.steps.saturating_add(b));
        self.budget_end = budget_end;
        if self.startup_pending && self.frames.is_empty() && budget_end > self.steps {
            self.startup_pending = false;
            self.desktop_startup(&mut watch);
        }
        if budget_end > self.steps {
            if let Some(p) = self.pending.take() {
                // The interrupted blocking call, from the state before it.
                let Pending {
                    builtin,
                    nargs,
                    at,
                    ram,
                    os,
                } = *p;
                (self.ram, self.os) = (ram, os);
                // The keyboard word is set again from the script at this step.
                self.next_key_sync = 0;
                if let Some(exit) = self.web_blocking_call(builtin, nargs, at) {
                    self.ended = Some(exit.clone());
                    return exit;
                }
            }
        }
        self.sync_keyboard();
        let program = Arc::clone(&self.program);
        let code = &program.code[timing::index(self.os.profile())];
        let mut native = self.native.clone();
        let exit = loop {
            let mut switch = u64::MAX;
            if native.is_none() {
                switch = self.tier_limit();
                native = self.native.clone();
            }
            let key_change = self.next_key_sync;
            let limit = budget_end.min(key_change).min(switch);
            let soft = limit.saturating_sub(crate::fuse::MAX_FUSED_STEPS);
            let flow = if let Some(native) = &native {
                self.exec_native::<W>(&program, code, native, limit, &mut watch)
            } else if self.steps < soft {
                self.exec::<W>(&program, code, true, soft, &mut watch)
            } else if self.steps < limit {
                self.exec::<W>(&program, code, false, limit, &mut watch)
            } else {
                Flow::Limit
            };
            let flow = match flow {
                // A fused instruction declined: run its commands one by one.
                Flow::Deopt => {
                    let stop = limit.min(self.steps + crate::fuse::MAX_FUSED_STEPS);
                    self.exec::<W>(&program, code, false, stop, &mut watch)
                }
                other => other,
            };
            if let Flow::End(exit) = flow {
                break exit;
            }
            self.sync_keyboard();
            if self.steps >= budget_end {
                break Exit::Budget {
                    stack: self.call_stack(),
                };
            }
        };
        if exit == Exit::Halted
            && self.program.synthetic_entry
            && self.frames.is_empty()
            && self.cur == self.program.entry
            && Timing::of(self.os.profile()).hidden_sys_init
        {
            // Desktop: `Main.main` returned into the built-in `Sys.init`,
            // which takes its value off the stack (SP back to its frame's
            // base) and halts.
            let sp = self.ram.read(0);
            self.ram.write(0, sp.wrapping_sub(1));
        }
        self.charge_profile();
        self.tier_credit();
        if !matches!(exit, Exit::Budget { .. } | Exit::Returned(_)) {
            self.ended = Some(exit.clone());
        }
        exit
    }

    /// Web: the blocking built-in `b` with `nargs` arguments on the stack,
    /// whose call step has been counted. The web IDE hands its result back
    /// one step after the wait ends (a keyboard read waits for its key's
    /// release). If that step falls past the budget, the IDE is still in the
    /// call when the budget ends: the machine stops there at the budget,
    /// the arguments still on the stack and the read's cursor (and
    /// prompt) drawn, and the next run makes the call again from the state
    /// before it, watching the keys from the call's step `at`. Otherwise
    /// the arguments are replaced by the result.
    /// `Some` when the call ends the run.
    #[cold]
    pub(crate) fn web_blocking_call(&mut self, b: Builtin, nargs: u16, at: u64) -> Option<Exit> {
        let sp = self.ram.read(0);
        let base = sp.wrapping_sub(nargs as i16);
        let args: Vec<i16> = (0..nargs as i16)
            .map(|k| self.ram.read(i32::from(base.wrapping_add(k))))
            .collect();
        let before = (self.budget_end != u64::MAX).then(|| (self.ram.clone(), self.os.clone()));
        let mut clock = at;
        let c = self.os.call(b, &args, &mut self.ram, &mut clock);
        if c.stop.is_none() && clock.saturating_add(1) > self.budget_end {
            if let Some((ram, os)) = before {
                let (mut shown_ram, mut shown_os) = (ram.clone(), os.clone());
                let mut clock = at;
                shown_os.start_blocking(b, &args, &mut shown_ram, &mut clock);
                self.pending = Some(Box::new(Pending {
                    builtin: b,
                    nargs,
                    at,
                    ram,
                    os,
                }));
                (self.ram, self.os) = (shown_ram, shown_os);
                self.steps = self.budget_end;
                return None;
            }
        }
        self.steps = self.steps.max(clock + u64::from(c.stop.is_none()));
        self.ram.write(i32::from(base), c.value);
        self.ram.write(0, base.wrapping_add(1));
        let stop = c.stop?;
        Some(match stop {
            Stop::Halt => Exit::Halted,
            Stop::SysError(code) => Exit::SysError {
                code,
                stack: self.call_stack(),
            },
            Stop::RuntimeError(message) => Exit::RuntimeError {
                message,
                stack: self.call_stack(),
            },
            Stop::Hang(message) => Exit::Hang {
                message,
                stack: self.call_stack(),
            },
            Stop::BlockedForever => Exit::BlockedForever {
                stack: self.call_stack(),
            },
        })
    }

    /// Whether the machine stands in an idle loop: within the next 64
    /// steps its whole state (position, call stack, registers, RAM, OS)
    /// comes back to what it is now, and no scripted key change is still
    /// to come, so running on changes nothing but the step count (a `goto`
    /// to its own label, or the OS's compiled `while (true) {}` of
    /// `Sys.halt`). The official tools spin there for ever; a run without
    /// a budget may stop there instead. Costs a snapshot and 64 steps.
    pub fn idle(&self) -> bool {
        if self.ended.is_some()
            || self.pending.is_some()
            || self.beyond_end.is_some()
            || self.startup_pending
        {
            return false;
        }
        if self.os.keys().next_change(self.steps).is_some() {
            return false;
        }
        let mut m = self.clone();
        m.native = None;
        m.tier = None;
        m.profile = None;
        for _ in 0..64 {
            if !matches!(m.run(Some(1)), Exit::Budget { .. }) {
                return false;
            }
            let same_frames = m.frames.len() == self.frames.len()
                && m.frames.iter().zip(&self.frames).all(|(a, b)| {
                    (a.caller, a.ret_pc, a.ret, a.nargs, a.flags)
                        == (b.caller, b.ret_pc, b.ret, b.nargs, b.flags)
                });
            if m.pc == self.pc
                && m.cur == self.cur
                && (m.nargs, m.flags) == (self.nargs, self.flags)
                && same_frames
                && m.ram == self.ram
                && m.os == self.os
            {
                return true;
            }
        }
        false
    }

    /// Set the keyboard word from the key script if a key change is due.
    fn sync_keyboard(&mut self) {
        if self.steps >= self.next_key_sync {
            let keys = self.os.keys();
            self.ram.write(KBD as i32, keys.key_at(self.steps));
            self.next_key_sync = keys.next_change(self.steps).unwrap_or(u64::MAX);
        }
    }

    /// Attribute the instructions since the last mark to the running function.
    #[inline]
    pub(crate) fn charge_profile(&mut self) {
        if let Some(p) = &mut self.profile {
            p[self.cur as usize] += self.steps - self.profile_mark;
            self.profile_mark = self.steps;
        }
    }
}

/// [`Machine::call`] named a function the program does not define.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("no VM function named {0}")]
pub struct UnknownFunction(pub String);
