//! One adapter process and the pipeline to it: a writer thread feeds its
//! stdin (so that a full pipe never blocks the caller's watchdog), a
//! reader thread reads its stdout line by line and hands each batch's
//! answers to the caller waiting for them, in the order the batches were
//! sent, and a third thread keeps the last lines of its stderr. Several
//! batches may be in flight at once.

use super::protocol::{self, Expect, Line};
use crate::implementation::Answer;
use crate::implementation::FailureKind;
use common::{Outcome, TraceRecord};
use std::collections::VecDeque;
use std::io::{BufRead, BufReader, Read, Write};
use std::path::Path;
use std::process::{Child, ChildStdout, Command, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc::{self, Receiver, Sender};
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};
use std::time::{Duration, Instant};

/// Lines of stderr kept for a failure's message.
pub const STDERR_LINES: usize = 12;

/// The longest line read from an adapter's stdout (a handshake, an answer
/// or a batch's closing line): an answer with a whole pixel's op trace is
/// a few megabytes. A longer line is the adapter's failure.
pub const MAX_LINE_BYTES: usize = 64 << 20;

/// The most of one stderr line kept (the rest is read and dropped).
pub const STDERR_LINE_BYTES: usize = 4096;

/// How long to wait for a process that closed its stdout to exit, and for
/// its last stderr lines, before reporting it.
const EXIT_GRACE: Duration = Duration::from_secs(2);

/// One answer: the outcome and, when it was asked for, the op trace.
pub type Answered = (Outcome<Answer>, Option<Vec<TraceRecord>>);

/// What came back for one batch: the answers in request order, and why
/// they stop short when they do.
pub struct Reply {
    pub answers: Vec<Answered>,
    pub failure: Option<(FailureKind, String)>,
}

/// One request of a batch as the reader checks its answer.
#[derive(Clone, Copy)]
pub struct Request {
    pub expect: Expect,
    /// Whether the request asked for an op trace.
    pub trace: bool,
}

struct Pending {
    batch: u64,
    first_id: u64,
    requests: Vec<Request>,
    reply: Sender<Reply>,
}

/// What the reader and the callers share: the ways into the process, and
/// why it was stopped.
struct Queue {
    to_writer: Option<Sender<String>>,
    to_reader: Option<Sender<Pending>>,
    next_id: u64,
    next_batch: u64,
    /// Why no more batches are sent (set once).
    stopped: Option<String>,
}

fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(PoisonError::into_inner)
}

/// The parts of a running adapter the threads share.
struct Shared {
    queue: Mutex<Queue>,
    child: Mutex<Child>,
    stderr: Mutex<VecDeque<String>>,
    stderr_done: Mutex<Option<Receiver<()>>>,
    /// Batches sent and not yet answered.
    in_flight: AtomicUsize,
}

impl Shared {
    /// Stop sending batches (recording why, the first time) and kill the
    /// process.
    fn stop(&self, why: &str) {
        {
            let mut q = lock(&self.queue);
            q.stopped.get_or_insert_with(|| why.to_string());
            q.to_writer = None;
            q.to_reader = None;
        }
        let mut child = lock(&self.child);
        let _ = child.kill();
        kill_group(&child);
    }

    /// The last lines of stderr, once the process has closed it (or after
    /// a grace period).
    fn stderr_tail(&self) -> Vec<String> {
        if let Some(done) = lock(&self.stderr_done).take() {
            let _ = done.recv_timeout(EXIT_GRACE);
        }
        lock(&self.stderr).iter().cloned().collect()
    }

    /// How the process ended, in words, waiting a little for it to end.
    fn exit_status(&self) -> String {
        let deadline = Instant::now() + EXIT_GRACE;
        loop {
            match lock(&self.child).try_wait() {
                Ok(Some(status)) => return status_words(status),
                Ok(None) if Instant::now() < deadline => {}
                Ok(None) => return "closed its stdout but is still running".into(),
                Err(e) => return format!("cannot be waited for: {e}"),
            }
            std::thread::sleep(Duration::from_millis(10));
        }
    }
}

/// Kill what is left of the adapter's process group (it leads its own):
/// a child it forked may hold its stdout open after it exits.
fn kill_group(child: &Child) {
    #[cfg(target_os = "linux")]
    if let Some(pid) = rustix::process::Pid::from_raw(child.id() as i32) {
        let _ = rustix::process::kill_process_group(pid, rustix::process::Signal::KILL);
    }
    #[cfg(not(target_os = "linux"))]
    let _ = child;
}

/// Watch for the adapter's own exit: then kill its process group, so that
/// a child holding its stdout lets the reader see the end (and the crash)
/// instead of a hang. Ends when the adapter has exited or was stopped.
fn reap(shared: &Shared) {
    loop {
        std::thread::sleep(Duration::from_millis(20));
        let mut child = lock(&shared.child);
        match child.try_wait() {
            Ok(None) if lock(&shared.queue).stopped.is_none() => {}
            _ => {
                kill_group(&child);
                return;
            }
        }
    }
}

fn status_words(status: std::process::ExitStatus) -> String {
    #[cfg(unix)]
    {
        use std::os::unix::process::ExitStatusExt;
        if let Some(signal) = status.signal() {
            return format!("was killed by signal {signal}");
        }
    }
    match status.code() {
        Some(code) => format!("exited with status {code}"),
        None => format!("ended ({status})"),
    }
}

/// A running adapter process.
pub struct Adapter {
    shared: Arc<Shared>,
}

/// Why an adapter could not be started.
pub enum StartError {
    /// The program could not be run at all.
    Spawn(String),
    /// It ran, and failed before or in its handshake.
    Failed {
        kind: FailureKind,
        message: String,
        stderr: Vec<String>,
    },
}

impl Adapter {
    /// Start `program` with `args` in `dir` and read its handshake line,
    /// waiting at most `handshake` for it.
    pub fn start(
        label: &str,
        program: &str,
        args: &[String],
        dir: Option<&Path>,
        handshake: Duration,
    ) -> Result<(Adapter, String), StartError> {
        let mut command = Command::new(program);
        command
            .args(args)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped());
        if let Some(dir) = dir {
            command.current_dir(dir);
        }
        // A group of its own, so that stopping it stops what it forked.
        #[cfg(target_os = "linux")]
        std::os::unix::process::CommandExt::process_group(&mut command, 0);
        let mut child = command.spawn().map_err(|e| {
            let place = dir
                .map(|d| format!(" in {}", d.display()))
                .unwrap_or_default();
            StartError::Spawn(format!("cannot start `{program}`{place}: {e}"))
        })?;
        let (stdin, stdout, stderr) =
            match (child.stdin.take(), child.stdout.take(), child.stderr.take()) {
                (Some(i), Some(o), Some(e)) => (i, o, e),
                _ => {
                    return Err(StartError::Spawn(format!(
                        "`{program}`: its pipes could not be opened"
                    )))
                }
            };
        let (to_writer, writer_rx) = mpsc::channel::<String>();
        let (to_reader, reader_rx) = mpsc::channel::<Pending>();
        let (stderr_tx, stderr_done) = mpsc::channel();
        let shared = Arc::new(Shared {
            queue: Mutex::new(Queue {
                to_writer: Some(to_writer),
                to_reader: Some(to_reader),
                next_id: 0,
                next_batch: 0,
                stopped: None,
            }),
            child: Mutex::new(child),
            stderr: Mutex::new(VecDeque::new()),
            stderr_done: Mutex::new(Some(stderr_done)),
            in_flight: AtomicUsize::new(0),
        });
        let spawn = |name: &str, f: Box<dyn FnOnce() + Send>| {
            std::thread::Builder::new()
                .name(format!("pipe {name}: {label}"))
                .spawn(f)
                .map(|_| ())
                .map_err(|e| StartError::Spawn(format!("cannot start a thread: {e}")))
        };
        spawn(
            "writer",
            Box::new(move || {
                let mut stdin = std::io::BufWriter::with_capacity(1 << 16, stdin);
                for text in writer_rx {
                    if stdin
                        .write_all(text.as_bytes())
                        .and_then(|()| stdin.flush())
                        .is_err()
                    {
                        break;
                    }
                }
            }),
        )?;
        let watched = Arc::clone(&shared);
        spawn("reaper", Box::new(move || reap(&watched)))?;
        let keep = Arc::clone(&shared);
        spawn(
            "stderr",
            Box::new(move || {
                keep_stderr(&keep, stderr);
                let _ = stderr_tx.send(());
            }),
        )?;
        let (hello_tx, hello_rx) = mpsc::channel();
        let read = Arc::clone(&shared);
        spawn(
            "reader",
            Box::new(move || reader(&read, stdout, hello_tx, reader_rx)),
        )?;
        let adapter = Adapter { shared };
        let hello = match hello_rx.recv_timeout(handshake) {
            Ok(Ok(line)) => return Ok((adapter, line)),
            Ok(Err(Some((kind, why)))) => {
                adapter.shared.stop("a bad handshake");
                StartError::Failed {
                    kind,
                    message: format!("its handshake line: {why}"),
                    stderr: adapter.shared.stderr_tail(),
                }
            }
            Ok(Err(None)) | Err(mpsc::RecvTimeoutError::Disconnected) => StartError::Failed {
                kind: FailureKind::EarlyExit,
                message: format!(
                    "it {} before writing its handshake line",
                    adapter.shared.exit_status()
                ),
                stderr: adapter.shared.stderr_tail(),
            },
            Err(mpsc::RecvTimeoutError::Timeout) => {
                adapter.shared.stop("no handshake");
                StartError::Failed {
                    kind: FailureKind::Hang,
                    message: format!(
                        "no handshake line within {:.1} s; stopped",
                        handshake.as_secs_f64()
                    ),
                    stderr: adapter.shared.stderr_tail(),
                }
            }
        };
        Err(hello)
    }

    /// Send one batch: `write(batch number, first request id)` gives its
    /// lines (the opening line first) and its requests. Returns where its
    /// reply will come, with the number of batches ahead of it; or why the
    /// adapter takes no more batches.
    pub fn send_with(
        &self,
        write: impl FnOnce(u64, u64) -> (String, Vec<Request>),
    ) -> Result<(Receiver<Reply>, u64), String> {
        let mut q = lock(&self.shared.queue);
        if let Some(why) = &q.stopped {
            return Err(why.clone());
        }
        let (lines, requests) = write(q.next_batch, q.next_id);
        let (reply, rx) = mpsc::channel();
        let pending = Pending {
            batch: q.next_batch,
            first_id: q.next_id,
            requests,
            reply,
        };
        q.next_id += pending.requests.len() as u64;
        q.next_batch += 1;
        let ahead = self.shared.in_flight.fetch_add(1, Ordering::Relaxed) as u64;
        let sent = q
            .to_reader
            .as_ref()
            .is_some_and(|r| r.send(pending).is_ok())
            && q.to_writer.as_ref().is_some_and(|w| w.send(lines).is_ok());
        if !sent {
            return Err("its pipes are closed".into());
        }
        Ok((rx, ahead))
    }

    /// Stop the adapter: no more batches, the process killed.
    pub fn stop(&self, why: &str) {
        self.shared.stop(why);
    }

    /// The last lines of its stderr.
    pub fn stderr_tail(&self) -> Vec<String> {
        self.shared.stderr_tail()
    }
}

impl Drop for Adapter {
    fn drop(&mut self) {
        self.shared.stop("closed");
        let _ = lock(&self.shared.child).wait();
    }
}

/// How [`read_bounded`] ended.
#[derive(Debug, PartialEq)]
enum Bounded {
    /// The end of the stream, with nothing read.
    End,
    /// A line (its newline, if any, kept).
    Line,
    /// A line longer than the bound: its first `limit` bytes are in the
    /// buffer, and the rest of it was read and dropped when `skipped`.
    TooLong,
}

/// Read one line into `buf`, keeping at most `limit` bytes of it. With
/// `skip`, the rest of a longer line is read and dropped (a chunk at a
/// time, never held); without, reading stops at the bound.
fn read_bounded(
    from: &mut impl BufRead,
    buf: &mut Vec<u8>,
    limit: usize,
    skip: bool,
) -> std::io::Result<Bounded> {
    buf.clear();
    if from.take(limit as u64 + 1).read_until(b'\n', buf)? == 0 {
        return Ok(Bounded::End);
    }
    if buf.len() <= limit || buf.last() == Some(&b'\n') {
        return Ok(Bounded::Line);
    }
    buf.truncate(limit);
    if skip {
        let mut rest = Vec::new();
        loop {
            rest.clear();
            let n = from.take(1 << 16).read_until(b'\n', &mut rest)?;
            if n == 0 || rest.last() == Some(&b'\n') {
                break;
            }
        }
    }
    Ok(Bounded::TooLong)
}

fn keep_stderr(shared: &Shared, stderr: impl Read) {
    stderr_lines(stderr, STDERR_LINE_BYTES, &shared.stderr);
}

/// Read `stderr` to its end, keeping its last [`STDERR_LINES`] lines in
/// `tail`, each cut to `line_bytes` bytes (the rest of a longer line is
/// read and dropped) and then to an [`protocol::excerpt`].
fn stderr_lines(stderr: impl Read, line_bytes: usize, tail: &Mutex<VecDeque<String>>) {
    let mut lines = BufReader::new(stderr);
    let mut buf = Vec::new();
    loop {
        match read_bounded(&mut lines, &mut buf, line_bytes, true) {
            Ok(Bounded::End) | Err(_) => return,
            Ok(_) => {
                let line = String::from_utf8_lossy(&buf).trim_end().to_string();
                let mut tail = lock(tail);
                if tail.len() == STDERR_LINES {
                    tail.pop_front();
                }
                tail.push_back(protocol::excerpt(&line));
            }
        }
    }
}

/// What the harness keeps of an adapter's stderr `bytes` with lines cut
/// to `line_bytes` (the harness's own bound is [`STDERR_LINE_BYTES`]):
/// for the fuzz target `pipe_reader` (docs/fuzzing.md).
#[doc(hidden)]
pub fn stderr_tail(bytes: &[u8], line_bytes: usize) -> Vec<String> {
    let tail = Mutex::new(VecDeque::new());
    stderr_lines(bytes, line_bytes, &tail);
    tail.into_inner()
        .unwrap_or_else(PoisonError::into_inner)
        .into()
}

/// The lines the harness reads from an adapter's stdout `bytes` with lines
/// of at most `limit` bytes (the harness's own bound is
/// [`MAX_LINE_BYTES`]), and the failure that stops them, if one does: for
/// the fuzz target `pipe_reader` (docs/fuzzing.md).
#[doc(hidden)]
pub fn stdout_lines(bytes: &[u8], limit: usize) -> (Vec<String>, Option<String>) {
    let mut out = bytes;
    let mut buf = String::new();
    let mut lines = Vec::new();
    loop {
        match next_line(&mut out, &mut buf, limit) {
            Ok(true) => lines.push(buf.clone()),
            Ok(false) => return (lines, None),
            Err((_, why)) => return (lines, Some(why)),
        }
    }
}

/// The handshake line, or why there is none: the output ended (`None`) or
/// its first line failed.
type Hello = Result<String, Option<(FailureKind, String)>>;

/// Read one line into `buf`, its line break (`\n`, and any `\r` before
/// it) removed: `Ok(false)` at the end of the output. A line that cannot
/// be read is a crash; one past `limit` bytes ([`MAX_LINE_BYTES`] for an
/// adapter), its line break apart, or not UTF-8 breaks the protocol.
fn next_line(
    out: &mut impl BufRead,
    buf: &mut String,
    limit: usize,
) -> Result<bool, (FailureKind, String)> {
    buf.clear();
    let mut bytes = std::mem::take(buf).into_bytes();
    let read = read_bounded(out, &mut bytes, limit, false).map_err(|e| {
        (
            FailureKind::Crash,
            format!("its output could not be read: {e}"),
        )
    })?;
    match read {
        Bounded::End => return Ok(false),
        Bounded::TooLong => {
            return Err((
                FailureKind::Protocol,
                format!(
                    "it wrote a line longer than {limit} bytes (the harness's bound for one line of the protocol)"
                ),
            ))
        }
        Bounded::Line => {}
    }
    *buf = String::from_utf8(bytes).map_err(|_| {
        (
            FailureKind::Protocol,
            "it wrote a line that is not UTF-8".to_string(),
        )
    })?;
    let trimmed = buf.trim_end_matches(['\n', '\r']).len();
    buf.truncate(trimmed);
    Ok(true)
}

fn reader(shared: &Shared, stdout: ChildStdout, hello: Sender<Hello>, pending: Receiver<Pending>) {
    let mut out = BufReader::with_capacity(1 << 16, stdout);
    let mut buf = String::new();
    let first = match next_line(&mut out, &mut buf, MAX_LINE_BYTES) {
        Ok(true) => Ok(buf.clone()),
        Ok(false) => Err(None),
        Err(e) => Err(Some(e)),
    };
    let ended = first.is_err();
    let _ = hello.send(first);
    if ended {
        return;
    }
    while let Ok(p) = pending.recv() {
        let (answers, failure) = read_batch(shared, &mut out, &mut buf, &p);
        let failed = failure.is_some();
        if let Some((kind, why)) = &failure {
            let stop = match kind {
                FailureKind::Crash => format!("it {why}"),
                _ => format!("it {} on batch {}", kind, p.batch),
            };
            shared.stop(&stop);
        }
        shared.in_flight.fetch_sub(1, Ordering::Relaxed);
        let _ = p.reply.send(Reply { answers, failure });
        if failed {
            // Batches sent after it are not run.
            for later in pending.try_iter() {
                let why = lock(&shared.queue).stopped.clone().unwrap_or_default();
                let _ = later.reply.send(Reply {
                    answers: Vec::new(),
                    failure: Some((
                        FailureKind::NotRun,
                        format!("an earlier batch failed: {why}"),
                    )),
                });
            }
            return;
        }
    }
}

/// Read the answers of one batch and its closing line.
fn read_batch(
    shared: &Shared,
    out: &mut BufReader<ChildStdout>,
    buf: &mut String,
    p: &Pending,
) -> (Vec<Answered>, Option<(FailureKind, String)>) {
    let n = p.requests.len();
    let mut answers = Vec::with_capacity(n);
    let protocol = |k: usize, e: String| {
        Some((
            FailureKind::Protocol,
            format!(
                "answer line {} of batch {} ({n} requests): {e}",
                k + 1,
                p.batch
            ),
        ))
    };
    loop {
        let k = answers.len();
        match next_line(out, buf, MAX_LINE_BYTES) {
            Ok(true) => {}
            Ok(false) => {
                let status = shared.exit_status();
                return (
                    answers,
                    Some((
                        FailureKind::Crash,
                        format!(
                            "{status} after answering {k} of the {n} inputs of batch {}",
                            p.batch
                        ),
                    )),
                );
            }
            Err(failure) => return (answers, Some(failure)),
        }
        let request = p.requests.get(k).or(p.requests.last());
        let Some(request) = request else {
            return (answers, protocol(k, "an empty batch".into()));
        };
        match protocol::read_line(buf, &request.expect) {
            // An answer to another request reads as the wrong type for this
            // one: say what is really wrong, its id.
            Err(e) => {
                let expected = p.first_id + k as u64;
                let message = match answer_id(buf) {
                    Some(id) if id != expected && k < n => format!(
                        "field `id`: {id}, expected {expected} (answers come in request order); the line: `{}`",
                        protocol::excerpt(buf)
                    ),
                    _ => e.to_string(),
                };
                return (answers, protocol(k, message));
            }
            Ok(Line::End { batch, count }) => {
                let problem = if batch != p.batch {
                    Some(format!(
                        "field `batch`: closes batch {batch}, expected {}",
                        p.batch
                    ))
                } else if count != n as u64 || k != n {
                    Some(format!(
                        "field `count`: {count}, after {k} answers to {n} requests"
                    ))
                } else {
                    None
                };
                return match problem {
                    Some(m) => (
                        answers,
                        protocol(k, format!("{m}; the line: `{}`", protocol::excerpt(buf))),
                    ),
                    None => (answers, None),
                };
            }
            Ok(Line::Answer { id, outcome, trace }) => {
                let expected = p.first_id + k as u64;
                let problem = if k == n {
                    Some(format!(
                        "field `id`: {id} is an answer beyond the batch's {n} requests (its closing line {{\"batch\":{},\"count\":{n}}} is missing)",
                        p.batch
                    ))
                } else if id != expected {
                    Some(format!(
                        "field `id`: {id}, expected {expected} (answers come in request order)"
                    ))
                } else if request.trace && trace.is_none() {
                    Some("field `trace`: missing, and the request asked for the op trace".into())
                } else {
                    None
                };
                if let Some(m) = problem {
                    return (
                        answers,
                        protocol(k, format!("{m}; the line: `{}`", protocol::excerpt(buf))),
                    );
                }
                answers.push((outcome, trace));
            }
        }
    }
}

/// The `id` of an answer line that may not parse as the answer expected.
fn answer_id(line: &str) -> Option<u64> {
    serde_json::from_str::<serde_json::Value>(line)
        .ok()?
        .get("id")?
        .as_u64()
}
