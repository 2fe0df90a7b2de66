//! The full 512x256 image per implementation (targets on the 2-core CI
//! machine: ref-f316 under 1 s, ref-f64 under 0.2 s).

use criterion::{criterion_group, criterion_main, Criterion};
use reference::{RefImpl, Reference};
use std::hint::black_box;
use std::time::Duration;

fn render(c: &mut Criterion) {
    let mut group = c.benchmark_group("render 512x256");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(10));
    for imp in RefImpl::ALL {
        let r = Reference::seed(imp);
        group.bench_function(imp.name(), |b| b.iter(|| black_box(r.render())));
    }
    group.finish();
}

criterion_group!(benches, render);
criterion_main!(benches);
