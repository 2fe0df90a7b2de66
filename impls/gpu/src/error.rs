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
    /// A dispatch ran longer than its time limit (a shader that loops for
    /// ever, or nearly). The device stays busy with it and is not used
    /// again; the harness goes on with the other implementations.
    #[error(
        "GPU kernel `{kernel}` ran longer than its limit of {seconds} s and was abandoned \
         (the shader loops for ever or nearly; raise `timeout_s` if it is only slow)"
    )]
    Timeout {
        /// The kernel's label.
        kernel: String,
        /// The limit it outran, in seconds.
        seconds: f64,
    },
    /// A user's shader file could not be read (missing, not a regular
    /// file, too large, not UTF-8); the reason names the file.
    #[error("the shader: {source}")]
    ShaderFile {
        /// The reason, with the file's path.
        source: common::input::InputError,
    },
    /// A user's shader does not parse, does not validate, or lacks the
    /// entry functions of its convention. The diagnostic names the user's
    /// file, line and column.
    #[error("{diagnostic}")]
    Shader {
        /// naga's diagnostic (or the convention's), pointing into the
        /// user's file.
        diagnostic: String,
    },
    /// A level or number type the shader does not provide.
    #[error("the shader `{shader}` does not provide {what}")]
    NotProvided {
        /// The shader's file.
        shader: String,
        /// What was asked of it.
        what: String,
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
