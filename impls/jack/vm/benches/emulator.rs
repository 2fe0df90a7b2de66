//! Emulator speed in VM instructions per second (criterion's "elements"),
//! on a Float316-like workload (`benches/workload/*.vm`, hand-compiled with
//! the Jack compiler's templates: field access through `this`, array reads
//! and writes through `that`, Math.multiply/divide, small methods, loops):
//! one machine, and many clones of a snapshot in parallel with rayon. Also
//! the real thing: the Jack raymarcher (`impls/jack/raymarcher`, compiled
//! with jack-compiler) computing pixels from a snapshot taken after
//! `Main.init`. And the corpus of programs written in other styles
//! (`tests/support/corpus.rs`), each on both engines, with a table of their
//! rates beside the raymarcher's.

#[path = "../tests/support/corpus.rs"]
mod corpus;
#[path = "../tests/support/corpus_runs.rs"]
mod corpus_runs;
#[path = "../tests/support/raymarcher.rs"]
mod support;

use corpus_runs::load_corpus;
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use hack_vm::{Config, Engine, Exit, Machine, Program};
use rayon::prelude::*;
use std::sync::Arc;
use std::time::{Duration, Instant};
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

/// Each corpus program on each engine, under criterion.
fn corpus_programs(c: &mut Criterion) {
    let loaded = load_corpus(None);
    let mut g = c.benchmark_group("hack-vm corpus");
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    for l in &loaded {
        let _ = l.program.compile_native(hack_vm::Profile::Desktop);
        for engine in [Engine::Interp, Engine::Native] {
            g.throughput(Throughput::Elements(l.run(engine)));
            g.bench_function(format!("{}, {engine:?}", l.entry.name), |b| {
                b.iter(|| l.run(engine))
            });
        }
    }
    g.finish();
}

/// The best rate (VM instructions per second) of five runs of `run`,
/// which returns its steps.
fn best_rate(mut run: impl FnMut() -> u64) -> f64 {
    (0..5)
        .map(|_| {
            let t = Instant::now();
            let steps = run();
            steps as f64 / t.elapsed().as_secs_f64()
        })
        .fold(0.0, f64::max)
}

/// A table on stderr: each corpus program's rate on each engine, and its
/// ratio to the raymarcher's on the same engine, measured one after
/// another in this process (so the ratios hold on a loaded machine).
fn corpus_table(_: &mut Criterion) {
    let loaded = load_corpus(None);
    let ray = raymarcher();
    let _ = ray.compile_native(hack_vm::Profile::Desktop);
    let engines = [Engine::Interp, Engine::Native];
    let ray_rates = engines.map(|engine| {
        let init = support::initialised(&ray, engine);
        best_rate(|| pixels(&init))
    });
    eprintln!(
        "\n| program | interpreter | compiled | interpreter / raymarcher | compiled / raymarcher |"
    );
    eprintln!("|---|---:|---:|---:|---:|");
    let row = |name: &str, rates: [f64; 2]| {
        eprintln!(
            "| {name} | {:.3} G/s | {:.3} G/s | {:.2} | {:.2} |",
            rates[0] / 1e9,
            rates[1] / 1e9,
            rates[0] / ray_rates[0],
            rates[1] / ray_rates[1]
        );
    };
    row("raymarcher (ours), 32 pixels", ray_rates);
    for l in &loaded {
        let _ = l.program.compile_native(hack_vm::Profile::Desktop);
        row(
            l.entry.name,
            engines.map(|engine| best_rate(|| l.run(engine))),
        );
    }
}

/// A test script's `repeat N { vmstep; }` on a counting loop: it runs at
/// the emulator's own speed (one run of N steps), compared with
/// `Machine::run` of the same N steps.
fn script_repeat(c: &mut Criterion) {
    const STEPS: u64 = 10_000_000;
    let dir = tempfile::tempdir().unwrap();
    let vm =
        "function Sys.init 0\nlabel L\npush static 0\npush constant 1\nadd\npop static 0\ngoto L\n";
    std::fs::write(dir.path().join("Sys.vm"), vm).unwrap();
    let tst = dir.path().join("LoopVME.tst");
    std::fs::write(
        &tst,
        format!("load Sys.vm,\nrepeat {STEPS} {{ vmstep; }}\n"),
    )
    .unwrap();
    let mut g = c.benchmark_group("hack-vm script");
    g.throughput(Throughput::Elements(STEPS));
    g.sample_size(10);
    g.bench_function("repeat N { vmstep; }", |b| {
        b.iter(|| {
            let r = hack_vm::run_script(&tst, hack_vm::Profile::Desktop).unwrap();
            assert_eq!(r.steps, STEPS);
        })
    });
    let program = Program::from_sources(&[("Sys.vm", vm)]).unwrap();
    g.bench_function("Machine::run, the same steps", |b| {
        b.iter(|| {
            let mut m = Machine::new(Arc::clone(&program), Config::default());
            m.run(Some(STEPS));
            assert_eq!(m.steps(), STEPS);
        })
    });
    g.finish();
}

criterion_group!(
    benches,
    emulator,
    script_repeat,
    jack_raymarcher,
    corpus_programs,
    corpus_table
);
criterion_main!(benches);
