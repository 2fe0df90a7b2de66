//! The description of a GPU adapter, as reports and the cast name it. It
//! lives here, not in the GPU crate, so that the harness's core can carry
//! one without depending on wgpu.

use serde::{Deserialize, Serialize};

/// The adapter a GPU implementation runs on, as reports name it.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct AdapterDescription {
    /// The adapter's name (`llvmpipe (LLVM 15.0.6, 256 bits)` for lavapipe).
    pub name: String,
    /// The graphics API it is driven through (`Vulkan`, `Metal`, ...).
    pub backend: String,
    /// Discrete, integrated, virtual, CPU or other.
    pub device_type: String,
    /// The driver's name (`llvmpipe`).
    pub driver: String,
    /// The driver's version string.
    pub driver_info: String,
    /// Whether it is a software rasteriser on the CPU (lavapipe, llvmpipe,
    /// SwiftShader): no figure or verdict from it stands for a GPU's.
    pub software: bool,
}

impl AdapterDescription {
    /// Whether this is a software rasteriser running on the CPU (lavapipe).
    pub fn is_software(&self) -> bool {
        self.software
    }
}

impl std::fmt::Display for AdapterDescription {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} ({}, {}, driver {} {})",
            self.name, self.backend, self.device_type, self.driver, self.driver_info
        )
    }
}
