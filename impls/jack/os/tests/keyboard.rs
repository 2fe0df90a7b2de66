//! Keyboard (spec 3.7) driven by key scripts.

mod support;

use jack_os::{KeyScript, Profile, Stop};
use support::Machine;

const HOLD: u64 = 10;

fn machine(profile: Profile, keys: &str) -> Machine {
    Machine::with_keys(profile, KeyScript::parse(keys, HOLD).unwrap())
}

#[test]
fn key_pressed_reads_the_keyboard_word() {
    let mut m = machine(Profile::Desktop, "");
    assert_eq!(m.ok("Keyboard.keyPressed", &[]), 0);
    m.ram.write(24576, 131);
    assert_eq!(m.ok("Keyboard.keyPressed", &[]), 131);
}

#[test]
fn read_char_waits_for_the_release_and_echoes() {
    let mut m = machine(Profile::Desktop, "A,ENTER");
    m.clock = 5; // while A is down
    assert_eq!(m.ok("Keyboard.readChar", &[]), 65);
    assert_eq!(m.clock, 10, "returns at the release");
    assert!(m.shows(0, 0, 'A'));
    assert_eq!(m.os.cursor(), (0, 1));
    assert_eq!(m.ok("Keyboard.readChar", &[]), 128);
    assert_eq!(m.clock, 30);
    // Enter draws nothing: the cursor box drawn before the wait stays.
    assert_eq!(m.os.cursor(), (0, 2));
    let top = m.cell_y(0);
    assert!(m.black(8 + 2, top + 2) && m.black(8 + 6, top + 9));
    assert_eq!(
        m.call("Keyboard.readChar", &[]).stop,
        Some(Stop::BlockedForever)
    );
}

#[test]
fn read_line_collects_until_enter() {
    let mut m = machine(Profile::Web, "H,i,BACKSPACE,o,ENTER");
    let prompt = m.string("? ");
    let head = m.os.heap_head();
    let s = m.ok("Keyboard.readLine", &[prompt]);
    assert_eq!(m.text(s), "Ho");
    assert_eq!(m.ram.read(i32::from(s)), 100);
    assert_eq!(m.os.heap_head(), head + 207);
    assert!(m.shows_text(0, 0, "? Ho"));
    assert_eq!(m.os.cursor(), (1, 0), "clearChar then println");
    assert_eq!(m.clock, 90, "the release of Enter");
    // The cursor at (0,4) was cleared.
    assert!((32..40).all(|x| (0..11).all(|y| !m.black(x, y))));
}

#[test]
fn backspace_on_an_empty_line_is_err18_and_input_goes_on() {
    let mut m = machine(Profile::Web, "BACKSPACE,A,ENTER");
    let prompt = m.string(">");
    let c = m.call("Keyboard.readLine", &[prompt]);
    // The next ordinary key ends the read with 0 (halted), after echoing it.
    assert_eq!(
        c,
        jack_os::Completion {
            value: 0,
            stop: Some(Stop::SysError(18))
        }
    );
    assert_eq!(m.clock, 30);
    assert!(m.shows_text(0, 1, "ERR18A"));

    let mut m = machine(Profile::Web, "BACKSPACE,ENTER");
    let prompt = m.string(">");
    let c = m.call("Keyboard.readLine", &[prompt]);
    assert_eq!(c.stop, Some(Stop::SysError(18)));
    assert_ne!(c.value, 0, "Enter returns the string");
    assert_eq!(m.os.cursor(), (0, 6), "no println when halted");
}

#[test]
fn the_101st_char_is_err17() {
    let keys = vec!["x"; 101].join(",");
    let mut m = machine(Profile::Desktop, &keys);
    let prompt = m.string(">");
    let c = m.call("Keyboard.readLine", &[prompt]);
    assert_eq!(
        c,
        jack_os::Completion {
            value: 0,
            stop: Some(Stop::SysError(17))
        }
    );
}

#[test]
fn read_int() {
    let mut m = machine(Profile::Web, "-,1,2,x,3,ENTER,ENTER");
    let prompt = m.string("n=");
    assert_eq!(m.ok("Keyboard.readInt", &[prompt]), -12);
    assert_eq!(m.err("Keyboard.readInt", &[prompt], 15), 0);
    assert_eq!(
        m.call("Keyboard.readInt", &[prompt]).stop,
        Some(Stop::BlockedForever)
    );
}

#[test]
fn a_read_with_no_more_keys_blocks_forever() {
    let mut m = machine(Profile::Desktop, "A");
    m.clock = 10; // A already released
    let prompt = m.string("");
    assert_eq!(
        m.call("Keyboard.readLine", &[prompt]).stop,
        Some(Stop::BlockedForever)
    );
}
