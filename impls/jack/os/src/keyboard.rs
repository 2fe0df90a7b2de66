//! `Keyboard` reads (spec section 3.7). A read completes on the release of a
//! key, using the code seen while it was down; the key script supplies keys
//! by VM instruction count, and a read moves the clock to the release.

use crate::context::Ctx;
use crate::string::{BACKSPACE, NEW_LINE};
use crate::Stop;

/// Capacity of the string readLine allocates (207 heap words, never freed).
const LINE_CAPACITY: i32 = 100;

impl Ctx<'_> {
    /// Move the clock to the next press and then to its release; the key's
    /// code, or `None` (after recording [`Stop::BlockedForever`]) if the
    /// script never delivers one.
    fn next_key(&mut self) -> Option<i32> {
        let keys = &self.os.keys;
        let mut clock = *self.clock;
        while keys.key_at(clock) == 0 {
            clock = keys.next_change(clock)?;
        }
        let code = keys.key_at(clock);
        while keys.key_at(clock) != 0 {
            clock = keys.next_change(clock)?;
        }
        *self.clock = clock;
        Some(i32::from(code))
    }

    fn wait_key(&mut self) -> Option<i32> {
        let key = self.next_key();
        if key.is_none() {
            self.fatal(Stop::BlockedForever);
        }
        key
    }

    /// `Keyboard.readChar()`: cursor, wait, printChar, return the code.
    pub fn read_char(&mut self) -> i32 {
        self.draw_cursor();
        let Some(c) = self.wait_key() else { return 0 };
        self.print_char(c);
        c
    }

    /// `Keyboard.readLine(msg)`: printString(msg), cursor, String.new(100),
    /// then keys until Enter (Backspace erases, with ERR18 on an empty line;
    /// the 101st char is ERR17 and returns 0). After Enter, unless halted:
    /// clearChar and println.
    pub fn read_line(&mut self, message: i32) -> i32 {
        self.print_string(message);
        self.draw_cursor();
        let s = self.string_new(LINE_CAPACITY);
        if self.halted() {
            return 0;
        }
        loop {
            let Some(c) = self.wait_key() else { return 0 };
            match c {
                NEW_LINE => break,
                BACKSPACE => {
                    if self.string_length(s) > 0 {
                        self.backspace();
                    }
                    self.string_erase_last_char(s);
                }
                _ => {
                    self.string_append_char(s, c);
                    let halted = self.halted();
                    self.print_char(c);
                    self.draw_cursor();
                    if halted {
                        return 0;
                    }
                }
            }
        }
        if !self.halted() {
            self.clear_char();
            self.println();
        }
        s
    }

    /// `Keyboard.readInt(msg)`: readLine, then intValue (ERR15 when empty).
    pub fn read_int(&mut self, message: i32) -> i32 {
        let s = self.read_line(message);
        if matches!(self.stop, Some(Stop::BlockedForever)) {
            return 0;
        }
        self.string_int_value(s)
    }
}
