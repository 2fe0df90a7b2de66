//! The benchmark corpus: Jack programs written in the styles people use
//! (`benches/corpus/NAME/*.jack`, each with a `Main.run(n)` doing `n`
//! rounds of its work) and `examples/jack-port`, compiled with
//! jack-compiler, for the corpus tests and the benches (included with
//! `#[path]`).

use hack_vm::{Config, Engine, KeyScript, Machine, Profile, Program};
use jack_compiler::VmClass;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// How a corpus program is run.
#[derive(Clone, Copy, Debug)]
pub enum Work {
    /// `Main.run(rounds)`, to its return.
    Rounds,
    /// From the start (`Main.main`) for a budget of steps.
    Main,
}

/// One program of the corpus.
#[derive(Clone, Copy, Debug)]
pub struct Entry {
    pub name: &'static str,
    /// The directory, relative to this crate.
    pub dir: &'static str,
    pub work: Work,
    /// The key script (`KeyScript::parse`) and how long each key is held.
    pub keys: &'static str,
    pub hold: u64,
}

const fn rounds(name: &'static str, dir: &'static str) -> Entry {
    Entry {
        name,
        dir,
        work: Work::Rounds,
        keys: "",
        hold: 1,
    }
}

/// Every program of the corpus.
pub const CORPUS: &[Entry] = &[
    rounds("getters", "benches/corpus/getters"),
    rounds("objects", "benches/corpus/objects"),
    rounds("chains", "benches/corpus/chains"),
    rounds("muldiv", "benches/corpus/muldiv"),
    rounds("strings", "benches/corpus/strings"),
    rounds("recursion", "benches/corpus/recursion"),
    rounds("sort", "benches/corpus/sort"),
    rounds("bits", "benches/corpus/bits"),
    Entry {
        name: "square",
        dir: "benches/corpus/square",
        work: Work::Rounds,
        keys: "RIGHT,X,DOWN,X,LEFT,Z,UP,Z,RIGHT",
        hold: 20_000,
    },
    Entry {
        name: "jack-port",
        dir: "../../../examples/jack-port",
        work: Work::Main,
        keys: "SPACE",
        hold: 1_000_000,
    },
];

impl Entry {
    fn path(&self) -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join(self.dir)
    }

    /// The program compiled for `profile`.
    pub fn program(&self, profile: Profile) -> Arc<Program> {
        let classes = jack_compiler::compile_dir(&self.path(), profile)
            .unwrap_or_else(|e| panic!("{} compiles: {e}", self.name));
        let files: Vec<(String, String)> = classes.into_iter().map(VmClass::into_file).collect();
        Program::from_sources(&files).unwrap_or_else(|e| panic!("{} loads: {e}", self.name))
    }

    /// A machine of `program` (this entry's) on `engine`, with the keys.
    pub fn machine(&self, program: &Arc<Program>, profile: Profile, engine: Engine) -> Machine {
        let config = Config {
            profile,
            engine,
            keys: KeyScript::parse(self.keys, self.hold).expect("a valid key script"),
            ..Config::default()
        };
        Machine::new(program.clone(), config)
    }

    /// Set `m` to run `size` rounds of `Main.run` (a machine of
    /// [`Work::Main`] is ready as it is); then `m.run` runs it.
    pub fn start(&self, m: &mut Machine, size: i16) {
        if let Work::Rounds = self.work {
            let exit = m
                .call("Main.run", &[size], Some(0))
                .expect("every corpus program has Main.run");
            assert!(matches!(exit, hack_vm::Exit::Budget { .. }), "{exit}");
        }
    }
}
