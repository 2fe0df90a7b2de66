//! The device: the adapter chosen, the device and queue opened on it, the
//! health records its callbacks fill, and the bind group layout every
//! kernel shares. Kernels and shaders compile on it; [`crate::Gpu`] holds
//! one.

use crate::error::GpuError;
use common::AdapterDescription;
use std::sync::{Arc, Mutex};

/// The description of wgpu's adapter `info`.
fn describe(info: &wgpu::AdapterInfo) -> AdapterDescription {
    // wgpu calls a CPU rasteriser `Cpu` on Vulkan; the names catch one
    // that a backend reports otherwise.
    let named = |s: &str| {
        let s = s.to_lowercase();
        ["llvmpipe", "lavapipe", "softpipe", "swiftshader"]
            .iter()
            .any(|n| s.contains(n))
    };
    AdapterDescription {
        name: info.name.clone(),
        backend: format!("{:?}", info.backend),
        device_type: format!("{:?}", info.device_type),
        driver: info.driver.clone(),
        driver_info: info.driver_info.clone(),
        software: info.device_type == wgpu::DeviceType::Cpu
            || named(&info.name)
            || named(&info.driver),
    }
}

/// Problems the device reports outside any call: a lost device, or an
/// error no error scope caught.
#[derive(Default)]
pub(crate) struct Health {
    lost: Mutex<Option<String>>,
    uncaptured: Mutex<Vec<String>>,
    stuck: Mutex<Option<(String, f64)>>,
}

impl Health {
    /// The first problem recorded, if any.
    pub(crate) fn check(&self) -> Result<(), GpuError> {
        if let Some((kernel, seconds)) = lock(&self.stuck).clone() {
            return Err(GpuError::Timeout { kernel, seconds });
        }
        if let Some(reason) = lock(&self.lost).clone() {
            return Err(GpuError::DeviceLost { reason });
        }
        if let Some(message) = lock(&self.uncaptured).first().cloned() {
            return Err(GpuError::Execution {
                kernel: "device".into(),
                message,
            });
        }
        Ok(())
    }

    /// Record that a dispatch of `kernel` outran its time limit: the
    /// device is still busy with it, so every later call fails at once.
    pub(crate) fn set_stuck(&self, kernel: &str, seconds: f64) {
        *lock(&self.stuck) = Some((kernel.to_string(), seconds));
    }
}

/// Lock a mutex, ignoring poisoning (the data are plain records).
pub(crate) fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

/// Preference among adapter kinds: real GPUs first, the CPU last.
fn rank(info: &wgpu::AdapterInfo) -> u8 {
    match info.device_type {
        wgpu::DeviceType::DiscreteGpu => 0,
        wgpu::DeviceType::IntegratedGpu => 1,
        wgpu::DeviceType::VirtualGpu => 2,
        wgpu::DeviceType::Other => 3,
        wgpu::DeviceType::Cpu => 4,
    }
}

/// Pick any real GPU, else a software adapter (lavapipe); only adapters that
/// run compute shaders count.
fn choose_adapter(instance: &wgpu::Instance) -> Result<wgpu::Adapter, GpuError> {
    let adapters = pollster::block_on(instance.enumerate_adapters(wgpu::Backends::all()));
    let mut seen = Vec::new();
    let mut usable = Vec::new();
    for adapter in adapters {
        let info = adapter.get_info();
        let compute = adapter
            .get_downlevel_capabilities()
            .flags
            .contains(wgpu::DownlevelFlags::COMPUTE_SHADERS);
        seen.push(format!(
            "{} on {:?}{}",
            info.name,
            info.backend,
            if compute {
                ""
            } else {
                " without compute shaders"
            }
        ));
        if compute {
            usable.push(adapter);
        }
    }
    usable.sort_by_key(|a| rank(&a.get_info()));
    usable
        .into_iter()
        .next()
        .ok_or_else(|| GpuError::NoAdapter {
            detail: if seen.is_empty() {
                "wgpu saw no adapter at all".into()
            } else {
                format!("seen: {}", seen.join("; "))
            },
        })
}

/// An open device with its health records and the bind group layout every
/// kernel shares, before any kernel is compiled.
pub(crate) struct Device {
    pub(crate) device: wgpu::Device,
    pub(crate) queue: wgpu::Queue,
    pub(crate) health: Arc<Health>,
    pub(crate) adapter: AdapterDescription,
    pub(crate) layout: wgpu::BindGroupLayout,
}

impl Device {
    /// Open the preferred adapter's device and watch it for loss and for
    /// errors no scope catches.
    pub(crate) fn open() -> Result<Device, GpuError> {
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        let adapter = choose_adapter(&instance)?;
        let description = describe(&adapter.get_info());
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("f316-harness"),
            required_limits: adapter.limits(),
            ..Default::default()
        }))
        .map_err(|source| GpuError::RequestDevice {
            adapter: description.name.clone(),
            source,
        })?;

        let health = Arc::new(Health::default());
        let lost = Arc::clone(&health);
        device.set_device_lost_callback(move |reason, message| {
            *lock(&lost.lost) = Some(format!("{reason:?}: {message}"));
        });
        let uncaptured = Arc::clone(&health);
        device.on_uncaptured_error(Arc::new(move |error: wgpu::Error| {
            lock(&uncaptured.uncaptured).push(error.to_string());
        }));
        let layout = bind_group_layout(&device);
        Ok(Device {
            device,
            queue,
            health,
            adapter: description,
            layout,
        })
    }
}

impl Device {
    /// Release the device now; every later call fails with
    /// [`GpuError::DeviceLost`].
    pub(crate) fn destroy(&self) {
        self.device.destroy();
        // Deliver the device-lost callback now; its error is the point.
        let _ = self.device.poll(wgpu::PollType::wait_indefinitely());
    }
}

/// The bind group layout of shaders/io.wgsl.
pub(crate) fn bind_group_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    let storage = |binding, read_only| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    };
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("kernel io"),
        entries: &[
            storage(0, true),
            storage(1, false),
            wgpu::BindGroupLayoutEntry {
                binding: 2,
                visibility: wgpu::ShaderStages::COMPUTE,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            },
        ],
    })
}
