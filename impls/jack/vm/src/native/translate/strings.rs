//! `String.length`, `charAt` and `appendChar` run by compiled code itself:
//! string-building code calls them every few instructions, and a host
//! call costs many times what they do. Each reads and writes the words
//! the OS would (`jack_os`'s string layouts: web, the characters in a
//! separate array `RAM[s+2]`; desktop, from `s+2`), after tests that every
//! word is one the OS touches without a rule and that no error is raised;
//! else the interpreter makes the call. Every test comes before the first
//! store, so that leaving for the interpreter repeats nothing.

use super::{Before, Stack, Translator};
use cranelift_codegen::ir::condcodes::IntCC;
use cranelift_codegen::ir::{InstBuilder, Value};
use jack_os::{Builtin, Profile};

impl Translator<'_, '_> {
    /// `s + k` for a zero-extended `s`, without wrapping: an address past
    /// 65535 fails every test, and goes to the interpreter (where the
    /// desktop's Java `short` wraps it, and the web finds it past RAM).
    fn offset(&mut self, s: Value, k: i64) -> Value {
        self.b.ins().iadd_imm_s(s, k)
    }

    fn load_offset(&mut self, s: Value, k: i64) -> Value {
        let a = self.offset(s, k);
        self.load_word(a)
    }

    /// The length word of `string`, after the test that it is a word a
    /// built-in reads without a rule; the held stack words go to RAM first,
    /// since the string may lie on them.
    fn length(&mut self, string: Value, s: &mut Stack, before: &Before) -> Value {
        let a = self.offset(string, 1);
        let ok = self.os_word_ok(a);
        self.guard(ok, before);
        s.flush(self);
        s.forget();
        self.load_word(a)
    }

    /// Run `String.length`, `charAt` or `appendChar` on the operand stack
    /// `s` and return its value, leaving at `before` where a test fails.
    pub(super) fn inline_string(
        &mut self,
        builtin: Builtin,
        s: &mut Stack,
        before: &Before,
    ) -> Value {
        let desktop = self.env.profile == Profile::Desktop;
        match builtin {
            Builtin::StringLength => {
                let string = s.pop(self);
                let string = self.exact(string);
                self.length(string, s, before)
            }
            Builtin::StringCharAt => {
                let i = s.pop(self);
                let i = self.exact(i);
                let string = s.pop(self);
                let string = self.exact(string);
                let len = self.length(string, s, before);
                // ERR15 unless 0 <= i < length (as 16-bit numbers).
                let from_0 = self.non_negative(i);
                let (i_high, len_high) = (self.signed_high(i), self.signed_high(len));
                let below = self.b.ins().icmp(IntCC::SignedLessThan, i_high, len_high);
                let chars = if desktop {
                    self.offset(string, 2)
                } else {
                    let array = self.offset(string, 2);
                    let ok = self.os_word_ok(array);
                    self.guard(ok, before);
                    self.load_word(array)
                };
                let at = self.b.ins().iadd(chars, i);
                let ok = self.os_word_ok(at);
                self.guard_all(&[from_0, below, ok], before);
                self.load_word(at)
            }
            Builtin::StringAppendChar => {
                let c = s.pop(self);
                let string = s.pop(self);
                let string = self.exact(string);
                // The string's words (maxLength, length and, on the web, the
                // array's address) lie in the words a built-in may touch:
                // its first and its last, which cannot wrap past the end.
                let last = self.offset(string, if desktop { 1 } else { 2 });
                let first_ok = self.os_word_ok(string);
                let last_ok = self.os_word_ok(last);
                self.guard_all(&[first_ok, last_ok], before);
                s.flush(self);
                let cap = self.load_word(string);
                let len = self.load_offset(string, 1);
                // ERR17 on a full string.
                let room = self.b.ins().icmp(IntCC::NotEqual, len, cap);
                let next = self.b.ins().iadd_imm_s(len, 1);
                let length_at = self.offset(string, 1);
                if desktop {
                    // The char at s+2+length, then the length.
                    let base = self.offset(string, 2);
                    let at = self.b.ins().iadd(base, len);
                    let ok = self.os_word_ok(at);
                    self.guard_all(&[room, ok], before);
                    self.store_word(at, c);
                    self.store_word(length_at, next);
                } else {
                    // The length, then setCharAt(length): ERR16 unless
                    // 0 <= length < length + 1 (as 16-bit numbers).
                    let array = self.load_offset(string, 2);
                    let at = self.b.ins().iadd(array, len);
                    let from_0 = self.non_negative(len);
                    let no_wrap =
                        self.b
                            .ins()
                            .icmp_imm_s(IntCC::NotEqual, len, i64::from(i16::MAX));
                    let ok = self.os_word_ok(at);
                    self.guard_all(&[room, from_0, no_wrap, ok], before);
                    self.store_word(length_at, next);
                    self.store_word(at, c);
                }
                s.forget();
                string
            }
            _ => unreachable!("only the string built-ins blocks::inline_builtin names"),
        }
    }
}
