//! The Jack OS of the nand2tetris web IDE, implemented natively in Rust for
//! the Hack VM emulator (`hack-vm`) and described to the Jack compiler by a
//! subroutine table. The reference is `shared/spec/jack-vm-os.md` (sections
//! 0, 1 and 3); two profiles select which official tool is followed:
//! [`Profile::Desktop`] (default: truncating `Math.divide`, the documented
//! API where the web IDE has defects) and [`Profile::Web`] (the web IDE
//! exactly, defects included).
//!
//! Entry points: [`subroutines`] / [`lookup`] (the table of built-ins),
//! [`Os::call`] (run one built-in on a [`Ram`]), [`math::multiply`] and
//! [`math::divide`] (the fast paths the VM may call directly), and
//! [`KeyScript`] (scripted keyboard input for unattended runs).

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
pub use os::{Completion, Os, Stop};
pub use profile::{Profile, ProfileParseError};
pub use ram::{Ram, KBD, RAM_SIZE, SCREEN};
pub use table::{lookup, subroutines, Builtin, OsSubroutine, SubroutineKind};
