//! Containment: every implementation fails like a real component. A panic,
//! an endless loop, a crashed or misbehaving adapter process becomes a
//! [`Failure`] that names the implementation and the input (or the batch)
//! it was working on, keeps the answers that came before, and lets the
//! other implementations go on; the harness itself neither panics nor
//! hangs. The failure types live with the error types they belong to, in
//! `implementation`.
//!
//! [`Contained`] wraps any in-process [`Implementation`]: each call runs
//! on a worker thread under `catch_unwind`, and a [`Watchdog`] turns an
//! answer that never comes into a reported hang. Workers are reused from
//! call to call; only one that hangs is replaced (the looping thread is
//! left behind; it holds its own reference to the implementation, so
//! nothing it uses is freed under it). Pipe adapters report their own
//! failures the same way (`pipe`).

use crate::implementation::{
    Answer, Bitmap, Failure, FailureKind, ImageAnswers, ImplError, Implementation, Numbers,
};
use common::{Outcome, TraceRecord};
use std::any::Any;
use std::cell::RefCell;
use std::panic::{self, AssertUnwindSafe};
use std::sync::{mpsc, Arc, Mutex, Once, PoisonError};
use std::time::{Duration, Instant};
use vectors::{Level, Vector};

/// How long an answer may take before it is reported as a hang.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Watchdog {
    /// Allowed for any batch, whatever its size.
    pub base: Duration,
    /// Allowed on top of `base` for each input of a batch, per level
    /// (ops, sdf, pixels, image).
    pub per_input: [Duration; 4],
}

/// The longest duration a user may set (`watchdog_s`, `HARNESS_WATCHDOG_S`,
/// a shader's `timeout_s`): one day.
pub const MAX_DURATION_S: u64 = 86_400;

/// `s` as a duration when it lies in (0, [`MAX_DURATION_S`]].
pub fn user_seconds(s: f64) -> Option<Duration> {
    (s.is_finite() && s > 0.0 && s <= MAX_DURATION_S as f64).then(|| Duration::from_secs_f64(s))
}

impl Default for Watchdog {
    /// Generous for the slowest built-in (the Jack program on the Hack VM
    /// emulator in the dev profile: about 1 s per pixel on a loaded
    /// machine, a minute or two per image). `HARNESS_WATCHDOG_S` sets a
    /// fixed number of seconds per batch instead.
    fn default() -> Self {
        if let Ok(text) = std::env::var("HARNESS_WATCHDOG_S") {
            match text.parse::<f64>().ok().and_then(user_seconds) {
                Some(limit) => return Watchdog::fixed(limit),
                None => eprintln!(
                    "warning: HARNESS_WATCHDOG_S: `{text}` is not a number of seconds in \
                     (0, {MAX_DURATION_S}]: not used, the default watchdog applies"
                ),
            }
        }
        Watchdog {
            base: Duration::from_secs(30),
            per_input: [
                Duration::from_millis(2),
                Duration::from_millis(50),
                Duration::from_secs(5),
                Duration::from_secs(900),
            ],
        }
    }
}

impl Watchdog {
    /// The same time for every batch.
    pub fn fixed(limit: Duration) -> Self {
        Watchdog {
            base: limit,
            per_input: [Duration::ZERO; 4],
        }
    }

    /// The time allowed for a batch of `n` inputs of `level`.
    pub fn limit(&self, level: Level, n: usize) -> Duration {
        let i = Level::ALL.iter().position(|l| *l == level).unwrap_or(0);
        let n = u32::try_from(n).unwrap_or(u32::MAX);
        let per = self.per_input[i].checked_mul(n).unwrap_or(Duration::MAX);
        self.base.saturating_add(per)
    }
}

thread_local! {
    /// The last panic of a contained worker thread: message and location.
    static LAST_PANIC: RefCell<Option<String>> = const { RefCell::new(None) };
}

/// Worker threads of contained implementations are named with this prefix:
/// their panics are recorded for the failure instead of printed.
const WORKER: &str = "contained:";

fn install_panic_hook() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let previous = panic::take_hook();
        panic::set_hook(Box::new(move |info| {
            let contained = std::thread::current()
                .name()
                .is_some_and(|n| n.starts_with(WORKER));
            if contained {
                let at = info
                    .location()
                    .map(|l| format!(" at {}:{}:{}", l.file(), l.line(), l.column()))
                    .unwrap_or_default();
                let message = payload_text(info.payload());
                LAST_PANIC.with(|p| *p.borrow_mut() = Some(format!("{message}{at}")));
            } else {
                previous(info);
            }
        }));
    });
}

fn payload_text(payload: &(dyn Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "a panic with a non-text payload".to_string())
}

/// Run `f`, turning a panic into its message (with its location).
fn catch<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    panic::catch_unwind(AssertUnwindSafe(f)).map_err(|payload| {
        LAST_PANIC
            .with(|p| p.borrow_mut().take())
            .unwrap_or_else(|| payload_text(payload.as_ref()))
    })
}

/// A job for a worker thread.
type Job = Box<dyn FnOnce() + Send>;

/// A thread that runs contained jobs one after another, so that a batch
/// costs a message rather than a thread.
struct Worker {
    jobs: mpsc::Sender<Job>,
}

/// The workers waiting for a job, shared by every contained implementation:
/// as many as ever ran at once.
static IDLE: Mutex<Vec<Worker>> = Mutex::new(Vec::new());

impl Worker {
    fn spawn() -> std::io::Result<Worker> {
        let (jobs, queue) = mpsc::channel::<Job>();
        std::thread::Builder::new()
            .name(format!("{WORKER}worker"))
            .spawn(move || {
                for job in queue {
                    job();
                }
            })?;
        Ok(Worker { jobs })
    }
}

fn idle() -> std::sync::MutexGuard<'static, Vec<Worker>> {
    IDLE.lock().unwrap_or_else(PoisonError::into_inner)
}

/// Run `job` on a worker thread and wait at most `limit` for it. `None`: it
/// did not finish in time. The worker that ran it goes back to the idle
/// ones; one that hangs is left behind with its job (its queue closes, so
/// its thread ends if the job ever does), and a new one takes its place
/// when needed.
fn on_worker<T: Send + 'static>(
    label: &str,
    limit: Duration,
    job: impl FnOnce() -> T + Send + 'static,
) -> Result<Option<T>, ImplError> {
    install_panic_hook();
    let (tx, rx) = mpsc::channel();
    let mut job: Job = Box::new(move || {
        let _ = tx.send(job());
    });
    let worker = loop {
        let worker = match idle().pop() {
            Some(w) => w,
            None => Worker::spawn().map_err(|e| {
                ImplError::Failed(format!("{label}: cannot start a worker thread: {e}"))
            })?,
        };
        match worker.jobs.send(job) {
            Ok(()) => break worker,
            // That worker's thread is gone: the job comes back for another.
            Err(mpsc::SendError(back)) => job = back,
        }
    };
    let answer = wait(&rx, limit).ok_or_else(|| {
        // The jobs catch panics, so one always sends unless its thread is
        // gone.
        ImplError::Failed(format!(
            "{label}: its worker thread ended without an answer"
        ))
    })?;
    if answer.is_some() {
        idle().push(worker);
    }
    Ok(answer)
}

/// Run a set-up step `job` (a shader's compilation) on a contained worker
/// and wait at most `limit`, counted from this call: `Some(v)` when it
/// finished in time, `None` when it did not. A job past its limit is left
/// on its worker, which holds everything the job uses; what it returns
/// when it ends is dropped. A panic is a failure of `label`.
pub fn within<T: Send + 'static>(
    label: &str,
    limit: Duration,
    job: impl FnOnce() -> T + Send + 'static,
) -> Result<Option<T>, ImplError> {
    let start = Instant::now();
    match on_worker(label, limit, move || catch(job))? {
        // A result that came after the limit (this thread waited late) is
        // past it all the same.
        Some(Ok(value)) if start.elapsed() <= limit => Ok(Some(value)),
        Some(Ok(_)) | None => Ok(None),
        Some(Err(message)) => Err(ImplError::Failed(format!("{label} panicked: {message}"))),
    }
}

/// Wait at most `limit` for a value on `rx`: `Some(Some(v))` when it came,
/// `Some(None)` when the time ran out, `None` when the sender is gone. The
/// runner's jobs wait here on the runner's own threads
/// (`runner::run`), so the global rayon pool stays free for
/// implementations that parallelise inside a batch.
pub fn wait<T>(rx: &mpsc::Receiver<T>, limit: Duration) -> Option<Option<T>> {
    match rx.recv_timeout(limit) {
        Ok(v) => Some(Some(v)),
        Err(mpsc::RecvTimeoutError::Timeout) => Some(None),
        Err(mpsc::RecvTimeoutError::Disconnected) => None,
    }
}

/// An in-process implementation behind the containment layer.
pub struct Contained {
    inner: Arc<dyn Implementation>,
    watchdog: Watchdog,
}

impl Contained {
    /// Contain `inner` under `watchdog`.
    pub fn new(inner: Box<dyn Implementation>, watchdog: Watchdog) -> Self {
        Contained {
            inner: Arc::from(inner),
            watchdog,
        }
    }

    /// Contain `inner` under the default watchdog.
    pub fn boxed(inner: Box<dyn Implementation>) -> Box<dyn Implementation> {
        Box::new(Contained::new(inner, Watchdog::default()))
    }
}

/// Answer `batch` one input at a time up to the first that panics: the
/// answers before it and the panic's message.
fn answers_before_panic(
    imp: &dyn Implementation,
    batch: &[Vector],
) -> (Vec<Outcome<Answer>>, Option<String>) {
    let mut answered = Vec::new();
    for v in batch {
        match catch(|| imp.eval(std::slice::from_ref(v))) {
            Ok(Ok(mut a)) if a.len() == 1 => answered.extend(a.pop()),
            // The batch as a whole panicked, this input alone does not:
            // keep what came before and name this input.
            Ok(_) => return (answered, None),
            Err(message) => return (answered, Some(message)),
        }
    }
    (answered, None)
}

enum Evaluated {
    Done(Result<Vec<Outcome<Answer>>, ImplError>),
    Panicked(Vec<Outcome<Answer>>, String),
}

impl Contained {
    /// One of the inner implementation's whole-image paths, with a panic
    /// contained as a failure. No watchdog: those paths bound their own
    /// time (the Jack program by its instruction budget, a shader by its
    /// dispatch time limit), and a whole image has no batch to time.
    fn whole<T>(
        &self,
        run: impl FnOnce(&dyn Implementation) -> Option<Result<T, ImplError>>,
        what: &str,
    ) -> Option<Result<T, ImplError>> {
        install_panic_hook();
        match catch(|| run(self.inner.as_ref())) {
            Ok(result) => result,
            Err(message) => Some(Err(Failure::new(
                &self.label(),
                FailureKind::Panic,
                format!("{what}: {message}"),
                &[],
            )
            .into())),
        }
    }
}

impl Implementation for Contained {
    fn label(&self) -> String {
        self.inner.label()
    }

    fn numbers(&self) -> Numbers {
        self.inner.numbers()
    }

    fn supports(&self, level: Level) -> bool {
        self.inner.supports(level)
    }

    fn batch_size(&self, level: Level) -> usize {
        self.inner.batch_size(level)
    }

    fn adapter(&self) -> Option<common::AdapterDescription> {
        self.inner.adapter()
    }

    fn checks_domain(&self) -> bool {
        self.inner.checks_domain()
    }

    /// In order when the inner one is; each batch still goes through
    /// [`Contained::eval`].
    fn in_order(&self) -> bool {
        self.inner.in_order()
    }

    fn eval(&self, batch: &[Vector]) -> Result<Vec<Outcome<Answer>>, ImplError> {
        let Some(first) = batch.first() else {
            return Ok(Vec::new());
        };
        let label = self.label();
        let limit = self.watchdog.limit(first.level(), batch.len());
        let inner = Arc::clone(&self.inner);
        let owned = batch.to_vec();
        let result = on_worker(&label, limit, move || match catch(|| inner.eval(&owned)) {
            Ok(done) => Evaluated::Done(done),
            Err(whole) => {
                let (answered, message) = answers_before_panic(inner.as_ref(), &owned);
                Evaluated::Panicked(answered, message.unwrap_or(whole))
            }
        })?;
        match result {
            Some(Evaluated::Done(done)) => done,
            Some(Evaluated::Panicked(answered, message)) => {
                Err(Failure::new(&label, FailureKind::Panic, message, batch)
                    .after(answered, batch)
                    .into())
            }
            None => Err(Failure::new(
                &label,
                FailureKind::Hang,
                format!(
                    "no answer within the watchdog's {:.1} s",
                    limit.as_secs_f64()
                ),
                batch,
            )
            .naming_a_lone_input(batch)
            .into()),
        }
    }

    fn render_image(&self, progress: bool) -> Option<Result<ImageAnswers, ImplError>> {
        self.whole(|inner| inner.render_image(progress), "the whole image")
    }

    fn program_screen(
        &self,
        expected_cost: Option<u64>,
        progress: bool,
    ) -> Option<Result<Bitmap, ImplError>> {
        self.whole(
            |inner| inner.program_screen(expected_cost, progress),
            "the whole program's screen",
        )
    }

    fn trace(&self, input: &Vector) -> Result<Vec<TraceRecord>, ImplError> {
        let label = self.label();
        let limit = self.watchdog.limit(input.level(), 1) * 4;
        let inner = Arc::clone(&self.inner);
        let owned = input.clone();
        let one = std::slice::from_ref(input);
        match on_worker(&label, limit, move || catch(|| inner.trace(&owned)))? {
            Some(Ok(trace)) => trace,
            Some(Err(message)) => Err(Failure::new(&label, FailureKind::Panic, message, one)
                .after(Vec::new(), one)
                .into()),
            None => Err(Failure::new(
                &label,
                FailureKind::Hang,
                format!(
                    "no trace within the watchdog's {:.1} s",
                    limit.as_secs_f64()
                ),
                one,
            )
            .after(Vec::new(), one)
            .into()),
        }
    }
}

#[cfg(test)]
mod duration_tests {
    use super::*;

    /// A long fixed watchdog times a large batch without a multiply overflow
    /// (1e19 s used to panic two runner threads), and user durations are
    /// bounded to one day.
    #[test]
    fn limits_saturate_and_user_seconds_are_bounded() {
        let w = Watchdog {
            base: Duration::from_secs(86_400),
            per_input: [Duration::from_secs(u64::MAX / 2); 4],
        };
        assert_eq!(w.limit(Level::Image, 1 << 20), Duration::MAX);
        assert_eq!(user_seconds(86_400.0), Some(Duration::from_secs(86_400)));
        for bad in [1e300, 1e19, 86_400.5, 0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert_eq!(user_seconds(bad), None, "{bad}");
        }
    }

    /// A set-up step past its limit is `None` and left on its worker; one
    /// in time is its value; a panic is a failure naming the label.
    #[test]
    fn a_step_within_its_limit_or_not() {
        let slow = within("slow", Duration::from_millis(20), || {
            std::thread::sleep(Duration::from_millis(500));
            1
        });
        assert!(matches!(slow, Ok(None)), "{slow:?}");
        assert!(matches!(
            within("quick", Duration::from_secs(60), || 2),
            Ok(Some(2))
        ));
        let panicked = within("boom", Duration::from_secs(60), || -> u8 {
            panic!("no driver")
        });
        match panicked {
            Err(ImplError::Failed(message)) => {
                assert!(message.starts_with("boom panicked: no driver"), "{message}")
            }
            other => panic!("{other:?}"),
        }
    }
}
