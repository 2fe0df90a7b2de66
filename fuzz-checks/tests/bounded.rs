//! The fuzz targets' properties under `cargo test`: every checked-in seed
//! (`fuzz/corpus/TARGET`) and every committed regression input
//! (`fuzz/regressions/TARGET`, the crashes of earlier fuzz runs), then a
//! bounded number of proptest mutations of the seeds.

use proptest::prelude::*;
use std::path::{Path, PathBuf};

fn fuzz_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../fuzz")
}

/// The inputs of `fuzz/KIND/TARGET`, sorted. The folder must exist: a
/// regressions folder with no crash yet holds only a `.gitkeep` (git keeps
/// no empty folder), and a name that starts with a dot is no input.
fn inputs(kind: &str, target: &str) -> Vec<(PathBuf, Vec<u8>)> {
    let dir = fuzz_dir().join(kind).join(target);
    let entries = std::fs::read_dir(&dir).unwrap_or_else(|e| {
        panic!(
            "{}: {e} (every fuzz target has fuzz/{kind}/{target}/)",
            dir.display()
        )
    });
    let mut files: Vec<PathBuf> = entries
        .map(|e| e.unwrap().path())
        .filter(|p| {
            !p.file_name()
                .is_some_and(|n| n.to_string_lossy().starts_with('.'))
        })
        .collect();
    files.sort();
    files
        .into_iter()
        .map(|p| {
            let bytes = std::fs::read(&p).unwrap();
            (p, bytes)
        })
        .collect()
}

/// Every folder of `fuzz/corpus` and `fuzz/regressions` is a target's: a
/// misspelt one would never be replayed.
#[test]
fn every_input_folder_names_a_target() {
    for kind in ["corpus", "regressions"] {
        let dir = fuzz_dir().join(kind);
        for entry in std::fs::read_dir(&dir).unwrap() {
            let name = entry.unwrap().file_name().to_string_lossy().into_owned();
            assert!(
                fuzz_checks::TARGETS.iter().any(|(t, _)| *t == name),
                "fuzz/{kind}/{name} is no fuzz target's"
            );
        }
    }
}

fn check_of(target: &str) -> fn(&[u8]) {
    fuzz_checks::TARGETS
        .iter()
        .find(|(name, _)| *name == target)
        .unwrap()
        .1
}

#[test]
fn every_target_has_a_seed_corpus_and_a_fuzz_target() {
    for (name, _) in fuzz_checks::TARGETS {
        assert!(
            inputs("corpus", name).len() >= 2,
            "fuzz/corpus/{name} holds too few seeds"
        );
        let target = fuzz_dir().join("fuzz_targets").join(format!("{name}.rs"));
        let text = std::fs::read_to_string(&target).unwrap();
        assert!(
            text.contains(&format!("fuzz_checks::{name}(")),
            "{}",
            target.display()
        );
    }
}

/// The seeds reach past the parsers: some compile, load and run, so the
/// properties about compiled code, runs and evaluations are exercised.
#[test]
fn seeds_reach_the_deep_paths() {
    let text = |target: &str, file: &str| {
        String::from_utf8(std::fs::read(fuzz_dir().join("corpus").join(target).join(file)).unwrap())
            .unwrap()
    };
    let jack = text("jack_source", "Statements.jack");
    jack_compiler::compile_sources(&[("Main.jack", jack)], jack_compiler::Profile::Desktop)
        .expect("a seed compiles");
    let vm = text("vm_source", "Loop.vm");
    hack_vm::Program::from_sources(&[("Main.vm", vm)]).expect("a seed loads");
    let set = text("vector_set", "ops-small.json");
    assert!(
        vectors::VectorSet::parse("ops-small.json", &set)
            .unwrap()
            .vectors
            .len()
            > 100
    );
    let scene = text("scene", "camera-march.json");
    serde_json::from_str::<reference::Scene>(&scene).expect("a seed is a scene");
    // The adapters' real answers read back: the handshake, then every
    // answer and batch end of the operations' exchange.
    let exchange = text("pipe_reader", "ref-pipe-ops.txt");
    let mut lines = exchange.lines();
    let hello = harness::pipe::protocol::read_handshake(lines.next().unwrap()).unwrap();
    let expect = harness::pipe::protocol::Expect {
        level: vectors::Level::Ops,
        op: Some(common::Op::Add),
        pixel: None,
        numbers: hello.numbers,
    };
    let read: Vec<_> = lines
        .filter(|l| !l.contains("\"value\":false") && !l.contains("\"value\":true"))
        .map(|l| harness::pipe::protocol::read_line(l, &expect))
        .collect();
    assert!(read.len() > 5 && read.iter().all(Result::is_ok), "{read:?}");
    for seed in [
        "jack-inline.toml",
        "jack-bindings-file.toml",
        "shaders.toml",
    ] {
        let cast = harness::cast::Cast::with_project(
            &fuzz_checks::project_file(),
            &text("cast_file", seed),
        )
        .expect("a seed declares implementations");
        assert!(cast.entries().len() > harness::cast::Cast::builtin().entries().len());
    }
}

/// Every seed and every committed regression input, of every target (a
/// target without its folders fails).
#[test]
fn seeds_and_regression_inputs_pass() {
    for (name, check) in fuzz_checks::TARGETS {
        for kind in ["corpus", "regressions"] {
            for (path, bytes) in inputs(kind, name) {
                let run = std::panic::catch_unwind(|| check(&bytes));
                assert!(run.is_ok(), "{} fails {name}", path.display());
            }
        }
    }
}

/// A seed of `target` with up to `n` byte edits (overwrite, insert,
/// delete) and possibly truncated: mostly well-formed inputs with a local
/// fault, which is where parsers break.
fn mutated(target: &'static str, n: usize) -> impl Strategy<Value = Vec<u8>> {
    let seeds: Vec<Vec<u8>> = inputs("corpus", target)
        .into_iter()
        .map(|(_, b)| b)
        .collect();
    let edits = prop::collection::vec((any::<prop::sample::Index>(), 0u8..3, any::<u8>()), 0..n);
    (
        prop::sample::select(seeds),
        edits,
        any::<prop::sample::Index>(),
        any::<bool>(),
    )
        .prop_map(|(mut bytes, edits, cut, truncate)| {
            for (at, kind, byte) in edits {
                let i = if bytes.is_empty() {
                    0
                } else {
                    at.index(bytes.len())
                };
                match kind {
                    0 if !bytes.is_empty() => bytes[i] = byte,
                    1 => bytes.insert(i, byte),
                    _ if !bytes.is_empty() => {
                        bytes.remove(i);
                    }
                    _ => {}
                }
            }
            if truncate && !bytes.is_empty() {
                bytes.truncate(cut.index(bytes.len()));
            }
            bytes
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn mutated_jack_sources(bytes in mutated("jack_source", 8)) {
        check_of("jack_source")(&bytes);
    }

    #[test]
    fn mutated_vm_sources(bytes in mutated("vm_source", 8)) {
        check_of("vm_source")(&bytes);
    }

    #[test]
    fn mutated_vector_sets(bytes in mutated("vector_set", 6)) {
        check_of("vector_set")(&bytes);
    }

    #[test]
    fn mutated_scenes(bytes in mutated("scene", 6)) {
        check_of("scene")(&bytes);
    }

    #[test]
    fn mutated_cast_files(bytes in mutated("cast_file", 6)) {
        check_of("cast_file")(&bytes);
    }

    #[test]
    fn mutated_adapter_outputs(bytes in mutated("pipe_reader", 8)) {
        check_of("pipe_reader")(&bytes);
    }

    #[test]
    fn mutated_tst_scripts(bytes in mutated("tst_script", 8)) {
        check_of("tst_script")(&bytes);
    }

    /// Output that is not the protocol at all.
    #[test]
    fn arbitrary_adapter_outputs(bytes in prop::collection::vec(any::<u8>(), 0..512)) {
        check_of("pipe_reader")(&bytes);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, failure_persistence: None, ..ProptestConfig::default() })]

    /// Any words as operands, not only normalised ones.
    #[test]
    fn random_operands_agree_with_jack(bytes in prop::collection::vec(any::<u8>(), 13)) {
        check_of("f316_vs_jack")(&bytes);
    }
}
