//! `harness jack cost --scene FILE [--step N] [--json] [--map PNG]
//! [--compare-profiles]`: what the Jack program generated from a scene
//! costs before anyone ports it by hand. VM instructions per pixel (mean
//! and max over every N-th pixel of every N-th row, pixels in parallel),
//! the whole image's time on the official desktop VM emulator and on ours,
//! the program's size in VM commands against the Hack ROM, and a cost map.
//! `--compare-profiles` runs the same pixels under the web IDE's profile
//! too and names those whose answer changes. The nightly's scenes step
//! measures every pixel through [`measure_generated`].

use anyhow::Context;
use hack_vm::Profile;
use harness_report::html::duration;
use rayon::prelude::*;
use scene_jack::cost::{self, Runner};
use scene_jack::JackSources;
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

/// Arguments of `harness jack cost`.
#[derive(Debug, clap::Args)]
pub struct CostArgs {
    /// The scene description (docs/scenes.md).
    #[arg(long)]
    pub scene: PathBuf,
    /// Measure every N-th pixel of every N-th row (1: every pixel).
    #[arg(long, default_value_t = DEFAULT_STEP, value_parser = clap::value_parser!(u32).range(1..=256))]
    pub step: u32,
    /// Print the figures as JSON.
    #[arg(long)]
    pub json: bool,
    /// Write the cost map: each measured pixel's VM instructions as grey
    /// (white: the most expensive), over the drawn image.
    #[arg(long, value_name = "PNG")]
    pub map: Option<PathBuf>,
    /// Run the measured pixels under the web IDE's profile as well (its
    /// flooring `Math.divide`) and say which answers differ.
    #[arg(long)]
    pub compare_profiles: bool,
}

/// The default `--step`: a quarter of the pixels, under a minute in a
/// release build for the costliest shipped scene on two cores.
pub const DEFAULT_STEP: u32 = 2;

/// The official desktop VM emulator's speed in its script mode, VM
/// instructions per second (measured by the author).
pub const DESKTOP_RATE: f64 = 1.4e6;

/// The hand-written seed program's `Main.main`, VM instructions (desktop
/// profile, docs/performance.md), and its time on the official desktop
/// emulator, 9 h 45 min: the scale of the estimates.
pub const SEED_MAIN_INSTRUCTIONS: u64 = 21_788_679_506;
pub const SEED_DESKTOP_S: f64 = 9.0 * 3600.0 + 45.0 * 60.0;

/// What a scene's generated program costs.
#[derive(Clone, Debug, Serialize)]
pub struct SceneCost {
    /// The description's file.
    pub scene: String,
    /// Its `name`.
    pub name: String,
    /// The drawn image (pixels the program computes).
    pub width: u32,
    pub height: u32,
    /// Every `step`-th pixel of every `step`-th row was measured.
    pub step: u32,
    pub pixels_measured: usize,
    /// VM instructions of `Main.init` (constants, set-up; once).
    pub init_instructions: u64,
    /// VM instructions per pixel through `Image.pixel`: mean and max.
    pub mean: f64,
    pub max: u64,
    /// The pixel that took `max`.
    pub worst: (u32, u32),
    /// Pixels whose computation stopped (`Sys.error`, out of domain).
    pub trapped: usize,
    /// `init_instructions + mean x width x height`.
    pub whole_image_instructions: u64,
    /// The whole image on the official desktop emulator at
    /// [`DESKTOP_RATE`], seconds.
    pub desktop_s: f64,
    /// The same by the hand-written seed program's 9 h 45 min there.
    pub desktop_seed_scale_s: f64,
    /// Our emulator's rate over the measured pixels on `threads` threads,
    /// VM instructions per second, and the whole image at that rate.
    pub ours_rate: f64,
    pub ours_s: f64,
    pub threads: usize,
    /// Static words the classes declare (of 240).
    pub static_words: usize,
    /// The program's size (VM commands, Hack ROM estimates; see
    /// `scene_jack::cost`) and whether it fits the ROM of [`cost::ROM_WORDS`].
    pub vm_commands: usize,
    pub rom_textbook: usize,
    pub rom_shared: usize,
    pub rom_words: usize,
    pub fits_textbook: bool,
    pub fits_shared: bool,
    /// The pixels whose answer differs under the web profile, when asked:
    /// `Some(empty)` when none does.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub profile_differences: Option<Vec<ProfileDifference>>,
}

/// A pixel answered differently by the two profiles.
#[derive(Clone, Debug, Serialize)]
pub struct ProfileDifference {
    pub x: u32,
    pub y: u32,
    pub desktop: String,
    pub web: String,
}

/// A measurement: the figures, and the measured pixels in row order over
/// the measured grid (`ceil(width / step)` a row) with each one's answer
/// and count.
pub struct Measured {
    pub cost: SceneCost,
    pub pixels: Vec<(u32, u32)>,
    pub answers: Vec<cost::Counted<cost::Pixel>>,
}

/// The measured pixels of a `width` x `height` image, row by row.
fn sample(width: u32, height: u32, step: u32) -> Vec<(u32, u32)> {
    (0..height)
        .step_by(step as usize)
        .flat_map(|y| (0..width).step_by(step as usize).map(move |x| (x, y)))
        .collect()
}

/// Generate the program of the description `file` and measure it.
pub fn measure(file: &Path, step: u32, compare_profiles: bool) -> anyhow::Result<Measured> {
    measure_generated(file, &scene_jack::emit_file(file)?, step, compare_profiles)
}

/// Measure `generated`, the program of the description `file`.
pub fn measure_generated(
    file: &Path,
    generated: &scene_jack::Generated,
    step: u32,
    compare_profiles: bool,
) -> anyhow::Result<Measured> {
    let (program, sources) = (&generated.program, &generated.sources);
    let size = cost::size(&cost::compile(sources, Profile::Desktop)?);
    let runner = Runner::new(sources, Profile::Desktop)?;
    let (width, height) = scene_jack::drawn(program);
    let pixels = sample(width, height, step);
    let start = Instant::now();
    let answers: Vec<cost::Counted<cost::Pixel>> = pixels
        .par_iter()
        .map(|&(x, y)| runner.pixel(x, y))
        .collect();
    let wall = start.elapsed().as_secs_f64();
    let total: u64 = answers.iter().map(|a| a.instructions).sum();
    let (worst, max) = pixels
        .iter()
        .zip(&answers)
        .max_by_key(|(_, a)| a.instructions)
        .map_or(((0, 0), 0), |(&p, a)| (p, a.instructions));
    let mean = total as f64 / pixels.len().max(1) as f64;
    let whole =
        runner.init_instructions + (mean * f64::from(width) * f64::from(height)).round() as u64;
    let ours_rate = total as f64 / wall.max(1e-9);
    let profile_differences = if compare_profiles {
        Some(web_differences(sources, &pixels, &answers)?)
    } else {
        None
    };
    Ok(Measured {
        cost: SceneCost {
            scene: file.display().to_string(),
            name: generated.checked.description.name.clone(),
            width,
            height,
            step,
            pixels_measured: pixels.len(),
            init_instructions: runner.init_instructions,
            mean,
            max,
            worst,
            trapped: answers.iter().filter(|a| a.answer.is_err()).count(),
            whole_image_instructions: whole,
            desktop_s: whole as f64 / DESKTOP_RATE,
            desktop_seed_scale_s: whole as f64 / SEED_MAIN_INSTRUCTIONS as f64 * SEED_DESKTOP_S,
            ours_rate,
            ours_s: whole as f64 / ours_rate.max(1.0),
            threads: rayon::current_num_threads(),
            static_words: sources.statics,
            vm_commands: size.vm_commands,
            rom_textbook: size.rom_textbook,
            rom_shared: size.rom_shared,
            rom_words: cost::ROM_WORDS,
            fits_textbook: size.rom_textbook <= cost::ROM_WORDS,
            fits_shared: size.rom_shared <= cost::ROM_WORDS,
            profile_differences,
        },
        pixels,
        answers,
    })
}

/// A pixel's answer as text: its level and shade, or how it stopped.
fn answer_text(a: &cost::Answer<cost::Pixel>) -> String {
    match a {
        Ok(p) => format!("level {} shade {:?}", p.level, p.shade),
        Err(exit) => exit.to_string(),
    }
}

/// The pixels whose answer under the web profile (compiled by its rules,
/// its OS, its flooring `Math.divide`) differs from `desktop`'s.
fn web_differences(
    sources: &JackSources,
    pixels: &[(u32, u32)],
    desktop: &[cost::Counted<cost::Pixel>],
) -> anyhow::Result<Vec<ProfileDifference>> {
    let web = Runner::new(sources, Profile::Web).context("under the web profile")?;
    Ok(pixels
        .par_iter()
        .zip(desktop)
        .filter_map(|(&(x, y), d)| {
            let w = web.pixel(x, y);
            // Counts differ by the profiles' clocks (docs/timing.md); only
            // the answers are compared. A stop is compared by its text.
            let (d, w) = (answer_text(&d.answer), answer_text(&w.answer));
            (d != w).then_some(ProfileDifference {
                x,
                y,
                desktop: d,
                web: w,
            })
        })
        .collect())
}

/// The cost map: each measured pixel's count as grey over the drawn image
/// (a measured pixel stands for its `step` x `step` block), black 0 and
/// white the largest count.
pub fn cost_map(m: &Measured) -> image::GrayImage {
    let c = &m.cost;
    let row = c.width.div_ceil(c.step) as usize;
    let max = c.max.max(1) as f64;
    image::GrayImage::from_fn(c.width, c.height, |x, y| {
        let i = (y / c.step) as usize * row + (x / c.step) as usize;
        let n = m.answers.get(i).map_or(0, |a| a.instructions);
        image::Luma([(n as f64 / max * 255.0).round() as u8])
    })
}

/// Which pixels a step measures: `every pixel`, `every 2nd pixel of
/// every 2nd row`.
pub(crate) fn every_nth(step: u32) -> String {
    let suffix = match (step % 10, step % 100) {
        (_, 11..=13) => "th",
        (1, _) => "st",
        (2, _) => "nd",
        (3, _) => "rd",
        _ => "th",
    };
    match step {
        1 => "every pixel".into(),
        n => format!("every {n}{suffix} pixel of every {n}{suffix} row"),
    }
}

/// The figures as text, one per line.
fn text(c: &SceneCost) -> String {
    let fits = |yes: bool| if yes { "fits" } else { "does not fit" };
    let mut out = format!(
        "scene {} ({}), {}x{} drawn, {} measured: {} pixels\n\
         VM instructions per pixel: mean {:.0}, max {} at ({},{}); Main.init {}\n\
         whole image: {} VM instructions\n\
         official desktop VM emulator at {:.1} M instructions/s: {} (by the hand-written seed program's 9 h 45 min there: {})\n\
         ours: {} at {:.0} M instructions/s ({} threads, this machine)\n\
         size: {} VM commands; Hack ROM about {} words in line ({} the {}), {} with shared call/return/compare routines ({})\n",
        c.name,
        c.scene,
        c.width,
        c.height,
        every_nth(c.step),
        c.pixels_measured,
        c.mean,
        c.max,
        c.worst.0,
        c.worst.1,
        c.init_instructions,
        c.whole_image_instructions,
        DESKTOP_RATE / 1e6,
        duration(c.desktop_s),
        duration(c.desktop_seed_scale_s),
        duration(c.ours_s),
        c.ours_rate / 1e6,
        c.threads,
        c.vm_commands,
        c.rom_textbook,
        fits(c.fits_textbook),
        c.rom_words,
        c.rom_shared,
        fits(c.fits_shared),
    );
    if c.trapped > 0 {
        out.push_str(&format!(
            "{} measured pixels stopped (Sys.error or out of domain)\n",
            c.trapped
        ));
    }
    match &c.profile_differences {
        None => {}
        Some(d) if d.is_empty() => out.push_str(&format!(
            "profiles: none of the {} measured pixels differs under the web profile (flooring Math.divide)\n",
            c.pixels_measured
        )),
        Some(d) => {
            out.push_str(&format!(
                "profiles: {} of the {} measured pixels differ under the web profile (flooring Math.divide):\n",
                d.len(),
                c.pixels_measured
            ));
            for p in d.iter().take(20) {
                out.push_str(&format!(
                    "  ({},{}): desktop {}, web {}\n",
                    p.x, p.y, p.desktop, p.web
                ));
            }
        }
    }
    out
}

/// Run `harness jack cost`. Exit 0; with `--compare-profiles`, 1 when a
/// pixel differs between the profiles.
pub fn run(args: CostArgs) -> anyhow::Result<ExitCode> {
    if let Some(map) = &args.map {
        crate::output::check_png(map, "--map")?;
    }
    let m = measure(&args.scene, args.step, args.compare_profiles)?;
    if let Some(path) = &args.map {
        harness_report::atomic::write_png(path, &image::DynamicImage::ImageLuma8(cost_map(&m)))?;
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&m.cost)?);
    } else {
        print!("{}", text(&m.cost));
    }
    let differ = m
        .cost
        .profile_differences
        .as_ref()
        .is_some_and(|d| !d.is_empty());
    Ok(if differ {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_read_as_ordinals() {
        assert_eq!(every_nth(1), "every pixel");
        assert_eq!(every_nth(2), "every 2nd pixel of every 2nd row");
        assert_eq!(every_nth(12), "every 12th pixel of every 12th row");
        assert_eq!(every_nth(23), "every 23rd pixel of every 23rd row");
    }

    /// A division whose quotient the web IDE floors, planted in the seed
    /// program's `Image.pixel` (-1 / 2 is 0 on the desktop, -1 on the web,
    /// times x & 1): the odd pixels are named, the even ones are not.
    #[test]
    fn a_division_the_web_floors_is_named_at_its_pixels() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../vectors/scenes/seed.json");
        let mut g = scene_jack::emit_file(&path).unwrap();
        let image = g
            .sources
            .classes
            .iter_mut()
            .find(|c| c.name == "Image.jack")
            .unwrap();
        let clean = "return Image.levelOf(level);";
        assert!(image.text.contains(clean));
        image.text = image.text.replace(
            clean,
            "return Image.levelOf(level) + (((0 - 1) / 2) * (x & 1));",
        );
        let pixels = [(0, 0), (1, 0), (2, 100), (3, 100)];
        let runner = Runner::new(&g.sources, Profile::Desktop).unwrap();
        let desktop: Vec<_> = pixels.iter().map(|&(x, y)| runner.pixel(x, y)).collect();
        let found = web_differences(&g.sources, &pixels, &desktop).unwrap();
        let at: Vec<(u32, u32)> = found.iter().map(|d| (d.x, d.y)).collect();
        assert_eq!(at, [(1, 0), (3, 100)]);
        assert_ne!(found[0].desktop, found[0].web);
    }

    #[test]
    fn the_sample_takes_every_step_th_pixel_of_every_step_th_row() {
        assert_eq!(
            sample(5, 3, 2),
            [(0, 0), (2, 0), (4, 0), (0, 2), (2, 2), (4, 2)]
        );
        assert_eq!(sample(3, 2, 1).len(), 6);
    }
}
