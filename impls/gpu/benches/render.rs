//! Full-image renders per GPU implementation, with the set-up (adapter,
//! device, kernel compilation) measured separately. Without an adapter the
//! benchmark fails unless `F316_SKIP_GPU` is set.

use criterion::{criterion_group, criterion_main, Criterion};
use gpu::Gpu;
use std::time::Duration;

fn bench(c: &mut Criterion) {
    let gpu = match Gpu::new_unless_skipped() {
        Ok(Some(gpu)) => gpu,
        Ok(None) => return,
        Err(error) => panic!("{error}"),
    };
    eprintln!("adapter: {}", gpu.adapter_info());

    let mut group = c.benchmark_group("gpu");
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(20));
    group.bench_function("setup", |b| b.iter(|| Gpu::new().expect("set-up")));
    group.bench_function("render_f32", |b| {
        b.iter(|| gpu.render_f32().expect("render"))
    });
    group.bench_function("render_f316", |b| {
        b.iter(|| gpu.render_f316().expect("render"))
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
