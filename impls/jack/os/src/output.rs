//! `Output` (spec section 3.5): a 23x64 character grid over the screen,
//! cell (r, c) at pixel (8c, 11r) in the web IDE and (8c, 11r + 1) in the
//! desktop VM emulator, whose text starts at screen word 32 (its
//! `START_ADDRESS`, spec section 6).

use crate::context::{decimal, Ctx};
use crate::font::glyph;
use crate::{Profile, Stop};

/// Rows 0..=22.
const LAST_ROW: i32 = 22;
/// Columns 0..=63.
const COLUMNS: i32 = 64;

/// Pixel row of the top of row 0's cells, per profile.
const fn first_row_y(profile: Profile) -> i32 {
    match profile {
        Profile::Desktop => 1,
        Profile::Web => 0,
    }
}

impl Ctx<'_> {
    /// The top pixel row of the cursor's cell.
    fn cell_top(&self) -> i32 {
        self.os.row * 11 + first_row_y(self.profile())
    }

    /// Fill the cell white, 9x12 pixels inclusive: x in [8c, 8c+8], y in
    /// [top, top+11], so it also erases the next cell's first column and the
    /// first row of the cell below (and wraps to column 0 at c = 63).
    pub fn clear_char(&mut self) {
        self.draw_cell(self.cell_index(), None);
    }

    /// The linear pixel index (`512y + x`) of the cursor's cell's top left.
    fn cell_index(&self) -> i32 {
        512 * self.cell_top() + self.os.col * 8
    }

    /// The cursor: clearChar, then a black 5x8 box.
    pub fn draw_cursor(&mut self) {
        self.clear_char();
        let (x, y) = (self.os.col * 8, self.cell_top());
        self.draw_rect(x + 2, y + 2, x + 6, y + 9, true);
    }

    /// `Output.moveCursor(i, j)`: ERR20 outside the grid. `web` accepts
    /// j = 64, whose cursor drawing recurses until the JS stack overflows.
    pub fn move_cursor(&mut self, i: i32, j: i32) {
        let last_col = match self.profile() {
            Profile::Desktop => COLUMNS - 1,
            Profile::Web => COLUMNS,
        };
        if !(0..=LAST_ROW).contains(&i) || !(0..=last_col).contains(&j) {
            self.error(20);
            return;
        }
        if j == COLUMNS {
            // In the IDE, clearChar at column 64 is ERR9, whose "ERR9" is
            // printed at column 64 again, and so on. The cursor stays where
            // it was, so that no later call can recurse here.
            self.fatal(Stop::RuntimeError(
                "Maximum call stack size exceeded".into(),
            ));
            return;
        }
        self.os.row = i;
        self.os.col = j;
        self.draw_cursor();
    }

    /// `Output.printChar(k)`: a glyph (32..=126) is drawn over a cleared
    /// cell; any other code draws nothing. The cursor then advances.
    pub fn print_char(&mut self, k: i32) {
        if let Some(g) = glyph(k) {
            self.draw_cell(self.cell_index(), Some(g));
        }
        self.os.col += 1;
        if self.os.col == COLUMNS {
            self.println();
        }
    }

    /// `Output.println()`: column 0 of the next row; row 22 wraps to row 0
    /// (no scrolling, no clearing).
    pub fn println(&mut self) {
        self.os.col = 0;
        self.os.row = if self.os.row >= LAST_ROW {
            0
        } else {
            self.os.row + 1
        };
    }

    /// `Output.backSpace()`: clearChar, one column back (stopping at column 0
    /// of the previous row, never column 63), then the cursor.
    pub fn backspace(&mut self) {
        self.clear_char();
        self.os.col -= 1;
        if self.os.col < 0 {
            self.os.col = 0;
            self.os.row = (self.os.row - 1).max(0);
        }
        self.draw_cursor();
    }

    /// `Output.printString(s)`: printChar of chars 0..length-1 (the length is
    /// re-read after every char, as in the IDE).
    pub fn print_string(&mut self, s: i32) {
        let mut i = 0;
        while i < self.string_length(s) {
            if self.profile() == crate::Profile::Desktop && self.halted() {
                break;
            }
            let c = self.string_char_at(s, i);
            self.print_char(c);
            i += 1;
        }
    }

    /// `Output.printInt(v)`: the signed decimal of v.
    pub fn print_int(&mut self, v: i16) {
        for c in decimal(v) {
            self.print_char(c);
        }
    }
}
