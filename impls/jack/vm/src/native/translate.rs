//! One VM function to Cranelift IR.
//!
//! The compiled function (signature `native::Entry`) takes the machine
//! state in a [`Ctx`] and the index of the block to start at (from the
//! dispatcher), or the callee's registers as arguments (from a compiled
//! call), keeps SP, LCL, ARG, THIS, THAT, the flags, the argument count and
//! the step count in registers, and returns a code (see `native::RETURNED`,
//! `native::CONTINUE`; a code >= 0 is the instruction the interpreter must
//! run next) and the step count. One test on entering compiled code covers
//! every `local` and `argument` access of the function (`frame_ok`). The
//! step budget is tested where a loop's head, the function's first block,
//! a call's continuation or the dispatcher's entry starts a stretch, for
//! the most steps the stretch can take before the next test
//! (`blocks::budgets`). Where the stack depth is fixed at each instruction
//! (`blocks::static_depths`, Jack-compiled code), the stack range (256 to
//! the profile's stack end, `Timing::stack_end`) is tested once on entering
//! the function; elsewhere each block tests its own. If a test fails, and
//! wherever an instruction meets a case that
//! only the interpreter handles (a register or an address outside RAM
//! through a computed address, a failed segment check, a division by zero,
//! a blocking built-in), it stores the exact state before that instruction
//! and exits. Other built-ins end their block and run through a host call
//! (`builtin::call`), after which compiled code goes on. Within a block the operand stack lives in SSA values (see
//! [`Stack`]): each pushed word reaches RAM once, with its last value, where
//! the block ends or leaves, or before an access that might touch it; the
//! entry test shows that the block's `local` and `argument` words lie below
//! its stack words, and the span test of a `this`/`that` run that its words
//! miss them. Every access is then one load or store at a fixed offset
//! from its segment's host address.
//!
//! Words live in 32-bit values: a register (SP, LCL, ARG, THIS, THAT, the
//! argument count) zero-extended, an operand-stack word or a held local in
//! its low 16 bits, the bits above left as the arithmetic made them (a sum
//! can carry past bit 15). RAM is read zero-extended and written 16 bits
//! wide; whatever needs the word itself (an address, a branch, `pop
//! pointer`, a comparison, a division, `Math.abs`/`min`/`max`) takes the
//! low 16 bits, zero- or sign-extended. Address arithmetic on registers
//! does not wrap, so a sum past 65535 fails the test that would have
//! passed its 16-bit wrap, and the interpreter runs that instruction. (16-bit
//! operations with a 16-bit immediate, which Cranelift emits for every
//! 16-bit constant operand, stall x86 decoders several cycles each.)

use super::blocks::{self, Block, Budget, Kind, MAX_INLINE_LOCALS};
use super::code_map::{source_loc, Part};
use super::{builtin, Ctx, Fault, CALLED, CONTINUE, RETURNED};
use crate::exec::HEAP_START;
use crate::machine::{Frame, HOST, THAT_OK, THIS_OK};
use crate::program::{FnId, Function, Op, Program};
use crate::timing::{Timing, STACK_BASE};
use cranelift_codegen::ir::condcodes::IntCC;
use cranelift_codegen::ir::{
    self, types, AbiParam, AliasRegionData, BlockArg, FuncRef, InstBuilder, JumpTableData,
    MemFlagsData, TrapCode, Value,
};
use cranelift_frontend::{FunctionBuilder, Variable};
use jack_os::{Profile, KBD, RAM_SIZE};
use std::collections::HashSet;
use std::mem::offset_of;

mod strings;

const T32: ir::Type = types::I32;
const T64: ir::Type = types::I64;

/// Calls with more arguments are left to the interpreter (so that a
/// compiled call's ARG is a plain word, see `Translator::called_ok`).
const MAX_COMPILED_ARGS: u16 = 250;

/// No block arguments.
const NONE: &[BlockArg] = &[];

/// A field offset as Cranelift takes it.
fn field(offset: usize) -> i32 {
    offset as i32
}

/// The flags of each kind of memory access, whose alias regions tell
/// Cranelift that RAM, the context's changing fields and the frame stack
/// never overlap; what stays fixed while compiled code runs (the context's
/// pointers and limits, the watch set) is read-only.
#[derive(Clone, Copy)]
struct Mem {
    ram: MemFlagsData,
    ctx: MemFlagsData,
    frames: MemFlagsData,
    fixed: MemFlagsData,
}

impl Mem {
    fn new(func: &mut ir::Function) -> Mem {
        let mut region = |user_id: u32, description: &'static str| {
            let r = func.dfg.alias_regions.insert(AliasRegionData {
                user_id,
                description: description.into(),
            });
            MemFlagsData::trusted().with_alias_region(Some(r))
        };
        Mem {
            ram: region(0, "ram"),
            ctx: region(1, "ctx"),
            frames: region(2, "frames"),
            fixed: MemFlagsData::trusted().with_readonly().with_can_move(),
        }
    }
}

/// The registers kept in variables while compiled code runs.
struct Vars {
    sp: Variable,
    lcl: Variable,
    arg: Variable,
    this: Variable,
    that: Variable,
    flags: Variable,
    nargs: Variable,
    steps: Variable,
}

/// What the translation of one function needs from its surroundings.
pub(crate) struct Env<'a> {
    pub program: &'a Program,
    /// The profile's plain instructions.
    pub code: &'a [Op],
    /// The function's first instruction in `code` (where a call lands).
    pub start: u32,
    /// The profile's step and stack rules.
    pub timing: Timing,
    pub id: FnId,
    /// The function's blocks, and the block starting at each instruction
    /// (relative to the function's start), from [`blocks::blocks`].
    pub blocks: &'a [Block],
    pub block_at: &'a [Option<u32>],
    /// SP - LCL before each instruction, where the function's code fixes
    /// it ([`blocks::static_depths`]).
    pub depths: Option<&'a [Option<i32>]>,
    /// No compiled code writes a saved frame word (`native::frames_intact`).
    pub frames_intact: bool,
    pub profile: Profile,
    /// `Math.divide`'s rounding (the profile's unless the machine chose).
    pub divide: jack_os::DivideRule,
    pub fault: Option<Fault>,
    pub target: cranelift_codegen::isa::TargetFrontendConfig,
    /// The compiled function of a callee, as a reference in this function.
    pub callee: &'a mut dyn FnMut(&mut ir::Function, FnId) -> FuncRef,
}

struct Translator<'a, 'b> {
    b: FunctionBuilder<'b>,
    env: Env<'a>,
    v: Vars,
    ctx: Value,
    ram: Value,
    stop_at: Value,
    /// Two words in the host stack frame, not registers, since only exits
    /// read them ([`SLOT_LEN`], [`SLOT_WHICH`]).
    slots: ir::StackSlot,
    mem: Mem,
    /// The Cranelift block of each VM block.
    cl: Vec<ir::Block>,
    /// VM block index by instruction index relative to the function start.
    block_at: &'a [Option<u32>],
    start: u32,
    /// Stores the state and returns (code, pc).
    leave: ir::Block,
    /// The highest `local` and `argument` index the function uses, where
    /// one test of LCL (ARG) on entering compiled code and after each call
    /// covers every such access (None: each access tests its address).
    reach: [Option<u16>; 2],
    /// The this/that flags already known set in the current block (tested
    /// or set by `pop pointer`), whose accesses need no test.
    flags_known: u8,
    /// The address test of each `this`/`that` access of the current block,
    /// by instruction index relative to `block_start`.
    ptr_tests: Vec<PtrTest>,
    block_start: u32,
    /// The current block's stack words, `lo..hi` (None if it has none).
    stack_span: Option<(Value, Value)>,
    /// LCL + the highest `local` index and ARG + the highest `argument`
    /// index, where `reach` covers them: LCL and ARG keep one value through
    /// compiled code (a call that returns with others leaves it).
    frame_tops: [Option<Value>; 2],
    /// SP - LCL before each instruction (relative to `start`), where the
    /// function's code fixes it ([`blocks::static_depths`]): then SP is
    /// LCL + that depth wherever compiled code runs (the dispatcher tests
    /// it on entering), every stack word lies at a fixed offset from
    /// `lcl_host`, and the stack tests are made once on entering the
    /// function. None: each block tests its stack.
    depths: Option<&'a [Option<i32>]>,
    /// The host address of RAM[LCL] (static depths only).
    lcl_host: Option<Value>,
    /// Where each block tests the step budget ([`blocks::budgets`]).
    budgets: Vec<Budget>,
    /// The entry test shows what a `return` needs of LCL and ARG: the
    /// saved frame LCL-5 ..= LCL-1 and ARG are plain words.
    frame_shown: bool,
    /// The lowest and highest stack word of the function relative to LCL,
    /// and the lowest held by a block that uses `argument` (from
    /// `static_ok`).
    range: Option<(i32, i32, i32)>,
    /// While the body of a callee run inline is translated: the call, and
    /// the calls of the inline runs it is nested in (outermost first), so
    /// that leaving compiled code inside it first makes the frames those
    /// calls would have pushed on the frame stack.
    inlined: Vec<CallSite>,
    /// Beside `inlined`, a level per run: the values of its argument
    /// words where the caller's code had them in registers (None where
    /// not, or once a store may have changed them), so that the run's
    /// `push argument` takes them without a load of the word just stored.
    inline_args: Vec<Vec<Option<Value>>>,
    /// Desktop: FRAME and RET as a nested inline run's return left them
    /// for R13 and R14, not yet written: the next return overwrites them,
    /// and they go to RAM before a leave or an access of either word
    /// (compiled code reaches neither through `this`, `that` or
    /// `Memory.peek`, which lie in the heap and above).
    return_registers: Option<(Value, Value)>,
    /// Desktop: the function's locals 0..len, held in these variables
    /// across its blocks (see [`held_locals`]); RAM gets them where compiled
    /// code leaves (`leave_held`), returns, or passes on a callee's leave.
    held: Vec<Variable>,
    /// Writes the held locals to RAM, then leaves as `leave` does.
    leave_held: ir::Block,
    /// The held locals are the function's (its `function` line has run):
    /// a leave writes them to RAM first.
    locals_live: bool,
    /// Values known to be zero-extended words (loads, constants, registers),
    /// which [`Translator::exact`] takes as they are.
    zero_extended: HashSet<Value>,
}

/// Locals held in variables at most.
const MAX_HELD_LOCALS: u16 = 16;

/// How many of the function's locals its compiled code holds in variables
/// across blocks (0: none), where no other code of the function can reach
/// their words: under the desktop profile (whose `this`, `that` and
/// built-ins reach only the heap and above, compiled code's `argument`
/// words lie below LCL, and the `function` line zeroes the locals), with
/// static depths, every `local` access inside the entry test's reach (the
/// loader makes one past the function's local count a `Fail`), no
/// instruction popping a stack word below the locals (so no callee's ARG
/// reaches them), and no `pop constant` into the stack.
fn held_locals(env: &Env<'_>, depths: Option<&[Option<i32>]>, reach: [Option<u16>; 2]) -> u16 {
    let f = &env.program.functions[env.id as usize];
    let (Some(depths), Some(top)) = (depths, reach[LOCAL]) else {
        return 0;
    };
    let held = top + 1;
    let end = env.start as usize + depths.len();
    let code = &env.code[env.start as usize..end];
    let fits = env.profile == Profile::Desktop
        && env.timing.function_step
        && matches!(code.first(), Some(Op::Function { .. }))
        && held <= MAX_HELD_LOCALS
        && !code.iter().any(|&op| blocks::pops_into_stack(op))
        && blocks::pops_stay_above(env.code, env.start, depths, i32::from(f.n_vars));
    if fits {
        held
    } else {
        0
    }
}

/// A callee that a compiled call runs inline, in the caller's code: the
/// instructions from where a call lands (`start`) to its first `return`
/// (`end` is past it) run straight, none left to the interpreter, except
/// for calls of callees that run inline in turn (to [`MAX_INLINE_DEPTH`]
/// levels, [`MAX_INLINE_TOTAL`] instructions in all), and every `local`
/// and `argument` access lies inside the frame the call makes. One-line
/// methods (getters, setters), small leaf functions, and chains of them
/// (`set(get() + 1)`).
#[derive(Clone, Copy, Debug)]
struct Inline {
    start: u32,
    end: u32,
    /// Steps of the whole run, its `return` and its nested runs included.
    steps: u64,
    /// The highest SP over the run, nested frames included, relative to
    /// the callee's LCL.
    top: i32,
    /// Instructions translated for the run, nested runs included.
    size: usize,
    /// The most frames the run makes at once: 1, and those of its deepest
    /// nested run.
    frames: u32,
    /// No instruction of the run can write a word of its frame (see
    /// [`keeps_frames`]), so that its return finds the frame as the call
    /// wrote it.
    keeps_frame: bool,
    /// A run that ends in an `if-goto` (`end` is past it) and goes on
    /// inline only where the branch leads straight to a `return`
    /// ([`guarded_run`]).
    branch: Option<Branch>,
}

/// The two ways out of a guarded run's `if-goto` (not taken, taken): the
/// instructions up to and including a `return` that run inline, or None
/// where the call goes through the host instead. Where the call is the
/// caller's own, a recursion's other way may run inline too, its calls
/// nested runs or calls through the host from inside the run
/// ([`stretch`]).
#[derive(Clone, Copy, Debug)]
struct Branch {
    leaves: [Option<Way>; 2],
}

/// A way out of a guarded run's `if-goto` that runs inline: `goto`s
/// (`jumps` of them, a step each: the desktop's wasted step before a
/// label that follows another), then the instructions from `start` up to
/// and including a `return` (`end` is past it).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Way {
    start: u32,
    end: u32,
    jumps: u64,
}

/// Where the caller's code goes on after a run
/// ([`Translator::run_inline`]): after its return, or with the call
/// through the host still to make (a guarded run's way there), then on at
/// `join` where the run's other ways meet (a run nested in another).
enum RunEnd {
    Returned,
    Host(Option<ir::Block>),
}

/// Whether no instruction of `ops` (the body of an inline run) can write
/// a word of a frame on the stack: the saved words lie between the
/// `argument` and the `local` words the body's accesses are shown to
/// stay in, `temp` and `static` lie below the stack, and so does every
/// word a desktop `this`, `that` or `Memory.poke` reaches in compiled
/// code (the heap and above). A `pop constant` into the stack, and on the
/// web a write through a pointer or `Memory.poke`, may.
fn keeps_frames(ops: &[Op], profile: Profile) -> bool {
    ops.iter().all(|op| match *op {
        Op::PopRam(_) => !blocks::pops_into_stack(*op),
        Op::PopThis(_)
        | Op::PopThisChk(_)
        | Op::PopThat(_)
        | Op::PopThatChk(_)
        | Op::CallBuiltin {
            builtin: jack_os::Builtin::MemoryPoke,
            ..
        } => profile == Profile::Desktop,
        _ => true,
    })
}

/// Whether `op`, an instruction of an inline run, may write a word below
/// the running function's frame, the run's argument words among them:
/// stores to absolute stack addresses, the web's `this` and `that` (the
/// desktop's lie in the heap and above), and the built-ins that write
/// memory. (An inline run holds only straight instructions, so no built-in
/// called through the host.)
fn may_write_frames(op: Op, profile: Profile) -> bool {
    match op {
        Op::PopRam(_) => blocks::pops_into_stack(op),
        Op::PopThis(_) | Op::PopThisChk(_) | Op::PopThat(_) | Op::PopThatChk(_) => {
            profile != Profile::Desktop
        }
        Op::CallBuiltin { builtin, .. } => matches!(
            builtin,
            jack_os::Builtin::MemoryPoke | jack_os::Builtin::StringAppendChar
        ),
        _ => false,
    }
}

/// In `Translator::slots`: a compiled call's frame stack length (its
/// entry's index), which the call's leave path writes the entry at.
const SLOT_LEN: i32 = 0;
/// In `Translator::slots`: the entry's block index or [`CALLED`] | RET
/// word, for the returns: whether a compiled call entered the function,
/// and the RET word that call wrote, which is not on the frame stack (see
/// [`Translator::call`]).
const SLOT_WHICH: i32 = 8;

/// Callees of more instructions (before their `return`) are called, not
/// run inline.
const MAX_INLINE_OPS: usize = 32;

/// Inline runs nest at most this deep (a call chain of one-line functions).
const MAX_INLINE_DEPTH: u32 = 8;

/// An inline run, its nested runs included, translates at most this many
/// instructions.
const MAX_INLINE_TOTAL: usize = 96;

/// The callees of the calls nested in inline run `run` (a guarded run's
/// ways included), at every level.
fn nested_callees(env: &Env<'_>, run: Inline, out: &mut Vec<FnId>) {
    let ways = run.branch.map_or([None; 2], |b| b.leaves);
    let ways = ways.into_iter().flatten().map(|w| (w.start, w.end));
    for (start, end) in std::iter::once((run.start, run.end)).chain(ways) {
        for &op in &env.code[start as usize..end as usize] {
            if let Op::Call { callee, nargs, .. } = op {
                let callee = FnId::from(callee);
                out.push(callee);
                if let Some(inner) = inline_callee(env, callee, nargs, false) {
                    nested_callees(env, inner, out);
                }
            }
        }
    }
}

/// The locals a call of `f` zeroes: none where the `function` line is a
/// step (the callee's zeroes and pushes them), else all of them.
fn zeroed_by_call(timing: Timing, f: &Function) -> u16 {
    if timing.function_step {
        0
    } else {
        f.n_vars
    }
}

/// Where a call of `f` with `nargs` arguments lands (its `function` line,
/// where that is a step), if the callee may run inline at all: it has a
/// `function` line, and its arguments and locals are within the limits
/// that `Translator::call` compiles.
fn run_start(env: &Env<'_>, f: &Function, nargs: u16) -> Option<u32> {
    (f.headed && nargs <= MAX_COMPILED_ARGS && f.n_vars <= MAX_INLINE_LOCALS)
        .then(|| f.start - u32::from(env.timing.function_step))
}

/// Whether a call of `callee` with `nargs` arguments runs it inline (see
/// [`Inline`]); `first` where the call is the translated function's own,
/// not nested in a run (only there may a guarded run's ways hold calls).
fn inline_callee(env: &Env<'_>, callee: FnId, nargs: u16, first: bool) -> Option<Inline> {
    inline_run(env, callee, nargs, 1).or_else(|| guarded_run(env, callee, nargs, first))
}

/// Whether instruction `op` of a callee called with `nargs` arguments
/// may run inline (a `local` index is always below the callee's local
/// count).
fn fits_inline(op: Op, nargs: u16) -> bool {
    match op {
        Op::PushArg(i) | Op::PopArg(i) => i < nargs,
        op => blocks::kind(op) == Kind::Straight,
    }
}

/// Whether running `op` again changes nothing: it pushes one word made
/// from what it reads (a `push`, an arithmetic or logical operation), or
/// it is a `function` line (zeroed locals) or a `pop pointer` (a method's
/// `push argument 0; pop pointer 0`). Where a guarded run's branch goes to
/// the host, the callee runs its opening again.
fn repeatable(op: Op) -> bool {
    match op {
        Op::Function { .. } | Op::PopPtr(_) => true,
        Op::CallBuiltin { .. } | Op::Multiply | Op::Divide => false,
        op => blocks::stack_effect(op).1 == 1,
    }
}

/// A callee whose code opens with a test and a branch to a `return` (the
/// base case of a recursion, a guard clause): `if (k < 2) { return k; }`.
/// The opening instructions up to the `if-goto` are [`repeatable`], and
/// leave nothing on the stack but the condition; each way out of the branch
/// that reaches a `return` within [`MAX_INLINE_OPS`] straight
/// instructions runs inline, and so, at a call's `first` level, does a way
/// with calls in it, one of them of the callee itself ([`stretch`]: a
/// recursion's other case, `return fib(k - 1) + fib(k - 2);`, after the
/// desktop's `goto` to a label if any); the other way (if any) makes the
/// call through the host, whose callee runs the opening again.
fn guarded_run(env: &Env<'_>, callee: FnId, nargs: u16, first: bool) -> Option<Inline> {
    let f = &env.program.functions[callee as usize];
    let start = run_start(env, f, nargs)?;
    let code = env.code;
    let ops = &code[start as usize..];
    let at = ops
        .iter()
        .take(MAX_INLINE_OPS)
        .position(|&op| !(repeatable(op) && fits_inline(op, nargs)))?;
    let Op::IfGoto(target) = ops[at] else {
        return None;
    };
    let prefix = &ops[..=at];
    let (low, high) = blocks::depth_range(prefix);
    // The function line's locals (desktop) stay below the condition.
    let locals_pushed = match ops[0] {
        Op::Function { n_vars, .. } => i32::from(n_vars),
        _ => 0,
    };
    if low < 0 || blocks::net_depth(prefix) != locals_pushed {
        return None;
    }
    let way = |mut from: u32| -> Option<(Way, Stretch)> {
        let mut jumps = 0;
        while let Some(&Op::Goto(t)) = code.get(from as usize) {
            if jumps == 2 {
                return None;
            }
            (from, jumps) = (t, jumps + 1);
        }
        let rest = code.get(from as usize..)?;
        let len = rest
            .iter()
            .take(MAX_INLINE_OPS)
            .position(|&op| op == Op::Return)?;
        let body = &rest[..=len];
        let straight = || stretch(env, body, nargs, locals_pushed, |_, _| None);
        let with_calls = || {
            stretch(env, body, nargs, locals_pushed, |c, n| {
                Some(inline_callee(env, c, n, false))
            })
            .filter(|w| w.size <= MAX_INLINE_TOTAL)
        };
        // (Calls in a way pay where the callee calls itself: each call
        // of a recursion then runs two of its levels. Elsewhere they only
        // move a call through the host into the caller's larger code. A
        // straight way after a `goto` is left alone: it is the way around
        // an `if` statement's body, mostly the less taken.)
        let recursive = body
            .iter()
            .any(|&op| matches!(op, Op::Call { callee: c, .. } if FnId::from(c) == callee));
        let w = if jumps == 0 { straight() } else { None }
            .or_else(|| (first && recursive).then(with_calls).flatten())?;
        let end = from + len as u32 + 1;
        let steps = w.steps + jumps;
        Some((
            Way {
                start: from,
                end,
                jumps,
            },
            Stretch { steps, ..w },
        ))
    };
    let branch_at = start + at as u32;
    let ways = [branch_at + 1, target].map(way);
    if ways.iter().all(Option::is_none) {
        return None;
    }
    let locals = i32::from(zeroed_by_call(env.timing, f));
    let opening_steps = prefix.iter().map(|op| op.steps()).sum::<u64>();
    let (mut steps, mut size, mut top, mut frames) = (0u64, prefix.len(), high, 1);
    let mut keeps_frame = keeps_frames(prefix, env.profile);
    for (_, w) in ways.iter().flatten() {
        top = top.max(w.top);
        steps = steps.max(opening_steps + w.steps);
        size += w.size;
        frames = frames.max(w.frames);
        keeps_frame &= w.keeps_frame;
    }
    Some(Inline {
        start,
        end: branch_at + 1,
        steps,
        top: locals + top,
        size,
        frames,
        keeps_frame,
        branch: Some(Branch {
            leaves: ways.map(|w| w.map(|(way, _)| way)),
        }),
    })
}

/// What a run's stretch of code needs: its steps (its nested runs'
/// included, one for a call through the host), the highest depth it
/// reaches above the callee's LCL (nested frames included), the
/// instructions translated, the most frames it makes at once (its own
/// included), and whether it keeps its frame (see [`Inline::keeps_frame`]).
#[derive(Clone, Copy, Debug)]
struct Stretch {
    steps: u64,
    top: i32,
    size: usize,
    frames: u32,
    keeps_frame: bool,
}

/// The [`Stretch`] of `body`, a callee's straight instructions (called with
/// `nargs` arguments) up to and including a `return`, entered `depth`
/// words above its LCL; each call in it is made as `nested` says: None, the
/// run cannot hold it; Some(Some(run)), a nested run; Some(None), a call
/// through the host from inside the run (which then tests the budget for
/// the rest, [`steps_to_return`]).
fn stretch(
    env: &Env<'_>,
    body: &[Op],
    nargs: u16,
    mut depth: i32,
    nested: impl Fn(FnId, u16) -> Option<Option<Inline>>,
) -> Option<Stretch> {
    let (mut top, mut steps, mut size, mut frames) = (depth, 0u64, 0usize, 1u32);
    let len = body.len() - 1;
    let mut keeps_frame = keeps_frames(&body[..len], env.profile);
    let mut from = 0;
    // The stretches between nested calls, each call, the return.
    for (k, op) in body.iter().enumerate() {
        let fits = match *op {
            Op::Call { .. } | Op::Return => true,
            op => fits_inline(op, nargs),
        };
        if !fits {
            return None;
        }
        steps += op.steps();
        size += 1;
        let Op::Call {
            callee: inner,
            nargs: n,
            ..
        } = *op
        else {
            continue;
        };
        let (low, high) = blocks::depth_range(&body[from..k]);
        if depth + low < 0 {
            return None;
        }
        top = top.max(depth + high);
        depth += blocks::net_depth(&body[from..k]);
        if depth < i32::from(n) {
            return None;
        }
        let inner = FnId::from(inner);
        // The nested frame: 5 saved words above SP, then its run or the
        // locals the call zeroes.
        let (inner_top, inner_frames) = match nested(inner, n)? {
            Some(run) => {
                steps += run.steps;
                size += run.size;
                let host_way = run.branch.is_some_and(|b| b.leaves.contains(&None));
                keeps_frame &= run.keeps_frame && (!host_way || env.frames_intact);
                (run.top, run.frames)
            }
            None => {
                // The callee's compiled code may write this run's frame
                // unless none can.
                keeps_frame &= env.frames_intact;
                let f = &env.program.functions[inner as usize];
                (i32::from(zeroed_by_call(env.timing, f)), 1)
            }
        };
        top = top.max(depth + 5 + inner_top);
        depth += 1 - i32::from(n);
        frames = frames.max(1 + inner_frames);
        from = k + 1;
    }
    let (low, high) = blocks::depth_range(&body[from..]);
    if depth + low < 0 {
        return None;
    }
    Some(Stretch {
        steps,
        top: top.max(depth + high),
        size,
        frames,
        keeps_frame,
    })
}

/// The steps from `from`, in a guarded run's way with calls, up to and
/// including its `return`, its nested runs' included: what must be left
/// under the budget when a call through the host from inside the run
/// returns before `from`.
fn steps_to_return(env: &Env<'_>, from: u32) -> u64 {
    let mut steps = 0;
    for &op in &env.code[from as usize..] {
        steps += op.steps();
        match op {
            Op::Return => break,
            Op::Call { callee, nargs, .. } => {
                let run = inline_callee(env, FnId::from(callee), nargs, false);
                steps += run.map_or(0, |r| r.steps);
            }
            _ => {}
        }
    }
    steps
}

/// [`inline_callee`] for a run nested `level` deep (1: called from the
/// function being translated).
fn inline_run(env: &Env<'_>, callee: FnId, nargs: u16, level: u32) -> Option<Inline> {
    let f = &env.program.functions[callee as usize];
    if level > MAX_INLINE_DEPTH {
        return None;
    }
    let start = run_start(env, f, nargs)?;
    let ops = &env.code[start as usize..];
    let len = ops
        .iter()
        .take(MAX_INLINE_OPS)
        .position(|op| *op == Op::Return)?;
    let run = stretch(env, &ops[..=len], nargs, 0, |c, n| {
        inline_run(env, c, n, level + 1).map(Some)
    })?;
    // Where the call zeroes the locals (web), the run starts above them.
    let locals = i32::from(zeroed_by_call(env.timing, f));
    (run.size <= MAX_INLINE_TOTAL).then_some(Inline {
        start,
        end: start + len as u32 + 1,
        steps: run.steps,
        top: locals + run.top,
        size: run.size,
        frames: run.frames,
        keeps_frame: run.keeps_frame,
        branch: None,
    })
}

/// A compiled call: what its frame stack entry holds, and the caller's
/// registers it saved in the frame.
#[derive(Clone, Copy)]
struct CallSite {
    callee: FnId,
    /// The call's argument count.
    n: u16,
    /// The caller's instruction after the call, and the RET word.
    ret_pc: u32,
    ret: u16,
    /// The frame stack's length at the call, and the caller's argument
    /// count and flags.
    frames_len: Value,
    nargs: Value,
    flags: Value,
    /// The caller's LCL, ARG, THIS and THAT.
    lcl: Value,
    arg: Value,
    this: Value,
    that: Value,
}

/// Desktop, in `Translator::flags_known` beside the flags: the block's
/// `pop pointer` tested that THIS (THAT) lies in its desktop range.
fn in_range(this: bool) -> u8 {
    if this {
        0x40
    } else {
        0x80
    }
}

/// How a `this` or `that` access of a block tests its address.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum PtrTest {
    /// On its own (an index too large for a span test).
    Each,
    /// The first access while the pointer keeps its value in the block:
    /// it tests the span of every index of those accesses, up to this one.
    First(u16),
    /// Covered by the first access's test.
    Covered,
}

/// The address tests of the `this`/`that` accesses of `code` (one block):
/// the accesses between two `pop pointer`s of one pointer share one test.
fn ptr_tests(code: &[Op]) -> Vec<PtrTest> {
    let mut tests = vec![PtrTest::Each; code.len()];
    // The first access of each pointer's open run.
    let mut run: [Option<usize>; 2] = [None; 2];
    for (k, op) in code.iter().enumerate() {
        let (p, i) = match *op {
            Op::PushThis(i) | Op::PushThisChk(i) | Op::PopThis(i) | Op::PopThisChk(i) => (0, i),
            Op::PushThat(i) | Op::PushThatChk(i) | Op::PopThat(i) | Op::PopThatChk(i) => (1, i),
            Op::PopPtr(p) => {
                run[usize::from(p)] = None;
                continue;
            }
            // (In an inline run's body: the nested run's return reloads
            // both pointers from its frame.)
            Op::Call { .. } => {
                run = [None; 2];
                continue;
            }
            _ => continue,
        };
        if usize::from(i) + 6 >= RAM_SIZE {
            continue;
        }
        match run[p] {
            Some(first) => {
                if let PtrTest::First(top) = &mut tests[first] {
                    *top = (*top).max(i);
                }
                tests[k] = PtrTest::Covered;
            }
            None => {
                tests[k] = PtrTest::First(i);
                run[p] = Some(k);
            }
        }
    }
    tests
}

/// The stack words block code `code` holds in registers, `lo..hi`
/// relative to SP at its start (None if none): those it touches after its
/// `function` line, whose zeroed locals go to RAM at once; and the
/// instructions after that line.
fn held_span(code: &[Op]) -> (Option<(i32, i32)>, &[Op]) {
    let (locals, rest) = match code {
        [Op::Function { n_vars, .. }, rest @ ..] => (i32::from(*n_vars), rest),
        _ => (0, code),
    };
    let (min_depth, max_depth) = blocks::depth_range_through_calls(rest);
    let span = (min_depth < max_depth).then_some((locals + min_depth, locals + max_depth));
    (span, rest)
}

/// Index in `Translator::reach`.
const LOCAL: usize = 0;
const ARGUMENT: usize = 1;

/// The highest index of each of `local` and `argument` used in `code`, if
/// any, and if small enough that a plain LCL (ARG) below it is testable.
fn reach(code: &[Op]) -> [Option<u16>; 2] {
    let mut top = [None; 2];
    for op in code {
        let (seg, i) = match *op {
            Op::PushLocal(i) | Op::PopLocal(i) => (LOCAL, i),
            Op::PushArg(i) | Op::PopArg(i) => (ARGUMENT, i),
            _ => continue,
        };
        top[seg] = Some(top[seg].map_or(i, |t: u16| t.max(i)));
    }
    top.map(|t| t.filter(|&t| usize::from(t) + 6 < RAM_SIZE))
}

/// A block that leaves compiled code, its parameters (code, pc, function).
fn leave_block(b: &mut FunctionBuilder<'_>) -> ir::Block {
    let block = b.create_block();
    for _ in 0..3 {
        b.append_block_param(block, T32);
    }
    block
}

/// Build the IR of function `env.id` into `b` (signature: ctx pointer,
/// block index; returns the code).
pub(crate) fn translate(mut b: FunctionBuilder<'_>, env: Env<'_>) {
    let start = env.start;
    let (vm_blocks, block_at) = (env.blocks, env.block_at);

    let entry = b.create_block();
    b.append_block_params_for_function_params(entry);
    b.switch_to_block(entry);
    b.set_srcloc(source_loc(start, Part::FunctionEntry));
    let params = b.block_params(entry).to_vec();
    let (ctx, which) = (params[0], params[1]);
    let v = Vars {
        sp: b.declare_var(T32),
        lcl: b.declare_var(T32),
        arg: b.declare_var(T32),
        this: b.declare_var(T32),
        that: b.declare_var(T32),
        flags: b.declare_var(T32),
        nargs: b.declare_var(T32),
        steps: b.declare_var(T64),
    };
    let mem = Mem::new(b.func);
    let ram = b
        .ins()
        .load(T64, mem.fixed, ctx, field(offset_of!(Ctx, ram)));
    let stop_at = b
        .ins()
        .load(T64, mem.fixed, ctx, field(offset_of!(Ctx, stop_at)));
    let end = blocks::code_end(vm_blocks, start);
    let reach = reach(&env.code[start as usize..end as usize]);
    let depths = env.depths;
    let budgets = blocks::budgets(env.code, start, vm_blocks, block_at);
    let held: Vec<Variable> = (0..held_locals(&env, depths, reach))
        .map(|_| b.declare_var(T32))
        .collect();
    let leave_held = leave_block(&mut b);
    let cl: Vec<ir::Block> = vm_blocks.iter().map(|_| b.create_block()).collect();
    let leave = leave_block(&mut b);
    let slots = b.create_sized_stack_slot(ir::StackSlotData::new(
        ir::StackSlotKind::ExplicitSlot,
        16,
        3,
    ));
    b.ins().stack_store(T64, which, slots, SLOT_WHICH);
    let mut t = Translator {
        b,
        env,
        v,
        ctx,
        ram,
        stop_at,
        slots,
        mem,
        cl,
        block_at,
        start,
        leave,
        reach,
        flags_known: 0,
        ptr_tests: Vec::new(),
        block_start: 0,
        stack_span: None,
        frame_tops: [None; 2],
        depths,
        lcl_host: None,
        budgets,
        frame_shown: false,
        range: None,
        inlined: Vec::new(),
        inline_args: Vec::new(),
        return_registers: None,
        held,
        leave_held,
        locals_live: false,
        zero_extended: HashSet::new(),
    };
    t.range = t.static_range();
    // A compiled call passes the registers; the dispatcher, the context.
    let called = t.entered_by_call(which);
    let (from_call, from_ctx, join) = (t.b.create_block(), t.b.create_block(), t.b.create_block());
    t.b.ins().brif(called, from_call, NONE, from_ctx, NONE);
    t.b.switch_to_block(from_call);
    t.enter_called(&params[2..]);
    t.b.ins().jump(join, NONE);
    t.b.switch_to_block(from_ctx);
    t.load_state();
    t.b.ins().jump(join, NONE);
    t.b.switch_to_block(join);
    for (seg, var) in [(LOCAL, t.v.lcl), (ARGUMENT, t.v.arg)] {
        if let Some(top) = t.reach[seg] {
            t.frame_tops[seg] = Some(t.seg_addr(var, top));
        }
    }
    // A call enters at the first block (index 0); the dispatcher at
    // `which`, and an index out of range (never passed) leaves at once
    // with the pc the caller gave.
    let zero = t.c32(0);
    let which = t.b.ins().select(called, zero, which);
    if t.depths.is_some() {
        t.lcl_host = Some(t.seg_base(t.v.lcl));
    }
    let default = t.b.create_block();
    // A compiled call's frame shows most of the entry test: with static
    // depths the call path makes only what it does not (`called_ok`).
    let (from_call, from_ctx) = (t.b.create_block(), t.b.create_block());
    t.b.ins().brif(called, from_call, NONE, from_ctx, NONE);
    t.b.switch_to_block(from_call);
    // (The held locals are the `function` line's zeroes before any use.)
    for var in t.held.clone() {
        let zero = t.c16(0);
        t.b.def_var(var, zero);
    }
    match t.called_ok().or_else(|| t.entry_ok()) {
        Some(ok) => {
            let bad = t.b.create_block();
            t.b.ins().brif(ok, t.cl[0], NONE, bad, NONE);
            t.b.switch_to_block(bad);
            t.b.set_cold_block(bad);
            let pc = t.c32(i64::from(start));
            t.leave_with(pc, pc);
        }
        None => {
            t.b.ins().jump(t.cl[0], NONE);
        }
    }
    t.b.switch_to_block(from_ctx);
    if let Some(ok) = t.entry_ok() {
        // LCL or ARG such that some access of the function would not be
        // a plain word: the interpreter runs from the block's start.
        let (run, bad) = (t.b.create_block(), t.b.create_block());
        t.b.ins().brif(ok, run, NONE, bad, NONE);
        t.b.switch_to_block(bad);
        t.b.set_cold_block(bad);
        let exits: Vec<_> = vm_blocks
            .iter()
            .map(|blk| {
                let pc = t.c32(i64::from(blk.start));
                let me = t.c32(i64::from(t.env.id));
                let args = [
                    BlockArg::Value(pc),
                    BlockArg::Value(pc),
                    BlockArg::Value(me),
                ];
                t.b.func.dfg.block_call(leave, &args)
            })
            .collect();
        let def = t.b.func.dfg.block_call(default, NONE);
        let table = t.b.create_jump_table(JumpTableData::new(def, &exits));
        t.b.ins().br_table(which, table);
        t.b.switch_to_block(run);
    }
    let dispatch = t.b.create_block();
    t.b.ins().jump(dispatch, NONE);
    let stubs: Vec<_> = vm_blocks
        .iter()
        .enumerate()
        .map(|(i, blk)| {
            let stub = t.entry_stub(i, blk);
            t.b.func.dfg.block_call(stub, NONE)
        })
        .collect();
    t.b.switch_to_block(dispatch);
    // The entry test showed the held locals' words plain.
    for (i, var) in t.held.clone().into_iter().enumerate() {
        let p = t.lcl_host.expect("held locals have static depths");
        let x = t.load_at(p, i as u16);
        t.b.def_var(var, x);
    }
    let def = t.b.func.dfg.block_call(default, NONE);
    let table = t.b.create_jump_table(JumpTableData::new(def, &stubs));
    t.b.ins().br_table(which, table);

    t.b.switch_to_block(default);
    let pc =
        t.b.ins()
            .load(T32, mem.ctx, ctx, field(offset_of!(Ctx, pc)));
    t.leave_with(pc, pc);

    for (i, blk) in vm_blocks.iter().enumerate() {
        t.block(i, blk);
    }

    if !t.held.is_empty() {
        t.b.switch_to_block(leave_held);
        t.b.set_srcloc(source_loc(start, Part::Leave));
        // (Its first three parameters; the variables add theirs.)
        let args: Vec<BlockArg> = t.b.block_params(leave_held)[..3]
            .iter()
            .map(|&x| BlockArg::Value(x))
            .collect();
        t.store_held();
        t.b.ins().jump(leave, &args);
    }
    t.b.switch_to_block(leave);
    t.b.set_srcloc(source_loc(start, Part::Leave));
    let [code, pc, cur] = t.b.block_params(leave) else {
        unreachable!("leave has three parameters")
    };
    let (code, pc, cur) = (*code, *pc, *cur);
    t.store_state();
    t.b.ins()
        .store(mem.ctx, pc, ctx, field(offset_of!(Ctx, pc)));
    t.b.ins()
        .store(mem.ctx, cur, ctx, field(offset_of!(Ctx, cur)));
    let steps = t.b.use_var(t.v.steps);
    t.b.ins().return_(&[code, steps]);
    t.b.seal_all_blocks();
    t.b.finalize(t.env.target);
}

impl Translator<'_, '_> {
    /// A field of the context that stays fixed while compiled code runs
    /// (a pointer or a limit, at `offset`).
    fn fixed_field(&mut self, offset: usize) -> Value {
        self.b
            .ins()
            .load(T64, self.mem.fixed, self.ctx, field(offset))
    }

    /// The frame stack's length.
    fn frames_len(&mut self) -> Value {
        self.b.ins().load(
            T64,
            self.mem.ctx,
            self.ctx,
            field(offset_of!(Ctx, frames_len)),
        )
    }

    /// The 16-bit word `v` as a value: zero-extended, in 32 bits.
    fn c16(&mut self, v: i64) -> Value {
        let x = self.b.ins().iconst(T32, v & 0xFFFF);
        self.zero_extended.insert(x);
        x
    }

    /// The word in the low 16 bits of `x`, zero-extended (an address, or
    /// a register's value).
    fn exact(&mut self, x: Value) -> Value {
        if self.zero_extended.contains(&x) {
            return x;
        }
        let w = self.b.ins().band_imm_u(x, 0xFFFF);
        self.zero_extended.insert(w);
        w
    }

    /// The word in the low 16 bits of `x` in the high 16 bits, so that
    /// 32-bit comparisons of two such values compare the words as signed
    /// 16-bit numbers (and `Equal` compares the words).
    fn signed_high(&mut self, x: Value) -> Value {
        match self.word_const(x) {
            Some(c) => self.c32(c << 16),
            None => self.b.ins().ishl_imm_u(x, 16),
        }
    }

    /// The word `x` holds where it is a constant (`push constant`, and
    /// `neg` or `not` of one, which Jack writes for negative numbers).
    fn word_const(&self, x: Value) -> Option<i64> {
        let ir::ValueDef::Result(inst, 0) = self.b.func.dfg.value_def(x) else {
            return None;
        };
        match self.b.func.dfg.insts[inst] {
            ir::InstructionData::UnaryImm {
                opcode: ir::Opcode::Iconst,
                imm,
            } => Some(imm.bits() & 0xFFFF),
            _ => None,
        }
    }

    /// Whether the zero-extended word `x` is not negative as a 16-bit
    /// number.
    fn non_negative(&mut self, x: Value) -> Value {
        self.b.ins().icmp_imm_u(IntCC::UnsignedLessThan, x, 0x8000)
    }

    /// The word in the low 16 bits of `x`, sign-extended to 32 bits.
    fn signed(&mut self, x: Value) -> Value {
        let high = self.signed_high(x);
        self.b.ins().sshr_imm_u(high, 16)
    }

    /// Load the word at host address `p` + `offset`, zero-extended.
    fn load16(&mut self, flags: MemFlagsData, p: Value, offset: i32) -> Value {
        let x = self.b.ins().uload16(T32, flags, p, offset);
        self.zero_extended.insert(x);
        x
    }

    /// Store the low 16 bits of `x` at host address `p` + `offset`.
    fn store16(&mut self, flags: MemFlagsData, x: Value, p: Value, offset: i32) {
        self.plain_or_trap(flags, p, offset);
        self.b.ins().istore16(flags, x, p, offset);
    }

    /// Debug builds (the tests): a RAM store at host address `p` +
    /// `offset` traps unless it is a plain word, 5 to 24576. Every test
    /// before a store is meant to show that, so a wrong one crashes the
    /// test instead of writing a register's word or past the RAM buffer,
    /// which no comparison of results might see (a load from a wrong word
    /// shows in the value it reads; not checking loads halves the cost).
    fn plain_or_trap(&mut self, flags: MemFlagsData, p: Value, offset: i32) {
        if !cfg!(debug_assertions) || flags != self.mem.ram {
            return;
        }
        let a = self.b.ins().iadd_imm_s(p, i64::from(offset) - 10);
        let d = self.b.ins().isub(a, self.ram);
        let outside =
            self.b
                .ins()
                .icmp_imm_u(IntCC::UnsignedGreaterThan, d, 2 * (RAM_SIZE as i64 - 1 - 5));
        self.b.ins().trapnz(outside, TrapCode::unwrap_user(1));
    }

    fn c32(&mut self, v: i64) -> Value {
        self.b.ins().iconst(T32, v & 0xFFFF_FFFF)
    }

    /// Define the registers from a compiled call's arguments (see
    /// `native::Entry`): the caller's SP (where the frame begins), THIS and
    /// THAT, the argument count and entry flags, the step count.
    fn enter_called(&mut self, args: &[Value]) {
        let (base, ptrs, nargs_flags, steps) = (args[0], args[1], args[2], args[3]);
        let nargs = self.exact(nargs_flags);
        let lcl = self.b.ins().iadd_imm_s(base, 5);
        let arg = self.b.ins().isub(base, nargs);
        let f = &self.env.program.functions[self.env.id as usize];
        let locals = zeroed_by_call(self.env.timing, f);
        let sp = self.b.ins().iadd_imm_s(lcl, i64::from(locals));
        let this = self.exact(ptrs);
        let that = self.b.ins().ushr_imm_u(ptrs, 16);
        let flags = self.b.ins().ushr_imm_u(nargs_flags, 16);
        for (var, x) in [
            (self.v.sp, sp),
            (self.v.lcl, lcl),
            (self.v.arg, arg),
            (self.v.this, this),
            (self.v.that, that),
            (self.v.nargs, nargs),
            (self.v.flags, flags),
            (self.v.steps, steps),
        ] {
            self.b.def_var(var, x);
        }
    }

    /// The registers as the context holds them: variable, field offset,
    /// and width in the context (the flags are one byte, the step count
    /// eight, the others a word; all but the step count are 32-bit
    /// variables).
    fn state_fields(&self) -> [(Variable, usize, ir::Type); 8] {
        [
            (self.v.sp, offset_of!(Ctx, sp), types::I16),
            (self.v.lcl, offset_of!(Ctx, lcl), types::I16),
            (self.v.arg, offset_of!(Ctx, arg), types::I16),
            (self.v.this, offset_of!(Ctx, this), types::I16),
            (self.v.that, offset_of!(Ctx, that), types::I16),
            (self.v.nargs, offset_of!(Ctx, nargs), types::I16),
            (self.v.flags, offset_of!(Ctx, flags), types::I8),
            (self.v.steps, offset_of!(Ctx, steps), T64),
        ]
    }

    /// Load the registers from the context into the variables.
    fn load_state(&mut self) {
        let mem = self.mem.ctx;
        for (var, o, ty) in self.state_fields() {
            let x = match ty {
                types::I8 => self.b.ins().uload8(T32, mem, self.ctx, field(o)),
                types::I16 => self.load16(mem, self.ctx, field(o)),
                _ => self.b.ins().load(ty, mem, self.ctx, field(o)),
            };
            self.b.def_var(var, x);
        }
    }

    /// Store the variables into the context.
    fn store_state(&mut self) {
        let mem = self.mem.ctx;
        for (var, o, ty) in self.state_fields() {
            let x = self.b.use_var(var);
            match ty {
                types::I8 => {
                    self.b.ins().istore8(mem, x, self.ctx, field(o));
                }
                types::I16 => self.store16(mem, x, self.ctx, field(o)),
                _ => {
                    self.b.ins().store(mem, x, self.ctx, field(o));
                }
            }
        }
    }

    /// The host address of RAM word `a` (a zero-extended value known to be
    /// a plain word).
    fn word(&mut self, a: Value) -> Value {
        let a = self.b.ins().uextend(T64, a);
        let off = self.b.ins().ishl_imm_u(a, 1);
        self.b.ins().iadd(self.ram, off)
    }

    fn load_word(&mut self, a: Value) -> Value {
        let p = self.word(a);
        self.load16(self.mem.ram, p, 0)
    }

    fn store_word(&mut self, a: Value, x: Value) {
        let p = self.word(a);
        self.store16(self.mem.ram, x, p, 0);
    }

    /// `5 <= a <= 24576` for a zero-extended address (or a sum of one and
    /// an offset, which a word past 65535 fails).
    fn is_plain(&mut self, a: Value) -> Value {
        self.plain_from(a, 0)
    }

    /// Whether `a + 0 ..= a + top` are all plain words, with no wrapping:
    /// 5 <= a <= RAM_SIZE - 1 - top.
    fn plain_from(&mut self, a: Value, top: u16) -> Value {
        let limit = RAM_SIZE as i64 - 5 - i64::from(top);
        if limit <= 0 {
            return self.b.ins().iconst(types::I8, 0);
        }
        let t = self.b.ins().iadd_imm_s(a, -5);
        self.b.ins().icmp_imm_u(IntCC::UnsignedLessThan, t, limit)
    }

    /// Continue if `ok`, else leave for the interpreter at `at.pc` with
    /// the state before that instruction (computed only on the way out).
    fn guard(&mut self, ok: Value, at: &Before) {
        self.guard_all(&[ok], at);
    }

    /// Continue if every one of `conds` holds (each its own branch to one
    /// shared exit), else leave as [`Self::guard`] does.
    fn guard_all(&mut self, conds: &[Value], at: &Before) {
        if conds.is_empty() {
            return;
        }
        let stub = self.b.create_block();
        for &ok in conds {
            let cont = self.b.create_block();
            self.b.ins().brif(ok, cont, NONE, stub, NONE);
            self.b.switch_to_block(cont);
        }
        let cont = self.b.current_block().expect("a block");
        self.b.switch_to_block(stub);
        self.b.set_cold_block(stub);
        self.exit_before(at);
        self.b.switch_to_block(cont);
    }

    /// Write stack words (depth relative to `base`, value) to RAM.
    fn store_pending(&mut self, base: Value, words: &[(i32, Value)]) {
        for &(d, x) in words {
            self.store16(self.mem.ram, x, base, 2 * d);
        }
    }

    /// Leave for the interpreter at `at.pc`, in the state before it.
    fn exit_before(&mut self, at: &Before) {
        self.store_pending(at.base, &at.pending);
        let steps = self.b.ins().iadd_imm_s(at.steps0, at.k as i64);
        self.b.def_var(self.v.steps, steps);
        let sp = self.b.ins().iadd_imm_s(at.sp0, i64::from(at.depth));
        self.b.def_var(self.v.sp, sp);
        let pc = self.c32(i64::from(at.pc));
        self.leave_with(pc, pc);
    }

    /// Leave compiled code with `code` and `pc`, in this function (or in
    /// the callee being run inline, after pushing its frame, and those of
    /// the runs it is nested in, on the frame stack).
    fn leave_with(&mut self, code: Value, pc: Value) {
        self.write_return_registers();
        let calls = self.inlined.clone();
        if let Some(first) = calls.first() {
            self.write_frame_entries(&calls, first.frames_len);
            let len = self
                .b
                .ins()
                .iadd_imm_s(first.frames_len, calls.len() as i64);
            self.set_frames_len(len);
        }
        let me = calls.last().map_or(self.env.id, |call| call.callee);
        let me = self.c32(i64::from(me));
        let args = [
            BlockArg::Value(code),
            BlockArg::Value(pc),
            BlockArg::Value(me),
        ];
        let leave = if self.locals_live && !self.held.is_empty() {
            self.leave_held
        } else {
            self.leave
        };
        self.b.ins().jump(leave, &args);
    }

    /// Write the held locals to their words (at LCL, as the entry found it).
    fn store_held(&mut self) {
        for (i, var) in self.held.clone().into_iter().enumerate() {
            let p = self.lcl_host.expect("held locals have static depths");
            let x = self.b.use_var(var);
            self.store_at(p, i as u16, x);
        }
    }

    /// The held variable of `local i`, in the function's own code (not in
    /// an inline run's body).
    fn held_local(&self, i: u16) -> Option<Variable> {
        if self.inlined.is_empty() {
            self.held.get(usize::from(i)).copied()
        } else {
            None
        }
    }

    fn flag_set(&mut self, bit: u8) -> Value {
        let flags = self.b.use_var(self.v.flags);
        let m = self.b.ins().band_imm_u(flags, i64::from(bit));
        self.b.ins().icmp_imm_s(IntCC::NotEqual, m, 0)
    }

    fn set_flag(&mut self, bit: u8) {
        let flags = self.b.use_var(self.v.flags);
        let f = self.b.ins().bor_imm_u(flags, i64::from(bit));
        self.b.def_var(self.v.flags, f);
    }

    fn jump_to(&mut self, pc: u32) {
        let i = self.block_at[(pc - self.start) as usize].expect("jump targets start blocks");
        let blk = self.cl[i as usize];
        self.b.ins().jump(blk, NONE);
    }

    /// SP - LCL at the start of block `blk`, where depths are static
    /// (`Some(None)`: no path reaches it).
    fn depth_at(&self, blk: &Block) -> Option<Option<i32>> {
        let d = self.depths?;
        Some(d[(blk.start - self.start) as usize])
    }

    /// Whether compiled code can run block `blk` at all (else entering it
    /// leaves for the interpreter at once).
    fn runs(&self, blk: &Block) -> bool {
        blk.steps > 0 && self.depth_at(blk) != Some(None)
    }

    /// Whether `steps0` plus `covers` stays under the stop.
    fn fits(&mut self, steps0: Value, covers: u64) -> Value {
        let last = self.b.ins().iadd_imm_s(steps0, covers as i64);
        self.b
            .ins()
            .icmp(IntCC::UnsignedLessThanOrEqual, last, self.stop_at)
    }

    /// Where the dispatcher enters block `index`: it tests the budget the
    /// block covers and, where depths are static, that SP is LCL + the
    /// block's depth; else it leaves at the block's start.
    fn entry_stub(&mut self, index: usize, blk: &Block) -> ir::Block {
        if !self.runs(blk) {
            return self.cl[index];
        }
        let stub = self.b.create_block();
        self.b.switch_to_block(stub);
        self.b.set_srcloc(source_loc(blk.start, Part::BlockEntry));
        let steps0 = self.b.use_var(self.v.steps);
        let sp0 = self.b.use_var(self.v.sp);
        let mut ok = vec![self.fits(steps0, self.budgets[index].covers)];
        if let Some(Some(d)) = self.depth_at(blk) {
            let sp = self.lcl_plus(d);
            ok.push(self.b.ins().icmp(IntCC::Equal, sp0, sp));
        }
        let at = Before {
            pc: blk.start,
            k: 0,
            depth: 0,
            steps0,
            sp0,
            base: self.ram,
            pending: Vec::new(),
        };
        self.guard_all(&ok, &at);
        self.b.ins().jump(self.cl[index], NONE);
        stub
    }

    /// The stack range of a function with static depths (see
    /// `Translator::range`).
    fn static_range(&self) -> Option<(i32, i32, i32)> {
        let depths = self.depths?;
        let (mut low, mut high) = (i32::MAX, i32::MIN);
        let mut args_below = i32::MAX;
        for blk in self.env.blocks {
            let Some(d) = depths[(blk.start - self.start) as usize] else {
                continue;
            };
            if blk.steps == 0 {
                continue;
            }
            low = low.min(d + blk.min_depth);
            high = high.max(d + blk.max_depth);
            let code = &self.env.code[blk.start as usize..blk.end as usize];
            if let Some(&Op::Call { callee, nargs, .. }) = code.last() {
                let at = depths[(blk.end - 1 - self.start) as usize].expect("reached");
                low = low.min(at);
                high = high.max(at + 5 + self.frame_top(FnId::from(callee), nargs));
            }
            if let (Some((lo, _)), rest) = held_span(code) {
                if reach(rest)[ARGUMENT].is_some() {
                    args_below = args_below.min(d + lo);
                }
            }
        }
        (low <= high).then_some((low, high, args_below))
    }

    /// The tests that static depths move to the function's entry (None
    /// where depths are not static): the stack words of every block and
    /// every call's frame lie from 256 to the profile's stack end, and the
    /// `argument` words lie below every block's stack words.
    fn static_ok(&mut self) -> Option<Value> {
        let (low, high, args_below) = self.range?;
        // 256 - low <= LCL <= stack end - high, in 32 bits (no wrapping).
        let first = i64::from(STACK_BASE) - i64::from(low);
        let last = i64::from(self.env.timing.stack_end()) - i64::from(high);
        let mut ok = if last < first {
            self.b.ins().iconst(types::I8, 0)
        } else {
            let lcl = self.b.use_var(self.v.lcl);
            let d = self.b.ins().iadd_imm_s(lcl, -first);
            self.b
                .ins()
                .icmp_imm_u(IntCC::UnsignedLessThanOrEqual, d, last - first)
        };
        if let (Some(top), true) = (self.frame_tops[ARGUMENT], args_below < i32::MAX) {
            let lo = self.lcl_plus(args_below);
            let c = self.b.ins().icmp(IntCC::UnsignedLessThan, top, lo);
            ok = self.b.ins().band(ok, c);
        }
        // 10 <= LCL <= RAM_SIZE follows where first >= 10 (the stack end is
        // at most RAM_SIZE and high >= 0); ARG plain is tested here.
        if first >= 10 && high >= 0 {
            let arg = self.b.use_var(self.v.arg);
            let c = self.is_plain(arg);
            ok = self.b.ins().band(ok, c);
            self.frame_shown = true;
        }
        Some(ok)
    }

    /// The whole entry test (None: nothing to test); with held locals,
    /// the `argument` words lie below LCL (a compiled call's do).
    fn entry_ok(&mut self) -> Option<Value> {
        let ok = match (self.frame_ok(), self.static_ok()) {
            (Some(a), Some(b)) => Some(self.b.ins().band(a, b)),
            (a, b) => a.or(b),
        };
        match (self.frame_tops[ARGUMENT], ok) {
            (Some(top), Some(ok)) if !self.held.is_empty() => {
                let lcl = self.b.use_var(self.v.lcl);
                let below = self.b.ins().icmp(IntCC::UnsignedLessThan, top, lcl);
                Some(self.b.ins().band(ok, below))
            }
            _ => ok,
        }
    }

    /// The entry test on a compiled call's path, where depths are static
    /// and the call's frame shows the rest (None: make the whole test).
    /// The call made LCL = base + 5 and ARG = base - nargs for a base
    /// from 256 to the stack end less the frame, with nargs at most
    /// [`MAX_COMPILED_ARGS`]: so LCL >= 261, ARG is plain, the arguments
    /// lie below base, and what remains is the top of the stack and the
    /// argument count.
    fn called_ok(&mut self) -> Option<Value> {
        let (low, high, args_below) = self.range?;
        let locals_fit = self.reach[LOCAL].is_none_or(|top| i32::from(top) < high);
        if low < -5 || high < 0 || !locals_fit || args_below <= -6 {
            return None;
        }
        let lcl = self.b.use_var(self.v.lcl);
        let last = i64::from(self.env.timing.stack_end()) - i64::from(high);
        let mut ok = self
            .b
            .ins()
            .icmp_imm_u(IntCC::UnsignedLessThanOrEqual, lcl, last);
        if let Some(top) = self.reach[ARGUMENT] {
            let nargs = self.b.use_var(self.v.nargs);
            let fit = self
                .b
                .ins()
                .icmp_imm_u(IntCC::UnsignedGreaterThan, nargs, i64::from(top));
            ok = self.b.ins().band(ok, fit);
        }
        Some(ok)
    }

    fn block(&mut self, index: usize, blk: &Block) {
        self.b.switch_to_block(self.cl[index]);
        // The first block's `function` line makes the held locals live.
        self.locals_live = index > 0;
        self.b.set_srcloc(source_loc(blk.start, Part::BlockEntry));
        self.flags_known = 0;
        self.ptr_tests = ptr_tests(&self.env.code[blk.start as usize..blk.end as usize]);
        self.block_start = blk.start;
        let steps0 = self.b.use_var(self.v.steps);
        if !self.runs(blk) {
            let pc = self.c32(i64::from(blk.start));
            self.leave_with(pc, pc);
            return;
        }
        let depth = self.depth_at(blk).flatten();
        let sp0 = match depth {
            Some(d) => {
                let sp = self.lcl_plus(d);
                self.b.def_var(self.v.sp, sp);
                sp
            }
            None => self.b.use_var(self.v.sp),
        };
        // The block's steps, and those of the blocks after it up to the
        // next test, fit under the stop (a loop's head and a function's
        // entry test; the dispatcher tests where it enters).
        let budget = self.budgets[index];
        let mut ok = Vec::new();
        if budget.tested {
            ok.push(self.fits(steps0, budget.covers));
        }
        if blk.checks_stack && depth.is_none() {
            // Its stack stays where no stack rule applies: from 256 (no
            // pop at SP = 256) up to the profile's stack end.
            // Stack words sp0+min_depth ..= sp0+max_depth-1 (or sp0-1):
            // low <= sp0 <= high, one unsigned test of sp0 - low.
            let low = i64::from(STACK_BASE) - i64::from(blk.min_depth);
            let high = i64::from(self.env.timing.stack_end()) - i64::from(blk.max_depth);
            let c = if high < low {
                self.b.ins().iconst(types::I8, 0)
            } else {
                let d = self.b.ins().iadd_imm_s(sp0, -low);
                self.b
                    .ins()
                    .icmp_imm_u(IntCC::UnsignedLessThanOrEqual, d, high - low)
            };
            ok.push(c);
        }
        let (span, code) = held_span(&self.env.code[blk.start as usize..blk.end as usize]);
        self.set_stack_span(sp0, span);
        if let Some((lo, _)) = self.stack_span {
            // The block's `local` and `argument` words lie below its stack
            // words, so the stack can stay in registers across them (with
            // static depths: known for `local`, tested on entry for
            // `argument`).
            let used = reach(code);
            for seg in [LOCAL, ARGUMENT] {
                if let (Some(top), Some(_)) = (self.frame_tops[seg], used[seg]) {
                    let c = match (depth, seg) {
                        (Some(_), ARGUMENT) => continue,
                        (Some(d), _) => {
                            let low = d + span.expect("a span").0;
                            if i32::from(self.reach[LOCAL].expect("a top")) < low {
                                continue;
                            }
                            self.b.ins().iconst(types::I8, 0)
                        }
                        (None, _) => self.b.ins().icmp(IntCC::UnsignedLessThan, top, lo),
                    };
                    ok.push(c);
                }
            }
        }
        let base = match (depth, self.lcl_host) {
            (Some(d), Some(p)) => self.b.ins().iadd_imm_s(p, 2 * i64::from(d)),
            _ => self.word(sp0),
        };
        let entry = Before {
            pc: blk.start,
            k: 0,
            depth: 0,
            steps0,
            sp0,
            base,
            pending: Vec::new(),
        };
        self.guard_all(&ok, &entry);

        let mut s = Stack {
            sp0,
            base,
            depth: 0,
            slots: Vec::new(),
        };
        self.ops(&mut s, blk.start, blk.end, steps0, blk);
        if blocks::kind(self.env.code[blk.end as usize - 1]) == Kind::Straight {
            // Falls through into the next block (or the interpreted
            // instruction that ends this one).
            self.end_block(&mut s, steps0, blk);
            self.jump_to(blk.end);
        }
    }

    /// Translate instructions `from..to` of a block entered with step count
    /// `steps0` and stack `s` (`blk` is the block of the function being
    /// translated, which a final jump, call or return charges). In the body
    /// of an inline run, a nested run's call is followed by a stretch of
    /// its own (its first instruction and step count): the last is
    /// returned.
    fn ops(
        &mut self,
        s: &mut Stack,
        from: u32,
        to: u32,
        steps0: Value,
        blk: &Block,
    ) -> (u32, Value) {
        let (first, mut from, mut steps0) = (from, from, steps0);
        for pc in first..to {
            let op = self.env.code[pc as usize];
            self.b.set_srcloc(source_loc(pc, Part::Op));
            if matches!(
                op,
                Op::PushAbs(13 | 14) | Op::PopAbs(13 | 14) | Op::PopRam(13 | 14)
            ) {
                self.write_return_registers();
                self.return_registers = None;
            }
            let may_touch_stack = self.may_touch_stack(op, pc);
            if may_touch_stack {
                s.flush(self);
            }
            if may_write_frames(op, self.env.profile) {
                for args in &mut self.inline_args {
                    args.fill(None);
                }
            }
            let before = Before {
                pc,
                k: u64::from(pc - from),
                depth: s.depth,
                steps0,
                sp0: s.sp0,
                base: s.base,
                pending: s.pending(),
            };
            self.op(op, s, &before, blk);
            if may_touch_stack || matches!(op, Op::Function { .. }) {
                // The words go to RAM, the one the instruction itself
                // pushed (`push that i`, a local zeroed) included, and are
                // read back from there.
                s.flush(self);
                s.forget();
            }
            if matches!(op, Op::Call { .. }) && !self.inlined.is_empty() {
                from = pc + 1;
                steps0 = self.b.use_var(self.v.steps);
            }
        }
        (from, steps0)
    }

    /// Whether `op` at `pc` reads or writes RAM where the block's
    /// registers-held stack words might be (so they go to RAM before it,
    /// and are read back after it): calls and returns, and the accesses
    /// that no entry or span test separates from the stack.
    fn may_touch_stack(&self, op: Op, pc: u32) -> bool {
        let ptr_each = || self.ptr_tests[(pc - self.block_start) as usize] == PtrTest::Each;
        match op {
            Op::Call { .. } | Op::Return => true,
            Op::PopRam(_) => blocks::pops_into_stack(op),
            Op::PushLocal(_) | Op::PopLocal(_) => self.reach[LOCAL].is_none(),
            Op::PushArg(_) | Op::PopArg(_) => self.reach[ARGUMENT].is_none(),
            Op::PushThis(_)
            | Op::PushThisChk(_)
            | Op::PopThis(_)
            | Op::PopThisChk(_)
            | Op::PushThat(_)
            | Op::PushThatChk(_)
            | Op::PopThat(_)
            | Op::PopThatChk(_) => ptr_each(),
            _ => false,
        }
    }

    /// Write the block's pending stack words, and define SP and the step
    /// count as they are after the whole block.
    fn end_block(&mut self, s: &mut Stack, steps0: Value, blk: &Block) {
        s.flush(self);
        let steps = self.b.ins().iadd_imm_s(steps0, blk.steps as i64);
        self.b.def_var(self.v.steps, steps);
        let sp = s.sp(self);
        self.b.def_var(self.v.sp, sp);
    }

    /// Read RAM[a] through a computed address.
    fn read(&mut self, a: Value, before: &Before) -> Value {
        let ok = self.is_plain(a);
        self.guard(ok, before);
        self.load_word(a)
    }

    /// Write RAM[a] through a computed address.
    fn write(&mut self, a: Value, x: Value, before: &Before) {
        let ok = self.is_plain(a);
        self.guard(ok, before);
        self.store_word(a, x);
    }

    /// LCL + `d`, a stack depth relative to LCL (below it where code pops
    /// into its frame), as a 32-bit sum: never wrapped to 16 bits.
    /// Set [`Translator::stack_span`] to `span` (from [`held_span`]),
    /// relative to SP `sp0`.
    fn set_stack_span(&mut self, sp0: Value, span: Option<(i32, i32)>) {
        self.stack_span = span.map(|(lo, hi)| {
            let lo = self.b.ins().iadd_imm_s(sp0, i64::from(lo));
            let hi = self.b.ins().iadd_imm_s(sp0, i64::from(hi));
            (lo, hi)
        });
    }

    fn lcl_plus(&mut self, d: i32) -> Value {
        let lcl = self.b.use_var(self.v.lcl);
        self.b.ins().iadd_imm_s(lcl, i64::from(d))
    }

    fn seg_addr(&mut self, var: Variable, i: u16) -> Value {
        let base = self.b.use_var(var);
        self.b.ins().iadd_imm_s(base, i64::from(i))
    }

    /// `argument i` is one of the arguments (the entry test covers it
    /// where the function's accesses are covered).
    fn arg_ok(&mut self, i: u16, before: &Before) {
        if self.reach[ARGUMENT].is_some() {
            return;
        }
        let nargs = self.b.use_var(self.v.nargs);
        let i = self.c16(i64::from(i));
        let ok = self.b.ins().icmp(IntCC::UnsignedGreaterThan, nargs, i);
        self.guard(ok, before);
    }

    /// Desktop: leave unless `pop pointer p` of `x` is in the pointer's
    /// range (the heap for THIS, 2048 to 24576 for THAT), so that the
    /// block's accesses through it at index 0 need no test. The other
    /// values the desktop takes (THIS not above 0, THAT 0, which widens the
    /// `that` range) and its errors are the interpreter's.
    fn desktop_pointer_ok(&mut self, p: u8, x: Value, before: &Before) {
        if self.env.profile != Profile::Desktop {
            return;
        }
        let from = self.b.ins().iadd_imm_s(x, -2048);
        let room = if p == 0 { 16383 - 2048 } else { 24576 - 2048 };
        let ok = self
            .b
            .ins()
            .icmp_imm_u(IntCC::UnsignedLessThanOrEqual, from, room);
        self.guard(ok, before);
        self.flags_known |= in_range(p == 0);
    }

    /// The web IDE's test that the invocation set the pointer (the desktop
    /// tests addresses instead, [`Self::desktop_span_ok`]).
    fn web_flag_ok(&mut self, bit: u8, before: &Before) {
        if self.env.profile != Profile::Desktop {
            self.flag_ok(bit, before);
        }
    }

    fn flag_ok(&mut self, bit: u8, before: &Before) {
        if self.flags_known & bit == 0 {
            let ok = self.flag_set(bit);
            self.guard(ok, before);
            self.flags_known |= bit;
        }
    }

    /// Whether LCL and ARG leave every `local` and `argument` access of the
    /// function (up to `reach`) on a plain word, without wrapping, and the
    /// argument count covers every `argument` index (None if no access is
    /// covered so).
    fn frame_ok(&mut self) -> Option<Value> {
        let mut ok = None;
        for (var, top) in [
            (self.v.lcl, self.reach[LOCAL]),
            (self.v.arg, self.reach[ARGUMENT]),
        ] {
            let Some(top) = top else { continue };
            let mut c = self.span_ok(var, top);
            if var == self.v.arg {
                let nargs = self.b.use_var(self.v.nargs);
                let fit =
                    self.b
                        .ins()
                        .icmp_imm_u(IntCC::UnsignedGreaterThan, nargs, i64::from(top));
                c = self.b.ins().band(c, fit);
            }
            ok = Some(match ok {
                None => c,
                Some(o) => self.b.ins().band(o, c),
            });
        }
        ok
    }

    /// [`Self::plain_from`] of register `var`'s value.
    fn span_ok(&mut self, var: Variable, top: u16) -> Value {
        let base = self.b.use_var(var);
        self.plain_from(base, top)
    }

    /// Leave unless the words `var + 0 ..= var + top` (no wrapping) miss
    /// the block's stack words: one test of the first word where they lie
    /// above the stack (objects and arrays on the heap), and of the last
    /// word where they do not.
    fn off_stack(&mut self, var: Variable, top: u16, before: &Before) {
        let Some((lo, hi)) = self.stack_span else {
            return;
        };
        let first = self.b.use_var(var);
        let above = self
            .b
            .ins()
            .icmp(IntCC::UnsignedGreaterThanOrEqual, first, hi);
        let (below, cont) = (self.b.create_block(), self.b.create_block());
        self.b.ins().brif(above, cont, NONE, below, NONE);
        self.b.switch_to_block(below);
        self.b.set_cold_block(below);
        let last = self.seg_addr(var, top);
        let ok = self.b.ins().icmp(IntCC::UnsignedLessThan, last, lo);
        self.guard(ok, before);
        self.b.ins().jump(cont, NONE);
        self.b.switch_to_block(cont);
    }

    /// The host address of the segment whose base register is `var`, whose
    /// accesses `var + i` a test has shown to be plain words (at offset 2i).
    fn seg_base(&mut self, var: Variable) -> Value {
        let base = self.b.use_var(var);
        self.word(base)
    }

    /// The host address of the segment of `this i` or `that i` (pointer
    /// register `var`), tested as the block's span tests decided (None:
    /// the caller tests the access's address).
    fn ptr_base(&mut self, var: Variable, before: &Before) -> Option<Value> {
        let test = self.ptr_tests[(before.pc - self.block_start) as usize];
        if let PtrTest::First(top) = test {
            if self.env.profile == Profile::Desktop {
                // The desktop's ranges lie above its stack (256..=2047)
                // and inside RAM: their test is the only one needed, and
                // none where the block's `pop pointer` tested word 0.
                if !(top == 0 && self.flags_known & in_range(var == self.v.this) != 0) {
                    self.desktop_span_ok(var, top, before);
                }
            } else {
                let ok = self.span_ok(var, top);
                self.guard(ok, before);
                self.off_stack(var, top, before);
            }
        }
        (test != PtrTest::Each).then(|| self.seg_base(var))
    }

    /// Desktop: leave unless `var + 0 ..= var + top` lie in the range the
    /// desktop allows the segment of pointer `var`: the heap for `this`,
    /// 2048 to 24576 for `that` (which the interpreter widens to word 0
    /// after a `pop pointer 1` of 0, a state compiled code never runs in).
    /// Stricter than the desktop only where the interpreter then decides.
    fn desktop_span_ok(&mut self, var: Variable, top: u16, before: &Before) {
        if self.env.profile != Profile::Desktop {
            return;
        }
        let end = if var == self.v.this { 16383 } else { 24576 };
        let room = end - 2048 - i64::from(top);
        let ok = if room < 0 {
            self.b.ins().iconst(types::I8, 0)
        } else {
            let base = self.b.use_var(var);
            let from = self.b.ins().iadd_imm_s(base, -2048);
            self.b
                .ins()
                .icmp_imm_u(IntCC::UnsignedLessThanOrEqual, from, room)
        };
        self.guard(ok, before);
    }

    fn ptr_read(&mut self, var: Variable, i: u16, before: &Before) -> Value {
        match self.ptr_base(var, before) {
            Some(p) => self.load_at(p, i),
            None => {
                self.desktop_span_ok(var, i, before);
                let a = self.seg_addr(var, i);
                self.read(a, before)
            }
        }
    }

    fn ptr_write(&mut self, var: Variable, i: u16, x: Value, before: &Before) {
        match self.ptr_base(var, before) {
            Some(p) => self.store_at(p, i, x),
            None => {
                self.desktop_span_ok(var, i, before);
                let a = self.seg_addr(var, i);
                self.write(a, x, before)
            }
        }
    }

    /// Word `i` from host address `p`.
    fn load_at(&mut self, p: Value, i: u16) -> Value {
        self.load16(self.mem.ram, p, 2 * i32::from(i))
    }

    /// Word `i` from host address `p` = x.
    fn store_at(&mut self, p: Value, i: u16, x: Value) {
        self.store16(self.mem.ram, x, p, 2 * i32::from(i));
    }

    /// RAM[base + i] of segment `seg` (`base` its register).
    fn seg_read(&mut self, seg: usize, var: Variable, i: u16, before: &Before) -> Value {
        if self.reach[seg].is_some() {
            let p = self.seg_base(var);
            self.load_at(p, i)
        } else {
            let a = self.seg_addr(var, i);
            self.read(a, before)
        }
    }

    /// RAM[base + i] = x, for segment `seg` (`base` its register).
    fn seg_write(&mut self, seg: usize, var: Variable, i: u16, x: Value, before: &Before) {
        if self.reach[seg].is_some() {
            let p = self.seg_base(var);
            self.store_at(p, i, x);
        } else {
            let a = self.seg_addr(var, i);
            self.write(a, x, before);
        }
    }

    fn op(&mut self, op: Op, s: &mut Stack, before: &Before, blk: &Block) {
        match op {
            Op::PushConst(c) => {
                let x = self.c16(i64::from(c));
                s.push(x);
            }
            Op::PushLocal(i) => {
                let x = match self.held_local(i) {
                    Some(var) => self.b.use_var(var),
                    None => self.seg_read(LOCAL, self.v.lcl, i, before),
                };
                s.push(x);
            }
            Op::PushArg(i) => {
                self.arg_ok(i, before);
                let known = self.inline_args.last().and_then(|a| a[usize::from(i)]);
                let x = match known {
                    Some(x) => x,
                    None => self.seg_read(ARGUMENT, self.v.arg, i, before),
                };
                s.push(x);
            }
            Op::PushThis(i) | Op::PushThisChk(i) => {
                if matches!(op, Op::PushThisChk(_)) {
                    self.web_flag_ok(THIS_OK, before);
                }
                let x = self.ptr_read(self.v.this, i, before);
                s.push(x);
            }
            Op::PushThat(i) | Op::PushThatChk(i) => {
                if matches!(op, Op::PushThatChk(_)) {
                    self.web_flag_ok(THAT_OK, before);
                }
                let x = self.ptr_read(self.v.that, i, before);
                s.push(x);
            }
            Op::PushAbs(a) => {
                let a = self.c16(i64::from(a));
                let x = self.load_word(a);
                s.push(x);
            }
            Op::PushPtr(p) => {
                let x = self
                    .b
                    .use_var(if p == 0 { self.v.this } else { self.v.that });
                self.zero_extended.insert(x);
                s.push(x);
            }
            Op::PopLocal(i) => {
                let x = s.pop(self);
                match self.held_local(i) {
                    Some(var) => self.b.def_var(var, x),
                    None => self.seg_write(LOCAL, self.v.lcl, i, x, before),
                }
            }
            Op::PopArg(i) => {
                self.arg_ok(i, before);
                let x = s.pop(self);
                self.seg_write(ARGUMENT, self.v.arg, i, x, before);
                if let Some(args) = self.inline_args.last_mut() {
                    args[usize::from(i)] = Some(x);
                }
            }
            Op::PopThis(i) | Op::PopThisChk(i) => {
                if matches!(op, Op::PopThisChk(_)) {
                    self.web_flag_ok(THIS_OK, before);
                }
                let x = s.pop(self);
                self.ptr_write(self.v.this, i, x, before);
            }
            Op::PopThat(i) | Op::PopThatChk(i) => {
                if matches!(op, Op::PopThatChk(_)) {
                    self.web_flag_ok(THAT_OK, before);
                }
                let x = s.pop(self);
                self.ptr_write(self.v.that, i, x, before);
            }
            Op::PopAbs(a) => {
                // 5..=255: never a stack word.
                let x = s.pop(self);
                let a = self.c16(i64::from(a));
                self.store_word(a, x);
            }
            Op::PopRam(a) => {
                let x = s.pop(self);
                let addr = self.c16(i64::from(a));
                self.store_word(addr, x);
            }
            Op::PopPtr(p) => {
                let x = s.pop(self);
                let x = self.exact(x);
                self.desktop_pointer_ok(p, x, before);
                let (var, bit) = if p == 0 {
                    (self.v.this, THIS_OK)
                } else {
                    (self.v.that, THAT_OK)
                };
                self.b.def_var(var, x);
                self.set_flag(bit);
                self.flags_known |= bit;
            }
            Op::Add | Op::Sub | Op::And | Op::Or | Op::Multiply => {
                let y = s.pop(self);
                let x = s.pop(self);
                let r = match op {
                    Op::Add => self.b.ins().iadd(x, y),
                    Op::Sub if self.env.fault == Some(Fault::SubSwapped) => self.b.ins().isub(y, x),
                    Op::Sub => self.b.ins().isub(x, y),
                    Op::And => self.b.ins().band(x, y),
                    Op::Or => self.b.ins().bor(x, y),
                    _ => self.b.ins().imul(x, y),
                };
                s.push(r);
            }
            Op::Eq | Op::Gt | Op::Lt => {
                let y = s.pop(self);
                let x = s.pop(self);
                let cc = match op {
                    Op::Eq => IntCC::Equal,
                    Op::Gt => IntCC::SignedGreaterThan,
                    _ => IntCC::SignedLessThan,
                };
                let words_equal = op == Op::Eq
                    && self.zero_extended.contains(&x)
                    && self.zero_extended.contains(&y);
                let (x, y) = if words_equal {
                    (x, y)
                } else {
                    (self.signed_high(x), self.signed_high(y))
                };
                let c = self.b.ins().icmp(cc, x, y);
                let r = self.b.ins().bmask(T32, c);
                s.push(r);
            }
            Op::Neg | Op::Not => {
                let x = s.pop(self);
                let r = match (self.word_const(x), op) {
                    (Some(c), Op::Neg) => self.c16(-c),
                    (Some(c), _) => self.c16(!c),
                    (None, Op::Neg) => self.b.ins().ineg(x),
                    (None, _) => self.b.ins().bnot(x),
                };
                s.push(r);
            }
            Op::Divide => {
                let y = s.pop(self);
                let x = s.pop(self);
                // A zero divisor goes through the OS's error path.
                let y = self.signed(y);
                let ok = self.b.ins().icmp_imm_s(IntCC::NotEqual, y, 0);
                self.guard(ok, before);
                let q = self.divide(x, y);
                s.push(q);
            }
            Op::Goto(t) => {
                self.end_block(s, before.steps0, blk);
                self.jump_to(t);
            }
            Op::IfGoto(t) => {
                let x = s.pop(self);
                let x = self.exact(x);
                let steps0 = before.steps0;
                self.end_block(s, steps0, blk);
                let taken = self.block_at[(t - self.start) as usize].expect("a block");
                let next = self.block_at[(before.pc + 1 - self.start) as usize].expect("a block");
                let (taken, next) = (self.cl[taken as usize], self.cl[next as usize]);
                self.b.ins().brif(x, taken, NONE, next, NONE);
            }
            Op::Call {
                callee, nargs, ret, ..
            } => self.call(FnId::from(callee), nargs, ret, s, before, blk),
            Op::Return => self.ret(s, before, blk),
            Op::CallBuiltin { builtin, .. } if blocks::inline_builtin(builtin) => {
                self.inline_builtin(builtin, s, before)
            }
            Op::CallBuiltin { builtin, nargs } => self.builtin(builtin, nargs, s, before, blk),
            Op::Function { n_vars, .. } => {
                // The locals, zeroed (the block's entry test covers them);
                // the held ones in their variables, RAM later.
                let held = match self.held_local(0) {
                    Some(_) => self.held.len(),
                    None => 0,
                };
                let zero = self.c16(0);
                for &var in &self.held[..held] {
                    self.b.def_var(var, zero);
                }
                s.depth += held as i32;
                for _ in held..usize::from(n_vars) {
                    let zero = self.c16(0);
                    s.push(zero);
                }
                self.locals_live = true;
            }
            _ => unreachable!("interpreted instructions end blocks before them"),
        }
    }

    /// A built-in that compiled code runs itself (`blocks::inline_builtin`);
    /// a `Memory.peek` or `poke` of a word outside plain RAM (desktop:
    /// outside the heap and the screen) leaves for the interpreter, as
    /// does a string built-in that would raise an error (see `strings`).
    fn inline_builtin(&mut self, builtin: jack_os::Builtin, s: &mut Stack, before: &Before) {
        use jack_os::Builtin::*;
        let r = match builtin {
            MathAbs => {
                let x = s.pop(self);
                let x = self.signed(x);
                self.b.ins().iabs(x)
            }
            MathMin | MathMax => {
                let y = s.pop(self);
                let y = self.signed(y);
                let x = s.pop(self);
                let x = self.signed(x);
                if builtin == MathMin {
                    self.b.ins().smin(x, y)
                } else {
                    self.b.ins().smax(x, y)
                }
            }
            MemoryPeek | MemoryPoke => {
                let v = (builtin == MemoryPoke).then(|| s.pop(self));
                let a = s.pop(self);
                let a = self.exact(a);
                let ok = self.os_word_ok(a);
                self.guard(ok, before);
                // The word may be one of the stack words held in registers.
                s.flush(self);
                let r = match v {
                    Some(v) => {
                        self.store_word(a, v);
                        self.c16(0)
                    }
                    None => self.load_word(a),
                };
                s.forget();
                r
            }
            StringLength | StringCharAt | StringAppendChar => {
                self.inline_string(builtin, s, before)
            }
            _ => unreachable!("only the built-ins blocks::inline_builtin names"),
        };
        s.push(r);
    }

    /// Whether zero-extended address `a` is a word a built-in reads and writes
    /// without a rule: web, a plain word (not a register, inside RAM);
    /// desktop, the heap or the screen (its `Memory` check, word 0 aside).
    fn os_word_ok(&mut self, a: Value) -> Value {
        match self.env.profile {
            Profile::Web => self.is_plain(a),
            Profile::Desktop => {
                let d = self.b.ins().iadd_imm_s(a, -i64::from(HEAP_START));
                let last = KBD as i64 - i64::from(HEAP_START);
                self.b
                    .ins()
                    .icmp_imm_u(IntCC::UnsignedLessThanOrEqual, d, last)
            }
        }
    }

    /// `call Class.builtin n` (not a blocking one) through a host call
    /// (`builtin::call`): the block ends, its state goes to the context,
    /// and compiled code goes on with the next block, or leaves where the
    /// built-in moved a register or ended the run. The block's stack test
    /// covers the pops, the push and (desktop) the built-in's frame.
    fn builtin(
        &mut self,
        builtin: jack_os::Builtin,
        n: u8,
        s: &mut Stack,
        before: &Before,
        blk: &Block,
    ) {
        let sp = s.sp(self);
        self.end_block(s, before.steps0, blk);
        let mut sig = ir::Signature::new(self.b.func.signature.call_conv);
        sig.params
            .extend([T64, T32, T64, T32, T64].map(AbiParam::new));
        sig.returns.push(AbiParam::new(T32));
        let sig = self.b.import_signature(sig);
        let host = builtin::call as unsafe extern "C" fn(*mut Ctx, u32, u64, u32, u64) -> i32;
        let host = self.b.ins().iconst(T64, host as usize as i64);
        let what = builtin::what(builtin, n, self.env.profile);
        let what = self.c32(i64::from(what));
        let mut regs = self.b.ins().uextend(T64, sp);
        for (var, shift) in [(self.v.lcl, 16), (self.v.arg, 32), (self.v.this, 48)] {
            let x = self.b.use_var(var);
            let x = self.b.ins().uextend(T64, x);
            let x = self.b.ins().ishl_imm_u(x, shift);
            regs = self.b.ins().bor(regs, x);
        }
        let that = self.b.use_var(self.v.that);
        let steps = self.b.use_var(self.v.steps);
        let call = self
            .b
            .ins()
            .call_indirect(sig, host, &[self.ctx, what, regs, that, steps]);
        let code = self.b.inst_results(call)[0];
        let steps = self
            .b
            .ins()
            .load(T64, self.mem.ctx, self.ctx, field(offset_of!(Ctx, steps)));
        self.b.def_var(self.v.steps, steps);
        let (cont, out) = (self.b.create_block(), self.b.create_block());
        let done = self
            .b
            .ins()
            .icmp_imm_s(IntCC::Equal, code, i64::from(builtin::DONE));
        self.b.ins().brif(done, cont, NONE, out, NONE);
        self.b.switch_to_block(out);
        self.b.set_cold_block(out);
        // The registers are the ones the built-in left in the context.
        for (var, o) in [
            (self.v.sp, offset_of!(Ctx, sp)),
            (self.v.lcl, offset_of!(Ctx, lcl)),
            (self.v.arg, offset_of!(Ctx, arg)),
            (self.v.this, offset_of!(Ctx, this)),
            (self.v.that, offset_of!(Ctx, that)),
        ] {
            let x = self.load16(self.mem.ctx, self.ctx, field(o));
            self.b.def_var(var, x);
        }
        let pc = self.c32(i64::from(before.pc + 1));
        self.leave_with(code, pc);
        self.b.switch_to_block(cont);
        let sp = self.b.ins().iadd_imm_s(sp, 1 - i64::from(n));
        self.b.def_var(self.v.sp, sp);
        self.jump_to(before.pc + 1);
    }

    /// `Math.divide` of `x` by a non-zero divisor `y` (sign-extended) under
    /// the OS's rounding.
    fn divide(&mut self, x: Value, y: Value) -> Value {
        // In 32 bits, so that -32768 / -1 does not trap (it wraps: only
        // the low 16 bits of the result count).
        let x32 = self.signed(x);
        let q = self.b.ins().sdiv(x32, y);
        match self.env.divide {
            jack_os::DivideRule::Truncate => q,
            jack_os::DivideRule::Floor => {
                // Round toward minus infinity: one less when the remainder
                // is non-zero and the signs differ.
                let r = self.b.ins().srem(x32, y);
                let inexact = self.b.ins().icmp_imm_s(IntCC::NotEqual, r, 0);
                let signs = self.b.ins().bxor(x32, y);
                let differ = self.b.ins().icmp_imm_s(IntCC::SignedLessThan, signs, 0);
                let both = self.b.ins().band(inexact, differ);
                let one = self.b.ins().uextend(T32, both);
                self.b.ins().isub(q, one)
            }
        }
    }

    /// `call callee nargs`: push the frame in RAM and run the callee's
    /// compiled code directly; when it returns here, continue with the
    /// next block. The frame stack's entry for the call is written only
    /// where compiled code leaves inside the callee (a compiled return
    /// reads nothing of it: the callee has the RET word as an argument), as
    /// for a callee that runs inline; inside an
    /// inline run (a nested call, which [`inline_run`] showed runs inline
    /// too), the run's code goes on after its return.
    fn call(
        &mut self,
        callee: FnId,
        n: u16,
        ret: u16,
        s: &mut Stack,
        before: &Before,
        blk: &Block,
    ) {
        let f = &self.env.program.functions[callee as usize];
        let n_vars = zeroed_by_call(self.env.timing, f);
        if n_vars > MAX_INLINE_LOCALS || n > MAX_COMPILED_ARGS {
            self.exit_before(before);
            return;
        }
        // Nested in an inline run: the frame stack holds none of the
        // frames of the runs around this call yet.
        let nested = self.inlined.last().copied();
        let len = match nested {
            Some(outer) => self.b.ins().iadd_imm_s(outer.frames_len, 1),
            None => self.frames_len(),
        };
        let inline = inline_callee(&self.env, callee, n, nested.is_none());
        // Room in the frame stack and native nesting bounded (no room if
        // calls must not run compiled) for the call's frame, and those of
        // the runs nested in it (tested by the outermost call), the callee
        // not watched, and the new frame in plain RAM.
        let mut ok = Vec::new();
        if nested.is_none() {
            let limit = self.fixed_field(offset_of!(Ctx, frames_limit));
            let frames = inline.map_or(1, |run| run.frames);
            let last = self.b.ins().iadd_imm_s(len, i64::from(frames) - 1);
            ok.push(self.b.ins().icmp(IntCC::UnsignedLessThan, last, limit));
        }
        if nested.is_none() {
            let watched = self.watched(&[callee]);
            ok.push(self.b.ins().icmp_imm_s(IntCC::Equal, watched, 0));
            if let Some(run) = inline {
                self.nested_unwatched(run, before);
            }
        }
        let base = s.sp(self);
        if self.depths.is_none() && nested.is_none() {
            // (With static depths the entry test covered the frame; the
            // test of the outermost inline run's call covers those nested
            // in it.)
            let base64 = self.b.ins().uextend(T64, base);
            let top = self.frame_top(callee, n);
            let top = self.b.ins().iadd_imm_s(base64, 5 + i64::from(top));
            let end = i64::from(self.env.timing.stack_end());
            ok.push(
                self.b
                    .ins()
                    .icmp_imm_s(IntCC::UnsignedLessThanOrEqual, top, end),
            );
            ok.push(self.b.ins().icmp_imm_s(
                IntCC::UnsignedGreaterThanOrEqual,
                base64,
                i64::from(STACK_BASE),
            ));
        }
        self.guard_all(&ok, before);

        // The frame in RAM: RET, LCL, ARG, THIS, THAT, then zeroed locals.
        let saved = [
            self.c16(i64::from(ret)),
            self.b.use_var(self.v.lcl),
            self.b.use_var(self.v.arg),
            self.b.use_var(self.v.this),
            self.b.use_var(self.v.that),
        ];
        let p = self.b.ins().iadd_imm_s(s.base, 2 * i64::from(s.depth));
        for (k, x) in saved.into_iter().enumerate() {
            self.store16(self.mem.ram, x, p, 2 * k as i32);
        }
        let zero = self.c16(0);
        for k in 0..i32::from(n_vars) {
            self.store16(self.mem.ram, zero, p, 10 + 2 * k);
        }
        let call = CallSite {
            callee,
            n,
            ret_pc: before.pc + 1,
            ret,
            frames_len: len,
            nargs: self.b.use_var(self.v.nargs),
            flags: self.b.use_var(self.v.flags),
            lcl: self.b.use_var(self.v.lcl),
            arg: self.b.use_var(self.v.arg),
            this: self.b.use_var(self.v.this),
            that: self.b.use_var(self.v.that),
        };
        // The steps up to here, the call's included (it ends the block
        // unless it is nested in an inline run).
        let charged = match nested {
            Some(_) => before.k + 1,
            None => blk.steps,
        };
        let steps = self.b.ins().iadd_imm_s(before.steps0, charged as i64);
        let end = match inline {
            Some(inline) => {
                let args = (0..i32::from(n))
                    .map(|i| s.known(s.depth - i32::from(n) + i))
                    .collect();
                self.inline_args.push(args);
                let end = self.run_inline(call, inline, base, p, steps, n_vars, blk);
                self.inline_args.pop();
                end
            }
            None => RunEnd::Host(None),
        };
        if nested.is_some() {
            s.depth += 1 - i32::from(n);
        }
        let RunEnd::Host(join) = end else {
            return;
        };
        // The call through the host (a guarded run's way there goes on
        // here, its frame already written).
        let Some(steps) = self.host_call(call, base, p, steps) else {
            self.jump_to(before.pc + 1);
            return;
        };
        // Inside a run: it goes on after the call, with what compiled code
        // knows of the run's frame reset as after a nested run, and a
        // budget test of the rest of the run.
        self.flags_known &= !(in_range(true) | in_range(false));
        for args in &mut self.inline_args {
            args.fill(None);
        }
        let ok = self.fits(steps, steps_to_return(&self.env, before.pc + 1));
        let after = Before {
            pc: before.pc + 1,
            k: 0,
            depth: s.depth,
            steps0: steps,
            sp0: s.sp0,
            base: s.base,
            pending: Vec::new(),
        };
        self.guard(ok, &after);
        if let Some(join) = join {
            self.b.ins().jump(join, NONE);
            self.b.switch_to_block(join);
        }
    }

    /// The call `site` through the host, its frame written at SP `base`
    /// (host address `p`), from step count `steps` (the call's included):
    /// the frame stack grows by the call's entry, which is written (with
    /// those of the runs the call is nested in) only if the callee leaves
    /// compiled code, for a return into this code needs none of it. Where it returns here, in
    /// compiled code: SP is its ARG + 1, the registers are the frame's
    /// words in RAM (which the callee may have written, unless no compiled
    /// code can: then they are the caller's own), nargs and flags are the
    /// caller's. Returns None from the function's own code (the block
    /// ends); inside a run, the step count after the call, with the
    /// builder where the run goes on.
    fn host_call(&mut self, site: CallSite, base: Value, p: Value, steps: Value) -> Option<Value> {
        let CallSite { callee, n, ret, .. } = site;
        let f = &self.env.program.functions[callee as usize];
        let entry_flags = f.entry_flags(n);
        let len1 = self.b.ins().iadd_imm_s(site.frames_len, 1);
        self.set_frames_len(len1);
        // Desktop: R13 and R14 as a nested run's return left them, before
        // the callee's own returns write them.
        self.write_return_registers();
        self.return_registers = None;
        // The frame stack's length where this function's code runs (the
        // outermost run's entry index), kept across the call in a slot.
        let own_len = self
            .inlined
            .first()
            .map_or(site.frames_len, |c| c.frames_len);
        self.b.ins().stack_store(T64, own_len, self.slots, SLOT_LEN);

        // The callee's registers go as arguments (`native::Entry`).
        let this = self.b.use_var(self.v.this);
        let that = self.b.use_var(self.v.that);
        let that = self.b.ins().ishl_imm_u(that, 16);
        let ptrs = self.b.ins().bor(this, that);
        let nargs_flags = self.c32(i64::from(n) | i64::from(entry_flags) << 16);
        let func = (self.env.callee)(self.b.func, callee);
        let called = self.c32(i64::from(CALLED | u32::from(ret)));
        let ctx = self.ctx;
        let call = self
            .b
            .ins()
            .call(func, &[ctx, called, base, ptrs, nargs_flags, steps]);
        let (code, steps) = (self.b.inst_results(call)[0], self.b.inst_results(call)[1]);
        let back = self.b.create_block();
        let out = self.b.create_block();
        let returned = self
            .b
            .ins()
            .icmp_imm_s(IntCC::Equal, code, i64::from(RETURNED));
        self.b.ins().brif(returned, back, NONE, out, NONE);
        self.b.switch_to_block(out);
        self.b.set_cold_block(out);
        // The callee left compiled code: the state is in the context, and
        // the frame stack entries of the runs around the call and of the
        // call itself, and the held locals, go to memory.
        let own_len = self.b.ins().stack_load(T64, T64, self.slots, SLOT_LEN);
        let calls: Vec<CallSite> = self.inlined.iter().copied().chain([site]).collect();
        self.write_frame_entries(&calls, own_len);
        self.store_held();
        self.b.ins().return_(&[code, steps]);

        self.b.switch_to_block(back);
        self.b.def_var(self.v.steps, steps);
        let sp = self.b.ins().iadd_imm_s(base, 1 - i64::from(n));
        self.b.def_var(self.v.sp, sp);
        if !self.inlined.is_empty() {
            // The callee's return left the length at the call's entry.
            let own_len = self.b.ins().stack_load(T64, T64, self.slots, SLOT_LEN);
            self.set_frames_len(own_len);
        }
        if !self.env.frames_intact {
            let (lcl, arg) = (self.b.use_var(self.v.lcl), self.b.use_var(self.v.arg));
            let mut restored = Vec::new();
            for (var, k) in [
                (self.v.lcl, 1),
                (self.v.arg, 2),
                (self.v.this, 3),
                (self.v.that, 4),
            ] {
                let x = self.load16(self.mem.ram, p, 2 * k);
                self.b.def_var(var, x);
                restored.push(x);
            }
            self.same_frame_or_leave(restored[0], restored[1], lcl, arg, site.ret_pc);
        }
        (!self.inlined.is_empty()).then_some(steps)
    }

    /// After a call returned in compiled code with LCL and ARG `restored`
    /// from its frame: if they are the caller's `lcl` and `arg`, which keep
    /// the entry test's word, go on (at `next`, where the caller's code
    /// continues); if the callee changed them, the interpreter runs on
    /// from `next`.
    fn same_frame_or_leave(
        &mut self,
        restored_lcl: Value,
        restored_arg: Value,
        lcl: Value,
        arg: Value,
        next: u32,
    ) {
        let same_lcl = self.b.ins().icmp(IntCC::Equal, restored_lcl, lcl);
        let same_arg = self.b.ins().icmp(IntCC::Equal, restored_arg, arg);
        let same = self.b.ins().band(same_lcl, same_arg);
        let (cont, bad) = (self.b.create_block(), self.b.create_block());
        self.b.ins().brif(same, cont, NONE, bad, NONE);
        self.b.switch_to_block(bad);
        self.b.set_cold_block(bad);
        let pc = self.c32(i64::from(next));
        self.leave_with(pc, pc);
        self.b.switch_to_block(cont);
        // The same values: keep the ones the function entered with.
        self.b.def_var(self.v.lcl, lcl);
        self.b.def_var(self.v.arg, arg);
    }

    /// Nonzero where one of `callees` is watched (their watch bytes or'ed).
    fn watched(&mut self, callees: &[FnId]) -> Value {
        let watch = self.fixed_field(offset_of!(Ctx, watch));
        let bytes: Vec<Value> = callees
            .iter()
            .map(|&f| {
                let at = i32::try_from(f).expect("function ids fit");
                self.b.ins().uload8(T32, self.mem.fixed, watch, at)
            })
            .collect();
        bytes
            .into_iter()
            .reduce(|a, b| self.b.ins().bor(a, b))
            .expect("at least one callee")
    }

    /// Leave before the outermost call of inline run `run` where a call
    /// nested in it is of a watched function (tested only where the watch
    /// set names some function): the interpreter makes the call, and the
    /// callee's compiled code then runs up to the watched call.
    fn nested_unwatched(&mut self, run: Inline, before: &Before) {
        let mut callees = Vec::new();
        nested_callees(&self.env, run, &mut callees);
        if callees.is_empty() {
            return;
        }
        let any = self.b.ins().uload8(
            T32,
            self.mem.fixed,
            self.ctx,
            field(offset_of!(Ctx, any_watched)),
        );
        let (check, cont) = (self.b.create_block(), self.b.create_block());
        self.b.ins().brif(any, check, NONE, cont, NONE);
        self.b.switch_to_block(check);
        self.b.set_cold_block(check);
        let watched = self.watched(&callees);
        let ok = self.b.ins().icmp_imm_s(IntCC::Equal, watched, 0);
        self.guard(ok, before);
        self.b.ins().jump(cont, NONE);
        self.b.switch_to_block(cont);
    }

    /// The highest SP that a call of `callee` with `nargs` arguments
    /// reaches before its callee's own code tests the stack, relative to
    /// the callee's LCL: its locals where the call zeroes them, the whole
    /// run of a callee run inline.
    fn frame_top(&self, callee: FnId, nargs: u16) -> i32 {
        match inline_callee(&self.env, callee, nargs, true) {
            Some(inline) => inline.top,
            None => i32::from(zeroed_by_call(
                self.env.timing,
                &self.env.program.functions[callee as usize],
            )),
        }
    }

    /// Write the frame stack entries of `calls`, compiled calls each made
    /// by the callee of the one before (the first by this function), at
    /// indices `first`, `first + 1`, ... (their own `frames_len` values,
    /// which a call through the host may have reloaded from its slot).
    fn write_frame_entries(&mut self, calls: &[CallSite], first: Value) {
        let mut caller = self.env.id;
        for (i, call) in calls.iter().enumerate() {
            let frames_len = self.b.ins().iadd_imm_s(first, i as i64);
            self.write_frame_entry(
                caller,
                &CallSite {
                    frames_len,
                    ..*call
                },
            );
            caller = call.callee;
        }
    }

    /// Whether the entry's `which` (a block index, or [`CALLED`] | RET
    /// word) says a compiled call entered the function.
    fn entered_by_call(&mut self, which: Value) -> Value {
        self.b.ins().icmp_imm_s(IntCC::SignedLessThan, which, 0)
    }

    /// Store the frame stack's length `len` in the context.
    fn set_frames_len(&mut self, len: Value) {
        self.b.ins().store(
            self.mem.ctx,
            len,
            self.ctx,
            field(offset_of!(Ctx, frames_len)),
        );
    }

    /// The host address of frame stack entry `i`.
    fn frame_entry(&mut self, i: Value) -> Value {
        let frames = self.fixed_field(offset_of!(Ctx, frames));
        let off = self
            .b
            .ins()
            .imul_imm_s(i, std::mem::size_of::<Frame>() as i64);
        self.b.ins().iadd(frames, off)
    }

    /// Write the frame stack entry of a call from `caller` (`Frame`, two
    /// words: caller and ret_pc; ret, nargs, flags, and watched = false) at
    /// index `call.frames_len`.
    fn write_frame_entry(&mut self, caller: FnId, call: &CallSite) {
        let CallSite {
            frames_len: len,
            ret_pc,
            ret,
            nargs,
            flags,
            ..
        } = *call;
        let fp = self.frame_entry(len);
        let head = i64::from(caller) | i64::from(ret_pc) << 32;
        let head = self.b.ins().iconst(T64, head);
        self.b.ins().store(self.mem.frames, head, fp, 0);
        let nargs = self.b.ins().uextend(T64, nargs);
        let nargs = self.b.ins().ishl_imm_u(nargs, 16);
        let flags = self.b.ins().uextend(T64, flags);
        let flags = self.b.ins().ishl_imm_u(flags, 32);
        let tail = self.b.ins().bor(nargs, flags);
        let tail = self.b.ins().bor_imm_u(tail, i64::from(ret));
        self.b.ins().store(self.mem.frames, tail, fp, 8);
    }

    /// Run callee `inline` of `call` in this function's code, its frame
    /// written to RAM at `p` (host address of the caller's SP `base`), from
    /// step count `steps` (the call's included), the locals zeroed by the
    /// call being `zeroed`: the callee's registers in the variables, its
    /// instructions translated as a block of its own (leaving compiled code
    /// anywhere in it pushes its frame stack entry first), then its return.
    /// The outermost run tests the budget for its whole run, nested runs
    /// included. Returns where the caller's code goes on (see [`RunEnd`]).
    #[allow(clippy::too_many_arguments)]
    fn run_inline(
        &mut self,
        call: CallSite,
        inline: Inline,
        base: Value,
        p: Value,
        steps: Value,
        zeroed: u16,
        blk: &Block,
    ) -> RunEnd {
        let f = &self.env.program.functions[call.callee as usize];
        let n = call.n;
        let nargs = self.c16(i64::from(n));
        let flags = self.c32(i64::from(f.entry_flags(n)));
        let lcl = self.b.ins().iadd_imm_s(base, 5);
        let arg = self.b.ins().iadd_imm_s(base, -i64::from(n));
        let sp0 = self.b.ins().iadd_imm_s(lcl, i64::from(zeroed));
        for (var, x) in [
            (self.v.steps, steps),
            (self.v.lcl, lcl),
            (self.v.arg, arg),
            (self.v.sp, sp0),
            (self.v.nargs, nargs),
            (self.v.flags, flags),
        ] {
            self.b.def_var(var, x);
        }
        let code = &self.env.code[inline.start as usize..inline.end as usize];
        let saved = (
            self.reach,
            std::mem::replace(&mut self.ptr_tests, ptr_tests(code)),
            self.block_start,
            self.stack_span,
            self.flags_known,
        );
        self.reach = reach(code);
        self.block_start = inline.start;
        self.flags_known = 0;
        let outermost = self.inlined.is_empty();
        self.inlined.push(call);
        let sbase = self.b.ins().iadd_imm_s(p, 2 * (5 + i64::from(zeroed)));
        self.set_stack_span(sp0, held_span(code).0);
        let entry = Before {
            pc: inline.start,
            k: 0,
            depth: 0,
            steps0: steps,
            sp0,
            base: sbase,
            pending: Vec::new(),
        };
        if outermost {
            let ok = self.fits(steps, inline.steps);
            self.guard(ok, &entry);
        }
        let mut s = Stack {
            sp0,
            base: sbase,
            depth: 0,
            slots: Vec::new(),
        };
        let (from, steps0) = self.ops(&mut s, inline.start, inline.end - 1, steps, blk);
        self.b.set_srcloc(source_loc(inline.end - 1, Part::Op));
        let end = match inline.branch {
            Some(branch) => {
                // The steps to here, the `if-goto` included.
                let steps = self
                    .b
                    .ins()
                    .iadd_imm_s(steps0, i64::from(inline.end - from));
                self.branch_inline(inline, branch, s, steps, blk)
            }
            None => {
                self.return_inline(&mut s, inline.end - 1, from, steps0, inline.keeps_frame);
                RunEnd::Returned
            }
        };
        (
            self.reach,
            self.ptr_tests,
            self.block_start,
            self.stack_span,
            self.flags_known,
        ) = saved;
        // The registers come back from the frame, which the run may have
        // written: no `pop pointer` test of the caller's holds for them.
        self.flags_known &= !(in_range(true) | in_range(false));
        end
    }

    /// The `if-goto` that ends the opening of guarded run `inline` (with
    /// the stack `s` before it, and the step count `steps` after it): each
    /// way to a `return` of `branch` runs inline, as
    /// [`Translator::run_inline`] runs a callee; the other way (if any)
    /// sets the registers back to the caller's, as its call saved them,
    /// and returns [`RunEnd::Host`] with the builder there, for the call
    /// through the host (which sets SP and the step count itself). Nested
    /// in a run, the ways meet again after the call.
    fn branch_inline(
        &mut self,
        inline: Inline,
        branch: Branch,
        mut s: Stack,
        steps: Value,
        blk: &Block,
    ) -> RunEnd {
        let x = s.pop(self);
        let x = self.exact(x);
        // Each way pushes the run's frame again, and its return pops it.
        let call = self.inlined.pop().expect("an inline run");
        let join = (!self.inlined.is_empty()).then(|| self.b.create_block());
        let host = self.b.create_block();
        let ways = branch.leaves.map(|leaf| match leaf {
            Some(_) => self.b.create_block(),
            None => host,
        });
        self.b.ins().brif(x, ways[1], NONE, ways[0], NONE);
        // What compiled code knows here, for each way alike.
        let flags_known = self.flags_known;
        let args = self.inline_args.clone();
        let pending = self.return_registers;
        let opening_code = &self.env.code[inline.start as usize..inline.end as usize];
        for (leaf, way) in branch.leaves.into_iter().zip(ways) {
            let Some(Way {
                start: from,
                end,
                jumps,
            }) = leaf
            else {
                continue;
            };
            self.b.switch_to_block(way);
            self.inline_args.clone_from(&args);
            self.return_registers = pending;
            let steps = self.b.ins().iadd_imm_s(steps, jumps as i64);
            self.inlined.push(call);
            let code = &self.env.code[from as usize..end as usize];
            // The opening and this way as one stretch of code: the words
            // the opening pushed stay in registers too (those above SP
            // included, which RAM gets later).
            let stretch: Vec<Op> = opening_code.iter().chain(code).copied().collect();
            self.reach = reach(&stretch);
            self.ptr_tests = ptr_tests(code);
            self.block_start = from;
            self.flags_known = flags_known;
            self.set_stack_span(s.sp0, held_span(&stretch).0);
            let mut leaf_stack = s.clone();
            let (from, steps0) = self.ops(&mut leaf_stack, from, end - 1, steps, blk);
            self.b.set_srcloc(source_loc(end - 1, Part::Op));
            self.return_inline(&mut leaf_stack, end - 1, from, steps0, inline.keeps_frame);
            if let Some(join) = join {
                // (Desktop: R13 and R14 as this way's return leaves them.)
                self.write_return_registers();
                self.return_registers = None;
                self.b.ins().jump(join, NONE);
            }
        }
        if !branch.leaves.contains(&None) {
            if let Some(join) = join {
                self.b.switch_to_block(join);
                // (Where the ways meet, the argument words of the runs
                // around this one are read again.)
                for args in &mut self.inline_args {
                    args.fill(None);
                }
            }
            return RunEnd::Returned;
        }
        self.inline_args = args;
        self.return_registers = pending;
        self.b.switch_to_block(host);
        for (var, x) in [
            (self.v.lcl, call.lcl),
            (self.v.arg, call.arg),
            (self.v.this, call.this),
            (self.v.that, call.that),
            (self.v.nargs, call.nargs),
            (self.v.flags, call.flags),
        ] {
            self.b.def_var(var, x);
        }
        RunEnd::Host(join)
    }

    /// The `return` (at `pc`) of the innermost callee run inline, which
    /// ends the stretch of its code from `from` entered with step count
    /// `steps0`:
    /// as `ret` does, with what the call knows (the frame is the call's,
    /// the caller's code continues: at the call's next block, or after
    /// the call where the caller is itself run inline).
    /// Where the run keeps its frame (`keeps_frame`), the RET word and the
    /// saved registers are the ones the call wrote: the return takes them
    /// from the call, untested.
    fn return_inline(
        &mut self,
        s: &mut Stack,
        pc: u32,
        from: u32,
        steps0: Value,
        keeps_frame: bool,
    ) {
        let call = *self.inlined.last().expect("an inline run");
        s.flush(self);
        let before = Before {
            pc,
            k: u64::from(pc - from),
            depth: s.depth,
            steps0,
            sp0: s.sp0,
            base: s.base,
            pending: Vec::new(),
        };
        let frame = self.b.use_var(self.v.lcl);
        let fr = self.word(frame);
        let ret_word = if keeps_frame {
            self.c16(i64::from(call.ret))
        } else {
            // The RET word intact (else the interpreter returns where it
            // says).
            let ret_word = self.load16(self.mem.ram, fr, -10);
            let ok = self
                .b
                .ins()
                .icmp_imm_s(IntCC::Equal, ret_word, i64::from(call.ret));
            self.guard(ok, &before);
            ret_word
        };
        if self.env.profile == Profile::Desktop && self.inlined.len() > 1 {
            self.return_registers = Some((frame, ret_word));
        } else {
            self.return_registers = None;
            self.desktop_return_registers(frame, ret_word);
        }
        let x = s.pop(self);
        let arg = self.b.use_var(self.v.arg);
        self.store_word(arg, x);
        self.inlined.pop();
        let steps = self.b.ins().iadd_imm_s(steps0, i64::from(pc + 1 - from));
        let sp = self.b.ins().iadd_imm_s(arg, 1);
        for (var, x) in [
            (self.v.steps, steps),
            (self.v.sp, sp),
            (self.v.nargs, call.nargs),
            (self.v.flags, call.flags),
        ] {
            self.b.def_var(var, x);
        }
        if keeps_frame {
            for (var, x) in [
                (self.v.lcl, call.lcl),
                (self.v.arg, call.arg),
                (self.v.this, call.this),
                (self.v.that, call.that),
            ] {
                self.b.def_var(var, x);
            }
        } else {
            let mut restored = Vec::new();
            for (var, at) in [
                (self.v.lcl, -8),
                (self.v.arg, -6),
                (self.v.this, -4),
                (self.v.that, -2),
            ] {
                let r = self.load16(self.mem.ram, fr, at);
                self.b.def_var(var, r);
                restored.push(r);
            }
            self.same_frame_or_leave(restored[0], restored[1], call.lcl, call.arg, call.ret_pc);
        }
        if self.inlined.is_empty() {
            self.jump_to(call.ret_pc);
        }
    }

    /// Write the R13 and R14 that a nested inline run's return left
    /// pending (`Translator::return_registers`).
    fn write_return_registers(&mut self) {
        if let Some((frame, ret_word)) = self.return_registers {
            self.desktop_return_registers(frame, ret_word);
        }
    }

    /// Desktop: a return leaves FRAME in R13 and RET in R14, as the
    /// desktop's does (crate::exec).
    fn desktop_return_registers(&mut self, frame: Value, ret_word: Value) {
        if self.env.profile == Profile::Desktop {
            self.store16(self.mem.ram, frame, self.ram, 2 * 13);
            self.store16(self.mem.ram, ret_word, self.ram, 2 * 14);
        }
    }

    /// `return` to a caller whose frame holds its RET word intact: return
    /// to its compiled code (it called this one; it restores its own
    /// registers) or, through its frame stack entry, to the dispatcher.
    fn ret(&mut self, s: &mut Stack, before: &Before, blk: &Block) {
        // The held locals' words keep their last values, as the
        // interpreter leaves them; this function's code ends here.
        self.store_held();
        self.locals_live = false;
        let len = self.frames_len();
        let len1 = self.b.ins().iadd_imm_s(len, -1);
        // A compiled call returns to compiled code (so not to the host, not
        // watched, and returns may run compiled), its RET word the one it
        // passed; another frame needs a frame stack entry to return to
        // (0 < len <= cap; cap is 0 if returns must not run compiled) that
        // does not return to the host and whose call was not watched (the
        // interpreter tells the watcher), its RET word the entry's.
        let which = self.b.ins().stack_load(T64, T32, self.slots, SLOT_WHICH);
        let nested = self.entered_by_call(which);
        let called_ret = self.exact(which);
        let (other, checked) = (self.b.create_block(), self.b.create_block());
        let expected = self.b.append_block_param(checked, T32);
        self.zero_extended.insert(expected);
        let ret = [BlockArg::Value(called_ret)];
        self.b.ins().brif(nested, checked, &ret, other, NONE);
        self.b.switch_to_block(other);
        let fp = self.frame_entry(len1);
        let cap = self.fixed_field(offset_of!(Ctx, frames_cap));
        let ok = self.b.ins().icmp(IntCC::UnsignedLessThan, len1, cap);
        self.guard(ok, before);
        let ret_pc = self
            .b
            .ins()
            .load(T32, self.mem.frames, fp, field(offset_of!(Frame, ret_pc)));
        let ok = self
            .b
            .ins()
            .icmp_imm_s(IntCC::NotEqual, ret_pc, i64::from(HOST as i32));
        self.guard(ok, before);
        let watched =
            self.b
                .ins()
                .uload8(T32, self.mem.frames, fp, field(offset_of!(Frame, watched)));
        let ok = self.b.ins().icmp_imm_s(IntCC::Equal, watched, 0);
        self.guard(ok, before);
        let ret = self.load16(self.mem.frames, fp, field(offset_of!(Frame, ret)));
        self.b.ins().jump(checked, &[BlockArg::Value(ret)]);
        self.b.switch_to_block(checked);
        let ok = self.b.ins().iconst(types::I8, 1);
        // FRAME = LCL: FRAME-5 ..= FRAME-1 are plain words, and so is ARG
        // (shown on entry where depths are static).
        let frame = self.b.use_var(self.v.lcl);
        let arg = self.b.use_var(self.v.arg);
        let ok = if self.frame_shown {
            ok
        } else {
            let t = self.b.ins().iadd_imm_s(frame, -10);
            let c =
                self.b
                    .ins()
                    .icmp_imm_u(IntCC::UnsignedLessThanOrEqual, t, RAM_SIZE as i64 - 10);
            let ok = self.b.ins().band(ok, c);
            let c = self.is_plain(arg);
            self.b.ins().band(ok, c)
        };
        self.guard(ok, before);
        let fr = self.word(frame);
        let ret_word = self.load16(self.mem.ram, fr, -10);
        let ok = self.b.ins().icmp(IntCC::Equal, ret_word, expected);
        self.guard(ok, before);

        // Commit, in the interpreter's order: the desktop's R13 and R14,
        // the value to RAM[ARG], then the saved registers (which that
        // store may have changed).
        self.desktop_return_registers(frame, ret_word);
        let x = s.pop(self);
        self.store_word(arg, x);
        self.set_frames_len(len1);
        let steps = self.b.ins().iadd_imm_s(before.steps0, blk.steps as i64);
        self.b.def_var(self.v.steps, steps);
        // Back into the caller's compiled code if it is below this one (it
        // restores its registers from its frame), else to the dispatcher,
        // which enters the caller at RET's block.
        let (back, top) = (self.b.create_block(), self.b.create_block());
        self.b.ins().brif(nested, back, NONE, top, NONE);
        self.b.switch_to_block(back);
        let returned = self.c32(i64::from(RETURNED));
        self.b.ins().return_(&[returned, steps]);

        self.b.switch_to_block(top);
        let fp = self.frame_entry(len1);
        let ret_pc = self
            .b
            .ins()
            .load(T32, self.mem.frames, fp, field(offset_of!(Frame, ret_pc)));
        let sp = self.b.ins().iadd_imm_s(arg, 1);
        self.b.def_var(self.v.sp, sp);
        let regs = [
            (self.v.that, -2),
            (self.v.this, -4),
            (self.v.arg, -6),
            (self.v.lcl, -8),
        ];
        for (var, at) in regs {
            let r = self.load16(self.mem.ram, fr, at);
            self.b.def_var(var, r);
        }
        let caller = self
            .b
            .ins()
            .load(T32, self.mem.frames, fp, field(offset_of!(Frame, caller)));
        let nargs = self.load16(self.mem.frames, fp, field(offset_of!(Frame, nargs)));
        self.b.def_var(self.v.nargs, nargs);
        let flags = self
            .b
            .ins()
            .uload8(T32, self.mem.frames, fp, field(offset_of!(Frame, flags)));
        self.b.def_var(self.v.flags, flags);
        let cont = self.c32(i64::from(CONTINUE));
        self.b.ins().jump(
            self.leave,
            &[
                BlockArg::Value(cont),
                BlockArg::Value(ret_pc),
                BlockArg::Value(caller),
            ],
        );
    }
}

/// What an instruction's side exit restores: its own index, the step
/// count and SP before it, and the stack words the block has pushed but
/// not yet written to RAM.
struct Before {
    pc: u32,
    /// Instructions of the block before it, and SP relative to the entry.
    k: u64,
    depth: i32,
    /// The step count and SP at the block's entry.
    steps0: Value,
    sp0: Value,
    /// The host address of stack word `sp0`, and the unwritten words
    /// (depth relative to `sp0`, value).
    base: Value,
    pending: Vec<(i32, Value)>,
}

/// One stack word the block has pushed or read.
#[derive(Clone, Copy)]
struct Slot {
    depth: i32,
    value: Value,
    /// Pushed, not yet written to RAM.
    dirty: bool,
}

/// The stack during one block, kept in SSA values (a compile-time stack):
/// SP relative to its value at the entry, and the words whose values are
/// in registers. A pushed word reaches RAM only where the block ends or
/// leaves, before a call or return, and before an access that might touch
/// it (the last value of each word, as the interpreter leaves it); the
/// block's entry and span tests show the other accesses cannot.
#[derive(Clone)]
struct Stack {
    sp0: Value,
    /// The host address of stack word `sp0` (words sp0+d at offset 2d).
    base: Value,
    depth: i32,
    slots: Vec<Slot>,
}

impl Stack {
    fn sp(&self, t: &mut Translator<'_, '_>) -> Value {
        t.b.ins().iadd_imm_s(self.sp0, i64::from(self.depth))
    }

    fn push(&mut self, x: Value) {
        let depth = self.depth;
        self.slots.retain(|s| s.depth != depth);
        self.slots.push(Slot {
            depth,
            value: x,
            dirty: true,
        });
        self.depth += 1;
    }

    fn pop(&mut self, t: &mut Translator<'_, '_>) -> Value {
        self.depth -= 1;
        let depth = self.depth;
        if let Some(x) = self.known(depth) {
            return x;
        }
        let x = t.load16(t.mem.ram, self.base, 2 * depth);
        self.slots.push(Slot {
            depth,
            value: x,
            dirty: false,
        });
        x
    }

    /// The value of stack word `depth` where the block has it in a
    /// register.
    fn known(&self, depth: i32) -> Option<Value> {
        self.slots
            .iter()
            .find(|s| s.depth == depth)
            .map(|s| s.value)
    }

    /// The words pushed and not yet written.
    fn pending(&self) -> Vec<(i32, Value)> {
        self.slots
            .iter()
            .filter(|s| s.dirty)
            .map(|s| (s.depth, s.value))
            .collect()
    }

    /// Write the pending words to RAM.
    fn flush(&mut self, t: &mut Translator<'_, '_>) {
        t.store_pending(self.base, &self.pending());
        for s in &mut self.slots {
            s.dirty = false;
        }
    }

    /// Forget the words' values after a store that may have changed them
    /// (the pending ones were flushed before it).
    fn forget(&mut self) {
        debug_assert!(self.slots.iter().all(|s| !s.dirty));
        self.slots.clear();
    }
}
