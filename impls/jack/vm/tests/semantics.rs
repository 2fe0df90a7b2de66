//! Edge cases of every VM command and of the machine (spec §1, §2).

use hack_vm::{Config, Exit, FnId, KeyScript, Machine, Profile, Program, Ram, Register, Watcher};

fn load(sources: &[(&str, &str)]) -> Machine {
    load_under(sources, Profile::Desktop)
}

fn load_under(sources: &[(&str, &str)], profile: Profile) -> Machine {
    Machine::new(
        Program::from_sources(sources).expect("loads"),
        Config {
            profile,
            ..Config::default()
        },
    )
}

/// Run a single-file program without functions from SP=256 to its end and
/// return the machine.
fn run_flat(src: &str) -> Machine {
    run_flat_under(src, Profile::Desktop)
}

/// [`run_flat`] under `profile`.
fn run_flat_under(src: &str, profile: Profile) -> Machine {
    let mut m = load_under(&[("T.vm", src)], profile);
    m.set_register(Register::Sp, 256);
    assert_eq!(m.run(Some(10_000)), Exit::Halted);
    m
}

fn top(m: &Machine) -> i16 {
    m.ram().read(i32::from(m.ram().read(0)) - 1)
}

fn load_err(sources: &[(&str, &str)]) -> String {
    Program::from_sources(sources)
        .expect_err("must not load")
        .to_string()
}

fn runtime_error(exit: Exit) -> (String, String) {
    match exit {
        Exit::RuntimeError { message, stack } => (message, stack.to_string()),
        other => panic!("expected a runtime error, got {other}"),
    }
}

/// Push -32768: 0 - 32767 - 1.
const MIN: &str = "push constant 0\npush constant 32767\nsub\npush constant 1\nsub\n";

#[test]
fn arithmetic_wraps() {
    assert_eq!(
        top(&run_flat("push constant 32767\npush constant 1\nadd\n")),
        -32768
    );
    assert_eq!(
        top(&run_flat(&format!("{MIN}push constant 1\nsub\n"))),
        32767
    );
    assert_eq!(top(&run_flat(&format!("{MIN}neg\n"))), -32768);
    assert_eq!(top(&run_flat("push constant 5\nneg\n")), -5);
    assert_eq!(top(&run_flat("push constant 0\nnot\n")), -1);
    assert_eq!(
        top(&run_flat("push constant 12\npush constant 10\nand\n")),
        8
    );
    assert_eq!(
        top(&run_flat("push constant 12\npush constant 10\nor\n")),
        14
    );
    assert_eq!(top(&run_flat(&format!("{MIN}{MIN}add\n"))), 0);
}

#[test]
fn comparisons_use_true_signed_values() {
    let minus_one = "push constant 1\nneg\n";
    let cases = [
        (format!("push constant 32767\n{minus_one}gt\n"), -1),
        (format!("{MIN}push constant 1\nlt\n"), -1),
        (format!("{MIN}push constant 32767\nlt\n"), -1),
        (format!("push constant 32767\n{MIN}gt\n"), -1),
        (format!("push constant 32767\n{MIN}lt\n"), 0),
        (format!("{MIN}{MIN}eq\n"), -1),
        (format!("{MIN}push constant 32767\neq\n"), 0),
        (format!("{MIN}{MIN}gt\n"), 0),
        (format!("{minus_one}push constant 0\nlt\n"), -1),
    ];
    for (src, want) in cases {
        assert_eq!(top(&run_flat(&src)), want, "{src}");
    }
}

#[test]
fn if_goto_pops_and_jumps_on_nonzero() {
    let src = "push constant 2\nneg\nif-goto A\npush constant 1\nlabel A\nlabel B\npush constant 0\nif-goto B\npush constant 9\n";
    let m = run_flat(src);
    // Jumped over `push 1`; then 0 does not jump.
    assert_eq!(m.ram().read(0), 257);
    assert_eq!(top(&m), 9);
    // Labels are free: 6 commands ran; the desktop spends one more step
    // at `label B`, where the jump to A lands (A is followed by B).
    assert_eq!(m.steps(), 7);
    let mut web = load_under(&[("T.vm", src)], Profile::Web);
    web.set_register(Register::Sp, 256);
    assert_eq!(web.run(Some(10_000)), Exit::Halted);
    assert_eq!(web.steps(), 6);
    // The same end state, but for the heap header: the web IDE sets it at
    // reset, the desktop only in a Memory.init that this program never calls.
    assert_eq!(&m.ram().words()[2048..2050], [0, 0]);
    assert_eq!(&web.ram().words()[2048..2050], [0, 14334]);
    assert!(
        web.ram().words()[..2048] == m.ram().words()[..2048],
        "same end state"
    );
    assert!(
        web.ram().words()[2050..] == m.ram().words()[2050..],
        "same end state"
    );
}

#[test]
fn pop_below_256_is_a_runtime_error() {
    let src = [("T.vm", "push constant 1\npop temp 0\npop temp 0\n")];
    for (profile, message) in [
        (
            Profile::Web,
            "Cannot pop the stack below 256 in strict mode",
        ),
        (Profile::Desktop, "Stack overflow in __implicit.2"),
    ] {
        let mut m = load_under(&src, profile);
        let (msg, stack) = runtime_error(m.run(None));
        assert_eq!(msg, message);
        assert_eq!(stack, "__implicit");
        // The failing pop is a step.
        assert_eq!(m.steps(), 3);
    }
    // Web: below 256 is fine if SP is not exactly 256. Desktop: SP must
    // stay in the stack segment.
    let mut m = load_under(&[("T.vm", "pop temp 0\n")], Profile::Web);
    m.set_register(Register::Sp, 100);
    assert_eq!(m.run(None), Exit::Halted);
    assert_eq!(m.ram().read(0), 99);
    let mut m = load(&[("T.vm", "pop temp 0\n")]);
    m.set_register(Register::Sp, 100);
    assert_eq!(
        runtime_error(m.run(None)).0,
        "Stack overflow in __implicit.0"
    );
}

#[test]
fn memory_outside_ram_reads_minus_one_and_drops_writes() {
    // The web IDE takes any pointer (the desktop refuses THAT = -1 and
    // `that 1` of 24576). THAT = -1 (65535): reads give -1, writes vanish.
    let flat = |src| run_flat_under(src, Profile::Web);
    let m = flat("push constant 0\nnot\npop pointer 1\npush that 0\npush constant 5\npop that 0\npush that 0\n");
    assert_eq!(m.ram().read(256), -1);
    assert_eq!(m.ram().read(257), -1);
    // THAT = 24576 + 1 via that 1: keyboard word is writable, 24577 is not.
    let m = flat(
        "push constant 24576\npop pointer 1\npush constant 7\npop that 0\npush constant 8\npop that 1\npush that 0\npush that 1\n",
    );
    assert_eq!(
        (m.ram().read(24576), m.ram().read(256), m.ram().read(257)),
        (7, 7, -1)
    );
}

/// `src` (one file, `Sys.vm`) loaded under the web profile on `engine`.
fn web_machine(src: &str, engine: hack_vm::Engine) -> Machine {
    Machine::new(
        Program::from_sources(&[("Sys.vm", src)]).unwrap(),
        Config {
            profile: Profile::Web,
            engine,
            ..Config::default()
        },
    )
}

/// A push at SP = 0 writes its value into SP, then SP becomes 1, as the
/// web IDE's push does (it keeps SP's old value for the increment); the
/// next push writes RAM[1]. Both engines.
#[test]
fn a_push_at_sp_0_leaves_sp_1() {
    let src = "function Sys.init 0\npush constant 0\npop pointer 1\npush constant 0\npop that 0\n\
               push constant 7\npush constant 5\nlabel L\ngoto L\n";
    for engine in [hack_vm::Engine::Interp, hack_vm::Engine::Native] {
        let mut m = web_machine(src, engine);
        assert!(
            matches!(m.run(Some(100)), Exit::Budget { .. }),
            "{engine:?}"
        );
        assert_eq!((m.ram().read(0), m.ram().read(1)), (2, 5), "{engine:?}");
    }
}

/// `src` (one file, `Sys.vm`) under the web profile, on both engines
/// (which must agree): how it ended and after how many steps.
fn web_on_both_engines(src: &str, budget: u64) -> (String, u64) {
    let runs: Vec<(String, u64)> = [hack_vm::Engine::Interp, hack_vm::Engine::Native]
        .into_iter()
        .map(|engine| {
            let mut m = web_machine(src, engine);
            let exit = m.run(Some(budget));
            (exit.to_string(), m.steps())
        })
        .collect();
    assert_eq!(runs[0], runs[1], "the interpreter, then compiled code");
    runs[0].clone()
}

/// `Main.f` stores `ret` into its own RET word (through `that`, from
/// LCL - 5) and returns: 11 steps from the start to its return.
fn returning_to(ret: i16) -> String {
    let set = constant(ret);
    format!(
        "function Sys.init 0\ncall Main.f 0\nlabel L\ngoto L\n\
         function Main.f 0\npush constant 0\npop pointer 1\npush that 1\npush constant 5\nsub\n\
         pop pointer 1\n{set}pop that 0\npush constant 0\nreturn\n"
    )
}

/// The commands that push `k`.
fn constant(k: i16) -> String {
    if k < 0 {
        format!("push constant 0\npush constant {}\nsub\n", -i32::from(k))
    } else {
        format!("push constant {k}\n")
    }
}

/// As [`returning_to`], with `Main.g` (Sys.init's callee, which the
/// interpreter calls) calling `Main.f`, which writes its RET word at 261
/// without reading a register, after `pad` pairs of commands (`push
/// constant 1`, `pop temp 0`): from 17 on, too long for compiled code to
/// run it inline, so that it runs as a compiled call's callee. 8 + 2 pad
/// steps to its return.
fn returning_after(ret: i16, pad: usize) -> String {
    let set = constant(ret);
    format!(
        "function Sys.init 0\ncall Main.g 0\nlabel L\ngoto L\n\
         function Main.g 0\ncall Main.f 0\nlabel M\ngoto M\n\
         function Main.f 0\n{}push constant 261\npop pointer 1\n{set}pop that 0\n\
         push constant 0\nreturn\n",
        "push constant 1\npop temp 0\n".repeat(pad)
    )
}

/// A return resumes its caller at the RET word plus one, as the web IDE
/// does: past the caller's last command the return itself runs and the
/// next step fails with the IDE's message; before its first command the VM
/// halts.
#[test]
fn a_web_return_past_its_callers_end_fails_the_next_step() {
    // Sys.init's commands: its function line, call, label, goto (4).
    let (exit, steps) = web_on_both_engines(&returning_to(30000), 100);
    assert!(
        exit.contains("Current operation step beyond end of function operations (30001 > 4)"),
        "{exit}"
    );
    assert!(exit.contains("in Sys.init"), "{exit}");
    assert_eq!(steps, 12, "the call, f's 10 commands, the step after");
    let (exit, steps) = web_on_both_engines(&returning_to(-5), 100);
    assert_eq!((exit.as_str(), steps), ("halted", 13));
    // Its own RET word: back after the call, looping to the budget.
    let (exit, steps) = web_on_both_engines(&returning_to(1), 100);
    assert!(exit.contains("budget"), "{exit}");
    assert_eq!(steps, 100);
}

/// The same returns from a callee that a compiled call runs (not inline):
/// its return finds a RET word other than the one the call wrote, and the
/// interpreter makes it; with its own RET word, compiled code goes on.
#[test]
fn a_compiled_callee_returns_where_its_ret_word_says() {
    for pad in [17, 40] {
        let (exit, steps) = web_on_both_engines(&returning_after(30000, pad), 1000);
        assert!(exit.contains("(30001 > 4) in Sys.init > Main.g"), "{exit}");
        assert_eq!(steps, 9 + 2 * pad as u64);
        let (exit, steps) = web_on_both_engines(&returning_after(-5, pad), 1000);
        assert_eq!((exit.as_str(), steps), ("halted", 10 + 2 * pad as u64));
        let (exit, steps) = web_on_both_engines(&returning_after(1, pad), 1000);
        assert!(exit.contains("budget"), "{exit}");
        assert_eq!(steps, 1000);
        // Every step but Sys.init's call ran compiled, the return included.
        let mut m = web_machine(&returning_after(1, pad), hack_vm::Engine::Native);
        m.run(Some(1000));
        assert_eq!(m.compiled_steps(), 999);
    }
}

/// A recursion that runs its stack past the end of RAM. Each level takes
/// 8 words (a frame and 3 locals); the 3,041st call's frame starts at the
/// keyboard word, 24,576, so its own stack lies past the end: the test it
/// pops reads -1, it returns at once, and its saved LCL and ARG, written
/// past the end, come back as -1. Its caller's return then reads its RET
/// word outside RAM, as 65,535, and fails the step after it: 1 + 3,040 x 9
/// + 10 + 1 steps, plus the failing one.
#[test]
fn a_web_recursion_past_the_end_of_ram_stops_after_a_return() {
    let src = "function Sys.init 0\ncall Main.f 0\nlabel E\ngoto E\n\
               function Main.f 3\npush static 0\npush constant 1\nadd\npop static 0\n\
               push static 0\npush constant 5000\neq\nif-goto D\ncall Main.f 0\nreturn\n\
               label D\npush constant 0\nreturn\n";
    let (exit, steps) = web_on_both_engines(src, 1_000_000);
    assert!(
        exit.contains("Current operation step beyond end of function operations (65536 > 14)"),
        "{exit}"
    );
    assert!(exit.contains("Main.f x 3039"), "{exit}");
    assert_eq!(steps, 1 + 3040 * 9 + 10 + 1 + 1);
}

#[test]
fn computed_addresses_reach_the_registers() {
    // THAT = 0: `push that 0` reads SP, `pop that 3` writes THIS.
    let m = run_flat("push constant 0\npop pointer 1\npush that 0\npush constant 1234\npop that 3\npush pointer 0\n");
    assert_eq!(m.ram().read(256), 256);
    assert_eq!(m.ram().read(3), 1234);
    assert_eq!(top(&m), 1234);
    // `pop constant 1` writes LCL (a quirk).
    let m = run_flat("push constant 4321\npop constant 1\n");
    assert_eq!(m.ram().read(1), 4321);
}

#[test]
fn temp_pointer_and_statics() {
    let m = run_flat(
        "push constant 3\npop temp 7\npush temp 7\npush constant 9\npop static 5\npush static 5\n",
    );
    assert_eq!(m.ram().read(12), 3);
    // Desktop: the file's static segment from 16, static 5 at 21 (the web
    // IDE's first slot would be 16).
    assert_eq!(m.ram().read(21), 9);
    assert_eq!(top(&m), 9);
}

#[test]
fn statics_get_slots_in_order_of_first_appearance_per_class() {
    let a = "function A.f 0\npush static 1\npush static 0\npush static 1\nreturn\n";
    let b = "function B.f 0\npush constant 5\npop static 0\npush constant 0\nreturn\nfunction B.g 0\npush static 7\nreturn\n";
    let main = "function Main.main 0\npush constant 0\nreturn\n";
    let p = Program::from_sources(&[("A.vm", a), ("B.vm", b), ("Main.vm", main)]).unwrap();
    assert_eq!(p.static_count(), 4);
    let mut m = Machine::new(p, Config::default());
    m.call("B.f", &[], None).unwrap();
    // A.1 -> 16, A.0 -> 17, B.0 -> 18, B.7 -> 19.
    assert_eq!(m.ram().read(18), 5);
}

#[test]
fn more_than_240_statics_fail_on_the_web_and_run_on_the_desktop() {
    let mut src = String::new();
    for c in 0..2 {
        src.push_str(&format!("function C{c}.f 0\n"));
        for i in 0..121 {
            src.push_str(&format!("push static {i}\npop temp 0\n"));
        }
        src.push_str("push constant 0\nreturn\n");
    }
    src.push_str("function Main.main 0\npush constant 0\nreturn\n");
    // Web: 242 slots by class; C1's last two do not fit.
    let mut m = load_under(&[("T.vm", src.as_str())], Profile::Web);
    assert_eq!(m.call("C0.f", &[], None).unwrap(), Exit::Returned(0));
    let (msg, stack) = runtime_error(m.call("C1.f", &[], None).unwrap());
    assert!(msg.contains("Too many static variables"), "{msg}");
    assert_eq!(stack, "C1.f");
    // Desktop: one segment per file, 121 words for T.vm: both fit. Two files
    // of 121 reach RAM[257], which the desktop allows.
    let mut m = load(&[("T.vm", src.as_str())]);
    assert_eq!(m.call("C1.f", &[], None).unwrap(), Exit::Returned(0));
    let one = |c: &str| {
        let mut f = format!("function {c}.f 0\n");
        for i in 0..121 {
            f.push_str(&format!("push static {i}\npop temp 0\n"));
        }
        f + "push constant 0\nreturn\n"
    };
    let (c0, c1) = (one("C0"), one("C1"));
    let main = "function Main.main 0\npush constant 0\nreturn\n";
    let mut m = load(&[
        ("C0.vm", c0.as_str()),
        ("C1.vm", c1.as_str()),
        ("Main.vm", main),
    ]);
    assert_eq!(m.call("C0.f", &[], None).unwrap(), Exit::Returned(0));
    // The desktop's segment of C1.vm is RAM[137..=257]: it runs on past
    // RAM[255], into the stack (its segments are bounded by each file's
    // largest index, not by 255).
    assert_eq!(m.call("C1.f", &[], None).unwrap(), Exit::Returned(0));
}

const FIB: &str = concat!(
    fib_function!(),
    "function Main.main 0
push constant 10
call Main.fib 1
return
"
);

#[test]
fn host_calls_return_values_and_leave_the_stack_clean() {
    let mut m = load(&[("Main.vm", FIB)]);
    for (n, f) in [(10, 55), (1, 1), (0, 0), (20, 6765)] {
        assert_eq!(m.call("Main.fib", &[n], None).unwrap(), Exit::Returned(f));
        assert_eq!(m.ram().read(0), 256);
    }
    assert!(m.call("Main.nope", &[], None).is_err());
    // Clones are independent snapshots, and can run in parallel.
    let snap = m.clone();
    let results: Vec<Exit> = std::thread::scope(|s| {
        let hs: Vec<_> = (0..4)
            .map(|i| {
                let mut c = snap.clone();
                s.spawn(move || c.call("Main.fib", &[i + 5], None).unwrap())
            })
            .collect();
        hs.into_iter().map(|h| h.join().unwrap()).collect()
    });
    assert_eq!(results, [5, 8, 13, 21].map(Exit::Returned));
}

#[test]
fn budget_stops_exactly_and_reports_the_call_stack() {
    let mut m = load(&[("Main.vm", FIB)]);
    let e = m.run(Some(25));
    assert_eq!(m.steps(), 25);
    let Exit::Budget { stack } = e else {
        panic!("{e}")
    };
    assert_eq!(stack.names().next(), Some("Sys.init"));
    assert_eq!(stack.innermost(), Some("Main.fib"));
    // Continue to the end.
    assert_eq!(m.run(None), Exit::Halted);
    assert_eq!(m.ram().read(266), 55);
    let total = m.steps();
    // Any budget split gives the same total.
    for chunk in [1, 3, 7, 100] {
        let mut m = load(&[("Main.vm", FIB)]);
        while let Exit::Budget { .. } = m.run(Some(chunk)) {}
        assert_eq!(m.steps(), total, "chunk {chunk}");
    }
}

#[test]
fn an_observed_run_ends_like_a_plain_one_and_reports_every_slice() {
    let mut plain = load(&[("Main.vm", FIB)]);
    assert_eq!(plain.run(None), Exit::Halted);
    let total = plain.steps();
    for every in [1, 7, 100, total, total + 1] {
        let mut m = load(&[("Main.vm", FIB)]);
        let mut seen = Vec::new();
        assert_eq!(
            m.run_observed(None, every, &mut |n| seen.push(n)),
            Exit::Halted
        );
        assert_eq!(m.steps(), total, "every {every}");
        assert_eq!(m.ram().read(266), 55);
        // One report a slice (and one more if the end comes right after a
        // slice's last instruction), never going back.
        let slices = total.div_ceil(every) as usize;
        assert!((slices..=slices + 1).contains(&seen.len()), "every {every}");
        assert!(seen.windows(2).all(|w| w[0] <= w[1]), "every {every}");
        assert_eq!(seen.last(), Some(&total));
    }
    // A budget below the program's length stops exactly there, with the
    // call stack, however it is sliced; a zero slice counts as one.
    for every in [0, 1, 10, 24, 25, 26, 1000] {
        let mut m = load(&[("Main.vm", FIB)]);
        let mut last = 0;
        let e = m.run_observed(Some(25), every, &mut |n| last = n);
        assert_eq!(m.steps(), 25, "every {every}");
        assert_eq!(last, 25);
        let Exit::Budget { stack } = e else {
            panic!("every {every}: {e}")
        };
        assert_eq!(stack.innermost(), Some("Main.fib"));
    }
}

#[test]
fn runtime_errors_of_segments() {
    let src = "
function Main.args 0
push argument 1
return
function Main.local 1
push local 1
return
function Main.field 0
push this 0
return
function Main.method 0
push argument 0
pop pointer 0
push this 0
call Main.field 0
return
function Main.main 0
push constant 0
return
";
    let m = load_under(&[("Main.vm", src)], Profile::Web);
    let err = |name: &str, args: &[i16]| runtime_error(m.clone().call(name, args, None).unwrap());
    assert_eq!(err("Main.args", &[1]).0, "Argument offset out of bounds");
    assert_eq!(
        m.clone().call("Main.args", &[1, 2], None).unwrap(),
        Exit::Returned(2)
    );
    assert_eq!(err("Main.local", &[]).0, "Local offset out of bounds");
    assert_eq!(
        err("Main.field", &[]).0,
        "The this segment cannot be accessed since it was not initialized"
    );
    // A method may read fields; the function it calls may not.
    let (msg, stack) = err("Main.method", &[3000]);
    assert!(msg.contains("this segment"), "{msg}");
    assert_eq!(stack, "Main.method > Main.field");
    // The desktop words its shared checks its own way, with the function
    // and the index of the failing command in it (the `function` line is
    // command 0): "Out of segment space in Main.main.1" in its own run.
    let d = load(&[("Main.vm", src)]);
    let derr = |name: &str, args: &[i16]| runtime_error(d.clone().call(name, args, None).unwrap());
    assert_eq!(
        derr("Main.args", &[1]).0,
        "Out of segment space in Main.args.1"
    );
    assert_eq!(
        derr("Main.local", &[]).0,
        "Out of segment space in Main.local.1"
    );
}

#[test]
fn entry_without_frame_cannot_use_local_or_argument() {
    let load = |s: &[(&str, &str)]| load_under(s, Profile::Web);
    let mut m = load(&[("T.vm", "push local 0\n")]);
    let (msg, _) = runtime_error(m.run(None));
    assert_eq!(
        msg,
        "The local segment cannot be accessed since it was not initialized"
    );
    let mut m = load(&[("T.vm", "function Sys.init 0\npush argument 0\n")]);
    let (msg, _) = runtime_error(m.run(None));
    assert_eq!(
        msg,
        "The argument segment cannot be accessed since it was not initialized"
    );
    let mut m = load(&[("T.vm", "push that 0\n")]);
    let (msg, _) = runtime_error(m.run(None));
    assert!(msg.contains("that segment"), "{msg}");
}

#[test]
fn builtins_replace_arguments_with_one_value() {
    let src = "function Main.main 0\npush constant 7\npush constant 3\ncall Math.max 2\npush constant 3000\n\
               push constant 200\ncall Memory.poke 2\npush constant 9\nneg\npush constant 2\ncall Math.divide 2\nreturn\n";
    let mut m = load(&[("Main.vm", src)]);
    assert_eq!(m.run(None), Exit::Halted);
    // Stack of Main.main: 7 (max), 0 (void poke), then -9/2 returned into
    // RAM[ARG] = 261 (Main.main's frame, right above the built-in
    // Sys.init's at 256).
    assert_eq!(m.ram().read(3000), 200);
    assert_eq!(m.ram().read(261), -4, "desktop truncates: -9/2 = -4");
    // The hidden call of Sys.init, `function Main.main`, 11 commands.
    assert_eq!(m.steps(), 1 + 1 + 11);
}

#[test]
fn web_profile_divides_toward_minus_infinity() {
    let src =
        "function Main.main 0\npush constant 9\nneg\npush constant 2\ncall Math.divide 2\nreturn\n";
    let p = Program::from_sources(&[("Main.vm", src)]).unwrap();
    let mut m = Machine::new(
        p,
        Config {
            profile: hack_vm::Profile::Web,
            ..Config::default()
        },
    );
    m.run(None);
    assert_eq!(m.ram().read(263), -5);
}

/// A machine may take the other profile's `Math.divide` and keep the rest of
/// its own (the fault `web-divide`): on both engines, and for a divisor
/// the compiled code divides inline as for one it passes to the OS.
#[test]
fn the_divide_rule_is_chosen_apart_from_the_profile() {
    let src = "function Main.main 0\npush constant 0\nreturn\n\
               function Main.f 0\npush constant 9\nneg\npush constant 2\ncall Math.divide 2\nreturn\n\
               function Main.g 0\npush constant 7\npush constant 2\nneg\ncall Math.divide 2\nreturn\n";
    let p = Program::from_sources(&[("Main.vm", src)]).unwrap();
    for engine in [hack_vm::Engine::Interp, hack_vm::Engine::Native] {
        for (divide, f, g) in [
            (None, -4, -3),
            (Some(hack_vm::DivideRule::Truncate), -4, -3),
            (Some(hack_vm::DivideRule::Floor), -5, -4),
        ] {
            let mut m = Machine::new(
                p.clone(),
                Config {
                    profile: Profile::Desktop,
                    divide,
                    engine,
                    ..Config::default()
                },
            );
            let mut call = |name| m.call(name, &[], Some(1000)).unwrap();
            assert_eq!(call("Main.f"), Exit::Returned(f), "{engine:?} {divide:?}");
            assert_eq!(call("Main.g"), Exit::Returned(g), "{engine:?} {divide:?}");
        }
    }
}

#[test]
fn sys_error_and_divide_by_zero_stop_with_the_stack() {
    let src = "function Main.main 0\ncall Main.f 0\nreturn\nfunction Main.f 0\npush constant 1\npush constant 0\ncall Math.divide 2\nreturn\n";
    let mut m = load(&[("Main.vm", src)]);
    match m.run(None) {
        Exit::SysError { code, stack } => {
            assert_eq!(code, 3);
            assert_eq!(stack.to_string(), "Sys.init > Main.main > Main.f");
        }
        other => panic!("{other}"),
    }
    // Ended runs stay ended.
    assert!(matches!(m.run(None), Exit::SysError { code: 3, .. }));
    let mut m = load(&[(
        "Main.vm",
        "function Main.main 0\npush constant 42\ncall Sys.error 1\nreturn\n",
    )]);
    assert!(matches!(m.run(None), Exit::SysError { code: 42, .. }));
    let mut m = load(&[(
        "Main.vm",
        "function Main.main 0\ncall Sys.halt 0\npush constant 1\nreturn\n",
    )]);
    assert_eq!(m.run(None), Exit::Halted);
    // Start-up, `function Main.main`, and the call of Sys.halt.
    assert_eq!(m.steps(), 3);
}

#[test]
fn a_vm_function_overrides_the_builtin() {
    let math = "function Math.multiply 0\npush constant 77\nreturn\n";
    let main =
        "function Main.main 0\npush constant 2\npush constant 3\ncall Math.multiply 2\nreturn\n";
    let p = Program::from_sources(&[("Main.vm", main), ("Math.vm", math)]).unwrap();
    let mut m = Machine::new(p, Config::default());
    assert_eq!(m.call("Main.main", &[], None).unwrap(), Exit::Returned(77));
}

#[test]
fn return_follows_an_overwritten_ret_word() {
    // Main.main: 0 function, 1 call, 2 push 99, 3 return, 4 push 1, 5 return.
    let main =
        "function Main.main 0\ncall Main.f 0\npush constant 99\nreturn\npush constant 1\nreturn\n";
    let plain = "function Main.f 0\npush constant 0\nreturn\n";
    // RAM[LCL-5] := 3 through `that`, so the return resumes at command 4
    // (the web IDE: the desktop keeps `that` off the stack).
    let rewrite =
        "function Main.f 0\npush constant 0\npop pointer 1\npush that 1\npush constant 5\nsub\n\
                   pop pointer 1\npush constant 3\npop that 0\npush constant 0\nreturn\n";
    for (f, want) in [(plain, 99), (rewrite, 1)] {
        let src = format!("{main}{f}");
        let mut m = load_under(&[("Main.vm", src.as_str())], Profile::Web);
        assert_eq!(
            m.call("Main.main", &[], None).unwrap(),
            Exit::Returned(want)
        );
    }
}

#[test]
fn entry_point_rules() {
    let p = Program::from_sources(&[("T.vm", "push constant 1\n")]).unwrap();
    assert_eq!(p.function_name(p.entry()), "__implicit");
    let p = Program::from_sources(&[("T.vm", "function Foo.bar 0\npush constant 1\n")]).unwrap();
    assert_eq!(p.function_name(p.entry()), "Foo.bar");
    let p = Program::from_sources(&[("T.vm", "push constant 1\nfunction Main.main 0\nreturn\n")])
        .unwrap();
    assert_eq!(p.function_name(p.entry()), "Sys.init");
    let e = load_err(&[("T.vm", "function A.a 0\nreturn\nfunction B.b 0\nreturn\n")]);
    assert_eq!(e, "Could not determine an entry point for VM");
    let e = load_err(&[("T.vm", "push constant 1\nfunction Sys.init 0\nreturn\n")]);
    assert!(e.contains("Sys.init"), "{e}");
}

#[test]
fn load_time_checks_name_file_and_line() {
    let cases: [(&[(&str, &str)], &str); 9] = [
        (
            &[("T.vm", "function A.f 0\nlabel X\nlabel X\n")],
            "T.vm:3: Cannot redeclare label X",
        ),
        (
            &[("T.vm", "function A.f 0\ngoto Y\n")],
            "T.vm:2: Undeclared label Y",
        ),
        (
            &[("T.vm", "function A.f 0\nlabel X\nfunction A.g 0\ngoto X\n")],
            "T.vm:4: Undeclared label X",
        ),
        (
            &[("T.vm", "function A.f 0\nfunction A.f 0\n")],
            "T.vm:2: VM Already has a function named A.f",
        ),
        (
            &[("T.vm", "function A.f 0\ncall A.g 0\n")],
            "T.vm:2: Undefined function A.g",
        ),
        (
            &[("T.vm", "function A.f 0\ncall Math.multiply 1\n")],
            "T.vm:2: OS function Math.multiply expects 2 arguments, not 1",
        ),
        (
            &[("T.vm", "function A.f 0\ncall String.length 0\n")],
            "T.vm:2: OS function String.length expects 1 arguments, not 0",
        ),
        (
            &[("A.vm", "function A.f 0\n"), ("B.vm", "function A.g 0\n")],
            "B.vm:1: function A.g must be named B.<name>",
        ),
        (
            &[("T.vm", "function A.f 40000\n")],
            "T.vm:1: Illegal nVars value 40000 (must be between 0 and 32767)",
        ),
    ];
    for (sources, want) in cases {
        let got = load_err(sources);
        assert!(got.starts_with(want), "got {got:?}, want {want:?}");
    }
    // Sys.init may be defined twice; the later one is used.
    let p = Program::from_sources(&[(
        "T.vm",
        "function Sys.init 0\npush constant 1\nfunction Sys.init 0\npush constant 2\n",
    )]);
    let mut m = Machine::new(p.unwrap(), Config::default());
    m.run(None);
    assert_eq!(m.ram().read(256), 2);
}

struct Log(Vec<String>);

impl Watcher for Log {
    fn on_call(&mut self, program: &Program, function: FnId, args: &[i16], _ram: &Ram) {
        self.0
            .push(format!("call {}{args:?}", program.function_name(function)));
    }
    fn on_return(&mut self, program: &Program, function: FnId, value: i16, ram: &Ram) {
        self.0.push(format!(
            "ret {} {value} sp={}",
            program.function_name(function),
            ram.read(0)
        ));
    }
}

#[test]
fn watcher_sees_calls_and_returns_of_chosen_functions() {
    let mut m = load(&[("Main.vm", FIB)]);
    let p = m.program().clone();
    let mut watch = vec![false; p.functions().len()];
    watch[p.function_id("Main.fib").unwrap() as usize] = true;
    let mut log = Log(Vec::new());
    let e = m
        .call_watched("Main.fib", &[2], None, &watch, &mut log)
        .unwrap();
    assert_eq!(e, Exit::Returned(1));
    assert_eq!(
        log.0,
        [
            "call Main.fib[2]",
            "call Main.fib[0]",
            "ret Main.fib 0 sp=263",
            "call Main.fib[1]",
            "ret Main.fib 1 sp=264",
            "ret Main.fib 1 sp=257",
        ]
    );
    // Unwatched runs count the same instructions.
    let mut a = load(&[("Main.vm", FIB)]);
    let mut b = a.clone();
    a.run(None);
    b.run_watched(None, &watch, &mut Log(Vec::new()));
    assert_eq!(a.steps(), b.steps());
}

#[test]
fn function_profile_sums_to_the_total() {
    let p = Program::from_sources(&[("Main.vm", FIB)]).unwrap();
    let mut m = Machine::new(
        p,
        Config {
            profile_functions: true,
            ..Config::default()
        },
    );
    m.run(None);
    let prof = m.function_profile();
    assert_eq!(prof.iter().map(|(_, c)| c).sum::<u64>(), m.steps());
    assert_eq!(prof[0].0, "Main.fib");
}

#[test]
fn keyboard_word_follows_the_key_script_exactly() {
    // Spin while a key is held; key 'A' is held for clocks 0..100.
    let src =
        "push constant 24576\npop pointer 1\nlabel L\npush that 0\nif-goto L\npush constant 7\n";
    for hold in [100, 101] {
        let p = Program::from_sources(&[("T.vm", src)]).unwrap();
        let keys = KeyScript::parse("A", hold).unwrap();
        let mut m = Machine::new(
            p,
            Config {
                keys,
                ..Config::default()
            },
        );
        assert_eq!(m.run(None), Exit::Halted);
        // Reads at clocks 2, 4, ...; the first read at or after `hold` sees 0.
        let first_zero = hold.div_ceil(2) * 2;
        assert_eq!(m.steps(), first_zero + 3, "hold {hold}");
    }
}

#[test]
fn a_program_write_to_the_keyboard_word_lasts_until_the_next_key_change() {
    // Store 5 in the keyboard word, then read it back a few steps later.
    let src = "push constant 5\npop temp 0\npush constant 24576\npop pointer 1\n\
               push temp 0\npop that 0\npush constant 0\npop temp 1\npush that 0\n";
    let keys = || KeyScript::parse("A", 1000).unwrap();
    let run = |split: bool| {
        let p = Program::from_sources(&[("T.vm", src)]).unwrap();
        let mut m = Machine::new(
            p,
            Config {
                keys: keys(),
                ..Config::default()
            },
        );
        m.set_register(Register::Sp, 256);
        // Splitting the run into one-step calls must not change anything.
        let end = if split {
            loop {
                match m.run(Some(1)) {
                    Exit::Budget { .. } => continue,
                    other => break other,
                }
            }
        } else {
            m.run(None)
        };
        assert_eq!(end, Exit::Halted);
        m
    };
    for split in [false, true] {
        let m = run(split);
        assert_eq!(top(&m), 5, "split {split}");
        assert_eq!(m.ram().read(24576), 5, "split {split}");
    }
    // The key script still rules at its next change: 'A' is released at 1000.
    let p = Program::from_sources(&[("T.vm", &format!("{src}label L\ngoto L\n"))]).unwrap();
    let mut m = Machine::new(
        p,
        Config {
            keys: keys(),
            ..Config::default()
        },
    );
    m.set_register(Register::Sp, 256);
    assert!(matches!(m.run(Some(999)), Exit::Budget { .. }));
    assert_eq!(m.ram().read(24576), 5);
    assert!(matches!(m.run(Some(1)), Exit::Budget { .. }));
    assert_eq!(m.ram().read(24576), 0);
}
