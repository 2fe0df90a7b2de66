//! The benchmark corpus (tests/support/corpus.rs) on both engines under
//! both profiles: the same exit, step count, RAM and call stack at every
//! budget stop of a run cut into slices, and at its end; and the share of
//! each run that compiled code runs.

use crate::corpus_programs::{Work, CORPUS};
use hack_vm::{Config, Engine, Exit, Machine, Profile, Program};
use std::sync::Arc;

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

/// Compiled code runs nearly all of every corpus program under both
/// profiles: a change that leaves work to the interpreter (a block refused,
/// an entry test failing, a condition of the compiled engine inverted)
/// gives the same results and shows only here.
#[test]
fn corpus_programs_run_almost_wholly_compiled() {
    for entry in CORPUS {
        for profile in [Profile::Desktop, Profile::Web] {
            let program = entry.program(profile);
            let mut m = entry.machine(&program, profile, Engine::Native);
            entry.start(&mut m, 1);
            let exit = m.run(Some(JACK_PORT_STEPS));
            // (The entry's last return is the interpreter's: no frame to
            // return to. jack-port's run stops at a budget, and the blocks
            // and inline runs that the budget ends in, a few dozen steps,
            // are interpreted a step at a time.)
            let interpreted = m.steps() - m.compiled_steps();
            assert!(
                interpreted <= m.steps() / 10_000 + 2,
                "{} {profile:?}: {interpreted} of {} steps interpreted ({exit})",
                entry.name,
                m.steps()
            );
        }
    }
}

/// `this` and `that` accesses run compiled up to RAM's last word on the web
/// (whose test is that the span's words are all plain, without wrapping):
/// a loop reads `that 6` with THAT at 24570 (word 24576) and writes `this 1`
/// with THIS at 24575.
#[test]
fn pointer_accesses_at_the_top_of_ram_run_compiled() {
    let source = "function Main.main 0\nlabel LOOP\npush constant 24570\npop pointer 1\n\
                  push that 6\npush constant 24575\npop pointer 0\npop this 1\ngoto LOOP\n";
    runs_compiled(&[("Main.vm", source)], &[Profile::Web], Some("Main.main"));
}

/// A block that touches no stack word runs compiled wherever SP is (no
/// stack test): here SP is 100, below the stack, set by `pop constant 0`,
/// and the loop only jumps.
#[test]
fn blocks_without_stack_words_run_compiled_wherever_sp_is() {
    let source = "push constant 100\npop constant 0\nlabel LOOP\ngoto LOOP\n";
    runs_compiled(
        &[("Main.vm", source)],
        &[Profile::Desktop, Profile::Web],
        None,
    );
}

/// Code before a program's first `function` line (its `__implicit`
/// function) runs compiled too, from its first instruction: 400 straight
/// instructions, then a loop.
#[test]
fn code_before_any_function_runs_compiled() {
    let source = "push constant 1\npop temp 0\n".repeat(200)
        + "label LOOP\npush temp 0\npush constant 1\nadd\npop temp 0\ngoto LOOP\n";
    runs_compiled(
        &[("Main.vm", &source)],
        &[Profile::Desktop, Profile::Web],
        None,
    );
}

/// The same where that code is the entry of a program whose first file
/// holds a function (about 60 instructions) before it: compiled code starts
/// at the code's own first instruction, not one of the first function's
/// length further on.
#[test]
fn code_before_any_function_of_a_later_file_runs_compiled() {
    let first = "function A.f 0\n".to_string()
        + &"push constant 1\npop temp 1\n".repeat(30)
        + "push constant 0\nreturn\n";
    let source = "push constant 1\npop temp 0\n".repeat(200)
        + "label LOOP\npush temp 0\npush constant 1\nadd\npop temp 0\ngoto LOOP\n";
    runs_compiled(
        &[("A.vm", &first), ("B.vm", &source)],
        &[Profile::Desktop, Profile::Web],
        None,
    );
}

/// Calls at the limits of compiled calls run compiled: a callee of 64
/// locals (on the web the call zeroes them) and a call of 250 arguments,
/// each callee branching, so that it is called, not run inline. Over
/// 100,000 steps only the block the budget ends in (at most the 250
/// pushes and the call) is interpreted; a call sent to the interpreter
/// would cost steps in each of the hundreds of rounds.
#[test]
fn calls_at_the_compiled_limits_run_compiled() {
    let callee = |locals: usize| {
        format!(
            "function Main.f {locals}\npush argument 0\nif-goto ONE\npush constant 0\nreturn\n\
             label ONE\npush constant 1\nreturn\n"
        )
    };
    let call = |args: usize| {
        format!(
            "function Main.main 0\nlabel LOOP\n{}call Main.f {args}\npop temp 0\ngoto LOOP\n",
            "push constant 1\n".repeat(args)
        )
    };
    for (args, locals) in [(1, 64), (250, 0)] {
        let program =
            Program::from_sources(&[("Main.vm", &(call(args) + &callee(locals)))]).expect("loads");
        for profile in [Profile::Desktop, Profile::Web] {
            let interpreted = interpreted_steps(&program, profile, Some("Main.main"), 100_000);
            assert!(
                interpreted <= 260,
                "{profile:?}, {args} arguments, {locals} locals: {interpreted} steps interpreted"
            );
        }
    }
}

/// On the desktop `this` and `that` spans run compiled up to the last word
/// of the range the desktop allows them: `this 14335` from THIS = 2048 is
/// the heap's last word, 16383, and `that 22528` from THAT = 2048 is word
/// 24576.
#[test]
fn desktop_spans_that_end_at_their_segments_last_word_run_compiled() {
    for (segment, pointer, index) in [("this", 0, 14335), ("that", 1, 22528)] {
        let source = format!(
            "function Main.main 0\npush constant 2048\npop pointer {pointer}\nlabel LOOP\n\
             push {segment} 0\npush {segment} {index}\nadd\npop temp 0\ngoto LOOP\n"
        );
        runs_compiled(
            &[("Main.vm", &source)],
            &[Profile::Desktop],
            Some("Main.main"),
        );
    }
}

/// Stack ranges that fill the desktop stack exactly (its 1,791 words,
/// SP from 256 to 2047) run compiled: code before any function, at SP =
/// 256, pushing 1,791 words (each block tests its own range), and a
/// function whose loop first pops the words below its LCL down to 256,
/// then pushes to the end (its entry tests the whole range). Only the
/// round the budget ends in is interpreted.
#[test]
fn stack_ranges_that_fill_the_desktop_stack_run_compiled() {
    let round = |below: usize| {
        let above = 1791 - below;
        "pop temp 0\n".repeat(below)
            + &"push constant 1\n".repeat(1791)
            + &"pop temp 0\n".repeat(above)
            + "goto LOOP\n"
    };
    let implicit =
        Program::from_sources(&[("Main.vm", &format!("label LOOP\n{}", round(0)))]).expect("loads");
    let interpreted = interpreted_steps(&implicit, Profile::Desktop, None, 100_000);
    // (A round is 3,583 steps: 1,791 pops, 1,791 pushes and the goto.)
    assert!(interpreted <= 3583, "{interpreted} steps interpreted");
    // Main.main's LCL lies a few words above 256 (Sys.init's frame and its
    // own): of the dips below it, one fits the stack and runs to the
    // budget; the others stop at the stack's ends.
    let mut fits = Vec::new();
    for below in 0..16 {
        let source = format!("function Main.main 0\nlabel LOOP\n{}", round(below));
        let program = Program::from_sources(&[("Main.vm", &source)]).expect("loads");
        let mut m = compiled_machine(program, Profile::Desktop);
        match m.run(Some(100_000)) {
            Exit::Budget { .. } => fits.push((below, m.steps() - m.compiled_steps())),
            Exit::RuntimeError { message, .. } => {
                assert!(message.starts_with("Stack overflow"), "{below}: {message}")
            }
            exit => panic!("{below}: {exit}"),
        }
    }
    assert!(
        matches!(fits[..], [(_, interpreted)] if interpreted <= 3583),
        "{fits:?}"
    );
}

/// On the web a function may move ARG into its own locals (here to local
/// 1, with `pop constant 2`), so that its `argument` words lie at or above
/// LCL. With no locals held in registers (the web holds none) nothing
/// compiled depends on their order, and its loop runs compiled.
#[test]
fn an_arg_moved_into_the_locals_runs_compiled_on_the_web() {
    let source = "function Main.main 0\npush constant 7\ncall Main.f 1\nreturn\n\
                  function Main.f 2\npush constant 1\npop pointer 1\npush that 0\n\
                  push constant 1\nadd\npop constant 2\nlabel LOOP\npush argument 0\n\
                  push constant 1\nadd\npop local 0\ngoto LOOP\n";
    runs_compiled(&[("Main.vm", source)], &[Profile::Web], Some("Main.main"));
}

/// Returns run compiled from frames high in RAM: on the web, 700 calls
/// deep (LCL above 4,000), a loop calls a function without static depths,
/// whose return tests its saved frame itself.
#[test]
fn returns_from_frames_high_in_ram_run_compiled() {
    let source = "function Main.main 0\npush constant 700\ncall Main.g 1\nreturn\n\
                  function Main.g 0\npush argument 0\nif-goto DEEPER\nlabel LOOP\n\
                  push constant 1\ncall Main.f 1\npop temp 0\ngoto LOOP\nlabel DEEPER\n\
                  push argument 0\npush constant 1\nsub\ncall Main.g 1\nreturn\n\
                  function Main.f 0\npush constant 5\npush argument 0\nif-goto ONE\n\
                  push constant 1\nlabel ONE\nreturn\n";
    runs_compiled(&[("Main.vm", source)], &[Profile::Web], Some("Main.main"));
}

/// On the desktop a call's frame test does not count a called callee's
/// locals (its `function` line tests them): a loop at the bottom of a
/// recursion near the stack's end, with a call it never makes of a
/// function of 60 locals (called, not run inline: its opening writes a
/// static), runs compiled until the recursive call's own frames no longer
/// fit (two: the call runs its callee's recursive way inline, the call
/// in it too), up to two depths before the stack overflows.
#[test]
fn desktop_calls_leave_a_called_callees_locals_to_its_function_line() {
    // (About 300 calls of Main.g, 6 words each, fill the desktop stack.)
    let mut loop_interpreted = Vec::new();
    let overflow = (250..=350).find(|&depth| {
        let source = format!(
            "function Main.main 0\npush constant {depth}\ncall Main.g 1\nreturn\n\
             function Main.g 0\npush argument 0\nif-goto DEEPER\nlabel LOOP\n\
             push constant 0\nif-goto NEVER\ngoto LOOP\nlabel NEVER\ncall Main.big 0\n\
             pop temp 0\ngoto LOOP\nlabel DEEPER\npush argument 0\npush constant 1\nsub\n\
             call Main.g 1\nreturn\nfunction Main.big 60\npush constant 0\npop static 0\n\
             push constant 0\nif-goto ONE\npush constant 5\nreturn\nlabel ONE\npush constant 6\n\
             return\n"
        );
        let program = Program::from_sources(&[("Main.vm", &source)]).expect("loads");
        let mut m = compiled_machine(program, Profile::Desktop);
        m.call("Main.main", &[], Some(0)).expect("the entry exists");
        match m.run(Some(100_000)) {
            Exit::Budget { .. } => {
                if m.steps() - m.compiled_steps() > 1000 {
                    loop_interpreted.push(depth);
                }
                false
            }
            Exit::RuntimeError { message, .. } if message.starts_with("Stack overflow") => true,
            exit => panic!("{depth}: {exit}"),
        }
    });
    assert!(overflow.is_some(), "no depth up to 350 overflows the stack");
    assert!(loop_interpreted.len() <= 2, "{loop_interpreted:?}");
}

/// A block's stack test covers the words the block pops and pushes, not
/// its final call's arguments, which the call's own test covers: a loop
/// of code before any function pops the word at 256, then calls with one
/// argument, the word at 255 under the stack, and runs compiled.
#[test]
fn a_call_whose_argument_lies_under_the_stack_runs_compiled() {
    let source = "push constant 0\nlabel LOOP\npop temp 0\ncall Main.f 1\npush constant 0\n\
                  goto LOOP\nfunction Main.f 0\npush argument 0\nif-goto ONE\npush constant 3\n\
                  return\nlabel ONE\npush constant 4\nreturn\n";
    runs_compiled(
        &[("Main.vm", source)],
        &[Profile::Desktop, Profile::Web],
        None,
    );
}

/// The program of `sources` (from its start, or from a call of `entry`)
/// runs 10,000 steps on the compiled engine under each of `profiles`,
/// interpreting at most 8 of them.
fn runs_compiled(sources: &[(&str, &str)], profiles: &[Profile], entry: Option<&str>) {
    let program = Program::from_sources(sources).expect("loads");
    for &profile in profiles {
        let interpreted = interpreted_steps(&program, profile, entry, 10_000);
        assert!(
            interpreted <= 8,
            "{profile:?}: {interpreted} steps interpreted"
        );
    }
}

/// How many of `budget` steps of `program` (from its start, or from a call
/// of `entry`) the compiled engine leaves to the interpreter under
/// `profile`; the run must end at the budget.
fn interpreted_steps(
    program: &Arc<Program>,
    profile: Profile,
    entry: Option<&str>,
    budget: u64,
) -> u64 {
    let mut m = compiled_machine(program.clone(), profile);
    if let Some(f) = entry {
        m.call(f, &[], Some(0)).expect("the entry exists");
    }
    let exit = m.run(Some(budget));
    assert!(matches!(exit, Exit::Budget { .. }), "{profile:?}: {exit}");
    m.steps() - m.compiled_steps()
}

/// A machine on the compiled engine from the first step.
fn compiled_machine(program: Arc<Program>, profile: Profile) -> Machine {
    let config = Config {
        profile,
        engine: Engine::Native,
        ..Config::default()
    };
    Machine::new(program, config)
}
