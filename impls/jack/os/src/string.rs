//! `String` (spec section 3.4). Web layout: `s = alloc(n+3)`; `RAM[s]` =
//! maxLength, `RAM[s+1]` = length, `RAM[s+2]` = the char array `alloc(n)`:
//! 2n+7 heap words. Desktop layout (its built-in `String`): one block
//! `s = alloc(n+2)` holding maxLength, length and the n chars from `s+2`;
//! with the desktop's 2-word block headers, n+4 heap words. The desktop's
//! functions stop at their first error (its `Sys.error` ends the built-in).

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
        if self.profile() == Profile::Desktop {
            if n < 0 {
                self.error(14);
                return 0;
            }
            let s = self.alloc(n + 2);
            if self.halted() {
                return 0;
            }
            self.checked_set(s, n);
            self.checked_set(s + 1, 0);
            return s;
        }
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

    fn string_max_length(&mut self, s: i32) -> i32 {
        if self.profile() == Profile::Desktop {
            return self.checked_get(s);
        }
        self.get(s)
    }

    /// `s.length()`.
    pub fn string_length(&mut self, s: i32) -> i32 {
        if self.profile() == Profile::Desktop {
            return self.checked_get(s + 1);
        }
        self.get(s + 1)
    }

    /// Address of char 0: web, the char array `RAM[s+2]`; desktop, `s+2`.
    fn string_chars(&self, s: i32) -> i32 {
        if self.profile() == Profile::Desktop {
            return s + 2;
        }
        self.get(s + 2)
    }

    fn char_get(&mut self, a: i32) -> i32 {
        if self.profile() == Profile::Desktop {
            return self.checked_get(a);
        }
        self.get(a)
    }

    fn char_set(&mut self, a: i32, c: i32) {
        if self.profile() == Profile::Desktop {
            self.checked_set(a, c);
        } else {
            self.set(a, c);
        }
    }

    /// Desktop `s.intValue()`: the chars as Java text; an optional '-',
    /// then digits up to the first non-digit, accumulated in a wrapping
    /// 32-bit int and cut to 16 bits. An empty string is 0 (no error).
    fn desktop_int_value(&mut self, s: i32) -> i32 {
        let len = self.string_length(s);
        let chars: Vec<u16> = (0..len.max(0))
            .map(|i| self.checked_get(s + 2 + i) as u16)
            .collect();
        let negative = chars.first() == Some(&u16::from(b'-'));
        let mut value: i32 = 0;
        for &c in &chars[usize::from(negative)..] {
            if !(u16::from(b'0')..=u16::from(b'9')).contains(&c) {
                break;
            }
            value = value
                .wrapping_mul(10)
                .wrapping_add(i32::from(c - u16::from(b'0')));
        }
        i32::from(if negative {
            value.wrapping_neg()
        } else {
            value
        } as i16)
    }

    /// `s.charAt(i)`: ERR15 (and 0) unless 0 <= i < length.
    pub fn string_char_at(&mut self, s: i32, i: i32) -> i32 {
        if i < 0 || i >= self.string_length(s) {
            self.error(15);
            return 0;
        }
        let a = self.string_chars(s) + i;
        self.char_get(a)
    }

    /// `s.setCharAt(i, c)`: ERR16 unless 0 <= i < length.
    pub fn string_set_char_at(&mut self, s: i32, i: i32, c: i32) {
        if i < 0 || i >= self.string_length(s) {
            self.error(16);
            return;
        }
        let a = self.string_chars(s) + i;
        self.char_set(a, c);
    }

    /// `s.appendChar(c)`: ERR17 (and 0) on a full string, else returns s.
    pub fn string_append_char(&mut self, s: i32, c: i32) -> i32 {
        if self.profile() == Profile::Desktop {
            let capacity = self.string_max_length(s);
            let len = self.string_length(s);
            if len == capacity {
                self.error(17);
                return 0;
            }
            self.checked_set(s + 2 + len, c);
            self.checked_set(s + 1, len + 1);
            return s;
        }
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
        if self.profile() == Profile::Desktop {
            self.checked_set(s + 1, len - 1);
        } else {
            self.set(s + 1, len - 1);
        }
    }

    /// `s.intValue()`: optional '-', then digits up to the first non-digit,
    /// accumulated as a JavaScript number and then wrapped ("40000" gives
    /// -25536). An empty string raises ERR15 from charAt(0).
    pub fn string_int_value(&mut self, s: i32) -> i32 {
        if self.profile() == Profile::Desktop {
            return self.desktop_int_value(s);
        }
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
        if self.profile() == Profile::Desktop {
            self.checked_set(s + 1, len);
            for (i, c) in (0..).zip(decimal(v)) {
                self.checked_set(s + 2 + i, c);
            }
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
