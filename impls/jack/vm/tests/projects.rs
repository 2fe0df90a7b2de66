//! The nand2tetris project 7 and 8 VM emulator tests (spec §5.2): each
//! program written from its description, the XVME.tst set-up reproduced
//! with `set_register`/`ram_mut`, the stated number of steps run, and the
//! stated RAM compared.

use hack_vm::{Config, Exit, Machine, Profile, Program, Register};

fn machine(sources: &[(&str, &str)]) -> Machine {
    machine_under(sources, Profile::Desktop)
}

fn machine_under(sources: &[(&str, &str)], profile: Profile) -> Machine {
    let program = Program::from_sources(sources).expect("loads");
    Machine::new(
        program,
        Config {
            profile,
            ..Config::default()
        },
    )
}

/// Run `steps` vmsteps (a run that halts earlier just stays halted).
fn steps(m: &mut Machine, n: u64) -> Exit {
    m.run(Some(n))
}

fn ram(m: &Machine, a: i32) -> i16 {
    m.ram().read(a)
}

fn set(m: &mut Machine, a: i32, v: i16) {
    m.ram_mut().write(a, v);
}

#[test]
fn simple_add() {
    let mut m = machine(&[("SimpleAdd.vm", "push constant 7\npush constant 8\nadd\n")]);
    m.set_register(Register::Sp, 256);
    let e = steps(&mut m, 3);
    assert!(matches!(e, Exit::Budget { .. }), "{e}");
    assert_eq!(m.steps(), 3);
    assert_eq!((ram(&m, 0), ram(&m, 256)), (257, 15));
}

const STACK_TEST: &str = "
push constant 17
push constant 17
eq
push constant 17
push constant 16
eq
push constant 16
push constant 17
eq
push constant 892
push constant 891
lt
push constant 891
push constant 892
lt
push constant 891
push constant 891
lt
push constant 32767
push constant 32766
gt
push constant 32766
push constant 32767
gt
push constant 32766
push constant 32766
gt
push constant 57
push constant 31
push constant 53
add
push constant 112
sub
neg
and
push constant 82
or
not
";

#[test]
fn stack_test() {
    let mut m = machine(&[("StackTest.vm", STACK_TEST)]);
    m.set_register(Register::Sp, 256);
    steps(&mut m, 38);
    assert_eq!(m.steps(), 38);
    assert_eq!(ram(&m, 0), 266);
    let got: Vec<i16> = (256..266).map(|a| ram(&m, a)).collect();
    assert_eq!(got, [-1, 0, 0, 0, -1, 0, -1, 0, 0, -91]);
}

#[test]
fn basic_test() {
    let src = "push constant 10\npop local 0\npush constant 21\npush constant 22\npop argument 2\npop argument 1\n\
               push constant 36\npop this 6\npush constant 42\npush constant 45\npop that 5\npop that 2\n\
               push constant 510\npop temp 6\npush local 0\npush that 5\nadd\npush argument 1\nsub\n\
               push this 6\npush this 6\nadd\nsub\npush temp 6\nadd\n";
    let mut m = machine(&[("BasicTest.vm", src)]);
    m.set_register(Register::Sp, 256);
    m.set_register(Register::Local, 300);
    m.set_register(Register::Argument, 400);
    m.set_register(Register::This, 3000);
    m.set_register(Register::That, 3010);
    steps(&mut m, 25);
    assert_eq!(m.steps(), 25);
    for (a, v) in [
        (256, 472),
        (300, 10),
        (401, 21),
        (402, 22),
        (3006, 36),
        (3012, 42),
        (3015, 45),
        (11, 510),
    ] {
        assert_eq!(ram(&m, a), v, "RAM[{a}]");
    }
}

#[test]
fn pointer_test() {
    let src = "push constant 3030\npop pointer 0\npush constant 3040\npop pointer 1\npush constant 32\npop this 2\n\
               push constant 46\npop that 6\npush pointer 0\npush pointer 1\nadd\npush this 2\nsub\npush that 6\nadd\n";
    let mut m = machine(&[("PointerTest.vm", src)]);
    m.set_register(Register::Sp, 256);
    steps(&mut m, 15);
    assert_eq!(m.steps(), 15);
    for (a, v) in [(256, 6084), (3, 3030), (4, 3040), (3032, 32), (3046, 46)] {
        assert_eq!(ram(&m, a), v, "RAM[{a}]");
    }
}

#[test]
fn static_test() {
    let src = "push constant 111\npush constant 333\npush constant 888\npop static 8\npop static 3\npop static 1\n\
               push static 3\npush static 1\nsub\npush static 8\nadd\n";
    let mut m = machine_under(&[("StaticTest.vm", src)], Profile::Web);
    m.set_register(Register::Sp, 256);
    steps(&mut m, 11);
    assert_eq!(ram(&m, 256), 1110);
    // Web: slots in order of first appearance: static 8, 3, 1 -> RAM 16, 17, 18.
    assert_eq!((ram(&m, 16), ram(&m, 17), ram(&m, 18)), (888, 333, 111));
    // Desktop: the file's segment from 16, static i at 16 + i.
    let mut m = machine(&[("StaticTest.vm", src)]);
    m.set_register(Register::Sp, 256);
    steps(&mut m, 11);
    assert_eq!(ram(&m, 256), 1110);
    assert_eq!((ram(&m, 24), ram(&m, 19), ram(&m, 17)), (888, 333, 111));
}

#[test]
fn basic_loop() {
    let src = "push constant 0\npop local 0\nlabel LOOP\npush argument 0\npush local 0\nadd\npop local 0\n\
               push argument 0\npush constant 1\nsub\npop argument 0\npush argument 0\nif-goto LOOP\npush local 0\n";
    let mut m = machine(&[("BasicLoop.vm", src)]);
    m.set_register(Register::Sp, 256);
    m.set_register(Register::Local, 300);
    m.set_register(Register::Argument, 400);
    set(&mut m, 400, 3);
    steps(&mut m, 33);
    assert_eq!(m.steps(), 33);
    assert_eq!((ram(&m, 0), ram(&m, 256)), (257, 6));
}

#[test]
fn fibonacci_series() {
    let src = "push argument 1\npop pointer 1\npush constant 0\npop that 0\npush constant 1\npop that 1\n\
               push argument 0\npush constant 2\nsub\npop argument 0\nlabel LOOP\npush argument 0\n\
               if-goto COMPUTE_ELEMENT\ngoto END\nlabel COMPUTE_ELEMENT\npush that 0\npush that 1\nadd\n\
               pop that 2\npush pointer 1\npush constant 1\nadd\npop pointer 1\npush argument 0\n\
               push constant 1\nsub\npop argument 0\ngoto LOOP\nlabel END\n";
    for profile in Profile::ALL {
        let mut m = machine_under(&[("FibonacciSeries.vm", src)], profile);
        m.set_register(Register::Sp, 256);
        m.set_register(Register::Local, 300);
        m.set_register(Register::Argument, 400);
        set(&mut m, 400, 6);
        set(&mut m, 401, 3000);
        let e = steps(&mut m, 73);
        assert!(matches!(e, Exit::Budget { .. }), "{e}");
        let got: Vec<i16> = (3000..3006).map(|a| ram(&m, a)).collect();
        assert_eq!(got, [0, 1, 1, 2, 3, 5]);
        // The next step runs past the end of the program: halt.
        assert_eq!(steps(&mut m, 1), Exit::Halted);
        assert_eq!(m.steps(), 73);
    }
}

#[test]
fn simple_function() {
    let src = "function SimpleFunction.test 2\npush local 0\npush local 1\nadd\nnot\npush argument 0\nadd\n\
               push argument 1\nsub\nreturn\n";
    // Nine commands; the return from the entry ends the run. The desktop
    // runs the `function` line first (pushing the two locals at 317): ten
    // steps, the count the published test script runs.
    for (profile, count) in [(Profile::Web, 9), (Profile::Desktop, 10)] {
        let mut m = machine_under(&[("SimpleFunction.vm", src)], profile);
        m.set_register(Register::Sp, 317);
        m.set_register(Register::Local, 317);
        m.set_register(Register::Argument, 310);
        m.set_register(Register::This, 3000);
        m.set_register(Register::That, 4000);
        for (i, v) in [1234, 37, 9, 305, 300, 3010, 4010].into_iter().enumerate() {
            set(&mut m, 310 + i as i32, v);
        }
        assert_eq!(steps(&mut m, 10), Exit::Halted);
        assert_eq!(m.steps(), count, "{profile}");
        let regs: Vec<i16> = (0..5).map(|a| ram(&m, a)).collect();
        assert_eq!(regs, [311, 305, 300, 3010, 4010]);
        assert_eq!(ram(&m, 310), 1196);
    }
}

const NESTED_SYS: &str = "
function Sys.init 0
push constant 4000
pop pointer 0
push constant 5000
pop pointer 1
call Sys.main 0
pop temp 1
label LOOP
goto LOOP

function Sys.main 5
push constant 4001
pop pointer 0
push constant 5001
pop pointer 1
push constant 200
pop local 1
push constant 40
pop local 2
push constant 6
pop local 3
push constant 123
call Sys.add12 1
pop temp 0
push local 0
push local 1
push local 2
push local 3
push local 4
add
add
add
add
return

function Sys.add12 0
push constant 4002
pop pointer 0
push constant 5002
pop pointer 1
push argument 0
push constant 12
add
return
";

#[test]
fn nested_call() {
    let mut m = machine(&[("Sys.vm", NESTED_SYS)]);
    m.set_register(Register::Sp, 261);
    m.set_register(Register::Local, 261);
    m.set_register(Register::Argument, 256);
    m.set_register(Register::This, -3);
    m.set_register(Register::That, -4);
    set(&mut m, 5, -1);
    set(&mut m, 6, -1);
    for (i, v) in [1234, -1, -2, -3, -4].into_iter().enumerate() {
        set(&mut m, 256 + i as i32, v);
    }
    for a in 261..300 {
        set(&mut m, a, -1);
    }
    steps(&mut m, 50);
    let got: Vec<i16> = (0..7).map(|a| ram(&m, a)).collect();
    assert_eq!(got, [261, 261, 256, 4000, 5000, 135, 246]);
    assert_eq!(m.call_stack().to_string(), "Sys.init");
}

const FIB_MAIN: &str = "
function Main.fibonacci 0
push argument 0
push constant 2
lt
if-goto N_LT_2
goto N_GE_2
label N_LT_2
push argument 0
return
label N_GE_2
push argument 0
push constant 2
sub
call Main.fibonacci 1
push argument 0
push constant 1
sub
call Main.fibonacci 1
add
return
";

#[test]
fn fibonacci_element() {
    let sys = "function Sys.init 0\npush constant 4\ncall Main.fibonacci 1\nlabel END\ngoto END\n";
    // Web: fib(4) itself takes 90 steps, Sys.init 2 before the loop.
    // Desktop: 9 more for the `function` lines of the nine calls, and the
    // `function Sys.init` line it starts at.
    for (profile, done) in [(Profile::Web, 92), (Profile::Desktop, 102)] {
        let run = |n| {
            let mut m = machine_under(&[("Main.vm", FIB_MAIN), ("Sys.vm", sys)], profile);
            m.set_register(Register::Sp, 261);
            steps(&mut m, n);
            m
        };
        let m = run(110);
        assert_eq!((ram(&m, 0), ram(&m, 261)), (262, 3));
        let m = run(done);
        assert_eq!((ram(&m, 0), ram(&m, 261)), (262, 3), "{profile}");
        let m = run(done - 1);
        assert_ne!(
            ram(&m, 0),
            262,
            "{profile}: one step before the end fib(4) has not returned"
        );
    }
}

#[test]
fn statics_test() {
    let class = |c: &str| {
        format!(
            "function {c}.set 0\npush argument 0\npop static 0\npush argument 1\npop static 1\npush constant 0\nreturn\n\
             function {c}.get 0\npush static 0\npush static 1\nsub\nreturn\n"
        )
    };
    let sys = "function Sys.init 0\npush constant 6\npush constant 8\ncall Class1.set 2\npop temp 0\n\
               push constant 23\npush constant 15\ncall Class2.set 2\npop temp 0\ncall Class1.get 0\n\
               call Class2.get 0\nlabel END\ngoto END\n";
    let (c1, c2) = (class("Class1"), class("Class2"));
    let mut m = machine(&[
        ("Class1.vm", c1.as_str()),
        ("Class2.vm", c2.as_str()),
        ("Sys.vm", sys),
    ]);
    m.set_register(Register::Sp, 261);
    steps(&mut m, 36);
    assert_eq!((ram(&m, 0), ram(&m, 261), ram(&m, 262)), (263, -2, 8));
    // Statics kept apart per class: Class1 at 16, 17; Class2 at 18, 19.
    let got: Vec<i16> = (16..20).map(|a| ram(&m, a)).collect();
    assert_eq!(got, [6, 8, 23, 15]);
}

#[test]
fn bootstrap_stack_at_main_main_entry() {
    let main = "function Main.main 2\npush constant 42\nreturn\n";
    let mut m = machine_under(&[("Main.vm", main)], Profile::Web);
    // Seven init built-ins and the call of Main.main: eight steps.
    steps(&mut m, 8);
    assert_eq!(m.call_stack().to_string(), "Sys.init > Main.main");
    let low: Vec<i16> = (256..263).map(|a| ram(&m, a)).collect();
    assert_eq!(low, [0; 7]);
    let frame: Vec<i16> = (263..268).map(|a| ram(&m, a)).collect();
    assert_eq!(frame, [8, 0, 0, 0, 0]);
    assert_eq!((ram(&m, 2), ram(&m, 1), ram(&m, 0)), (263, 268, 270));
    assert_eq!(steps(&mut m, 100), Exit::Halted);
    assert_eq!((ram(&m, 263), ram(&m, 0)), (42, 264));
    assert_eq!(m.steps(), 10);
}

#[test]
fn desktop_bootstrap_is_one_hidden_call_of_sys_init() {
    let main = "function Main.main 2\npush constant 42\nreturn\n";
    let mut m = machine(&[("Main.vm", main)]);
    assert_eq!(
        steps(&mut m, 1),
        Exit::Budget {
            stack: ["Sys.init", "Main.main"].into_iter().collect()
        }
    );
    // The hidden `call Sys.init` has run: the built-in's frame at 256 and
    // Main.main's frame (RET -1) right above it at 261, with LCL = 266, as
    // the desktop VM emulator has them (its OS inits touch no stack).
    assert_eq!(m.steps(), 1);
    assert_eq!(m.call_stack().to_string(), "Sys.init > Main.main");
    let low: Vec<i16> = (256..266).map(|a| ram(&m, a)).collect();
    // RET of the hidden call: the 3 command lines and 5 invisible ones.
    assert_eq!(low, [8, 0, 0, 0, 0, -1, 261, 256, 0, 0]);
    assert_eq!((ram(&m, 2), ram(&m, 1), ram(&m, 0)), (261, 266, 266));
    // `function Main.main 2` is a step: it pushes the two locals.
    steps(&mut m, 1);
    assert_eq!((ram(&m, 0), m.steps()), (268, 2));
    assert_eq!(steps(&mut m, 100), Exit::Halted);
    // The return value lands at 261; the built-in Sys.init takes it off
    // the stack: SP 261 at the end, as on the desktop.
    assert_eq!((ram(&m, 261), ram(&m, 0)), (42, 261));
    assert_eq!(m.steps(), 4);
}
