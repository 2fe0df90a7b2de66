//! Output (spec 3.5): glyph placement, the 9x12 clearChar, wrapping, the
//! cursor.

mod support;

use jack_os::{Profile, Stop};
use support::Machine;

#[test]
fn a_printed_char_shows_the_font_glyph_at_its_cell() {
    let mut m = Machine::new(Profile::Desktop);
    m.ok("Output.moveCursor", &[3, 10]);
    m.ok("Output.printChar", &[65]);
    assert!(m.shows(3, 10, 'A'));
    assert_eq!(m.os.cursor(), (3, 11));
    // Nothing but the glyph is black.
    let glyph_pixels: usize = support::glyph('A').iter().flatten().filter(|b| **b).count();
    assert_eq!(m.black_count(), glyph_pixels);
}

#[test]
fn every_glyph_matches_the_font() {
    let mut m = Machine::new(Profile::Web);
    for code in 32..=126u8 {
        m.ok("Output.printChar", &[i16::from(code)]);
    }
    for (k, code) in (32..=126u8).enumerate() {
        assert!(m.shows(k / 64, k % 64, char::from(code)), "{code}");
    }
}

#[test]
fn clear_char_erases_9_by_12_pixels() {
    let mut m = Machine::new(Profile::Desktop);
    m.blacken();
    m.ok("Output.moveCursor", &[1, 1]);
    m.ok("Output.printChar", &[32]);
    let top = m.cell_y(1);
    for x in 0..24 {
        for y in 0..36 {
            let cleared = (8..=16).contains(&x) && (top..=top + 11).contains(&y);
            assert_eq!(m.black(x, y), !cleared, "({x},{y})");
        }
    }
}

#[test]
fn clear_char_at_column_63_wraps_to_column_0_of_the_next_rows() {
    for profile in Profile::ALL {
        let mut m = Machine::new(profile);
        m.blacken();
        m.ok("Output.moveCursor", &[2, 63]);
        m.ok("Output.printChar", &[32]);
        // x = 512 paints (0, y+1) for y = top..=top+11 (top 22 web, 23 desktop).
        let top = m.cell_y(2);
        assert!(m.black(0, top));
        assert!((top + 1..=top + 12).all(|y| !m.black(0, y)));
        assert!(m.black(0, top + 13));
        assert!(m.black(1, top + 1));
        assert_eq!(m.os.cursor(), (3, 0));
    }
}

#[test]
fn non_glyph_codes_draw_nothing_but_advance() {
    let mut m = Machine::new(Profile::Desktop);
    m.blacken();
    for code in [0, 31, 127, 128, 129, -1, 1000] {
        m.ok("Output.printChar", &[code]);
    }
    assert_eq!(m.black_count(), 512 * 256);
    assert_eq!(m.os.cursor(), (0, 7));
}

#[test]
fn printing_wraps_to_the_next_row_and_row_22_wraps_to_0() {
    let mut m = Machine::new(Profile::Desktop);
    for _ in 0..64 {
        m.ok("Output.printChar", &[88]);
    }
    assert_eq!(m.os.cursor(), (1, 0));
    m.ok("Output.moveCursor", &[22, 5]);
    m.ok("Output.println", &[]);
    assert_eq!(m.os.cursor(), (0, 0));
    m.ok("Output.moveCursor", &[22, 63]);
    m.ok("Output.printChar", &[88]);
    assert_eq!(m.os.cursor(), (0, 0));
}

#[test]
fn print_int_and_print_string() {
    let mut m = Machine::new(Profile::Web);
    m.ok("Output.printInt", &[-32768]);
    assert!(m.shows_text(0, 0, "-32768"));
    let s = m.string("Hi!");
    m.ok("Output.printString", &[s]);
    assert!(m.shows_text(0, 6, "Hi!"));
    assert_eq!(m.os.cursor(), (0, 9));
}

fn assert_cursor_box(m: &Machine, r: usize, c: usize) {
    let top = m.cell_y(r);
    for x in 8 * c..8 * c + 8 {
        for y in top..top + 11 {
            let inside = (8 * c + 2..=8 * c + 6).contains(&x) && (top + 2..=top + 9).contains(&y);
            assert_eq!(m.black(x, y), inside, "({x},{y})");
        }
    }
}

#[test]
fn move_cursor_draws_the_cursor_box() {
    let mut m = Machine::new(Profile::Desktop);
    m.ok("Output.moveCursor", &[4, 7]);
    assert_cursor_box(&m, 4, 7);
    assert_eq!(m.black_count(), 5 * 8);
}

#[test]
fn move_cursor_errors() {
    for profile in Profile::ALL {
        let mut m = Machine::new(profile);
        for (i, j) in [(-1, 0), (23, 0), (0, -1), (0, 65)] {
            m.err("Output.moveCursor", &[i, j], 20);
        }
        assert_eq!(
            m.os.cursor(),
            (0, 20),
            "four ERR20s printed, cursor not moved"
        );
        assert!(m.shows_text(0, 0, "ERR20ERR20ERR20ERR20"));
    }
    let mut d = Machine::new(Profile::Desktop);
    d.err("Output.moveCursor", &[0, 64], 20);
    let mut w = Machine::new(Profile::Web);
    assert_eq!(
        w.call("Output.moveCursor", &[0, 64]).stop,
        Some(Stop::RuntimeError(
            "Maximum call stack size exceeded".into()
        ))
    );
    // Calls after the crash (which a VM should not make) still return.
    assert_eq!(w.os.cursor(), (0, 0));
    w.ok("Output.printChar", &[65]);
}

#[test]
fn backspace_clears_steps_back_and_draws_the_cursor() {
    let mut m = Machine::new(Profile::Desktop);
    m.ok("Output.printChar", &[65]);
    m.ok("Output.printChar", &[66]);
    m.ok("Output.backSpace", &[]);
    assert_eq!(m.os.cursor(), (0, 1));
    assert!(m.shows(0, 0, 'A'));
    assert_cursor_box(&m, 0, 1);
    // From column 0 the cursor goes up a row but stays at column 0.
    m.ok("Output.moveCursor", &[2, 0]);
    m.ok("Output.backSpace", &[]);
    assert_eq!(m.os.cursor(), (1, 0));
    m.ok("Output.moveCursor", &[0, 0]);
    m.ok("Output.backSpace", &[]);
    assert_eq!(m.os.cursor(), (0, 0));
    assert_cursor_box(&m, 0, 0);
}

#[test]
fn desktop_text_starts_at_screen_row_1_and_web_text_at_row_0() {
    for (profile, top) in [(Profile::Desktop, 1), (Profile::Web, 0)] {
        let mut m = Machine::new(profile);
        // 'T' is black in its glyph row 0.
        m.ok("Output.printChar", &[i16::from(b'T')]);
        assert!(m.shows(0, 0, 'T'));
        let first_black_row = (0..256).find(|&y| (0..8).any(|x| m.black(x, y)));
        assert_eq!(first_black_row, Some(top), "{profile}");
        // The desktop's START_ADDRESS is screen word 32 (pixel row 1): its
        // screen word 0 stays white.
        assert_eq!(m.ram.read(16384) == 0, profile == Profile::Desktop);
    }
}
