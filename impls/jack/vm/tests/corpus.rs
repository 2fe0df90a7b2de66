//! The benchmark corpus (tests/support/corpus.rs) on both engines under
//! both profiles: the same exit, step count, RAM and call stack at every
//! budget stop of a run cut into slices, and at its end.

#[path = "support/corpus.rs"]
mod corpus;

use corpus::{Work, CORPUS};
use hack_vm::{Engine, Exit, Profile};

/// Small runs: a round of each program, the jack-port's start and its
/// first rows.
const JACK_PORT_STEPS: u64 = 3_000_000;

#[test]
fn corpus_programs_run_the_same_on_both_engines() {
    for entry in CORPUS {
        for profile in [Profile::Desktop, Profile::Web] {
            let program = entry.program(profile);
            let mut a = entry.machine(&program, profile, Engine::Interp);
            let mut b = entry.machine(&program, profile, Engine::Native);
            assert_eq!(b.engine(), Engine::Native);
            entry.start(&mut a, 1);
            entry.start(&mut b, 1);
            // Slices of odd lengths put stops all through the program.
            let mut slice = 7_919;
            loop {
                let ea = a.run(Some(slice));
                let eb = b.run(Some(slice));
                let what = format!("{} {profile:?} at {}", entry.name, a.steps());
                assert_eq!(ea, eb, "{what}");
                assert_eq!(a.steps(), b.steps(), "{what}");
                assert!(a.ram() == b.ram(), "{what}: RAM differs");
                assert_eq!(a.call_stack(), b.call_stack(), "{what}");
                let done = matches!(entry.work, Work::Main) && a.steps() >= JACK_PORT_STEPS;
                if !matches!(ea, Exit::Budget { .. }) || done {
                    // A program that fails would be the same on both
                    // engines and measure nothing: each one must finish
                    // its round (or run on, from Main.main).
                    assert!(
                        matches!(ea, Exit::Returned(_)) || done,
                        "{what}: ended with {ea}"
                    );
                    break;
                }
                slice = slice * 3 / 2 + 1;
            }
        }
    }
}
