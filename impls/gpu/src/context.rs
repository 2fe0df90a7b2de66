//! The GPU context: one device ([`crate::device`]) and our two seed-scene
//! kernels, created once by [`Gpu::new`] and shared by all calls.

use crate::device::Device;
use crate::error::GpuError;
use crate::shader::{Compiled, ShaderNumbers, ShaderOptions, ShaderSource};
use common::AdapterDescription;

/// The GPU context: adapter, device, queue and our two seed-scene kernels
/// (`gpu-f32`, `gpu-f316`: our own WGSL run as shaders of the convention,
/// [`ShaderSource::ours`]), created once; the scene kernels compile on the
/// same device. Methods take `&self`; buffers are reused between calls.
pub struct Gpu {
    pub(crate) dev: Device,
    pub(crate) f316: Compiled,
    pub(crate) f32: Compiled,
}

impl Gpu {
    /// Open the preferred adapter, compile both shaders' kernels and
    /// dispatch each once. A driver may compile a kernel's machine code
    /// only at its first dispatch (lavapipe does: 13 s for the Float316
    /// pixel kernel when Mesa's shader cache is cold), and that belongs to
    /// set-up, not to the first measured batch. The time this takes is the
    /// set-up cost, separate from any render.
    ///
    /// `WGPU_BACKEND` (e.g. `vulkan`) restricts the backends tried.
    pub fn new() -> Result<Gpu, GpuError> {
        let dev = Device::open()?;
        let ours = |numbers| {
            Compiled::new(
                &dev,
                &ShaderSource::ours(numbers),
                &ShaderOptions::ours(numbers),
            )
        };
        Ok(Gpu {
            f316: ours(ShaderNumbers::Float316)?,
            f32: ours(ShaderNumbers::F32)?,
            dev,
        })
    }

    /// The adapter the kernels run on.
    pub fn adapter_info(&self) -> &AdapterDescription {
        &self.dev.adapter
    }

    /// Release the device now. Every later call fails with
    /// [`GpuError::DeviceLost`], as it would after a driver reset.
    pub fn destroy(&self) {
        self.dev.destroy();
    }
}
