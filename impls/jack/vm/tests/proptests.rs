//! Property tests: the loader never panics on random or mutated text, and
//! running with fused instructions gives exactly the state of running one
//! plain command at a time (RAM, step count and end), on random programs
//! that poke at registers, RAM edges, the this/that checks and the built-ins.

use hack_vm::{Config, Exit, LoadError, Machine, Program};
use proptest::prelude::*;
use std::sync::Arc;

const VALID: &str = "function Main.main 2\npush constant 7\npop local 0\nlabel L\npush local 0\n\
                     push constant 1\nsub\npop local 0\npush local 0\nif-goto L\npush argument 0\n\
                     call Math.multiply 2\npush static 3\npop this 1\nreturn\n";

/// `loaded`, after checking that an error at a line names a file and a
/// line that exists (`Main.vm:LINE: ...`; `Sys.vm` is two lines long).
fn located(text: &str, loaded: Result<Arc<Program>, LoadError>) -> Result<Arc<Program>, LoadError> {
    if let Err(e) = &loaded {
        if let LoadError::Syntax { file, line, .. } = e {
            let lines = match file.as_str() {
                "Main.vm" => text.split('\n').count(),
                "Sys.vm" => 2,
                other => panic!("{e}: unknown file {other}"),
            };
            assert!((1..=lines).contains(line), "{e}");
            assert!(
                e.to_string().starts_with(&format!("{file}:{line}: ")),
                "{e}"
            );
        }
    }
    loaded
}

proptest! {
    #[test]
    fn loader_never_panics_on_random_text(text in "[ a-z0-9./$_:\\-\n\t/*]{0,200}") {
        let _ = located(&text, Program::from_sources(&[("Main.vm", text.as_str())]));
    }

    #[test]
    fn loader_never_panics_on_mutated_programs(
        edits in prop::collection::vec((0usize..400, 0u8..4, prop::sample::select(
            vec!["push", "pop", "function", "call", "return", "label", "goto", "if-goto", " ", "\n", "0",
                 "32768", "-1", "local", "this", "Main.main", "Sys.init", "/*", "//", "x", "99999999999999999999"])), 0..6)
    ) {
        let mut text = VALID.to_string();
        for (at, kind, word) in edits {
            let at = (at % (text.len() + 1)..=text.len()).find(|&i| text.is_char_boundary(i)).unwrap_or(text.len());
            match kind {
                0 => text.insert_str(at, word),
                1 => { text.truncate(at); }
                2 => { let end = (at + word.len()).min(text.len()); if text.is_char_boundary(end) { text.replace_range(at..end, word); } }
                _ => { text.insert(at, '\n'); }
            }
        }
        let two = [("Main.vm", text.as_str()), ("Sys.vm", "function Sys.init 0\ncall Main.main 0\n")];
        if let Ok(p) = located(&text, Program::from_sources(&two)) {
            // Whatever loads also runs without panicking.
            let mut m = Machine::new(p, Config::default());
            let _ = m.run(Some(10_000));
        }
    }

    #[test]
    fn fused_execution_equals_plain_execution(
        body in prop::collection::vec(command(), 1..60),
        labels in prop::collection::vec(0usize..60, 3),
        args in prop::array::uniform2(any::<i16>()),
        web in any::<bool>(),
    ) {
        let mut lines: Vec<String> = body;
        for (k, at) in labels.into_iter().enumerate() {
            lines.insert(at.min(lines.len()), format!("label L{k}"));
        }
        let src = format!(
            "function Main.main 0\npush constant 0\nreturn\nfunction Main.f 3\n{}\npush constant 0\nreturn\n{}",
            lines.join("\n"),
            // Fused argument reads are checked once per call: a call with
            // too few arguments must fail exactly where plain code fails.
            // Main.m opens like a method, which a fused call runs itself.
            "function Main.g 1\npush argument 0\npush argument 1\nadd\npop local 0\npush local 0\nreturn\n\
             function Main.m 1\npush argument 0\npop pointer 0\npush this 0\npush argument 1\nadd\nreturn\n"
        );
        let program = Program::from_sources(&[("Main.vm", src.as_str())]).expect("generated programs load");
        let profile = if web { hack_vm::Profile::Web } else { hack_vm::Profile::Desktop };
        let start = || {
            let mut m = Machine::new(program.clone(), Config { profile, ..Config::default() });
            // Enter Main.f without running anything.
            let e = m.call("Main.f", &args, Some(0)).expect("Main.f exists");
            assert!(matches!(e, Exit::Budget { .. }));
            m
        };
        const BUDGET: u64 = 3000;
        let mut fused = start();
        let fused_end = fused.run(Some(BUDGET));
        let mut plain = start();
        let plain_end = loop {
            let e = plain.run(Some(1));
            if !matches!(e, Exit::Budget { .. }) || plain.steps() >= BUDGET {
                break e;
            }
        };
        prop_assert_eq!(fused.steps(), plain.steps(), "{}", src);
        prop_assert_eq!(&fused_end, &plain_end, "{}", src);
        prop_assert!(fused.ram() == plain.ram(), "RAM differs\n{}", src);
    }
}

/// One VM command of the random programs.
fn command() -> impl Strategy<Value = String> {
    let value = prop_oneof![
        0u16..8,
        250u16..262,
        3000u16..3004,
        16380u16..16390,
        24570u16..24578,
        Just(32767)
    ];
    let seg = prop::sample::select(vec!["local", "argument", "this", "that", "temp", "static"]);
    prop_oneof![
        4 => value.clone().prop_map(|v| format!("push constant {v}")),
        3 => (seg.clone(), 0u16..4).prop_map(|(s, i)| format!("push {s} {i}")),
        3 => (seg.clone(), 0u16..4).prop_map(|(s, i)| format!("pop {s} {i}")),
        1 => (0u16..2).prop_map(|p| format!("push pointer {p}")),
        2 => (0u16..2).prop_map(|p| format!("pop pointer {p}")),
        1 => value.prop_map(|v| format!("pop constant {}", v % 6)),
        4 => prop::sample::select(vec!["add", "sub", "neg", "eq", "gt", "lt", "and", "or", "not"]).prop_map(String::from),
        1 => prop::sample::select(vec!["call Math.multiply 2", "call Math.divide 2", "call Math.abs 1", "call Main.g 1", "call Main.g 2", "call Main.m 1", "call Main.m 2"]).prop_map(String::from),
        1 => (0u8..3).prop_map(|l| format!("if-goto L{l}")),
        1 => (0u8..3).prop_map(|l| format!("goto L{l}")),
        1 => Just("return".to_string()),
        // Shapes the fuser turns into one instruction: runs of moves
        // between consecutive words, and an array read into a variable.
        1 => (seg.clone(), 0u16..3, seg.clone(), 0u16..3, 1u16..6).prop_map(|(s, i, d, j, n)| {
            (0..n).map(|k| format!("push {s} {}\npop {d} {}", i + k, j + k)).collect::<Vec<_>>().join("\n")
        }),
        1 => (seg.clone(), 0u16..4, seg.clone(), 0u16..4, seg.clone(), 0u16..4).prop_map(|(a, i, b, j, d, k)| {
            format!("push {a} {i}\npush {b} {j}\nadd\npop pointer 1\npush that 0\npop {d} {k}")
        }),
    ]
}
