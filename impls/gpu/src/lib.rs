//! The GPU implementations, as wgpu compute kernels:
//!
//! - a user's shader ([`shader`]): WGSL or Shadertoy-style GLSL, unmodified,
//!   wrapped into compute kernels ([`shader::UserShader`]);
//! - `gpu-f32`: the float formulation of the seed scene (spec section 7) in
//!   WGSL f32, a shader of the same convention ([`Gpu::f32_sdf`],
//!   [`Gpu::f32_pixels`], [`Gpu::render_f32`]);
//! - `gpu-f316`: Float316 ported to WGSL integer arithmetic with Jack's
//!   16-bit semantics, a Float316 shader of the convention, bit-exact with
//!   `ref-f316` ([`Gpu::f316_ops`], [`Gpu::f316_sdf`], [`Gpu::f316_pixels`],
//!   [`Gpu::render_f316`]).
//!
//! - kernels generated from any scene description ([`Gpu::scene_kernel`],
//!   [`scene_wgsl`]): the scene's intermediate form, one WGSL statement per
//!   statement, with only the library functions the scene uses.
//!
//! [`Gpu::new`] picks an adapter (any real GPU, else Mesa's lavapipe on the
//! CPU), opens the device and compiles our two shaders' kernels once
//! ([`shader::ShaderSource::ours`]): that is the
//! set-up cost, measured apart from the renders. Every call batches its
//! input to the device's limits, reuses its buffers and reads results back
//! once per batch. Failures (no adapter, a shader that does not compile, a
//! lost device) are [`GpuError`] values; results are never faked.
//!
//! Tests that need an adapter fail when there is none, unless the
//! environment variable [`SKIP_ENV`] is set: see
//! [`Gpu::new_unless_skipped`].

mod context;
mod device;
mod error;
mod float316;
mod float32;
mod image;
mod kernel;
mod scene_kernel;
mod scene_wgsl;
pub mod shader;
mod words;

pub use common::AdapterDescription;
pub use context::Gpu;
pub use error::GpuError;
pub use image::all_pixels;
pub use scene_kernel::{GpuNum, GpuPixel, SceneKernel};
pub use scene_wgsl::generate as scene_wgsl;

/// Set this environment variable (to any value) to skip the GPU leg where no
/// adapter can be had. Without it, a missing adapter is an error.
pub const SKIP_ENV: &str = "F316_SKIP_GPU";

/// Say on standard error that a GPU check was skipped because [`SKIP_ENV`]
/// is set, naming the running test (its thread's name) and `why`. Written
/// straight to the stream, past `cargo test`'s output capture (which takes
/// only the print macros), so that a passing run without a GPU shows each
/// skipped check and is not mistaken for a verified one.
pub fn report_skipped(why: &str) {
    use std::io::Write;
    let thread = std::thread::current();
    let test = thread.name().unwrap_or("a GPU check");
    let _ = writeln!(
        std::io::stderr(),
        "SKIPPED (no GPU, {SKIP_ENV} is set): {test}: {why}"
    );
}

impl Gpu {
    /// [`Gpu::new`], except that a failure gives `Ok(None)` when the
    /// environment variable [`SKIP_ENV`] says the GPU leg is skipped.
    pub fn new_unless_skipped() -> Result<Option<Gpu>, GpuError> {
        match Gpu::new() {
            Ok(gpu) => Ok(Some(gpu)),
            Err(error) if std::env::var_os(SKIP_ENV).is_some() => {
                eprintln!("GPU leg skipped ({SKIP_ENV} is set): {error}");
                Ok(None)
            }
            Err(error) => Err(error),
        }
    }
}
