//! The Jack OS of the nand2tetris web IDE, implemented natively in Rust for
//! the Hack VM emulator (`hack-vm`) and described to the Jack compiler by a
//! subroutine table. It behaves as the official nand2tetris tools' OS does,
//! quirks included (Output, Screen, Math, String, Array, Memory, Keyboard
//! and Sys, each module's rules stated in its own documentation); two
//! profiles select which official tool is followed:
//! [`Profile::Desktop`] (default: truncating `Math.divide`, the documented
//! API where the web IDE has defects) and [`Profile::Web`] (the web IDE
//! exactly, defects included).
//!
//! Entry points: [`subroutines`] / [`lookup`] (the table of built-ins),
//! [`Os::call`] (run one built-in on a [`Ram`]), [`math::multiply`] and
//! [`math::divide`] (the fast paths the VM may call directly), and
//! [`KeyScript`] (scripted keyboard input for unattended runs).
//!
//! Errors follow the web IDE: `Sys.error` prints `"ERR<code>"` at the cursor
//! and marks the run halted, but the built-in that raised it runs to its end
//! (so a circle can print ERR8 once per off-screen row); the VM pushes the
//! value and stops. Where the IDE itself crashes or never returns, the call
//! reports a [`Stop`] instead of crashing or hanging.
//!
//! Choices where the spec is silent (checked against the IDE's TypeScript
//! where possible):
//! - Several errors in one call: the exit code is the **last** one, as the
//!   IDE's `Sys.error` overwrites it (`String.new(-3)`: ERR14 then ERR2 -> 2).
//! - The desktop profile's strict bounds apply to `Screen.drawPixel` only;
//!   lines, rectangles, circles and Output's drawing share the web rules in
//!   both profiles (so clearChar at column 63 wraps to column 0 in both).
//! - Desktop `String.new(0)` allocates the 3-word header and no char array
//!   (`RAM[s+2] = 0`).
//! - `intValue` accumulates digits as a JavaScript double, then wraps, so it
//!   matches the IDE even for strings of more than 15 digits.
//! - A free-list walk that never ends (a double free) is [`Stop::Hang`]; a
//!   read whose key never comes is [`Stop::BlockedForever`], even after an
//!   error inside the same `readLine`.

mod context;
mod font;
mod keyboard;
mod keys;
pub mod math;
mod memory;
mod os;
mod output;
mod profile;
mod ram;
mod screen;
mod string;
mod table;

pub use keys::{KeyScript, KeyScriptError};
pub use math::DivideRule;
pub use os::{Completion, Os, Stop};
pub use profile::{Profile, ProfileParseError};
pub use ram::{Ram, KBD, RAM_SIZE, SCREEN};
pub use table::{lookup, subroutines, Builtin, OsSubroutine, SubroutineKind};
