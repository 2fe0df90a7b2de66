//! The OS as the VM sees it: state, reset, and one entry point per call.

use crate::context::{Ctx, OsState};
use crate::{math, Builtin, KeyScript, Profile, Ram};

/// How a built-in call ends the run.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Stop {
    /// `Sys.halt()`: exit code 0.
    Halt,
    /// `Sys.error(code)`, called by the program or raised by a built-in;
    /// `"ERR<code>"` has been printed at the cursor.
    SysError(i16),
    /// The official tool throws (e.g. web `Output.moveCursor(i, 64)`:
    /// "Maximum call stack size exceeded"), or the call itself is malformed.
    RuntimeError(String),
    /// The official tool loops forever inside the built-in (e.g.
    /// `Memory.deAlloc` on a free list with a cycle); detected, not run.
    Hang(String),
    /// A keyboard read waits for a key the script never delivers.
    BlockedForever,
}

/// The result of one built-in call: the value the VM pushes (0 for void
/// built-ins), and whether the VM must stop after pushing it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Completion {
    /// The return value, mod 2^16.
    pub value: i16,
    /// `Some` when the run ends with this call.
    pub stop: Option<Stop>,
}

/// All OS state outside RAM: free-list head, cursor, colour, profile, keys.
/// Cloning it (with a [`Ram`]) snapshots a machine.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Os {
    state: OsState,
}

impl Os {
    /// An OS in its reset state; call [`Os::reset`] on the RAM as well.
    pub fn new(profile: Profile, keys: KeyScript) -> Os {
        Os::with_divide(profile, crate::DivideRule::of(profile), keys)
    }

    /// An OS of `profile` whose `Math.divide` rounds by `divide` (every
    /// other rule is the profile's).
    pub fn with_divide(profile: Profile, divide: crate::DivideRule, keys: KeyScript) -> Os {
        Os {
            state: OsState::new(profile, divide, keys),
        }
    }

    /// Section 1 reset: RAM all 0, SP = 256, the heap header (web: `RAM[2048]
    /// = 0`, `RAM[2049] = 14334`; desktop: 14334 and 16384, as its
    /// `Memory.init` writes them); free-list head 2048, cursor (0,0),
    /// colour black.
    pub fn reset(&mut self, ram: &mut Ram) {
        self.state = OsState::new(
            self.state.profile,
            self.state.divide,
            self.state.keys.clone(),
        );
        ram.words_mut().fill(0);
        ram.write(0, 256);
        match self.state.profile {
            Profile::Web => {
                ram.write(crate::ram::HEAP_BASE, 0);
                ram.write(crate::ram::HEAP_BASE + 1, crate::ram::HEAP_SIZE as i16);
            }
            // As the desktop's built-in Memory.init writes it (a VM that
            // never calls Memory.init clears it again).
            Profile::Desktop => crate::memory::desktop_header(ram),
        }
    }

    /// The profile chosen at construction.
    pub fn profile(&self) -> Profile {
        self.state.profile
    }

    /// `Math.divide`'s rounding, chosen at construction.
    pub fn divide_rule(&self) -> crate::DivideRule {
        self.state.divide
    }

    /// The key script.
    pub fn keys(&self) -> &KeyScript {
        &self.state.keys
    }

    /// Output cursor (row, column).
    pub fn cursor(&self) -> (i32, i32) {
        (self.state.row, self.state.col)
    }

    /// The free-list head pointer.
    pub fn heap_head(&self) -> i32 {
        self.state.heap_head
    }

    /// Screen colour: true = black.
    pub fn color(&self) -> bool {
        self.state.color
    }

    /// Run built-in `f` with `args` in VM order (`this` first for methods).
    /// `clock` is the VM's instruction count; keyboard reads advance it to
    /// the release of the key they consume. Never panics: a wrong number of
    /// arguments is a [`Stop::RuntimeError`].
    pub fn call(&mut self, f: Builtin, args: &[i16], ram: &mut Ram, clock: &mut u64) -> Completion {
        if args.len() != f.vm_arity() {
            return Completion {
                value: 0,
                stop: Some(Stop::RuntimeError(format!(
                    "OS function {} expects {} arguments, not {}",
                    f.full_name(),
                    f.vm_arity(),
                    args.len()
                ))),
            };
        }
        let mut ctx = Ctx {
            os: &mut self.state,
            ram,
            clock,
            stop: None,
        };
        let value = dispatch(&mut ctx, f, args);
        Completion {
            value: value as i16,
            stop: ctx.stop,
        }
    }
}

impl Os {
    /// What a blocking built-in (`f.blocks()`) shows before its wait: the
    /// cursor of a keyboard read (after `readLine`'s and `readInt`'s
    /// prompt); nothing for `Sys.wait`. A VM whose run stops while the
    /// official tool is still waiting shows this state; the call itself is
    /// then made from the state before it.
    pub fn start_blocking(&mut self, f: Builtin, args: &[i16], ram: &mut Ram, clock: &mut u64) {
        let mut ctx = Ctx {
            os: &mut self.state,
            ram,
            clock,
            stop: None,
        };
        match f {
            Builtin::KeyboardReadChar => ctx.draw_cursor(),
            Builtin::KeyboardReadLine | Builtin::KeyboardReadInt => {
                ctx.print_string(arg(args, 0));
                ctx.draw_cursor();
            }
            _ => {}
        }
    }
}

/// Argument `i` as an unwrapped number (the arity is checked by the caller).
fn arg(args: &[i16], i: usize) -> i32 {
    args.get(i).copied().map_or(0, i32::from)
}

/// Run one built-in; the result is wrapped to 16 bits by the caller.
fn dispatch(ctx: &mut Ctx, f: Builtin, args: &[i16]) -> i32 {
    use Builtin::*;
    let a = |i| arg(args, i);
    let w = |i| args.get(i).copied().unwrap_or(0);
    match f {
        MemoryInit if ctx.profile() == Profile::Desktop => {
            crate::memory::desktop_header(ctx.ram);
            0
        }
        MathInit | MemoryInit | ArrayInit | StringInit | OutputInit | ScreenInit | KeyboardInit => {
            0
        }
        MathMultiply => math::multiply(w(0), w(1)).into(),
        MathDivide => match math::divide(ctx.divide_rule(), w(0), w(1)) {
            Some(q) => q.into(),
            None => {
                ctx.error(3);
                0
            }
        },
        MathMin => math::min(w(0), w(1)).into(),
        MathMax => math::max(w(0), w(1)).into(),
        MathAbs => math::abs(w(0)).into(),
        MathSqrt => match math::sqrt(w(0)) {
            Some(r) => r.into(),
            None => {
                ctx.error(4);
                0
            }
        },
        MemoryPeek if ctx.profile() == Profile::Desktop => ctx.checked_get(a(0)),
        MemoryPoke if ctx.profile() == Profile::Desktop => {
            ctx.checked_set(a(0), a(1));
            0
        }
        MemoryPeek => ctx.get(a(0)),
        MemoryPoke => {
            ctx.set(a(0), a(1));
            0
        }
        MemoryAlloc => ctx.alloc(a(0)),
        MemoryDeAlloc | ArrayDispose | StringDispose => {
            ctx.dealloc(a(0));
            0
        }
        ArrayNew => ctx.array_new(a(0)),
        StringNew => ctx.string_new(a(0)),
        StringLength => ctx.string_length(a(0)),
        StringCharAt => ctx.string_char_at(a(0), a(1)),
        StringSetCharAt => {
            ctx.string_set_char_at(a(0), a(1), a(2));
            0
        }
        StringAppendChar => ctx.string_append_char(a(0), a(1)),
        StringEraseLastChar => {
            ctx.string_erase_last_char(a(0));
            0
        }
        StringIntValue => ctx.string_int_value(a(0)),
        StringSetInt => {
            ctx.string_set_int(a(0), w(1));
            0
        }
        StringBackSpace => crate::string::BACKSPACE,
        StringDoubleQuote => crate::string::DOUBLE_QUOTE,
        StringNewLine => crate::string::NEW_LINE,
        OutputMoveCursor => {
            ctx.move_cursor(a(0), a(1));
            0
        }
        OutputPrintChar => {
            ctx.print_char(a(0));
            0
        }
        OutputPrintString => {
            ctx.print_string(a(0));
            0
        }
        OutputPrintInt => {
            ctx.print_int(w(0));
            0
        }
        OutputPrintln => {
            ctx.println();
            0
        }
        OutputBackSpace => {
            ctx.backspace();
            0
        }
        ScreenClearScreen => {
            ctx.clear_screen();
            0
        }
        ScreenSetColor => {
            ctx.os.color = a(0) != 0;
            0
        }
        ScreenDrawPixel => {
            ctx.draw_pixel(a(0), a(1));
            0
        }
        ScreenDrawLine => {
            let color = ctx.os.color;
            ctx.draw_line(a(0), a(1), a(2), a(3), color);
            0
        }
        ScreenDrawRectangle => {
            let color = ctx.os.color;
            ctx.draw_rect(a(0), a(1), a(2), a(3), color);
            0
        }
        ScreenDrawCircle => {
            ctx.draw_circle(a(0), a(1), a(2));
            0
        }
        KeyboardKeyPressed => ctx.get(crate::KBD as i32),
        KeyboardReadChar => ctx.read_char(),
        KeyboardReadLine => ctx.read_line(a(0)),
        KeyboardReadInt => ctx.read_int(a(0)),
        SysHalt => {
            ctx.halt();
            0
        }
        SysError => {
            ctx.error(w(0));
            0
        }
        SysWait => {
            // A real-time pause in the IDE: no state change here.
            if a(0) <= 0 {
                ctx.error(1);
            }
            0
        }
    }
}
