//! `Screen` (spec section 3.6). The web IDE's bounds test accepts x = 512
//! and y = 256; a pixel is then dropped only if its word address 32y + x/16
//! is past the screen, so (512, y) paints (0, y+1). The desktop profile
//! tightens only `Screen.drawPixel` (spec section 0); the other drawing
//! functions and Output share the web rules.

use crate::context::Ctx;
use crate::math::isqrt;
use crate::Profile;

/// Words of screen memory.
const SCREEN_WORDS: i32 = 8192;
/// Pixels of screen memory: pixel (x, y) is bit `x % 16` of word
/// `32y + x / 16`, so its linear index is `512y + x`.
const SCREEN_PIXELS: i32 = SCREEN_WORDS * 16;
/// Largest radius drawCircle accepts.
const MAX_RADIUS: i32 = 181;

/// The web IDE's (off by one) bounds test.
fn out_of_bounds(x: i32, y: i32) -> bool {
    !(0..=512).contains(&x) || !(0..=256).contains(&y)
}

impl Ctx<'_> {
    /// Set (black) or clear bit x%16 of screen word 32y + x/16, if that word
    /// is on the screen. Coordinates have passed a bounds test.
    pub fn plot(&mut self, x: i32, y: i32, black: bool) {
        let word = y * 32 + x.div_euclid(16);
        if !(0..SCREEN_WORDS).contains(&word) {
            return;
        }
        let addr = crate::SCREEN as i32 + word;
        let bit = 1i16 << x.rem_euclid(16);
        let old = self.ram.read(addr);
        self.ram
            .write(addr, if black { old | bit } else { old & !bit });
    }

    /// The screen's words.
    fn screen_words(&mut self) -> &mut [i16] {
        &mut self.ram.words_mut()[crate::SCREEN..crate::SCREEN + SCREEN_WORDS as usize]
    }

    /// Set or clear the pixels of linear indices `from..=to` (see
    /// [`SCREEN_PIXELS`]) that are on the screen, a word at a time: what
    /// [`Ctx::plot`] of each would do.
    fn fill_pixels(&mut self, from: i32, to: i32, black: bool) {
        let (from, to) = (from.max(0), to.min(SCREEN_PIXELS - 1));
        if from > to {
            return;
        }
        let (first, last) = (from / 16, to / 16);
        let words = self.screen_words();
        for w in first..=last {
            let lo = if w == first { from % 16 } else { 0 };
            let hi = if w == last { to % 16 } else { 15 };
            let mask = ((0xFFFF_u32 << lo) & (0xFFFF_u32 >> (15 - hi))) as u16 as i16;
            let word = &mut words[w as usize];
            *word = if black { *word | mask } else { *word & !mask };
        }
    }

    /// Clear the 9x12 pixels of a character cell whose top left pixel has
    /// linear index `from` (see [`SCREEN_PIXELS`]; its column a multiple of
    /// 8), and set those of `glyph`'s 11 rows: what `draw_rect` of the cell
    /// in white and a [`Ctx::plot`] of each glyph pixel would do, a row at
    /// a time. A row's ninth pixel is the next cell's first, the next row's
    /// first at column 63; rows past the screen are dropped.
    pub(crate) fn draw_cell(&mut self, from: i32, glyph: Option<&crate::font::Glyph>) {
        const CELL_ROW: u32 = 0x1FF;
        let words = self.screen_words();
        for dy in 0..12 {
            let at = from + 512 * dy;
            let shift = at.rem_euclid(16);
            let clear = CELL_ROW << shift;
            let bits = glyph
                .and_then(|g| g.get(dy as usize))
                .map_or(0, |&b| u32::from(b) << shift);
            let first = at.div_euclid(16);
            for (w, half) in [(first, 0), (first + 1, 16)] {
                // A row reaches its second word only from bit 8.
                if half == 16 && shift < 8 {
                    continue;
                }
                if (0..SCREEN_WORDS).contains(&w) {
                    let word = &mut words[w as usize];
                    *word =
                        (*word & !((clear >> half) as u16 as i16)) | (bits >> half) as u16 as i16;
                }
            }
        }
    }

    /// `Screen.drawPixel(x, y)` in the current colour: ERR7 out of bounds
    /// (`desktop`: 0 <= x < 512, 0 <= y < 256; `web`: the off-by-one test).
    pub fn draw_pixel(&mut self, x: i32, y: i32) {
        let bad = match self.profile() {
            Profile::Desktop => !(0..512).contains(&x) || !(0..256).contains(&y),
            Profile::Web => out_of_bounds(x, y),
        };
        if bad {
            self.error(7);
            return;
        }
        self.plot(x, y, self.os.color);
    }

    /// `Screen.drawLine`: ERR8 if an end is out of bounds. Vertical and
    /// horizontal runs are inclusive; otherwise a 4-connected staircase of
    /// dx+dy+1 pixels whose first move is vertical.
    pub fn draw_line(&mut self, x1: i32, y1: i32, x2: i32, y2: i32, black: bool) {
        if out_of_bounds(x1, y1) || out_of_bounds(x2, y2) {
            self.error(8);
            return;
        }
        if x1 == x2 {
            for y in y1.min(y2)..=y1.max(y2) {
                self.plot(x1, y, black);
            }
        } else if y1 == y2 {
            for x in x1.min(x2)..=x1.max(x2) {
                self.plot(x, y1, black);
            }
        } else {
            let (dx, dy) = ((x2 - x1).abs(), (y2 - y1).abs());
            let (sx, sy) = ((x2 - x1).signum(), (y2 - y1).signum());
            let (mut a, mut b, mut diff) = (0, 0, 0);
            while a <= dx && b <= dy {
                self.plot(x1 + sx * a, y1 + sy * b, black);
                if diff < 0 {
                    a += 1;
                    diff += dy;
                } else {
                    b += 1;
                    diff -= dx;
                }
            }
        }
    }

    /// `Screen.drawRectangle` (and Output's cell drawing): ERR9 if a corner
    /// is out of bounds; fills x1..=x2 by y1..=y2, nothing if inverted.
    pub fn draw_rect(&mut self, x1: i32, y1: i32, x2: i32, y2: i32, black: bool) {
        if out_of_bounds(x1, y1) || out_of_bounds(x2, y2) {
            self.error(9);
            return;
        }
        for y in y1..=y2 {
            self.fill_pixels(512 * y + x1, 512 * y + x2, black);
        }
    }

    /// `Screen.drawCircle(x, y, r)`: ERR12 for a centre out of bounds, ERR13
    /// for r > 181, nothing for r < 0. One horizontal line per row dy in
    /// -r..=r; each off-screen row raises ERR8 and the others are drawn.
    pub fn draw_circle(&mut self, x: i32, y: i32, r: i32) {
        if out_of_bounds(x, y) {
            self.error(12);
            return;
        }
        if r > MAX_RADIUS {
            self.error(13);
            return;
        }
        let black = self.os.color;
        for dy in -r..=r {
            let h = isqrt(r * r - dy * dy);
            self.draw_line(x - h, y + dy, x + h, y + dy, black);
        }
    }

    /// `Screen.clearScreen()`: `desktop` zeroes the screen 16384..=24575;
    /// `web` zeroes 8192..=24576 (upper heap and keyboard word included).
    pub fn clear_screen(&mut self) {
        let range = match self.profile() {
            Profile::Desktop => crate::SCREEN..crate::KBD,
            Profile::Web => 8192..crate::RAM_SIZE,
        };
        self.ram.words_mut()[range].fill(0);
    }
}
