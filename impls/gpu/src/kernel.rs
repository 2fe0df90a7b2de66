//! One compute kernel: its pipeline, its reusable buffers, and the batched
//! run that feeds it input words and reads output words back once per batch.
//!
//! Every kernel has the same bindings: input words, output words, and the
//! item count of the batch (shaders/io.wgsl for the scene kernels, the
//! shader wrapper's own names for shaders, shader/wrappers/io.*). A kernel
//! reads `in_words` and writes `out_words` words per item. A scene kernel's
//! source is compiled after the prelude: those bindings and the Bayer matrix.

use crate::device::{lock, Device, Health};
use crate::error::GpuError;
use crate::image::bayer_wgsl;
use std::sync::{mpsc, Mutex};
use std::time::Duration;

/// Invocations per workgroup; equals `WG` in shaders/io.wgsl.
const WORKGROUP_SIZE: usize = 64;

/// The most items one batch holds, whatever the device allows: bounds the
/// memory a batch takes and the length of one dispatch.
const MAX_BATCH_ITEMS: usize = 1 << 20;

/// The bindings shared by every kernel, as WGSL.
const IO_WGSL: &str = include_str!("shaders/io.wgsl");

/// The buffers of one batch size, reused between runs.
struct Buffers {
    capacity: usize,
    input: wgpu::Buffer,
    output: wgpu::Buffer,
    readback: wgpu::Buffer,
    params: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
}

/// A compiled kernel with its buffers.
pub(crate) struct Kernel {
    label: String,
    in_words: usize,
    out_words: usize,
    pipeline: wgpu::ComputePipeline,
    buffers: Mutex<Option<Buffers>>,
    /// How long one batch may run before the device counts as stuck
    /// (`None`: no limit, for our own kernels, whose loops are bounded).
    time_limit: Option<Duration>,
}

/// Run `f` inside validation, out-of-memory and internal error scopes and
/// return the first error they caught.
fn scoped<T>(device: &wgpu::Device, f: impl FnOnce() -> T) -> (T, Option<wgpu::Error>) {
    let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let memory = device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
    let internal = device.push_error_scope(wgpu::ErrorFilter::Internal);
    let value = f();
    let errors = [internal.pop(), memory.pop(), validation.pop()].map(pollster::block_on);
    (value, errors.into_iter().flatten().next())
}

/// The WGSL every kernel's source follows: the bindings and the Bayer matrix.
fn prelude() -> String {
    format!("{IO_WGSL}\n{}", bayer_wgsl("BAYER", "bayer"))
}

/// Compile `source` (after the [`prelude`]) into a compute
/// pipeline with entry point `entry`. A malformed shader is a
/// [`GpuError::Compile`], never a panic.
pub(crate) fn compile(
    device: &wgpu::Device,
    health: &Health,
    layout: &wgpu::BindGroupLayout,
    label: &str,
    source: &str,
    entry: &str,
) -> Result<wgpu::ComputePipeline, GpuError> {
    let source = wgpu::ShaderSource::Wgsl(format!("{}\n{source}", prelude()).into());
    compile_source(device, health, layout, label, source, entry)
}

/// Compile a shader module from `source` into a compute pipeline with entry
/// point `entry`; any error is a [`GpuError::Compile`].
pub(crate) fn compile_source(
    device: &wgpu::Device,
    health: &Health,
    layout: &wgpu::BindGroupLayout,
    label: &str,
    source: wgpu::ShaderSource<'_>,
    entry: &str,
) -> Result<wgpu::ComputePipeline, GpuError> {
    let (pipeline, error) = scoped(device, || {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(label),
            source,
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(label),
            bind_group_layouts: &[Some(layout)],
            immediate_size: 0,
        });
        device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(label),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some(entry),
            compilation_options: Default::default(),
            cache: None,
        })
    });
    if let Some(error) = error {
        return Err(GpuError::Compile {
            kernel: label.to_string(),
            message: error.to_string(),
        });
    }
    health.check()?;
    Ok(pipeline)
}

impl Kernel {
    /// A kernel around an already compiled `pipeline`; a batch that runs
    /// longer than `time_limit` is a [`GpuError::Timeout`].
    pub(crate) fn from_pipeline(
        label: String,
        pipeline: wgpu::ComputePipeline,
        in_words: usize,
        out_words: usize,
        time_limit: Option<Duration>,
    ) -> Kernel {
        Kernel {
            label,
            in_words,
            out_words,
            pipeline,
            buffers: Mutex::new(None),
            time_limit,
        }
    }

    /// Change how long one batch may run.
    pub(crate) fn set_time_limit(&mut self, time_limit: Option<Duration>) {
        self.time_limit = time_limit;
    }

    /// The most items one batch may hold on this device: storage binding
    /// and buffer sizes, and workgroups per dispatch dimension.
    fn batch_items(&self, limits: &wgpu::Limits) -> usize {
        let item_bytes = (4 * self.in_words.max(self.out_words)) as u64;
        let by_binding = limits
            .max_storage_buffer_binding_size
            .min(limits.max_buffer_size)
            / item_bytes;
        let by_dispatch =
            limits.max_compute_workgroups_per_dimension as u64 * WORKGROUP_SIZE as u64;
        by_binding.min(by_dispatch).min(MAX_BATCH_ITEMS as u64) as usize
    }

    fn make_buffers(&self, gpu: &Device, capacity: usize) -> Buffers {
        let buffer = |label, words: usize, usage| {
            gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: (4 * words.max(4)) as u64,
                usage,
                mapped_at_creation: false,
            })
        };
        use wgpu::BufferUsages as U;
        let input = buffer("input", capacity * self.in_words, U::STORAGE | U::COPY_DST);
        let output = buffer(
            "output",
            capacity * self.out_words,
            U::STORAGE | U::COPY_SRC,
        );
        let readback = buffer(
            "readback",
            capacity * self.out_words,
            U::MAP_READ | U::COPY_DST,
        );
        let params = buffer("params", 4, U::UNIFORM | U::COPY_DST);
        let bind_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(&self.label),
            layout: &gpu.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: input.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: output.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: params.as_entire_binding(),
                },
            ],
        });
        Buffers {
            capacity,
            input,
            output,
            readback,
            params,
            bind_group,
        }
    }

    /// Run the kernel on `input` (`in_words` per item) and return the output
    /// words (`out_words` per item), in batches that fit the device.
    pub(crate) fn run(&self, gpu: &Device, input: &[u32]) -> Result<Vec<u32>, GpuError> {
        gpu.health.check()?;
        debug_assert_eq!(input.len() % self.in_words, 0);
        let items = input.len() / self.in_words;
        let batch = self.batch_items(&gpu.device.limits());
        let mut output = Vec::with_capacity(items * self.out_words);
        let mut cache = lock(&self.buffers);
        for chunk in input.chunks(batch * self.in_words) {
            let n = chunk.len() / self.in_words;
            if cache.as_ref().is_none_or(|b| b.capacity < n) {
                *cache = Some(self.make_buffers(gpu, n));
            }
            let buffers = cache.as_ref().expect("buffers were just made");
            self.run_batch(gpu, buffers, chunk, n, &mut output)?;
        }
        Ok(output)
    }

    fn run_batch(
        &self,
        gpu: &Device,
        buffers: &Buffers,
        chunk: &[u32],
        n: usize,
        output: &mut Vec<u32>,
    ) -> Result<(), GpuError> {
        let out_bytes = (4 * n * self.out_words) as u64;
        let (submission, error) = scoped(&gpu.device, || {
            gpu.queue
                .write_buffer(&buffers.input, 0, bytemuck::cast_slice(chunk));
            gpu.queue.write_buffer(
                &buffers.params,
                0,
                bytemuck::cast_slice(&[n as u32, 0, 0, 0]),
            );
            let mut encoder = gpu
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some(&self.label),
                });
            {
                let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some(&self.label),
                    timestamp_writes: None,
                });
                pass.set_pipeline(&self.pipeline);
                pass.set_bind_group(0, &buffers.bind_group, &[]);
                pass.dispatch_workgroups(n.div_ceil(WORKGROUP_SIZE) as u32, 1, 1);
            }
            encoder.copy_buffer_to_buffer(&buffers.output, 0, &buffers.readback, 0, out_bytes);
            gpu.queue.submit([encoder.finish()])
        });
        if let Some(error) = error {
            // A lost device shows as invalid resources: name the cause.
            let _ = gpu.device.poll(wgpu::PollType::Poll);
            gpu.health.check()?;
            return Err(self.failure(error.to_string()));
        }
        let (sender, receiver) = mpsc::channel();
        buffers
            .readback
            .map_async(wgpu::MapMode::Read, 0..out_bytes, move |result| {
                // The receiver waits below; a send error cannot happen.
                let _ = sender.send(result);
            });
        let polled = gpu.device.poll(wgpu::PollType::Wait {
            submission_index: Some(submission),
            timeout: self.time_limit,
        });
        if let (Err(wgpu::PollError::Timeout), Some(limit)) = (&polled, self.time_limit) {
            return Err(self.stuck(gpu, limit));
        }
        gpu.health.check()?;
        polled.map_err(|e| self.failure(e.to_string()))?;
        let mapped = receiver.recv().map_err(|e| self.failure(e.to_string()))?;
        mapped.map_err(|e| self.failure(e.to_string()))?;
        {
            let view = buffers
                .readback
                .get_mapped_range(0..out_bytes)
                .map_err(|e| self.failure(e.to_string()))?;
            output.extend_from_slice(bytemuck::cast_slice(&view));
        }
        buffers.readback.unmap();
        Ok(())
    }

    fn failure(&self, message: String) -> GpuError {
        GpuError::Execution {
            kernel: self.label.clone(),
            message,
        }
    }

    /// A batch outran `limit`. The device cannot be stopped (lavapipe runs
    /// the dispatch on CPU threads to its end), so it is marked stuck (every
    /// later call fails at once) and its handles are leaked: dropping them
    /// would wait for the dispatch, and the harness must go on.
    fn stuck(&self, gpu: &Device, limit: Duration) -> GpuError {
        gpu.health.set_stuck(&self.label, limit.as_secs_f64());
        std::mem::forget(gpu.device.clone());
        std::mem::forget(gpu.queue.clone());
        std::mem::forget(self.pipeline.clone());
        GpuError::Timeout {
            kernel: self.label.clone(),
            seconds: limit.as_secs_f64(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::device::Device;

    /// A malformed shader through the pipeline-creation function is a
    /// `Compile` error naming the kernel, not a panic. Needs an adapter
    /// (fails without one unless `F316_SKIP_GPU` is set).
    #[test]
    fn malformed_wgsl_is_a_compile_error() {
        let device = match Device::open() {
            Ok(device) => device,
            Err(error) if std::env::var_os(crate::SKIP_ENV).is_some() => {
                eprintln!("GPU leg skipped: {error}");
                return;
            }
            Err(error) => panic!("{error} (set {} to skip the GPU leg)", crate::SKIP_ENV),
        };
        let compile = |source: &str| {
            compile(
                &device.device,
                &device.health,
                &device.layout,
                "probe",
                source,
                "main",
            )
        };
        let good = "@compute @workgroup_size(WG) fn main() { outp[0] = params.count; }";
        assert!(compile(good).is_ok(), "a well-formed kernel compiles");
        let bad = "@compute @workgroup_size(WG) fn main( { outp[0] = ; }";
        match compile(bad) {
            Err(GpuError::Compile { kernel, message }) => {
                assert_eq!(kernel, "probe");
                assert!(!message.is_empty());
            }
            other => panic!("expected a compile error, got {other:?}"),
        }
        let missing_entry = "@compute @workgroup_size(WG) fn other() {}";
        assert!(matches!(
            compile(missing_entry),
            Err(GpuError::Compile { .. })
        ));
    }
}
