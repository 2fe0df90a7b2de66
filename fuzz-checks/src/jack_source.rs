//! Jack sources through the compiler (lexer, parser, checks, code
//! generation), VM sources through the loader and a bounded run.

use hack_vm::{Config, LoadError, Machine, Program};
use jack_compiler::{compile_sources, Profile};

/// VM instructions a fuzzed program may run.
const RUN_BUDGET: u64 = 20_000;

/// The 1-based number of lines of `text` (a position may point one past
/// the last character).
fn line_count(text: &str) -> usize {
    text.split('\n').count()
}

/// Any text compiles or fails with errors located inside it; compiled code
/// has a Jack position for every VM line and either loads or fails at a
/// line that maps back to the Jack source.
pub fn jack_source(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    for profile in [Profile::Desktop, Profile::Web] {
        match compile_sources(&[("Main.jack", text)], profile) {
            Err(errors) => {
                assert!(!errors.0.is_empty(), "a failed compile names an error");
                for e in &errors.0 {
                    assert_eq!(e.file, "Main.jack");
                    assert!(e.pos.line >= 1 && e.pos.col >= 1, "{e}");
                    assert!(e.pos.line as usize <= line_count(text), "{e}");
                    assert!(e.to_string().starts_with("Main.jack:"), "{e}");
                }
            }
            Ok(classes) => {
                for c in &classes {
                    assert_eq!(c.lines.len(), c.code.lines().count(), "{}", c.class_name);
                }
                let files: Vec<(String, String)> = classes
                    .iter()
                    .map(|c| (c.file_name(), c.code.clone()))
                    .collect();
                if let Err(LoadError::Syntax { file, line, .. }) = Program::from_sources(&files) {
                    let class = classes.iter().find(|c| c.file_name() == file);
                    let pos = class.and_then(|c| c.jack_pos(line));
                    assert!(pos.is_some(), "{file}:{line} maps to no Jack position");
                }
            }
        }
    }
}

/// Any text loads or fails naming its file and a line inside it; a
/// program that loads runs to an end within a small budget.
pub fn vm_source(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match Program::from_sources(&[("Main.vm", text)]) {
        Err(LoadError::Syntax { file, line, .. }) => {
            assert_eq!(file, "Main.vm");
            assert!(
                line <= line_count(text),
                "line {line} of {}",
                line_count(text)
            );
        }
        Err(_) => {}
        Ok(program) => {
            let mut machine = Machine::new(program, Config::default());
            let _ = machine.run(Some(RUN_BUDGET));
            assert!(machine.steps() <= RUN_BUDGET, "{} steps", machine.steps());
        }
    }
}
