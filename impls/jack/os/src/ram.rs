//! The Hack VM's data memory (spec section 1).

/// Number of addressable words: 0..=24576.
pub const RAM_SIZE: usize = 24577;
/// First word of the screen memory map (512x256 pixels, 8192 words).
pub const SCREEN: usize = 16384;
/// The keyboard word.
pub const KBD: usize = 24576;
/// Address of the heap's initial free block.
pub(crate) const HEAP_BASE: i32 = 2048;
/// Size of the initial free block (data words after its 2-word header).
pub(crate) const HEAP_SIZE: i32 = 14334;
/// The desktop's last heap word; a block "address" past it ends its list.
pub(crate) const HEAP_END: i32 = 16383;

/// 24577 signed 16-bit words. Reads outside 0..=24576 give -1 and writes
/// outside are dropped, as in the web IDE; nothing here panics.
#[derive(Clone, PartialEq, Eq)]
pub struct Ram {
    /// The words, then [`GUARD`] words of [`GUARD_WORD`].
    words: Box<[i16; RAM_SIZE + GUARD]>,
}

/// Debug builds (the tests): words past the end of RAM that nothing may
/// touch. Code that addresses RAM through a raw pointer (the VM's compiled
/// code) and read past its end would find [`GUARD_WORD`], not the -1 a read
/// past RAM gives, and one that wrote there would leave two machines' RAM
/// unequal: either shows in a comparison with the interpreter.
const GUARD: usize = if cfg!(debug_assertions) { 64 } else { 0 };
/// What the guard words hold.
const GUARD_WORD: i16 = 0x5A5A;

impl Default for Ram {
    fn default() -> Self {
        Ram::new()
    }
}

impl std::fmt::Debug for Ram {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Ram")
            .field("sp", &self.words[0])
            .field(
                "nonzero_words",
                &self.words().iter().filter(|w| **w != 0).count(),
            )
            .finish()
    }
}

impl Ram {
    /// All words zero.
    pub fn new() -> Ram {
        let mut words = vec![0; RAM_SIZE + GUARD];
        words[RAM_SIZE..].fill(GUARD_WORD);
        Ram {
            words: words
                .into_boxed_slice()
                .try_into()
                .expect("RAM_SIZE + GUARD words"),
        }
    }

    fn index(addr: i32) -> Option<usize> {
        usize::try_from(addr).ok().filter(|&a| a < RAM_SIZE)
    }

    /// The word at `addr`, or -1 outside 0..=24576.
    #[inline]
    pub fn read(&self, addr: i32) -> i16 {
        Ram::index(addr).map_or(-1, |a| self.words[a])
    }

    /// Store `v` at `addr`; dropped outside 0..=24576.
    #[inline]
    pub fn write(&mut self, addr: i32, v: i16) {
        if let Some(a) = Ram::index(addr) {
            self.words[a] = v;
        }
    }

    /// All 24577 words.
    pub fn words(&self) -> &[i16] {
        &self.words[..RAM_SIZE]
    }

    /// All 24577 words, mutable.
    pub fn words_mut(&mut self) -> &mut [i16] {
        &mut self.words[..RAM_SIZE]
    }

    /// Screen pixel (x, y), true = black: bit `x % 16` of word
    /// `16384 + 32y + x/16`. False outside 512x256.
    pub fn pixel(&self, x: usize, y: usize) -> bool {
        if x >= 512 || y >= 256 {
            return false;
        }
        let word = self.words[SCREEN + 32 * y + x / 16] as u16;
        word >> (x % 16) & 1 == 1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn out_of_range_reads_are_minus_one_and_writes_are_dropped() {
        let mut ram = Ram::new();
        assert_eq!(ram.read(-1), -1);
        assert_eq!(ram.read(24577), -1);
        assert_eq!(ram.read(24576), 0);
        ram.write(24577, 5);
        ram.write(-3, 5);
        assert!(ram.words().iter().all(|w| *w == 0));
        ram.write(24576, 7);
        assert_eq!(ram.read(24576), 7);
    }

    #[test]
    fn pixel_bit_zero_is_the_leftmost() {
        let mut ram = Ram::new();
        ram.write(SCREEN as i32 + 32 * 3 + 1, 0b101);
        assert!(ram.pixel(16, 3));
        assert!(!ram.pixel(17, 3));
        assert!(ram.pixel(18, 3));
        assert!(!ram.pixel(512, 3));
        ram.write(SCREEN as i32, i16::MIN);
        assert!(ram.pixel(15, 0));
    }
}
