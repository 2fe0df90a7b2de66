//! The GPU kernels on a real adapter (a GPU, or lavapipe on the CPU). One
//! test binary so that the device is opened and the kernels compiled once.
//! Without an adapter these tests fail, unless `F316_SKIP_GPU` is set.

mod device;
mod f316_image;
mod f316_ops;
mod f316_vs_reference;
mod f32_errors;
mod scenes;
mod support;
mod user_shader;
