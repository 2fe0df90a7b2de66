//! Speed of the Jack raymarcher on the emulator: one operation, one SDF
//! evaluation and one pixel from the snapshot. The whole image is measured
//! by `examples/jack_costs.rs` (recorded in the README).

use common::{Op, F316};
use criterion::{criterion_group, criterion_main, Criterion};
use jack::{Budgets, Profile, Raymarcher};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let jack =
        Raymarcher::new(Profile::Desktop, Budgets::default()).expect("the raymarcher builds");
    let (a, b) = (F316::new(0, 129, 10240), F316::new(1, 127, 12288));
    c.bench_function("jack op div", |bn| {
        bn.iter(|| jack.op(Op::Div, black_box(&[a, b])).unwrap())
    });
    c.bench_function("jack op sqrt", |bn| {
        bn.iter(|| jack.op(Op::Sqrt, black_box(&[a])).unwrap())
    });
    let p = [F316::new(0, 127, 8192), F316::ZERO, F316::new(0, 128, 8192)];
    c.bench_function("jack sdf", |bn| bn.iter(|| jack.sdf(black_box(p)).unwrap()));
    let mut g = c.benchmark_group("jack pixel");
    g.sample_size(20);
    g.bench_function("torus (330,150)", |bn| {
        bn.iter(|| jack.pixel(black_box(330), black_box(150)).unwrap())
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
