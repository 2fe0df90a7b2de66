//! `harness render`: render the 512x256 dithered image with one
//! implementation of the cast (the one whole-image render,
//! [`crate::measure`]), write it as PNG (white 255, black 0) and optionally
//! the per-pixel shade values before dithering as JSON.

use crate::cast::Cast;
use crate::implementation::{Answer, Num};
use anyhow::{Context, Result};
use common::image_consts::{HEIGHT, WIDTH};
use common::Outcome;
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

/// Write `bytes` to `path` through a temporary file in the same directory
/// and a rename, so a reader never sees a partial file.
pub fn write_atomically(path: &Path, write: impl FnOnce(&Path) -> Result<()>) -> Result<()> {
    let dir = path
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = path
        .file_name()
        .with_context(|| format!("{} is not a file path", path.display()))?;
    let tmp = dir.join(format!(
        ".{}.tmp{}",
        name.to_string_lossy(),
        std::process::id()
    ));
    let result = write(&tmp).and_then(|()| {
        std::fs::rename(&tmp, path)
            .with_context(|| format!("cannot move the new file into {}", path.display()))
    });
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// Write `value` to `path` as JSON, atomically.
pub fn write_json_atomically(path: &Path, value: &impl serde::Serialize) -> Result<()> {
    write_atomically(path, |tmp| {
        let f = std::fs::File::create(tmp)
            .with_context(|| format!("cannot create {}", tmp.display()))?;
        serde_json::to_writer(std::io::BufWriter::new(f), value)
            .with_context(|| format!("cannot write {}", tmp.display()))
    })
}

/// Write the bits as an 8-bit grayscale PNG (white 255, black 0).
pub fn write_png(path: &Path, white: &[bool]) -> Result<()> {
    let samples = white.iter().map(|&w| if w { 255 } else { 0 }).collect();
    let img = image::GrayImage::from_raw(WIDTH as u32, HEIGHT as u32, samples)
        .context("the image does not have 512x256 pixels")?;
    write_atomically(path, |tmp| {
        img.save_with_format(tmp, image::ImageFormat::Png)
            .with_context(|| format!("cannot write {}", tmp.display()))
    })
}

/// Render an image.
pub fn run(args: RenderArgs, cast: &Cast) -> Result<ExitCode> {
    if let Some(path) = &args.scene {
        if scene::is_description(&scene::read(path)?) {
            let described = scene::load(path)?;
            let seed_on_jack = args.implementation == "jack" && scene::is_seed(&described);
            if !seed_on_jack {
                return super::render_scene::run(&args, &described, path);
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
    let imp = cast
        .open_for_scene(&label, scene.as_ref())
        .with_context(|| format!("implementation `{label}`"))?;
    let (full, answers) =
        crate::measure::render_with(imp.as_ref(), 0.0, crate::progress::wanted())?;
    write_png(&args.out, full.images.bits.data())?;
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
        write_json_atomically(path, &file)?;
    }
    Ok(ExitCode::SUCCESS)
}
