//! A tiny machine for driving the OS through its public API in tests.
#![allow(dead_code)]

use jack_os::{lookup, Completion, KeyScript, Os, Profile, Ram, Stop};

pub struct Machine {
    pub os: Os,
    pub ram: Ram,
    pub clock: u64,
    pub profile: Profile,
}

impl Machine {
    pub fn new(profile: Profile) -> Machine {
        Machine::with_keys(profile, KeyScript::none())
    }

    pub fn with_keys(profile: Profile, keys: KeyScript) -> Machine {
        let mut os = Os::new(profile, keys);
        let mut ram = Ram::new();
        os.reset(&mut ram);
        Machine {
            os,
            ram,
            clock: 0,
            profile,
        }
    }

    /// Call a built-in by name; panics on an unknown name (test bug).
    pub fn call(&mut self, name: &str, args: &[i16]) -> Completion {
        let f = lookup(name)
            .unwrap_or_else(|| panic!("no built-in {name}"))
            .builtin;
        self.os.call(f, args, &mut self.ram, &mut self.clock)
    }

    /// Call a built-in that must not stop the run; its value.
    pub fn ok(&mut self, name: &str, args: &[i16]) -> i16 {
        let c = self.call(name, args);
        assert_eq!(c.stop, None, "{name}{args:?} stopped");
        c.value
    }

    /// Call a built-in that must raise `Sys.error(code)`; its value.
    pub fn err(&mut self, name: &str, args: &[i16], code: i16) -> i16 {
        let c = self.call(name, args);
        assert_eq!(c.stop, Some(Stop::SysError(code)), "{name}{args:?}");
        c.value
    }

    /// A string object holding `text`, built as the compiler builds literals.
    pub fn string(&mut self, text: &str) -> i16 {
        let s = self.ok("String.new", &[text.len() as i16]);
        for b in text.bytes() {
            assert_eq!(self.ok("String.appendChar", &[s, b as i16]), s);
        }
        s
    }

    /// The text of string object `s`, read from RAM by its profile's
    /// layout (web: a pointer to the chars at s+2; desktop: the chars from
    /// s+2).
    pub fn text(&self, s: i16) -> String {
        let s = i32::from(s);
        let chars = match self.profile {
            Profile::Web => i32::from(self.ram.read(s + 2)),
            Profile::Desktop => s + 2,
        };
        let len = self.ram.read(s + 1);
        (0..i32::from(len))
            .map(|i| char::from(self.ram.read(chars + i) as u8))
            .collect()
    }

    /// Fill the whole screen black.
    pub fn blacken(&mut self) {
        self.ram.words_mut()[16384..24576].fill(-1);
    }

    pub fn black(&self, x: usize, y: usize) -> bool {
        self.ram.pixel(x, y)
    }

    /// The top pixel row of text row `r`: 11r, one lower on the desktop.
    pub fn cell_y(&self, r: usize) -> usize {
        11 * r + usize::from(self.profile == Profile::Desktop)
    }

    /// Whether the 8x11 cell (r, c) shows exactly the glyph of `ch`.
    pub fn shows(&self, r: usize, c: usize, ch: char) -> bool {
        let g = glyph(ch);
        let y = self.cell_y(r);
        (0..11).all(|i| (0..8).all(|j| self.black(8 * c + j, y + i) == g[i][j]))
    }

    /// Whether cells of row `r` starting at column `c` show `text`.
    pub fn shows_text(&self, r: usize, c: usize, text: &str) -> bool {
        text.chars()
            .enumerate()
            .all(|(k, ch)| self.shows(r, c + k, ch))
    }

    /// Number of black pixels on the screen.
    pub fn black_count(&self) -> usize {
        self.ram.words()[16384..24576]
            .iter()
            .map(|w| w.count_ones() as usize)
            .sum()
    }
}

/// The official glyph of `ch`, straight from hack-font.json.
pub fn glyph(ch: char) -> Vec<Vec<bool>> {
    let font: serde_json::Value =
        serde_json::from_str(include_str!("../../hack-font.json")).unwrap();
    font["glyphs"][(ch as u32).to_string()]
        .as_array()
        .unwrap()
        .iter()
        .map(|row| row.as_str().unwrap().chars().map(|c| c == '#').collect())
        .collect()
}
