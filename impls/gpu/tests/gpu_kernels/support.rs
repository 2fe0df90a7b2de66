//! The shared device of the test binary.

use gpu::Gpu;
use std::sync::OnceLock;

/// The device, opened once; `None` only when the GPU leg is explicitly
/// skipped (`F316_SKIP_GPU`). No adapter without that variable fails. A
/// skipped test says so on the terminal ([`gpu::report_skipped`]).
pub fn gpu() -> Option<&'static Gpu> {
    static GPU: OnceLock<Option<Gpu>> = OnceLock::new();
    let gpu = GPU
        .get_or_init(|| match Gpu::new_unless_skipped() {
            Ok(gpu) => gpu,
            Err(error) => panic!("{error} (set {} to skip the GPU leg)", gpu::SKIP_ENV),
        })
        .as_ref();
    if gpu.is_none() {
        gpu::report_skipped("no adapter");
    }
    gpu
}

/// A small deterministic generator (SplitMix64) for test tables.
pub struct Rng(u64);

impl Rng {
    /// A generator with a fixed seed.
    pub fn new(seed: u64) -> Self {
        Rng(seed)
    }

    /// The next 64 random bits.
    pub fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in 0..n.
    pub fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }

    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// `inputs` and `answers` side by side, once they are known to be as many:
/// a kernel that answers fewer or more inputs than it was given fails.
pub fn paired<'a, I, A>(
    what: &str,
    inputs: &'a [I],
    answers: &'a [A],
) -> impl Iterator<Item = (&'a I, &'a A)> {
    assert_eq!(
        answers.len(),
        inputs.len(),
        "{what}: {} answers to {} inputs",
        answers.len(),
        inputs.len()
    );
    inputs.iter().zip(answers)
}
