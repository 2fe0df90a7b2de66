//! Speed of the Jack raymarcher on the emulator: one operation, one SDF
//! evaluation and one pixel from the snapshot, through its entry points
//! and through bindings (the raymarcher's and examples/jack-port's). The
//! whole image is measured by `examples/jack_costs.rs`.

use common::{Op, F316};
use criterion::{criterion_group, criterion_main, Criterion};
use jack::{Bindings, BoundProgram, Budgets, JackProgram, Profile, Raymarcher};
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
    bound(c, a, b);
}

/// Operations through bindings: the raymarcher's own, and the port's
/// (value-returning functions, another field order).
fn bound(c: &mut Criterion, a: F316, b: F316) {
    let raymarcher = JackProgram::from_jack(&jack::sources::SOURCES, Profile::Desktop).unwrap();
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/jack-port");
    let port = JackProgram::from_dir(std::path::Path::new(dir), Profile::Desktop).unwrap();
    let port_bindings = std::fs::read_to_string(format!("{dir}/bindings.toml")).unwrap();
    for (name, program, text) in [
        (
            "raymarcher",
            raymarcher,
            jack::sources::BINDINGS.to_string(),
        ),
        ("port", port, port_bindings),
    ] {
        let bindings: Bindings = toml::from_str(&text).unwrap();
        let bound = BoundProgram::open(&program, &bindings, Budgets::default()).unwrap();
        c.bench_function(&format!("bound {name} op div"), |bn| {
            bn.iter(|| bound.op(Op::Div, black_box(&[a, b])).unwrap())
        });
        c.bench_function(&format!("bound {name} op sqrt"), |bn| {
            bn.iter(|| bound.op(Op::Sqrt, black_box(&[a])).unwrap())
        });
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
