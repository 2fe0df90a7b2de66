//! The shared device of the test binary.

use common::Outcome;
use gpu::Gpu;
use reference::Reference;
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

/// A float reference's seed image: each pixel's value and whether it is
/// white; a trapped pixel fails the test.
pub fn float_pixels(r: &Reference) -> (Vec<f64>, Vec<bool>) {
    r.render()
        .pixels
        .iter()
        .map(|p| match p {
            Outcome::Value(p) => (p.value.value, p.white),
            other => panic!("a float pixel trapped: {other:?}"),
        })
        .unzip()
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
