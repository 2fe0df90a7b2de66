//! `harness vectors regenerate [--only NAME] [--dir DIR]`: rebuild the
//! committed vector sets deterministically (same seed, same vectors);
//! `harness vectors check FILE`: validate a set file; `harness vectors gen
//! --level 1|2 [--op OP] --out FILE`: TestFloat-style Float316 cases;
//! `harness vectors gen --scene FILE [--pixels] --out FILE`: a scene's own
//! SDF points or pixels (`vectors::gen::scene_derived`).
//!
//! Pixel sets take their silhouette and shadow-edge pixels from ref-f316's
//! shades, and their dither-tie pixels (dithered value exactly 0.5) from
//! ref-f316's image.

use anyhow::{bail, Context};
use common::image_consts::bayer;
use common::{Op, OpValue, Outcome, F316};
use harness::cast::Cast;
use harness::implementation::{Answer, Num};
use rayon::prelude::*;
use std::path::PathBuf;
use std::process::ExitCode;
use vectors::gen::pixels::PixelFacts;
use vectors::gen::scene_derived;
use vectors::gen::testfloat::{self, CaseLevel};
use vectors::named::SETS;
use vectors::{Level, PixelVector, Shard, Vector, VectorSet};

/// `harness vectors` subcommands.
#[derive(Debug, clap::Subcommand)]
pub enum VectorsCommand {
    /// Rebuild the committed sets in vectors/sets (or --dir).
    Regenerate {
        /// Only this set.
        #[arg(long)]
        only: Option<String>,
        /// Write here instead of vectors/sets.
        #[arg(long)]
        dir: Option<PathBuf>,
    },
    /// Write TestFloat-style Float316 cases as a set (docs/coverage.md),
    /// or with --scene the vectors derived from a scene (docs/scenes.md).
    Gen {
        /// TestFloat level: 1 (quick) or 2 (thorough).
        #[arg(long, required_unless_present = "scene")]
        level: Option<CaseLevel>,
        /// A scene description: write its SDF points near every surface,
        /// seam, blend region and repetition cell boundary.
        #[arg(long, conflicts_with_all = ["level", "op", "shard"])]
        scene: Option<PathBuf>,
        /// With --scene: its pixels on silhouettes, the horizon, and
        /// reflection, shadow and surface edges instead.
        #[arg(long, requires = "scene")]
        pixels: bool,
        /// Only this operation (default: every operation).
        #[arg(long)]
        op: Option<Op>,
        /// The seed of level 2's random pairs.
        #[arg(long, default_value_t = testfloat::DEFAULT_SEED)]
        seed: u64,
        /// Keep only shard K/N of the cases (K counts from 0).
        #[arg(long)]
        shard: Option<Shard>,
        /// The set file to write.
        #[arg(long)]
        out: PathBuf,
    },
    /// Validate a set file and print its summary.
    Check {
        /// The file.
        file: PathBuf,
    },
}

/// Whether ref-f316's dithered value of a pixel with clamped shade `shade`
/// is exactly 0.5, the threshold (spec section 6: `add(value, (B-32)/64)`).
fn dithers_to_half(shade: F316, x: usize, y: usize) -> bool {
    let t = F316::from_f64_truncating((f64::from(bayer(x, y)) - 32.0) / 64.0)
        .expect("Bayer offsets encode");
    let half = F316::new(0, 126, 8192);
    let sum = reference::op(Op::Add, &[shade, t], reference::Arith::default());
    matches!(sum, Ok(Outcome::Value(OpValue::Num(v))) if v == half)
}

/// Facts about every pixel of ref-f316's image, for the pixel generators.
pub fn pixel_facts() -> anyhow::Result<PixelFacts> {
    // The generators are defined on ref-f316's image.
    let reference = Cast::builtin().open("ref-f316")?;
    let all: Vec<Vector> = (0..common::image_consts::HEIGHT as u16)
        .flat_map(|y| (0..common::image_consts::WIDTH as u16).map(move |x| (x, y)))
        .map(|(x, y)| {
            Vector::Pixel(PixelVector {
                category: String::new(),
                x,
                y,
            })
        })
        .collect();
    let answers: Vec<Outcome<Answer>> = all
        .par_chunks(512)
        .map(|row| reference.eval(row))
        .collect::<Result<Vec<_>, _>>()?
        .concat();
    let mut shades = Vec::with_capacity(all.len());
    let mut ties = Vec::new();
    for (v, a) in all.iter().zip(&answers) {
        let Vector::Pixel(p) = v else { unreachable!() };
        let shade = match a {
            Outcome::Value(Answer::Pixel {
                shade: Num::F316(t),
                ..
            }) => *t,
            other => bail!("ref-f316 gave no shade at ({},{}): {other:?}", p.x, p.y),
        };
        if dithers_to_half(shade, usize::from(p.x), usize::from(p.y)) {
            ties.push((p.x, p.y));
        }
        shades.push(shade.to_f64());
    }
    let background = F316::from_f64_truncating(0.835)
        .expect("0.835 encodes")
        .to_f64();
    Ok(PixelFacts {
        shades,
        background,
        dither_ties: ties,
    })
}

/// Run `harness vectors`.
pub fn run(cmd: VectorsCommand) -> anyhow::Result<ExitCode> {
    match cmd {
        VectorsCommand::Regenerate { only, dir } => {
            let dir = dir.unwrap_or_else(vectors::sets_dir);
            let specs: Vec<_> = SETS
                .iter()
                .filter(|s| only.as_deref().is_none_or(|n| n == s.name))
                .collect();
            if specs.is_empty() {
                bail!("no set named `{}`", only.unwrap_or_default());
            }
            let facts = if specs.iter().any(|s| s.level == Level::Pixels) {
                Some(pixel_facts()?)
            } else {
                None
            };
            std::fs::create_dir_all(&dir).with_context(|| format!("creating {}", dir.display()))?;
            for spec in specs {
                let set = spec.build(facts.as_ref());
                let path = dir.join(format!("{}.json", spec.name));
                set.save(&path)?;
                println!("{}: {} vectors", path.display(), set.vectors.len());
            }
            Ok(ExitCode::SUCCESS)
        }
        VectorsCommand::Gen {
            level,
            scene,
            pixels,
            op,
            seed,
            shard,
            out,
        } => {
            let set = match (scene, level) {
                (Some(file), _) => {
                    let checked = scene::load(&file)?;
                    if pixels {
                        scene_derived::pixel_set(&checked)?
                    } else {
                        scene_derived::sdf_set(&checked, seed)?
                    }
                }
                (None, Some(level)) => {
                    let ops = op.map_or_else(|| Op::ALL.to_vec(), |op| vec![op]);
                    let set = testfloat::set(&ops, level, seed);
                    shard.unwrap_or(Shard::WHOLE).of_set(&set)
                }
                (None, None) => bail!("say --level 1|2 or --scene FILE"),
            };
            set.save(&out)?;
            println!("{}: {} vectors", out.display(), set.vectors.len());
            Ok(ExitCode::SUCCESS)
        }
        VectorsCommand::Check { file } => {
            let set = VectorSet::load(&file)?;
            println!(
                "{}: set {} (level {}, format {}), {} vectors",
                file.display(),
                set.name,
                set.level,
                set.format_version,
                set.vectors.len()
            );
            Ok(ExitCode::SUCCESS)
        }
    }
}
