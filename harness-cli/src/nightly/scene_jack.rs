//! The scenes step's Jack leg: the program generated from each scene
//! (crate `scene-jack`), opened through a cast entry `scene = FILE` as a
//! user's program is opened through its bindings, and compared with
//! ref-f316 bit for bit:
//!
//! - every bound operation on the small ops set;
//! - the SDF at the step's query points;
//! - every drawn pixel (level and shade) through `Image.pixel`, pixels in
//!   parallel on copies of the program after `Main.init` (the engine
//!   compiles the program once the first 100 M steps are interpreted): the
//!   pass that also measures its cost (`harness jack cost --step 1`);
//! - the whole program's screen: `Main.main`, unmodified, through the
//!   bindings' whole-program capture, against the screen the reference's
//!   levels make by the program's documented rule
//!   (`scene_jack::expected_screen`), and for the seed scene against the
//!   committed render as well.
//!
//! The pixels and the screen are compared with gpu-f316's too where it
//! rendered the scene.

use super::scenes::{bit_exact_pixels, compare_sdf, comparison, diverged, example, SdfTriples};
use super::Night;
use crate::commands::jack::cost::{self, Measured};
use anyhow::{bail, Context, Result};
use common::image_consts::{HEIGHT, WIDTH};
use common::{Outcome, F316};
use harness::cast::Cast;
use harness::implementation::{Answer, Implementation, Num};
use harness_report::model::Comparison;
use harness_report::BIT_EXACT;
use rayon::prelude::*;
use reference::{Scalar, SceneImage, ScenePixel, SdfValue};
use std::path::Path;
use std::time::Instant;
use vectors::{Level, SdfVector, Vector};

/// The generated program's label in the report.
pub const LABEL: &str = "jack-generated";

/// The label of the generated program's screen.
pub fn screen_label() -> String {
    super::steps::screen_label(LABEL)
}

/// What the leg found: its comparison rows, the measured pixels (their
/// cost figures and answers), those pixels as an image, its SDF answers
/// and `Main.main`'s screen.
pub struct JackLeg {
    pub comparisons: Vec<Comparison>,
    pub measured: Measured,
    /// Every drawn pixel, row by row.
    pub image: SceneImage,
    /// The answers at the step's SDF query points.
    pub sdf: Vec<SdfTriples>,
    /// The seconds the pixel pass took (every drawn pixel, in parallel).
    pub pixels_s: f64,
    /// `Main.main`'s screen, or why the run gave none.
    pub screen: Result<MainScreen, String>,
}

/// The screen `Main.main` left, and the seconds it took on one thread.
pub struct MainScreen {
    /// 512x256, row by row, `true` = white.
    pub white: Vec<bool>,
    pub seconds: f64,
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

/// What the leg compares against: the scene, its ref-f316 SDF answers at
/// `points`, and the Float316 legs' renders so far (`images`).
pub struct Judges<'a> {
    pub file: &'a Path,
    pub scope: &'a str,
    pub points: &'a [[F316; 3]],
    pub ref_sdf: &'a [Outcome<SdfValue>],
    pub images: &'a [(String, SceneImage)],
}

/// Run the leg.
pub fn run(night: &mut Night<'_>, j: &Judges<'_>) -> Result<JackLeg> {
    let generated = scene_jack::emit_file(j.file)?;
    let program = open(j.file)?;
    let mut comparisons = ops(night, j.scope, program.as_ref())?;
    let sdf = sdf(program.as_ref(), j.points)?;
    let mut sdf_row = compare_sdf(j.scope, j.points, j.ref_sdf, &sdf);
    sdf_row.b = LABEL.into();
    comparisons.push(sdf_row);
    let start = Instant::now();
    let measured = cost::measure_generated(j.file, &generated, 1, false)?;
    let pixels_s = start.elapsed().as_secs_f64();
    let image = measured_image(&measured, generated.program.pixels.levels)?;
    let float316 = j
        .images
        .iter()
        .filter(|(label, _)| label == "ref-f316" || label == "gpu-f316");
    for (label, theirs) in float316.clone() {
        let (drawn, beyond) = crop(theirs, image.width, image.height);
        let mut row = bit_exact_pixels(j.scope, label, LABEL, &drawn, &image);
        if beyond > 0 {
            row.findings.push(format!(
                "{beyond} pixels beyond the {}x{} screen are not drawn by Main.main and not compared",
                WIDTH, HEIGHT
            ));
        }
        comparisons.push(row);
    }
    let start = Instant::now();
    let screen = match program.program_screen(
        Some(measured.cost.whole_image_instructions),
        night.options.progress,
    ) {
        Some(Ok(bitmap)) => Ok(MainScreen {
            white: bitmap.white,
            seconds: start.elapsed().as_secs_f64(),
        }),
        Some(Err(e)) => Err(e.to_string()),
        None => Err("the bindings have no whole-program capture".into()),
    };
    for (label, theirs) in float316 {
        comparisons.push(screen_row(
            j.scope,
            label,
            &generated.program,
            theirs,
            &screen,
        ));
    }
    if scene::is_seed(&generated.checked) {
        comparisons.push(committed_row(j.scope, &screen)?);
    }
    Ok(JackLeg {
        comparisons,
        measured,
        image,
        sdf,
        pixels_s,
        screen,
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
    let c = &m.cost;
    if c.step != 1 {
        bail!("the leg compares every pixel; step {} measured", c.step);
    }
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
            Err(exit) => {
                let what = || format!("pixel ({x},{y})");
                let out_of_domain = Some(scene_jack::OUT_OF_DOMAIN);
                Ok(
                    match jack::outcome_of((**exit).clone(), out_of_domain, what)? {
                        Outcome::Value(v) => {
                            bail!("pixel ({x},{y}) returned {v} without its answer")
                        }
                        Outcome::SysError(code) => Outcome::SysError(code),
                        Outcome::Hang => Outcome::Hang,
                        Outcome::OutOfDomain => Outcome::OutOfDomain,
                    },
                )
            }
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(SceneImage {
        width: c.width as usize,
        height: c.height as usize,
        levels,
        pixels,
    })
}

/// The top-left `width` x `height` pixels of `image` (the part the Hack
/// screen shows), and how many pixels lie beyond them.
fn crop(image: &SceneImage, width: usize, height: usize) -> (SceneImage, usize) {
    let (w, h) = (width.min(image.width), height.min(image.height));
    let pixels: Vec<_> = (0..h)
        .flat_map(|y| image.pixels[y * image.width..][..w].iter().copied())
        .collect();
    let beyond = image.pixels.len() - pixels.len();
    let cropped = SceneImage {
        width: w,
        height: h,
        levels: image.levels,
        pixels,
    };
    (cropped, beyond)
}

/// `Main.main`'s screen against the one `theirs` (labelled `label`, a
/// render of `program`'s scene) makes by the program's screen rule. Where
/// `theirs` stops at a drawn pixel, `Main.main` must stop as well (one
/// case: the run's end).
fn screen_row(
    scope: &str,
    label: &str,
    program: &scene::Program,
    theirs: &SceneImage,
    screen: &Result<MainScreen, String>,
) -> Comparison {
    let expected = scene_jack::expected_screen(program, |x, y| {
        theirs
            .pixels
            .get(y as usize * theirs.width + x as usize)
            .and_then(|p| p.value())
            .map(|p| p.level)
    });
    let mut c = comparison("screen", scope, label, &screen_label(), BIT_EXACT);
    match (expected, screen) {
        (Ok(want), Ok(got)) => compare_screens(&mut c, &want, &got.white),
        (Err((x, y)), Err(stopped)) => {
            c.cases = 1;
            c.findings.push(format!(
                "{label} stops at pixel ({x},{y}); Main.main stops too: {stopped}"
            ));
        }
        (Err((x, y)), Ok(_)) => {
            c.cases = 1;
            diverged(&mut c, || {
                example(
                    "Main.main".into(),
                    format!("stops at pixel ({x},{y})"),
                    "draws the whole image".into(),
                )
            });
        }
        (Ok(_), Err(stopped)) => main_stopped(&mut c, stopped),
    }
    c
}

/// One divergent case in `c`: `Main.main` stopped (`stopped` says how)
/// where the other side draws the whole image.
fn main_stopped(c: &mut Comparison, stopped: &str) {
    c.cases = 1;
    diverged(c, || {
        example(
            "Main.main".into(),
            "draws the whole image".into(),
            stopped.to_string(),
        )
    });
}

/// The seed scene's screen against the committed render of the original
/// program (`vectors/images/seed-float316-512x256.png`).
fn committed_row(scope: &str, screen: &Result<MainScreen, String>) -> Result<Comparison> {
    let committed = harness_report::measure::spec_image()?;
    let mut c = comparison(
        "screen",
        scope,
        "committed render",
        &screen_label(),
        BIT_EXACT,
    );
    match screen {
        Ok(got) => compare_screens(&mut c, committed.data(), &got.white),
        Err(stopped) => main_stopped(&mut c, stopped),
    }
    Ok(c)
}

/// Two 512x256 screens, pixel by pixel, into `c`.
fn compare_screens(c: &mut Comparison, want: &[bool], got: &[bool]) {
    let colour = |w: Option<&bool>| match w {
        Some(true) => "white",
        Some(false) => "black",
        None => "no pixel",
    };
    for i in 0..want.len().max(got.len()) {
        c.cases += 1;
        let (a, b) = (want.get(i), got.get(i));
        if a != b {
            diverged(c, || {
                example(
                    format!("pixel({},{})", i % WIDTH, i / WIDTH),
                    colour(a).into(),
                    colour(b).into(),
                )
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(width: usize, height: usize) -> SceneImage {
        SceneImage {
            width,
            height,
            levels: 2,
            pixels: (0..width * height)
                .map(|i| {
                    Outcome::Value(ScenePixel {
                        value: Scalar {
                            value: i as f64,
                            triple: None,
                        },
                        level: 0,
                    })
                })
                .collect(),
        }
    }

    #[test]
    fn cropping_keeps_the_top_left_pixels_and_counts_the_rest() {
        let (c, beyond) = crop(&image(5, 3), 3, 2);
        assert_eq!((c.width, c.height, beyond), (3, 2, 9));
        let values: Vec<f64> = c
            .pixels
            .iter()
            .map(|p| p.value().unwrap().value.value)
            .collect();
        assert_eq!(values, [0.0, 1.0, 2.0, 5.0, 6.0, 7.0]);
        let (same, none) = crop(&image(4, 2), 512, 256);
        assert_eq!((same.width, same.height, none), (4, 2, 0));
    }

    #[test]
    fn screens_differ_pixel_by_pixel_and_a_run_that_stops_diverges() {
        let mut c = comparison("screen", "s", "a", "b", BIT_EXACT);
        compare_screens(&mut c, &[true, false, true], &[true, true, true]);
        assert_eq!((c.cases, c.divergences), (3, 1));
        assert_eq!(
            (c.examples[0].case.as_str(), c.examples[0].a.as_str()),
            ("pixel(1,0)", "black")
        );
        let stopped: Result<MainScreen, String> = Err("Sys.error(316)".into());
        let c = committed_row("s", &stopped).unwrap();
        assert_eq!((c.cases, c.divergences), (1, 1));
    }

    #[test]
    fn a_path_with_a_quote_is_refused_not_misquoted() {
        assert_eq!(toml_literal(Path::new("/a/b.json")).unwrap(), "'/a/b.json'");
        assert!(toml_literal(Path::new("/a/it's.json")).is_err());
    }
}
