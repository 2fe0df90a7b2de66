//! The full 512x256 image per implementation (targets on the 2-core CI
//! machine: ref-f316 under 1 s, ref-f64 under 0.2 s), hand-written and
//! from the seed scene's description (`vectors/scenes/seed.json`).

use criterion::{criterion_group, criterion_main, Criterion};
use reference::{Described, RefImpl, Reference, Settings};
use std::hint::black_box;
use std::time::Duration;

fn render(c: &mut Criterion) {
    let mut group = c.benchmark_group("render 512x256");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(10));
    let seed = scene::load(
        &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../vectors/scenes/seed.json"),
    )
    .expect("the shipped seed scene loads");
    for imp in RefImpl::ALL {
        let r = Reference::seed(imp);
        group.bench_function(imp.name(), |b| b.iter(|| black_box(r.render())));
        let d = Described::new(imp, &seed, Settings::default()).expect("the seed scene prepares");
        group.bench_function(format!("{} described", imp.name()), |b| {
            b.iter(|| black_box(d.render()))
        });
    }
    group.finish();
}

criterion_group!(benches, render);
criterion_main!(benches);
