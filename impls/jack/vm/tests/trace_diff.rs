//! Two runs compared by their call traces (`compare_call_traces`).

use hack_vm::{
    compare_call_traces, CallEvent, Config, Exit, Machine, Profile, Program, TraceDivergence,
};

/// `Main.fib(n)` (21891 calls for n = 20: more events than one batch of
/// the comparison), then `Main.half(-9)`, whose `Math.divide` rounds
/// differently under the two profiles, then `Main.show` of the result.
fn program(n: i16) -> String {
    format!(
        "{}function Main.half 0
push argument 0
push constant 2
call Math.divide 2
return
function Main.show 0
push constant 0
return
function Main.main 0
push constant {n}
call Main.fib 1
pop temp 0
push constant 9
neg
call Main.half 1
call Main.show 1
return
",
        fib_function!()
    )
}

fn machine(source: &str, profile: Profile) -> Machine {
    Machine::new(
        Program::from_sources(&[("Main.vm", source)]).expect("loads"),
        Config {
            profile,
            ..Config::default()
        },
    )
}

/// Calls of `Main.fib(n)`.
fn fib_calls(n: u64) -> u64 {
    if n < 2 {
        1
    } else {
        1 + fib_calls(n - 1) + fib_calls(n - 2)
    }
}

#[test]
fn the_profiles_part_at_the_return_of_the_function_that_divides() {
    for n in [6, 20] {
        let source = program(n);
        let mut desktop = machine(&source, Profile::Desktop);
        let mut web = machine(&source, Profile::Web);
        let found = compare_call_traces(&mut desktop, &mut web, None, &mut |_| {});
        // Main.main's call, fib's calls and returns, Main.half's call.
        assert_eq!(found.matching, 1 + 2 * fib_calls(n as u64) + 1, "n = {n}");
        let return_of = |value| {
            Some(CallEvent::Return {
                function: "Main.half".into(),
                value,
            })
        };
        assert_eq!(
            found.divergence,
            Some(TraceDivergence {
                stack: ["Sys.init", "Main.main", "Main.half"]
                    .map(String::from)
                    .into(),
                a: return_of(-4),
                b: return_of(-5),
            })
        );
        // Both runs go on to their end afterwards.
        assert_eq!(desktop.run(None), Exit::Halted);
        assert_eq!(web.run(None), Exit::Halted);
    }
}

#[test]
fn equal_runs_match_to_the_end_and_stay_runnable() {
    let source = program(20);
    let mut a = machine(&source, Profile::Desktop);
    let mut b = machine(&source, Profile::Desktop);
    let found = compare_call_traces(&mut a, &mut b, None, &mut |_| {});
    // Every call returns: main, fib, half, show.
    assert_eq!(found.matching, 2 * (1 + fib_calls(20) + 2));
    assert_eq!(found.divergence, None);
    assert_eq!(a.run(None), Exit::Halted);
    assert_eq!(a.steps(), b.steps());
    let mut plain = machine(&source, Profile::Desktop);
    assert_eq!(plain.run(None), Exit::Halted);
    assert_eq!(plain.steps(), a.steps());
}

#[test]
fn a_run_that_stops_first_parts_with_none_and_functions_match_by_name() {
    // The same calls after a loop without calls of 3000 iterations, in a
    // program with an extra function first (so every id differs).
    let slow = program(6)
        .replace(
            "function Main.main 0\n",
            "function Main.main 0\npush constant 3000\npop temp 1\nlabel SPIN\npush temp 1\npush constant 1\nsub\npop temp 1\npush temp 1\nif-goto SPIN\n",
        )
        .replace("function Main.fib 0\n", "function Main.unused 0\npush constant 0\nreturn\nfunction Main.fib 0\n");
    let fast_total = {
        let mut m = machine(&program(6), Profile::Desktop);
        m.run(None);
        m.steps()
    };
    let mut fast = machine(&program(6), Profile::Desktop);
    let mut slow = machine(&slow, Profile::Desktop);
    // Enough for the fast run to end, not for the slow one to call fib.
    let found = compare_call_traces(&mut fast, &mut slow, Some(fast_total + 10), &mut |_| {});
    assert_eq!(found.matching, 1);
    let divergence = found.divergence.expect("the slow run stops first");
    assert_eq!(divergence.stack, ["Sys.init", "Main.main"]);
    assert_eq!(
        divergence.a,
        Some(CallEvent::Call {
            function: "Main.fib".into(),
            args: vec![6]
        })
    );
    assert_eq!(divergence.b, None);
    assert!(matches!(slow.run(Some(0)), Exit::Budget { .. }));
    assert_eq!(slow.steps(), fast_total + 10);
}
