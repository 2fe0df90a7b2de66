//! The set-up cost of the kernels generated from scene descriptions: for
//! each scene file given (default: the shipped ones), the size of the
//! generated WGSL and the time to generate and compile its Float316 and
//! f32 kernels (lavapipe compiles at the first dispatch, which the set-up
//! includes). `cargo run --release -p gpu --example scene_setup [--wgsl
//! DIR] [FILE...]`; `--wgsl DIR` writes each generated kernel there.

use scene::Formulation;
use std::time::Instant;

fn main() {
    let gpu = gpu::Gpu::new().unwrap_or_else(|e| panic!("{e}"));
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../vectors/scenes");
    let mut files: Vec<String> = std::env::args().skip(1).collect();
    let wgsl_dir = match files.iter().position(|a| a == "--wgsl") {
        Some(i) => {
            let dir = files.get(i + 1).cloned().expect("--wgsl DIR");
            files.drain(i..i + 2);
            Some(dir)
        }
        None => None,
    };
    if files.is_empty() {
        files = ["seed", "rtdemo", "sdf-engine", "toon"]
            .iter()
            .map(|n| format!("{dir}/{n}.json"))
            .collect();
    }
    println!("| scene | numbers | WGSL lines | WGSL bytes | set-up |");
    println!("|---|---|---:|---:|---:|");
    for file in &files {
        let checked = scene::load(std::path::Path::new(file)).unwrap_or_else(|e| panic!("{e}"));
        let name = &checked.description.name;
        for form in [Formulation::Float316, Formulation::Ieee] {
            let program = scene::lower(&checked, form);
            let source = gpu::scene_wgsl(&program);
            if let Some(dir) = &wgsl_dir {
                let file = format!("{dir}/{name}-{form:?}.wgsl");
                std::fs::write(&file, &source).unwrap_or_else(|e| panic!("{file}: {e}"));
            }
            let start = Instant::now();
            gpu.scene_kernel(&program).unwrap_or_else(|e| panic!("{e}"));
            let setup = start.elapsed().as_secs_f64();
            println!(
                "| {name} | {form:?} | {} | {} | {setup:.2} s |",
                source.lines().count(),
                source.len()
            );
        }
    }
}
