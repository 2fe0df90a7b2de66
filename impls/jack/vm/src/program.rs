//! A loaded VM program: the decoded instruction arrays and the function
//! table. Built once by [`crate::load`], shared read-only (`Arc<Program>`)
//! by every [`crate::Machine`].

use crate::native::Native;
use jack_os::{Builtin, DivideRule, Profile};
use std::collections::HashMap;
use std::sync::atomic::AtomicU64;
use std::sync::{Arc, OnceLock};
use std::time::Duration;

/// Index of a VM function in [`Program::functions`].
pub type FnId = u32;

/// One decoded instruction. Labels are gone (jumps land on the next real
/// command), segment addresses that are fixed at load time are resolved,
/// and call targets are function ids. Fused forms cover several VM commands;
/// `Op::steps` says how many.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
// A plain one-byte tag: without it the operands' tags double as the
// instruction's, and dispatch becomes a chain of tests.
#[repr(u8)]
pub(crate) enum Op {
    PushConst(i16),
    /// `local i`, with i below the function's local count (the loader
    /// makes any other index a [`Op::Fail`]); likewise `PopLocal`.
    PushLocal(u16),
    PushArg(u16),
    /// `this i`, proven at load time to follow a `pop pointer 0` of the
    /// same invocation; `PushThisChk` checks at run time.
    PushThis(u16),
    PushThisChk(u16),
    PushThat(u16),
    PushThatChk(u16),
    /// static or temp: a fixed address in 5..=255.
    PushAbs(u16),
    PushPtr(u8),
    PopLocal(u16),
    PopArg(u16),
    PopThis(u16),
    PopThisChk(u16),
    PopThat(u16),
    PopThatChk(u16),
    PopAbs(u16),
    PopPtr(u8),
    /// `pop constant n`: writes RAM[n] (a quirk of the web IDE).
    PopRam(u16),
    /// An access that fails at run time with a message fixed at load time
    /// (index into `Program::messages`), e.g. `local i` with i >= nVars.
    Fail(u16),
    /// `local`/`argument` in the entry function, which may run without a
    /// frame: fully checked, slow. (segment is Local or Argument, push?)
    EntryAccess {
        local: bool,
        push: bool,
        index: u16,
    },
    Add,
    Sub,
    Neg,
    Eq,
    Gt,
    Lt,
    And,
    Or,
    Not,
    Goto(u32),
    IfGoto(u32),
    Call {
        callee: u16,
        nargs: u16,
        ret: u16,
        /// Fused only: the callee is a method whose first commands are
        /// `push argument 0; pop pointer 0`, and the call runs them too.
        method: bool,
    },
    CallBuiltin {
        builtin: Builtin,
        nargs: u8,
    },
    /// `call Math.multiply 2` / `call Math.divide 2` to the built-in.
    Multiply,
    Divide,
    Return,
    /// The `function` line: a step of its own under the desktop profile,
    /// where a call lands here (see [`crate::timing`]); it pushes the
    /// zeroed locals. `method` (fused code only): the function opens with
    /// `push argument 0; pop pointer 0`, and this instruction runs them too.
    Function {
        n_vars: u16,
        method: bool,
    },
    /// Ran past the last command of a function: the VM halts (both
    /// profiles; see [`crate::timing`]).
    Halt,

    // Fused forms (module `fuse`); the comment gives the commands.
    /// push a; push b
    Push2(Src, Src),
    /// push a; pop d
    Move(Src, Dst),
    /// `len` (2..=4) moves from consecutive words to consecutive words:
    /// push from+k; pop to+k for k in 0..len (same bases; not constants,
    /// not pointer).
    MoveRun {
        from: Src,
        to: Dst,
        len: u8,
    },
    /// push a; push b; op
    BinSS {
        op: Bin,
        a: Src,
        b: Src,
    },
    /// push a; push b; op; pop d
    BinPop {
        op: Bin,
        a: Src,
        b: Src,
        d: Dst,
    },
    /// push b; op (the left operand is on the stack)
    BinS {
        op: Bin,
        b: Src,
    },
    /// push b; op; pop d
    BinSPop {
        op: Bin,
        b: Src,
        d: Dst,
    },
    /// push a; push b; eq|gt|lt; [not;] if-goto target
    CmpJump {
        op: Bin,
        a: Src,
        b: Src,
        not: bool,
        target: u32,
    },
    /// eq|gt|lt; not; if-goto target
    CmpNotJump {
        op: Bin,
        target: u32,
    },
    /// not; if-goto target
    NotIfGoto(u32),
    /// push index; push base; add; pop pointer 1; push that 0
    ArrayRead {
        index: Src,
        base: Src,
    },
    /// push index; push base; add; pop pointer 1; push that 0; pop d
    ArrayReadPop {
        index: Src,
        base: Src,
        to: Dst,
    },
    /// add; pop pointer 1; push that 0
    PtrRead,
    /// pop temp 0; pop pointer 1; push temp 0; pop that 0
    StoreThat,
    /// push v; pop temp 0; pop pointer 1; push temp 0; pop that 0
    StoreThatSrc(Src),
    /// push a; return
    PushReturn(Src),
}

/// Where a fused operand lives: a register whose value is added to the
/// operand's offset (an index into the dispatch loop's register table), a fixed
/// address, a constant, or (targets only) a pointer register.
pub(crate) const LCL: usize = 0;
pub(crate) const ARG: usize = 1;
pub(crate) const THIS: usize = 2;
pub(crate) const THAT: usize = 3;
/// Base 0: the offset is the address (static or temp, 5..=255).
pub(crate) const ABS: usize = 4;
/// Sources only: the offset is the value.
pub(crate) const CONST: usize = 5;
/// Targets only: `pop pointer off`.
pub(crate) const PTR: usize = 6;

/// The operand of a fused `push` or the target of a fused `pop`: read or
/// written without a branch on its kind. `need` holds the invocation flags
/// (`THIS_OK`, `THAT_OK`, `ARGS_FIT`; desktop code: `NEAR_THIS`,
/// `NEAR_THAT` for `this`/`that`) without which the access could fail,
/// so a fused instruction checks all its operands with one test.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Operand {
    pub base: u8,
    pub need: u8,
    pub off: u16,
}

/// A fused push's operand (base is never `PTR`).
pub(crate) type Src = Operand;
/// A fused pop's target (base is never `CONST`).
pub(crate) type Dst = Operand;

impl Operand {
    pub(crate) const fn new(base: usize, need: u8, off: u16) -> Operand {
        Operand {
            base: base as u8,
            need,
            off,
        }
    }
}

/// A binary operation of a fused instruction (Mul/Div: the built-ins).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Bin {
    Add,
    Sub,
    And,
    Or,
    Eq,
    Gt,
    Lt,
    Mul,
    Div,
}

impl Op {
    /// VM commands (steps) this instruction stands for.
    pub(crate) const fn steps(self) -> u64 {
        match self {
            Op::Halt => 0,
            Op::Function { method: true, .. } => 3,
            Op::Push2(..)
            | Op::Move(..)
            | Op::BinS { .. }
            | Op::NotIfGoto(_)
            | Op::PushReturn(_) => 2,
            Op::BinSS { .. } | Op::BinSPop { .. } | Op::CmpNotJump { .. } | Op::PtrRead => 3,
            Op::BinPop { .. } | Op::StoreThat => 4,
            Op::CmpJump { not, .. } => 4 + not as u64,
            Op::Call { method: true, .. } => 3,
            Op::ArrayRead { .. } | Op::StoreThatSrc(_) => 5,
            Op::ArrayReadPop { .. } => 6,
            Op::MoveRun { len, .. } => 2 * len as u64,
            _ => 1,
        }
    }
}

/// A VM function of the program.
#[derive(Clone, Debug)]
pub struct Function {
    /// Full name, e.g. `Float316.add`.
    pub name: String,
    /// File it came from (empty for the synthetic `Sys.init`).
    pub file: String,
    /// Number of locals (`function f nVars`).
    pub n_vars: u16,
    /// Whether the function has a `function` line (`__implicit` has none).
    pub(crate) headed: bool,
    /// One more than the highest `argument` index the function uses (0 if
    /// none): an invocation with at least this many arguments never fails
    /// an argument access, so its fused instructions skip the check.
    pub(crate) arg_reach: u16,
    /// First instruction of the body; `start - 1` holds its
    /// [`Op::Function`] line.
    pub(crate) start: u32,
    /// Command index (as stored in a frame's RET, counting the `function`
    /// line and labels) to the instruction that runs it.
    pub(crate) resume: Vec<u32>,
    /// The desktop VM emulator's address of the function's command 0 (its
    /// `function` line): files in load order, every non-blank line one
    /// address, labels included. A RET word of the desktop is such an
    /// address.
    pub(crate) address: u32,
}

impl Function {
    /// The desktop's index in the function of the command at instruction
    /// `pc` (its `function` line 0, labels not counted), which its
    /// messages and a script's `line` print.
    pub(crate) fn desktop_index(&self, pc: u32) -> u32 {
        pc.wrapping_sub(self.start)
            .wrapping_add(u32::from(self.headed))
    }

    /// The desktop's RET word for a call whose instruction is at `call_pc`:
    /// the address of the first command after the call that is not a label.
    pub(crate) fn desktop_return_address(&self, call_pc: u32) -> Option<u32> {
        let r = &self.resume;
        // Labels share the index of the command after them: the call is
        // the last command index resuming at its own instruction.
        let call = r.iter().rposition(|&p| p == call_pc)?;
        let mut next = call + 1;
        while next + 1 < r.len() && r[next] == r[next + 1] {
            next += 1;
        }
        Some(self.address + next as u32)
    }
}

impl Function {
    /// The flags an invocation with `nargs` arguments starts with.
    #[inline(always)]
    pub(crate) fn entry_flags(&self, nargs: u16) -> u8 {
        if nargs >= self.arg_reach {
            crate::machine::ARGS_FIT
        } else {
            0
        }
    }
}

/// One profile's instruction arrays.
#[derive(Debug)]
pub(crate) struct Code {
    /// Per function: its `Function` line, one instruction per other
    /// non-label command, a `Halt`, then the wasted-step
    /// jumps of [`crate::timing`] (desktop only; unused in web code).
    pub plain: Vec<Op>,
    /// Same indexing as `plain`; at some indices a fused instruction.
    pub fused: Vec<Op>,
}

/// A loaded, checked and decoded VM program. Immutable (but for its
/// compiled code, made on first use, and the step count that decides when);
/// share it with `Arc`.
#[derive(Debug)]
pub struct Program {
    pub(crate) functions: Vec<Function>,
    pub(crate) by_name: HashMap<String, FnId>,
    /// The decoded code, per profile (indexed by [`crate::timing::index`]):
    /// the same instructions at the same indices, except the jumps that
    /// cost the desktop a wasted step.
    pub(crate) code: [Code; 2],
    pub(crate) messages: Vec<String>,
    pub(crate) entry: FnId,
    /// The entry is the synthetic `Sys.init` (no VM `Sys.init`, a `Main.main`).
    pub(crate) synthetic_entry: bool,
    /// A command the web IDE refuses at load and the desktop runs (file,
    /// line, message): see [`Program::check_profile`].
    pub(crate) web_refusal: Option<(String, usize, String)>,
    /// Number of command lines of all files (function and label lines
    /// included): the desktop VM emulator's program size before its
    /// invisible start-up code.
    pub(crate) command_lines: usize,
    /// Number of static slots allocated (RAM 16..16+n).
    pub(crate) statics: usize,
    /// Compiled code under each OS profile (desktop, web) and rounding of
    /// `Math.divide` (see [`native_index`]), made on first use.
    pub(crate) native: [OnceLock<Result<Arc<Native>, String>>; 4],
    /// Steps that [`crate::Engine::Auto`] machines of each profile have run
    /// on the interpreter, all machines together (see `crate::tier`).
    pub(crate) interpreted: [AtomicU64; 2],
}

impl Program {
    /// The function called `name`, if the program defines it.
    pub fn function_id(&self, name: &str) -> Option<FnId> {
        self.by_name.get(name).copied()
    }

    /// All functions; a [`FnId`] indexes this slice.
    pub fn functions(&self) -> &[Function] {
        &self.functions
    }

    /// The name of function `id`.
    pub fn function_name(&self, id: FnId) -> &str {
        &self.functions[id as usize].name
    }

    /// The entry function (spec §2.6): `Sys.init`, the synthetic `Sys.init`,
    /// `__implicit` or the sole function.
    pub fn entry(&self) -> FnId {
        self.entry
    }

    /// The load-time checks that only one profile's tool makes: the web
    /// IDE refuses a static index past 239, which the desktop runs. Call it
    /// with the profile a program is about to run under; a machine of that
    /// profile that runs the program anyway stops at the refused command
    /// with the same message.
    pub fn check_profile(&self, profile: Profile) -> Result<(), crate::LoadError> {
        match (&self.web_refusal, profile) {
            (Some((file, line, message)), Profile::Web) => {
                Err(crate::LoadError::at(file, *line, message.clone()))
            }
            _ => Ok(()),
        }
    }

    /// Number of distinct static variables (RAM 16.. holds them).
    pub fn static_count(&self) -> usize {
        self.statics
    }

    /// Number of decoded instructions (labels excluded; function lines,
    /// ends and wasted-step jumps included).
    pub fn instruction_count(&self) -> usize {
        self.code[0].plain.len()
    }

    /// Compile the program to native code for machines of OS `profile`
    /// (done once; later calls and [`crate::Machine::new`] share it), and
    /// say how long compiling took, or why it cannot be done on this host.
    pub fn compile_native(&self, profile: Profile) -> Result<Duration, String> {
        self.native(profile, DivideRule::of(profile))
            .map(|n| n.compile_time())
    }

    /// The compiled code for `profile` with `divide`, compiling it on first
    /// use.
    pub(crate) fn native(
        &self,
        profile: Profile,
        divide: DivideRule,
    ) -> Result<Arc<Native>, String> {
        let slot = &self.native[native_index(profile, divide)];
        slot.get_or_init(|| Native::compile(self, profile, divide, None).map(Arc::new))
            .clone()
    }

    /// The compiled code for `profile` with `divide` if it has been made
    /// (`Err`: it cannot be), without compiling.
    pub(crate) fn native_made(
        &self,
        profile: Profile,
        divide: DivideRule,
    ) -> Option<&Result<Arc<Native>, String>> {
        self.native[native_index(profile, divide)].get()
    }
}

/// The slot of [`Program::native`] for `profile` with `divide`.
fn native_index(profile: Profile, divide: DivideRule) -> usize {
    crate::timing::index(profile) * 2 + usize::from(divide == DivideRule::Floor)
}
