//! A user's shader (`gpu::shader`): the set-up (front end, device, kernel
//! compilation and first dispatch) and the full-image render, for the seed
//! scene's Shadertoy port and WGSL port in `examples/shaders/`. Without an
//! adapter the benchmark fails unless `F316_SKIP_GPU` is set.

use criterion::{criterion_group, criterion_main, Criterion};
use gpu::shader::{Shade, ShaderOptions, ShaderSource, UserShader};
use gpu::GpuError;
use std::path::Path;
use std::time::Duration;

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("user_shader");
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(20));
    for file in ["seed.glsl", "seed.wgsl"] {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../examples/shaders")
            .join(file);
        let source = ShaderSource::read(&path, None).expect("readable");
        let options = ShaderOptions {
            shade: Shade::Red,
            ..ShaderOptions::default()
        };
        let shader = match UserShader::open(&source, &options) {
            Ok(shader) => shader,
            Err(e @ GpuError::NoAdapter { .. }) if std::env::var_os(gpu::SKIP_ENV).is_some() => {
                eprintln!("GPU leg skipped: {e}");
                return;
            }
            Err(e) => panic!("{e}"),
        };
        eprintln!("adapter: {}", shader.adapter_info());
        group.bench_function(format!("setup {file}"), |b| {
            b.iter(|| UserShader::open(&source, &options).expect("set-up"))
        });
        group.bench_function(format!("render {file}"), |b| {
            b.iter(|| shader.render().expect("render"))
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
