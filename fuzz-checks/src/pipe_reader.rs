//! An adapter's output through the pipe protocol's reader
//! (`harness::pipe::protocol`): the first line as the handshake, every
//! other line as an answer to each kind of request the handshake allows.
//! Whatever the bytes, the reader returns; a rejection names the field at
//! fault (or the line as a whole) and quotes the line, cut to a readable
//! length; an accepted answer has the shape its request asks for.

use common::{Op, OpValue, Outcome};
use harness::implementation::{Answer, Num, Numbers};
use harness::pipe::protocol::{excerpt, read_handshake, read_line, Expect, Line, LineError};
use harness::pipe::{stderr_tail, stdout_lines, STDERR_LINES};
use vectors::Level;

/// Lines of one input that are read (a longer output is cut there).
const LINES: usize = 64;

/// The requests an answer line is read against: an operation giving a
/// number, `gt` (a boolean), and each other level.
const REQUESTS: [(Level, Option<Op>); 5] = [
    (Level::Ops, Some(Op::Add)),
    (Level::Ops, Some(Op::Gt)),
    (Level::Sdf, None),
    (Level::Pixels, None),
    (Level::Image, None),
];

/// The property of target `pipe_reader`: the bytes as an adapter's stdout
/// and stderr through the bounded line reader ([`line_reader`]), and their
/// lines through the protocol's reader.
pub fn pipe_reader(data: &[u8]) {
    line_reader(data);
    protocol_reader(data);
}

/// The line bounds the reader is fuzzed with, small enough that fuzzed
/// inputs have lines at, under and past each.
const LINE_LIMITS: [usize; 3] = [1, 16, 200];

/// The bytes as an adapter's stdout and as its stderr, through the
/// harness's bounded line reader with small bounds (and bounds at and one
/// under the first line's length): stdout's lines are the
/// input's lines (split at `\n`, a `\r` before it dropped), up to the first
/// line past the bound or not UTF-8, where the reader stops with an error
/// naming the bound or the encoding, never holding more than the bound;
/// stderr keeps its last [`STDERR_LINES`] lines, each cut to the bound.
pub fn line_reader(data: &[u8]) {
    // Besides the fixed bounds, the first line's length and one less: a
    // line exactly at the bound, and one a byte past it.
    let first = raw_lines(data).next().map_or(0, <[u8]>::len);
    let at_the_first = [first.max(1), first.saturating_sub(1).max(1)];
    for limit in LINE_LIMITS.into_iter().chain(at_the_first) {
        let (lines, failure) = stdout_lines(data, limit);
        let (want, stop) = split_lines(data, limit);
        assert_eq!(lines, want, "stdout, lines of at most {limit} bytes");
        for line in &lines {
            assert!(line.len() <= limit, "a line of {} bytes kept", line.len());
        }
        match (stop, failure) {
            (None, None) => {}
            (Some(Stop::TooLong), Some(why)) => assert!(
                why.contains(&format!("a line longer than {limit} bytes")),
                "{why}"
            ),
            (Some(Stop::NotUtf8), Some(why)) => assert!(why.contains("not UTF-8"), "{why}"),
            (stop, failure) => panic!("expected {stop:?}, the reader said {failure:?}"),
        }
        let tail = stderr_tail(data, limit);
        assert!(
            tail.len() <= STDERR_LINES,
            "{} stderr lines kept",
            tail.len()
        );
        assert_eq!(
            tail,
            stderr_model(data, limit),
            "stderr, lines cut at {limit}"
        );
    }
}

/// Why the model of the stdout reader stops.
#[derive(Debug)]
enum Stop {
    TooLong,
    NotUtf8,
}

/// The input's lines (their end not counted in the bound) up to the first
/// one past `limit` or not UTF-8.
fn split_lines(data: &[u8], limit: usize) -> (Vec<String>, Option<Stop>) {
    let mut lines = Vec::new();
    for raw in raw_lines(data) {
        if raw.len() > limit {
            return (lines, Some(Stop::TooLong));
        }
        match std::str::from_utf8(raw) {
            Ok(text) => lines.push(text.trim_end_matches('\r').to_string()),
            Err(_) => return (lines, Some(Stop::NotUtf8)),
        }
    }
    (lines, None)
}

/// The last [`STDERR_LINES`] lines, each cut to `limit` bytes, read
/// lossily, trimmed and quoted as [`excerpt`] does.
fn stderr_model(data: &[u8], limit: usize) -> Vec<String> {
    let all: Vec<String> = raw_lines(data)
        .map(|raw| excerpt(String::from_utf8_lossy(&raw[..raw.len().min(limit)]).trim_end()))
        .collect();
    all[all.len().saturating_sub(STDERR_LINES)..].to_vec()
}

/// The bytes between line ends (`\n`); an input ending in `\n` has no
/// empty last line.
fn raw_lines(data: &[u8]) -> impl Iterator<Item = &[u8]> {
    let body = data.strip_suffix(b"\n").unwrap_or(data);
    body.split(|&b| b == b'\n')
        .filter(move |_| !data.is_empty())
}

/// The adapter's output through the protocol's reader.
fn protocol_reader(data: &[u8]) {
    let mut lines = data.split(|&b| b == b'\n').take(LINES).map(|l| {
        String::from_utf8_lossy(l)
            .trim_end_matches('\r')
            .to_string()
    });
    let Some(first) = lines.next() else {
        return;
    };
    // After a refused handshake, every kind of adapter is tried, so that
    // the answer reader is reached whatever the first line is.
    let (numbers, levels) = match read_handshake(&first) {
        Ok(h) => {
            assert!(!h.name.is_empty() && !h.levels.is_empty(), "{h:?}");
            (vec![h.numbers], h.levels)
        }
        Err(e) => {
            well_formed(
                &e,
                &first,
                &["protocol", "name", "numbers", "levels", "trace"],
            );
            (
                vec![Numbers::Float316, Numbers::F64, Numbers::F32],
                vec![Level::Ops, Level::Sdf, Level::Pixels, Level::Image],
            )
        }
    };
    for line in lines {
        for &numbers in &numbers {
            for (level, op) in REQUESTS.into_iter().filter(|(l, _)| levels.contains(l)) {
                let pixel = (level == Level::Pixels).then_some((3, 5));
                let expect = Expect {
                    level,
                    op,
                    pixel,
                    numbers,
                };
                match read_line(&line, &expect) {
                    Ok(read) => answer_fits(&read, &expect, &line),
                    Err(e) => well_formed(&e, &line, &ANSWER_FIELDS),
                }
            }
        }
    }
}

/// The top-level fields of an answer line.
const ANSWER_FIELDS: [&str; 11] = [
    "id", "batch", "count", "outcome", "code", "value", "sd", "col", "shade", "white", "trace",
];

/// A rejection names a field of the line (a top-level one, or one of a
/// trace record) or the line as a whole, says what was wrong, and quotes
/// the line as [`excerpt`] cuts it.
fn well_formed(e: &LineError, line: &str, fields: &[&str]) {
    let text = e.to_string();
    assert!(!e.message.trim().is_empty(), "an empty message: {text}");
    assert_eq!(e.line, excerpt(line), "{text}");
    assert!(
        e.line.chars().count() <= 200 + " ... (00000000000 bytes)".len(),
        "a quote of {} characters",
        e.line.chars().count()
    );
    match &e.field {
        None => assert!(text.starts_with("the line: "), "{text}"),
        Some(field) => {
            let top = field.split(['[', '.']).next().unwrap_or_default();
            assert!(fields.contains(&top), "an unknown field `{field}`: {text}");
            assert!(text.starts_with(&format!("field `{field}`: ")), "{text}");
        }
    }
}

/// An accepted answer holds what its request asks: a boolean for `gt`, a
/// number of the adapter's type for the others, the level's fields, a
/// whole image; every trace record has its operation's operands.
fn answer_fits(read: &Line, expect: &Expect, line: &str) {
    let Line::Answer { outcome, trace, .. } = read else {
        return;
    };
    let of_type = |n: &Num| {
        matches!(
            (n, expect.numbers),
            (Num::F316(_), Numbers::Float316)
                | (Num::F64(_), Numbers::F64)
                | (Num::F32(_), Numbers::F32)
        )
    };
    if let Outcome::Value(answer) = outcome {
        let fits = match (answer, expect.level) {
            (Answer::Bool { .. }, Level::Ops) => expect.op == Some(Op::Gt),
            (Answer::Num { value }, Level::Ops) => expect.op != Some(Op::Gt) && of_type(value),
            (Answer::Sdf { sd, col }, Level::Sdf) => of_type(sd) && of_type(col),
            (Answer::Pixel { shade, .. }, Level::Pixels) => of_type(shade),
            (Answer::Image { bitmap }, Level::Image) => {
                bitmap.white.len() == bitmap.width * bitmap.height
            }
            _ => false,
        };
        assert!(fits, "{answer:?} accepted for {expect:?}: {line}");
    }
    for r in trace.iter().flatten() {
        assert_eq!(r.args.len(), r.op.arity(), "{r:?}");
        if let Outcome::Value(v) = &r.result {
            assert_eq!(matches!(v, OpValue::Bool(_)), r.op == Op::Gt, "{r:?}");
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    #[should_panic(expected = "an unknown field `colour`")]
    fn a_rejection_naming_no_field_of_the_protocol_breaks_the_property() {
        let e = LineError {
            field: Some("colour".into()),
            message: "missing".into(),
            line: excerpt("{}"),
        };
        well_formed(&e, "{}", &ANSWER_FIELDS);
    }

    #[test]
    #[should_panic(expected = "an empty message")]
    fn a_rejection_that_says_nothing_breaks_the_property() {
        let e = LineError {
            field: None,
            message: " ".into(),
            line: excerpt("x"),
        };
        well_formed(&e, "x", &ANSWER_FIELDS);
    }
}
