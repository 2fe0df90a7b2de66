//! Every implementation fails like a real component: a pipe adapter that
//! exits before its handshake, crashes mid-batch, hangs, writes a garbage
//! line, a wrong id or a wrong count, and an in-process implementation
//! that panics or loops for ever (a test fault), are each contained and
//! named, with the input and the answers that came before; `harness
//! check` calls the commit bad.

use common::{Op, Outcome, F316};
use harness::cast::Cast;
use harness::contain::{Contained, Watchdog};
use harness::implementation::{
    Answer, Bitmap, Failure, FailureKind, ImageAnswers, ImplError, Implementation, Numbers,
};
use harness::pipe::{Pipe, PipeConfig};
use harness::runner::{diff_set, RunOptions};
use harness_cli::commands::check::{no_divergence_between, Bisect};
use std::time::Duration;
use vectors::{Level, OpVector, Vector, VectorSet};

use crate::support;

const ADAPTER: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/adapters/misbehaving.py");

/// Ten `double` vectors: the misbehaving adapter answers the first five.
fn doubles() -> VectorSet {
    let vectors = (0..10)
        .map(|i| {
            Vector::Op(OpVector {
                category: "double".into(),
                op: Op::Double,
                a: F316::new(i % 2, 120 + i, 8192 + 100 * i),
                b: None,
            })
        })
        .collect();
    VectorSet::new("doubles", Level::Ops, "", None, vectors)
}

fn misbehaving(mode: &str) -> Result<Pipe, ImplError> {
    let mut config = PipeConfig::new(&format!("py-{mode}"), "python3", &[ADAPTER, mode]);
    config.watchdog = Watchdog::fixed(Duration::from_secs(3));
    Pipe::open(&config)
}

fn failure(e: &ImplError) -> &Failure {
    match e {
        ImplError::Contained(f) => f,
        other => panic!("a contained failure expected, got {other}"),
    }
}

/// Run the doubles through ref-f316 and `subject`: the subject's failure,
/// after checking that the answers before it were kept and agree.
fn contained_run(subject: &dyn Implementation, kept: usize) -> Failure {
    contained_run_on(&doubles(), subject, kept)
}

/// [`contained_run`] on `set`.
fn contained_run_on(set: &VectorSet, subject: &dyn Implementation, kept: usize) -> Failure {
    let reference = Cast::builtin().open("ref-f316").unwrap();
    let report = diff_set(&[reference.as_ref(), subject], set, RunOptions::default());
    let (label, e) = report.failures().next().expect("the subject failed");
    assert_eq!(label, subject.label());
    let f = failure(e).clone();
    assert_eq!(f.index, kept, "{f}");
    if let Some(input) = &f.input {
        assert_eq!(Some(input), set.vectors.get(kept), "{f}");
    }
    match report.comparisons.first() {
        Some(c) => {
            assert_eq!(
                c.vectors, kept,
                "the answers before the failure are compared"
            );
            assert!(!c.diverged);
        }
        None => assert_eq!(kept, 0, "nothing to compare"),
    }
    f
}

#[test]
fn an_adapter_that_exits_before_its_handshake_is_named_with_its_stderr() {
    let e = misbehaving("early-exit").err().expect("no handshake");
    let f = failure(&e);
    assert_eq!(f.kind, FailureKind::EarlyExit);
    let text = f.to_string();
    assert!(
        text.contains("py-early-exit exited before its handshake"),
        "{text}"
    );
    assert!(text.contains("exited with status 3"), "{text}");
    assert!(text.contains("my-port: cannot open port.cfg"), "{text}");
}

#[test]
fn an_adapter_that_crashes_mid_batch_keeps_its_answers_and_shows_its_stderr() {
    let pipe = misbehaving("crash").unwrap();
    let f = contained_run(&pipe, 5);
    assert_eq!(f.kind, FailureKind::Crash);
    let text = f.to_string();
    assert!(
        text.contains("exited with status 1 after answering 5 of the 10 inputs"),
        "{text}"
    );
    assert!(
        text.contains("ZeroDivisionError: in my_port.double"),
        "{text}"
    );
    // It takes no more batches afterwards, and says why: the crash.
    let again = pipe.eval(&doubles().vectors).unwrap_err();
    let f = failure(&again);
    assert_eq!(f.kind, FailureKind::NotRun);
    assert!(
        f.message.contains(
            "the adapter takes no more batches: it exited with status 1 after answering 5 of the 10 inputs of batch 0"
        ),
        "{f}"
    );
}

#[test]
fn an_adapter_that_hangs_is_stopped_by_the_watchdog() {
    let pipe = misbehaving("hang").unwrap();
    let f = contained_run(&pipe, 5);
    assert_eq!(f.kind, FailureKind::Hang);
    assert!(
        f.to_string()
            .contains("no answer within the watchdog's 3.0 s"),
        "{f}"
    );
}

#[test]
fn a_garbage_line_is_named_with_the_line() {
    let f = contained_run(&misbehaving("garbage").unwrap(), 5);
    assert_eq!(f.input, Some(doubles().vectors[5].clone()));
    assert_eq!(f.kind, FailureKind::Protocol);
    let text = f.to_string();
    assert!(text.contains("answer line 6 of batch 0"), "{text}");
    assert!(text.contains("not JSON"), "{text}");
    assert!(text.contains(r#"`{"id": 5, "value": [0, 1`"#), "{text}");
}

#[test]
fn a_wrong_id_is_named_with_the_field() {
    let f = contained_run(&misbehaving("wrong-id").unwrap(), 5);
    assert_eq!(f.kind, FailureKind::Protocol);
    assert!(f.to_string().contains("field `id`: 12, expected 5"), "{f}");
}

#[test]
fn a_wrong_count_is_named_with_the_field() {
    let f = contained_run(&misbehaving("wrong-count").unwrap(), 10);
    assert_eq!(f.kind, FailureKind::Protocol);
    assert!(
        f.to_string()
            .contains("field `count`: 11, after 10 answers to 10 requests"),
        "{f}"
    );
}

/// An adapter that exits leaving a child that holds its stdout is the crash
/// at its exit, not a hang at the watchdog, and the child is killed with
/// the adapter's process group.
#[test]
fn an_adapter_whose_child_holds_its_stdout_crashes_at_its_exit() {
    let pipe = misbehaving("fork-child").unwrap();
    // (A hang would be the 3 s watchdog's, not a crash.)
    let f = contained_run(&pipe, 5);
    assert_eq!(f.kind, FailureKind::Crash, "{f}");
    assert!(
        f.to_string()
            .contains("exited with status 1 after answering 5"),
        "{f}"
    );
    let child: u32 = f
        .stderr
        .iter()
        .find_map(|l| l.strip_prefix("child ")?.parse().ok())
        .expect("the child's pid on stderr");
    // Killed (a zombie until init reaps it, then gone).
    let deadline = std::time::Instant::now() + Duration::from_secs(5);
    loop {
        let state = std::fs::read_to_string(format!("/proc/{child}/stat")).unwrap_or_default();
        if state.is_empty() || state.contains(") Z ") {
            break;
        }
        assert!(
            std::time::Instant::now() < deadline,
            "still running: {state}"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// Answers in the wrong order are named by their id, even where the answer
/// that came has another type than the one expected (a `gt`'s boolean for
/// a `double`'s triple).
#[test]
fn answers_out_of_order_are_an_id_error_whatever_their_type() {
    let mut set = doubles();
    set.vectors[6] = Vector::Op(OpVector {
        category: "gt".into(),
        op: Op::Gt,
        a: F316::new(0, 130, 9000),
        b: Some(F316::new(0, 131, 9000)),
    });
    let f = contained_run_on(&set, &misbehaving("swap").unwrap(), 5);
    assert_eq!(f.kind, FailureKind::Protocol, "{f}");
    assert!(f.to_string().contains("field `id`: 6, expected 5"), "{f}");
}

/// A line without an end, on an answer or on the handshake, is a protocol
/// failure once it passes the harness's bound, long before any watchdog,
/// and holds at most that bound; a stderr line without an end is read and
/// dropped past its first kilobytes, and the answers after it count.
#[test]
fn a_line_without_an_end_is_refused_at_its_bound() {
    let f = contained_run(&misbehaving("long-line").unwrap(), 5);
    assert_eq!(f.kind, FailureKind::Protocol);
    assert!(
        f.to_string().contains("a line longer than 67108864 bytes"),
        "{f}"
    );
    let e = misbehaving("long-handshake").err().expect("no handshake");
    let f = failure(&e);
    assert_eq!(f.kind, FailureKind::Protocol);
    assert!(
        f.to_string()
            .contains("its handshake line: it wrote a line longer than"),
        "{f}"
    );
    let pipe = misbehaving("long-stderr").unwrap();
    let report = diff_set(
        &[Cast::builtin().open("ref-f316").unwrap().as_ref(), &pipe],
        &doubles(),
        RunOptions::default(),
    );
    // The sixth answer is where `long-stderr` behaves: it has no fault.
    assert_eq!(report.failures().count(), 0, "{report:?}");
    let tail = pipe.stderr_tail();
    assert!(tail.iter().any(|l| l == "my-port: warming up"), "{tail:?}");
    assert!(tail.iter().all(|l| l.len() < 5000), "kept in excerpt");
}

/// A test fault: ref-f316, except that it panics on the vector `on`
/// (`panics`) or never answers it (`loops`).
struct Faulty {
    inner: Box<dyn Implementation>,
    on: Vector,
    panics: bool,
}

impl Implementation for Faulty {
    fn label(&self) -> String {
        format!("ref-f316+{}", if self.panics { "panics" } else { "loops" })
    }
    fn numbers(&self) -> Numbers {
        Numbers::Float316
    }
    fn supports(&self, level: Level) -> bool {
        self.inner.supports(level)
    }
    fn eval(&self, batch: &[Vector]) -> Result<Vec<Outcome<Answer>>, ImplError> {
        if let Some(v) = batch.iter().find(|v| **v == self.on) {
            if self.panics {
                let overflow = i16::MAX;
                panic!("attempt to multiply with overflow: {overflow} * 2 in {v}");
            }
            loop {
                std::thread::sleep(Duration::from_secs(1));
            }
        }
        self.inner.eval(batch)
    }
}

/// [`Faulty`] on the sixth of the doubles.
fn faulty(panics: bool) -> Contained {
    faulty_on(doubles().vectors[5].clone(), panics)
}

fn faulty_on(on: Vector, panics: bool) -> Contained {
    let inner = Cast::builtin().open("ref-f316").unwrap();
    Contained::new(
        Box::new(Faulty { inner, on, panics }),
        Watchdog::fixed(Duration::from_secs(2)),
    )
}

/// The agreement check of bindings.rs, jack.rs and gpu.rs fails a subject
/// that answers its first inputs and then crashes, though every answer it
/// kept agrees with ref-f316.
#[test]
fn the_agreement_check_fails_a_subject_that_crashes_after_answering() {
    let ops = vectors::load_named(vectors::named::small_set_name(Level::Ops)).unwrap();
    let subject = faulty_on(ops.vectors[7].clone(), true);
    let checked = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        support::assert_agrees_with_ref_f316_on_the_small_sets(&subject)
    }));
    let payload = checked.expect_err("a crash at input #7 fails the check");
    let message = payload
        .downcast_ref::<String>()
        .cloned()
        .unwrap_or_default();
    assert!(
        message.contains("ref-f316+panics panicked on input #7"),
        "{message}"
    );
}

#[test]
fn an_in_process_panic_becomes_a_failure_of_its_input() {
    let f = contained_run(&faulty(true), 5);
    assert_eq!(f.kind, FailureKind::Panic);
    let text = f.to_string();
    assert!(
        text.starts_with("ref-f316+panics panicked on input #5 double((1,125,8692))"),
        "{text}"
    );
    assert!(text.contains("attempt to multiply with overflow"), "{text}");
    assert!(
        text.contains("containment.rs:"),
        "the panic's location: {text}"
    );
}

#[test]
fn an_in_process_endless_loop_becomes_a_hang_of_its_batch() {
    let f = contained_run(&faulty(false), 0);
    assert_eq!(f.kind, FailureKind::Hang);
    assert!(f.input.is_none(), "a hang names its batch");
    assert!(
        f.to_string().contains("on the batch of inputs #0..#9"),
        "{f}"
    );
}

#[test]
fn check_calls_a_contained_panic_or_hang_of_the_implementation_under_test_bad() {
    let reference = Cast::builtin().open("ref-f316").unwrap();
    for subject in [faulty(true), faulty(false)] {
        let verdict = no_divergence_between(reference.as_ref(), &subject, &[doubles()]).unwrap();
        let Bisect::Bad(why) = &verdict else {
            panic!("bad expected: {verdict:?}")
        };
        assert!(why.contains(&subject.label()), "{why}");
        assert_eq!(verdict.exit_code(), 1);
    }
}

/// An implementation with whole-image paths only: it draws a two-pixel
/// screen and a two-pixel image with its costs, or panics drawing them.
struct WholeProgram {
    panics: bool,
}

/// The two pixels [`WholeProgram`] renders.
fn two_pixels() -> Vec<Outcome<Answer>> {
    [(F316::ONE, true), (F316::ZERO, false)]
        .map(|(shade, white)| {
            Outcome::Value(Answer::Pixel {
                shade: harness::implementation::Num::F316(shade),
                white,
            })
        })
        .to_vec()
}

impl Implementation for WholeProgram {
    fn label(&self) -> String {
        "whole-program".into()
    }
    fn numbers(&self) -> Numbers {
        Numbers::Float316
    }
    fn supports(&self, _: Level) -> bool {
        false
    }
    fn eval(&self, _: &[Vector]) -> Result<Vec<Outcome<Answer>>, ImplError> {
        Ok(Vec::new())
    }
    fn render_image(&self, _: bool) -> Option<Result<ImageAnswers, ImplError>> {
        assert!(!self.panics, "the image broke");
        Some(Ok(ImageAnswers {
            pixels: two_pixels(),
            costs: Some(vec![3, 4]),
        }))
    }
    fn program_screen(&self, _: Option<u64>, _: bool) -> Option<Result<Bitmap, ImplError>> {
        assert!(!self.panics, "the screen broke");
        Some(Ok(Bitmap {
            width: 2,
            height: 1,
            white: vec![true, false],
        }))
    }
}

/// Containment keeps an implementation's whole-image paths (the nightly's
/// Jack image with its costs and the whole program's screen come through
/// them), and contains their panics; an implementation without them has
/// none once contained either.
#[test]
fn the_whole_image_paths_pass_through_containment() {
    let contained = |inner: Box<dyn Implementation>| {
        Contained::new(inner, Watchdog::fixed(Duration::from_secs(2)))
    };
    let whole = |panics| contained(Box::new(WholeProgram { panics }));
    let screen = whole(false).program_screen(None, false);
    let Some(Ok(bitmap)) = screen else {
        panic!("the screen is passed on: {screen:?}")
    };
    assert_eq!(bitmap.white, [true, false]);
    let image = whole(false).render_image(false);
    let Some(Ok(image)) = image else {
        panic!("the image is passed on: {image:?}")
    };
    assert_eq!(image.pixels, two_pixels());
    assert_eq!(image.costs, Some(vec![3, 4]));
    for (what, result) in [
        (
            "the screen broke",
            whole(true).program_screen(None, false).map(|r| r.map(drop)),
        ),
        (
            "the image broke",
            whole(true).render_image(false).map(|r| r.map(drop)),
        ),
    ] {
        let Some(Err(e)) = result else {
            panic!("a panic is a failure: {what}")
        };
        let f = failure(&e);
        assert_eq!(f.kind, FailureKind::Panic);
        assert!(f.message.contains(what), "{f}");
    }
    // ref-f316 gives its whole image through the library's own loop, and
    // has no program screen.
    let reference = contained(Cast::builtin().open("ref-f316").unwrap());
    let image = reference.render_image(false);
    let Some(Ok(image)) = image else {
        panic!("ref-f316's image is passed on: {image:?}")
    };
    assert_eq!(image.pixels.len(), 512 * 256);
    assert!(reference.program_screen(None, false).is_none());
    // One with neither has none once contained.
    let plain = contained(Box::new(ThreadNoting {
        threads: Default::default(),
        hang_on: None,
    }));
    assert!(plain.render_image(false).is_none());
    assert!(plain.program_screen(None, false).is_none());
}

/// Answers every input with a number, and notes the thread each batch ran
/// on; loops for ever on a batch that holds the input `hang_on`.
struct ThreadNoting {
    threads: std::sync::Mutex<std::collections::HashSet<std::thread::ThreadId>>,
    hang_on: Option<Vector>,
}

impl Implementation for ThreadNoting {
    fn label(&self) -> String {
        "thread-noting".into()
    }
    fn numbers(&self) -> Numbers {
        Numbers::Float316
    }
    fn supports(&self, level: Level) -> bool {
        level == Level::Ops
    }
    fn eval(&self, batch: &[Vector]) -> Result<Vec<Outcome<Answer>>, ImplError> {
        if self.hang_on.as_ref().is_some_and(|h| batch.contains(h)) {
            loop {
                std::thread::sleep(Duration::from_secs(1));
            }
        }
        self.threads
            .lock()
            .unwrap()
            .insert(std::thread::current().id());
        Ok(batch.iter().map(|_| Outcome::OutOfDomain).collect())
    }
}

/// Containment costs no thread per batch: 300 batches in turn run on a
/// handful of reused workers (other tests of this binary share them), and
/// a worker that hangs is replaced, so the calls after it are answered.
#[test]
fn contained_batches_reuse_their_workers_and_replace_one_that_hangs() {
    let set = doubles();
    let noting = std::sync::Arc::new(ThreadNoting {
        threads: Default::default(),
        hang_on: Some(set.vectors[9].clone()),
    });
    struct Shared(std::sync::Arc<ThreadNoting>);
    impl Implementation for Shared {
        fn label(&self) -> String {
            self.0.label()
        }
        fn numbers(&self) -> Numbers {
            self.0.numbers()
        }
        fn supports(&self, level: Level) -> bool {
            self.0.supports(level)
        }
        fn eval(&self, batch: &[Vector]) -> Result<Vec<Outcome<Answer>>, ImplError> {
            self.0.eval(batch)
        }
    }
    let contained = Contained::new(
        Box::new(Shared(std::sync::Arc::clone(&noting))),
        Watchdog::fixed(Duration::from_millis(300)),
    );
    let answers = |at: usize| contained.eval(&set.vectors[at..at + 1]);
    for _ in 0..300 {
        assert_eq!(answers(0).unwrap().len(), 1);
    }
    let threads = noting.threads.lock().unwrap().len();
    assert!(threads <= 16, "300 batches ran on {threads} threads");
    let hang = answers(9).expect_err("the batch hangs");
    assert_eq!(failure(&hang).kind, FailureKind::Hang);
    for _ in 0..3 {
        assert_eq!(answers(1).unwrap().len(), 1, "answered after the hang");
    }
}

/// `count` distinct `double` vectors.
fn many_doubles(count: i16) -> VectorSet {
    let vectors = (0..count)
        .map(|i| {
            Vector::Op(OpVector {
                category: "double".into(),
                op: Op::Double,
                a: F316::new(i % 2, 120 + i % 50, 8192 + i % 8000),
                b: None,
            })
        })
        .collect();
    VectorSet::new("many-doubles", Level::Ops, "", None, vectors)
}

/// A pipe answers its batches in set order, whatever the threads do: an
/// adapter that crashes at its sixth answer always crashes on the set's
/// sixth input, with the five before it compared, however many batches
/// the set has (three here).
#[test]
fn a_pipe_gets_its_batches_in_set_order_so_a_crash_is_always_at_the_same_input() {
    let set = many_doubles(2 * 4096 + 10);
    for _ in 0..5 {
        let f = contained_run_on(&set, &misbehaving("crash").unwrap(), 5);
        assert_eq!(f.kind, FailureKind::Crash, "{f}");
    }
}

/// Notes the order its batches came in, and whether two ever overlapped.
#[derive(Default)]
struct InOrder {
    starts: std::sync::Mutex<Vec<i16>>,
    busy: std::sync::atomic::AtomicBool,
    overlapped: std::sync::atomic::AtomicBool,
}

impl Implementation for InOrder {
    fn label(&self) -> String {
        "in-order".into()
    }
    fn numbers(&self) -> Numbers {
        Numbers::Float316
    }
    fn supports(&self, level: Level) -> bool {
        level == Level::Ops
    }
    fn batch_size(&self, _: Level) -> usize {
        3
    }
    fn in_order(&self) -> bool {
        true
    }
    fn eval(&self, batch: &[Vector]) -> Result<Vec<Outcome<Answer>>, ImplError> {
        use std::sync::atomic::Ordering::SeqCst;
        if self.busy.swap(true, SeqCst) {
            self.overlapped.store(true, SeqCst);
        }
        let Vector::Op(first) = &batch[0] else {
            panic!("ops only")
        };
        self.starts.lock().unwrap().push(first.a.m - 8192);
        std::thread::sleep(Duration::from_millis(2));
        self.busy.store(false, SeqCst);
        Ok(batch.iter().map(|_| Outcome::OutOfDomain).collect())
    }
}

/// An implementation that answers in order gets every batch in set
/// order, one at a time, while the runner still runs others beside it.
#[test]
fn the_runner_gives_an_in_order_implementation_its_batches_in_turn() {
    let reference = Cast::builtin().open("ref-f316").unwrap();
    let set = many_doubles(40);
    let subject = InOrder::default();
    let report = diff_set(&[reference.as_ref(), &subject], &set, RunOptions::default());
    assert_eq!(report.comparisons[0].vectors, 40);
    let starts = subject.starts.lock().unwrap().clone();
    assert_eq!(starts, (0..40).step_by(3).collect::<Vec<i16>>());
    assert!(!subject.overlapped.load(std::sync::atomic::Ordering::SeqCst));
}
