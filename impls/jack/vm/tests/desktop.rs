//! The desktop profile's memory, as the desktop VM emulator of suite 2.5
//! lays it out (issue 28): the start-up frames, the stack at a built-in
//! that ends the run, the stack after `Main.main` returns, and registers a
//! user preset before the run.

use crate::jack_main;

use hack_vm::{Config, Exit, Machine, Profile, Program};
use std::sync::Arc;

fn compile(main: &str) -> Arc<Program> {
    jack_main::compile_main(main, Profile::Desktop)
}

fn desktop(program: Arc<Program>) -> Machine {
    Machine::new(
        program,
        Config {
            profile: Profile::Desktop,
            ..Config::default()
        },
    )
}

fn vm(text: &str) -> Machine {
    desktop(Program::from_sources(&[("Main.vm", text)]).unwrap())
}

fn words(m: &Machine, from: i32, to: i32) -> Vec<i16> {
    (from..to).map(|a| m.ram().read(a)).collect()
}

#[test]
fn main_main_runs_in_a_frame_at_261_with_lcl_266_and_sp_is_261_after_it_returns() {
    let mut m = desktop(compile(
        "class Main { function void main() { var int x; let x = 5; return; } }",
    ));
    // The hidden call of Sys.init and `function Main.main 1`.
    assert!(matches!(m.run(Some(2)), Exit::Budget { .. }));
    assert_eq!(words(&m, 261, 266)[1..], [261, 256, 0, 0]);
    assert_eq!(words(&m, 0, 3), [267, 266, 261], "SP, LCL, ARG");
    assert_eq!(m.run(None), Exit::Halted);
    // The return value (0) lands at ARG = 261, and the built-in Sys.init
    // takes it off the stack.
    assert_eq!(m.ram().read(0), 261);
    assert_eq!(m.ram().read(261), 0);
    assert_eq!(m.ram().read(266), 5, "the local stays where it was");
}

#[test]
fn at_sys_halt_the_desktop_stack_ends_above_the_built_ins_frame_at_271() {
    let mut m = vm("function Main.main 0\ncall Sys.halt 0\npop temp 0\npush constant 0\nreturn\n");
    assert_eq!(m.run(None), Exit::Halted);
    // Sys.halt's frame at 266: RET is the desktop address of `pop temp 0`
    // (line 2 of the program), then Main.main's LCL, ARG, THIS, THAT.
    assert_eq!(words(&m, 266, 271), [2, 266, 261, 0, 0]);
    assert_eq!(words(&m, 0, 3), [271, 271, 266], "SP, LCL, ARG");
    // The same from Jack, where Main.main has no locals.
    let mut m = desktop(compile(
        "class Main { function void main() { do Sys.halt(); return; } }",
    ));
    assert_eq!(m.run(None), Exit::Halted);
    assert_eq!(m.ram().read(0), 271);
}

#[test]
fn a_built_in_error_ends_above_its_frame_with_the_arguments_below_it() {
    let mut m = vm(
        "function Main.main 0\nlabel A\nlabel B\npush constant 7\npush constant 0\ncall Math.divide 2\nlabel C\nreturn\n",
    );
    let e = m.run(None);
    assert!(matches!(e, Exit::SysError { code: 3, .. }), "{e}");
    // The two arguments at 266, 267; the frame at 268 with RET the address
    // of `return` (line 7: the label after the call is skipped).
    assert_eq!(words(&m, 266, 273), [7, 0, 7, 266, 261, 0, 0]);
    assert_eq!(words(&m, 0, 3), [273, 273, 266], "SP, LCL, ARG");
}

#[test]
fn a_preset_stack_pointer_moves_the_start_up_frames_and_sys_halt_ends_at_315() {
    let mut m = desktop(compile(
        "class Main { function void main() { do Sys.halt(); return; } }",
    ));
    m.ram_mut().write(0, 300);
    assert_eq!(m.run(None), Exit::Halted);
    // The built-in Sys.init's frame at 300, Main.main's at 305 (LCL 310),
    // Sys.halt's at 310.
    assert_eq!(m.ram().read(0), 315);
    assert_eq!(words(&m, 305, 310), [-1, 305, 300, 0, 0]);
    assert_eq!(words(&m, 311, 315), [310, 305, 0, 0]);
}

#[test]
fn a_printing_recursion_overflows_at_the_built_in_call_that_finds_no_room() {
    let mut m = vm("function Main.main 0\npush constant 1\ncall Output.printInt 1\npop temp 0\ncall Main.main 0\nreturn\n");
    let e = m.run(Some(1_000_000));
    let Exit::RuntimeError { message, stack } = e else {
        panic!("{e}")
    };
    assert!(message.starts_with("Stack overflow"), "{message}");
    // Level k of Main.main has LCL = 266 + 5k. At k = 355 the argument
    // sits at 2041, the built-in's frame fills 2042..2046, printInt runs
    // and the push of its result at 2047 fails: 356 levels, each printing
    // a 1.
    assert_eq!(stack.to_string(), "Sys.init > Main.main x 356");
    // The start-up, 355 levels of 5 steps, and the function line, push and
    // call of the last.
    assert_eq!(m.steps(), 1 + 355 * 5 + 3);
    assert_eq!(m.os().cursor(), (5, 36), "356 characters printed");
    assert_eq!(words(&m, 0, 3), [2047, 2047, 2041], "SP, LCL, ARG");
    assert_eq!(
        m.ram().read(2047),
        0,
        "the result was written, then SP failed"
    );
}

#[test]
fn the_web_profile_keeps_its_own_start_up_and_halt() {
    let mut m = Machine::new(
        compile("class Main { function void main() { do Sys.halt(); return; } }"),
        Config {
            profile: Profile::Web,
            ..Config::default()
        },
    );
    assert_eq!(m.run(None), Exit::Halted);
    // Seven 0s at 256..262, Main.main's frame at 263, LCL 268; Sys.halt
    // pops nothing and pushes its 0.
    assert_eq!(m.ram().read(0), 269);
}

#[test]
fn the_desktop_heap_starts_14334_16384_and_a_two_char_string_costs_six_words() {
    let mut m = desktop(compile(
        "class Main { function void main() { var String s; var Array a;
           let s = \"ab\"; let a = Array.new(1); do Output.printInt(a); return; } }",
    ));
    assert!(matches!(m.run(Some(1)), Exit::Budget { .. }));
    assert_eq!(words(&m, 2048, 2050), [14334, 16384]);
    assert_eq!(m.run(None), Exit::Halted);
    // s = 2050 (maxLength 2, length 2, 'a', 'b'), a = 2056: what the
    // desktop prints.
    assert_eq!(words(&m, 266, 268), [2050, 2056]);
    assert_eq!(words(&m, 2048, 2054), [0, 2054, 2, 2, 97, 98]);
    assert_eq!(words(&m, 2054, 2058), [0, 2057, 0, 14325]);
}

#[test]
fn with_a_vm_sys_init_the_desktop_leaves_the_heap_header_zero() {
    let sys = "function Sys.init 0\nlabel L\ngoto L\n";
    for (profile, header) in [(Profile::Desktop, [0, 0]), (Profile::Web, [0, 14334])] {
        let mut m = Machine::new(
            Program::from_sources(&[("Sys.vm", sys)]).unwrap(),
            Config {
                profile,
                ..Config::default()
            },
        );
        m.run(Some(10));
        assert_eq!(words(&m, 2048, 2050), header, "{profile}");
    }
    // Its own call of the built-in Memory.init writes it.
    let mut m = vm("function Main.f 0\ncall Memory.init 0\nlabel L\ngoto L\n");
    m.run(Some(10));
    assert_eq!(words(&m, 2048, 2050), [14334, 16384]);
}

#[test]
fn a_desktop_built_in_reading_outside_the_heap_and_screen_is_an_error_at_its_call() {
    let mut m = desktop(compile(
        "class Main { function void main() { do Output.printInt(Memory.peek(1)); return; } }",
    ));
    let e = m.run(None);
    let Exit::RuntimeError { message, .. } = e else {
        panic!("{e}")
    };
    assert_eq!(
        message,
        "A built-in function tried to access memory outside the Heap or Screen range"
    );
    // The hidden call, `function Main.main`, `push constant 1`, the call.
    assert_eq!(m.steps(), 4);
}

#[test]
fn a_lone_function_file_runs_from_its_function_line_without_the_web_ides_segment_check() {
    let f = "function Foo.bar 2\npush local 1\npush constant 3\nadd\npop temp 0\n\
             push constant 7\npop temp 1\npush argument 0\npop temp 2\n";
    let mut m = vm(f);
    assert_eq!(m.run(None), Exit::Halted);
    // The function line and 8 commands; local 1 is RAM[LCL + 1] = RAM[1]
    // (LCL = 0), argument 0 is RAM[0], SP.
    assert_eq!(m.steps(), 9);
    assert_eq!(words(&m, 5, 8), [3, 7, 258]);
    let mut web = Machine::new(
        Program::from_sources(&[("Foo.vm", f)]).unwrap(),
        Config {
            profile: Profile::Web,
            ..Config::default()
        },
    );
    let e = web.run(None);
    assert!(matches!(e, Exit::RuntimeError { .. }), "{e}");
    assert_eq!(web.steps(), 1);
}

#[test]
fn desktop_runtime_errors_read_as_the_desktop_words_them() {
    let mut m = vm("function Main.main 0\npush argument 1\nreturn\n");
    let e = m.run(None);
    let Exit::RuntimeError { message, .. } = e else {
        panic!("{e}")
    };
    assert_eq!(message, "Out of segment space in Main.main.1");
    // Labels are not commands of the desktop's index.
    let mut m =
        vm("function Main.main 0\nlabel A\npush constant 1\nlabel B\npop argument 0\nreturn\n");
    let Exit::RuntimeError { message, .. } = m.run(None) else {
        panic!()
    };
    assert_eq!(message, "Out of segment space in Main.main.2");
    // A `function` line that overflows the stack is charged to its caller.
    let mut m = vm("function Main.main 0\ncall Main.g 0\nreturn\nfunction Main.g 30000\npush constant 0\nreturn\n");
    let Exit::RuntimeError { message, stack } = m.run(None) else {
        panic!()
    };
    assert_eq!(message, "Stack overflow in Main.main.0");
    assert_eq!(stack.to_string(), "Sys.init > Main.main > Main.g");
    // The web IDE keeps its own words.
    let mut web = Machine::new(
        Program::from_sources(&[("Main.vm", "function Main.main 0\npush argument 1\nreturn\n")])
            .unwrap(),
        Config {
            profile: Profile::Web,
            ..Config::default()
        },
    );
    let Exit::RuntimeError { message, .. } = web.run(None) else {
        panic!()
    };
    assert_eq!(message, "Argument offset out of bounds");
}

#[test]
fn a_static_index_past_239_runs_on_the_desktop_and_is_refused_by_the_web_ide() {
    let src = "function Main.main 0\npush constant 9\npop static 240\npush static 240\npop temp 0\npush constant 0\nreturn\n";
    let p = Program::from_sources(&[("Main.vm", src)]).unwrap();
    // The desktop's segment for Main is 16..=256: static 240 is RAM[256].
    assert!(p.check_profile(Profile::Desktop).is_ok());
    let mut m = desktop(Arc::clone(&p));
    m.run(Some(4));
    assert_eq!(m.ram().read(256), 9);
    assert_eq!(m.run(None), Exit::Halted);
    assert_eq!(m.ram().read(5), 9);
    let e = p.check_profile(Profile::Web).unwrap_err().to_string();
    assert_eq!(
        e,
        "Main.vm:3: Illegal static index 240 (must be between 0 and 239)"
    );
    let mut web = Machine::new(
        p,
        Config {
            profile: Profile::Web,
            ..Config::default()
        },
    );
    let Exit::RuntimeError { message, .. } = web.run(None) else {
        panic!()
    };
    assert_eq!(
        message,
        "Illegal static index 240 (must be between 0 and 239)"
    );
}

#[test]
fn a_goto_to_its_own_label_and_a_compiled_while_true_are_idle_loops() {
    for profile in Profile::ALL {
        let sys = "function Sys.init 0\npush constant 1\npop temp 0\nlabel L\ngoto L\n";
        let mut m = Machine::new(
            Program::from_sources(&[("Sys.vm", sys)]).unwrap(),
            Config {
                profile,
                ..Config::default()
            },
        );
        assert!(!m.idle(), "{profile}: at the start");
        m.run(Some(5));
        assert!(m.idle(), "{profile}");
        // The OS's Sys.halt: `while (true) {}` as the course's compiler
        // writes it.
        let halt = "function Sys.init 0\ncall Sys.halt 0\nreturn\nfunction Sys.halt 0\nlabel WHILE_EXP0\n\
                    push constant 0\nnot\nnot\nif-goto WHILE_END0\ngoto WHILE_EXP0\nlabel WHILE_END0\n\
                    push constant 0\nreturn\n";
        let mut m = Machine::new(
            Program::from_sources(&[("Sys.vm", halt)]).unwrap(),
            Config {
                profile,
                ..Config::default()
            },
        );
        m.run(Some(1000));
        assert!(m.idle(), "{profile}");
        // A loop that counts is not idle.
        let count = "function Sys.init 0\nlabel L\npush static 0\npush constant 1\nadd\npop static 0\ngoto L\n";
        let mut m = Machine::new(
            Program::from_sources(&[("Sys.vm", count)]).unwrap(),
            Config {
                profile,
                ..Config::default()
            },
        );
        m.run(Some(1000));
        assert!(!m.idle(), "{profile}");
    }
}

#[test]
fn a_stated_load_order_places_each_files_statics() {
    let dir = tempfile::tempdir().unwrap();
    let a = "function A.f 0\npush constant 11\npop static 1\npush constant 0\nreturn\n";
    let b = "function B.f 0\npush constant 22\npop static 0\npush constant 0\nreturn\n";
    let main = "function Main.main 0\ncall A.f 0\npop temp 0\ncall B.f 0\npop temp 0\npush constant 0\nreturn\n";
    for (f, t) in [("A.vm", a), ("B.vm", b), ("Main.vm", main)] {
        std::fs::write(dir.path().join(f), t).unwrap();
    }
    let run = |order: &[&str], profile: Profile| {
        let order: Vec<String> = order.iter().map(|s| s.to_string()).collect();
        let p = Program::load_dir_in_order(dir.path(), &order).unwrap();
        let mut m = Machine::new(
            p,
            Config {
                profile,
                ..Config::default()
            },
        );
        assert_eq!(m.run(None), Exit::Halted);
        words(&m, 16, 19)
    };
    // Sorted (A, B, Main): A's segment is RAM[16..=17], B's RAM[18].
    assert_eq!(run(&[], Profile::Desktop), [0, 11, 22]);
    // B first: B's static 0 is RAM[16], A's segment RAM[17..=18].
    assert_eq!(run(&["B", "Main.vm"], Profile::Desktop), [22, 0, 11]);
    // The web IDE numbers statics by first appearance in the load order.
    assert_eq!(run(&[], Profile::Web), [11, 22, 0]);
    assert_eq!(run(&["B"], Profile::Web), [22, 11, 0]);
    let bad = Program::load_dir_in_order(dir.path(), &["C".to_string()]).unwrap_err();
    assert!(bad.to_string().contains("names C"), "{bad}");
}

#[test]
fn a_printing_recursion_overflows_the_desktop_stack_at_step_3252() {
    // The printing recursion: the desktop VM emulator stops it
    // with a stack overflow at step 3,252.
    let mut m = desktop(compile(
        "class Main { function void main() { do Main.f(0); return; }
           function void f(int n) { do Output.printInt(n); do Output.printChar(32); do Main.f(n + 1); return; } }",
    ));
    let e = m.run(Some(10_000_000));
    let Exit::RuntimeError { message, stack } = e else {
        panic!("{e}")
    };
    assert_eq!(m.steps(), 3252);
    // At Main.f's command 2, its `call Output.printInt 1`: no room for the
    // built-in's frame and result.
    assert_eq!(message, "Stack overflow in Main.f.2");
    assert_eq!(stack.to_string(), "Sys.init > Main.main > Main.f x 296");
}

/// The interpreter, then compiled code.
const ENGINES: [hack_vm::Engine; 2] = [hack_vm::Engine::Interp, hack_vm::Engine::Native];

/// A machine for `program` under `profile` on `engine`.
fn on_engine(program: &Arc<Program>, profile: Profile, engine: hack_vm::Engine) -> Machine {
    Machine::new(
        program.clone(),
        Config {
            profile,
            engine,
            ..Config::default()
        },
    )
}

/// `text` (one file, Main.vm) under `profile` on the interpreter and on
/// compiled code: both end the same way after the same steps, which are
/// returned with the exit.
fn on_both_engines(profile: Profile, text: &str) -> (Exit, u64) {
    let program = Program::from_sources(&[("Main.vm", text)]).unwrap();
    let runs: Vec<(Exit, u64)> = ENGINES
        .into_iter()
        .map(|engine| {
            let mut m = on_engine(&program, profile, engine);
            let e = m.run(Some(10_000));
            (e, m.steps())
        })
        .collect();
    assert_eq!(
        runs[0], runs[1],
        "the interpreter, then compiled code:\n{text}"
    );
    runs[0].clone()
}

/// The desktop's message for `text`, on both engines.
fn desktop_error(text: &str) -> String {
    match on_both_engines(Profile::Desktop, text).0 {
        Exit::RuntimeError { message, .. } => message,
        e => panic!("{e}, not an error:\n{text}"),
    }
}

fn desktop_halts(text: &str) {
    let (e, _) = on_both_engines(Profile::Desktop, text);
    assert_eq!(e, Exit::Halted, "{text}");
}

const MAIN: &str = "function Main.main 0\n";
const END: &str = "push constant 0\nreturn\n";

#[test]
fn the_desktop_tests_the_value_of_each_pop_pointer() {
    assert_eq!(
        desktop_error(&format!("{MAIN}push constant 30000\npop pointer 1\n{END}")),
        "'That' segment must be in the Heap or Screen range in Main.main.2"
    );
    assert_eq!(
        desktop_error(&format!("{MAIN}push constant 16384\npop pointer 0\n{END}")),
        "'This' segment must be in the Heap range in Main.main.2"
    );
    assert_eq!(
        desktop_error(&format!("{MAIN}push constant 2047\npop pointer 1\n{END}")),
        "'That' segment must be in the Heap or Screen range in Main.main.2"
    );
    // THIS: the heap, 0 or below; THAT: 0, the heap, the screen and 24576.
    for (v, p) in [
        (2048, 0),
        (16383, 0),
        (0, 0),
        (-5, 0),
        (0, 1),
        (2048, 1),
        (16384, 1),
        (24576, 1),
    ] {
        let push = if v < 0 {
            format!("push constant {}\nneg", -v)
        } else {
            format!("push constant {v}")
        };
        desktop_halts(&format!("{MAIN}{push}\npop pointer {p}\n{END}"));
    }
    // The web IDE takes any value.
    let (e, _) = on_both_engines(
        Profile::Web,
        &format!("{MAIN}push constant 30000\npop pointer 1\n{END}"),
    );
    assert_eq!(e, Exit::Halted);
}

#[test]
fn a_fused_array_access_outside_the_heap_and_screen_fails_at_its_pop_pointer() {
    let read = |base: i32| {
        format!("{MAIN}push constant {base}\npush constant 5\nadd\npop pointer 1\npush that 0\npop temp 0\n{END}")
    };
    assert_eq!(
        desktop_error(&read(24572)),
        "'That' segment must be in the Heap or Screen range in Main.main.4"
    );
    desktop_halts(&read(24571));
    let store = |base: i32| {
        format!(
            "{MAIN}push constant {base}\npush constant 1\nadd\npush constant 7\npop temp 0\n\
             pop pointer 1\npush temp 0\npop that 0\n{END}"
        )
    };
    assert_eq!(
        desktop_error(&store(1000)),
        "'That' segment must be in the Heap or Screen range in Main.main.6"
    );
    desktop_halts(&store(3000));
}

#[test]
fn the_desktop_tests_each_this_and_that_address_instead_of_the_web_ides_pointer_check() {
    // THIS was never set: 0 is outside the heap.
    let text = format!("{MAIN}push this 0\npop temp 0\n{END}");
    assert_eq!(desktop_error(&text), "Out of segment space in Main.main.1");
    let Exit::RuntimeError { message, .. } = on_both_engines(Profile::Web, &text).0 else {
        panic!()
    };
    assert_eq!(
        message,
        "The this segment cannot be accessed since it was not initialized"
    );
    // The last heap word, then one past it.
    desktop_halts(&format!(
        "{MAIN}push constant 16380\npop pointer 0\npush this 3\npop this 3\n{END}"
    ));
    assert_eq!(
        desktop_error(&format!(
            "{MAIN}push constant 16380\npop pointer 0\npush this 4\npop temp 0\n{END}"
        )),
        "Out of segment space in Main.main.3"
    );
    // `that` reaches the keyboard word and stops there.
    desktop_halts(&format!(
        "{MAIN}push constant 24570\npop pointer 1\npush that 6\npop temp 0\n{END}"
    ));
    assert_eq!(
        desktop_error(&format!(
            "{MAIN}push constant 24570\npop pointer 1\npush that 7\npop temp 0\n{END}"
        )),
        "Out of segment space in Main.main.3"
    );
    // A callee uses the pointer its caller set, with no `pop pointer` of
    // its own: the desktop runs it, the web IDE refuses it.
    let text = format!(
        "{MAIN}push constant 3000\npop pointer 0\ncall Main.f 0\npop temp 0\n{END}\
         function Main.f 0\npush this 2\nreturn\n"
    );
    desktop_halts(&text);
    let (e, _) = on_both_engines(Profile::Web, &text);
    assert!(matches!(e, Exit::RuntimeError { .. }), "{e}");
}

/// Fused instructions let a `this`/`that` offset below 64 through at once
/// where the pointer leaves room for every such offset (crate::exec); at
/// the border, one word either side, each access still gets the desktop's
/// answer.
#[test]
fn at_the_end_of_the_heap_and_the_screen_fused_accesses_get_the_desktops_answer() {
    for (p, seg, room, last) in [(0, "this", 16320, 16383), (1, "that", 24513, 24576)] {
        for base in [room, room + 1] {
            let text = format!(
                "{MAIN}push constant {base}\npop pointer {p}\npush {seg} 63\npush constant 1\nadd\n\
                 pop temp 0\n{END}"
            );
            if base + 63 <= last {
                desktop_halts(&text);
            } else {
                assert_eq!(desktop_error(&text), "Out of segment space in Main.main.3");
            }
        }
    }
}

#[test]
fn after_a_pop_pointer_1_of_0_that_reaches_from_word_0_until_a_return() {
    // RAM[5..] through THAT = 0, in the function and in its callee.
    desktop_halts(&format!(
        "{MAIN}push constant 0\npop pointer 1\npush that 5\npop that 6\n\
         call Main.f 0\npop temp 0\n{END}function Main.f 0\npush that 7\nreturn\n"
    ));
    // The return starts the range at 2048 again.
    assert_eq!(
        desktop_error(&format!(
            "{MAIN}push constant 0\npop pointer 1\ncall Main.f 0\npop temp 0\npush that 5\n{END}\
             function Main.f 0\npush constant 1\nreturn\n"
        )),
        "Out of segment space in Main.main.5"
    );
    // So does a `pop pointer 1` of any other value, for the same word.
    assert_eq!(
        desktop_error(&format!(
            "{MAIN}push constant 0\npop pointer 1\npush constant 2048\npop pointer 1\n\
             push constant 0\npop pointer 1\npush that 1\npop temp 0\npush constant 3000\n\
             pop pointer 1\npush that 0\npop temp 0\npush pointer 1\npush constant 2048\nsub\n\
             pop pointer 1\n{END}"
        )),
        "'That' segment must be in the Heap or Screen range in Main.main.16"
    );
}

/// A VM call's RET word is the desktop's program address of the command
/// after the call (every non-blank line one address from 0, a label after
/// the call skipped), and a return leaves FRAME in R13 and RET in R14, as
/// the desktop's return does; a return with LCL = 0 (from a VM `Sys.init`,
/// which runs without a frame) has nowhere to go. Both engines.
#[test]
fn a_calls_ret_word_is_a_program_address_and_a_return_sets_r13_and_r14() {
    let text = "function Sys.init 0\ncall Main.f 0\nreturn\n\
                function Main.f 0\npush constant 7\nlabel L\nreturn\n";
    let program = Program::from_sources(&[("Main.vm", text)]).unwrap();
    for engine in ENGINES {
        let mut m = on_engine(&program, Profile::Desktop, engine);
        // Sys.init's function line, the call, f's function line and its
        // push: f's frame is at 256 (the entry has none).
        assert!(matches!(m.run(Some(4)), Exit::Budget { .. }));
        assert_eq!(
            words(&m, 256, 261),
            [2, 0, 0, 0, 0],
            "{engine:?}: RET is the address of Sys.init's `return`"
        );
        assert!(matches!(m.run(Some(1)), Exit::Budget { .. }));
        assert_eq!(words(&m, 13, 15), [261, 2], "{engine:?}: R13, R14");
        assert_eq!((m.ram().read(0), m.ram().read(256)), (257, 7));
        match m.run(Some(10)) {
            Exit::RuntimeError { message, .. } => {
                assert_eq!(message, "Nowhere to return to in Sys.init.2", "{engine:?}")
            }
            other => panic!("{engine:?}: {other}"),
        }
        assert_eq!(m.steps(), 6);
    }
}

/// A fused array read (`a[i]`) whose pointer the desktop refuses leaves
/// RAM as the plain commands leave it, even where its operand, a local,
/// lies at the top of the stack that the fused sum writes (found by
/// `compiled_execution_equals_interpretation`). Both engines, and the
/// commands one step at a time.
#[test]
fn a_refused_array_read_leaves_the_stack_as_the_plain_commands_do() {
    let text = "function Main.main 0\npush constant 0\nreturn\nfunction Main.f 3\nlabel L0\nadd\npush constant 1\npop static 0\npop pointer 0\n\
                if-goto L0\npush local 0\npush static 0\nadd\npop pointer 1\npush that 0\n\
                pop temp 0\npush constant 0\nreturn\n";
    let program = Program::from_sources(&[("Main.vm", text)]).unwrap();
    let run = |engine, one_by_one: bool| {
        let mut m = on_engine(&program, Profile::Desktop, engine);
        m.call("Main.f", &[0, 0], Some(0)).unwrap();
        let exit = if one_by_one {
            loop {
                match m.run(Some(1)) {
                    Exit::Budget { .. } => {}
                    other => break other,
                }
            }
        } else {
            m.run(Some(1000))
        };
        (exit.to_string(), m.steps(), words(&m, 256, 266))
    };
    let plain = run(hack_vm::Engine::Interp, true);
    // Main.f's local 0, at 263, is 0 + 1 when `pop pointer 1` refuses 1.
    assert_eq!(plain.2[7], 1, "{plain:?}");
    assert_eq!(run(hack_vm::Engine::Interp, false), plain);
    assert_eq!(run(hack_vm::Engine::Native, false), plain);
}
