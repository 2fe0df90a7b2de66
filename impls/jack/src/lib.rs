//! The Jack raymarcher (`impls/jack/raymarcher/*.jack`) on the Hack VM
//! emulator, as the harness uses it: compiled with `jack-compiler`, loaded
//! into `hack-vm` with the native Jack OS, initialised once (`Main.init`)
//! and snapshotted; every computation then runs on a clone of the snapshot,
//! independently and in parallel.
//!
//! - [`Raymarcher::op`], [`Raymarcher::sdf`], [`Raymarcher::pixel`],
//!   [`Raymarcher::render`]: results as [`common::Outcome`]s with the VM
//!   instructions each took. `Sys.error(code)` is `SysError(code)`, except
//!   [`OUT_OF_DOMAIN_CODE`] (floor/mod2 outside their table), which is
//!   `OutOfDomain`; an exhausted instruction budget ([`Budgets`]) is `Hang`.
//! - [`Raymarcher::trace_op`], [`Raymarcher::trace_sdf`],
//!   [`Raymarcher::trace_pixel`]: op traces (`common::TraceRecord`) read
//!   from the emulator by watching the Float316 subroutines.
//! - [`Raymarcher::profile_pixels`]: instructions per Jack function.
//! - The slow path: [`run_main`] (the whole program with a scripted SPACE)
//!   and [`Raymarcher::render_band_on_screen`], read from screen memory.

mod bind;
mod error;
mod profile;
mod raymarcher;
mod screen;
pub mod sources;
mod trace;

pub use bind::{
    normalized_coords, outcome_of, BindError, Bindings, BoundPixel, BoundProgram, BudgetFields,
    Capture, JackProgram, Layout, PixelShade, Ready, Signatures, Statements, WholeRun,
    DEFAULT_READY_BUDGET,
};
pub use error::JackError;
pub use hack_vm::{Config, DivideRule, Profile};
pub use raymarcher::{Budgets, Counted, Raymarcher, Render, Shaded, OUT_OF_DOMAIN_CODE};
pub use screen::{read_screen, run_main, ScreenImage};
