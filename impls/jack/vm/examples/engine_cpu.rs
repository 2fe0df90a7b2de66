//! Each engine's speed on the raymarcher in VM instructions per second of
//! the thread's CPU time (`/proc/thread-self/schedstat`, Linux), which a
//! loaded machine does not distort as it does criterion's wall-clock
//! figures: `cargo run --release -p hack-vm --example engine_cpu [ROUNDS]`
//! runs ROUNDS (default 16) rounds of the bench's 32 pixels on each engine
//! from a snapshot after `Main.init`, in one process (Auto on a program of
//! its own, not yet compiled, so that its row includes its interpreted
//! start and the compiling). With `main ENGINE` (`auto`, `native` or
//! `interp`) it runs instead the whole `Main.main` (SPACE scripted, as the
//! whole-program test does) on that engine alone. With `corpus [NAME]
//! [ENGINE]` it runs each program of the benchmark corpus (or NAME) for
//! about a CPU second on each engine (or ENGINE), one after another, and
//! prints their rates: a process that runs one program on one engine is
//! what a profiler needs.

#[path = "../tests/support/corpus.rs"]
mod corpus;
#[path = "../tests/support/corpus_runs.rs"]
mod corpus_runs;
#[path = "../tests/support/raymarcher.rs"]
mod support;

use hack_vm::{Config, Engine, Exit, KeyScript, Machine, Profile};

/// Seconds this thread has run on a CPU.
fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/thread-self/schedstat")
        .expect("Linux reports the thread's CPU time");
    let ns: f64 = stat
        .split_whitespace()
        .next()
        .and_then(|f| f.parse().ok())
        .expect("schedstat starts with nanoseconds on CPU");
    ns / 1e9
}

/// The whole `Main.main` on `engine`: its end, instruction count and CPU time.
fn whole_main(engine: Engine) {
    let config = Config {
        keys: KeyScript::parse("SPACE", 1_000_000).expect("a valid key script"),
        engine,
        ..Config::default()
    };
    let mut m = Machine::new(support::raymarcher(), config);
    let started = cpu_seconds();
    let exit = m.run(None);
    let cpu = cpu_seconds() - started;
    println!(
        "{engine:?}: Main.main ran {} VM instructions to {exit} in {cpu:.2} CPU s, {:.0} M/s",
        m.steps(),
        m.steps() as f64 / cpu / 1e6
    );
}

/// The corpus programs named `name` (all if None) on `engines`, each run
/// repeated for about a CPU second.
fn corpus_rates(name: Option<&str>, engines: &[Engine]) {
    for loaded in corpus_runs::load_corpus(name) {
        let _ = loaded.program.compile_native(Profile::Desktop);
        for &engine in engines {
            let started = cpu_seconds();
            let mut steps = 0;
            while cpu_seconds() - started < 1.0 {
                steps += loaded.run(engine);
            }
            let cpu = cpu_seconds() - started;
            println!(
                "{} on {engine:?}: {:.0} M VM instructions per CPU second",
                loaded.entry.name,
                steps as f64 / cpu / 1e6
            );
        }
    }
}

fn main() {
    if std::env::args().nth(1).as_deref() == Some("corpus") {
        let name = std::env::args().nth(2).filter(|n| n != "all");
        let engines = match std::env::args().nth(3) {
            Some(e) => vec![e.parse().expect("ENGINE is auto, native or interp")],
            None => vec![Engine::Interp, Engine::Native],
        };
        corpus_rates(name.as_deref(), &engines);
        return;
    }
    if std::env::args().nth(1).as_deref() == Some("main") {
        let engine = std::env::args().nth(2).unwrap_or_else(|| "native".into());
        whole_main(engine.parse().expect("ENGINE is auto, native or interp"));
        return;
    }
    let rounds: u16 = match std::env::args().nth(1) {
        Some(a) => a.parse().expect("ROUNDS is a number"),
        None => 16,
    };
    let program = support::raymarcher();
    match program.compile_native(Profile::Desktop) {
        Ok(t) => println!("compiled to native code in {:.3} s", t.as_secs_f64()),
        Err(e) => println!("no native code: {e}"),
    }
    for engine in [Engine::Interp, Engine::Native, Engine::Auto] {
        let program = match engine {
            Engine::Auto => support::raymarcher(),
            _ => program.clone(),
        };
        let init = support::initialised(&program, engine);
        let started = cpu_seconds();
        let (mut steps, mut last) = (0, engine);
        for _ in 0..rounds {
            for i in 0..32 {
                let mut m = init.clone();
                let exit = m
                    .call("Image.pixel", &[i * 16, 100], None)
                    .expect("Image.pixel exists");
                assert!(matches!(exit, Exit::Returned(_)), "{exit}");
                steps += m.steps() - init.steps();
                last = m.engine();
            }
        }
        let cpu = cpu_seconds() - started;
        println!(
            "{engine:?} (last pixel on {last:?}): {steps} VM instructions in {cpu:.3} CPU s, {:.0} M/s",
            steps as f64 / cpu / 1e6
        );
    }
}
