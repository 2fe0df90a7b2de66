//! Each engine's speed on the raymarcher in VM instructions per second of
//! the thread's CPU time (`/proc/thread-self/schedstat`, Linux), which a
//! loaded machine does not distort as it does criterion's wall-clock
//! figures: `cargo run --release -p hack-vm --example engine_cpu [ROUNDS]`
//! runs ROUNDS (default 16) rounds of the bench's 32 pixels on each engine
//! from a snapshot after `Main.init`, in one process.

#[path = "../tests/support/raymarcher.rs"]
mod support;

use hack_vm::{Config, Engine, Exit, Machine, Profile};

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

fn main() {
    let rounds: u16 = match std::env::args().nth(1) {
        Some(a) => a.parse().expect("ROUNDS is a number"),
        None => 16,
    };
    let program = support::raymarcher();
    match program.compile_native(Profile::Desktop) {
        Ok(t) => println!("compiled to native code in {:.3} s", t.as_secs_f64()),
        Err(e) => println!("no native code: {e}"),
    }
    for engine in [Engine::Interp, Engine::Native] {
        let config = Config {
            engine,
            ..Config::default()
        };
        let mut init = Machine::new(program.clone(), config);
        let exit = init.call("Main.init", &[], None).expect("Main.init exists");
        assert_eq!(exit, Exit::Returned(0));
        let started = cpu_seconds();
        let mut steps = 0;
        for _ in 0..rounds {
            for i in 0..32 {
                let mut m = init.clone();
                let exit = m
                    .call("Image.pixel", &[i * 16, 100], None)
                    .expect("Image.pixel exists");
                assert!(matches!(exit, Exit::Returned(_)), "{exit}");
                steps += m.steps() - init.steps();
            }
        }
        let cpu = cpu_seconds() - started;
        println!(
            "{engine:?}: {steps} VM instructions in {cpu:.3} CPU s, {:.0} M/s",
            steps as f64 / cpu / 1e6
        );
    }
}
