//! `ref-pipe [--fault mul-keep-low]`: a pipe adapter (see
//! `docs/protocol.md`) around the Rust reference's Float316 port. It
//! declares every level (ops, sdf, pixels, image) and op traces.
//!
//! Clean, it agrees with ref-f316 bit for bit. With `--fault mul-keep-low`
//! its `mul` keeps the low*low partial product that the spec drops: some
//! products round up by one in their last bit (before normalising), which
//! the harness detects and localizes to `mul` through this adapter's trace.

use common::{Op, OpValue, Outcome, TraceRecord, F316};
use reference::{Arith, RefImpl, Reference, Scene, Settings, Variant};
use serde::Deserialize;
use std::io::{self, BufRead, BufWriter, Write};

/// One request line: the fields of every level (docs/protocol.md).
#[derive(Deserialize)]
struct Request {
    id: u64,
    op: Option<Op>,
    a: Option<F316>,
    b: Option<F316>,
    p: Option<[F316; 3]>,
    x: Option<usize>,
    y: Option<usize>,
    u: Option<F316>,
    v: Option<F316>,
    #[serde(default)]
    trace: bool,
}

/// The line that opens a batch.
#[derive(Deserialize)]
struct Batch {
    batch: u64,
    level: String,
    count: usize,
}

fn triple(t: F316) -> String {
    format!("[{},{},{}]", t.s, t.e, t.m)
}

/// The answer's fields for an outcome whose value `fields` writes.
fn outcome<T>(o: Outcome<T>, fields: impl FnOnce(T) -> String) -> String {
    match o {
        Outcome::Value(v) => fields(v),
        Outcome::SysError(code) => format!(r#""outcome":"sys_error","code":{code}"#),
        Outcome::Hang => r#""outcome":"hang""#.into(),
        Outcome::OutOfDomain => r#""outcome":"out_of_domain""#.into(),
    }
}

fn op_value(v: OpValue) -> String {
    match v {
        OpValue::Num(t) => format!(r#""value":{}"#, triple(t)),
        OpValue::Bool(b) => format!(r#""value":{b}"#),
    }
}

fn record(r: &TraceRecord) -> String {
    let args: Vec<String> = r.args.iter().map(|a| triple(*a)).collect();
    let result = outcome(r.result, |v| match v {
        OpValue::Num(t) => format!(r#""result":{}"#, triple(t)),
        OpValue::Bool(b) => format!(r#""result":{b}"#),
    });
    let path = serde_json::to_string(&r.path).unwrap_or_else(|_| "[]".into());
    format!(
        r#"{{"op":"{}","args":[{}],{result},"path":{path}}}"#,
        r.op,
        args.join(",")
    )
}

struct Port {
    arith: Arith,
    scene: Reference,
}

impl Port {
    /// The answer line to one request (without its newline).
    fn answer(&self, level: &str, q: &Request) -> Result<String, String> {
        let missing = |f: &str| format!("request {}: no `{f}`", q.id);
        let (fields, trace) = match level {
            "ops" => {
                let op = q.op.ok_or_else(|| missing("op"))?;
                let args: Vec<F316> = q.a.into_iter().chain(q.b).collect();
                if q.trace {
                    let t =
                        reference::trace_op(op, &args, self.arith).map_err(|e| e.to_string())?;
                    (outcome(t.outcome, op_value), Some(t.records))
                } else {
                    let o = reference::op(op, &args, self.arith).map_err(|e| e.to_string())?;
                    (outcome(o, op_value), None)
                }
            }
            "sdf" => {
                let p = q.p.ok_or_else(|| missing("p"))?;
                let sdf = |s: reference::SdfValue| {
                    let t = |x: reference::Scalar| x.triple.map(triple).unwrap_or_default();
                    format!(r#""sd":{},"col":{}"#, t(s.sd), t(s.col))
                };
                if q.trace {
                    let t = self.scene.trace_sdf(p).map_err(|e| e.to_string())?;
                    (outcome(t.outcome, sdf), Some(t.records))
                } else {
                    (outcome(self.scene.sdf(p), sdf), None)
                }
            }
            "pixels" => {
                let (x, y) = (
                    q.x.ok_or_else(|| missing("x"))?,
                    q.y.ok_or_else(|| missing("y"))?,
                );
                let uv = [
                    q.u.ok_or_else(|| missing("u"))?,
                    q.v.ok_or_else(|| missing("v"))?,
                ];
                let pixel = |p: reference::PixelValue| {
                    let shade = p.value.triple.map(triple).unwrap_or_default();
                    format!(r#""shade":{shade},"white":{}"#, p.white)
                };
                if q.trace {
                    let t = self
                        .scene
                        .trace_pixel_from_coords(x, y, uv)
                        .map_err(|e| e.to_string())?;
                    (outcome(t.outcome, pixel), Some(t.records))
                } else {
                    let o = self
                        .scene
                        .pixel_from_coords(x, y, uv)
                        .map_err(|e| e.to_string())?;
                    (outcome(o, pixel), None)
                }
            }
            "image" => {
                let image = self.scene.render();
                let bits: String = (0..image.height)
                    .flat_map(|y| (0..image.width).map(move |x| (x, y)))
                    .map(|(x, y)| if image.is_white(x, y) { '1' } else { '0' })
                    .collect();
                (format!(r#""white":"{bits}""#), None)
            }
            other => return Err(format!("unknown level `{other}`")),
        };
        let trace = trace
            .map(|records| {
                let records: Vec<String> = records.iter().map(record).collect();
                format!(r#","trace":[{}]"#, records.join(","))
            })
            .unwrap_or_default();
        Ok(format!(r#"{{"id":{},{fields}{trace}}}"#, q.id))
    }
}

fn run(settings: Settings) -> Result<(), String> {
    let scene =
        Reference::new(RefImpl::F316, &Scene::default(), settings).map_err(|e| e.to_string())?;
    let port = Port {
        arith: settings.arith,
        scene,
    };
    let stdin = io::stdin().lock();
    let mut out = BufWriter::new(io::stdout().lock());
    let io = |e: io::Error| e.to_string();
    writeln!(
        out,
        r#"{{"protocol":1,"name":"ref-pipe","numbers":"float316","levels":["ops","sdf","pixels","image"],"trace":true}}"#
    )
    .and_then(|()| out.flush())
    .map_err(io)?;
    let mut lines = stdin.lines();
    while let Some(header) = lines.next() {
        let header = header.map_err(io)?;
        let batch: Batch = serde_json::from_str(&header).map_err(|e| format!("batch line: {e}"))?;
        for _ in 0..batch.count {
            let line = lines
                .next()
                .ok_or("input ended inside a batch")?
                .map_err(io)?;
            let q: Request = serde_json::from_str(&line).map_err(|e| format!("request: {e}"))?;
            writeln!(out, "{}", port.answer(&batch.level, &q)?).map_err(io)?;
        }
        writeln!(
            out,
            r#"{{"batch":{},"count":{}}}"#,
            batch.batch, batch.count
        )
        .and_then(|()| out.flush())
        .map_err(io)?;
    }
    Ok(())
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let settings = match args.as_slice() {
        [] => Settings::default(),
        [flag, fault] if flag == "--fault" && fault == "mul-keep-low" => {
            Variant::MulKeepLow.apply(Settings::default())
        }
        _ => {
            eprintln!("usage: ref-pipe [--fault mul-keep-low]");
            std::process::exit(2);
        }
    };
    if let Err(e) = run(settings) {
        eprintln!("ref-pipe: {e}");
        std::process::exit(1);
    }
}
