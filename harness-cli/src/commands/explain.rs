//! `harness explain IMPL --pixel X,Y | --point P | --image`: why a
//! lower-precision implementation differs from ref-f64 there (on the seed
//! scene, or with `--scene FILE` on a described one): the class
//! (threshold flip, control-flow divergence, accumulated error), the
//! decision that changed and the root-cause operations (see
//! [`harness::explain`]). The explanation is made by the reference
//! implementation IMPL agrees with (ref-f316 with IMPL's variants, or
//! ref-f32); whether IMPL agrees with it bit for bit on the input is
//! checked and said. `--image` explains every pixel whose dithered bit
//! differs (or, when none does, the largest shade differences) and prints
//! the summary. Exit 0: no difference; 1: a difference was explained;
//! 2: usage or input error.

use super::localize::{parse_pixel, parse_point};
use anyhow::{bail, Context};
use harness::cast::Cast;
use harness::explain::{self, Class, Explainer, Summary};
use std::process::ExitCode;
use vectors::{PixelVector, SdfVector, Vector};

/// Shade differences explained by `--image` when no dithered bit differs.
const LARGEST: usize = 10;

fn pixel_vector(x: usize, y: usize) -> Vector {
    Vector::Pixel(PixelVector {
        category: "explain".into(),
        x: x as u16,
        y: y as u16,
    })
}

/// Arguments of `harness explain`.
#[derive(Debug, clap::Args)]
pub struct ExplainArgs {
    /// A Float316 or f32 implementation of the cast (ref-f316,
    /// ref-f316+newton-1, jack, gpu-f316, ref-f32, gpu-f32, a declared one).
    pub implementation: String,
    /// A pixel `X,Y`.
    #[arg(long, conflicts_with_all = ["point", "image"])]
    pub pixel: Option<String>,
    /// A scene query point: `x,y,z` or `s,e,m:s,e,m:s,e,m`.
    #[arg(long, conflicts_with = "image")]
    pub point: Option<String>,
    /// Every divergent pixel of the image, summarised.
    #[arg(long)]
    pub image: bool,
    /// Print the explanation(s) as JSON.
    #[arg(long)]
    pub json: bool,
    /// A scene description (docs/scenes.md): both sides are made from it
    /// (with --pixel or --point).
    #[arg(long, conflicts_with = "image")]
    pub scene: Option<std::path::PathBuf>,
}

/// Run `harness explain`.
pub fn run(args: ExplainArgs, cast: &Cast) -> anyhow::Result<ExitCode> {
    let open = |label: &str| {
        cast.open(label)
            .with_context(|| format!("implementation `{label}`"))
    };
    let imp = open(&args.implementation)?;
    let label = explain::reference_label(imp.as_ref())?;
    let explainer = match &args.scene {
        Some(file) => Explainer::for_scene(&label, &scene::load(file)?)?,
        None => Explainer::new(&label)?,
    };
    let reference = open(&label)?;
    let holds = |inputs: &[Vector]| -> anyhow::Result<String> {
        if imp.label() == label {
            return Ok(String::new());
        }
        if args.scene.is_some() {
            // The cast's entries answer the seed scene.
            return Ok(format!(
                "whether {} agrees with {label} bit for bit on this scene is not checked here \
                 (the nightly's scenes step compares them)\n",
                imp.label()
            ));
        }
        Ok(
            match explain::holds_for(imp.as_ref(), reference.as_ref(), inputs)? {
                None => format!(
                    "holds for {}: it agrees with {label} bit for bit on {}\n",
                    imp.label(),
                    if inputs.len() == 1 {
                        "this input".to_string()
                    } else {
                        format!("all {} inputs", inputs.len())
                    }
                ),
                Some(why) => format!("{why}\n"),
            },
        )
    };
    if args.image {
        let (pixels, divergent) = explainer.image_pixels(LARGEST)?;
        let explanations = explainer.pixels(&pixels);
        let summary = Summary::of(&explanations);
        if args.json {
            println!(
                "{}",
                serde_json::to_string_pretty(&(&summary, &explanations))?
            );
        } else {
            let what = if divergent {
                "pixels whose dithered bit differs"
            } else {
                "no dithered bit differs; the pixels whose shades differ most"
            };
            println!(
                "{label} against {}: {} {what}",
                explain::ORACLE,
                pixels.len()
            );
            print!("{}", explain::summary_text(&summary));
            let inputs: Vec<Vector> = pixels.iter().map(|&(x, y)| pixel_vector(x, y)).collect();
            print!("{}", holds(&inputs)?);
        }
        return Ok(if pixels.is_empty() {
            ExitCode::SUCCESS
        } else {
            ExitCode::from(1)
        });
    }
    let (explanation, input) = if let Some(p) = &args.pixel {
        let (x, y) = parse_pixel(p)?;
        (explainer.pixel(x, y), pixel_vector(x, y))
    } else if let Some(p) = &args.point {
        let p = parse_point(p)?;
        let input = Vector::Sdf(SdfVector {
            category: "explain".into(),
            p,
        });
        (explainer.point(p), input)
    } else {
        bail!("say which input: --pixel X,Y, --point x,y,z or --image");
    };
    if args.json {
        println!("{}", serde_json::to_string_pretty(&explanation)?);
    } else {
        print!("{}", explain::story(&explanation));
        print!("{}", holds(&[input])?);
    }
    Ok(if differs(&explanation) {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}

/// Whether the input differs as the pixels policy judges it: a pixel by
/// its dithered bit (a shade difference alone is explained, and matters
/// only through the bit), an SDF point by any difference.
fn differs(e: &explain::Explanation) -> bool {
    match &e.answers {
        Some(a) if a.low_white.is_some() && e.class != Class::Unexplained => {
            a.low_white != a.oracle_white
        }
        _ => e.class != Class::Agree,
    }
}
