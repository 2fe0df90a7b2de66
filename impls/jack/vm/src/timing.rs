//! How many steps each VM command costs under each profile: the one place
//! that states the official tools' clocks (spec §2.7 for the web IDE, §6
//! for the desktop VM emulator). Every engine that runs a [`Program`]
//! (the interpreter in `exec`, and any other) must count exactly this.
//!
//! | | web | desktop |
//! |---|---|---|
//! | ordinary command (push, pop, arithmetic, goto, if-goto, return) | 1 | 1 |
//! | `label` reached in sequence | 0 | 0 |
//! | jump to a label directly followed by another label | 1 (the jump) | 2: the jump, then a do-nothing step at the second label |
//! | `call` of a VM function | 1 (frame, locals, all in the call) | 1 (frame), then 1 for the callee's `function` line (locals) |
//! | `call` of a built-in | 1 | 1 |
//! | blocking built-in (`Sys.wait`, `Keyboard.read*`) | 2: the call, and the step that hands its result back | 1 |
//! | start of a program with `Main.main` and no `Sys.init` | 8: seven OS init calls and the call of Main.main, then Main.main's body | 1: a hidden `call Sys.init` (the built-in, which calls Main.main), then `function Main.main` (1) |
//! | start at a VM `Sys.init` (or a single file's first function) | its body at once | its `function` line first (1) |
//! | running past a function's last command | halt, 0 | halt, 0 (the desktop tool itself runs on into the next function's `function` line, "Missing return", or stops with "No more instructions to execute"; the harness halts in both) |
//! | `Sys.halt`, `Sys.error` | the call (1), then the run ends | the call (1), then the run ends |
//! | a command that fails (runtime error) | 1 | 1 |
//! | stack: SP outside 256..=2047 | no check (the stack runs on through the heap and the screen) | "Stack overflow" at the push, pop or `function` line that leaves it |
//!
//! A keyboard read moves the clock on to the release of the key it takes
//! (keys are scripted by step, see `jack_os::KeyScript`), in both profiles.
//!
//! How the interpreter keeps this at the edges: the decoded code holds a
//! [`crate::program::Op::Function`] at each function's head, which only
//! desktop calls land on; a desktop jump to a label followed by a label
//! goes through an extra `Goto` placed after the function (the code arrays
//! differ per profile only in those jump targets); the hand-over step is
//! added where a built-in returns; the start-up is set up by
//! [`crate::Machine::new`]. No instruction pays for any of this.
//!
//! The compiled engine (`crate::native`) translates the same per-profile
//! code: a desktop call enters the callee at its `Function` op (which
//! zeroes the locals, as a step of its own), each block charges its
//! instructions' [`crate::program::Op::steps`], and its stack test uses
//! [`Timing::stack_end`]; blocking built-ins, halts and errors are left to
//! the interpreter.

use crate::Profile;
use jack_os::RAM_SIZE;

/// The first word past the stack segment; the desktop keeps SP in
/// `STACK_BASE..=STACK_LAST`.
pub(crate) const STACK_BASE: u16 = 256;
/// The last word of the stack segment.
pub(crate) const STACK_LAST: u16 = 2047;

/// The step rules of one profile (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Timing {
    /// A call of a VM function lands on the callee's `function` line,
    /// which is a step of its own (desktop).
    pub function_step: bool,
    /// A blocking built-in spends one more step handing its result back (web).
    pub handover_step: bool,
    /// A jump to a label directly followed by another label wastes a step (desktop).
    pub label_pair_step: bool,
    /// The program starts with one hidden `call Sys.init` (desktop) rather
    /// than the seven OS init calls and the call of `Main.main` (web).
    pub hidden_sys_init: bool,
    /// SP must stay in the stack segment ("Stack overflow"), desktop.
    pub stack_check: bool,
}

impl Timing {
    /// The rules of `profile`.
    pub const fn of(profile: Profile) -> Timing {
        let desktop = matches!(profile, Profile::Desktop);
        Timing {
            function_step: desktop,
            handover_step: !desktop,
            label_pair_step: desktop,
            hidden_sys_init: desktop,
            stack_check: desktop,
        }
    }

    /// The highest SP that pushes may reach before a stack rule of this
    /// profile applies: the end of the stack segment (desktop, "Stack
    /// overflow" beyond), the end of RAM (web, whose stack runs on through
    /// plain memory). Compiled code checks each block's stack against it.
    pub(crate) const fn stack_end(self) -> u16 {
        if self.stack_check {
            STACK_LAST
        } else {
            RAM_SIZE as u16
        }
    }
}

/// Index of `profile`'s code in [`crate::program::Program`]'s arrays.
pub(crate) const fn index(profile: Profile) -> usize {
    match profile {
        Profile::Desktop => 0,
        Profile::Web => 1,
    }
}

/// The desktop's start-up before `Main.main` runs (its built-in `Sys.init`):
/// the RAM words it writes from the stack pointer `regs[0]` up, and the
/// registers (SP, LCL, ARG, THIS, THAT) at the `function Main.main` line.
/// `regs` are the registers before the run (a `--set` or a test script may
/// have moved them). `program_size` is the RET word of the hidden call (the
/// desktop program's length, with its five invisible commands).
///
/// The hidden `call Sys.init 0` pushes its frame at SP. The built-in's calls
/// of the other built-ins (the OS inits) touch no stack, so its call of
/// `Main.main` pushes the next frame right above: from the default SP of
/// 256, the built-in's frame is at 256, `Main.main`'s at 261 (RET -1, the
/// desktop's "return into a built-in") and LCL = 266.
pub(crate) fn desktop_startup(program_size: i16, regs: [i16; 5]) -> (Vec<i16>, [i16; 5]) {
    let [sp, lcl, arg, this, that] = regs;
    // The hidden call's frame: RET, LCL, ARG, THIS, THAT.
    let mut words = vec![program_size, lcl, arg, this, that];
    let (sys_lcl, sys_arg) = (sp.wrapping_add(5), sp);
    // Main.main's frame, called by the built-in with no arguments.
    words.extend([-1, sys_lcl, sys_arg, this, that]);
    let main_base = sp.wrapping_add(5);
    let main_lcl = main_base.wrapping_add(5);
    (words, [main_lcl, main_lcl, main_base, this, that])
}
