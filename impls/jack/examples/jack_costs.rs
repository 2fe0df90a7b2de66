//! Where the Jack raymarcher's VM instructions go: per Float316 operation
//! (mean and max over a generated operand set), per SDF evaluation, per
//! pixel (mean, max and a cost map PNG), the whole image (with its wall
//! time and a check against the committed render), and per Jack function.
//!
//! `cargo run --release -p jack --example jack_costs -- [COST_MAP.png]`

use common::image_consts::{HEIGHT, WIDTH};
use common::{Op, F316};
use jack::{Budgets, Config, Profile, Raymarcher};
use proptest::prelude::*;
use std::time::Instant;
use vectors::gen::{self, Draw};

/// A normalised value with |x| roughly in [2^-6, 2^8], of either sign or
/// positive.
fn value(signed: bool) -> impl Strategy<Value = F316> {
    gen::ops::normalised(121..=135)
        .prop_map(move |v| if signed { v } else { F316::new(0, v.e, v.m) })
}

/// CPU seconds this process has used (user + system), from /proc.
fn cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // Fields after the command name (which may hold spaces) start at ")".
    let fields: Vec<&str> = stat.rsplit_once(')')?.1.split_whitespace().collect();
    let ticks: f64 = fields.get(11)?.parse::<f64>().ok()? + fields.get(12)?.parse::<f64>().ok()?;
    Some(ticks / 100.0)
}

fn stats(counts: &[u64]) -> (f64, u64) {
    let sum: u64 = counts.iter().sum();
    (
        sum as f64 / counts.len() as f64,
        counts.iter().copied().max().unwrap_or(0),
    )
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let map_path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "jack-cost-map.png".to_string());
    let jack = Raymarcher::new(Profile::Desktop, Budgets::default())?;
    let mut draw = Draw::new(0x5eed_f316);

    println!("| Float316 operation | mean instructions | max |");
    println!("|---|---:|---:|");
    for op in Op::ALL {
        let signed = !matches!(op, Op::Sqrt | Op::InvSqrt);
        let mut counts = Vec::new();
        for _ in 0..2000 {
            let mut a = draw.one(&value(signed));
            if op == Op::Mod2 {
                // An integral operand: floor of a value below 2^8.
                a = jack
                    .op(Op::Floor, &[a])?
                    .outcome
                    .value()
                    .and_then(|v| match v {
                        common::OpValue::Num(n) => Some(n),
                        common::OpValue::Bool(_) => None,
                    })
                    .unwrap_or(F316::ZERO);
            }
            let args: Vec<F316> = if op.arity() == 2 {
                vec![a, draw.one(&value(true))]
            } else {
                vec![a]
            };
            counts.push(jack.op(op, &args)?.instructions);
        }
        let (mean, max) = stats(&counts);
        println!("| {op} | {mean:.1} | {max} |");
    }

    let mut sdf_counts = Vec::new();
    for _ in 0..2000 {
        let c = (0..8000i32).prop_map(|v| {
            F316::from_f64_truncating(f64::from(v) / 1000.0 - 4.0).unwrap_or(F316::ZERO)
        });
        let p = [draw.one(&c), draw.one(&c), draw.one(&c)];
        sdf_counts.push(jack.sdf(p)?.instructions);
    }
    let (mean, max) = stats(&sdf_counts);
    println!("\nSDF evaluation (2000 points in [-4,4]^3): mean {mean:.0}, max {max} instructions");

    let threads = rayon::current_num_threads();
    let (start, cpu_start) = (Instant::now(), cpu_seconds());
    let render = jack.render()?;
    let wall = start.elapsed();
    let cpu = cpu_seconds().zip(cpu_start).map(|(b, a)| b - a);
    let counts: Vec<u64> = render.pixels.iter().map(|p| p.instructions).collect();
    let (mean, max) = stats(&counts);
    println!(
        "Whole image: {} instructions in {:.1} s wall on {threads} threads; per pixel mean {mean:.0}, max {max}",
        render.instructions(),
        wall.as_secs_f64(),
    );
    if let Some(cpu) = cpu {
        println!(
            "CPU time {cpu:.1} s ({:.0} M instructions per CPU second; {:.1} s on {threads} idle cores)",
            render.instructions() as f64 / cpu / 1e6,
            cpu / threads as f64
        );
    }
    let reference = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../vectors/images/seed-float316-512x256.png"
    );
    let reference = image::open(reference)?.to_luma8();
    let differing = render
        .pixels
        .iter()
        .enumerate()
        .filter(|(i, p)| {
            let white = p.outcome.value().map(|s| s.white);
            let want = reference.get_pixel((i % WIDTH) as u32, (i / WIDTH) as u32)[0] == 255;
            white != Some(want)
        })
        .count();
    println!("Pixels differing from vectors/images/seed-float316-512x256.png: {differing}");

    let map = image::GrayImage::from_fn(WIDTH as u32, HEIGHT as u32, |x, y| {
        let c = counts[y as usize * WIDTH + x as usize];
        image::Luma([(c * 255 / max.max(1)) as u8])
    });
    map.save(&map_path)?;
    println!("Cost map (white = {max} instructions): {map_path}");

    let profiling = Raymarcher::with_config(
        Config {
            profile_functions: true,
            ..Config::default()
        },
        Budgets::default(),
    )?;
    let sample: Vec<(usize, usize)> = (0..HEIGHT)
        .step_by(8)
        .flat_map(|y| (0..WIDTH).step_by(8).map(move |x| (x, y)))
        .collect();
    let profile = profiling.profile_pixels(&sample)?;
    let total: u64 = profile.iter().map(|(_, n)| n).sum();
    println!("\n| Jack function (exclusive) | share of a pixel's instructions |");
    println!("|---|---:|");
    for (f, n) in profile.iter().take(15) {
        println!("| {f} | {:.1}% |", 100.0 * *n as f64 / total as f64);
    }
    Ok(())
}
