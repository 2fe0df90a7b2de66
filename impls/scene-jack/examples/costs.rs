//! The cost of a scene's generated Jack program: its size in VM commands
//! and estimated Hack ROM words, and VM instructions per pixel (mean, max)
//! over every `STEP`-th pixel of every `STEP`-th row (default 1: all).
//!
//! `cargo run -p scene-jack --example costs -- vectors/scenes/seed.json [STEP]`

use scene_jack::cost::{self, Runner};
use std::path::Path;

fn main() {
    let mut args = std::env::args().skip(1);
    let file = args.next().expect("a scene file");
    let step: u32 = args.next().map_or(1, |s| s.parse().expect("STEP"));
    let g = scene_jack::emit_file(Path::new(&file)).unwrap_or_else(|e| panic!("{e}"));
    let (p, j) = (g.program, g.sources);
    let profile = hack_vm::Profile::Desktop;
    let size = cost::size(&cost::compile(&j, profile).expect("compiles"));
    println!(
        "{file}: {} static words, {} VM commands, about {} Hack instructions in line, {} with shared call/return routines (the ROM has {})",
        j.statics,
        size.vm_commands,
        size.rom_textbook,
        size.rom_shared,
        cost::ROM_WORDS
    );
    let runner = Runner::new(&j, profile).expect("sets up");
    let (w, h) = scene_jack::drawn(&p);
    let pixels: Vec<(u32, u32)> = (0..h)
        .step_by(step as usize)
        .flat_map(|y| (0..w).step_by(step as usize).map(move |x| (x, y)))
        .collect();
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let parts: Vec<cost::PixelCost> = std::thread::scope(|s| {
        let chunks: Vec<_> = pixels
            .chunks(pixels.len().div_ceil(threads))
            .map(|c| s.spawn(|| cost::pixel_cost(&runner, c)))
            .collect();
        chunks
            .into_iter()
            .map(|c| c.join().expect("a worker"))
            .collect()
    });
    let total: f64 = parts.iter().map(|c| c.mean * c.pixels as f64).sum();
    let worst = parts.iter().max_by_key(|c| c.max).expect("some pixels");
    println!(
        "Main.init: {} VM instructions; per pixel over {} pixels: mean {:.0}, max {} at {:?}",
        runner.init_instructions,
        pixels.len(),
        total / pixels.len() as f64,
        worst.max,
        worst.worst
    );
}
