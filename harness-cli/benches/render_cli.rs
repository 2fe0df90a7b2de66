//! `harness render --impl ref-f316` as a user runs it: the whole process
//! (start-up, opening the cast, the contained batches of the runner, the
//! PNG), timed against the renderer's own figure, `cargo bench -p
//! reference`'s whole image. Containment must cost nothing: the command
//! stays within 10% of the library. Figures: docs/performance.md,
//! "Contained batches".

use criterion::{criterion_group, criterion_main, Criterion};
use std::process::Command;
use std::time::Duration;

fn render_cli(c: &mut Criterion) {
    let out = tempfile::tempdir().expect("a temporary folder");
    let png = out.path().join("seed.png");
    let mut group = c.benchmark_group("harness render (whole process)");
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(15));
    group.bench_function("ref-f316", |b| {
        b.iter(|| {
            let status = Command::new(env!("CARGO_BIN_EXE_harness"))
                .args(["render", "--impl", "ref-f316", "--out"])
                .arg(&png)
                .status()
                .expect("the harness binary runs");
            assert!(status.success(), "harness render: {status}");
        })
    });
    group.finish();
}

criterion_group!(benches, render_cli);
criterion_main!(benches);
