//! The slow path: the Jack program drawing on the Hack screen by itself,
//! with its Float316 pixel counters (`Image.render`, or all of `Main.main`
//! with a scripted SPACE), read back from screen memory.

use crate::raymarcher::outcome_of;
use crate::{sources, JackError, Raymarcher};
use common::image_consts::{HEIGHT, WIDTH};
use common::Outcome;
use hack_vm::{Config, Exit, KeyScript, Machine, Profile, Ram};
use std::ops::Range;

/// Pixels read from the Hack screen, `true` = white, row-major, and the
/// instructions the drawing took.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ScreenImage {
    /// The first row and the number of rows.
    pub rows: Range<usize>,
    /// `white[(y - rows.start) * WIDTH + x]`.
    pub white: Vec<bool>,
    /// VM instructions executed.
    pub instructions: u64,
}

/// Rows `rows` of the screen (black = a 1 bit).
pub fn read_screen(ram: &Ram, rows: Range<usize>) -> Vec<bool> {
    rows.flat_map(|y| (0..WIDTH).map(move |x| !ram.pixel(x, y)))
        .collect()
}

impl Raymarcher {
    /// Draw the rows `rows` with `Image.render(y0, y1)`: the image loop with
    /// its Float316 counters, a cropped version of `Main.main`.
    pub fn render_band_on_screen(
        &self,
        rows: Range<usize>,
        budget: u64,
    ) -> Result<Outcome<ScreenImage>, JackError> {
        if rows.start > rows.end || rows.end > HEIGHT {
            return Err(JackError::BadArgument(format!(
                "rows {rows:?} are outside 0..{HEIGHT}"
            )));
        }
        let mut m = self.machine();
        let args = [rows.start as i16, rows.end as i16];
        let (outcome, instructions) = self.run_call(&mut m, "Image.render", &args, budget)?;
        Ok(outcome.map(|_| ScreenImage {
            white: read_screen(m.ram(), rows.clone()),
            rows,
            instructions,
        }))
    }
}

/// Instructions between two progress reports of [`run_main`].
const PROGRESS_EVERY: u64 = 100_000_000;

/// Run the whole program as a user would: `Main.main` from the start,
/// SPACE pressed, until it returns (or `max_instructions` run out: a hang).
/// `progress` is told the instructions run so far every 100 million
/// (about a third of a second of emulation).
pub fn run_main(
    profile: Profile,
    max_instructions: u64,
    progress: &mut dyn FnMut(u64),
) -> Result<Outcome<ScreenImage>, JackError> {
    let program = sources::program(profile)?;
    let keys = KeyScript::parse("SPACE", KeyScript::DEFAULT_HOLD).expect("SPACE is a key name");
    let mut m = Machine::new(
        program,
        Config {
            profile,
            keys,
            ..Config::default()
        },
    );
    let exit = match m.run_observed(Some(max_instructions), PROGRESS_EVERY, progress) {
        Exit::Halted => Exit::Returned(0),
        other => other,
    };
    let outcome = outcome_of(exit, || "Main.main".to_string())?;
    Ok(outcome.map(|_| ScreenImage {
        white: read_screen(m.ram(), 0..HEIGHT),
        rows: 0..HEIGHT,
        instructions: m.steps(),
    }))
}
