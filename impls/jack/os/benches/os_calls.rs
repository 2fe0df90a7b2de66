//! Speed of the built-ins the VM calls most: Math.multiply/divide (through
//! `Os::call` and directly), printChar, drawLine, alloc + deAlloc.

use criterion::{criterion_group, criterion_main, BatchSize, Criterion};
use jack_os::{math, Builtin, KeyScript, Os, Profile, Ram};
use std::hint::black_box;

fn machine() -> (Os, Ram, u64) {
    let mut os = Os::new(Profile::Desktop, KeyScript::none());
    let mut ram = Ram::new();
    os.reset(&mut ram);
    (os, ram, 0)
}

fn bench(c: &mut Criterion) {
    let (mut os, mut ram, mut clock) = machine();
    c.bench_function("call Math.multiply", |b| {
        b.iter(|| {
            os.call(
                Builtin::MathMultiply,
                black_box(&[123, -456]),
                &mut ram,
                &mut clock,
            )
        })
    });
    c.bench_function("call Math.divide", |b| {
        b.iter(|| {
            os.call(
                Builtin::MathDivide,
                black_box(&[-12345, 67]),
                &mut ram,
                &mut clock,
            )
        })
    });
    c.bench_function("math::divide web", |b| {
        b.iter(|| math::divide(Profile::Web, black_box(-12345), black_box(67)))
    });
    c.bench_function("call Output.printChar", |b| {
        b.iter(|| {
            os.call(
                Builtin::OutputPrintChar,
                black_box(&[65]),
                &mut ram,
                &mut clock,
            )
        })
    });
    c.bench_function("call Screen.drawLine 511x255", |b| {
        b.iter(|| {
            os.call(
                Builtin::ScreenDrawLine,
                black_box(&[0, 0, 511, 255]),
                &mut ram,
                &mut clock,
            )
        })
    });
    c.bench_function("100 x Memory.alloc(8), then 100 x deAlloc", |b| {
        b.iter_batched(
            machine,
            |(mut os, mut ram, mut clock)| {
                let mut blocks = [0i16; 100];
                for p in &mut blocks {
                    *p = os
                        .call(Builtin::MemoryAlloc, &[8], &mut ram, &mut clock)
                        .value;
                }
                for p in blocks {
                    os.call(Builtin::MemoryDeAlloc, &[p], &mut ram, &mut clock);
                }
                ram
            },
            BatchSize::LargeInput,
        )
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
