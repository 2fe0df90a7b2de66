//! The shared device of the test binary.

use gpu::Gpu;
use std::sync::OnceLock;

/// The device, opened once; `None` only when the GPU leg is explicitly
/// skipped (`F316_SKIP_GPU`). No adapter without that variable fails.
pub fn gpu() -> Option<&'static Gpu> {
    static GPU: OnceLock<Option<Gpu>> = OnceLock::new();
    GPU.get_or_init(|| match Gpu::new_unless_skipped() {
        Ok(gpu) => gpu,
        Err(error) => panic!("{error} (set {} to skip the GPU leg)", gpu::SKIP_ENV),
    })
    .as_ref()
}
