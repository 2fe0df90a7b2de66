//! The state one built-in call works on, and the `Sys.error` path shared by
//! every OS class.

use crate::{KeyScript, Profile, Ram, Stop};

/// Words the web IDE reads outside 0..=24576 inside its OS code: 65535
/// (a built-in that returns it pushes -1).
const OUT_OF_RANGE_READ: i32 = 65535;

/// The OS's own state (outside RAM).
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct OsState {
    pub profile: Profile,
    /// `Math.divide`'s rounding (the profile's unless chosen).
    pub divide: crate::DivideRule,
    pub keys: KeyScript,
    /// Free-list head (not in RAM; spec 3.2). Kept unwrapped, as in the IDE.
    pub heap_head: i32,
    /// Output cursor row 0..=22 and column 0..=63.
    pub row: i32,
    pub col: i32,
    /// Screen colour: true = black.
    pub color: bool,
    /// Desktop: `Sys.error` is building its "ERR" string.
    pub in_error: bool,
}

impl OsState {
    pub fn new(profile: Profile, divide: crate::DivideRule, keys: KeyScript) -> OsState {
        OsState {
            profile,
            divide,
            keys,
            heap_head: crate::ram::HEAP_BASE,
            row: 0,
            col: 0,
            color: true,
            in_error: false,
        }
    }
}

/// The desktop's error for a built-in's access outside the heap and screen.
pub(crate) const OUTSIDE_HEAP_OR_SCREEN: &str =
    "A built-in function tried to access memory outside the Heap or Screen range";

/// One built-in call in progress.
pub(crate) struct Ctx<'a> {
    pub os: &'a mut OsState,
    pub ram: &'a mut Ram,
    pub clock: &'a mut u64,
    /// How the call ends the run, if it does.
    pub stop: Option<Stop>,
}

impl Ctx<'_> {
    /// A word as the OS code sees it: signed inside RAM, 65535 outside.
    pub fn get(&self, addr: i32) -> i32 {
        if (0..crate::RAM_SIZE as i32).contains(&addr) {
            i32::from(self.ram.read(addr))
        } else {
            OUT_OF_RANGE_READ
        }
    }

    /// Store `v` mod 2^16 (dropped outside RAM).
    pub fn set(&mut self, addr: i32, v: i32) {
        self.ram.write(addr, v as i16);
    }

    /// The desktop's check on a built-in's memory access: the word must be
    /// in the heap or the screen (2048..=24576, the keyboard included) or
    /// be word 0; else the run stops with the desktop's message. The
    /// address is a 16-bit word, as the desktop's Java `short`.
    #[inline]
    fn checked(&mut self, addr: i32) -> Option<i32> {
        let addr = i32::from(addr as i16);
        if (2048..=crate::KBD as i32).contains(&addr) || addr == 0 {
            Some(addr)
        } else {
            self.fatal(Stop::RuntimeError(OUTSIDE_HEAP_OR_SCREEN.into()));
            None
        }
    }

    /// A word read the desktop's way (see [`Ctx::checked`]); 0 once refused.
    pub fn checked_get(&mut self, addr: i32) -> i32 {
        if self.halted() {
            return 0;
        }
        self.checked(addr).map_or(0, |a| self.get(a))
    }

    /// A word written the desktop's way (see [`Ctx::checked`]).
    pub fn checked_set(&mut self, addr: i32, v: i32) {
        if self.halted() {
            return;
        }
        if let Some(a) = self.checked(addr) {
            self.set(a, v);
        }
    }

    pub fn profile(&self) -> crate::Profile {
        self.os.profile
    }

    pub fn divide_rule(&self) -> crate::DivideRule {
        self.os.divide
    }

    /// Whether `Sys.error`, `Sys.halt` or a fatal condition has stopped the run.
    pub fn halted(&self) -> bool {
        self.stop.is_some()
    }

    /// `Sys.error(code)`: print `"ERR<code>"` at the cursor and stop with that
    /// exit code. The caller carries on to the end of its built-in. As in the
    /// web IDE, a later error in the same call replaces the exit code.
    pub fn error(&mut self, code: i16) {
        if self.profile() == crate::Profile::Desktop && !self.os.in_error && !self.halted() {
            // The desktop's built-in Sys.error prints through a Jack string
            // "ERR" that it builds with String.new(3) and appendChar: a
            // 5-word heap block (an error inside that is printed alone).
            self.os.in_error = true;
            let s = self.string_new(3);
            for c in b"ERR" {
                if self.halted() {
                    break;
                }
                self.string_append_char(s, i32::from(*c));
            }
            self.os.in_error = false;
        }
        for c in b"ERR" {
            self.print_char(i32::from(*c));
        }
        self.print_int(code);
        if matches!(self.stop, None | Some(Stop::SysError(_)) | Some(Stop::Halt)) {
            self.stop = Some(Stop::SysError(code));
        }
    }

    /// `Sys.halt()`.
    pub fn halt(&mut self) {
        if self.stop.is_none() {
            self.stop = Some(Stop::Halt);
        }
    }

    /// A condition the official tool does not survive (a JS exception, an
    /// endless loop, input that never comes): it wins over any exit code.
    pub fn fatal(&mut self, stop: Stop) {
        if !matches!(
            self.stop,
            Some(Stop::RuntimeError(_) | Stop::Hang(_) | Stop::BlockedForever)
        ) {
            self.stop = Some(stop);
        }
    }
}

/// The decimal digits of `v` as character codes, with a leading '-' for a
/// negative value (as JavaScript's `toString`): at most 6 codes.
pub(crate) fn decimal(v: i16) -> impl Iterator<Item = i32> {
    let mut buf = [0i32; 6];
    let mut n = i32::from(v).unsigned_abs();
    let mut len = 0;
    loop {
        buf[len] = i32::from(b'0') + (n % 10) as i32;
        len += 1;
        n /= 10;
        if n == 0 {
            break;
        }
    }
    if v < 0 {
        buf[len] = i32::from(b'-');
        len += 1;
    }
    buf.into_iter().take(len).rev()
}

#[cfg(test)]
mod tests {
    use super::decimal;

    fn text(v: i16) -> String {
        decimal(v).map(|c| char::from(c as u8)).collect()
    }

    #[test]
    fn decimal_text() {
        assert_eq!(text(0), "0");
        assert_eq!(text(-32768), "-32768");
        assert_eq!(text(32767), "32767");
        assert_eq!(text(-5), "-5");
        assert_eq!(text(120), "120");
    }
}
