//! `harness render`: render the 512x256 dithered image with one
//! implementation, write it as PNG (white 255, black 0) and optionally the
//! per-pixel shade values before dithering as JSON.
//!
//! To add an implementation, add an arm to [`render_image`] that returns a
//! [`Rendered`]; writing the files is shared.

use anyhow::{bail, Context, Result};
use common::image_consts::{HEIGHT, WIDTH};
use common::Outcome;
use reference::{PixelValue, RefImpl, Reference, Scalar, Scene, Settings, Variant};
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Arguments of `harness render`.
#[derive(Debug, clap::Args)]
pub struct RenderArgs {
    /// Implementation: ref-f316, ref-f64, ref-f32, jack, gpu-f316, gpu-f32.
    #[arg(long = "impl", value_name = "IMPL")]
    pub implementation: String,
    /// A scene description (docs/scenes.md, e.g. vectors/scenes/rtdemo.json),
    /// or the seed scene's parameters (JSON); the seed scene when left out.
    #[arg(long, value_name = "FILE")]
    pub scene: Option<PathBuf>,
    /// A precision variant or injected fault (repeatable), e.g. newton-3,
    /// mul-low-product, sqrt-floor-div.
    #[arg(long = "variant", value_name = "NAME")]
    pub variants: Vec<Variant>,
    /// The PNG to write.
    #[arg(long, value_name = "FILE.png")]
    pub out: PathBuf,
    /// Also write each pixel's shade before dithering (JSON).
    #[arg(long, value_name = "FILE.json")]
    pub values: Option<PathBuf>,
}

/// What an implementation rendered: the white bits and, per pixel, the
/// outcome of its shade (value before dithering).
pub struct Rendered {
    /// `white[y * WIDTH + x]`.
    pub white: Vec<bool>,
    /// Per pixel, in the same order.
    pub values: Vec<Outcome<PixelValue>>,
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

/// Render with the implementation named `name`.
pub fn render_image(name: &str, scene: &Scene, settings: Settings) -> Result<Rendered> {
    if let Ok(imp) = name.parse::<RefImpl>() {
        let r = Reference::new(imp, scene, settings)?;
        let img = r.render();
        let white = (0..img.height)
            .flat_map(|y| (0..img.width).map(move |x| (x, y)))
            .map(|(x, y)| img.is_white(x, y))
            .collect();
        return Ok(Rendered {
            white,
            values: img.pixels,
        });
    }
    match name {
        "jack" => render_jack(scene, settings),
        "gpu-f316" | "gpu-f32" => render_gpu(name, scene, settings),
        _ => bail!(
            "unknown implementation `{name}` (expected ref-f316, ref-f64, ref-f32, jack, gpu-f316 or gpu-f32)"
        ),
    }
}

/// Implementations whose sources hold the seed scene and the spec's
/// settings only refuse anything else.
fn require_seed_scene(name: &str, scene: &Scene, settings: Settings) -> Result<()> {
    if *scene != Scene::default() || settings != Settings::default() {
        bail!("{name} renders the seed scene with the spec's settings only (no --scene, no --variant)");
    }
    Ok(())
}

/// The render's white bits: a trapped pixel is never drawn, so it is white,
/// as the reference counts it.
fn white_bits(values: &[Outcome<PixelValue>]) -> Vec<bool> {
    values
        .iter()
        .map(|v| !matches!(v, Outcome::Value(p) if !p.white))
        .collect()
}

/// `gpu-f316` / `gpu-f32`: the WGSL kernels, one invocation per pixel.
fn render_gpu(name: &str, scene: &Scene, settings: Settings) -> Result<Rendered> {
    require_seed_scene(name, scene, settings)?;
    let gpu = gpu::Gpu::new()?;
    let values: Vec<Outcome<PixelValue>> = if name == "gpu-f316" {
        gpu.render_f316()?
            .into_iter()
            .map(|o| {
                o.map(|(v, white)| PixelValue {
                    value: Scalar {
                        value: v.to_f64(),
                        triple: Some(v),
                    },
                    white,
                })
            })
            .collect()
    } else {
        gpu.render_f32()?
            .into_iter()
            .map(|(v, white)| {
                Outcome::Value(PixelValue {
                    value: Scalar {
                        value: f64::from(v),
                        triple: None,
                    },
                    white,
                })
            })
            .collect()
    };
    Ok(Rendered {
        white: white_bits(&values),
        values,
    })
}

/// `jack`: the Jack program on the emulator, every pixel through its entry
/// point `Image.pixel` from one initialised snapshot, in parallel. The Jack
/// sources hold the seed scene and the spec's settings, nothing else.
pub(crate) fn render_jack(scene: &Scene, settings: Settings) -> Result<Rendered> {
    require_seed_scene("jack", scene, settings)?;
    let jack = jack::Raymarcher::new(jack::Profile::Desktop, jack::Budgets::default())?;
    let values: Vec<Outcome<PixelValue>> = crate::impls::jack::render_with_bar(&jack)?
        .pixels
        .into_iter()
        .map(|p| {
            p.outcome.map(|s| PixelValue {
                value: Scalar {
                    value: s.value.to_f64(),
                    triple: Some(s.value),
                },
                white: s.white,
            })
        })
        .collect();
    Ok(Rendered {
        white: white_bits(&values),
        values,
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
pub fn run(args: RenderArgs) -> Result<ExitCode> {
    let settings = args
        .variants
        .iter()
        .fold(Settings::default(), |s, v| v.apply(s));
    if let Some(path) = &args.scene {
        if scene::is_description(&scene::read(path)?) {
            let described = scene::load(path)?;
            let name = &args.implementation;
            let image = super::render_scene::render(name, &described, path, settings)?;
            super::render_scene::write(name, &described, &image, &args.out, args.values.as_deref())?;
            return Ok(ExitCode::SUCCESS);
        }
    }
    let scene = match &args.scene {
        Some(path) => Scene::from_file(path)?,
        None => Scene::default(),
    };
    let rendered = render_image(&args.implementation, &scene, settings)?;
    write_png(&args.out, &rendered.white)?;
    if let Some(path) = &args.values {
        let file = ValuesFile {
            implementation: &args.implementation,
            width: WIDTH,
            height: HEIGHT,
            pixels: &rendered.values,
        };
        write_atomically(path, |tmp| {
            let f = std::fs::File::create(tmp)
                .with_context(|| format!("cannot create {}", tmp.display()))?;
            serde_json::to_writer(std::io::BufWriter::new(f), &file)
                .with_context(|| format!("cannot write {}", tmp.display()))
        })?;
    }
    Ok(ExitCode::SUCCESS)
}
