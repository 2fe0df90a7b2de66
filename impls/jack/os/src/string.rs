//! `String` (spec section 3.4). Layout: `s = alloc(n+3)`; `RAM[s]` =
//! maxLength, `RAM[s+1]` = length, `RAM[s+2]` = the char array `alloc(n)`:
//! 2n+7 heap words.

use crate::context::{decimal, Ctx};
use crate::Profile;

/// `String.backSpace()`.
pub(crate) const BACKSPACE: i32 = 129;
/// `String.doubleQuote()`.
pub(crate) const DOUBLE_QUOTE: i32 = 34;
/// `String.newLine()`.
pub(crate) const NEW_LINE: i32 = 128;

/// A JavaScript number (an integer-valued double) reduced mod 2^16, as the
/// web IDE stores it: exact even above 2^53, 0 for an infinity.
fn js_number_to_word(v: f64) -> i32 {
    if !v.is_finite() {
        return 0;
    }
    // Doubles of magnitude >= 2^127 are multiples of 2^74: 0 mod 2^16.
    if v.abs() >= 2f64.powi(127) {
        return 0;
    }
    i32::from(v.trunc() as i128 as i16)
}

impl Ctx<'_> {
    /// `String.new(n)`: ERR14 for n < 0 (and 0 is returned even if the
    /// header allocation then succeeds). `web`: n = 0 raises ERR2 from
    /// alloc(0); `desktop`: n = 0 is allowed and has no char array (0).
    pub fn string_new(&mut self, n: i32) -> i32 {
        if n < 0 {
            self.error(14);
        }
        let s = self.alloc(n + 3);
        if self.halted() {
            return 0;
        }
        self.set(s, n);
        self.set(s + 1, 0);
        let chars = if n == 0 && self.profile() == Profile::Desktop {
            0
        } else {
            self.alloc(n)
        };
        self.set(s + 2, chars);
        s
    }

    fn string_max_length(&self, s: i32) -> i32 {
        self.get(s)
    }

    /// `s.length()`.
    pub fn string_length(&self, s: i32) -> i32 {
        self.get(s + 1)
    }

    fn string_chars(&self, s: i32) -> i32 {
        self.get(s + 2)
    }

    /// `s.charAt(i)`: ERR15 (and 0) unless 0 <= i < length.
    pub fn string_char_at(&mut self, s: i32, i: i32) -> i32 {
        if i < 0 || i >= self.string_length(s) {
            self.error(15);
            return 0;
        }
        self.get(self.string_chars(s) + i)
    }

    /// `s.setCharAt(i, c)`: ERR16 unless 0 <= i < length.
    pub fn string_set_char_at(&mut self, s: i32, i: i32, c: i32) {
        if i < 0 || i >= self.string_length(s) {
            self.error(16);
            return;
        }
        self.set(self.string_chars(s) + i, c);
    }

    /// `s.appendChar(c)`: ERR17 (and 0) on a full string, else returns s.
    pub fn string_append_char(&mut self, s: i32, c: i32) -> i32 {
        let len = self.string_length(s);
        if len == self.string_max_length(s) {
            self.error(17);
            return 0;
        }
        self.set(s + 1, len + 1);
        self.string_set_char_at(s, len, c);
        s
    }

    /// `s.eraseLastChar()`: ERR18 on an empty string.
    pub fn string_erase_last_char(&mut self, s: i32) {
        let len = self.string_length(s);
        if len == 0 {
            self.error(18);
            return;
        }
        self.set(s + 1, len - 1);
    }

    /// `s.intValue()`: optional '-', then digits up to the first non-digit,
    /// accumulated as a JavaScript number and then wrapped ("40000" gives
    /// -25536). An empty string raises ERR15 from charAt(0).
    pub fn string_int_value(&mut self, s: i32) -> i32 {
        let negative = self.string_char_at(s, 0) == i32::from(b'-');
        let mut i = i32::from(negative);
        let mut value = 0f64;
        while i < self.string_length(s) {
            let c = self.string_char_at(s, i);
            if !(i32::from(b'0')..=i32::from(b'9')).contains(&c) {
                break;
            }
            value = value * 10.0 + f64::from(c - i32::from(b'0'));
            i += 1;
        }
        js_number_to_word(if negative { -value } else { value })
    }

    /// `s.setInt(v)`: the signed decimal of v; ERR19 (string unchanged) if
    /// it is longer than maxLength.
    pub fn string_set_int(&mut self, s: i32, v: i16) {
        let len = decimal(v).count() as i32;
        if len > self.string_max_length(s) {
            self.error(19);
            return;
        }
        self.set(s + 1, 0);
        for c in decimal(v) {
            self.string_append_char(s, c);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::js_number_to_word;

    #[test]
    fn js_numbers_wrap_like_the_ide() {
        assert_eq!(js_number_to_word(40000.0), -25536);
        assert_eq!(js_number_to_word(-0.0), 0);
        assert_eq!(js_number_to_word(-32768.0), -32768);
        assert_eq!(js_number_to_word(65536.0 * 3.0 + 5.0), 5);
        assert_eq!(
            js_number_to_word(1e20),
            (100_000_000_000_000_000_000i128 % 65536) as i32
        );
        assert_eq!(js_number_to_word(f64::INFINITY), 0);
        assert_eq!(js_number_to_word(1e300), 0);
    }
}
