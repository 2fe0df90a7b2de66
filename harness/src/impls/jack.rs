//! Adapter for the Jack raymarcher on the Hack VM emulator: every call runs
//! on a clone of a snapshot taken after `Main.init`; op traces come from
//! the emulator watching the Float316 subroutines. The image level renders
//! through the pixel entry point, pixels in parallel.
//!
//! The OS profile is selectable: `desktop` (the seed program's, truncating
//! `Math.divide`) or `web` (the web IDE's, whose `Math.divide` floors): the
//! latter is the "floor division in the emulator's Math.divide" fault.

use crate::cast::file::{FieldError, Fields};
use crate::cast::{Entry, Kind, Opener, Request, VariantInfo, VariantRole};
use crate::implementation::{Answer, Bitmap, ImplError, Implementation, Num, Numbers};
use common::image_consts::{HEIGHT, WIDTH};
use common::{OpValue, Outcome, TraceRecord};
pub use jack::Profile;
use jack::{Budgets, JackError, Raymarcher};
use vectors::{Level, Vector};

/// The `jack` kind: the seed Jack raymarcher on the emulator (built-in
/// `jack`, fault `web-divide`); a declared entry picks the OS profile with
/// `profile = "desktop" | "web"`.
pub struct JackKind;

/// The fault that runs the program under the web IDE's OS profile.
const WEB_DIVIDE: &str = "web-divide";

fn entry(profile: Profile) -> Entry {
    Entry::new("jack", "jack", Numbers::Float316, JackOpener { profile })
        .traces()
        .slow()
        .variants(vec![VariantInfo {
            name: WEB_DIVIDE.into(),
            role: VariantRole::Fault,
        }])
}

impl Kind for JackKind {
    fn name(&self) -> &'static str {
        "jack"
    }

    fn builtins(&self) -> Vec<Entry> {
        vec![entry(Profile::Desktop)
            .about("the seed Jack raymarcher on the Hack VM emulator, through its entry points")]
    }

    fn declare(&self, _name: &str, fields: &mut Fields<'_>) -> Result<Entry, FieldError> {
        let profile = fields
            .parsed::<Profile>("profile")?
            .unwrap_or(Profile::Desktop);
        Ok(entry(profile).about(format!(
            "the seed Jack raymarcher under the {} OS profile",
            profile.name()
        )))
    }
}

/// Opens the raymarcher under a profile (`web-divide`: the web one).
struct JackOpener {
    profile: Profile,
}

impl Opener for JackOpener {
    fn open(&self, request: &Request<'_>) -> Result<Box<dyn Implementation>, ImplError> {
        request.seed_scene_only()?;
        let profile = if request.label.variants.iter().any(|v| v == WEB_DIVIDE) {
            Profile::Web
        } else {
            self.profile
        };
        Ok(Box::new(JackAdapter::new(
            profile,
            request.label.to_string(),
        )?))
    }
}

/// The Jack raymarcher under one OS profile.
pub struct JackAdapter {
    raymarcher: Raymarcher,
    label: String,
}

/// The whole image through the pixel entry point, pixels in parallel,
/// with a bar of pixels done when standard error is a terminal.
pub fn render_with_bar(raymarcher: &Raymarcher) -> Result<jack::Render, JackError> {
    let bar = crate::progress::show(
        crate::progress::items((WIDTH * HEIGHT) as u64, "jack", "pixels"),
        crate::progress::wanted(),
    );
    let render = raymarcher.render_rows_observed(0..HEIGHT, &|| bar.inc(1));
    bar.finish_and_clear();
    render
}

fn failed(e: JackError) -> ImplError {
    ImplError::Failed(e.to_string())
}

impl JackAdapter {
    /// Compile the raymarcher and take its snapshot under `profile`.
    pub fn new(profile: Profile, label: String) -> Result<Self, ImplError> {
        let raymarcher = Raymarcher::new(profile, Budgets::default()).map_err(|e| {
            ImplError::Unavailable(format!("the Jack raymarcher does not build: {e}"))
        })?;
        Ok(JackAdapter { raymarcher, label })
    }

    fn answer(&self, v: &Vector) -> Result<Outcome<Answer>, ImplError> {
        Ok(match v {
            Vector::Op(o) => self
                .raymarcher
                .op(o.op, &o.args())
                .map_err(failed)?
                .outcome
                .map(|r| match r {
                    OpValue::Bool(value) => Answer::Bool { value },
                    OpValue::Num(t) => Answer::Num {
                        value: Num::F316(t),
                    },
                }),
            Vector::Sdf(s) => self
                .raymarcher
                .sdf(s.p)
                .map_err(failed)?
                .outcome
                .map(|(sd, col)| Answer::Sdf {
                    sd: Num::F316(sd),
                    col: Num::F316(col),
                }),
            Vector::Pixel(p) => self
                .raymarcher
                .pixel(usize::from(p.x), usize::from(p.y))
                .map_err(failed)?
                .outcome
                .map(|s| Answer::Pixel {
                    shade: Num::F316(s.value),
                    white: s.white,
                }),
            Vector::Image(_) => {
                let render = self.raymarcher.render().map_err(failed)?;
                // A pixel whose computation trapped is never drawn: the
                // Hack screen starts white.
                let white = render
                    .pixels
                    .iter()
                    .map(|p| p.outcome.value().is_none_or(|s| s.white))
                    .collect();
                Outcome::Value(Answer::Image {
                    bitmap: Bitmap {
                        width: WIDTH,
                        height: HEIGHT,
                        white,
                    },
                })
            }
        })
    }
}

impl Implementation for JackAdapter {
    fn label(&self) -> String {
        self.label.clone()
    }

    fn numbers(&self) -> Numbers {
        Numbers::Float316
    }

    fn supports(&self, _level: Level) -> bool {
        true
    }

    fn batch_size(&self, level: Level) -> usize {
        // Each vector runs on its own clone of the snapshot: small batches
        // spread over the cores.
        match level {
            Level::Ops => 256,
            Level::Sdf => 16,
            Level::Pixels | Level::Image => 1,
        }
    }

    fn eval(&self, batch: &[Vector]) -> Result<Vec<Outcome<Answer>>, ImplError> {
        batch.iter().map(|v| self.answer(v)).collect()
    }

    fn trace(&self, input: &Vector) -> Result<Vec<TraceRecord>, ImplError> {
        match input {
            Vector::Op(o) => self.raymarcher.trace_op(o.op, &o.args()),
            Vector::Sdf(s) => self.raymarcher.trace_sdf(s.p),
            Vector::Pixel(p) => self
                .raymarcher
                .trace_pixel(usize::from(p.x), usize::from(p.y)),
            Vector::Image(_) => {
                return Err(ImplError::Unsupported("a trace of the whole image".into()))
            }
        }
        .map_err(failed)
    }
}
