//! Errors of the GPU leg: every way a kernel can fail to give an honest
//! result, as a value the harness can report (a GPU row marked unavailable,
//! never a faked one).

/// What went wrong on the GPU side.
#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    /// No adapter that can run compute shaders.
    #[error(
        "no GPU adapter with compute shaders was found ({detail}); on a machine without a GPU \
         install Mesa's lavapipe (a Vulkan driver that runs on the CPU): \
         `apt-get install mesa-vulkan-drivers libvulkan1`, or run scripts/setup.sh"
    )]
    NoAdapter {
        /// The adapters seen and why none fits.
        detail: String,
    },
    /// The adapter refused to open a device.
    #[error("the GPU adapter `{adapter}` refused to open a device: {source}")]
    RequestDevice {
        /// The adapter's name.
        adapter: String,
        /// wgpu's reason.
        source: wgpu::RequestDeviceError,
    },
    /// A WGSL shader or its compute pipeline was rejected.
    #[error("GPU kernel `{kernel}` failed to compile: {message}")]
    Compile {
        /// The kernel's label.
        kernel: String,
        /// The compiler's or validator's message.
        message: String,
    },
    /// The device was lost (driver reset, out of memory, or destroyed).
    #[error("the GPU device was lost: {reason}")]
    DeviceLost {
        /// The reason the driver gave.
        reason: String,
    },
    /// Running a kernel raised a validation, memory or internal error.
    #[error("GPU kernel `{kernel}` failed: {message}")]
    Execution {
        /// The kernel's label.
        kernel: String,
        /// wgpu's message.
        message: String,
    },
    /// A pixel coordinate outside the 512x256 image.
    #[error("pixel ({x},{y}) lies outside the {width}x{height} image")]
    PixelOutsideImage {
        /// Column.
        x: u16,
        /// Row.
        y: u16,
        /// Image width.
        width: usize,
        /// Image height.
        height: usize,
    },
}
