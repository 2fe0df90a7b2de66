//! The pipe protocol's messages (see `docs/protocol.md`): the handshake an
//! adapter writes first, the request lines the harness writes, and the
//! reader of answer lines, which checks every field and names the one at
//! fault. Nothing here does I/O, so the reader can be fuzzed on its own.

use crate::implementation::{Answer, Bitmap, Num, Numbers};
use common::{Op, OpValue, Outcome, TraceRecord, F316};
use serde::de::{self, Deserializer, SeqAccess, Visitor};
use serde::Deserialize;
use std::fmt::{self, Write};
use vectors::{Level, Vector};

/// The protocol version this harness speaks.
pub const VERSION: u32 = 1;

/// Longest excerpt of an offending line quoted in a message.
const QUOTED: usize = 200;

/// What an adapter says about itself in its first line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Handshake {
    /// The adapter's own name for its port (informative).
    pub name: String,
    /// The numbers it computes with.
    pub numbers: Numbers,
    /// The levels it answers.
    pub levels: Vec<Level>,
    /// Whether it answers trace requests.
    pub trace: bool,
    /// The operations it has, when it says (`None`: all of them); the
    /// harness sends it no other and counts them as unsupported.
    pub ops: Option<Vec<Op>>,
}

#[derive(Deserialize)]
struct RawHandshake {
    protocol: Option<u32>,
    name: Option<String>,
    numbers: Option<String>,
    levels: Option<Vec<String>>,
    #[serde(default)]
    trace: bool,
    ops: Option<Vec<String>>,
}

/// A field of a line that does not say what the protocol asks.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{}: {message}; the line: `{line}`", field.as_ref().map_or("the line".to_string(), |f| format!("field `{f}`")))]
pub struct LineError {
    /// The offending field (`None`: the line as a whole).
    pub field: Option<String>,
    pub message: String,
    /// The line, cut to a readable length.
    pub line: String,
}

impl LineError {
    fn new(field: Option<&str>, message: impl Into<String>, line: &str) -> Self {
        LineError {
            field: field.map(str::to_string),
            message: message.into(),
            line: excerpt(line),
        }
    }
}

/// `line` cut to [`QUOTED`] characters.
pub fn excerpt(line: &str) -> String {
    let line = line.trim_end();
    match line.char_indices().nth(QUOTED) {
        Some((cut, _)) => format!("{}... ({} bytes)", &line[..cut], line.len()),
        None => line.to_string(),
    }
}

/// Read the adapter's handshake line.
pub fn read_handshake(line: &str) -> Result<Handshake, LineError> {
    let raw: RawHandshake = serde_json::from_str(line).map_err(|e| {
        diagnose::<RawHandshake>(
            line,
            e,
            &["protocol", "name", "numbers", "levels", "trace", "ops"],
        )
    })?;
    let err = |field: &str, message: String| LineError::new(Some(field), message, line);
    match raw.protocol {
        Some(VERSION) => {}
        Some(v) => {
            return Err(err(
                "protocol",
                format!("version {v}; this harness speaks {VERSION}"),
            ))
        }
        None => return Err(err("protocol", format!("missing (expected {VERSION})"))),
    }
    let name = raw
        .name
        .filter(|n| !n.is_empty())
        .ok_or_else(|| err("name", "missing or empty".into()))?;
    let numbers = raw
        .numbers
        .ok_or_else(|| err("numbers", "missing".into()))?;
    let numbers: Numbers = numbers
        .parse()
        .map_err(|e: crate::implementation::UnknownNumbers| err("numbers", e.to_string()))?;
    let levels = raw
        .levels
        .filter(|l| !l.is_empty())
        .ok_or_else(|| err("levels", "missing or empty".into()))?
        .iter()
        .map(|l| l.parse::<Level>().map_err(|e| err("levels", e)))
        .collect::<Result<Vec<_>, _>>()?;
    let ops = raw
        .ops
        .map(|ops| {
            if ops.is_empty() {
                return Err(err(
                    "ops",
                    "empty (leave it out when the port has every operation)".into(),
                ));
            }
            ops.iter()
                .map(|o| {
                    Op::ALL
                        .into_iter()
                        .find(|op| op.to_string() == *o)
                        .ok_or_else(|| {
                            let names: Vec<String> =
                                Op::ALL.iter().map(ToString::to_string).collect();
                            err("ops", format!("`{o}` is not one of {}", names.join(", ")))
                        })
                })
                .collect::<Result<Vec<_>, _>>()
        })
        .transpose()?;
    Ok(Handshake {
        name,
        numbers,
        levels,
        trace: raw.trace,
        ops,
    })
}

fn triple(out: &mut String, t: F316) {
    let _ = write!(out, "[{},{},{}]", t.s, t.e, t.m);
}

/// A number in JSON: a Float316 triple or a decimal that reads back as the
/// same f64 (Rust's shortest round-trip form).
fn number(out: &mut String, n: Num) {
    match n {
        Num::F316(t) => triple(out, t),
        Num::F64(x) => {
            let _ = write!(out, "{x:?}");
        }
        Num::F32(x) => {
            let _ = write!(out, "{:?}", f64::from(x));
        }
    }
}

/// The line that opens a batch of `count` requests of `level`.
pub fn batch_line(out: &mut String, batch: u64, level: Level, count: usize) {
    let _ = writeln!(
        out,
        r#"{{"batch":{batch},"level":"{level}","count":{count}}}"#
    );
}

/// One request line. `coords` are the pixel's normalized coordinates in
/// the adapter's numbers (pixels level only); `trace` asks for its op trace.
pub fn request_line(
    out: &mut String,
    id: u64,
    input: &Vector,
    coords: Option<[Num; 2]>,
    trace: bool,
) {
    let _ = write!(out, r#"{{"id":{id}"#);
    match input {
        Vector::Op(o) => {
            let _ = write!(out, r#","op":"{}","a":"#, o.op);
            triple(out, o.a);
            if let Some(b) = o.b {
                out.push_str(r#","b":"#);
                triple(out, b);
            }
        }
        Vector::Sdf(s) => {
            out.push_str(r#","p":["#);
            for (i, c) in s.p.iter().enumerate() {
                if i > 0 {
                    out.push(',');
                }
                triple(out, *c);
            }
            let [x, y, z] = s.p_f64();
            let _ = write!(out, r#"],"xyz":[{x:?},{y:?},{z:?}]"#);
        }
        Vector::Pixel(p) => {
            let _ = write!(out, r#","x":{},"y":{}"#, p.x, p.y);
            if let Some([u, v]) = coords {
                out.push_str(r#","u":"#);
                number(out, u);
                out.push_str(r#","v":"#);
                number(out, v);
            }
        }
        Vector::Image(_) => {
            let _ = write!(
                out,
                r#","width":{},"height":{}"#,
                common::image_consts::WIDTH,
                common::image_consts::HEIGHT
            );
        }
    }
    if trace {
        out.push_str(r#","trace":true"#);
    }
    out.push_str("}\n");
}

/// A JSON value of an answer field, as read: a triple, a number, a
/// boolean or a string.
#[derive(Clone, Debug, PartialEq)]
pub enum Wire {
    Triple(F316),
    Number(f64),
    Bool(bool),
    Text(String),
}

impl fmt::Display for Wire {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Wire::Triple(t) => write!(f, "the triple {t:?}"),
            Wire::Number(x) => write!(f, "the number {}", common::Shown(*x)),
            Wire::Bool(b) => write!(f, "{b}"),
            Wire::Text(s) => write!(f, "a string of {} characters", s.chars().count()),
        }
    }
}

struct WireVisitor;

impl<'de> Visitor<'de> for WireVisitor {
    type Value = Wire;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a Float316 triple [s,e,m], a number, a boolean or a string")
    }

    fn visit_bool<E: de::Error>(self, v: bool) -> Result<Wire, E> {
        Ok(Wire::Bool(v))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Wire, E> {
        Ok(Wire::Number(v as f64))
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Wire, E> {
        Ok(Wire::Number(v as f64))
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Wire, E> {
        Ok(Wire::Number(v))
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<Wire, E> {
        Ok(Wire::Text(v.to_string()))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Wire, A::Error> {
        let bad = || {
            de::Error::custom(
                "expected a Float316 triple [s,e,m] of three integers in -32768..=32767",
            )
        };
        let mut t = [0i16; 3];
        for slot in &mut t {
            *slot = seq.next_element::<i16>()?.ok_or_else(bad)?;
        }
        if seq.next_element::<de::IgnoredAny>()?.is_some() {
            return Err(bad());
        }
        Ok(Wire::Triple(F316::from(t)))
    }
}

impl<'de> Deserialize<'de> for Wire {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Wire, D::Error> {
        d.deserialize_any(WireVisitor)
    }
}

/// An answer line as read, before it is checked against its request.
#[derive(Deserialize, Default)]
struct RawAnswer {
    id: Option<u64>,
    batch: Option<u64>,
    count: Option<u64>,
    outcome: Option<String>,
    code: Option<i64>,
    value: Option<Wire>,
    sd: Option<Wire>,
    col: Option<Wire>,
    shade: Option<Wire>,
    white: Option<Wire>,
    trace: Option<Vec<RawRecord>>,
}

const ANSWER_FIELDS: [&str; 11] = [
    "id", "batch", "count", "outcome", "code", "value", "sd", "col", "shade", "white", "trace",
];

/// One record of an op trace, as read.
#[derive(Deserialize)]
struct RawRecord {
    op: String,
    args: Vec<Wire>,
    outcome: Option<String>,
    code: Option<i64>,
    result: Option<Wire>,
    #[serde(default)]
    path: Vec<String>,
}

/// What one answer line says.
#[derive(Clone, Debug, PartialEq)]
pub enum Line {
    /// The answer to request `id`, with its op trace when it was asked for.
    Answer {
        id: u64,
        outcome: Outcome<Answer>,
        trace: Option<Vec<TraceRecord>>,
    },
    /// The line that closes batch `batch` after `count` answers.
    End { batch: u64, count: u64 },
}

/// What the reader needs to know of the request being answered.
#[derive(Clone, Copy, Debug)]
pub struct Expect {
    pub level: Level,
    /// The request's operation (ops level).
    pub op: Option<Op>,
    /// The request's pixel (pixels level): where a shade alone is dithered.
    pub pixel: Option<(usize, usize)>,
    pub numbers: Numbers,
}

impl Expect {
    /// The expectation for an answer to `input` from an adapter computing
    /// with `numbers`.
    pub fn of(input: &Vector, numbers: Numbers) -> Self {
        Expect {
            level: input.level(),
            op: match input {
                Vector::Op(o) => Some(o.op),
                _ => None,
            },
            pixel: match input {
                Vector::Pixel(p) => Some((usize::from(p.x), usize::from(p.y))),
                _ => None,
            },
            numbers,
        }
    }
}

/// Name the field of `line` that failed to deserialize as `T`, or the
/// line itself when it is not a JSON object.
fn diagnose<T: serde::de::DeserializeOwned>(
    line: &str,
    e: serde_json::Error,
    fields: &[&str],
) -> LineError {
    let value: serde_json::Value = match serde_json::from_str(line) {
        Ok(v) => v,
        Err(e) => return LineError::new(None, format!("not JSON ({e})"), line),
    };
    let Some(object) = value.as_object() else {
        return LineError::new(None, "not a JSON object", line);
    };
    for field in fields {
        let Some(v) = object.get(*field) else {
            continue;
        };
        if let Err(fe) = serde_json::from_value::<T>(serde_json::json!({ *field: v })) {
            return LineError::new(Some(field), fe.to_string(), line);
        }
    }
    LineError::new(None, e.to_string(), line)
}

/// Read one answer line. `expect` describes the request it should answer
/// (the reader checks ids and counts; this checks the fields).
pub fn read_line(line: &str, expect: &Expect) -> Result<Line, LineError> {
    let raw: RawAnswer =
        serde_json::from_str(line).map_err(|e| diagnose::<RawAnswer>(line, e, &ANSWER_FIELDS))?;
    let err = |field: &str, message: String| LineError::new(Some(field), message, line);
    if let Some(batch) = raw.batch {
        let count = raw
            .count
            .ok_or_else(|| err("count", "missing in the line that closes a batch".into()))?;
        return Ok(Line::End { batch, count });
    }
    let id = raw
        .id
        .ok_or_else(|| err("id", "missing (an answer carries its request's id)".into()))?;
    let trace = raw
        .trace
        .as_ref()
        .map(|records| {
            records
                .iter()
                .enumerate()
                .map(|(i, r)| record(r, i, line))
                .collect()
        })
        .transpose()?;
    let outcome = match raw.outcome.as_deref() {
        Some("unsupported") => Outcome::Value(Answer::Unsupported),
        outcome => match trap(outcome, raw.code, "", line)? {
            Some(t) => t,
            None => Outcome::Value(value(&raw, expect, line)?),
        },
    };
    Ok(Line::Answer { id, outcome, trace })
}

/// A trap named by `outcome` (with `code` for `sys_error`); `None` for a
/// value. `prefix` names the enclosing field in messages.
fn trap<T>(
    outcome: Option<&str>,
    code: Option<i64>,
    prefix: &str,
    line: &str,
) -> Result<Option<Outcome<T>>, LineError> {
    let field = |f: &str| format!("{prefix}{f}");
    Ok(match outcome {
        None | Some("value") => None,
        Some("hang") => Some(Outcome::Hang),
        Some("out_of_domain") => Some(Outcome::OutOfDomain),
        Some("sys_error") => {
            let code = code.ok_or_else(|| {
                LineError::new(
                    Some(&field("code")),
                    "missing (a sys_error carries its code)",
                    line,
                )
            })?;
            let code = i16::try_from(code).map_err(|_| {
                LineError::new(
                    Some(&field("code")),
                    format!("{code} is not a Jack word"),
                    line,
                )
            })?;
            Some(Outcome::SysError(code))
        }
        Some(other) => {
            return Err(LineError::new(
                Some(&field("outcome")),
                format!(
                    "`{other}` (expected {})",
                    if prefix.is_empty() {
                        "value, sys_error, hang, out_of_domain or unsupported"
                    } else {
                        "value, sys_error, hang or out_of_domain"
                    }
                ),
                line,
            ))
        }
    })
}

/// A number of the adapter's type.
fn num(w: Option<&Wire>, field: &str, numbers: Numbers, line: &str) -> Result<Num, LineError> {
    let err = |m: String| LineError::new(Some(field), m, line);
    match (w, numbers) {
        (None, _) => Err(err("missing".into())),
        (Some(Wire::Triple(t)), Numbers::Float316) => Ok(Num::F316(*t)),
        (Some(Wire::Number(x)), Numbers::F32) => Ok(Num::F32(*x as f32)),
        (Some(Wire::Number(x)), Numbers::F64) => Ok(Num::F64(*x)),
        (Some(other), Numbers::Float316) => Err(err(format!(
            "{other}; a float316 adapter answers a triple [s,e,m]"
        ))),
        (Some(other), n) => Err(err(format!("{other}; an {n} adapter answers a number"))),
    }
}

fn boolean(w: Option<&Wire>, field: &str, line: &str) -> Result<bool, LineError> {
    match w {
        Some(Wire::Bool(b)) => Ok(*b),
        Some(other) => Err(LineError::new(
            Some(field),
            format!("{other}; expected true or false"),
            line,
        )),
        None => Err(LineError::new(Some(field), "missing", line)),
    }
}

/// The value fields of an answer of `expect.level`.
fn value(raw: &RawAnswer, expect: &Expect, line: &str) -> Result<Answer, LineError> {
    let n = expect.numbers;
    Ok(match expect.level {
        Level::Ops if expect.op == Some(Op::Gt) => Answer::Bool {
            value: boolean(raw.value.as_ref(), "value", line)?,
        },
        Level::Ops => Answer::Num {
            value: num(raw.value.as_ref(), "value", n, line)?,
        },
        Level::Sdf => Answer::Sdf {
            sd: num(raw.sd.as_ref(), "sd", n, line)?,
            col: num(raw.col.as_ref(), "col", n, line)?,
        },
        Level::Pixels => {
            let shade = num(raw.shade.as_ref(), "shade", n, line)?;
            match (&raw.white, expect.pixel) {
                (Some(_), _) | (None, None) => Answer::Pixel {
                    shade,
                    white: boolean(raw.white.as_ref(), "white", line)?,
                },
                // A shade alone: clamped and dithered as the reference
                // does, in the adapter's numbers.
                (None, Some((x, y))) => match crate::dither::finish(shade, x, y) {
                    Outcome::Value((shade, white)) => Answer::Pixel { shade, white },
                    _ => {
                        return Err(LineError::new(
                            Some("shade"),
                            format!("{shade}: no dithered value comes from this shade"),
                            line,
                        ))
                    }
                },
            }
        }
        Level::Image => Answer::Image {
            bitmap: bitmap(raw.white.as_ref(), line)?,
        },
    })
}

/// An image answer's `white`: one character per pixel, row by row, `1`
/// white and `0` black.
fn bitmap(w: Option<&Wire>, line: &str) -> Result<Bitmap, LineError> {
    use common::image_consts::{HEIGHT, WIDTH};
    let err = |m: String| LineError::new(Some("white"), m, line);
    let Some(Wire::Text(bits)) = w else {
        return Err(err(match w {
            Some(other) => format!("{other}; an image answer is a string of 0 and 1"),
            None => "missing".into(),
        }));
    };
    if bits.len() != WIDTH * HEIGHT {
        return Err(err(format!(
            "{} pixels, expected {} ({WIDTH}x{HEIGHT})",
            bits.chars().count(),
            WIDTH * HEIGHT
        )));
    }
    let white = bits
        .bytes()
        .enumerate()
        .map(|(i, b)| match b {
            b'1' => Ok(true),
            b'0' => Ok(false),
            _ => Err(err(format!(
                "pixel ({},{}) is `{}`, expected 0 or 1",
                i % WIDTH,
                i / WIDTH,
                char::from(b)
            ))),
        })
        .collect::<Result<_, _>>()?;
    Ok(Bitmap {
        width: WIDTH,
        height: HEIGHT,
        white,
    })
}

/// One record of a trace, checked.
fn record(r: &RawRecord, i: usize, line: &str) -> Result<TraceRecord, LineError> {
    let field = |f: &str| format!("trace[{i}].{f}");
    let err = |f: &str, m: String| LineError::new(Some(&field(f)), m, line);
    let op: Op =
        r.op.parse()
            .map_err(|e: common::op::UnknownOp| err("op", e.to_string()))?;
    let args = r
        .args
        .iter()
        .map(|a| match a {
            Wire::Triple(t) => Ok(*t),
            other => Err(err(
                "args",
                format!("{other}; an operand is a triple [s,e,m]"),
            )),
        })
        .collect::<Result<Vec<_>, _>>()?;
    if args.len() != op.arity() {
        return Err(err(
            "args",
            format!("{} operands; `{op}` takes {}", args.len(), op.arity()),
        ));
    }
    let result = match trap(r.outcome.as_deref(), r.code, &field(""), line)? {
        Some(t) => t,
        None => Outcome::Value(match (&r.result, op) {
            (Some(Wire::Bool(b)), Op::Gt) => OpValue::Bool(*b),
            (Some(Wire::Triple(t)), op) if op != Op::Gt => OpValue::Num(*t),
            (Some(other), _) => {
                return Err(err(
                    "result",
                    format!(
                        "{other}; `{op}` gives {}",
                        if op == Op::Gt {
                            "a boolean"
                        } else {
                            "a triple [s,e,m]"
                        }
                    ),
                ))
            }
            (None, _) => return Err(err("result", "missing".into())),
        }),
    };
    Ok(TraceRecord {
        op,
        args,
        result,
        path: r.path.clone(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const HELLO: &str = r#""protocol":1,"name":"p","numbers":"float316","levels":["ops"]"#;

    #[test]
    fn a_handshake_may_list_the_operations_the_port_has() {
        let all = read_handshake(&format!("{{{HELLO}}}")).unwrap();
        assert_eq!(all.ops, None);
        let some = read_handshake(&format!(r#"{{{HELLO},"ops":["add","inv_sqrt"]}}"#)).unwrap();
        assert_eq!(some.ops, Some(vec![Op::Add, Op::InvSqrt]));
        for (ops, why) in [
            (r#"[]"#, "empty"),
            (r#"["add","invsqrt"]"#, "`invsqrt` is not one of gt, add"),
            (r#""add""#, "ops"),
        ] {
            let e = read_handshake(&format!(r#"{{{HELLO},"ops":{ops}}}"#)).unwrap_err();
            assert!(e.to_string().contains(why), "{ops}: {e}");
        }
    }

    #[test]
    fn an_answer_may_say_the_port_has_no_such_operation() {
        let expect = Expect {
            level: Level::Ops,
            op: Some(Op::Halve),
            pixel: None,
            numbers: Numbers::Float316,
        };
        let line = read_line(r#"{"id":3,"outcome":"unsupported"}"#, &expect).unwrap();
        assert!(matches!(
            line,
            Line::Answer {
                id: 3,
                outcome: Outcome::Value(Answer::Unsupported),
                ..
            }
        ));
        // Only an answer can say so, not a record of a trace.
        let record = r#"{"id":3,"value":[0,127,8192],"trace":[{"op":"halve","args":[[0,127,8192]],"outcome":"unsupported"}]}"#;
        let e = read_line(record, &expect).unwrap_err().to_string();
        assert!(
            e.contains("expected value, sys_error, hang or out_of_domain"),
            "{e}"
        );
    }

    /// A pixel answered with its shade alone is clamped and dithered as the
    /// reference does, in the adapter's numbers; one with `white` is read
    /// as it is.
    #[test]
    fn a_pixel_may_be_answered_with_its_shade_alone() {
        let expect = |numbers| Expect {
            level: Level::Pixels,
            op: None,
            pixel: Some((3, 5)),
            numbers,
        };
        let read = |line: &str, numbers| match read_line(line, &expect(numbers)).unwrap() {
            Line::Answer {
                outcome: Outcome::Value(Answer::Pixel { shade, white }),
                ..
            } => (shade, white),
            other => panic!("{other:?}"),
        };
        // B(3, 5) = 30: white when (shade + 30/64) - 0.5 > 0.5, above 34/64;
        // 1.5 clamps to 1 (white), -0 to 0 (black), and 0.5 stays black.
        assert_eq!(
            read(r#"{"id":0,"shade":1.5}"#, Numbers::F64),
            (Num::F64(1.0), true)
        );
        assert_eq!(
            read(r#"{"id":0,"shade":0.5}"#, Numbers::F64),
            (Num::F64(0.5), false)
        );
        assert_eq!(
            read(r#"{"id":0,"shade":-0.0}"#, Numbers::F32),
            (Num::F32(0.0), false)
        );
        assert_eq!(
            read(r#"{"id":0,"shade":0.3,"white":true}"#, Numbers::F64),
            (Num::F64(0.3), true)
        );
        // B(3, 0) = 60: white when add(shade, 28/64) > 0.5: 0.125 is.
        let at = Expect {
            pixel: Some((3, 0)),
            ..expect(Numbers::Float316)
        };
        let line = r#"{"id":0,"shade":[0,124,8192]}"#;
        let Line::Answer { outcome, .. } = read_line(line, &at).unwrap() else {
            panic!("an answer")
        };
        assert_eq!(
            outcome,
            Outcome::Value(Answer::Pixel {
                shade: Num::F316(F316::new(0, 124, 8192)),
                white: true,
            })
        );
    }

    /// A huge number where a triple is due is shown as `1e300`, not its 301
    /// digits (issue 35 item 11).
    #[test]
    fn a_huge_number_in_an_answer_is_shown_compactly() {
        let expect = Expect {
            level: Level::Ops,
            op: Some(Op::Add),
            pixel: None,
            numbers: Numbers::Float316,
        };
        let e = read_line(r#"{"id":3,"value":1e300}"#, &expect)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("the number 1e300; a float316 adapter answers a triple"),
            "{e}"
        );
        assert!(!e.contains("000000"), "{e}");
    }
}
