//! String (spec 3.4).

mod support;

use jack_os::Profile;
use support::Machine;

#[test]
fn layout_costs_2n_plus_7_words() {
    let mut m = Machine::new(Profile::Web);
    let s = m.ok("String.new", &[5]);
    assert_eq!(s, 2050);
    assert_eq!(m.ram.read(2049), 8, "alloc(n+3)");
    assert_eq!((m.ram.read(2050), m.ram.read(2051)), (5, 0));
    assert_eq!(m.ram.read(2052), 2060, "char array alloc(n) right after");
    assert_eq!(m.os.heap_head(), 2048 + 17);
    m.ok("String.appendChar", &[s, 72]);
    assert_eq!(m.ram.read(2060), 72);
    assert_eq!(m.ok("String.length", &[s]), 1);
}

#[test]
fn the_desktop_string_is_one_block_of_n_plus_2_words() {
    let mut m = Machine::new(Profile::Desktop);
    let s = m.string("ab");
    assert_eq!(s, 2050);
    assert_eq!(
        (2050..2054).map(|a| m.ram.read(a)).collect::<Vec<_>>(),
        [2, 2, 97, 98],
        "maxLength, length, then the chars"
    );
    // With its 2-word block header a string of n chars costs n + 4 words,
    // so `let s = "ab"; let a = Array.new(1);` gives a = 2056.
    assert_eq!(m.ok("Array.new", &[1]), 2056);
}

#[test]
fn empty_strings_differ_between_profiles() {
    let mut m = Machine::new(Profile::Desktop);
    let s = m.ok("String.new", &[0]);
    assert_eq!(s, 2050);
    assert_eq!((m.ram.read(2050), m.ram.read(2051)), (0, 0));
    assert_eq!(m.ok("String.length", &[s]), 0);
    assert_eq!(m.ok("String.intValue", &[s]), 0, "desktop: no error");
    m.ok("Output.printString", &[s]);
    assert_eq!(m.os.cursor(), (0, 0));

    let mut m = Machine::new(Profile::Web);
    assert_eq!(m.err("String.new", &[0], 2), 2050);
    assert!(m.shows_text(0, 0, "ERR2"));
}

#[test]
fn negative_capacity_is_err14_and_returns_0() {
    let mut m = Machine::new(Profile::Web);
    // alloc(n+3) = alloc(2) still runs and succeeds.
    assert_eq!(m.err("String.new", &[-1], 14), 0);
    assert_eq!(m.os.heap_head(), 2048 + 4);
    assert!(m.shows_text(0, 0, "ERR14"));
    // alloc(0) then raises ERR2 too; the last code is the exit code.
    assert_eq!(m.err("String.new", &[-3], 2), 0);
    assert!(m.shows_text(0, 5, "ERR14ERR2"));
    // The desktop's Sys.error ends String.new: nothing else is allocated
    // but the 5-word block of the "ERR" string its Sys.error prints with.
    let mut m = Machine::new(Profile::Desktop);
    assert_eq!(m.err("String.new", &[-1], 14), 0);
    assert!(m.shows_text(0, 0, "ERR14"));
    assert_eq!(
        (2048..2055).map(|a| m.ram.read(a)).collect::<Vec<_>>(),
        [0, 2055, 3, 3, 69, 82, 82]
    );
}

#[test]
fn char_access_and_its_errors() {
    for profile in Profile::ALL {
        let mut m = Machine::new(profile);
        let s = m.string("abc");
        assert_eq!(m.text(s), "abc");
        assert_eq!(m.ok("String.charAt", &[s, 2]), 99);
        assert_eq!(m.err("String.charAt", &[s, 3], 15), 0);
        assert_eq!(m.err("String.charAt", &[s, -1], 15), 0);
        m.ok("String.setCharAt", &[s, 0, 65]);
        assert_eq!(m.text(s), "Abc");
        m.err("String.setCharAt", &[s, 3, 1], 16);
        m.err("String.setCharAt", &[s, -1, 1], 16);
        assert_eq!(m.err("String.appendChar", &[s, 100], 17), 0, "full");
        m.ok("String.eraseLastChar", &[s]);
        m.ok("String.eraseLastChar", &[s]);
        m.ok("String.eraseLastChar", &[s]);
        m.err("String.eraseLastChar", &[s], 18);
        assert_eq!(m.text(s), "");
        assert_eq!(m.ok("String.appendChar", &[s, 122]), s);
        assert_eq!(m.text(s), "z");
    }
}

#[test]
fn int_value_wraps_and_stops_at_a_non_digit() {
    let mut m = Machine::new(Profile::Web);
    let cases = [
        ("40000", -25536),
        ("-", 0),
        ("12-3", 12),
        ("-123", -123),
        ("-32768", -32768),
        ("32768", -32768),
        ("007", 7),
        ("x9", 0),
        ("123456789012", (123_456_789_012i64 as i16)),
        // JavaScript accumulates 20 nines to 1.0000000000000002e20
        // (checked with node: (-a) & 0xffff = 49152).
        ("-99999999999999999999", -16384),
    ];
    for (text, want) in cases {
        let s = m.string(text);
        assert_eq!(m.ok("String.intValue", &[s]), want, "{text:?}");
    }
    let empty = m.ok("String.new", &[3]);
    assert_eq!(m.err("String.intValue", &[empty], 15), 0);
}

#[test]
fn set_int_writes_the_signed_decimal_or_err19() {
    for profile in Profile::ALL {
        let mut m = Machine::new(profile);
        let s = m.string("abcdef");
        m.ok("String.setInt", &[s, -32768]);
        assert_eq!(m.text(s), "-32768");
        m.ok("String.setInt", &[s, 42]);
        assert_eq!(m.text(s), "42");
        let t = m.string("hello");
        m.err("String.setInt", &[t, -32768], 19);
        assert_eq!(m.text(t), "hello", "unchanged");
        m.ok("String.setInt", &[t, 12345]);
        assert_eq!(m.text(t), "12345");
    }
}

#[test]
fn character_constants_and_dispose() {
    let mut m = Machine::new(Profile::Web);
    assert_eq!(m.ok("String.backSpace", &[]), 129);
    assert_eq!(m.ok("String.doubleQuote", &[]), 34);
    assert_eq!(m.ok("String.newLine", &[]), 128);
    let s = m.string("ab");
    let head = m.os.heap_head();
    m.ok("String.dispose", &[s]);
    // Only the header block is freed: appended after the head remainder.
    assert_eq!(m.ram.read(head), s - 2);
    assert_eq!(m.ram.read(i32::from(s) - 2), 0);
}
