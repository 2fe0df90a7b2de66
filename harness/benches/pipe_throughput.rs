//! Throughput of the pipe kind, harness side: op answers per second from a
//! minimal Rust adapter (this binary, started again with `--pipe-adapter`:
//! it answers each request with the reference's Float316 operation), and
//! from the Python adapter of `examples/pipe-python`, both through the
//! runner as `harness diff` drives them (pipelined batches of 4096).
//! Figures: docs/performance.md, "Pipe kind".

use common::{Op, OpValue, Outcome, F316};
use criterion::{criterion_group, Criterion, Throughput};
use harness::pipe::{Pipe, PipeConfig};
use harness::runner::{run, RunOptions};
use serde::Deserialize;
use std::io::{BufRead, BufWriter, Write};
use std::time::Duration;
use vectors::{Level, OpVector, Vector, VectorSet};

/// The minimal adapter: level ops, Float316, no traces.
fn adapter() {
    #[derive(Deserialize)]
    struct Batch {
        batch: u64,
        count: usize,
    }
    #[derive(Deserialize)]
    struct Request {
        id: u64,
        op: Op,
        a: F316,
        b: Option<F316>,
    }
    let stdin = std::io::stdin().lock();
    let mut out = BufWriter::with_capacity(1 << 16, std::io::stdout().lock());
    let _ = writeln!(
        out,
        r#"{{"protocol":1,"name":"bench","numbers":"float316","levels":["ops"]}}"#
    );
    let _ = out.flush();
    let mut lines = stdin.lines().map_while(Result::ok);
    while let Some(header) = lines.next() {
        let Ok(batch) = serde_json::from_str::<Batch>(&header) else {
            return;
        };
        for line in lines.by_ref().take(batch.count) {
            let Ok(q) = serde_json::from_str::<Request>(&line) else {
                return;
            };
            let args: Vec<F316> = std::iter::once(q.a).chain(q.b).collect();
            let _ = match reference::op(q.op, &args, reference::Arith::SPEC) {
                Ok(Outcome::Value(OpValue::Num(t))) => {
                    writeln!(
                        out,
                        r#"{{"id":{},"value":[{},{},{}]}}"#,
                        q.id, t.s, t.e, t.m
                    )
                }
                Ok(Outcome::Value(OpValue::Bool(b))) => {
                    writeln!(out, r#"{{"id":{},"value":{b}}}"#, q.id)
                }
                Ok(Outcome::SysError(c)) => {
                    writeln!(out, r#"{{"id":{},"outcome":"sys_error","code":{c}}}"#, q.id)
                }
                Ok(Outcome::Hang) => writeln!(out, r#"{{"id":{},"outcome":"hang"}}"#, q.id),
                _ => writeln!(out, r#"{{"id":{},"outcome":"out_of_domain"}}"#, q.id),
            };
        }
        let _ = writeln!(
            out,
            r#"{{"batch":{},"count":{}}}"#,
            batch.batch, batch.count
        );
        let _ = out.flush();
    }
}

/// `n` operations cycled from the committed nightly ops set.
fn ops(n: usize) -> VectorSet {
    let base = vectors::load_named("ops-nightly").expect("the committed set");
    let vectors: Vec<Vector> = base.vectors.iter().cycle().take(n).cloned().collect();
    assert!(vectors
        .iter()
        .all(|v| matches!(v, Vector::Op(OpVector { .. }))));
    VectorSet::new("bench", Level::Ops, "", None, vectors)
}

fn bench(c: &mut Criterion, group: &str, pipe: &Pipe, n: usize, samples: usize) {
    let set = ops(n);
    let mut g = c.benchmark_group(group);
    g.throughput(Throughput::Elements(n as u64));
    g.sample_size(samples);
    g.measurement_time(Duration::from_secs(10));
    g.bench_function("ops answers", |b| {
        b.iter(|| {
            let runs = run(&[pipe], &set, RunOptions::default());
            assert!(
                runs[0].answers.is_ok(),
                "{:?}",
                runs[0].answers.as_ref().err()
            );
        })
    });
    g.finish();
}

fn pipes(c: &mut Criterion) {
    let exe = std::env::current_exe().expect("the bench binary");
    let rust = Pipe::open(&PipeConfig::new(
        "rust-minimal",
        &exe.display().to_string(),
        &["--pipe-adapter"],
    ))
    .expect("the minimal Rust adapter starts");
    bench(c, "pipe rust-minimal", &rust, 1 << 18, 20);
    let mut python = PipeConfig::new("float316.py", "python3", &["adapter.py"]);
    python.dir = Some(concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/pipe-python").into());
    match Pipe::open(&python) {
        Ok(p) => bench(c, "pipe python", &p, 1 << 14, 10),
        Err(e) => eprintln!("the Python adapter did not start ({e}); its figure is not measured"),
    }
}

criterion_group!(benches, pipes);

fn main() {
    if std::env::args().nth(1).as_deref() == Some("--pipe-adapter") {
        adapter();
        return;
    }
    benches();
    Criterion::default().configure_from_args().final_summary();
}
