//! Math, Sys and the init functions through `Os::call` (spec 3.1, 3.8).

mod support;

use jack_os::{subroutines, Profile, Stop};
use support::Machine;

#[test]
fn divide_differs_between_profiles() {
    let mut d = Machine::new(Profile::Desktop);
    let mut w = Machine::new(Profile::Web);
    assert_eq!(d.ok("Math.divide", &[-7, 2]), -3);
    assert_eq!(w.ok("Math.divide", &[-7, 2]), -4);
    assert_eq!(d.ok("Math.divide", &[7, -2]), -3);
    assert_eq!(w.ok("Math.divide", &[7, -2]), -4);
    assert_eq!(w.ok("Math.divide", &[-32768, -1]), -32768);
    for m in [&mut d, &mut w] {
        assert_eq!(m.err("Math.divide", &[1, 0], 3), 0);
        assert!(m.shows_text(0, 0, "ERR3"));
    }
}

#[test]
fn the_other_math_functions() {
    let mut m = Machine::new(Profile::Desktop);
    assert_eq!(m.ok("Math.multiply", &[300, 300]), 24464);
    assert_eq!(m.ok("Math.min", &[-2, 3]), -2);
    assert_eq!(m.ok("Math.max", &[-2, 3]), 3);
    assert_eq!(m.ok("Math.abs", &[-32768]), -32768);
    assert_eq!(m.ok("Math.sqrt", &[32767]), 181);
    assert_eq!(m.err("Math.sqrt", &[-1], 4), 0);
    assert!(m.shows_text(0, 0, "ERR4"));
}

#[test]
fn init_functions_are_no_ops() {
    let mut m = Machine::new(Profile::Web);
    let before = m.ram.clone();
    for s in subroutines().iter().filter(|s| s.name == "init") {
        assert_eq!(m.ok(s.full_name, &[]), 0);
    }
    assert_eq!(m.ram, before);
}

#[test]
fn halt_error_and_wait() {
    let mut m = Machine::new(Profile::Desktop);
    assert_eq!(m.call("Sys.halt", &[]).stop, Some(Stop::Halt));
    m.err("Sys.error", &[-5], -5);
    assert!(m.shows_text(0, 0, "ERR-5"));
    assert_eq!(m.os.cursor(), (0, 5), "no newline");
    m.err("Sys.wait", &[0], 1);
    m.err("Sys.wait", &[-1], 1);
    let before = (m.ram.clone(), m.clock);
    m.ok("Sys.wait", &[1000]);
    assert_eq!((m.ram.clone(), m.clock), before);
}
