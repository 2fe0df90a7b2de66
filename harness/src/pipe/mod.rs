//! Kind `pipe`: any program, in any language, that speaks the JSON-lines
//! protocol of `docs/protocol.md` on its stdin and stdout. The harness
//! starts it, reads its handshake (name, numbers, levels, trace support),
//! then sends pipelined batches of requests; pixel requests carry the
//! normalized coordinates the reference computes in the adapter's number
//! type. Every way an adapter can fail (exit before its handshake, crash
//! mid-batch, hang, a malformed line, a wrong id or count) is a contained
//! [`Failure`] naming the adapter, the input or batch, the line and the
//! field, with the last lines of its stderr; the answers before it are
//! kept.

mod process;
pub mod protocol;

#[doc(hidden)]
pub use process::{stderr_tail, stdout_lines};
pub use process::{MAX_LINE_BYTES, STDERR_LINES, STDERR_LINE_BYTES};

use crate::contain::Watchdog;
use crate::implementation::{Answer, BatchAnswers, ImplError, Implementation, Num, Numbers};
use crate::implementation::{Failure, FailureKind};
use common::{Outcome, TraceRecord};
use process::{Adapter, Reply, Request, StartError};
use protocol::{Expect, Handshake};
use reference::{RefImpl, Reference, Scalar};
use std::borrow::Cow;
use std::path::PathBuf;
use std::time::Duration;
use vectors::{Level, Vector};

/// How to start a pipe adapter.
#[derive(Clone, Debug, PartialEq)]
pub struct PipeConfig {
    /// The label the harness gives it in reports.
    pub label: String,
    /// The program to run (looked up on `PATH` unless it has a slash).
    pub program: String,
    /// Its arguments.
    pub args: Vec<String>,
    /// Its working directory (default: the harness's).
    pub dir: Option<PathBuf>,
    /// How long its answers may take.
    pub watchdog: Watchdog,
    /// How long its handshake may take.
    pub handshake: Duration,
    /// Whether the port checks the modelled domain itself (answers
    /// `out_of_domain` where the reference does); default no.
    pub checks_domain: bool,
}

impl PipeConfig {
    /// `program args...` under `label`, with the default watchdog.
    pub fn new(label: &str, program: &str, args: &[&str]) -> Self {
        PipeConfig {
            label: label.to_string(),
            program: program.to_string(),
            args: args.iter().map(|a| a.to_string()).collect(),
            dir: None,
            watchdog: Watchdog::default(),
            handshake: Duration::from_secs(60),
            checks_domain: false,
        }
    }
}

/// A started pipe adapter.
pub struct Pipe {
    label: String,
    hello: Handshake,
    adapter: Adapter,
    watchdog: Watchdog,
    checks_domain: bool,
    /// The reference in the adapter's numbers: pixel coordinates.
    coords: Reference,
    /// ref-f316: the coordinate operations that open a pixel's trace.
    tracer: Reference,
}

impl Pipe {
    /// Start the adapter and read its handshake. A program that cannot be
    /// started is unavailable; one that exits, hangs or writes a bad line
    /// before its handshake is a contained failure.
    pub fn open(config: &PipeConfig) -> Result<Pipe, ImplError> {
        let failure = |kind, message: String, stderr| {
            let mut f = Failure::new(&config.label, kind, message, &[]);
            f.stderr = stderr;
            ImplError::from(f)
        };
        let (adapter, line) = Adapter::start(
            &config.label,
            &config.program,
            &config.args,
            config.dir.as_deref(),
            config.handshake,
        )
        .map_err(|e| match e {
            // A declared adapter that cannot be started is the port's
            // failure (a wrong command or folder), never skipped.
            StartError::Spawn(why) => ImplError::Failed(why),
            StartError::Failed {
                kind,
                message,
                stderr,
            } => failure(kind, message, stderr),
        })?;
        let hello = protocol::read_handshake(&line).map_err(|e| {
            adapter.stop("a bad handshake");
            failure(
                FailureKind::Protocol,
                format!("its handshake line: {e}"),
                adapter.stderr_tail(),
            )
        })?;
        let which = match hello.numbers {
            Numbers::Float316 => RefImpl::F316,
            Numbers::F32 => RefImpl::F32,
            Numbers::F64 | Numbers::Ieee { .. } => RefImpl::F64,
        };
        Ok(Pipe {
            label: config.label.clone(),
            hello,
            adapter,
            watchdog: config.watchdog,
            checks_domain: config.checks_domain,
            coords: Reference::seed(which),
            tracer: Reference::seed(RefImpl::F316),
        })
    }

    /// What the adapter said in its handshake.
    pub fn handshake(&self) -> &Handshake {
        &self.hello
    }

    /// The last lines the adapter wrote on stderr, each cut to an excerpt.
    pub fn stderr_tail(&self) -> Vec<String> {
        self.adapter.stderr_tail()
    }

    fn num(&self, s: Scalar) -> Num {
        match (s.triple, self.hello.numbers) {
            (Some(t), _) => Num::F316(t),
            (None, Numbers::F32) => Num::F32(s.value as f32),
            (None, _) => Num::F64(s.value),
        }
    }

    /// The normalized coordinates of a pixel request.
    fn coords_of(&self, input: &Vector) -> Result<Option<[Num; 2]>, ImplError> {
        let Vector::Pixel(p) = input else {
            return Ok(None);
        };
        match self.coords.pixel_coords(usize::from(p.x), usize::from(p.y)) {
            Outcome::Value([u, v]) => Ok(Some([self.num(u), self.num(v)])),
            trap => Err(ImplError::Failed(format!(
                "the reference's coordinates of {input} give {}",
                trap.map(|_| "a value")
            ))),
        }
    }

    /// Send `batch` (asking for op traces when `trace`) and wait for its
    /// answers under the watchdog.
    fn ask(&self, batch: &[Vector], trace: bool) -> Result<Vec<process::Answered>, ImplError> {
        let sent = self.send(batch, trace)?;
        self.receive(batch, sent)
    }

    /// Send `batch` (asking for op traces when `trace`): where its reply
    /// will come, or `None` for an empty batch.
    fn send(&self, batch: &[Vector], trace: bool) -> Result<Option<Sent>, ImplError> {
        let Some(first) = batch.first() else {
            return Ok(None);
        };
        let level = first.level();
        let mut lines = String::with_capacity(64 * (batch.len() + 1));
        let mut requests = Vec::with_capacity(batch.len());
        // The ids are assigned when the batch is sent; write them after
        // reserving them under the adapter's lock.
        let coords = batch
            .iter()
            .map(|v| self.coords_of(v))
            .collect::<Result<Vec<_>, _>>()?;
        let label = &self.label;
        let sent = self.adapter.send_with(|batch_no, first_id| {
            protocol::batch_line(&mut lines, batch_no, level, batch.len());
            for (k, (v, c)) in batch.iter().zip(&coords).enumerate() {
                protocol::request_line(&mut lines, first_id + k as u64, v, *c, trace);
                requests.push(Request {
                    expect: Expect::of(v, self.hello.numbers),
                    trace,
                });
            }
            (std::mem::take(&mut lines), std::mem::take(&mut requests))
        });
        let (rx, ahead) = sent.map_err(|why| {
            ImplError::from(Failure::new(
                label,
                FailureKind::NotRun,
                format!("the adapter takes no more batches: {why}"),
                batch,
            ))
        })?;
        let limit = self.watchdog.limit(level, batch.len()) * (ahead as u32 + 1);
        Ok(Some(Sent { rx, limit }))
    }

    /// Wait for the reply to `batch`, sent as `sent`, under the watchdog.
    fn receive(
        &self,
        batch: &[Vector],
        sent: Option<Sent>,
    ) -> Result<Vec<process::Answered>, ImplError> {
        let Some(Sent { rx, limit }) = sent else {
            return Ok(Vec::new());
        };
        let reply = match crate::contain::wait(&rx, limit) {
            Some(Some(reply)) => reply,
            Some(None) => {
                let why = format!(
                    "no answer within the watchdog's {:.1} s; stopped",
                    limit.as_secs_f64()
                );
                self.adapter.stop(&why);
                // The answers it gave before it was stopped.
                let answers = crate::contain::wait(&rx, Duration::from_secs(2))
                    .flatten()
                    .map(|r| r.answers)
                    .unwrap_or_default();
                Reply {
                    answers,
                    failure: Some((FailureKind::Hang, why)),
                }
            }
            None => Reply {
                answers: Vec::new(),
                failure: Some((
                    FailureKind::Crash,
                    "its reader ended without a reply".into(),
                )),
            },
        };
        match reply.failure {
            None => Ok(reply.answers),
            Some((kind, message)) => {
                let outcomes = reply.answers.into_iter().map(|(o, _)| o).collect();
                let mut f = Failure::new(&self.label, kind, message, batch).after(outcomes, batch);
                if kind != FailureKind::NotRun {
                    f.stderr = self.adapter.stderr_tail();
                }
                Err(f.into())
            }
        }
    }

    /// The part of `batch` the adapter is sent: the vectors of operations
    /// its handshake lists, and which vectors were left out (`None`: none).
    fn listed<'b>(&self, batch: &'b [Vector]) -> (Cow<'b, [Vector]>, Option<Vec<bool>>) {
        let Some(ops) = &self.hello.ops else {
            return (Cow::Borrowed(batch), None);
        };
        let unlisted: Vec<bool> = batch
            .iter()
            .map(|v| matches!(v, Vector::Op(o) if !ops.contains(&o.op)))
            .collect();
        if !unlisted.contains(&true) {
            return (Cow::Borrowed(batch), None);
        }
        let listed = batch
            .iter()
            .zip(&unlisted)
            .filter(|(_, &u)| !u)
            .map(|(v, _)| v.clone())
            .collect();
        (Cow::Owned(listed), Some(unlisted))
    }

    /// Send `batch` for its answers alone, unless it holds a level the
    /// handshake does not declare.
    fn send_for_eval(&self, batch: &[Vector]) -> Result<Option<Sent>, ImplError> {
        if let Some(v) = batch.iter().find(|v| !self.supports(v.level())) {
            return Err(ImplError::Unsupported(format!(
                "the {} level (its handshake declares {:?})",
                v.level(),
                self.hello.levels
            )));
        }
        self.send(batch, false)
    }
}

/// The outcomes of answers asked for without traces.
fn outcomes(answered: Vec<process::Answered>) -> Vec<Outcome<Answer>> {
    answered.into_iter().map(|(o, _)| o).collect()
}

/// The answers to the listed part of `batch` put back in its order, with
/// `unsupported` for each vector left out (`unlisted`); a failure's kept
/// answers and the input it stopped at are moved the same way.
fn with_unlisted(
    batch: &[Vector],
    unlisted: Option<&[bool]>,
    answers: BatchAnswers,
) -> BatchAnswers {
    let Some(unlisted) = unlisted else {
        return answers;
    };
    let widen = |given: Vec<Outcome<Answer>>| {
        let mut given = given.into_iter();
        let mut out = Vec::with_capacity(batch.len());
        for &left_out in unlisted {
            match left_out {
                true => out.push(Outcome::Value(Answer::Unsupported)),
                false => match given.next() {
                    Some(answer) => out.push(answer),
                    None => break,
                },
            }
        }
        out
    };
    match answers {
        Ok(given) => Ok(widen(given)),
        Err(ImplError::Contained(f)) => {
            let mut f = *f;
            let kept = widen(std::mem::take(&mut f.answered));
            let mut f = f.after(kept, batch);
            f.batch.1 = batch.len();
            Err(f.into())
        }
        Err(e) => Err(e),
    }
}

/// A batch sent: where its reply comes, and how long it may take (its own
/// watchdog limit for each batch ahead of it, and itself).
struct Sent {
    rx: std::sync::mpsc::Receiver<Reply>,
    limit: Duration,
}

/// Batches a pipe keeps sent ahead of the one whose answers it waits for,
/// so the adapter never waits for the harness.
const SENT_AHEAD: usize = 1;

impl Implementation for Pipe {
    fn label(&self) -> String {
        self.label.clone()
    }

    fn numbers(&self) -> Numbers {
        self.hello.numbers
    }

    fn supports(&self, level: Level) -> bool {
        self.hello.levels.contains(&level)
    }

    fn checks_domain(&self) -> bool {
        self.checks_domain
    }

    fn batch_size(&self, level: Level) -> usize {
        match level {
            Level::Ops => 4096,
            Level::Sdf => 512,
            Level::Pixels => 16,
            Level::Image => 1,
        }
    }

    fn eval(&self, batch: &[Vector]) -> Result<Vec<Outcome<Answer>>, ImplError> {
        let (listed, unlisted) = self.listed(batch);
        let answers = self
            .send_for_eval(&listed)
            .and_then(|sent| self.receive(&listed, sent))
            .map(outcomes);
        with_unlisted(batch, unlisted.as_deref(), answers)
    }

    /// One process answers the batches in turn.
    fn in_order(&self) -> bool {
        true
    }

    /// Each batch is sent before the answers of the one ahead of it are
    /// awaited.
    fn eval_in_order(&self, batches: &[&[Vector]], done: &mut dyn FnMut(usize, BatchAnswers)) {
        let listed: Vec<_> = batches.iter().map(|b| self.listed(b)).collect();
        let mut waiting = std::collections::VecDeque::new();
        let mut answer = |k: usize, sent: Result<Option<Sent>, ImplError>| {
            let (part, unlisted) = &listed[k];
            let answers = sent.and_then(|s| self.receive(part, s)).map(outcomes);
            done(k, with_unlisted(batches[k], unlisted.as_deref(), answers));
        };
        for (k, (part, _)) in listed.iter().enumerate() {
            waiting.push_back((k, self.send_for_eval(part)));
            if waiting.len() > SENT_AHEAD {
                if let Some((j, sent)) = waiting.pop_front() {
                    answer(j, sent);
                }
            }
        }
        for (j, sent) in waiting {
            answer(j, sent);
        }
    }

    /// The adapter's trace of `input`. For a pixel, the adapter traces its
    /// pixel function from the coordinates it was given, and the harness
    /// puts the operations that computed them (ref-f316's) in front.
    fn trace(&self, input: &Vector) -> Result<Vec<TraceRecord>, ImplError> {
        if !self.hello.trace || self.hello.numbers != Numbers::Float316 {
            return Err(ImplError::Unsupported(format!("{}: op traces", self.label)));
        }
        if !self.supports(input.level()) {
            return Err(ImplError::Unsupported(format!(
                "the {} level",
                input.level()
            )));
        }
        let answered = self.ask(std::slice::from_ref(input), true)?;
        let own = answered
            .into_iter()
            .next()
            .and_then(|(_, t)| t)
            .unwrap_or_default();
        let mut records = match input {
            Vector::Pixel(p) => {
                self.tracer
                    .trace_pixel_coords(usize::from(p.x), usize::from(p.y))
                    .map_err(|e| ImplError::Failed(e.to_string()))?
                    .records
            }
            _ => Vec::new(),
        };
        records.extend(own);
        Ok(records)
    }
}
