//! Emulator speed in VM instructions per second (criterion's "elements"),
//! on a Float316-like workload (`benches/workload/*.vm`, hand-compiled with
//! the Jack compiler's templates: field access through `this`, array reads
//! and writes through `that`, Math.multiply/divide, small methods, loops):
//! one machine, and many clones of a snapshot in parallel with rayon. Also
//! the real thing: the Jack raymarcher (`impls/jack/raymarcher`, compiled
//! with jack-compiler) computing pixels from a snapshot taken after
//! `Main.init`.

#[path = "../tests/support/raymarcher.rs"]
mod support;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use hack_vm::{Config, Engine, Exit, Machine, Program};
use rayon::prelude::*;
use std::sync::Arc;
use support::raymarcher;

const ROUNDS: i16 = 2000;

fn workload() -> Arc<Program> {
    Program::from_sources(&[
        ("Bench.vm", include_str!("workload/Bench.vm")),
        ("Main.vm", include_str!("workload/Main.vm")),
    ])
    .expect("the workload loads")
}

fn one_call(snapshot: &Machine) -> u64 {
    let mut m = snapshot.clone();
    let exit = m
        .call("Main.run", &[ROUNDS], None)
        .expect("Main.run exists");
    assert!(matches!(exit, Exit::Returned(_)), "{exit}");
    m.steps()
}

fn emulator(c: &mut Criterion) {
    let snapshot = Machine::new(workload(), Config::default());
    let steps = one_call(&snapshot);
    let mut g = c.benchmark_group("hack-vm");
    g.throughput(Throughput::Elements(steps));
    g.bench_function("float316-like, single thread", |b| {
        b.iter(|| one_call(&snapshot))
    });
    let jobs = 4 * rayon::current_num_threads() as u64;
    g.throughput(Throughput::Elements(steps * jobs));
    g.bench_function(
        format!(
            "float316-like, {jobs} clones on {} threads",
            rayon::current_num_threads()
        ),
        |b| {
            b.iter(|| {
                (0..jobs)
                    .into_par_iter()
                    .map(|_| one_call(&snapshot))
                    .sum::<u64>()
            })
        },
    );
    g.finish();
}

/// Pixels (x, 100) for x = 0, 16, .., 496 from clones of `snapshot`.
fn pixels(snapshot: &Machine) -> u64 {
    (0..32)
        .map(|i| {
            let mut m = snapshot.clone();
            let exit = m
                .call("Image.pixel", &[i * 16, 100], None)
                .expect("Image.pixel exists");
            assert!(matches!(exit, Exit::Returned(_)), "{exit}");
            m.steps() - snapshot.steps()
        })
        .sum()
}

/// The raymarcher's pixels on each engine, side by side (the compiled
/// engine's compile time is printed once, outside the measurement).
fn jack_raymarcher(c: &mut Criterion) {
    let program = raymarcher();
    match program.compile_native(hack_vm::Profile::Desktop) {
        Ok(t) => eprintln!(
            "raymarcher compiled to native code in {:.3} s",
            t.as_secs_f64()
        ),
        Err(e) => eprintln!("no native code: {e}"),
    }
    let mut g = c.benchmark_group("hack-vm");
    for engine in [Engine::Interp, Engine::Native] {
        let init = support::initialised(&program, engine);
        let steps = pixels(&init);
        g.throughput(Throughput::Elements(steps));
        g.bench_function(
            format!("raymarcher, 32 pixels, single thread, {engine:?}"),
            |b| b.iter(|| pixels(&init)),
        );
    }
    g.finish();
}

criterion_group!(benches, emulator, jack_raymarcher);
criterion_main!(benches);
