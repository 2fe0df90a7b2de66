//! Built-in OS calls from compiled code. A compiled block that ends in
//! `call Class.builtin n` writes its state to the context and calls
//! [`call`], which runs the built-in as the interpreter does (pop the
//! arguments, call the OS, push the result) and tells compiled code
//! whether it may go on with the next block, so that OS-heavy code (string
//! output, `Memory.alloc`, `Screen` drawing) does not leave compiled code
//! at every call. Compiled code tests beforehand that the pops and the push
//! are plain stack words (else the interpreter runs the call); blocking
//! built-ins are never called from here (see `blocks::kind`).

use super::{Ctx, CONTINUE, STOPPED};
use crate::exec::{Halt, STACK_OVERFLOW};
use crate::timing::{Timing, STACK_BASE, STACK_LAST};
use jack_os::{Profile, RAM_SIZE};

/// Code: the call was made and its value pushed; the registers are as
/// they were, so compiled code goes on (SP is its value less the
/// arguments plus one, the step count is in the context; the context's
/// registers are not written).
pub(crate) const DONE: i32 = -4;

/// The `what` word compiled code passes: the built-in's index in
/// [`jack_os::subroutines`], the argument count, the profile.
pub(crate) fn what(builtin: jack_os::Builtin, nargs: u8, profile: Profile) -> u32 {
    builtin as u32 | u32::from(nargs) << 8 | u32::from(matches!(profile, Profile::Desktop)) << 16
}

/// Run the built-in `what` (see [`what`]) for compiled code, with the
/// registers `regs` (SP with the arguments pushed, LCL, ARG and THIS, 16
/// bits each from the lowest), THAT and the step count `steps` (the call's
/// own step included); the step count after it goes to `Ctx::steps`.
/// Returns [`DONE`]; [`CONTINUE`] where the built-in wrote a register (the
/// registers in the context, the push made, compiled code re-entered at
/// the next instruction with its entry tests); or [`STOPPED`] with
/// `Ctx::stopped` (the registers in the context) where the run ends. The
/// registers come as arguments, not through the context, since a load of
/// the words compiled code has just stored one by one would wait for them.
///
/// # Safety
/// `ctx` is the context `Machine::enter_native` made, its `os` and
/// `ram_obj` pointing at the running machine's, and SP at least 256 plus
/// the argument count.
pub(crate) unsafe extern "C" fn call(
    ctx: *mut Ctx,
    what: u32,
    regs: u64,
    that: u32,
    steps: u64,
) -> i32 {
    // SAFETY: as the caller promises.
    let ctx = unsafe { &mut *ctx };
    let (os, ram) = unsafe { (&mut *ctx.os, &mut *ctx.ram_obj) };
    let builtin = jack_os::subroutines()[(what & 0xFF) as usize].builtin;
    let n = ((what >> 8) & 0xFF) as u16;
    let timing = Timing::of(if what >> 16 != 0 {
        Profile::Desktop
    } else {
        Profile::Web
    });
    let top = regs as u16;
    let sp = top - n;
    let regs = [
        sp,
        (regs >> 16) as u16,
        (regs >> 32) as u16,
        (regs >> 48) as u16,
        that as u16,
    ];
    let w = ram.words_mut();
    // Word by word: a slice copy of a length known only here is a call
    // of memcpy, a tenth of the time of string-heavy code.
    let mut args = [0i16; 8];
    for (arg, &word) in args.iter_mut().zip(&w[usize::from(sp)..usize::from(top)]) {
        *arg = word;
    }
    for (word, r) in w.iter_mut().zip(regs) {
        *word = r as i16;
    }
    ctx.steps = steps;
    let c = os.call(builtin, &args[..usize::from(n)], ram, &mut ctx.steps);
    let w = ram.words_mut();
    let moved = (0..5).any(|i| w[i] as u16 != regs[i]);
    if c.stop.is_none() && !moved {
        w[usize::from(sp)] = c.value;
        return DONE;
    }
    [ctx.sp, ctx.lcl, ctx.arg, ctx.this, ctx.that] = [0, 1, 2, 3, 4].map(|i| w[i] as u16);
    let pushed = match &c.stop {
        // Desktop: the run ends inside the built-in, its result not pushed.
        Some(_) if timing.function_step => Ok(()),
        _ => push(ctx, w, c.value, timing),
    };
    ctx.stopped = match (pushed, c.stop) {
        (Err(halt), _) => Some(halt),
        (Ok(()), Some(stop)) if timing.function_step => Some(Halt::OsInFrame(stop, n as u8)),
        (Ok(()), Some(stop)) => Some(Halt::Os(stop)),
        (Ok(()), None) => return CONTINUE,
    };
    STOPPED
}

/// The interpreter's push of `v` at the context's SP, after a built-in
/// that moved a register: a word of the stack segment, else the profile's
/// rule (a register or a word outside RAM written as the interpreter
/// writes it, the desktop's "Stack overflow").
fn push(ctx: &mut Ctx, w: &mut [i16], v: i16, timing: Timing) -> Result<(), Halt> {
    let at = ctx.sp;
    if (STACK_BASE..STACK_LAST).contains(&at) {
        w[usize::from(at)] = v;
    } else {
        match at {
            // SP itself, as the interpreter's push writes it: the SP set
            // below replaces it, unless the desktop's overflow stops first.
            0 => ctx.sp = v as u16,
            1 => ctx.lcl = v as u16,
            2 => ctx.arg = v as u16,
            3 => ctx.this = v as u16,
            4 => ctx.that = v as u16,
            a if usize::from(a) < RAM_SIZE => w[usize::from(a)] = v,
            _ => {}
        }
        if timing.stack_check && !(STACK_BASE..=STACK_LAST).contains(&at.wrapping_add(1)) {
            return Err(Halt::Error(STACK_OVERFLOW.into()));
        }
    }
    ctx.sp = at.wrapping_add(1);
    Ok(())
}
