//! Runs of the benchmark corpus (`corpus.rs`, included beside this file
//! as `corpus`) of about [`CORPUS_STEPS`] VM instructions each, under the
//! desktop profile, for the bench and the `engine_cpu` example.

use crate::corpus::{Entry, Work, CORPUS};
use hack_vm::{Engine, Exit, Profile, Program};
use std::sync::Arc;

/// VM instructions per corpus run: about 20 M (0.01-0.05 s a run).
pub const CORPUS_STEPS: u64 = 20_000_000;

/// A corpus program loaded, with the size of a run of about
/// [`CORPUS_STEPS`] (rounds of `Main.run`, or steps from the start).
pub struct Loaded {
    pub entry: &'static Entry,
    pub program: Arc<Program>,
    size: u64,
}

/// The corpus programs named `name` (every one if None), loaded and sized:
/// a process that profiles one program compiles no other.
pub fn load_corpus(name: Option<&str>) -> Vec<Loaded> {
    CORPUS
        .iter()
        .filter(|e| name.is_none_or(|n| n == e.name))
        .map(Loaded::new)
        .collect()
}

impl Loaded {
    /// `entry` compiled and sized from one round.
    fn new(entry: &'static Entry) -> Loaded {
        let program = entry.program(Profile::Desktop);
        let size = match entry.work {
            Work::Main => CORPUS_STEPS,
            Work::Rounds => {
                let mut m = entry.machine(&program, Profile::Desktop, Engine::Native);
                entry.start(&mut m, 1);
                let exit = m.run(None);
                assert!(matches!(exit, Exit::Returned(_)), "{}: {exit}", entry.name);
                (CORPUS_STEPS / m.steps()).clamp(1, 32767)
            }
        };
        Loaded {
            entry,
            program,
            size,
        }
    }

    /// One run on `engine` (compiled code compiled beforehand): its steps.
    pub fn run(&self, engine: Engine) -> u64 {
        let mut m = self.entry.machine(&self.program, Profile::Desktop, engine);
        let size = i16::try_from(self.size).unwrap_or(i16::MAX);
        self.entry.start(&mut m, size);
        let exit = match self.entry.work {
            Work::Main => m.run(Some(self.size)),
            Work::Rounds => m.run(None),
        };
        assert!(
            matches!(exit, Exit::Returned(_) | Exit::Budget { .. }),
            "{}: {exit}",
            self.entry.name
        );
        m.steps()
    }
}
