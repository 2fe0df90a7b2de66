//! The one abstraction every implementation is seen through: an
//! [`Implementation`] evaluates batches of [`Vector`]s of any level it
//! supports and answers each with an `Outcome<Answer>` (a value, a
//! `Sys.error` code, a hang or out of domain: a trap is an answer to
//! compare, never a crash). Float316 implementations can also record an op
//! trace for one input. One adapter module per implementation lives in
//! `impls/`.

use common::{Outcome, TraceRecord, F316};
use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;
use vectors::{Level, Vector};

/// The number format an implementation computes with; it decides the
/// comparison policy.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Numbers {
    /// Float316 triples: compared bit for bit.
    Float316,
    /// IEEE f64: the oracle of the error figures.
    F64,
    /// IEEE f32.
    F32,
    /// Another IEEE binary width (binary16, binary128, ...): its answers
    /// travel as f64 values and are compared by error figures.
    Ieee { bits: u16 },
}

impl Numbers {
    /// The name used in project files and listings: `float316`, `f64`,
    /// `f32`, `f16`, ...
    pub fn name(self) -> String {
        match self {
            Numbers::Float316 => "float316".into(),
            Numbers::F64 => "f64".into(),
            Numbers::F32 => "f32".into(),
            Numbers::Ieee { bits } => format!("f{bits}"),
        }
    }
}

impl fmt::Display for Numbers {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.name())
    }
}

/// A number type name that is neither `float316` nor an IEEE binary width.
#[derive(Debug, thiserror::Error)]
#[error("unknown number type `{0}` (expected float316, f64, f32 or another IEEE width: f16, f128)")]
pub struct UnknownNumbers(pub String);

impl FromStr for Numbers {
    type Err = UnknownNumbers;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "float316" => Ok(Numbers::Float316),
            "f64" => Ok(Numbers::F64),
            "f32" => Ok(Numbers::F32),
            "f16" => Ok(Numbers::Ieee { bits: 16 }),
            "f128" => Ok(Numbers::Ieee { bits: 128 }),
            _ => Err(UnknownNumbers(s.to_string())),
        }
    }
}

/// A number as an implementation produced it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Num {
    /// A Float316 triple.
    F316(F316),
    /// An f64.
    F64(f64),
    /// An f32.
    F32(f32),
}

impl Num {
    /// The exact real value as f64 (exact for all three kinds).
    pub fn to_f64(self) -> f64 {
        match self {
            Num::F316(v) => v.to_f64(),
            Num::F64(v) => v,
            Num::F32(v) => f64::from(v),
        }
    }
}

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Num::F316(v) => write!(f, "{v}"),
            Num::F64(v) => write!(f, "{v:e}"),
            Num::F32(v) => write!(f, "{v:e}f32"),
        }
    }
}

/// The whole dithered image: `white[y * width + x]`.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Bitmap {
    pub width: usize,
    pub height: usize,
    pub white: Vec<bool>,
}

/// What an implementation answers for one vector (wrapped in an
/// [`Outcome`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum Answer {
    /// `gt`.
    Bool { value: bool },
    /// Every other operation.
    Num { value: Num },
    /// A scene query: signed distance and colour.
    Sdf { sd: Num, col: Num },
    /// A pixel: the shade before dithering (after the clamp to [0, 1]) and
    /// whether the dithered pixel is white.
    Pixel { shade: Num, white: bool },
    /// The whole image.
    Image { bitmap: Bitmap },
    /// One pixel of an image answer, as divergences of the `image` level
    /// report it (the image carries no shades).
    Dot { white: bool },
    /// The implementation has no such operation (a port that writes
    /// `halve` inline): the input is counted, not compared.
    Unsupported,
}

/// A Float316 operation's result as an answer.
impl From<common::OpValue> for Answer {
    fn from(r: common::OpValue) -> Answer {
        match r {
            common::OpValue::Bool(value) => Answer::Bool { value },
            common::OpValue::Num(t) => Answer::Num {
                value: Num::F316(t),
            },
        }
    }
}

impl fmt::Display for Answer {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Answer::Bool { value } => write!(f, "{value}"),
            Answer::Num { value } => write!(f, "{value}"),
            Answer::Sdf { sd, col } => write!(f, "sd {sd}, col {col}"),
            Answer::Pixel { shade, white } => {
                write!(
                    f,
                    "shade {shade}, {}",
                    if *white { "white" } else { "black" }
                )
            }
            Answer::Image { bitmap } => {
                let n = bitmap.white.iter().filter(|w| **w).count();
                write!(
                    f,
                    "{}x{} image, {n} white pixels",
                    bitmap.width, bitmap.height
                )
            }
            Answer::Dot { white } => f.write_str(if *white { "white" } else { "black" }),
            Answer::Unsupported => f.write_str("unsupported"),
        }
    }
}

/// Why an implementation gave no answers at all.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, thiserror::Error)]
#[serde(tag = "kind", content = "reason", rename_all = "snake_case")]
pub enum ImplError {
    /// The implementation cannot run here (no GPU adapter, missing
    /// snapshot, ...); the reason says why. It is reported, never faked.
    #[error("unavailable: {0}")]
    Unavailable(String),
    /// It has no entry point for this level or cannot trace.
    #[error("does not support {0}")]
    Unsupported(String),
    /// It ran and failed in a way that is not an answer (an internal error).
    #[error("failed: {0}")]
    Failed(String),
    /// It panicked, hung, crashed or broke its protocol while answering:
    /// contained, with the input and the answers that came before.
    #[error("{0}")]
    Contained(Box<Failure>),
}

/// How an implementation failed to answer.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FailureKind {
    /// It panicked (an in-process implementation).
    Panic,
    /// Its answer did not come within the watchdog's time.
    Hang,
    /// Its process exited (or was killed) while answering.
    Crash,
    /// Its process wrote something the protocol does not allow: a
    /// malformed line, a wrong id, a wrong count.
    Protocol,
    /// Its process exited before its handshake.
    EarlyExit,
    /// It was not asked: an earlier failure stopped it.
    NotRun,
}

impl fmt::Display for FailureKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            FailureKind::Panic => "panicked",
            FailureKind::Hang => "hung",
            FailureKind::Crash => "crashed",
            FailureKind::Protocol => "broke the protocol",
            FailureKind::EarlyExit => "exited before its handshake",
            FailureKind::NotRun => "not run",
        })
    }
}

/// A contained failure of one implementation.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Failure {
    /// The implementation's label.
    pub label: String,
    pub kind: FailureKind,
    /// What happened, in words (the panic message, the offending line and
    /// field, the exit status, ...).
    pub message: String,
    /// The input it was working on, when it is known.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub input: Option<Vector>,
    /// Index of the first input left without an answer: in the batch as the
    /// implementation reports it, in the set once the runner has placed it.
    pub index: usize,
    /// The batch it was answering: index of its first input and its length.
    pub batch: (usize, usize),
    /// The last lines the adapter process wrote on stderr.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub stderr: Vec<String>,
    /// The answers to the inputs of the batch before `index`, kept.
    #[serde(skip)]
    pub answered: Vec<Outcome<Answer>>,
}

impl Failure {
    /// A failure of `label` on a batch, before the runner places it.
    pub fn new(label: &str, kind: FailureKind, message: String, batch: &[Vector]) -> Self {
        Failure {
            label: label.to_string(),
            kind,
            message,
            input: None,
            index: 0,
            batch: (0, batch.len()),
            stderr: Vec::new(),
            answered: Vec::new(),
        }
    }

    /// The same failure with the answers given before it, naming the input
    /// it stopped at.
    pub fn after(mut self, answered: Vec<Outcome<Answer>>, batch: &[Vector]) -> Self {
        self.index = answered.len();
        self.input = batch.get(answered.len()).cloned();
        self.answered = answered;
        self
    }

    /// The failure of a batch of one input names that input.
    pub fn naming_a_lone_input(self, batch: &[Vector]) -> Self {
        if batch.len() == 1 && self.answered.is_empty() {
            self.after(Vec::new(), batch)
        } else {
            self
        }
    }

    /// Move the failure from batch indices to set indices: the batch
    /// started at `start` in the set.
    pub fn placed(mut self, start: usize) -> Self {
        self.index += start;
        self.batch.0 += start;
        self
    }

    /// Whether the implementation itself failed (a panic, hang, crash,
    /// protocol violation or early exit), as opposed to not being asked.
    pub fn is_own(&self) -> bool {
        self.kind != FailureKind::NotRun
    }
}

impl fmt::Display for Failure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} {}", self.label, self.kind)?;
        match &self.input {
            Some(input) => write!(f, " on input #{} {input}", self.index)?,
            None if self.batch.1 > 0 => write!(
                f,
                " on the batch of inputs #{}..#{}",
                self.batch.0,
                self.batch.0 + self.batch.1 - 1
            )?,
            None => {}
        }
        write!(f, ": {}", self.message)?;
        if !self.stderr.is_empty() {
            write!(f, "; last lines of its stderr:")?;
            for line in &self.stderr {
                write!(f, "\n    | {line}")?;
            }
        }
        Ok(())
    }
}

impl From<Failure> for ImplError {
    fn from(f: Failure) -> Self {
        ImplError::Contained(Box::new(f))
    }
}

/// A whole image from an implementation's own render path.
#[derive(Clone, Debug)]
pub struct ImageAnswers {
    /// Each pixel's answer (an [`Answer::Pixel`]), row by row.
    pub pixels: Vec<Outcome<Answer>>,
    /// Each pixel's cost in the implementation's unit (the Jack program:
    /// Hack VM instructions), when it counts one.
    pub costs: Option<Vec<u64>>,
}

/// The batch sizes of [`Implementation::batch_size`] unless an
/// implementation says otherwise: large for the cheap levels, a few pixels,
/// one image.
pub fn default_batch_size(level: Level) -> usize {
    match level {
        Level::Ops => 4096,
        Level::Sdf => 256,
        Level::Pixels => 4,
        Level::Image => 1,
    }
}

/// What one batch gave: its answers, or why it gave none (a contained
/// failure carries the answers before it).
pub type BatchAnswers = Result<Vec<Outcome<Answer>>, ImplError>;

/// One implementation, as the runner and the localizer see it.
pub trait Implementation: Send + Sync {
    /// The name printed in reports: the label it was opened under, its
    /// cast name with `+VARIANT` for each variant or fault applied
    /// (`ref-f316+sqrt-floor-div`).
    fn label(&self) -> String;

    /// The numbers it computes with (decides the comparison policy).
    fn numbers(&self) -> Numbers;

    /// Whether it answers vectors of `level`.
    fn supports(&self, level: Level) -> bool;

    /// Whether it checks the reference's modelled domain itself, answering
    /// out of domain where the reference does (the default: ours do). A
    /// port without such a check (a user's program that floors any value)
    /// is not compared on the inputs a checking side answers out of
    /// domain: those are counted per operation instead (docs/verdict.md).
    fn checks_domain(&self) -> bool {
        true
    }

    /// How many vectors of `level` one [`Implementation::eval`] call should
    /// get: the runner splits work into batches of this size and runs the
    /// batches in parallel.
    fn batch_size(&self, level: Level) -> usize {
        default_batch_size(level)
    }

    /// Answer every vector of `batch` (all of one level), in order.
    fn eval(&self, batch: &[Vector]) -> Result<Vec<Outcome<Answer>>, ImplError>;

    /// Whether one process answers its batches one after another (a pipe
    /// adapter). The runner then hands it all of a set's batches at once,
    /// in set order, through [`Implementation::eval_in_order`], so which
    /// batch a crash stops it at never depends on thread timing.
    fn in_order(&self) -> bool {
        false
    }

    /// Answer `batches` in set order, handing each one's answers to
    /// `done` with its index as they come. The default evaluates them one
    /// by one; a pipe keeps the next batch in flight.
    fn eval_in_order(&self, batches: &[&[Vector]], done: &mut dyn FnMut(usize, BatchAnswers)) {
        for (k, batch) in batches.iter().enumerate() {
            done(k, self.eval(batch));
        }
    }

    /// The whole image by a path of its own that also counts each pixel's
    /// cost, or `None` (the default): the image is then rendered pixel by
    /// pixel through [`Implementation::eval`]. `progress`: a bar on a
    /// terminal.
    fn render_image(&self, progress: bool) -> Option<Result<ImageAnswers, ImplError>> {
        let _ = progress;
        None
    }

    /// The screen a run of the whole program from its start draws (the
    /// slow path, against the entry points the levels use), or `None` when
    /// it has no such path. `expected_cost` (the image's total cost, when
    /// known) sizes the progress bar.
    fn program_screen(
        &self,
        expected_cost: Option<u64>,
        progress: bool,
    ) -> Option<Result<Bitmap, ImplError>> {
        let _ = (expected_cost, progress);
        None
    }

    /// The GPU adapter it runs on, for an implementation that runs on one
    /// (`harness cast` prints it).
    fn adapter(&self) -> Option<common::AdapterDescription> {
        None
    }

    /// The op trace of one input (see `common::trace` for the convention),
    /// or `Unsupported` when the implementation cannot trace.
    fn trace(&self, input: &Vector) -> Result<Vec<TraceRecord>, ImplError> {
        let _ = input;
        Err(ImplError::Unsupported(format!(
            "{}: op traces",
            self.label()
        )))
    }
}

#[cfg(test)]
mod display_tests {
    use super::*;

    /// A huge or tiny number is shown in scientific notation, never as its
    /// hundreds of digits (issue 35 item 11).
    #[test]
    fn huge_and_tiny_numbers_are_shown_compactly() {
        assert_eq!(Num::F64(1e300).to_string(), "1e300");
        assert_eq!(Num::F64(-1e-300).to_string(), "-1e-300");
        assert_eq!(Num::F32(f32::MAX).to_string(), "3.4028235e38f32");
        // 2^997 and -2^-992 as Float316 triples.
        assert_eq!(
            Num::F316(F316::new(0, 1124, 8192)).to_string(),
            "(0,1124,8192)=1.3393857589828342e300"
        );
        assert_eq!(
            Num::F316(F316::new(1, -865, 8192)).to_string(),
            "(1,-865,8192)=-2.3891548633682403e-299"
        );
        assert_eq!(
            Num::F316(F316::new(0, 127, 12288)).to_string(),
            "(0,127,12288)=1.5"
        );
    }
}
