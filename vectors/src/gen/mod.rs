//! Deterministic generators: proptest strategies drawn by a `TestRunner`
//! whose RNG is seeded from a fixed number, plus hand-made catalogues of
//! hard cases. The same seed always gives the same vectors, so the
//! committed sets can be rebuilt bit for bit.

pub mod classes;
pub mod ops;
pub mod pixels;
pub mod scene_derived;
pub mod sdf;
pub mod testfloat;

use proptest::strategy::{Strategy, ValueTree};
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};

/// A source of values drawn from proptest strategies with a fixed seed.
pub struct Draw {
    runner: TestRunner,
}

impl Draw {
    /// A drawer whose sequence is fixed by `seed`.
    pub fn new(seed: u64) -> Self {
        let mut bytes = [0u8; 32];
        bytes[..8].copy_from_slice(&seed.to_le_bytes());
        let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &bytes);
        Draw {
            runner: TestRunner::new_with_rng(Config::default(), rng),
        }
    }

    /// One value of the strategy (its first, unshrunk value).
    pub fn one<S: Strategy>(&mut self, strategy: &S) -> S::Value {
        strategy
            .new_tree(&mut self.runner)
            .expect("the generators' strategies never reject values")
            .current()
    }
}
