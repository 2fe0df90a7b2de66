//! The scenes step's Jack leg: the program generated from each scene
//! (crate `scene-jack`), opened through a cast entry `scene = FILE` as a
//! user's program is opened through its bindings, and compared with
//! ref-f316 bit for bit: every bound operation on the small ops set, the
//! SDF at the step's query points, and every [`STEP`]-th pixel of every
//! [`STEP`]-th row (level and shade) through `Image.pixel`, the pass that
//! also measures its cost (`harness jack cost`). Those pixels are compared
//! with gpu-f316's too where it rendered the scene. The whole-program
//! screen is not run here (the seed's takes 22 G VM instructions; scene-jack's
//! ignored test compares it).

use super::scenes::{bit_exact_pixels, compare_sdf, SdfTriples};
use super::Night;
use crate::commands::jack::cost::{self, Measured};
use anyhow::{bail, Context, Result};
use common::{Outcome, F316};
use hack_vm::Exit;
use harness::cast::Cast;
use harness::implementation::{Answer, Implementation, Num};
use harness_report::model::Comparison;
use rayon::prelude::*;
use reference::{Described, Scalar, SceneImage, ScenePixel};
use std::path::Path;
use vectors::{Level, SdfVector, Vector};

/// The generated program's label in the report.
pub const LABEL: &str = "jack-generated";

/// Every `STEP`-th pixel of every `STEP`-th row is compared and measured.
pub const STEP: u32 = 2;

/// What the leg found: its comparison rows, the measured pixels (their
/// cost figures and answers) and those pixels as an image.
pub struct JackLeg {
    pub comparisons: Vec<Comparison>,
    pub measured: Measured,
    /// The measured pixels, `ceil(width / STEP)` a row.
    pub image: SceneImage,
}

/// `path` as a TOML literal string.
fn toml_literal(path: &Path) -> Result<String> {
    let text = path.to_str().context("the scene's path is not UTF-8")?;
    if text.contains(['\'', '\n', '\r']) {
        bail!("the scene's path {text:?} cannot be written in a project file");
    }
    Ok(format!("'{text}'"))
}

/// The generated program of `file` opened as a declared `scene = FILE`
/// entry.
fn open(file: &Path) -> Result<Box<dyn Implementation>> {
    // The project file's paths are taken from its own folder.
    let file = std::path::absolute(file)
        .with_context(|| format!("the scene's path {}", file.display()))?;
    let dir = file.parent().unwrap_or(Path::new("/"));
    let text = format!(
        "[impl.{LABEL}]\nkind = \"jack\"\nscene = {}\n",
        toml_literal(&file)?
    );
    let cast = Cast::with_project(&dir.join("harness.toml"), &text)?;
    Ok(cast.open(LABEL)?)
}

/// Run the leg for the scene of `file`: `f316` is its ref-f316, `points`
/// the SDF query points, `images` the legs' renders so far.
pub fn run(
    night: &mut Night<'_>,
    file: &Path,
    scope: &str,
    f316: &Described,
    points: &[[F316; 3]],
    images: &[(String, SceneImage)],
) -> Result<JackLeg> {
    let generated = scene_jack::emit_file(file)?;
    let program = open(file)?;
    let mut comparisons = ops(night, scope, program.as_ref())?;
    let theirs = sdf(program.as_ref(), points)?;
    let mut sdf_row = compare_sdf(scope, points, |p| f316.sdf(p), &theirs);
    sdf_row.b = LABEL.into();
    comparisons.push(sdf_row);
    let measured = cost::measure_generated(file, &generated, STEP, false)?;
    let image = measured_image(&measured, generated.program.pixels.levels)?;
    for (label, theirs) in images {
        if label == "ref-f316" || label == "gpu-f316" {
            let sampled = subsample(theirs, STEP);
            comparisons.push(bit_exact_pixels(
                scope, label, LABEL, &sampled, &image, STEP,
            ));
        }
    }
    Ok(JackLeg {
        comparisons,
        measured,
        image,
    })
}

/// ref-f316 against the program on the small ops set (every operation the
/// program kept; the others are counted as unsupported).
fn ops(
    night: &mut Night<'_>,
    scope: &str,
    program: &dyn Implementation,
) -> Result<Vec<Comparison>> {
    let Some(reference) = night.find("ref-f316") else {
        return Ok(Vec::new());
    };
    let set = vectors::load_named(vectors::named::small_set_name(Level::Ops))?;
    let level = harness::runner::diff_set(
        &[reference, program],
        &set,
        harness::runner::RunOptions::default(),
    );
    super::steps::record_failures(night, &level);
    Ok(level
        .comparisons
        .iter()
        .map(|c| super::steps::summarise(night, c, scope))
        .collect())
}

/// The program's SDF at `points`, through its bindings, batches in
/// parallel.
fn sdf(program: &dyn Implementation, points: &[[F316; 3]]) -> Result<Vec<SdfTriples>> {
    let vectors: Vec<Vector> = points
        .iter()
        .map(|&p| {
            Vector::Sdf(SdfVector {
                category: "scene".into(),
                p,
            })
        })
        .collect();
    let batches: Vec<Vec<Outcome<Answer>>> = vectors
        .par_chunks(program.batch_size(Level::Sdf).max(1))
        .map(|batch| program.eval(batch))
        .collect::<Result<_, _>>()?;
    Ok(batches
        .into_iter()
        .flatten()
        .map(|a| {
            a.map(|a| match a {
                Answer::Sdf {
                    sd: Num::F316(sd),
                    col: Num::F316(col),
                } => (Some(sd), Some(col)),
                _ => (None, None),
            })
        })
        .collect())
}

/// The measured pixels as an image of `levels` levels. A pixel that stops
/// answers as the bindings make it answer (`Sys.error(316)`: out of
/// domain); one that stops otherwise fails the leg.
fn measured_image(m: &Measured, levels: u8) -> Result<SceneImage> {
    let pixels = m
        .pixels
        .iter()
        .zip(&m.answers)
        .map(|(&(x, y), a)| match &a.answer {
            Ok(p) => Ok(Outcome::Value(ScenePixel {
                value: Scalar {
                    value: p.shade.to_f64(),
                    triple: Some(p.shade),
                },
                level: u8::try_from(p.level)
                    .with_context(|| format!("pixel ({x},{y}): level {}", p.level))?,
            })),
            Err(exit) => match **exit {
                Exit::SysError { code, .. } if code == scene_jack::OUT_OF_DOMAIN => {
                    Ok(Outcome::OutOfDomain)
                }
                Exit::SysError { code, .. } => Ok(Outcome::SysError(code)),
                Exit::Budget { .. } | Exit::Hang { .. } => Ok(Outcome::Hang),
                ref other => bail!("pixel ({x},{y}) stopped: {other}"),
            },
        })
        .collect::<Result<Vec<_>>>()?;
    let c = &m.cost;
    Ok(SceneImage {
        width: c.width.div_ceil(c.step) as usize,
        height: c.height.div_ceil(c.step) as usize,
        levels,
        pixels,
    })
}

/// Every `step`-th pixel of every `step`-th row of `image`.
pub fn subsample(image: &SceneImage, step: u32) -> SceneImage {
    let step = step as usize;
    let rows = (0..image.height).step_by(step);
    let width = image.width.div_ceil(step);
    SceneImage {
        width,
        height: image.height.div_ceil(step),
        levels: image.levels,
        pixels: rows
            .flat_map(|y| {
                (0..image.width)
                    .step_by(step)
                    .map(move |x| image.pixels[y * image.width + x])
            })
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn subsampling_keeps_every_step_th_pixel_of_every_step_th_row() {
        let pixels = (0..15)
            .map(|i| {
                Outcome::Value(ScenePixel {
                    value: Scalar {
                        value: f64::from(i),
                        triple: None,
                    },
                    level: 0,
                })
            })
            .collect();
        let image = SceneImage {
            width: 5,
            height: 3,
            levels: 2,
            pixels,
        };
        let s = subsample(&image, 2);
        assert_eq!((s.width, s.height), (3, 2));
        let values: Vec<f64> = s
            .pixels
            .iter()
            .map(|p| p.value().unwrap().value.value)
            .collect();
        assert_eq!(values, [0.0, 2.0, 4.0, 10.0, 12.0, 14.0]);
    }

    #[test]
    fn a_path_with_a_quote_is_refused_not_misquoted() {
        assert_eq!(toml_literal(Path::new("/a/b.json")).unwrap(), "'/a/b.json'");
        assert!(toml_literal(Path::new("/a/it's.json")).is_err());
    }
}
