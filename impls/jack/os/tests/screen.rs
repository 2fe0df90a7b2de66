//! Screen (spec 3.6): bounds, line shape, rectangles, circles, clearScreen.

mod support;

use jack_os::Profile;
use support::Machine;

fn black_pixels(m: &Machine) -> Vec<(usize, usize)> {
    let mut v = Vec::new();
    for y in 0..256 {
        for x in 0..512 {
            if m.black(x, y) {
                v.push((x, y));
            }
        }
    }
    v
}

#[test]
fn draw_pixel_uses_the_colour() {
    let mut m = Machine::new(Profile::Desktop);
    m.ok("Screen.drawPixel", &[17, 3]);
    assert_eq!(m.ram.read(16384 + 3 * 32 + 1), 2);
    m.ok("Screen.drawPixel", &[511, 255]);
    assert!(m.black(511, 255));
    m.ok("Screen.setColor", &[0]);
    m.ok("Screen.drawPixel", &[17, 3]);
    assert_eq!(black_pixels(&m), vec![(511, 255)]);
    m.ok("Screen.setColor", &[5]);
    assert!(m.os.color());
}

#[test]
fn draw_pixel_bounds_differ_between_profiles() {
    let mut d = Machine::new(Profile::Desktop);
    for (x, y) in [(512, 0), (0, 256), (-1, 0), (0, -1)] {
        d.err("Screen.drawPixel", &[x, y], 7);
    }
    assert!(d.shows_text(0, 0, "ERR7ERR7ERR7ERR7"));
    let mut w = Machine::new(Profile::Web);
    w.ok("Screen.drawPixel", &[512, 10]);
    assert_eq!(black_pixels(&w), vec![(0, 11)], "x = 512 paints (0, y+1)");
    w.ok("Screen.drawPixel", &[512, 255]);
    w.ok("Screen.drawPixel", &[3, 256]);
    assert_eq!(black_pixels(&w), vec![(0, 11)], "dropped past the screen");
    for (x, y) in [(513, 0), (0, 257), (-1, 0), (0, -1)] {
        w.err("Screen.drawPixel", &[x, y], 7);
    }
}

#[test]
fn a_general_line_is_a_staircase_whose_first_move_is_vertical() {
    let mut m = Machine::new(Profile::Desktop);
    m.ok("Screen.drawLine", &[0, 0, 3, 2]);
    assert_eq!(
        black_pixels(&m),
        vec![(0, 0), (0, 1), (1, 1), (2, 1), (2, 2), (3, 2)]
    );
    // Reversed direction: from (10,20) toward (7,22).
    let mut m = Machine::new(Profile::Web);
    m.ok("Screen.drawLine", &[10, 20, 7, 22]);
    assert_eq!(
        black_pixels(&m),
        vec![(10, 20), (8, 21), (9, 21), (10, 21), (7, 22), (8, 22)]
    );
}

#[test]
fn general_lines_have_dx_plus_dy_plus_1_pixels() {
    let mut m = Machine::new(Profile::Desktop);
    for (x1, y1, x2, y2) in [(5, 5, 100, 60), (300, 200, 20, 3), (0, 255, 511, 0)] {
        m.ok("Screen.clearScreen", &[]);
        m.ok("Screen.drawLine", &[x1, y1, x2, y2]);
        let n = (x2 - x1).unsigned_abs() + (y2 - y1).unsigned_abs() + 1;
        assert_eq!(m.black_count(), n as usize);
        assert!(m.black(x1 as usize, y1 as usize) && m.black(x2 as usize, y2 as usize));
    }
}

#[test]
fn axis_lines_are_inclusive_and_errors_are_err8() {
    let mut m = Machine::new(Profile::Desktop);
    m.ok("Screen.drawLine", &[4, 9, 4, 5]);
    m.ok("Screen.drawLine", &[30, 0, 20, 0]);
    assert_eq!(m.black_count(), 5 + 11);
    assert!(m.black(4, 5) && m.black(4, 9) && m.black(20, 0) && m.black(30, 0));
    m.err("Screen.drawLine", &[0, 0, 513, 0], 8);
    m.err("Screen.drawLine", &[-1, 0, 5, 5], 8);
    let mut w = Machine::new(Profile::Web);
    w.ok("Screen.drawLine", &[512, 0, 512, 2]);
    assert_eq!(black_pixels(&w), vec![(0, 1), (0, 2), (0, 3)]);
}

#[test]
fn rectangles_fill_inclusive_and_inverted_ones_draw_nothing() {
    let mut m = Machine::new(Profile::Desktop);
    m.ok("Screen.drawRectangle", &[10, 20, 14, 22]);
    assert_eq!(m.black_count(), 15);
    m.ok("Screen.drawRectangle", &[50, 5, 40, 9]);
    m.ok("Screen.drawRectangle", &[40, 9, 50, 5]);
    assert_eq!(m.black_count(), 15);
    m.err("Screen.drawRectangle", &[0, 0, 10, 257], 9);
    m.err("Screen.drawRectangle", &[0, -1, 10, 10], 9);
}

#[test]
fn circles() {
    let mut m = Machine::new(Profile::Desktop);
    m.ok("Screen.drawCircle", &[100, 100, 0]);
    assert_eq!(black_pixels(&m), vec![(100, 100)]);
    m.ok("Screen.drawCircle", &[100, 100, -4]);
    assert_eq!(m.black_count(), 1);
    m.ok("Screen.drawCircle", &[200, 100, 2]);
    // rows: h = 0, 1, 2, 1, 0 -> 1 + 3 + 5 + 3 + 1 pixels.
    assert_eq!(m.black_count(), 1 + 13);
    assert!(m.black(198, 100) && m.black(202, 100) && m.black(200, 98) && !m.black(199, 98));
    m.err("Screen.drawCircle", &[513, 0, 3], 12);
    m.err("Screen.drawCircle", &[0, -1, 3], 12);
    m.err("Screen.drawCircle", &[256, 128, 182], 13);
    // r = 181 is accepted; its rows above y = 0 are ERR8.
    m.err("Screen.drawCircle", &[256, 128, 181], 8);
}

#[test]
fn each_off_screen_circle_row_raises_err8_and_the_rest_is_drawn() {
    for profile in Profile::ALL {
        let mut m = Machine::new(profile);
        m.ok("Output.moveCursor", &[10, 0]);
        m.ok("Screen.clearScreen", &[]);
        // Rows y = -3..=-1 are off screen.
        m.err("Screen.drawCircle", &[10, 2, 5], 8);
        assert!(m.shows_text(10, 0, "ERR8ERR8ERR8"));
        assert_eq!(m.os.cursor(), (10, 12), "printed once per bad row");
        for dy in 0..=5i32 {
            let h = ((25 - dy * dy) as f64).sqrt() as usize;
            let y = (2 + dy) as usize;
            assert!((10 - h..=10 + h).all(|x| m.black(x, y)), "row {y}");
            assert!(!m.black(10 + h + 1, y));
        }
    }
}

#[test]
fn clear_screen_range_differs_between_profiles() {
    for (profile, heap_cleared) in [(Profile::Desktop, false), (Profile::Web, true)] {
        let mut m = Machine::new(profile);
        m.ram.words_mut().fill(7);
        m.ok("Screen.clearScreen", &[]);
        assert!(m.ram.words()[16384..24576].iter().all(|w| *w == 0));
        assert_eq!(m.ram.read(8191), 7);
        assert_eq!(m.ram.read(8192) == 0, heap_cleared);
        assert_eq!(m.ram.read(16383) == 0, heap_cleared);
        assert_eq!(m.ram.read(24576) == 0, heap_cleared, "keyboard word");
    }
}

#[test]
fn web_clear_screen_wipes_a_high_heap_head() {
    let mut m = Machine::new(Profile::Web);
    m.ok("Memory.alloc", &[7000]);
    assert!(m.os.heap_head() > 8191);
    m.ok("Screen.clearScreen", &[]);
    m.err("Memory.alloc", &[1], 6);
    let mut d = Machine::new(Profile::Desktop);
    d.ok("Memory.alloc", &[7000]);
    d.ok("Screen.clearScreen", &[]);
    d.ok("Memory.alloc", &[1]);
}

proptest::proptest! {
    /// drawRectangle, which fills a word at a time, sets or clears exactly
    /// the pixels that plotting each (x, y) of the rectangle would: the
    /// screen's words, over a screen already patterned, with corners up to
    /// the web IDE's (512, 256) (whose pixels wrap to the next row's start
    /// or fall past the screen).
    #[test]
    fn rectangles_fill_exactly_their_pixels(
        (x1, x2) in (0i16..=512, 0i16..=512),
        (y1, y2) in (0i16..=256, 0i16..=256),
        black in proptest::bool::ANY,
        web in proptest::bool::ANY,
    ) {
        let profile = if web { Profile::Web } else { Profile::Desktop };
        let mut m = Machine::new(profile);
        let pattern = |w: i32| (w.wrapping_mul(40503) >> 3) as i16;
        for w in 0..8192 {
            m.ram.write(16384 + w, pattern(w));
        }
        let mut expected: Vec<i16> = (0..8192).map(pattern).collect();
        for y in i32::from(y1)..=i32::from(y2) {
            for x in i32::from(x1)..=i32::from(x2) {
                let word = 32 * y + x / 16;
                if let Some(e) = expected.get_mut(word as usize) {
                    let bit = 1i16 << (x % 16);
                    *e = if black { *e | bit } else { *e & !bit };
                }
            }
        }
        m.ok("Screen.setColor", &[i16::from(black)]);
        m.ok("Screen.drawRectangle", &[x1, y1, x2, y2]);
        let screen: Vec<i16> = (0..8192).map(|w| m.ram.read(16384 + w)).collect();
        proptest::prop_assert!(screen == expected, "the screen differs");
        proptest::prop_assert_eq!(m.ram.read(24576), 0);
    }
}
