//! The device context: adapter description, pixel validation and a lost
//! device as errors.

use crate::support::gpu;
use gpu::{Gpu, GpuError};

#[test]
fn adapter_is_named() {
    let Some(gpu) = gpu() else { return };
    let info = gpu.adapter_info();
    assert!(!info.name.is_empty());
    assert!(!info.backend.is_empty());
    if info.driver == "llvmpipe" {
        assert!(info.is_software(), "{info}");
    }
    eprintln!("adapter: {info}");
}

#[test]
fn pixels_outside_the_image_are_an_error() {
    let Some(gpu) = gpu() else { return };
    assert!(matches!(
        gpu.f32_pixels(&[(0, 0), (512, 0)]),
        Err(GpuError::PixelOutsideImage { x: 512, y: 0, .. })
    ));
    assert!(gpu.f316_pixels(&[]).expect("empty input").is_empty());
}

/// A destroyed device (as after a driver reset) makes every call fail with
/// `DeviceLost`. Uses its own context, not the shared one.
#[test]
fn a_lost_device_is_an_error() {
    let Some(lost) = Gpu::new_unless_skipped().expect("adapter") else {
        gpu::report_skipped("no adapter");
        return;
    };
    lost.destroy();
    match lost.f32_sdf(&[[0.0, 0.0, 0.0]]) {
        Err(GpuError::DeviceLost { reason }) => assert!(reason.contains("Destroyed"), "{reason}"),
        other => panic!("expected DeviceLost, got {other:?}"),
    }
}
