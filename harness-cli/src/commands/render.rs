//! `harness render`: render the 512x256 dithered image with one
//! implementation of the cast (the one whole-image render,
//! [`harness_report::measure`]), write it as PNG (white 255, black 0, a trapped
//! pixel in the trap colour) and optionally the per-pixel shade values
//! before dithering as JSON. Exit 0 when every pixel answered a value, 1
//! when some trapped (`Sys.error`, hang, out of domain: counted by kind),
//! 3 when the implementation failed or could not open.

use anyhow::{Context, Result};
use common::image_consts::{HEIGHT, WIDTH};
use common::Outcome;
use harness::cast::Cast;
use harness::implementation::{Answer, Num};
use harness::verdict::{self, Status};
use harness_report::atomic;
use harness_report::images::dithered;
use reference::{PixelValue, Scalar, Scene};
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Arguments of `harness render`.
#[derive(Debug, clap::Args)]
pub struct RenderArgs {
    /// Implementation label (`harness cast` lists them), e.g. ref-f316,
    /// jack, gpu-f316, ref-f316+newton-3.
    #[arg(long = "impl", value_name = "IMPL")]
    pub implementation: String,
    /// A scene description (docs/scenes.md, e.g. vectors/scenes/rtdemo.json),
    /// or the seed scene's parameters (JSON); the seed scene when left out.
    #[arg(long, value_name = "FILE")]
    pub scene: Option<PathBuf>,
    /// A precision variant or injected fault (repeatable), e.g. newton-3,
    /// mul-low-product, sqrt-floor-div: the same as `--impl IMPL+NAME`.
    #[arg(long = "variant", value_name = "NAME")]
    pub variants: Vec<String>,
    /// The PNG to write.
    #[arg(long, value_name = "FILE.png")]
    pub out: PathBuf,
    /// Also write each pixel's shade before dithering (JSON).
    #[arg(long, value_name = "FILE.json")]
    pub values: Option<PathBuf>,
}

/// The `--values` file.
#[derive(Serialize)]
struct ValuesFile<'a> {
    implementation: &'a str,
    width: usize,
    height: usize,
    /// Row by row.
    pixels: &'a [Outcome<PixelValue>],
}

/// A pixel answer as the `--values` file holds it.
fn pixel_value(answer: &Outcome<Answer>) -> Result<Outcome<PixelValue>> {
    Ok(match answer {
        Outcome::Value(Answer::Pixel { shade, white }) => Outcome::Value(PixelValue {
            value: Scalar {
                value: shade.to_f64(),
                triple: match shade {
                    Num::F316(t) => Some(*t),
                    _ => None,
                },
            },
            white: *white,
        }),
        Outcome::Value(other) => anyhow::bail!("a pixel answered `{other}`"),
        Outcome::SysError(code) => Outcome::SysError(*code),
        Outcome::Hang => Outcome::Hang,
        Outcome::OutOfDomain => Outcome::OutOfDomain,
    })
}

/// Write the bits as an 8-bit grayscale PNG (white 255, black 0).
pub fn write_png(path: &Path, white: &[bool]) -> Result<()> {
    let samples = white.iter().map(|&w| if w { 255 } else { 0 }).collect();
    let img = image::GrayImage::from_raw(WIDTH as u32, HEIGHT as u32, samples)
        .context("the image does not have 512x256 pixels")?;
    atomic::write_png(path, &image::DynamicImage::ImageLuma8(img))
}

/// How many pixels trapped, by kind, as one phrase (`None` when none did).
fn traps_text(answers: &[Outcome<Answer>]) -> Option<String> {
    let count = |f: fn(&Outcome<Answer>) -> bool| answers.iter().filter(|a| f(a)).count();
    let kinds = [
        ("Sys.error", count(|a| matches!(a, Outcome::SysError(_)))),
        ("hang", count(|a| matches!(a, Outcome::Hang))),
        (
            "out of domain",
            count(|a| matches!(a, Outcome::OutOfDomain)),
        ),
    ];
    let total: usize = kinds.iter().map(|(_, n)| n).sum();
    let parts: Vec<String> = kinds
        .iter()
        .filter(|(_, n)| *n > 0)
        .map(|(k, n)| format!("{n} {k}"))
        .collect();
    (total > 0).then(|| {
        format!(
            "{total} of {} pixels trapped ({})",
            answers.len(),
            parts.join(", ")
        )
    })
}

/// Render an image.
pub fn run(args: RenderArgs, cast: &Cast) -> Result<ExitCode> {
    if let Some(path) = &args.scene {
        if scene::is_description(&scene::read(path)?) {
            let described = scene::load(path)?;
            let seed_on_jack = args.implementation == "jack" && scene::is_seed(&described);
            if !seed_on_jack {
                let asked = super::render_scene::SceneRender {
                    implementation: &args.implementation,
                    variants: &args.variants,
                    out: &args.out,
                    values: args.values.as_deref(),
                };
                return super::render_scene::run(&asked, &described, path);
            }
            // The hand-written Jack program is the seed scene.
            let args = RenderArgs {
                scene: None,
                ..args
            };
            return run(args, cast);
        }
    }
    let scene = match &args.scene {
        Some(path) => Some(Scene::from_file(path)?),
        None => None,
    };
    let label = std::iter::once(args.implementation.as_str())
        .chain(args.variants.iter().map(String::as_str))
        .collect::<Vec<_>>()
        .join("+");
    let rendered = cast
        .open_for_scene(&label, scene.as_ref())
        .with_context(|| format!("implementation `{label}`"))
        .and_then(|imp| {
            harness_report::measure::render_with(imp.as_ref(), 0.0, harness::progress::wanted())
        });
    let (full, answers) = match rendered {
        Ok(r) => r,
        Err(e) if verdict::implementation_failure(&e).is_some() => {
            eprintln!("error: {}", verdict::one_line(&format!("{e:#}")));
            println!("render: {label} gave no image; nothing written");
            return Ok(Status::Incomplete.exit_code());
        }
        Err(e) => return Err(e),
    };
    let images = &full.images;
    match &images.traps {
        None => write_png(&args.out, images.bits.data())?,
        Some(traps) => atomic::write_png(
            &args.out,
            &image::DynamicImage::ImageRgb8(dithered(&images.bits, Some(traps))),
        )?,
    }
    if args.values.is_some() && images.shades.is_none() {
        // Its image is the whole program's screen: bits, no shades.
        println!(
            "render: {label} gives no shades (it does not answer the pixels level; its image \
             comes from its whole program): --values not written"
        );
        return Ok(Status::Incomplete.exit_code());
    }
    if let Some(path) = &args.values {
        let pixels = answers
            .iter()
            .map(pixel_value)
            .collect::<Result<Vec<_>>>()
            .with_context(|| label.clone())?;
        let file = ValuesFile {
            implementation: &label,
            width: WIDTH,
            height: HEIGHT,
            pixels: &pixels,
        };
        atomic::write_json(path, &file)?;
    }
    Ok(match traps_text(&answers) {
        Some(text) => {
            println!("render: {label}: {text}, drawn in the trap colour");
            Status::Diverged.exit_code()
        }
        None => ExitCode::SUCCESS,
    })
}
