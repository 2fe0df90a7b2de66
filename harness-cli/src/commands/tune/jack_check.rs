//! The check on the generated Jack programs: each configuration's program
//! draws its reference's image bit for bit (level and shade triple at every
//! measured pixel), and what it costs, measured on the emulator (`harness
//! jack cost`'s measurement).

use crate::commands::jack::cost::{measure_generated, SceneCost};
use common::Outcome;
use reference::{Described, SceneImage};
use scene_jack::cost::{Answer, Pixel};
use std::path::Path;

/// A program measured and compared with its reference.
pub struct JackCheck {
    pub cost: SceneCost,
    /// Measured pixels whose answer differs from the reference's.
    pub mismatches: usize,
    /// The first few, in words.
    pub first_mismatches: Vec<String>,
}

/// Mismatches listed in full.
const LISTED: usize = 5;

/// Whether Jack's `answer` is the reference's `pixel`, bit for bit.
fn same(answer: &Answer<Pixel>, pixel: &Outcome<reference::ScenePixel>) -> bool {
    match (answer, pixel) {
        (Ok(a), Outcome::Value(p)) => {
            i16::from(p.level) == a.level && p.value.triple == Some(a.shade)
        }
        // A stop against a value differs; two stops count as the same
        // (the check is on what is drawn).
        (Err(_), Outcome::Value(_)) | (Ok(_), _) => false,
        (Err(_), _) => true,
    }
}

/// Generate the program of `checked` (whose ref-f316 is `reference`, its
/// image `image`), measure every `step`-th pixel of every `step`-th row and
/// compare each with the image.
pub fn check(
    file: &Path,
    checked: scene::Checked,
    reference: &Described,
    image: &SceneImage,
    step: u32,
) -> anyhow::Result<JackCheck> {
    let program = reference.program().clone();
    let sources = scene_jack::emit(&program)?;
    let generated = scene_jack::Generated {
        checked,
        program,
        sources,
    };
    let m = measure_generated(file, &generated, step, false)?;
    let mut check = JackCheck {
        cost: m.cost,
        mismatches: 0,
        first_mismatches: Vec::new(),
    };
    for (&(x, y), a) in m.pixels.iter().zip(&m.answers) {
        let p = &image.pixels[y as usize * image.width + x as usize];
        if !same(&a.answer, p) {
            check.mismatches += 1;
            if check.first_mismatches.len() < LISTED {
                check
                    .first_mismatches
                    .push(format!("({x},{y}): jack {:?}, ref-f316 {p:?}", a.answer));
            }
        }
    }
    Ok(check)
}
