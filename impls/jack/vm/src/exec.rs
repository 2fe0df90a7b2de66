//! The dispatch loop. SP, LCL, ARG, THIS and THAT live in host registers
//! while it runs; an access to RAM[0..4] through a computed address takes a
//! slow path that reads or writes the cached register, so the memory model
//! stays exactly that of spec §1. No allocation, no hashing per instruction.

use crate::exit::Exit;
use crate::machine::{
    Frame, Machine, Watcher, ARG_OK, HOST, LOCAL_OK, MAX_DEPTH, NEAR, NEAR_THAT, NEAR_THIS,
    THAT_OK, THAT_ZERO, THIS_OK,
};
use crate::program::{Bin, Code, Op, Operand, Program, ARG, CONST, LCL, PTR, THAT, THIS};
use crate::timing::{Timing, STACK_BASE, STACK_LAST};
use jack_os::{math, Builtin, Profile, Ram, Stop, RAM_SIZE};

/// The VM registers RAM[0..=4], cached: SP, and LCL, ARG, THIS, THAT in
/// a table that fused operands index by their base (`ABS`, `CONST` and
/// `PTR` read as 0), so reading an operand needs no branch on its kind.
#[derive(Clone, Copy, Debug)]
struct Regs {
    sp: u16,
    base: [u16; 8],
}

type Words = [i16; RAM_SIZE];

impl Regs {
    fn load(w: &Words) -> Regs {
        let mut base = [0; 8];
        for (b, word) in base[..4].iter_mut().zip(&w[1..5]) {
            *b = *word as u16;
        }
        Regs {
            sp: w[0] as u16,
            base,
        }
    }

    fn store(self, w: &mut Words) {
        w[0] = self.sp as i16;
        for (word, b) in w[1..5].iter_mut().zip(&self.base[..4]) {
            *word = *b as i16;
        }
    }
}

/// `5 <= a <= 24576`: an ordinary word (not a register, not outside RAM).
/// Takes the address as `usize` so that a passed test proves `w[a]` in
/// bounds and the compiler drops its own check.
#[inline(always)]
fn plain_word(a: usize) -> bool {
    a.wrapping_sub(5) < RAM_SIZE - 5
}

/// Read RAM[a] for a register or an address outside RAM.
#[cold]
#[inline(never)]
fn read_slow(sp: u16, seg: &[u16; 8], a: u16) -> i16 {
    (match a {
        0 => sp,
        1..=4 => seg[usize::from(a) - 1],
        _ => 0xFFFF,
    }) as i16
}

/// Write RAM[a] for a register or an address outside RAM (dropped);
/// returns the new SP.
#[cold]
#[inline(never)]
fn write_slow(sp: u16, seg: &mut [u16; 8], a: u16, v: i16) -> u16 {
    let v = v as u16;
    match a {
        0 => return v,
        1..=4 => seg[usize::from(a) - 1] = v,
        _ => {}
    }
    sp
}

fn words(ram: &mut Ram) -> &mut Words {
    ram.words_mut()
        .try_into()
        .expect("the RAM has RAM_SIZE words")
}

/// Why the loop stopped early (the call stack is added by the caller);
/// also what a built-in called from compiled code stopped with.
pub(crate) enum Halt {
    Exit(Exit),
    Error(String),
    Os(Stop),
    /// Desktop: a built-in with this many arguments ended the run; its
    /// arguments are popped and its frame is still to be written.
    OsInFrame(Stop, u8),
    /// Desktop: a built-in call at an SP where its frame and result do
    /// not fit below the end of the stack segment (arguments not popped).
    BuiltinOverflow(Builtin, u8),
    /// Web: a blocking built-in with this many arguments (on the stack),
    /// its call step counted (see `Machine::web_blocking_call`).
    Blocking(Builtin, u8),
    /// A fused instruction's fast-path conditions do not hold: run the
    /// plain commands from the same index.
    Deopt,
}

/// How [`Machine::exec`] returned.
pub(crate) enum Flow {
    /// The step count reached `stop_at`.
    Limit,
    /// The run ended.
    End(Exit),
    /// Plain code must run the next few commands (see `Halt::Deopt`).
    Deopt,
}

/// Fused instructions need `MIN_SP <= SP <= MAX_SP`: the stack words they
/// touch are inside the stack segment and none of their pops happens at
/// SP = 256, so neither profile's stack rules can apply to them.
const MIN_SP: u16 = 258;
const MAX_SP: u16 = STACK_LAST - 9;

/// Zero `n` words from `sp` (mod 2^16) for the web profile, whose stack has
/// no bounds: words outside RAM are dropped, so this writes at most
/// `RAM_SIZE` words however large `n` is. Returns the new SP.
#[cold]
#[inline(never)]
fn zero_unbounded(w: &mut Words, seg: &mut [u16; 8], sp: u16, n: u16) -> u16 {
    let (mut a, mut left) = (sp, u32::from(n));
    while left > 0 {
        let at = usize::from(a);
        let run = if plain_word(at) {
            let run = (RAM_SIZE - at).min(left as usize);
            w[at..at + run].fill(0);
            run as u32
        } else if at < 5 {
            write_slow(sp, seg, a, 0);
            1
        } else {
            // Past the end of RAM: on to the wrap-around at 65536.
            (0x1_0000 - at as u32).min(left)
        };
        a = a.wrapping_add(run as u16);
        left -= run;
    }
    sp.wrapping_add(n)
}

#[inline(always)]
fn fast_sp(sp: u16) -> bool {
    sp.wrapping_sub(MIN_SP) <= MAX_SP - MIN_SP
}

/// Whether none of `operands` can fail in this invocation (see
/// [`crate::program::Operand::need`]): the web IDE's flags, and under the
/// desktop profile `ARGS_FIT` and the pointers' [`near`] bits.
#[inline(always)]
fn operands_ok<const N: usize>(operands: [Operand; N], flags: u8) -> bool {
    let need = operands.iter().fold(0, |n, o| n | o.need);
    flags & need == need
}

#[inline(always)]
fn apply(op: Bin, x: i16, y: i16, divide: jack_os::DivideRule) -> Option<i16> {
    Some(match op {
        Bin::Add => x.wrapping_add(y),
        Bin::Sub => x.wrapping_sub(y),
        Bin::And => x & y,
        Bin::Or => x | y,
        Bin::Eq => -i16::from(x == y),
        Bin::Gt => -i16::from(x > y),
        Bin::Lt => -i16::from(x < y),
        Bin::Mul => math::multiply(x, y),
        Bin::Div => return math::divide(divide, x, y),
    })
}

const POP_BELOW: &str = "Cannot pop the stack below 256 in strict mode";
const ARG_OOB: &str = "Argument offset out of bounds";
const LOCAL_OOB: &str = "Local offset out of bounds";
const THIS_UNINIT: &str = "The this segment cannot be accessed since it was not initialized";
const THAT_UNINIT: &str = "The that segment cannot be accessed since it was not initialized";
pub(crate) const STACK_OVERFLOW: &str = "Stack overflow";
/// Desktop: a `return` with LCL = 0 (the entry function, which has no frame).
const NOWHERE_TO_RETURN: &str = "Nowhere to return to";
/// Desktop: a `this i` or `that i` outside the segment's range.
const SEGMENT_SPACE: &str = "Out of segment space";
const THIS_RANGE: &str = "'This' segment must be in the Heap range";
const THAT_RANGE: &str = "'That' segment must be in the Heap or Screen range";

/// The desktop's heap (2048..=16383) and the end of its `that` range (the
/// keyboard word, 24576).
pub(crate) const HEAP_START: i32 = 2048;
const HEAP_END: i32 = 16383;
const THAT_END: i32 = 24576;

/// Desktop: `this i` lies in the heap (the desktop tests the address, a
/// 16-bit sum, for every access).
#[inline(always)]
pub(crate) fn desktop_this_ok(this: u16, i: u16) -> bool {
    let at = i32::from(this.wrapping_add(i) as i16);
    (HEAP_START..=HEAP_END).contains(&at)
}

/// Desktop: `that i` lies from the segment's first word to 24576. The
/// range starts where the last `pop pointer 1` put THAT (0 included, see
/// [`THAT_ZERO`]); after a return it starts at THAT or 2048, whichever is
/// higher.
#[inline(always)]
pub(crate) fn desktop_that_ok(that: u16, i: u16, flags: u8) -> bool {
    let at = i32::from(that.wrapping_add(i) as i16);
    let floor = if flags & THAT_ZERO != 0 {
        0
    } else {
        i32::from(that as i16).max(HEAP_START)
    };
    (floor..=THAT_END).contains(&at)
}

/// Desktop: a `that` pointer that a fused `pop pointer 1` may store itself
/// (in its range, not from word 0: 0 is left to the plain command).
#[inline(always)]
fn desktop_that_base_ok(v: i16) -> bool {
    (HEAP_START..=THAT_END).contains(&i32::from(v))
}

/// Desktop: the values `pop pointer 0` accepts (the heap, or not above 0).
#[inline(always)]
pub(crate) fn desktop_this_value_ok(v: i16) -> bool {
    v <= 0 || (HEAP_START..=HEAP_END).contains(&i32::from(v))
}

/// Desktop: the values `pop pointer 1` accepts (0, the heap or the screen
/// through 24576).
#[inline(always)]
pub(crate) fn desktop_that_value_ok(v: i16) -> bool {
    v == 0 || (HEAP_START..=THAT_END).contains(&i32::from(v))
}

/// Desktop: the [`NEAR_THIS`] and [`NEAR_THAT`] bits of the pointers as
/// they are: set where every offset below [`NEAR`] passes the desktop's
/// address test, so that a fused instruction tests its `this`/`that`
/// operands with the flags (the desktop loop keeps these bits in its
/// flags, sets them where a pointer changes, and leaves them out of the
/// machine's and the frames'). `this i` with THIS in 2048..=16383 - 63
/// stays in the heap; `that i` with THAT from its range's floor (2048, or
/// 0 after a `pop pointer 1` of 0) to 24576 - 63 stays in its range.
/// Neither sum wraps, so each passes [`desktop_this_ok`] or
/// [`desktop_that_ok`].
#[inline(always)]
fn near(seg: &[u16; 8], flags: u8) -> u8 {
    let floor = if flags & THAT_ZERO != 0 {
        0
    } else {
        HEAP_START
    };
    this_near(seg[THIS] as i16) | that_near_above(seg[THAT] as i16, floor)
}

/// Desktop: the [`near`] bit of THAT at `v` with the `that` range's floor
/// at `floor`.
#[inline(always)]
fn that_near_above(v: i16, floor: i32) -> u8 {
    if (floor..=THAT_END - NEAR_END).contains(&i32::from(v)) {
        NEAR_THAT
    } else {
        0
    }
}

/// `flags` with the [`near`] bits of the pointers as they are.
#[inline(always)]
fn with_near(flags: u8, seg: &[u16; 8]) -> u8 {
    flags & !NEAR_BITS | near(seg, flags)
}

/// Both [`near`] bits.
const NEAR_BITS: u8 = NEAR_THIS | NEAR_THAT;

/// How far below its segment's end a pointer must lie for [`NEAR`] offsets.
const NEAR_END: i32 = NEAR as i32 - 1;

/// Desktop: the [`near`] bit of THIS at `v`.
#[inline(always)]
fn this_near(v: i16) -> u8 {
    if (HEAP_START..=HEAP_END - NEAR_END).contains(&i32::from(v)) {
        NEAR_THIS
    } else {
        0
    }
}

/// Desktop: the [`near`] bit of THAT at `v`, stored by a `pop pointer 1`
/// that passed the desktop's test (0, with THAT_ZERO set, or 2048..=24576).
#[inline(always)]
fn that_near(v: i16) -> u8 {
    if i32::from(v) <= THAT_END - NEAR_END {
        NEAR_THAT
    } else {
        0
    }
}

/// Desktop: the highest SP at a built-in call (its arguments pushed) that
/// leaves room for the call's 5-word frame and the pushed result, each
/// push keeping SP <= 2047.
const BUILTIN_LAST_BASE: u16 = STACK_LAST - 6;

impl Machine {
    /// Run instructions of `code` (its fused array if `fused`, else its plain
    /// one) until the step count reaches `stop_at` (None) or the run ends (Some).
    pub(crate) fn exec<const W: bool>(
        &mut self,
        program: &Program,
        code: &Code,
        fused: bool,
        stop_at: u64,
        watch: &mut Option<(&[bool], &mut dyn Watcher)>,
    ) -> Flow {
        // One loop per profile, so that neither tests the profile per instruction.
        match self.os.profile() {
            Profile::Desktop => self.exec_as::<W, true>(program, code, fused, stop_at, watch),
            Profile::Web => self.exec_as::<W, false>(program, code, fused, stop_at, watch),
        }
    }

    /// [`Machine::exec`] under the desktop profile (`D`) or the web one.
    fn exec_as<const W: bool, const D: bool>(
        &mut self,
        program: &Program,
        code: &Code,
        fused: bool,
        stop_at: u64,
        watch: &mut Option<(&[bool], &mut dyn Watcher)>,
    ) -> Flow {
        if let Some(message) = self.beyond_end.take() {
            // The step after a return past the caller's end (the callers
            // run this only with a step left before `stop_at`).
            self.steps += 1;
            return Flow::End(Exit::RuntimeError {
                message,
                stack: self.call_stack(),
            });
        }
        let mut pc = self.pc as usize;
        let mut steps = self.steps;
        let mut cur = self.cur;
        let mut nargs = self.nargs;
        let mut flags = self.flags;
        let functions = &program.functions;
        let frames = &mut self.frames;
        let os = &mut self.os;
        let ram = &mut self.ram;
        let mut profile = self.profile.as_deref_mut();
        let mut profile_mark = self.profile_mark;
        let scratch = &mut self.scratch;
        let beyond_end = &mut self.beyond_end;
        let divide = os.divide_rule();
        let timing = Timing::of(if D { Profile::Desktop } else { Profile::Web });
        debug_assert_eq!(timing, Timing::of(os.profile()));
        let (function_step, stack_check) = (timing.function_step, timing.stack_check);
        let plain = &code.plain[..];
        let ops = if fused { &code.fused[..] } else { plain };
        let mut w = words(ram);
        // SP apart from the segment table, so that it stays in a register.
        let Regs {
            mut sp,
            base: mut seg,
        } = Regs::load(w);
        if D {
            flags = with_near(flags, &seg);
        }

        let halt: Option<Halt> = 'run: loop {
            macro_rules! rd {
                ($a:expr) => {{
                    let a: u16 = $a;
                    if plain_word(usize::from(a)) {
                        w[usize::from(a)]
                    } else {
                        read_slow(sp, &seg, a)
                    }
                }};
            }
            macro_rules! wr {
                ($a:expr, $v:expr) => {{
                    let a: u16 = $a;
                    let v: i16 = $v;
                    if plain_word(usize::from(a)) {
                        w[usize::from(a)] = v;
                    } else {
                        sp = write_slow(sp, &mut seg, a, v);
                        if D {
                            // A register word: a pointer may have changed.
                            flags = with_near(flags, &seg);
                        }
                    }
                }};
            }
            // Inside the stack segment (256 <= SP < 2047) with one test;
            // elsewhere each profile's rule (crate::timing).
            macro_rules! push {
                ($v:expr) => {{
                    let v: i16 = $v;
                    let at = usize::from(sp);
                    if at.wrapping_sub(usize::from(STACK_BASE))
                        < usize::from(STACK_LAST - STACK_BASE)
                    {
                        w[at] = v;
                        sp += 1;
                    } else {
                        // SP is the word it had before the write, as in
                        // both tools: a push at SP = 0 leaves SP = 1.
                        let at = sp;
                        wr!(at, v);
                        if stack_check && !(STACK_BASE..=STACK_LAST).contains(&at.wrapping_add(1)) {
                            break 'run Some(Halt::Error(STACK_OVERFLOW.into()));
                        }
                        sp = at.wrapping_add(1);
                    }
                }};
            }
            macro_rules! pop {
                () => {{
                    let at = usize::from(sp);
                    if at.wrapping_sub(usize::from(STACK_BASE) + 1)
                        < usize::from(STACK_LAST - STACK_BASE)
                    {
                        sp -= 1;
                        w[at - 1]
                    } else {
                        if stack_check {
                            if !(STACK_BASE..=STACK_LAST).contains(&sp.wrapping_sub(1)) {
                                break 'run Some(Halt::Error(STACK_OVERFLOW.into()));
                            }
                        } else if sp == STACK_BASE {
                            break 'run Some(Halt::Error(POP_BELOW.into()));
                        }
                        sp = sp.wrapping_sub(1);
                        rd!(sp)
                    }
                }};
            }
            // The zeroed locals of a function: desktop, inside the stack
            // segment or "Stack overflow" before any write; web, anywhere.
            macro_rules! zero_locals {
                ($n:expr) => {{
                    let n: u16 = $n;
                    let (from, to) = (usize::from(sp), usize::from(sp) + usize::from(n));
                    if from >= usize::from(STACK_BASE) && to <= usize::from(STACK_LAST) {
                        w[from..to].fill(0);
                        sp = to as u16;
                    } else if stack_check {
                        break 'run Some(Halt::Error(STACK_OVERFLOW.into()));
                    } else {
                        sp = zero_unbounded(w, &mut seg, sp, n);
                    }
                }};
            }
            macro_rules! binary {
                (|$x:ident, $y:ident| $e:expr) => {{
                    let $y = pop!();
                    let $x = pop!();
                    push!($e);
                }};
            }
            // The test of a checked form (all of the desktop's `this`/`that`):
            // the web IDE's that the invocation set the pointer, or the
            // desktop's address test, at once for a near offset of a near
            // pointer and in full for the others.
            macro_rules! checked {
                (THIS, $i:expr) => {
                    checked!(@NEAR_THIS, $i, THIS_OK, THIS_UNINIT, desktop_this_ok(seg[THIS], $i))
                };
                (THAT, $i:expr) => {
                    checked!(@NEAR_THAT, $i, THAT_OK, THAT_UNINIT, desktop_that_ok(seg[THAT], $i, flags))
                };
                (@$near:expr, $i:expr, $bit:expr, $msg:expr, $exact:expr) => {
                    if D {
                        if $i >= NEAR || flags & $near == 0 {
                            if !$exact {
                                break 'run Some(Halt::Error(SEGMENT_SPACE.into()));
                            }
                        }
                    } else if flags & $bit == 0 {
                        break 'run Some(Halt::Error($msg.into()));
                    }
                };
            }
            // `push`/`pop` of `this i` or `that i` (`$s`: THIS or THAT), after
            // the test of the checked form if `checked`.
            macro_rules! this_that {
                (push $s:tt $i:expr) => {
                    push!(rd!(seg[$s].wrapping_add($i)))
                };
                (pop $s:tt $i:expr) => {{
                    let v = pop!();
                    wr!(seg[$s].wrapping_add($i), v)
                }};
                (checked $dir:tt $s:tt $i:expr) => {{
                    checked!($s, $i);
                    this_that!($dir $s $i)
                }};
            }
            macro_rules! charge {
                () => {
                    if let Some(p) = profile.as_deref_mut() {
                        p[cur as usize] += steps - profile_mark;
                        profile_mark = steps;
                    }
                };
            }
            // A built-in through the OS: pop the arguments, call, push the result.
            macro_rules! builtin {
                ($b:expr, $n:expr) => {{
                    let b: Builtin = $b;
                    let mut args = [0i16; 8];
                    let n = usize::from($n).min(args.len());
                    if stack_check && sp > BUILTIN_LAST_BASE {
                        // Desktop: no room for the built-in's frame.
                        break 'run Some(Halt::BuiltinOverflow(b, n as u8));
                    }
                    if timing.handover_step && b.blocks() {
                        // Web: its wait and hand-over, which a budget may cut.
                        break 'run Some(Halt::Blocking(b, n as u8));
                    }
                    for i in (0..n).rev() {
                        args[i] = pop!();
                    }
                    Regs { sp, base: seg }.store(w);
                    // Through a copy, so that `steps` itself can stay in a register.
                    let mut clock = steps;
                    let c = os.call(b, &args[..n], ram, &mut clock);
                    // The web IDE's hand-over step of a blocking built-in.
                    steps =
                        clock + u64::from(timing.handover_step && b.blocks() && c.stop.is_none());
                    w = words(ram);
                    Regs { sp, base: seg } = Regs::load(w);
                    if D {
                        // The built-in may have written a pointer's word.
                        flags = with_near(flags, &seg);
                    }
                    if let Some(stop) = c.stop {
                        if function_step {
                            // Desktop: the run ends inside the built-in,
                            // above its frame (pushed after the return).
                            break 'run Some(Halt::OsInFrame(stop, n as u8));
                        }
                        push!(c.value);
                        break 'run Some(Halt::Os(stop));
                    }
                    push!(c.value);
                }};
            }

            // Account for the commands a fused instruction covers beyond the first.
            macro_rules! skip {
                ($op:expr, $steps:expr) => {{
                    let n: u64 = $steps;
                    debug_assert_eq!(n, $op.steps());
                    let extra = n - 1;
                    steps += extra;
                    pc += extra as usize;
                }};
            }
            // A fused instruction's fast path: SP away from the stack's ends,
            // and every operand sure to pass its profile's tests.
            macro_rules! fast {
                ($($o:expr),+) => {
                    fast_sp(sp) && operands_ok([$($o),+], flags)
                };
            }
            // Undo the fetch and let plain code run from here.
            macro_rules! deopt {
                () => {
                    deopt!(0)
                };
                // After the fused instruction's first `$done` commands,
                // whose effects it has made: plain code runs the rest.
                ($done:expr) => {{
                    let done: usize = $done;
                    pc = pc - 1 + done;
                    steps = steps - 1 + done as u64;
                    break 'run Some(Halt::Deopt);
                }};
            }
            // Desktop: a `pop pointer 1` of a fused instruction stores `v`,
            // which passes the desktop's test without setting THAT_ZERO.
            macro_rules! desktop_that_store {
                ($v:expr) => {
                    if D && !desktop_that_base_ok($v) {
                        deopt!();
                    }
                };
            }
            // A fused `pop pointer 1` of `v` (desktop: checked by
            // `desktop_that_store!`).
            macro_rules! set_that {
                ($v:expr) => {{
                    let v: i16 = $v;
                    seg[THAT] = v as u16;
                    flags = (flags | THAT_OK) & !THAT_ZERO;
                    if D {
                        flags = flags & !NEAR_THAT | that_near(v);
                    }
                }};
            }
            // Read a fused operand (its checks were done by `operands_ok`).
            macro_rules! src {
                ($s:expr) => {{
                    let s: Operand = $s;
                    if usize::from(s.base) == CONST {
                        s.off as i16
                    } else {
                        rd!(seg[usize::from(s.base)].wrapping_add(s.off))
                    }
                }};
            }
            // Store into a fused target (checked by `operands_ok`).
            macro_rules! dst {
                ($d:expr, $v:expr) => {{
                    let d: Operand = $d;
                    let v: i16 = $v;
                    if usize::from(d.base) == PTR {
                        // pop pointer 0|1: THIS or THAT, and its flag.
                        let p = usize::from(d.off & 1);
                        seg[THIS + p] = v as u16;
                        flags |= THIS_OK << p;
                    } else {
                        wr!(seg[usize::from(d.base)].wrapping_add(d.off), v)
                    }
                }};
            }
            // `push a; push b; op` on the stack words at top, top+1; leaves
            // SP = top+1 and returns the result (also stored at top). A
            // division by zero leaves the two pushes made and the plain
            // division to run: going back before `push a` would read `a`
            // again, and `push b` may have overwritten it (ARG moved onto
            // the stack).
            macro_rules! push_push_op {
                ($op:expr, $a:expr, $b:expr) => {{
                    let top = sp;
                    let x = src!($a);
                    w[top as usize] = x;
                    sp = top + 1;
                    let y = src!($b);
                    w[top as usize + 1] = y;
                    let Some(r) = apply($op, x, y, divide) else {
                        std::hint::cold_path();
                        sp = top + 2;
                        deopt!(2)
                    };
                    w[top as usize] = r;
                    r
                }};
            }
            // `push b; op [; pop d]` with the left operand on the stack.
            macro_rules! push_op {
                ($op:expr, $steps:expr, $o:expr, $b:expr $(, $d:expr)?) => {{
                    let top = sp;
                    let x = w[top as usize - 1];
                    let y = src!($b);
                    w[top as usize] = y;
                    let Some(r) = apply($o, x, y, divide) else {
                        deopt!()
                    };
                    skip!($op, $steps);
                    w[top as usize - 1] = r;
                    $(
                        sp = top - 1;
                        dst!($d, r);
                    )?
                }};
            }
            // `push index; push base; add; pop pointer 1; push that 0 [; pop to]`.
            macro_rules! array_read {
                (@value $index:expr, $base:expr) => {{
                    // The two stack words the sum writes: an operand may
                    // lie there (a local at SP), so a desktop pointer the
                    // plain commands must refuse puts them back first.
                    let at = usize::from(sp);
                    let saved = (w[at], w[at + 1]);
                    let a = push_push_op!(Bin::Add, $index, $base);
                    if D && !desktop_that_base_ok(a) {
                        (w[at], w[at + 1]) = saved;
                        sp = at as u16;
                        deopt!();
                    }
                    let top = sp - 1;
                    sp = top;
                    set_that!(a);
                    let v = rd!(seg[THAT]);
                    w[top as usize] = v;
                    (top, v)
                }};
                ($index:expr, $base:expr) => {{
                    let (top, _) = array_read!(@value $index, $base);
                    sp = top + 1;
                }};
                ($index:expr, $base:expr, $to:expr) => {{
                    let (_, v) = array_read!(@value $index, $base);
                    dst!($to, v);
                }};
            }
            macro_rules! do_return {
                () => {{
                    let frame = seg[LCL];
                    let ret_at = frame.wrapping_sub(5);
                    let ret = rd!(ret_at);
                    if function_step {
                        if frame == 0 {
                            break 'run Some(Halt::Error(NOWHERE_TO_RETURN.into()));
                        }
                        // The desktop's return goes through R13 (FRAME)
                        // and R14 (RET).
                        w[13] = frame as i16;
                        w[14] = ret;
                    }
                    let v = pop!();
                    // RAM[ARG] = v; if ARG points at SP, the next line wins.
                    let a = usize::from(seg[ARG]);
                    if plain_word(a) {
                        w[a] = v;
                    } else {
                        write_slow(sp, &mut seg, a as u16, v);
                    }
                    sp = seg[ARG].wrapping_add(1);
                    seg[THAT] = rd!(frame.wrapping_sub(1)) as u16;
                    seg[THIS] = rd!(frame.wrapping_sub(2)) as u16;
                    seg[ARG] = rd!(frame.wrapping_sub(3)) as u16;
                    seg[LCL] = rd!(frame.wrapping_sub(4)) as u16;
                    charge!();
                    let Some(fr) = frames.pop() else {
                        // A return from the entry function ends the run.
                        break 'run Some(Halt::Exit(Exit::Halted));
                    };
                    let callee = cur;
                    cur = fr.caller;
                    nargs = fr.nargs;
                    flags = fr.flags;
                    if D {
                        // (No THAT_ZERO after a return.)
                        flags |= this_near(seg[THIS] as i16)
                            | that_near_above(seg[THAT] as i16, HEAP_START);
                    }
                    if W && fr.watched {
                        if let Some((_, watcher)) = watch {
                            Regs { sp, base: seg }.store(w);
                            watcher.on_return(program, callee, v, ram);
                            w = words(ram);
                        }
                    }
                    if fr.ret_pc == HOST {
                        break 'run Some(Halt::Exit(Exit::Returned(v)));
                    }
                    pc = if ret == fr.ret {
                        fr.ret_pc as usize
                    } else if function_step {
                        match desktop_resume(program, cur, ret) {
                            Ok(p) => p as usize,
                            Err(message) => break 'run Some(Halt::Error(message)),
                        }
                    } else {
                        match web_resume(program, cur, ret, usize::from(ret_at) < RAM_SIZE) {
                            WebResume::At(p) => p as usize,
                            WebResume::BeyondEnd(message) => {
                                *beyond_end = Some(message);
                                break 'run None;
                            }
                            WebResume::FunctionLine => {
                                break 'run Some(Halt::Error(format!(
                                    "Return address {ret} is not a command of {}",
                                    program.function_name(cur)
                                )))
                            }
                        }
                    };
                    // `do f(..)` drops the value with `pop temp 0`: in fused
                    // code that pop runs here, not in a dispatch of its own.
                    if fused {
                        if let Op::PopAbs(a) = plain[pc] {
                            if fast_sp(sp) {
                                steps += 1;
                                pc += 1;
                                sp -= 1;
                                w[a as usize] = w[sp as usize];
                            }
                        }
                    }
                }};
            }

            if steps >= stop_at {
                break None;
            }
            // By reference: each arm reads only the fields it needs.
            let op = &ops[pc];
            pc += 1;
            steps += 1;
            match *op {
                Op::PushConst(c) => push!(c),
                Op::PushLocal(i) => push!(rd!(seg[LCL].wrapping_add(i))),
                Op::PushArg(i) => {
                    if i >= nargs {
                        break Some(Halt::Error(ARG_OOB.into()));
                    }
                    push!(rd!(seg[ARG].wrapping_add(i)))
                }
                Op::PushThis(i) => this_that!(push THIS i),
                Op::PushThisChk(i) => this_that!(checked push THIS i),
                Op::PushThat(i) => this_that!(push THAT i),
                Op::PushThatChk(i) => this_that!(checked push THAT i),
                Op::PushAbs(a) => push!(w[a as usize]),
                Op::PushPtr(0) => push!(seg[THIS] as i16),
                Op::PushPtr(_) => push!(seg[THAT] as i16),
                Op::PopLocal(i) => {
                    let v = pop!();
                    wr!(seg[LCL].wrapping_add(i), v)
                }
                Op::PopArg(i) => {
                    if i >= nargs {
                        break Some(Halt::Error(ARG_OOB.into()));
                    }
                    let v = pop!();
                    wr!(seg[ARG].wrapping_add(i), v)
                }
                Op::PopThis(i) => this_that!(pop THIS i),
                Op::PopThisChk(i) => this_that!(checked pop THIS i),
                Op::PopThat(i) => this_that!(pop THAT i),
                Op::PopThatChk(i) => this_that!(checked pop THAT i),
                Op::PopAbs(a) => {
                    let v = pop!();
                    w[a as usize] = v;
                }
                Op::PopPtr(0) => {
                    if D {
                        let v = rd!(sp.wrapping_sub(1));
                        let near = this_near(v);
                        if near == 0 && !desktop_this_value_ok(v) {
                            break Some(Halt::Error(THIS_RANGE.into()));
                        }
                        flags = flags & !NEAR_THIS | near;
                    }
                    seg[THIS] = pop!() as u16;
                    flags |= THIS_OK;
                }
                Op::PopPtr(_) => {
                    if D {
                        let v = rd!(sp.wrapping_sub(1));
                        if !desktop_that_value_ok(v) {
                            break Some(Halt::Error(THAT_RANGE.into()));
                        }
                        flags = if v == 0 {
                            flags | THAT_ZERO
                        } else {
                            flags & !THAT_ZERO
                        };
                        flags = flags & !NEAR_THAT | that_near(v);
                    }
                    seg[THAT] = pop!() as u16;
                    flags |= THAT_OK;
                }
                Op::PopRam(a) => {
                    let v = pop!();
                    wr!(a, v)
                }
                Op::Fail(m) => break Some(Halt::Error(program.messages[m as usize].clone())),
                Op::EntryAccess { local, push, index } => {
                    let entry_invocation = frames.is_empty();
                    let ok = if entry_invocation && function_step {
                        // Desktop: the entry runs without a frame, and its
                        // segments are not checked for it.
                        true
                    } else if entry_invocation {
                        flags & if local { LOCAL_OK } else { ARG_OK } != 0
                    } else if local {
                        index < functions[cur as usize].n_vars
                    } else {
                        index < nargs
                    };
                    if !ok {
                        let m = match (entry_invocation, local) {
                            (true, true) => "The local segment cannot be accessed since it was not initialized",
                            (true, false) => "The argument segment cannot be accessed since it was not initialized",
                            (false, true) => LOCAL_OOB,
                            (false, false) => ARG_OOB,
                        };
                        break Some(Halt::Error(m.into()));
                    }
                    let a = if local { seg[LCL] } else { seg[ARG] }.wrapping_add(index);
                    if push {
                        push!(rd!(a));
                    } else {
                        let v = pop!();
                        wr!(a, v);
                    }
                }
                Op::Add => binary!(|x, y| x.wrapping_add(y)),
                Op::Sub => binary!(|x, y| x.wrapping_sub(y)),
                Op::And => binary!(|x, y| x & y),
                Op::Or => binary!(|x, y| x | y),
                Op::Eq => binary!(|x, y| -i16::from(x == y)),
                Op::Gt => binary!(|x, y| -i16::from(x > y)),
                Op::Lt => binary!(|x, y| -i16::from(x < y)),
                Op::Neg => {
                    let v = pop!();
                    push!(v.wrapping_neg())
                }
                Op::Not => {
                    let v = pop!();
                    push!(!v)
                }
                Op::Goto(t) => pc = t as usize,
                Op::IfGoto(t) => {
                    if pop!() != 0 {
                        pc = t as usize;
                    }
                }
                Op::Multiply => binary!(|x, y| math::multiply(x, y)),
                Op::Divide => {
                    let y = rd!(sp.wrapping_sub(1));
                    match math::divide(divide, rd!(sp.wrapping_sub(2)), y) {
                        Some(q) if sp != 256 && sp != 257 => {
                            sp = sp.wrapping_sub(1);
                            wr!(sp.wrapping_sub(1), q);
                        }
                        _ => builtin!(Builtin::MathDivide, 2u8),
                    }
                }
                Op::CallBuiltin { builtin, nargs: n } => builtin!(builtin, n),
                Op::Call {
                    callee,
                    nargs: n,
                    ret,
                    method,
                } => {
                    if frames.len() >= MAX_DEPTH {
                        break Some(Halt::Error(format!(
                            "Jack call stack deeper than {MAX_DEPTH} frames"
                        )));
                    }
                    let f = &functions[callee as usize];
                    let mut watched = false;
                    if W {
                        if let Some((set, watcher)) = watch {
                            if set.get(callee as usize).copied().unwrap_or(false) {
                                scratch.clear();
                                for k in (1..=n).rev() {
                                    scratch.push(rd!(sp.wrapping_sub(k)));
                                }
                                Regs { sp, base: seg }.store(w);
                                watcher.on_call(program, callee as u32, scratch, ram);
                                w = words(ram);
                                watched = true;
                            }
                        }
                    }
                    charge!();
                    let base = sp;
                    push!(ret as i16);
                    push!(seg[LCL] as i16);
                    push!(seg[ARG] as i16);
                    push!(seg[THIS] as i16);
                    push!(seg[THAT] as i16);
                    seg[ARG] = base.wrapping_sub(n);
                    seg[LCL] = base.wrapping_add(5);
                    if !function_step {
                        zero_locals!(f.n_vars);
                    }
                    // The caller's `that` range is 2048 up after the return.
                    frames.push(Frame {
                        caller: cur,
                        ret_pc: pc as u32,
                        ret: ret as i16,
                        nargs,
                        flags: flags & !(THAT_ZERO | NEAR_BITS),
                        watched,
                    });
                    cur = callee as u32;
                    nargs = n;
                    flags = f.entry_flags(n) | (flags & (THAT_ZERO | NEAR_BITS));
                    pc = f.start as usize;
                    if function_step {
                        // Desktop: the callee's `function` line is the next step.
                        pc -= 1;
                    } else if method && fast_sp(sp) {
                        // The method's `push argument 0; pop pointer 0`.
                        let this = rd!(seg[ARG]);
                        w[usize::from(sp)] = this;
                        seg[THIS] = this as u16;
                        flags |= THIS_OK;
                        steps += 2;
                        pc += 2;
                    }
                }
                Op::Return => do_return!(),
                Op::Function { n_vars, method } => {
                    zero_locals!(n_vars);
                    if method && nargs >= 1 && fast_sp(sp) {
                        // The method's `push argument 0; pop pointer 0`
                        // (desktop: of a value its test takes).
                        let this = rd!(seg[ARG]);
                        let near = if D { this_near(this) } else { 0 };
                        if !D || near != 0 || desktop_this_value_ok(this) {
                            w[usize::from(sp)] = this;
                            seg[THIS] = this as u16;
                            flags = flags & !NEAR_THIS | near | THIS_OK;
                            steps += 2;
                            pc += 2;
                        }
                    }
                }
                Op::Halt => {
                    steps -= 1;
                    break Some(Halt::Exit(Exit::Halted));
                }

                // Fused instructions.
                Op::Push2(a, b) => {
                    if !fast!(a, b) {
                        deopt!();
                    }
                    skip!(op, 2);
                    let top = sp;
                    w[top as usize] = src!(a);
                    sp = top + 1;
                    w[top as usize + 1] = src!(b);
                    sp = top + 2;
                }
                Op::Move(a, d) => {
                    if !fast!(a, d) {
                        deopt!();
                    }
                    skip!(op, 2);
                    let v = src!(a);
                    w[sp as usize] = v;
                    dst!(d, v);
                }
                Op::MoveRun { from, to, len } => {
                    let last = |o: Operand| Operand {
                        off: o.off.wrapping_add(u16::from(len) - 1),
                        ..o
                    };
                    if !fast!(from, to, last(from), last(to)) {
                        deopt!();
                    }
                    skip!(op, 2 * u64::from(len));
                    for k in 0..u16::from(len) {
                        if k > 0 && !fast_sp(sp) {
                            // A move stored into SP itself: the remaining
                            // moves run as instructions of their own.
                            let rest = 2 * u64::from(u16::from(len) - k);
                            steps -= rest;
                            pc -= rest as usize;
                            break;
                        }
                        let v = src!(Operand {
                            off: from.off.wrapping_add(k),
                            ..from
                        });
                        w[usize::from(sp)] = v;
                        dst!(
                            Operand {
                                off: to.off.wrapping_add(k),
                                ..to
                            },
                            v
                        );
                    }
                }
                Op::BinSS { op: o, a, b } => {
                    if !fast!(a, b) {
                        deopt!();
                    }
                    push_push_op!(o, a, b);
                    skip!(op, 3);
                }
                Op::BinPop { op: o, a, b, d } => {
                    if !fast!(a, b, d) {
                        deopt!();
                    }
                    let r = push_push_op!(o, a, b);
                    skip!(op, 4);
                    sp -= 1;
                    dst!(d, r);
                }
                Op::BinS { op: o, b } => {
                    if !fast!(b) {
                        deopt!();
                    }
                    push_op!(op, 2, o, b);
                }
                Op::BinSPop { op: o, b, d } => {
                    if !fast!(b, d) {
                        deopt!();
                    }
                    push_op!(op, 3, o, b, d);
                }
                Op::CmpJump {
                    op: o,
                    a,
                    b,
                    not,
                    target,
                } => {
                    if !fast!(a, b) {
                        deopt!();
                    }
                    skip!(op, 4 + u64::from(not));
                    let r = push_push_op!(o, a, b);
                    let r = if not { !r } else { r };
                    w[sp as usize - 1] = r;
                    sp -= 1;
                    if r != 0 {
                        pc = target as usize;
                    }
                }
                Op::CmpNotJump { op: o, target } => {
                    if !fast_sp(sp) {
                        deopt!();
                    }
                    skip!(op, 3);
                    let top = sp as usize;
                    let Some(r) = apply(o, w[top - 2], w[top - 1], divide) else {
                        deopt!()
                    };
                    w[top - 2] = !r;
                    sp -= 2;
                    if !r != 0 {
                        pc = target as usize;
                    }
                }
                Op::NotIfGoto(target) => {
                    if !fast_sp(sp) {
                        deopt!();
                    }
                    skip!(op, 2);
                    let top = sp as usize;
                    let r = !w[top - 1];
                    w[top - 1] = r;
                    sp -= 1;
                    if r != 0 {
                        pc = target as usize;
                    }
                }
                Op::ArrayRead { index, base } => {
                    if !fast!(index, base) {
                        deopt!();
                    }
                    array_read!(index, base);
                    skip!(op, 5);
                }
                Op::ArrayReadPop { index, base, to } => {
                    if !fast!(index, base, to) {
                        deopt!();
                    }
                    array_read!(index, base, to);
                    skip!(op, 6);
                }
                Op::PtrRead => {
                    if !fast_sp(sp) {
                        deopt!();
                    }
                    let top = sp as usize;
                    let a = w[top - 2].wrapping_add(w[top - 1]);
                    desktop_that_store!(a);
                    skip!(op, 3);
                    w[top - 2] = a;
                    sp -= 2;
                    set_that!(a);
                    let v = rd!(seg[THAT]);
                    w[top - 2] = v;
                    sp += 1;
                }
                Op::StoreThat | Op::StoreThatSrc(_) => {
                    let v = if let Op::StoreThatSrc(s) = *op {
                        if !fast!(s) {
                            deopt!();
                        }
                        desktop_that_store!(w[sp as usize - 1]);
                        let v = src!(s);
                        w[sp as usize] = v;
                        v
                    } else {
                        if !fast_sp(sp) {
                            deopt!();
                        }
                        desktop_that_store!(w[sp as usize - 2]);
                        sp -= 1;
                        w[sp as usize]
                    };
                    skip!(op, if matches!(*op, Op::StoreThat) { 4 } else { 5 });
                    // pop temp 0; pop pointer 1; push temp 0; pop that 0
                    w[5] = v;
                    sp -= 1;
                    set_that!(w[sp as usize]);
                    w[sp as usize] = v;
                    wr!(seg[THAT], v);
                }
                Op::PushReturn(a) => {
                    if !fast!(a) {
                        deopt!();
                    }
                    skip!(op, 2);
                    push!(src!(a));
                    do_return!();
                }
            }
        };

        Regs { sp, base: seg }.store(w);
        self.pc = pc as u32;
        self.steps = steps;
        self.cur = cur;
        self.nargs = nargs;
        self.flags = flags & !NEAR_BITS;
        self.profile_mark = profile_mark;
        match halt {
            Some(halt) => self.end_at(halt),
            None => Flow::Limit,
        }
    }

    /// The end of a run that stopped at `halt`, in the state the machine
    /// stopped in (registers, pc and steps stored).
    pub(crate) fn end_at(&mut self, mut halt: Halt) -> Flow {
        let function_step = Timing::of(self.os.profile()).function_step;
        match halt {
            Halt::OsInFrame(stop, n) => {
                self.desktop_builtin_frame(u16::from(n));
                halt = Halt::Os(stop);
            }
            Halt::BuiltinOverflow(b, n) => {
                halt = self.desktop_builtin_overflow(b, u16::from(n));
            }
            Halt::Blocking(b, n) => match self.web_blocking_call(b, u16::from(n), self.steps) {
                None => return Flow::Limit,
                Some(exit) => return Flow::End(exit),
            },
            _ => {}
        }
        Flow::End(match halt {
            Halt::Deopt => return Flow::Deopt,
            Halt::OsInFrame(..) | Halt::BuiltinOverflow(..) | Halt::Blocking(..) => {
                unreachable!("resolved above")
            }
            Halt::Exit(e) => e,
            Halt::Error(message) => Exit::RuntimeError {
                message: if function_step {
                    self.desktop_message(&message)
                } else {
                    message
                },
                stack: self.call_stack(),
            },
            Halt::Os(Stop::Halt) => Exit::Halted,
            Halt::Os(Stop::SysError(code)) => Exit::SysError {
                code,
                stack: self.call_stack(),
            },
            Halt::Os(Stop::RuntimeError(message)) => Exit::RuntimeError {
                message,
                stack: self.call_stack(),
            },
            Halt::Os(Stop::Hang(message)) => Exit::Hang {
                message,
                stack: self.call_stack(),
            },
            Halt::Os(Stop::BlockedForever) => Exit::BlockedForever {
                stack: self.call_stack(),
            },
        })
    }
}

/// Desktop: where a return resumes `caller` from a RET word that is not
/// the one its call wrote (the program overwrote its frame): the program
/// address `ret`, which must be one of the caller's commands here (the
/// desktop would go on at any address of the program).
fn desktop_resume(program: &Program, caller: u32, ret: i16) -> Result<u32, String> {
    let f = &program.functions[caller as usize];
    let index = i64::from(ret) - i64::from(f.address);
    match usize::try_from(index).ok().and_then(|i| f.resume.get(i)) {
        Some(&pc) if pc != u32::MAX => Ok(pc),
        _ if ret < 0 || ret as usize >= program.command_lines + 5 => {
            Err("Illegal return address".into())
        }
        _ => Err(format!(
            "Return address {ret} is not a command of {}",
            f.name
        )),
    }
}

/// Web: where a return resumes `caller` from its RET word `ret` (read at an
/// address `in_ram` or not), as the web IDE does: the word, or 65,535 when
/// read outside RAM, plus one is the caller's command index. Before the
/// first command or at the end the VM halts there; past the end the return
/// is done and the next step fails.
fn web_resume(program: &Program, caller: u32, ret: i16, in_ram: bool) -> WebResume {
    let f = &program.functions[caller as usize];
    let idx = if in_ram { i32::from(ret) } else { 0xFFFF } + 1;
    let end = f.resume.len() - 1;
    match usize::try_from(idx) {
        Ok(i) if i > end => WebResume::BeyondEnd(format!(
            "Current operation step beyond end of function operations ({idx} > {end})"
        )),
        Ok(i) if f.resume[i] == u32::MAX => WebResume::FunctionLine,
        Ok(i) => WebResume::At(f.resume[i]),
        Err(_) => WebResume::At(f.resume[end]),
    }
}

/// Where a web return resumes its caller.
enum WebResume {
    /// At this instruction.
    At(u32),
    /// Past the caller's last command: the next step fails with this.
    BeyondEnd(String),
    /// At the caller's `function` line, which never runs.
    FunctionLine,
}

impl Machine {
    /// The desktop's RET word for the built-in call just run (`self.pc`
    /// is the instruction after it).
    fn desktop_ret_word(&self) -> i16 {
        let f = &self.program.functions[self.cur as usize];
        f.desktop_return_address(self.pc.wrapping_sub(1))
            .map_or(-1, |a| a as i16)
    }

    /// Desktop: a built-in with `nargs` arguments (popped) ended the run
    /// (halt, error): the VM emulator had pushed the call's frame above
    /// the arguments (RET, LCL, ARG, THIS, THAT) and pointed ARG at them
    /// and LCL and SP above the frame, and the run stops there.
    #[cold]
    fn desktop_builtin_frame(&mut self, nargs: u16) {
        let ret = self.desktop_ret_word();
        let r = &mut self.ram;
        let base = r.read(0).wrapping_add(nargs as i16);
        let saved = [ret, r.read(1), r.read(2), r.read(3), r.read(4)];
        for (a, v) in (i32::from(base)..).zip(saved) {
            r.write(a, v);
        }
        r.write(2, base.wrapping_sub(nargs as i16));
        r.write(1, base.wrapping_add(5));
        r.write(0, base.wrapping_add(5));
    }

    /// Desktop: a built-in call at SP `base` > [`BUILTIN_LAST_BASE`]. Each
    /// push of the call's frame writes its word and then fails if SP would
    /// pass 2047, so from a base of 2043 on the frame stops at RAM[2047]
    /// and the built-in never runs; at 2042 the frame fits, the built-in
    /// runs, and the push of its result at 2047 fails.
    #[cold]
    fn desktop_builtin_overflow(&mut self, b: Builtin, nargs: u16) -> Halt {
        let base = self.ram.read(0);
        let ret = self.desktop_ret_word();
        let saved = [0, 1, 2, 3, 4].map(|a| self.ram.read(a));
        let frame = [ret, saved[1], saved[2], saved[3], saved[4]];
        let last = STACK_LAST as i16;
        if base > last - 5 {
            for (a, v) in (base..=last).zip(frame) {
                self.ram.write(i32::from(a), v);
            }
            self.ram.write(0, last);
            return Halt::Error(STACK_OVERFLOW.into());
        }
        let args: Vec<i16> = (0..nargs)
            .map(|k| {
                self.ram
                    .read(i32::from(base) - i32::from(nargs) + i32::from(k))
            })
            .collect();
        for (a, v) in (i32::from(base)..).zip(frame) {
            self.ram.write(a, v);
        }
        let lcl = base.wrapping_add(5);
        self.ram.write(2, base.wrapping_sub(nargs as i16));
        self.ram.write(1, lcl);
        self.ram.write(0, lcl);
        let c = self.os.call(b, &args, &mut self.ram, &mut self.steps);
        if let Some(stop) = c.stop {
            return Halt::Os(stop);
        }
        self.ram.write(i32::from(lcl), c.value);
        Halt::Error(STACK_OVERFLOW.into())
    }

    /// A runtime error's message as the desktop VM emulator words it: its
    /// own text for the checks it shares, then " in F.i", the function on
    /// top of its call stack and the failing command's index in it (the
    /// `function` line is 0; labels do not count). At a `function` line
    /// the callee is not on its call stack yet: the caller is named.
    #[cold]
    fn desktop_message(&self, web: &str) -> String {
        let text = match web {
            ARG_OOB | LOCAL_OOB => "Out of segment space",
            other => other,
        };
        let p = &self.program;
        let at = self.pc.wrapping_sub(1);
        let f = &p.functions[self.cur as usize];
        let at_function_line = at == f.start.wrapping_sub(1);
        let (name, index) = if at_function_line {
            let caller = self.frames.last().map_or(self.cur, |fr| fr.caller);
            (p.function_name(caller), 0)
        } else {
            (f.name.as_str(), f.desktop_index(at))
        };
        format!("{text} in {name}.{index}")
    }
}
