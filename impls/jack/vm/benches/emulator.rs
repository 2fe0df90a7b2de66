//! Emulator speed in VM instructions per second (criterion's "elements"),
//! on a Float316-like workload (`benches/workload/*.vm`, hand-compiled with
//! the Jack compiler's templates: field access through `this`, array reads
//! and writes through `that`, Math.multiply/divide, small methods, loops):
//! one machine, and many clones of a snapshot in parallel with rayon.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use hack_vm::{Config, Exit, Machine, Program};
use rayon::prelude::*;
use std::sync::Arc;

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

criterion_group!(benches, emulator);
criterion_main!(benches);
