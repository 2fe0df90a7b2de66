//! `harness render --scene FILE` for a scene description (docs/scenes.md):
//! the reference implementations and the GPU kernels are made from the
//! description; the hand-written Jack program answers the seed scene only.

use anyhow::{bail, Context, Result};
use common::Outcome;
use harness_report::atomic;
use reference::{Described, RefImpl, Scalar, SceneImage, ScenePixel, Settings};
use scene::Program;
use serde::Serialize;
use std::path::Path;
use std::process::ExitCode;

/// What `harness render --scene` asks of a description.
pub struct SceneRender<'a> {
    /// The label: a name, with `+VARIANT`s.
    pub implementation: &'a str,
    /// The variants of `--variant`.
    pub variants: &'a [String],
    /// The PNG file to write.
    pub out: &'a Path,
    /// The `--values` file, when asked.
    pub values: Option<&'a Path>,
}

/// Render the description `scene` (read from `file`) as `args` ask.
pub fn run(args: &SceneRender<'_>, scene: &scene::Checked, file: &Path) -> Result<ExitCode> {
    let mut settings = Settings::default();
    for v in args.variants {
        let variant: reference::Variant = v.parse()?;
        settings = variant.apply(settings);
    }
    let (name, variants) = match args.implementation.split_once('+') {
        Some((n, v)) => (n, Some(v)),
        None => (args.implementation, None),
    };
    for v in variants.into_iter().flat_map(|v| v.split('+')) {
        let variant: reference::Variant = v.parse()?;
        settings = variant.apply(settings);
    }
    let image = render(name, scene, file, settings)?;
    write(args.implementation, scene, &image, args.out, args.values)?;
    Ok(ExitCode::SUCCESS)
}

/// The `--values` file of a described scene.
#[derive(Serialize)]
struct ValuesFile<'a> {
    implementation: &'a str,
    scene: &'a str,
    width: usize,
    height: usize,
    levels: u8,
    /// Row by row.
    pixels: &'a [Outcome<ScenePixel>],
}

/// Render `scene` (read from `file`) with the implementation `name`.
pub fn render(
    name: &str,
    scene: &scene::Checked,
    file: &Path,
    settings: Settings,
) -> Result<SceneImage> {
    if let Ok(imp) = name.parse::<RefImpl>() {
        return Ok(Described::new(imp, scene, settings)?.render());
    }
    match name {
        "gpu-f316" | "gpu-f32" => {
            if settings != Settings::default() {
                bail!("{name} has no variants (no --variant)");
            }
            let form = if name == "gpu-f316" {
                RefImpl::F316
            } else {
                RefImpl::F32
            };
            let gpu = gpu::Gpu::new()?;
            let (kernel, program) = compile_gpu(&gpu, form, scene)?;
            kernel_image(&gpu, &kernel, &program)
        }
        "jack" => bail!("{}", jack_refusal(scene, file)),
        _ => bail!(
            "unknown implementation `{name}` (expected ref-f316, ref-f64, ref-f32, jack, gpu-f316 or gpu-f32)"
        ),
    }
}

/// What the hand-written Jack program says to a described scene: it
/// renders the seed scene only.
pub fn jack_refusal(scene: &scene::Checked, file: &Path) -> String {
    format!(
        "jack: the hand-written Jack program renders the seed scene only, and {} (`{}`) is another scene; generate one from the description with `harness jack emit --scene {} --out DIR`, or declare it in harness.toml with `kind = \"jack\"` and `scene = \"{}\"`",
        file.display(),
        scene.description.name,
        file.display(),
        file.display()
    )
}

/// Generate and compile the kernels of `scene` for `form` (`F316`:
/// gpu-f316, an IEEE one: gpu-f32) on `gpu`, with the program they came from.
pub fn compile_gpu(
    gpu: &gpu::Gpu,
    form: RefImpl,
    scene: &scene::Checked,
) -> Result<(gpu::SceneKernel, Program)> {
    let program = Described::new(form, scene, Settings::default())?
        .program()
        .clone();
    Ok((gpu.scene_kernel(&program)?, program))
}

/// The whole image of `program` through its compiled `kernel`.
pub fn kernel_image(
    gpu: &gpu::Gpu,
    kernel: &gpu::SceneKernel,
    program: &Program,
) -> Result<SceneImage> {
    let pixels = kernel
        .render(gpu)?
        .into_iter()
        .map(|o| {
            o.map(|p| ScenePixel {
                value: Scalar {
                    value: p.value.value,
                    triple: p.value.triple,
                },
                level: p.level,
            })
        })
        .collect();
    Ok(SceneImage {
        width: program.pixels.width as usize,
        height: program.pixels.height as usize,
        levels: program.pixels.levels,
        pixels,
    })
}

/// Write the image as an 8-bit grey PNG, and its values when asked.
pub fn write(
    name: &str,
    scene: &scene::Checked,
    image: &SceneImage,
    out: &Path,
    values: Option<&Path>,
) -> Result<()> {
    let img = image::GrayImage::from_raw(image.width as u32, image.height as u32, image.gray8())
        .context("the image has the wrong number of pixels")?;
    atomic::write_png(out, &image::DynamicImage::ImageLuma8(img))?;
    if let Some(path) = values {
        let file = ValuesFile {
            implementation: name,
            scene: &scene.description.name,
            width: image.width,
            height: image.height,
            levels: image.levels,
            pixels: &image.pixels,
        };
        atomic::write_json(path, &file)?;
    }
    Ok(())
}
