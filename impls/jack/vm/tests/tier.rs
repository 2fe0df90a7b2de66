//! `Engine::Auto`: a short run stays on the interpreter (it never
//! compiles), a long one switches to compiled code, and the steps of short
//! runs from clones of one snapshot count together.

use hack_vm::{Config, Engine, Exit, Machine, Program, AUTO_THRESHOLD};
use std::sync::Arc;

/// `Main.loop n` counts a local through all 65536 values `n` times
/// (393,222 steps each) and returns 0.
const LOOP: &str = "function Main.loop 1
label OUTER
label INNER
push local 0
push constant 1
add
pop local 0
push local 0
if-goto INNER
push argument 0
push constant 1
sub
pop argument 0
push argument 0
if-goto OUTER
push constant 0
return
";

fn program() -> Arc<Program> {
    Program::from_sources(&[("Main.vm", LOOP)]).expect("the loop loads")
}

fn machine(program: &Arc<Program>, engine: Engine, threshold: Option<u64>) -> Machine {
    let config = Config {
        engine,
        auto_threshold: threshold,
        ..Config::default()
    };
    Machine::new(program.clone(), config)
}

/// Run `Main.loop n` on `m`; its step count.
fn run_loop(m: &mut Machine, n: i16) -> u64 {
    let before = m.steps();
    let exit = m.call("Main.loop", &[n], None).expect("Main.loop exists");
    assert_eq!(exit, Exit::Returned(0));
    m.steps() - before
}

#[test]
fn a_short_run_never_compiles() {
    let mut m = machine(&program(), Engine::Auto, None);
    let steps = run_loop(&mut m, 10);
    assert!(steps < AUTO_THRESHOLD);
    assert_eq!(m.engine(), Engine::Interp);
    assert_eq!(m.compiled_steps(), 0);
}

#[test]
fn a_long_run_switches_to_compiled_code() {
    let program = program();
    let mut auto = machine(&program, Engine::Auto, None);
    let steps = run_loop(&mut auto, 300);
    assert!(steps > AUTO_THRESHOLD);
    assert_eq!(auto.engine(), Engine::Native);
    // It interprets up to the threshold (and on to the end of that slice
    // of the run), then compiled code runs the rest.
    let interpreted = steps - auto.compiled_steps();
    assert!(
        (AUTO_THRESHOLD..steps).contains(&interpreted),
        "{interpreted} of {steps} interpreted"
    );
    let mut interp = machine(&program, Engine::Interp, None);
    assert_eq!(run_loop(&mut interp, 300), steps);
    assert!(interp.ram() == auto.ram());
    assert_eq!(interp.compiled_steps(), 0);
}

#[test]
fn clones_count_their_steps_together_and_share_the_compiled_code() {
    let program = program();
    let snapshot = machine(&program, Engine::Auto, Some(1_000_000));
    let mut short = Vec::new();
    for _ in 0..2 {
        let mut m = snapshot.clone();
        run_loop(&mut m, 1);
        assert_eq!(m.engine(), Engine::Interp, "786,444 steps in all");
        short.push(m);
    }
    let mut third = snapshot.clone();
    run_loop(&mut third, 1);
    assert_eq!(third.engine(), Engine::Native, "past 1 M steps in all");
    assert_eq!(third.clone().engine(), Engine::Native);
    // A clone of the snapshot taken before the switch takes the compiled
    // code on its first run, however short.
    let mut late = snapshot.clone();
    assert_eq!(late.engine(), Engine::Interp);
    run_loop(&mut late, 1);
    assert_eq!(late.engine(), Engine::Native);
    assert!(late.ram() == short[0].ram());
}

#[test]
fn engines_parse_and_auto_is_the_default() {
    assert_eq!("auto".parse::<Engine>(), Ok(Engine::Auto));
    assert_eq!("interp".parse::<Engine>(), Ok(Engine::Interp));
    assert_eq!("native".parse::<Engine>(), Ok(Engine::Native));
    assert!("jit".parse::<Engine>().unwrap_err().contains("auto"));
    let expected = match std::env::var("HACK_VM_ENGINE").as_deref() {
        Ok("native") => Engine::Native,
        Ok("interp") => Engine::Interp,
        _ => Engine::Auto,
    };
    assert_eq!(Engine::default(), expected);
}

/// Compiling says how long it took, and only the first call compiles: a
/// later one reports the same time for the code it shares.
#[test]
fn compiling_reports_its_time_once() {
    let program = program();
    let first = program
        .compile_native(hack_vm::Profile::Desktop)
        .expect("this host compiles");
    assert!(
        first > std::time::Duration::ZERO,
        "compiling took {first:?}"
    );
    let again = program
        .compile_native(hack_vm::Profile::Desktop)
        .expect("this host compiles");
    assert_eq!(again, first);
}
