//! SplitMix64: the small deterministic generator behind every fixed table
//! of pseudo-random points and every shard assignment, so that the same
//! seed draws the same numbers on every machine and in every crate.

/// A SplitMix64 stream (Steele, Lea and Flood's generator, as in Java's
/// `SplittableRandom`): the state steps by the golden-ratio constant and
/// each output is that state through a 64-bit finaliser.
#[derive(Clone, Debug)]
pub struct SplitMix64 {
    state: u64,
}

impl SplitMix64 {
    /// A stream from `seed`; its first output depends only on the seed.
    pub fn new(seed: u64) -> Self {
        SplitMix64 { state: seed }
    }

    /// The next 64 bits.
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in `0..n` (`n` > 0), by the remainder.
    pub fn below(&mut self, n: u64) -> u64 {
        self.next_u64() % n
    }

    /// Uniform in [0, 1): the top 53 bits as a fraction.
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
}

#[cfg(test)]
mod tests {
    use super::SplitMix64;

    /// The generator's published first outputs from seed 0.
    #[test]
    fn known_values() {
        let mut g = SplitMix64::new(0);
        assert_eq!(g.next_u64(), 0xe220_a839_7b1d_cdaf);
        assert_eq!(g.next_u64(), 0x6e78_9e6a_a1b9_65f4);
        assert_eq!(g.next_u64(), 0x06c4_5d18_8009_454f);
    }

    #[test]
    fn unit_and_below_stay_in_range() {
        let mut g = SplitMix64::new(316);
        for _ in 0..1000 {
            assert!((0.0..1.0).contains(&g.unit()));
            assert!(g.below(7) < 7);
        }
    }
}
