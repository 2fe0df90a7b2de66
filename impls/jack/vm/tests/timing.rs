//! Each profile keeps its official tool's clock (module `timing`, spec
//! §2.7 and §6): tiny Jack programs with `Sys.wait`, scripted keys and
//! text, their step counts and screens pinned under both profiles; the
//! desktop's stack overflow and the bounded web locals.

use crate::jack_main::compile_main;
use hack_vm::{Config, Exit, KeyScript, Machine, Profile, Program, Ram};
use std::sync::Arc;

fn run(program: Arc<Program>, profile: Profile, keys: KeyScript) -> Machine {
    let mut m = Machine::new(
        program,
        Config {
            profile,
            keys,
            ..Config::default()
        },
    );
    assert_eq!(m.run(Some(10_000_000)), Exit::Halted, "{profile}");
    m
}

/// Run `main` (Jack) under both profiles: (web, desktop).
fn both(main: &str, keys: &str, hold: u64) -> (Machine, Machine) {
    let keys = KeyScript::parse(keys, hold).unwrap();
    let [web, desktop] =
        [Profile::Web, Profile::Desktop].map(|p| run(compile_main(main, p), p, keys.clone()));
    (web, desktop)
}

fn first_black_row(ram: &Ram) -> Option<usize> {
    (0..256).find(|&y| (0..512).any(|x| ram.pixel(x, y)))
}

/// The desktop's screen is the web IDE's one pixel row lower.
fn assert_one_row_lower(web: &Ram, desktop: &Ram) {
    assert!((0..512).all(|x| !desktop.pixel(x, 0)));
    for y in 0..255 {
        for x in 0..512 {
            assert_eq!(web.pixel(x, y), desktop.pixel(x, y + 1), "({x},{y})");
        }
    }
    assert!((0..512).all(|x| !web.pixel(x, 255)));
}

/// Five `Sys.wait` calls in a loop, digits and a string: one function
/// (F = 1) and no jump to a label pair (L = 0).
const WAITS: &str = "class Main {
    function void main() {
        var int i;
        let i = 0;
        while (i < 5) {
            do Sys.wait(10);
            do Output.printInt(i);
            let i = i + 1;
        }
        do Output.printInt(i);
        do Output.printString(\"Waited!\");
        return;
    }
}
";

#[test]
fn the_five_call_sys_wait_program_takes_123_web_steps_and_112_desktop_steps() {
    let (web, desktop) = both(WAITS, "", 1000);
    // Without any hand-over step the web count would be 118: 8 start-up
    // calls, 2 + 5 * 16 + 5 for the loop, 3 + 18 for the prints, 2 for the
    // return. The web IDE adds one hand-over step per Sys.wait; the desktop
    // counts 118 - 7 (one hidden call instead of eight) + 1 (function line).
    assert_eq!(web.steps(), 123);
    assert_eq!(desktop.steps(), 112);
    assert_eq!(first_black_row(web.ram()), Some(0));
    assert_eq!(first_black_row(desktop.ram()), Some(1));
    assert_one_row_lower(web.ram(), desktop.ram());
}

/// The course's Seven: prints 1 + (2 * 3).
const SEVEN: &str = "class Main {
    function void main() {
        do Output.printInt(1 + (2 * 3));
        return;
    }
}
";

#[test]
fn sevens_text_is_on_row_1_under_the_desktop_profile() {
    let (web, desktop) = both(SEVEN, "", 1000);
    assert_eq!(first_black_row(desktop.ram()), Some(1));
    assert_eq!(first_black_row(web.ram()), Some(0));
    assert_one_row_lower(web.ram(), desktop.ram());
    // The glyph of '7' in cell (0, 0) only.
    assert!((0..256).all(|y| (8..512).all(|x| !desktop.ram().pixel(x, y))));
    // 8 start-up calls + push 1, push 2, push 3, multiply, add, printInt,
    // pop temp 0, push 0, return; the desktop: 1 + 1 (function) + 9.
    assert_eq!(web.steps(), 17);
    assert_eq!(desktop.steps(), 11);
}

/// Reads a key (blocking), echoes it again, waits, returns.
const KEYS: &str = "class Main {
    function void main() {
        var char c;
        let c = Keyboard.readChar();
        do Output.printChar(c);
        do Sys.wait(5);
        return;
    }
}
";

#[test]
fn a_scripted_key_moves_the_clock_to_its_release_then_each_profile_counts_its_steps() {
    // 'A' is down during steps 0..100 and released at 100: readChar
    // returns there. Web: 100, its hand-over (101), pop (102), the echo (3),
    // Sys.wait with its hand-over (4), the return (2) = 111. Desktop: 100,
    // pop, echo, Sys.wait (3), return = 109.
    let (web, desktop) = both(KEYS, "A", 100);
    assert_eq!(web.steps(), 111);
    assert_eq!(desktop.steps(), 109);
    // The read's cursor box was replaced by its echo: "AA", one row lower
    // on the desktop.
    assert_one_row_lower(web.ram(), desktop.ram());
    assert_eq!(first_black_row(desktop.ram()), Some(1));
}

#[test]
fn sys_halt_and_a_runtime_error_are_counted_as_their_own_step() {
    let halt = "class Main { function void main() { do Sys.halt(); return; } }";
    let (web, desktop) = both(halt, "", 10);
    // Web: 8 start-up calls and the call of Sys.halt; desktop: 1, the
    // function line, the call.
    assert_eq!((web.steps(), desktop.steps()), (9, 3));
    let vm = "function Main.main 0\npush argument 3\nreturn\n";
    for (profile, steps) in [(Profile::Web, 9), (Profile::Desktop, 3)] {
        let p = Program::from_sources(&[("Main.vm", vm)]).unwrap();
        let mut m = Machine::new(
            p,
            Config {
                profile,
                ..Config::default()
            },
        );
        let e = m.run(None);
        assert!(matches!(e, Exit::RuntimeError { .. }), "{e}");
        assert_eq!(m.steps(), steps, "{profile}: the failing push is a step");
    }
}

#[test]
fn a_jump_to_a_label_pair_wastes_a_desktop_step() {
    // if with an empty else: the jump lands on `label ELSE`, which is
    // directly followed by `label END`.
    let main = "class Main {
        function void main() {
            var int i;
            while (i < 3) {
                if (i = 1) { let i = i + 1; }
                let i = i + 1;
            }
            return;
        }
    }";
    let (web, desktop) = both(main, "", 10);
    // Desktop = web - 7 + F (1) + L, with L = 1: the not-taken if at
    // i = 0 (at i = 1 the if is taken and makes i = 3).
    assert_eq!(desktop.steps(), web.steps() - 7 + 1 + 1);
}

fn load(vm: &str, profile: Profile) -> Machine {
    Machine::new(
        Program::from_sources(&[("Main.vm", vm)]).unwrap(),
        Config {
            profile,
            ..Config::default()
        },
    )
}

const RECURSE: &str = "function Main.main 0\ncall Main.main 0\nreturn\n";

#[test]
fn deep_recursion_is_a_desktop_stack_overflow_with_a_collapsed_call_stack() {
    let mut m = load(RECURSE, Profile::Desktop);
    match m.run(Some(60_000_000)) {
        Exit::RuntimeError { message, stack } => {
            // The desktop names the function and the failing command:
            // Main.main's command 1, its `call`.
            assert_eq!(message, "Stack overflow in Main.main.1");
            // Main.main's frame at 261, LCL 266; each call pushes 5 words;
            // the 357th call fails at its 2nd word, SP leaving 2047.
            assert_eq!(stack.to_string(), "Sys.init > Main.main x 357");
            assert_eq!(stack.depth(), 358);
        }
        other => panic!("{other}"),
    }
    // Nothing outside the stack segment was written (2048, 2049: the heap
    // header).
    assert!(m.ram().words()[2050..].iter().all(|w| *w == 0));
    assert_eq!(m.ram().read(0), 2047);
}

#[test]
fn web_recursion_runs_on_and_its_call_stack_prints_in_one_short_line() {
    let mut m = load(RECURSE, Profile::Web);
    let e = m.run(Some(2_000_000));
    let Exit::Budget { stack } = e else {
        panic!("{e}")
    };
    // One step per frame after the 8 start-up calls.
    assert_eq!(stack.to_string(), "Sys.init > Main.main x 1999993");
}

const BIG_LOCALS: &str = "function Main.main 0\nlabel L\ncall Main.g 0\npop temp 0\ngoto L\n\
                          function Main.g 30000\npush constant 0\nreturn\n";

#[test]
fn thirty_thousand_locals_overflow_the_desktop_stack_at_the_function_line() {
    let mut m = load(BIG_LOCALS, Profile::Desktop);
    let e = m.run(Some(2_000_000));
    let Exit::RuntimeError { message, stack } = e else {
        panic!("{e}")
    };
    assert_eq!(
        message, "Stack overflow in Main.main.0",
        "charged to the caller"
    );
    assert_eq!(stack.to_string(), "Sys.init > Main.main > Main.g");
    // Start-up, function Main.main, call Main.g, function Main.g.
    assert_eq!(m.steps(), 4);
    assert_eq!(m.ram().read(0), 271, "no local was pushed");
}

#[test]
fn thirty_thousand_web_locals_zero_what_ram_holds_and_drop_the_rest() {
    let mut m = load(BIG_LOCALS, Profile::Web);
    m.ram_mut().write(24000, 7);
    assert!(matches!(m.run(Some(11)), Exit::Budget { .. }));
    // 8 start-up calls, call Main.g (frame at 268, LCL 273, SP 30273),
    // push, return: the pushed 0 was dropped (outside RAM), so the value
    // read back into RAM[ARG] = 268 is -1.
    assert_eq!(m.ram().read(24000), 0);
    assert_eq!(m.ram().read(268), -1);
    assert_eq!(m.ram().read(5), 0, "pop temp 0 has not run yet");
    assert!(matches!(m.run(Some(1)), Exit::Budget { .. }));
    assert_eq!(m.ram().read(5), -1);
    // The loop goes on, bounded by the budget.
    assert!(matches!(m.run(Some(100_000)), Exit::Budget { .. }));
    assert_eq!(m.steps(), 100_012);
}

fn web_machine(main: &str, keys: &str, hold: u64) -> Machine {
    Machine::new(
        compile_main(main, Profile::Web),
        Config {
            profile: Profile::Web,
            keys: KeyScript::parse(keys, hold).unwrap(),
            ..Config::default()
        },
    )
}

#[test]
fn a_web_budget_that_ends_at_a_blocking_call_stops_there_with_the_argument_on_the_stack() {
    // Step 17 is the first `call Sys.wait 1`: the web IDE stops at 17 with
    // the argument 10 still on the stack (SP 270: Main.main's local at 268).
    let mut m = web_machine(WAITS, "", 1000);
    assert!(matches!(m.run(Some(17)), Exit::Budget { .. }));
    assert_eq!(m.steps(), 17);
    assert_eq!((m.ram().read(0), m.ram().read(269)), (270, 10));
    // Going on hands the result back (the step of 18) and ends as an
    // uninterrupted run does.
    assert!(matches!(m.run(Some(1)), Exit::Budget { .. }));
    assert_eq!(
        (m.steps(), m.ram().read(0), m.ram().read(269)),
        (18, 270, 0)
    );
    assert_eq!(m.run(None), Exit::Halted);
    assert_eq!(m.steps(), 123);
}

#[test]
fn a_web_budget_inside_a_key_wait_shows_the_cursor_and_not_the_echo() {
    let (whole, _) = both(KEYS, "A", 100);
    for budget in [9, 50, 100] {
        let mut m = web_machine(KEYS, "A", 100);
        assert!(
            matches!(m.run(Some(budget)), Exit::Budget { .. }),
            "{budget}"
        );
        assert_eq!(m.steps(), budget);
        // readChar's cursor box at cell (0, 0): x 2..=6, y 2..=9.
        let black: Vec<(usize, usize)> = (0..256)
            .flat_map(|y| (0..512).map(move |x| (x, y)))
            .filter(|&(x, y)| m.ram().pixel(x, y))
            .collect();
        assert_eq!(black.len(), 5 * 8, "{budget}: the cursor only");
        assert!(black
            .iter()
            .all(|&(x, y)| (2..=6).contains(&x) && (2..=9).contains(&y)));
        // Going on takes the key at its release (100), hands it back (101)
        // and ends as the uninterrupted run.
        assert_eq!(m.run(None), Exit::Halted);
        assert_eq!(m.steps(), 111);
        assert!(m.ram() == whole.ram(), "{budget}");
    }
}
