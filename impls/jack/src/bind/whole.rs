//! Whole-program mode: the program's own `Main.main`, unmodified, from its
//! entry with scripted keys, its pixels captured as it computes them (the
//! returns of a bound per-pixel function, the calls of a bound draw
//! function, and the screen at the end), and the op trace of chosen pixels
//! (every call of a bound op function inside the per-pixel function, or
//! between two draw calls).

use super::bound::{pixel_context, pixel_reg, BoundProgram};
use super::error::BindError;
use super::ready::{config, key_script};
use super::record::Recorder;
use super::spec::{Bindings, Ready};
use super::statement::{compile, Call, Classes};
use super::vm::outcome_of;
use super::JackProgram;
use crate::screen::read_screen;
use crate::JackError;
use common::image_consts::{HEIGHT, WIDTH};
use common::{Outcome, TraceRecord, F316};
use hack_vm::{Config, Exit, FnId, Machine, Program, Ram, Watcher};
use std::collections::BTreeMap;

/// How a whole run starts and what it watches.
#[derive(Clone, Debug)]
pub(crate) struct WholeSetup {
    pub config: Config,
    pixel: Option<Call>,
    draw: Option<Call>,
}

impl WholeSetup {
    /// Check `capture` of `bindings`.
    pub fn new(
        program: &JackProgram,
        bindings: &Bindings,
        classes: &Classes,
    ) -> Result<WholeSetup, BindError> {
        let mut config = config(program, &bindings.ready)?;
        let Some(capture) = &bindings.capture else {
            return Ok(WholeSetup {
                config,
                pixel: None,
                draw: None,
            });
        };
        if let Some(keys) = &capture.keys {
            let hold = capture.hold.or(match &bindings.ready {
                Ready::Run { hold, .. } => *hold,
                Ready::Init { .. } => None,
            });
            config.keys = key_script("capture.keys", keys, hold)?;
        }
        let context = pixel_context(true);
        let statement = |field: &str, text: &Option<String>| {
            text.as_ref()
                .map(|t| {
                    compile(
                        field,
                        t,
                        &context,
                        classes,
                        &program.program,
                        &program.signatures,
                    )
                })
                .transpose()
        };
        let pixel = statement("capture.pixel", &capture.pixel)?;
        let draw = statement("capture.draw", &capture.draw)?;
        use pixel_reg::*;
        if let Some(c) = &pixel {
            let by_int = c.arg_position(X).is_some() && c.arg_position(Y).is_some();
            let by_float = c.arg_position(U).is_some() && c.arg_position(V).is_some();
            if !by_int && !by_float {
                return Err(BindError::new(
                    "capture.pixel",
                    "the statement must name the pixel's `x` and `y`, or `u` and `v`, among its arguments",
                ));
            }
            if c.target.is_some_and(|t| t != WHITE && t != SHADE) {
                return Err(BindError::new(
                    "capture.pixel",
                    "the return value can only be `white` or `shade`",
                ));
            }
        }
        if let Some(c) = &draw {
            if c.arg_position(X).is_none() || c.arg_position(Y).is_none() {
                return Err(BindError::new(
                    "capture.draw",
                    "the statement must name the pixel's `x` and `y` among its arguments",
                ));
            }
        }
        Ok(WholeSetup {
            config,
            pixel,
            draw,
        })
    }
}

/// What a whole run produced.
#[derive(Clone, Debug, PartialEq)]
pub struct WholeRun {
    /// How the run ended: a value when the program halted.
    pub outcome: Outcome<()>,
    /// VM instructions executed.
    pub instructions: u64,
    /// The white bit of each pixel (`y * WIDTH + x`) given by a capture
    /// event (a return of the pixel function, a draw call), if one did.
    pub captured: Vec<Option<bool>>,
    /// The shade each pixel function returned, when it returns one.
    pub shades: Vec<Option<F316>>,
    /// The screen at the end, `true` = white.
    pub screen: Vec<bool>,
    /// Capture events seen.
    pub events: usize,
    /// The op traces of the pixels asked for.
    pub traces: BTreeMap<(usize, usize), Vec<TraceRecord>>,
}

impl WholeRun {
    /// The image: each pixel's captured bit, else its screen bit (a program
    /// may draw only its black pixels).
    pub fn image(&self) -> Vec<bool> {
        self.captured
            .iter()
            .zip(&self.screen)
            .map(|(c, &s)| c.unwrap_or(s))
            .collect()
    }
}

/// Watches the capture functions (and, when tracing, everything).
struct Capturer<'a> {
    bound: &'a BoundProgram,
    pixel: Option<&'a Call>,
    draw: Option<&'a Call>,
    /// Pixel-function calls in progress: the pixel, whether it is traced.
    open: Vec<(Option<(usize, usize)>, bool)>,
    recorder: Option<Recorder<'a>>,
    wanted: &'a [(usize, usize)],
    run: WholeRun,
}

impl Capturer<'_> {
    /// The pixel a capture call's arguments name.
    fn pixel_of(&self, call: &Call, args: &[i16], ram: &Ram) -> Option<(usize, usize)> {
        use pixel_reg::*;
        let arg = |reg| call.arg_position(reg).map(|p| args[p]);
        let (x, y) = match (arg(X), arg(Y), arg(U), arg(V)) {
            (Some(x), Some(y), _, _) => (i32::from(x), i32::from(y)),
            (_, _, Some(u), Some(v)) => {
                let float = &self.bound.float;
                let u = float.read_float(ram, u).to_f64();
                let v = float.read_float(ram, v).to_f64();
                (
                    (u * 256.0 + 256.0).round() as i32,
                    (128.0 - v * 256.0).round() as i32,
                )
            }
            _ => return None,
        };
        let inside = (0..WIDTH as i32).contains(&x) && (0..HEIGHT as i32).contains(&y);
        inside.then_some((x as usize, y as usize))
    }

    fn traced(&self, p: Option<(usize, usize)>) -> bool {
        p.is_some_and(|p| self.wanted.contains(&p))
    }

    fn keep_trace(&mut self, program: &Program, p: (usize, usize)) {
        if let Some(rec) = &mut self.recorder {
            let root = format!("pixel({},{})", p.0, p.1);
            let records = rec.take(program, &root);
            self.run.traces.insert(p, records);
        }
    }
}

impl Watcher for Capturer<'_> {
    fn on_call(&mut self, program: &Program, function: FnId, args: &[i16], ram: &Ram) {
        if let Some(draw) = self.draw.filter(|c| c.function == function) {
            if let Some(p) = self.pixel_of(draw, args, ram) {
                let white = draw
                    .arg_position(pixel_reg::WHITE)
                    .is_some_and(|i| args[i] != 0);
                self.run.captured[p.1 * WIDTH + p.0] = Some(white);
                self.run.events += 1;
                if self.pixel.is_none() {
                    // Draw calls delimit the pixels' operations.
                    if self.traced(Some(p)) {
                        self.keep_trace(program, p);
                    } else if let Some(rec) = &mut self.recorder {
                        rec.clear();
                    }
                }
            }
        }
        if let Some(pixel) = self.pixel.filter(|c| c.function == function) {
            let p = self.pixel_of(pixel, args, ram);
            let traced = self.traced(p);
            if let Some(rec) = &mut self.recorder {
                if traced {
                    rec.clear();
                    rec.active = true;
                }
            }
            self.open.push((p, traced));
        }
        if let Some(rec) = &mut self.recorder {
            rec.on_call(program, function, args, ram);
        }
    }

    fn on_return(&mut self, program: &Program, function: FnId, value: i16, ram: &Ram) {
        if let Some(rec) = &mut self.recorder {
            rec.on_return(program, function, value, ram);
        }
        let Some(pixel) = self.pixel.filter(|c| c.function == function) else {
            return;
        };
        let Some((p, traced)) = self.open.pop() else {
            return;
        };
        let Some(p) = p else { return };
        let i = p.1 * WIDTH + p.0;
        match pixel.target {
            Some(pixel_reg::WHITE) => self.run.captured[i] = Some(value != 0),
            Some(pixel_reg::SHADE) => {
                self.run.shades[i] = Some(self.bound.float.read_float(ram, value));
            }
            _ => {}
        }
        self.run.events += 1;
        if traced {
            self.keep_trace(program, p);
            if let Some(rec) = &mut self.recorder {
                rec.active = false;
            }
        }
    }
}

/// Instructions between two progress reports of a whole run.
const PROGRESS_EVERY: u64 = 100_000_000;

impl BoundProgram {
    /// Whether whole-program mode captures pixels as they are computed
    /// (else it reads the screen at the end only).
    pub fn captures_pixels(&self) -> bool {
        self.whole.pixel.is_some() || self.whole.draw.is_some()
    }

    /// Run the program from its entry with the bound keys for at most
    /// `budget` instructions, capturing pixels, and the op traces of
    /// `trace` (pixels). `progress` is told the instructions run so far.
    pub fn run_whole(
        &self,
        trace: &[(usize, usize)],
        budget: u64,
        progress: &mut dyn FnMut(u64),
    ) -> Result<WholeRun, JackError> {
        if !trace.is_empty() && !self.captures_pixels() {
            return Err(JackError::Unsupported(
                "op traces in whole-program mode need `capture.pixel` or `capture.draw`".into(),
            ));
        }
        let program = std::sync::Arc::clone(self.snapshot.program());
        let mut m = Machine::new(std::sync::Arc::clone(&program), self.whole.config.clone());
        let n = WIDTH * HEIGHT;
        let recorder = (!trace.is_empty()).then(|| {
            let mut r = Recorder::new(self, &program);
            // With draw calls only, every operation between two of them
            // belongs to the next pixel.
            r.active = self.whole.pixel.is_none();
            r
        });
        let mut watch = vec![false; program.functions().len()];
        if recorder.is_some() {
            watch = Recorder::watch_all(&program);
        }
        for c in [&self.whole.pixel, &self.whole.draw].into_iter().flatten() {
            watch[c.function as usize] = true;
        }
        let mut cap = Capturer {
            bound: self,
            pixel: self.whole.pixel.as_ref(),
            draw: self.whole.draw.as_ref(),
            open: Vec::new(),
            recorder,
            wanted: trace,
            run: WholeRun {
                outcome: Outcome::Hang,
                instructions: 0,
                captured: vec![None; n],
                shades: vec![None; n],
                screen: Vec::new(),
                events: 0,
                traces: BTreeMap::new(),
            },
        };
        let exit = loop {
            let left = budget.saturating_sub(m.steps());
            let exit = m.run_watched(Some(left.min(PROGRESS_EVERY)), &watch, &mut cap);
            progress(m.steps());
            match exit {
                Exit::Budget { .. } if m.steps() < budget => {}
                other => break other,
            }
        };
        let exit = match exit {
            Exit::Halted => Exit::Returned(0),
            other => other,
        };
        let mut run = cap.run;
        run.outcome =
            outcome_of(exit, self.out_of_domain, || "the whole program".into())?.map(|_| ());
        run.instructions = m.steps();
        run.screen = read_screen(m.ram(), 0..HEIGHT);
        Ok(run)
    }
}
