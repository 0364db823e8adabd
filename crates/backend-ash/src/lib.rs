//! Runs Stratus's frame graph on raw Vulkan (ash), from the program's SPIR-V (the committed
//! `spirv-out/`, embedded).
//!
//! The renderer is persistent and reads like backend-wgpu: the first frame of a plan creates
//! what it needs (resources by name, a pipeline and render pass per pass, descriptor sets,
//! framebuffers, a query pool); later frames only write the uniform block and record commands.
//! A new plan rebuilds only the resources whose size, format or usage changed and the pipelines
//! it lacks. Noise is uploaded when a different `Arc<NoiseSet>` arrives. History resources
//! ping-pong: frame N's `name.previous` is what frame N-1 wrote as `name`. The one difference
//! in what runs: wgpu translates the WGSL itself (with the plan's override values), while this
//! backend loads the exact bytes of `<module>.<variant>.spv`, where `cargo xtask
//! build-shaders` baked the same values in. Descriptor set layouts come from the plan's
//! bindings (the manifest's reflection); barriers come from the same reflection (what every
//! binding reads or writes).
//!
//! With [`Options::validation`] the Khronos validation layer runs with synchronization
//! validation, and every warning or error it reports (leaked objects at device destruction
//! included) turns into an [`Error::Validation`] from [`Renderer::new`], [`Renderer::render`]
//! or [`Renderer::finish`].
//!
//! With the `conformance` feature, `Renderer::render_with` runs the same frames from SPIR-V
//! supplied per pass (naga's GLSL or HLSL compiled by glslang): the conformance suite's paths.

#![deny(missing_docs)]

mod error;
mod gpu;
mod interface;
mod pipeline;
mod resources;

use std::{
    collections::HashMap,
    hash::{Hash, Hasher},
    sync::Arc,
    time::Instant,
};

use ash::vk;
use gpu_allocator::MemoryLocation;
use stratus_graph::{
    Backend, BackendError, FrameInput, FrameOutput, FramePlan, PassTiming, Program,
    backend::{
        FrameState, Made, Readout, cpu_wall_timings, history_half, timings_from_ticks, upload_data,
    },
    desc::{Lifetime, PREVIOUS, ResourceKind},
    plan::{Pass, PassKind, Requirements},
};
use stratus_noise::NoiseSet;
use stratus_scene::FrameUniforms;

pub use crate::error::Error;
#[cfg(not(feature = "conformance"))]
use crate::interface::{PassShader, Shaders};
#[cfg(feature = "conformance")]
pub use crate::interface::{PassShader, Shaders, Slot, SlotContent};
use crate::{
    error::vk,
    gpu::{FormatNeed, Gpu},
    interface::{Descriptor, SlotContent as Content, descriptors},
    pipeline::{Entries, PassPipeline, RasterTargets, module_from_words},
    resources::{
        COLOR_LAYER, GpuBuffer, GpuImage, Key, Tracker, Use, image_needs, range, view_type,
        vk_format,
    },
};

/// How to create the renderer.
#[derive(Clone, Copy, Debug, Default)]
pub struct Options {
    /// Turn on the Khronos validation layer with synchronization validation; any warning or
    /// error it reports makes the call that caused it fail with [`Error::Validation`].
    pub validation: bool,
}

/// The stage of the timestamps written before and after every pass: BOTTOM_OF_PIPE, as
/// wgpu-hal writes its pass timestamps, so both backends measure the same span.
///
/// On lavapipe (llvmpipe) a dispatch runs synchronously and a non-TOP_OF_PIPE timestamp
/// flushes first, so these stamps bracket the dispatch exactly, as long as llvmpipe has no
/// framebuffer bound. With a framebuffer bound (a raster pass), llvmpipe bins the timestamp
/// into the rasteriser's tiles and only takes the time at the *next* flush, so on lavapipe a
/// raster pass's own time is not exact (compute passes before it are unaffected); measured
/// against each pass submitted alone (`examples/timestamps.rs`).
const TIMESTAMP_STAGE: vk::PipelineStageFlags = vk::PipelineStageFlags::BOTTOM_OF_PIPE;

/// Which pipeline a pass runs: the program's SPIR-V, by file and pass, or a supplied module's,
/// by a hash of the [`PassShader`] (words, entry point and slots).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
enum PipelineKey {
    Program { spv: String, pass: String },
    Supplied(u64),
}

/// The GPU side of a resource of the plan.
struct Resource {
    /// What it was made from (kept while it serves the plan).
    made: Made,
    object: Object,
}

enum Object {
    /// The renderer's one uniform block.
    Uniform,
    Buffer(GpuBuffer),
    /// One image, or two for a history pair.
    Images(Vec<GpuImage>),
    Sampler(vk::Sampler),
}

/// What was built for one plan (and set of shaders): descriptor sets and framebuffers.
struct State {
    plan: FramePlan,
    shaders: Shaders,
    keys: Vec<PipelineKey>,
    pool: vk::DescriptorPool,
    /// Per pass, per history parity, one set per `@group`.
    sets: Vec<Vec<Vec<vk::DescriptorSet>>>,
    /// Per raster pass, per history parity (empty for compute passes).
    framebuffers: Vec<Vec<vk::Framebuffer>>,
    /// Supplied modules only: a nearest sampler for non-filterable combined images, and the
    /// zeros naga's HLSL sampler index buffers read.
    nearest: vk::Sampler,
    indices: Option<GpuBuffer>,
}

/// A Vulkan device ready to render frames of Stratus's frame graph.
pub struct Renderer {
    program: Arc<Program>,
    modules: HashMap<String, vk::ShaderModule>,
    pipelines: HashMap<PipelineKey, PassPipeline>,
    resources: HashMap<String, Resource>,
    uniform: Option<GpuBuffer>,
    state: Option<State>,
    tracker: Tracker,
    noise: Option<Arc<NoiseSet>>,
    query_pool: vk::QueryPool,
    query_count: u32,
    readbacks: HashMap<String, GpuBuffer>,
    /// Frame count, history validity, computed persistent resources (the shared rules).
    frames: FrameState,
    created: u64,
    cpu_timing: bool,
    torn_down: bool,
    /// The device was lost: every later frame says so at once.
    lost: Option<&'static str>,
    gpu: Gpu,
}

impl Renderer {
    /// Loads the Vulkan loader, creates an instance (with validation when asked), picks a
    /// device (a real GPU before a CPU driver such as lavapipe, as backend-wgpu does) that
    /// has a compute and graphics queue and every image format the frame graph needs, and
    /// creates the device, its command pool and memory allocator.
    pub fn new(options: Options) -> Result<Self, Error> {
        let program = Program::embedded().map_err(|e| Error::Shader(e.to_string()))?;
        Self::with_program(options, program)
    }

    /// As [`Renderer::new`], running `program` (a test's own graph and shaders).
    pub fn with_program(options: Options, program: Arc<Program>) -> Result<Self, Error> {
        let needs = format_needs(&program)?;
        let gpu = Gpu::new(options.validation, &needs)?;
        Ok(Self {
            program,
            modules: HashMap::new(),
            pipelines: HashMap::new(),
            resources: HashMap::new(),
            uniform: None,
            state: None,
            tracker: Tracker::default(),
            noise: None,
            query_pool: vk::QueryPool::null(),
            query_count: 0,
            readbacks: HashMap::new(),
            frames: FrameState::default(),
            created: 0,
            cpu_timing: false,
            torn_down: false,
            lost: None,
            gpu,
        })
    }

    /// The device in words, written like backend-wgpu's adapter, e.g.
    /// `llvmpipe (LLVM 15.0.6, 256 bits) (Vulkan, Cpu)`.
    pub fn adapter(&self) -> String {
        self.gpu.info.name.clone()
    }

    /// Whether passes are timed with GPU timestamp queries (else by CPU wall time).
    pub fn has_timestamps(&self) -> bool {
        self.gpu.info.timestamp_bits > 0 && !self.cpu_timing
    }

    /// Times every pass by submitting it alone and waiting for it on the CPU (`cpu-wall`),
    /// as devices without timestamp queries do. Useful to check the timestamps.
    pub fn set_cpu_wall_timing(&mut self, on: bool) {
        self.cpu_timing = on;
    }

    /// GPU objects this renderer has created so far.
    pub fn objects_created(&self) -> u64 {
        self.created
    }

    /// Renders one frame from the program's SPIR-V, waits for it, and reads back what
    /// `frame.readback` asks for.
    pub fn render(&mut self, frame: &FrameInput<'_>) -> Result<FrameOutput, Error> {
        self.render_shaders(frame, &Shaders::Committed)
    }

    /// Renders one frame from `shaders`: the program's SPIR-V (as [`Renderer::render`]) or one
    /// supplied module per pass. Everything but the modules and their descriptor layouts is
    /// the same frame: resources, barriers, timestamps, readback.
    #[cfg(feature = "conformance")]
    pub fn render_with(
        &mut self,
        frame: &FrameInput<'_>,
        shaders: &Shaders,
    ) -> Result<FrameOutput, Error> {
        self.render_shaders(frame, shaders)
    }

    fn render_shaders(
        &mut self,
        frame: &FrameInput<'_>,
        shaders: &Shaders,
    ) -> Result<FrameOutput, Error> {
        let computes = frame
            .plan
            .passes
            .iter()
            .filter(|p| matches!(p.kind, PassKind::Compute { .. }))
            .count();
        if let Shaders::PerPass(list) = shaders
            && list.len() != computes
        {
            return Err(Error::Shader(format!(
                "{} supplied shader module(s) for a plan of {computes} compute passes",
                list.len(),
            )));
        }
        if let Some(call) = self.lost {
            return Err(Error::DeviceLost { call });
        }
        self.gpu.check_messages()?;
        let result = self.render_inner(frame, shaders);
        if let Err(Error::DeviceLost { call }) = &result {
            // Nothing more runs on a lost device: no rebuilding on it, and the loss is what
            // the caller hears (before any message the layer adds about it).
            self.lost = Some(call);
            return result;
        }
        if result.is_err() {
            // SAFETY: valid device. The frame may still be in flight after a failed step;
            // wait, and build everything anew next time (the tracker's states may be stale).
            unsafe {
                let _ = self.gpu.device.device_wait_idle();
                let _ = self.gpu.device.reset_command_buffer(
                    self.gpu.command_buffer,
                    vk::CommandBufferResetFlags::empty(),
                );
            }
            self.drop_state();
            self.drop_resources();
        }
        self.gpu.check_messages()?;
        result
    }

    /// Tears the renderer down and reports whatever the validation layer said while doing
    /// so (leaked objects are reported when the device is destroyed). Dropping the renderer
    /// does the same but can only print such messages.
    pub fn finish(mut self) -> Result<(), Error> {
        self.teardown();
        self.gpu.check_messages()
    }

    fn teardown(&mut self) {
        if std::mem::replace(&mut self.torn_down, true) {
            return;
        }
        // SAFETY: waiting first; then nothing uses the pipelines or modules.
        unsafe {
            let _ = self.gpu.device.device_wait_idle();
        }
        self.drop_state();
        self.drop_resources();
        let device = &self.gpu.device;
        // SAFETY: idle (above); each object is destroyed once (drained or taken).
        unsafe {
            for (_, mut p) in self.pipelines.drain() {
                p.destroy(device);
            }
            for (_, m) in self.modules.drain() {
                device.destroy_shader_module(m, None);
            }
            device.destroy_query_pool(std::mem::take(&mut self.query_pool), None);
        }
        for (_, mut b) in self.readbacks.drain() {
            b.destroy(device, &mut self.gpu.allocator);
        }
        if let Some(mut u) = self.uniform.take() {
            u.destroy(device, &mut self.gpu.allocator);
        }
        self.gpu.destroy();
    }

    /// Destroys what was built for the current plan (the GPU is idle).
    fn drop_state(&mut self) {
        if let Some(mut state) = self.state.take() {
            let device = &self.gpu.device;
            // SAFETY: the GPU is idle (every submit is waited for); frees the sets too.
            unsafe {
                device.destroy_descriptor_pool(state.pool, None);
                for fb in state.framebuffers.iter().flatten() {
                    device.destroy_framebuffer(*fb, None);
                }
                device.destroy_sampler(state.nearest, None);
            }
            if let Some(mut b) = state.indices.take() {
                b.destroy(device, &mut self.gpu.allocator);
            }
        }
    }

    /// Destroys every resource (the GPU is idle).
    fn drop_resources(&mut self) {
        let names: Vec<String> = self.resources.keys().cloned().collect();
        for name in names {
            self.drop_resource(&name);
        }
        self.noise = None;
    }

    fn drop_resource(&mut self, name: &str) {
        let Some(r) = self.resources.remove(name) else {
            return;
        };
        let device = &self.gpu.device;
        match r.object {
            Object::Uniform => {}
            Object::Buffer(mut b) => b.destroy(device, &mut self.gpu.allocator),
            Object::Images(list) => {
                for mut i in list {
                    i.destroy(device, &mut self.gpu.allocator);
                }
            }
            // SAFETY: the GPU is idle.
            Object::Sampler(s) => unsafe { device.destroy_sampler(s, None) },
        }
        self.tracker.remove(name);
    }

    fn render_inner(
        &mut self,
        frame: &FrameInput<'_>,
        shaders: &Shaders,
    ) -> Result<FrameOutput, Error> {
        let t0 = Instant::now();
        self.prepare(frame, shaders)?;
        let plan = frame.plan;
        let run = self.frames.passes(frame);
        let timestamps = self.has_timestamps();

        // 1. The uniform block (host-visible; the previous frame was waited for).
        let uniforms: FrameUniforms = self.frames.uniforms(frame);
        self.uniform
            .as_mut()
            .expect("created by prepare")
            .mapped()?
            .copy_from_slice(bytemuck::bytes_of(&uniforms));

        // 2. Record: counters cleared, then every pass with barriers before and timestamps
        // around it.
        let cb = self.gpu.command_buffer;
        self.begin()?;
        let mut waited = 0.0;
        // SAFETY (this block and the recording below): `cb` is recording; every handle
        // belongs to this device and lives until the renderer changes plan after a wait.
        unsafe {
            if timestamps {
                self.gpu
                    .device
                    .cmd_reset_query_pool(cb, self.query_pool, 0, self.query_count);
            }
            if plan.stats {
                for r in plan
                    .resources
                    .iter()
                    .filter(|r| r.kind == ResourceKind::Counters)
                {
                    if let Some(Object::Buffer(b)) = self.resources.get(&r.name).map(|r| &r.object)
                    {
                        let fill = Use {
                            layout: vk::ImageLayout::UNDEFINED,
                            ..Use::COPY_DST
                        };
                        self.tracker
                            .barrier(&self.gpu.device, cb, &[((r.name.clone(), 0), fill)]);
                        self.gpu
                            .device
                            .cmd_fill_buffer(cb, b.buffer, 0, vk::WHOLE_SIZE, 0);
                    }
                }
            }
        }
        let mut wall = Vec::new();
        if !timestamps {
            // The clear is submitted on its own first, so that the first pass's CPU time is
            // the pass alone.
            waited += self.submit_and_wait()?;
            self.begin()?;
        }
        for (k, &i) in run.iter().enumerate() {
            self.record_pass(plan, i, timestamps.then_some(2 * k as u32))?;
            if !timestamps {
                // No timestamps: submit this pass alone and time it on the CPU.
                let t = Instant::now();
                let w = self.submit_and_wait()?;
                let ms = t.elapsed().as_secs_f64() * 1e3;
                wall.push(ms);
                waited += w;
                self.begin()?;
            }
        }

        // 3. Copy what the frame reads back to host-visible buffers, submit, wait, read.
        let copies = self.copy_readbacks(frame)?;
        let t_submit = Instant::now();
        let w = self.submit_and_wait()?;
        let cpu_ms = t_submit.duration_since(t0).as_secs_f64() * 1e3 - waited
            + (t_submit.elapsed().as_secs_f64() * 1e3 - w).max(0.0);
        self.frames.finished(frame, &run, &uniforms);

        let mut out = FrameOutput {
            width: plan.width,
            height: plan.height,
            cpu_ms,
            device: self.adapter(),
            ..Default::default()
        };
        // gpu-allocator picks HOST_COHERENT memory for GpuToCpu, so no invalidation is needed.
        for (index, readout) in copies {
            let bytes = self
                .readbacks
                .get_mut(&plan.resources[index].name)
                .expect("created by copy_readbacks")
                .mapped()?
                .to_vec();
            out.store(plan, index, readout, bytes);
        }
        let ran: Vec<&Pass> = run.iter().map(|&i| &plan.passes[i]).collect();
        out.timings = if timestamps {
            self.timestamps(&ran)?
        } else {
            cpu_wall_timings(&ran, &wall)
        };
        Ok(out)
    }

    /// Creates or updates what `frame` needs: resources, uploads, pipelines, descriptor sets,
    /// framebuffers, queries. Nothing when neither the plan, the shaders nor the noise changed.
    fn prepare(&mut self, frame: &FrameInput<'_>, shaders: &Shaders) -> Result<(), Error> {
        let plan = frame.plan;
        let noise_changed = !self
            .noise
            .as_ref()
            .is_some_and(|n| Arc::ptr_eq(n, frame.noise));
        let plan_changed = self
            .state
            .as_ref()
            .is_none_or(|s| &s.plan != plan || &s.shaders != shaders);
        if !plan_changed && !noise_changed {
            return Ok(());
        }
        let info = &self.gpu.info;
        if plan.width.max(plan.height) > info.max_image_2d {
            return Err(Error::Size {
                width: plan.width,
                height: plan.height,
                max: info.max_image_2d,
                device: info.name.clone(),
            });
        }
        // Before allocating: the plan's images against the device's memory (an allocation
        // failing half-way would name one image, not what to do).
        let needed: u64 = plan.resources.iter().map(|r| r.image_bytes()).sum();
        if info.device_memory > 0 && needed > info.device_memory {
            let gib = |b: u64| b as f64 / f64::from(1u32 << 30);
            return Err(Error::TooLarge {
                width: plan.width,
                height: plan.height,
                needed_gib: gib(needed),
                heap_gib: gib(info.device_memory),
                device: info.name.clone(),
            });
        }
        if self.state.as_ref().is_some_and(|s| &s.shaders != shaders) {
            self.frames.forget_computed();
        }
        if plan_changed {
            self.drop_state();
        }
        if self.uniform.is_none() {
            let size = std::mem::size_of::<FrameUniforms>() as u64;
            self.uniform = Some(GpuBuffer::new(
                &self.gpu.device,
                &mut self.gpu.allocator,
                "frame",
                size,
                vk::BufferUsageFlags::UNIFORM_BUFFER,
                MemoryLocation::CpuToGpu,
            )?);
            self.created += 1;
        }

        // Resources: keep those whose signature is unchanged.
        let mut rebuilt = false;
        for r in &plan.resources {
            let want = Made::for_frame(r, frame.noise).map_err(Error::Shader)?;
            let keep = self
                .resources
                .get(&r.name)
                .is_some_and(|have| have.made.serves(&want));
            if keep {
                continue;
            }
            self.drop_resource(&r.name);
            let object = self.create_resource(&want)?;
            match &object {
                Object::Images(list) => {
                    for (half, image) in list.iter().enumerate() {
                        self.tracker
                            .add_image((r.name.clone(), half), image, Use::NEW);
                    }
                }
                Object::Buffer(b) => {
                    self.tracker
                        .add_buffer((r.name.clone(), 0), b.buffer, Use::NEW)
                }
                _ => {}
            }
            self.resources
                .insert(r.name.clone(), Resource { made: want, object });
            rebuilt = true;
            self.frames.created(r);
        }
        let stale: Vec<String> = self
            .resources
            .keys()
            .filter(|n| !plan.resources.iter().any(|r| &r.name == *n))
            .cloned()
            .collect();
        for name in stale {
            self.drop_resource(&name);
        }
        if rebuilt || noise_changed {
            self.upload(plan, frame.noise)?;
            self.noise = Some(frame.noise.clone());
        }
        if self.state.is_none() || rebuilt {
            self.drop_state();
            self.build_state(plan, shaders)?;
        }
        let queries = 2 * plan.passes.len() as u32;
        if self.has_timestamps() && self.query_count < queries {
            let device = &self.gpu.device;
            // SAFETY: idle (every frame is waited for); the old pool is no longer used.
            unsafe { device.destroy_query_pool(self.query_pool, None) };
            let info = vk::QueryPoolCreateInfo::default()
                .query_type(vk::QueryType::TIMESTAMP)
                .query_count(queries);
            // SAFETY: valid device and info.
            self.query_pool = unsafe { device.create_query_pool(&info, None) }
                .map_err(vk("vkCreateQueryPool"))?;
            self.query_count = queries;
            self.created += 1;
        }
        Ok(())
    }

    fn create_resource(&mut self, made: &Made) -> Result<Object, Error> {
        let r = &made.desc;
        let device = &self.gpu.device;
        let allocator = &mut *self.gpu.allocator;
        Ok(match r.kind {
            ResourceKind::Uniform => Object::Uniform,
            ResourceKind::Counters => {
                self.created += 1;
                Object::Buffer(GpuBuffer::new(
                    device,
                    allocator,
                    &r.name,
                    r.buffer_size().max(4),
                    vk::BufferUsageFlags::STORAGE_BUFFER
                        | vk::BufferUsageFlags::TRANSFER_DST
                        | vk::BufferUsageFlags::TRANSFER_SRC,
                    MemoryLocation::GpuOnly,
                )?)
            }
            ResourceKind::Sampler => {
                let s = r
                    .sampler
                    .ok_or_else(|| Error::Shader(format!("sampler `{}` has no state", r.name)))?;
                let info = sampler_info(s);
                self.created += 1;
                // SAFETY: valid device and info.
                Object::Sampler(
                    unsafe { device.create_sampler(&info, None) }.map_err(vk("vkCreateSampler"))?,
                )
            }
            ResourceKind::Texture => {
                let [width, height, depth] = made.size().map_err(Error::Shader)?;
                let f = r
                    .format
                    .ok_or_else(|| Error::Shader(format!("texture `{}` has no format", r.name)))?;
                let count = if r.lifetime == Lifetime::History {
                    2
                } else {
                    1
                };
                let mut list = Vec::new();
                for _ in 0..count {
                    list.push(GpuImage::new(
                        device,
                        allocator,
                        &r.name,
                        view_type(r.dimension),
                        vk_format(f),
                        vk::Extent3D {
                            width,
                            height,
                            depth,
                        },
                        image_needs(r.usage, f).0,
                    )?);
                    self.created += 2;
                }
                Object::Images(list)
            }
        })
    }

    /// Uploads every uploaded texture through one staging buffer, in one submission.
    fn upload(&mut self, plan: &FramePlan, noise: &NoiseSet) -> Result<(), Error> {
        let mut list = Vec::new();
        let mut size = 0u64;
        for r in plan.resources.iter().filter(|r| r.usage.upload) {
            let src = r.upload.as_deref().unwrap_or_default();
            let (_, data) = upload_data(src, noise)
                .map_err(|e| Error::Shader(format!("resource `{}`: {e}", r.name)))?;
            list.push((r.name.clone(), size, data));
            size += data.len() as u64;
        }
        if list.is_empty() {
            return Ok(());
        }
        let mut staging = GpuBuffer::new(
            &self.gpu.device,
            &mut self.gpu.allocator,
            "noise staging",
            size,
            vk::BufferUsageFlags::TRANSFER_SRC,
            MemoryLocation::CpuToGpu,
        )?;
        self.created += 1;
        let result = (|| {
            let mapped = staging.mapped()?;
            for (_, offset, data) in &list {
                let start = *offset as usize;
                mapped[start..start + data.len()].copy_from_slice(data);
            }
            self.begin()?;
            let cb = self.gpu.command_buffer;
            let wants: Vec<(Key, Use)> = list
                .iter()
                .map(|(n, _, _)| ((n.clone(), 0), Use::COPY_DST))
                .collect();
            let device = &self.gpu.device;
            self.tracker.barrier(device, cb, &wants);
            for (name, offset, _) in &list {
                let Some(Object::Images(images)) = self.resources.get(name).map(|r| &r.object)
                else {
                    continue;
                };
                let image = &images[0];
                let region = vk::BufferImageCopy::default()
                    .buffer_offset(*offset)
                    .image_subresource(COLOR_LAYER)
                    .image_extent(image.extent);
                // SAFETY: recording; the staging buffer lives until after the wait.
                unsafe {
                    device.cmd_copy_buffer_to_image(
                        cb,
                        staging.buffer,
                        image.image,
                        vk::ImageLayout::TRANSFER_DST_OPTIMAL,
                        &[region],
                    );
                }
            }
            self.submit_and_wait().map(|_| ())
        })();
        staging.destroy(&self.gpu.device, &mut self.gpu.allocator);
        result
    }

    /// Pipelines (cached), the descriptor pool and sets (one per pass, parity and group),
    /// and the framebuffers of raster passes.
    fn build_state(&mut self, plan: &FramePlan, shaders: &Shaders) -> Result<(), Error> {
        let mut keys = Vec::new();
        for (i, pass) in plan.passes.iter().enumerate() {
            keys.push(self.pipeline(plan, pass, supplied(shaders, plan, i))?);
        }
        let mut state = State {
            plan: plan.clone(),
            shaders: shaders.clone(),
            keys,
            pool: vk::DescriptorPool::null(),
            sets: Vec::new(),
            framebuffers: Vec::new(),
            nearest: vk::Sampler::null(),
            indices: None,
        };
        let result = self.build_sets(&mut state, shaders);
        let result = result.and_then(|()| self.build_framebuffers(&mut state));
        self.state = Some(state);
        result
    }

    fn build_sets(&mut self, state: &mut State, shaders: &Shaders) -> Result<(), Error> {
        let plan = &state.plan;
        let parities = if plan.has_history() { 2 } else { 1 };
        let device = &self.gpu.device;
        let per_pass = plan
            .passes
            .iter()
            .enumerate()
            .map(|(i, pass)| {
                let slots = supplied(shaders, plan, i).map(|s| &s.slots[..]);
                descriptors(plan, pass, slots)
            })
            .collect::<Result<Vec<_>, Error>>()?;
        if let Shaders::PerPass(_) = shaders {
            // For images that a supplied module reads through a combined image sampler but
            // that are not filterable (GLSL has no image without a sampler to load from).
            let info = sampler_info(stratus_graph::plan::SamplerDesc {
                filter: stratus_graph::desc::Filter::Nearest,
                address: stratus_graph::desc::AddressMode::Repeat,
            });
            // SAFETY: valid device and info.
            state.nearest =
                unsafe { device.create_sampler(&info, None) }.map_err(vk("vkCreateSampler"))?;
            self.created += 1;
            let words = per_pass
                .iter()
                .flatten()
                .filter_map(|d| match d.content {
                    Content::SamplerIndices(n) => Some(n),
                    _ => None,
                })
                .max()
                .unwrap_or(0);
            if words > 0 {
                let mut b = GpuBuffer::new(
                    device,
                    &mut self.gpu.allocator,
                    "sampler indices",
                    u64::from(words) * 4,
                    vk::BufferUsageFlags::STORAGE_BUFFER,
                    MemoryLocation::CpuToGpu,
                )?;
                b.mapped()?.fill(0);
                state.indices = Some(b);
                self.created += 1;
            }
        }
        for (i, list) in per_pass.iter().enumerate() {
            self.check_limits(&plan.passes[i], list)?;
        }
        let mut counts: HashMap<vk::DescriptorType, u32> = HashMap::new();
        let mut max_sets = 0;
        for (key, list) in state.keys.iter().zip(&per_pass) {
            for d in list {
                *counts.entry(d.ty).or_default() += d.count * parities;
            }
            max_sets += self.pipelines[key].set_layouts.len() as u32 * parities;
        }
        let sizes: Vec<vk::DescriptorPoolSize> = counts
            .iter()
            .map(|(&ty, &n)| vk::DescriptorPoolSize::default().ty(ty).descriptor_count(n))
            .collect();
        if max_sets > 0 && !sizes.is_empty() {
            let info = vk::DescriptorPoolCreateInfo::default()
                .max_sets(max_sets)
                .pool_sizes(&sizes);
            // SAFETY: valid device and info.
            state.pool = unsafe { device.create_descriptor_pool(&info, None) }
                .map_err(vk("vkCreateDescriptorPool"))?;
            self.created += 1;
        }
        let first_sampler = plan
            .resources
            .iter()
            .find_map(|r| match self.resources.get(&r.name).map(|g| &g.object) {
                Some(Object::Sampler(s)) => Some(*s),
                _ => None,
            })
            .unwrap_or_default();
        enum Info {
            Buffer(vk::DescriptorBufferInfo),
            Images(Vec<vk::DescriptorImageInfo>),
        }
        let buffer = |b: vk::Buffer| {
            Info::Buffer(
                vk::DescriptorBufferInfo::default()
                    .buffer(b)
                    .offset(0)
                    .range(vk::WHOLE_SIZE),
            )
        };
        let mut infos = Vec::new();
        for (i, (pass, list)) in plan.passes.iter().zip(&per_pass).enumerate() {
            let layouts = &self.pipelines[&state.keys[i]].set_layouts;
            let raster = matches!(pass.kind, PassKind::Raster { .. });
            let mut per_parity = Vec::new();
            for parity in 0..parities {
                if layouts.is_empty() {
                    per_parity.push(Vec::new());
                    continue;
                }
                let info = vk::DescriptorSetAllocateInfo::default()
                    .descriptor_pool(state.pool)
                    .set_layouts(layouts);
                // SAFETY: the pool has room for every set of the plan.
                let sets = unsafe { device.allocate_descriptor_sets(&info) }
                    .map_err(vk("vkAllocateDescriptorSets"))?;
                self.created += sets.len() as u64;
                for d in list {
                    let missing = |what: String| {
                        Error::Shader(format!(
                            "set {} binding {} of pass `{}` needs {what}, which the frame does not have",
                            d.set, d.binding, pass.name
                        ))
                    };
                    let image = |name: &str| -> Result<(vk::DescriptorImageInfo, bool), Error> {
                        // `name.previous`: the pair's resource; the binding picks the half.
                        let r = self
                            .resources
                            .get(name.strip_suffix(PREVIOUS).unwrap_or(name))
                            .ok_or_else(|| missing(format!("`{name}`")))?;
                        let Object::Images(images) = &r.object else {
                            return Err(missing(format!("image `{name}`")));
                        };
                        let b = d.plan.ok_or_else(|| missing(format!("`{name}`")))?;
                        let half = if r.made.desc.lifetime == Lifetime::History {
                            history_half(parity as u64, b.previous)
                        } else {
                            0
                        };
                        let layout = Use::of_binding(b, shader_stage(raster))
                            .ok_or_else(|| missing(format!("`{name}`")))?
                            .layout;
                        let filterable = r.made.desc.format.is_some_and(|f| f.filterable());
                        Ok((
                            vk::DescriptorImageInfo::default()
                                .image_view(images[half].view)
                                .image_layout(layout),
                            filterable,
                        ))
                    };
                    let info = match &d.content {
                        Content::Plan(name) => match self
                            .resources
                            .get(name.strip_suffix(PREVIOUS).unwrap_or(name))
                            .map(|r| &r.object)
                        {
                            Some(Object::Uniform) => {
                                buffer(self.uniform.as_ref().expect("created by prepare").buffer)
                            }
                            Some(Object::Buffer(b)) => buffer(b.buffer),
                            Some(Object::Sampler(s)) => {
                                Info::Images(vec![vk::DescriptorImageInfo::default().sampler(*s)])
                            }
                            Some(Object::Images(_)) => Info::Images(vec![image(name)?.0]),
                            None => return Err(missing(format!("`{name}`"))),
                        },
                        Content::CombinedWithSampler(name) => {
                            let (info, filterable) = image(name)?;
                            let sampler = if filterable {
                                first_sampler
                            } else {
                                state.nearest
                            };
                            Info::Images(vec![info.sampler(sampler)])
                        }
                        Content::SamplerArray(n) => Info::Images(vec![
                            vk::DescriptorImageInfo::default()
                                .sampler(first_sampler);
                            *n as usize
                        ]),
                        Content::SamplerIndices(_) => buffer(
                            state
                                .indices
                                .as_ref()
                                .ok_or_else(|| missing("a sampler index buffer".into()))?
                                .buffer,
                        ),
                    };
                    let set = *sets
                        .get(d.set as usize)
                        .ok_or_else(|| missing(format!("descriptor set {}", d.set)))?;
                    infos.push((set, d.binding, d.ty, info));
                }
                per_parity.push(sets);
            }
            state.sets.push(per_parity);
        }
        let writes: Vec<_> = infos
            .iter()
            .map(|(set, binding, ty, info)| {
                let write = vk::WriteDescriptorSet::default()
                    .dst_set(*set)
                    .dst_binding(*binding)
                    .descriptor_type(*ty);
                match info {
                    Info::Buffer(i) => write.buffer_info(std::slice::from_ref(i)),
                    Info::Images(i) => write.image_info(i),
                }
            })
            .collect();
        // SAFETY: every set, buffer, view and sampler is alive and matches its layout.
        unsafe { device.update_descriptor_sets(&writes, &[]) };
        Ok(())
    }

    fn build_framebuffers(&mut self, state: &mut State) -> Result<(), Error> {
        let plan = &state.plan;
        let parities = if plan.has_history() { 2 } else { 1 };
        for (i, pass) in plan.passes.iter().enumerate() {
            let PassKind::Raster { colors, depth, .. } = &pass.kind else {
                state.framebuffers.push(Vec::new());
                continue;
            };
            let mut list = Vec::new();
            for parity in 0..parities {
                let targets = colors
                    .iter()
                    .map(|c| c.resource)
                    .chain(depth.iter().map(|d| d.resource));
                let mut views = Vec::new();
                let mut extent = vk::Extent3D::default();
                for index in targets {
                    let image = self.target(plan, index, parity as u64)?;
                    views.push(image.view);
                    extent = image.extent;
                }
                let info = vk::FramebufferCreateInfo::default()
                    .render_pass(self.pipelines[&state.keys[i]].render_pass)
                    .attachments(&views)
                    .width(extent.width)
                    .height(extent.height)
                    .layers(1);
                // SAFETY: the render pass and views are alive and compatible.
                let fb = unsafe { self.gpu.device.create_framebuffer(&info, None) }
                    .map_err(vk("vkCreateFramebuffer"))?;
                self.created += 1;
                list.push(fb);
            }
            state.framebuffers.push(list);
        }
        Ok(())
    }

    /// The image of texture resource `index` a frame of this parity writes (the current half
    /// of a history pair).
    fn target(&self, plan: &FramePlan, index: usize, parity: u64) -> Result<&GpuImage, Error> {
        let r = &plan.resources[index];
        match self.resources.get(&r.name).map(|g| &g.object) {
            Some(Object::Images(images)) => {
                Ok(&images[history_half(parity, false).min(images.len() - 1)])
            }
            _ => Err(Error::Shader(format!("`{}` is not a texture", r.name))),
        }
    }

    /// The tracker key of texture resource `index` in this frame (which half of a history
    /// pair, `previous` or not).
    fn key(&self, plan: &FramePlan, index: usize, previous: bool) -> Key {
        let r = &plan.resources[index];
        let half = if r.lifetime == Lifetime::History {
            history_half(self.frames.frame(), previous)
        } else {
            0
        };
        (r.name.clone(), half)
    }

    /// Records pass `i`: barriers for what it binds and draws into, timestamps at `query`.
    fn record_pass(&mut self, plan: &FramePlan, i: usize, query: Option<u32>) -> Result<(), Error> {
        let state = self.state.as_ref().expect("prepared");
        let pass = &plan.passes[i];
        let raster = matches!(pass.kind, PassKind::Raster { .. });
        let mut wants: Vec<(Key, Use)> = pass
            .bindings
            .iter()
            .filter_map(|b| {
                Use::of_binding(b, shader_stage(raster))
                    .map(|u| (self.key(plan, b.resource, b.previous), u))
            })
            .collect();
        if let PassKind::Raster { colors, depth, .. } = &pass.kind {
            for c in colors {
                wants.push((self.key(plan, c.resource, false), Use::COLOR_TARGET));
            }
            if let Some(d) = depth {
                wants.push((self.key(plan, d.resource, false), Use::DEPTH_TARGET));
            }
        }
        let p = &self.pipelines[&state.keys[i]];
        let parity = if plan.has_history() {
            (self.frames.frame() % 2) as usize
        } else {
            0
        };
        let sets = &state.sets[i][parity];
        let device = &self.gpu.device;
        let cb = self.gpu.command_buffer;
        // SAFETY: `cb` is recording; every handle is alive (see render_inner).
        unsafe {
            self.tracker.barrier(device, cb, &wants);
            if let Some(q) = query {
                device.cmd_write_timestamp(cb, TIMESTAMP_STAGE, self.query_pool, q);
            }
            let bind_point = if raster {
                vk::PipelineBindPoint::GRAPHICS
            } else {
                vk::PipelineBindPoint::COMPUTE
            };
            match &pass.kind {
                PassKind::Compute { dispatch, .. } => {
                    device.cmd_bind_pipeline(cb, bind_point, p.pipeline);
                    if !sets.is_empty() {
                        device.cmd_bind_descriptor_sets(cb, bind_point, p.layout, 0, sets, &[]);
                    }
                    let [x, y, z] = *dispatch;
                    device.cmd_dispatch(cb, x, y, z);
                }
                PassKind::Raster {
                    vertices,
                    colors,
                    depth,
                    ..
                } => {
                    let [w, h] = pass.extent;
                    let mut clears: Vec<vk::ClearValue> = colors
                        .iter()
                        .map(|_| vk::ClearValue {
                            color: vk::ClearColorValue { float32: [0.0; 4] },
                        })
                        .collect();
                    if depth.is_some() {
                        clears.push(vk::ClearValue {
                            depth_stencil: vk::ClearDepthStencilValue {
                                depth: 1.0,
                                stencil: 0,
                            },
                        });
                    }
                    let area = vk::Rect2D {
                        offset: vk::Offset2D { x: 0, y: 0 },
                        extent: vk::Extent2D {
                            width: w,
                            height: h,
                        },
                    };
                    let begin = vk::RenderPassBeginInfo::default()
                        .render_pass(p.render_pass)
                        .framebuffer(state.framebuffers[i][parity])
                        .render_area(area)
                        .clear_values(&clears);
                    device.cmd_begin_render_pass(cb, &begin, vk::SubpassContents::INLINE);
                    device.cmd_bind_pipeline(cb, bind_point, p.pipeline);
                    if !sets.is_empty() {
                        device.cmd_bind_descriptor_sets(cb, bind_point, p.layout, 0, sets, &[]);
                    }
                    // A negative height gives WebGPU's y-up clip space, as wgpu does (the
                    // SPIR-V is written without naga's coordinate-space adjustment).
                    let viewport = vk::Viewport {
                        x: 0.0,
                        y: h as f32,
                        width: w as f32,
                        height: -(h as f32),
                        min_depth: 0.0,
                        max_depth: 1.0,
                    };
                    device.cmd_set_viewport(cb, 0, &[viewport]);
                    device.cmd_set_scissor(cb, 0, &[area]);
                    device.cmd_draw(cb, *vertices, 1, 0, 0);
                    device.cmd_end_render_pass(cb);
                }
            }
            if let Some(q) = query {
                device.cmd_write_timestamp(cb, TIMESTAMP_STAGE, self.query_pool, q + 1);
            }
        }
        Ok(())
    }

    /// Records the copies a frame's readback asks for into persistent host-visible buffers
    /// (rows tightly packed: Vulkan, unlike WebGPU, needs no 256-byte row alignment).
    fn copy_readbacks(&mut self, frame: &FrameInput<'_>) -> Result<Vec<(usize, Readout)>, Error> {
        let plan = frame.plan;
        let wanted = frame.readback.targets(plan).map_err(Error::Shader)?;
        if wanted.is_empty() {
            return Ok(Vec::new());
        }
        let mut out = Vec::new();
        let mut copies = Vec::new();
        for (i, readout) in wanted {
            let r = &plan.resources[i];
            let (size, key) = match self.resources.get(&r.name).map(|g| &g.object) {
                Some(Object::Buffer(b)) => (b.size, (r.name.clone(), 0)),
                Some(Object::Images(_)) => {
                    let image = self.target(plan, i, self.frames.frame())?;
                    let f = r
                        .format
                        .unwrap_or(stratus_graph::desc::TexelFormat::Rgba8Unorm);
                    let e = image.extent;
                    (
                        u64::from(e.width)
                            * u64::from(e.height)
                            * u64::from(e.depth)
                            * u64::from(f.texel_size()),
                        self.key(plan, i, false),
                    )
                }
                _ => {
                    return Err(Error::Shader(format!(
                        "readback of `{}`: it holds no data the host can read (checked by the plan)",
                        r.name
                    )));
                }
            };
            if self.readbacks.get(&r.name).is_none_or(|b| b.size != size) {
                if let Some(mut old) = self.readbacks.remove(&r.name) {
                    old.destroy(&self.gpu.device, &mut self.gpu.allocator);
                }
                let b = GpuBuffer::new(
                    &self.gpu.device,
                    &mut self.gpu.allocator,
                    "readback",
                    size,
                    vk::BufferUsageFlags::TRANSFER_DST,
                    MemoryLocation::GpuToCpu,
                )?;
                self.created += 1;
                self.readbacks.insert(r.name.clone(), b);
            }
            copies.push((i, key));
            out.push((i, readout));
        }
        let cb = self.gpu.command_buffer;
        let wants: Vec<(Key, Use)> = copies
            .iter()
            .map(|(i, key)| {
                let u = if plan.resources[*i].kind == ResourceKind::Texture {
                    Use::COPY_SRC
                } else {
                    Use {
                        layout: vk::ImageLayout::UNDEFINED,
                        ..Use::COPY_SRC
                    }
                };
                (key.clone(), u)
            })
            .collect();
        let device = &self.gpu.device;
        // SAFETY: recording; every handle is alive until after the wait.
        unsafe {
            self.tracker.barrier(device, cb, &wants);
            for (i, _) in &copies {
                let r = &plan.resources[*i];
                let dst = self.readbacks[&r.name].buffer;
                match self.resources.get(&r.name).map(|g| &g.object) {
                    Some(Object::Buffer(b)) => {
                        let region = vk::BufferCopy::default().size(b.size);
                        device.cmd_copy_buffer(cb, b.buffer, dst, &[region]);
                    }
                    _ => {
                        let image = self.target(plan, *i, self.frames.frame())?;
                        let region = vk::BufferImageCopy::default()
                            .image_subresource(vk::ImageSubresourceLayers {
                                aspect_mask: range(image.format).aspect_mask,
                                ..COLOR_LAYER
                            })
                            .image_extent(image.extent);
                        device.cmd_copy_image_to_buffer(
                            cb,
                            image.image,
                            vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
                            dst,
                            &[region],
                        );
                    }
                }
            }
            let to_host = vk::MemoryBarrier::default()
                .src_access_mask(vk::AccessFlags::TRANSFER_WRITE)
                .dst_access_mask(vk::AccessFlags::HOST_READ);
            device.cmd_pipeline_barrier(
                cb,
                vk::PipelineStageFlags::TRANSFER,
                vk::PipelineStageFlags::HOST,
                vk::DependencyFlags::empty(),
                &[to_host],
                &[],
                &[],
            );
        }
        Ok(out)
    }

    /// The time of every pass that ran, from the frame's timestamp queries (all complete:
    /// the caller waited for the fence).
    fn timestamps(&self, ran: &[&Pass]) -> Result<Vec<PassTiming>, Error> {
        let mut ticks = vec![0u64; 2 * ran.len()];
        if ticks.is_empty() {
            return Ok(Vec::new());
        }
        // SAFETY: the pool has at least one query per entry of `ticks`, all written and
        // complete.
        unsafe {
            self.gpu.device.get_query_pool_results(
                self.query_pool,
                0,
                &mut ticks,
                vk::QueryResultFlags::TYPE_64 | vk::QueryResultFlags::WAIT,
            )
        }
        .map_err(vk("vkGetQueryPoolResults"))?;
        Ok(timings_from_ticks(
            ran,
            &ticks,
            self.gpu.info.timestamp_period,
            self.gpu.info.timestamp_bits,
        ))
    }

    /// Resets and begins the renderer's command buffer.
    fn begin(&self) -> Result<(), Error> {
        let cb = self.gpu.command_buffer;
        let info = vk::CommandBufferBeginInfo::default()
            .flags(vk::CommandBufferUsageFlags::ONE_TIME_SUBMIT);
        // SAFETY: the buffer is not pending (every submit is waited for).
        unsafe {
            self.gpu
                .device
                .reset_command_buffer(cb, vk::CommandBufferResetFlags::empty())
                .map_err(vk("vkResetCommandBuffer"))?;
            self.gpu
                .device
                .begin_command_buffer(cb, &info)
                .map_err(vk("vkBeginCommandBuffer"))
        }
    }

    /// Ends the command buffer, submits it and waits for the fence. Returns the milliseconds
    /// spent waiting.
    fn submit_and_wait(&self) -> Result<f64, Error> {
        let gpu = &self.gpu;
        let cbs = [gpu.command_buffer];
        let submit = vk::SubmitInfo::default().command_buffers(&cbs);
        // SAFETY: the buffer is recording; the fence is not in use by another submit.
        unsafe {
            gpu.device
                .end_command_buffer(gpu.command_buffer)
                .map_err(vk("vkEndCommandBuffer"))?;
            gpu.device
                .reset_fences(&[gpu.fence])
                .map_err(vk("vkResetFences"))?;
            gpu.device
                .queue_submit(gpu.queue, &[submit], gpu.fence)
                .map_err(vk("vkQueueSubmit"))?;
            let t = Instant::now();
            gpu.device
                .wait_for_fences(&[gpu.fence], true, u64::MAX)
                .map_err(vk("vkWaitForFences"))?;
            Ok(t.elapsed().as_secs_f64() * 1e3)
        }
    }

    /// Fails with [`Error::Unsupported`] where the descriptors need more samplers per stage
    /// than the device allows, or index an array of samplers that the device cannot index:
    /// creating such a pipeline is invalid, and crashes some drivers (lavapipe).
    fn check_limits(&self, pass: &Pass, list: &[Descriptor<'_>]) -> Result<(), Error> {
        let info = &self.gpu.info;
        let unsupported = |reason: String| Error::Unsupported {
            device: info.name.clone(),
            pass: pass.name.clone(),
            reason,
        };
        let samplers: u32 = list
            .iter()
            .filter(|d| {
                matches!(
                    d.ty,
                    vk::DescriptorType::SAMPLER | vk::DescriptorType::COMBINED_IMAGE_SAMPLER
                )
            })
            .map(|d| d.count)
            .sum();
        if samplers > info.max_stage_samplers {
            return Err(unsupported(format!(
                "its layout has {samplers} samplers, more than the {} per shader stage the device allows (maxPerStageDescriptorSamplers)",
                info.max_stage_samplers
            )));
        }
        if !info.sampler_array_indexing
            && list
                .iter()
                .any(|d| matches!(d.content, Content::SamplerArray(n) if n > 1))
        {
            return Err(unsupported(
                "it indexes an array of samplers, and the device cannot (no shaderSampledImageArrayDynamicIndexing)".into(),
            ));
        }
        Ok(())
    }

    /// Creates (once per SPIR-V file and pass, or per supplied module) the shader module,
    /// the descriptor set layouts (from the plan's bindings or the module's slots) and the
    /// pipeline of a pass. Returns its key.
    fn pipeline(
        &mut self,
        plan: &FramePlan,
        pass: &Pass,
        shader: Option<&PassShader>,
    ) -> Result<PipelineKey, Error> {
        let spv = plan
            .modules
            .get(&pass.module)
            .map(|m| m.spv_file.clone())
            .ok_or_else(|| {
                Error::Shader(format!(
                    "pass `{}`: no variant of module `{}`",
                    pass.name, pass.module
                ))
            })?;
        let key = match shader {
            None => PipelineKey::Program {
                spv: spv.clone(),
                pass: pass.pipeline_name(),
            },
            Some(s) => {
                let mut h = std::collections::hash_map::DefaultHasher::new();
                s.hash(&mut h);
                pass.name.hash(&mut h);
                PipelineKey::Supplied(h.finish())
            }
        };
        if self.pipelines.contains_key(&key) {
            return Ok(key);
        }
        let list = descriptors(plan, pass, shader.map(|s| &s.slots[..]))?;
        self.check_limits(pass, &list)?;
        let colors: Vec<_>;
        let entries = match &pass.kind {
            PassKind::Compute { entry, .. } => {
                Entries::Compute(shader.map_or(entry.as_str(), |s| s.entry.as_str()))
            }
            PassKind::Raster {
                vertex,
                fragment,
                colors: targets,
                depth,
                ..
            } => {
                if shader.is_some() {
                    return Err(Error::Shader(format!(
                        "pass `{}`: supplied modules run compute passes only",
                        pass.name
                    )));
                }
                colors = targets
                    .iter()
                    .map(|c| {
                        let f = plan.resources[c.resource]
                            .format
                            .unwrap_or(stratus_graph::desc::TexelFormat::Rgba8Unorm);
                        (vk_format(f), c)
                    })
                    .collect();
                Entries::Raster {
                    vertex,
                    fragment,
                    targets: RasterTargets {
                        colors,
                        depth: depth.as_ref(),
                    },
                }
            }
        };
        let device = &self.gpu.device;
        let p = match shader {
            None => {
                let module = match self.modules.get(&spv) {
                    Some(&m) => m,
                    None => {
                        let words = self.program.spirv.get(&spv).ok_or_else(|| {
                            Error::Shader(format!(
                                "the program has no {spv}; run `cargo xtask build-shaders` and rebuild"
                            ))
                        })?;
                        let m = module_from_words(device, words)?;
                        self.created += 1;
                        self.modules.insert(spv.clone(), m);
                        m
                    }
                };
                PassPipeline::new(device, module, &entries, &list)?
            }
            Some(s) => {
                // The pipeline keeps what it needs; the module can go right away.
                let module = module_from_words(device, &s.spirv)?;
                let p = PassPipeline::new(device, module, &entries, &list);
                // SAFETY: only the pipeline creation used the module.
                unsafe { device.destroy_shader_module(module, None) };
                p?
            }
        };
        self.created += 3;
        self.pipelines.insert(key.clone(), p);
        Ok(key)
    }
}

/// The supplied module of pass `i`: supplied modules replace the compute passes, in order;
/// raster passes run the program's SPIR-V.
fn supplied<'s>(shaders: &'s Shaders, plan: &FramePlan, i: usize) -> Option<&'s PassShader> {
    let Shaders::PerPass(list) = shaders else {
        return None;
    };
    if !matches!(plan.passes[i].kind, PassKind::Compute { .. }) {
        return None;
    }
    let k = plan.passes[..i]
        .iter()
        .filter(|p| matches!(p.kind, PassKind::Compute { .. }))
        .count();
    list.get(k)
}

/// The pipeline stage of a pass's shaders.
fn shader_stage(raster: bool) -> vk::PipelineStageFlags {
    if raster {
        vk::PipelineStageFlags::VERTEX_SHADER | vk::PipelineStageFlags::FRAGMENT_SHADER
    } else {
        vk::PipelineStageFlags::COMPUTE_SHADER
    }
}

/// As backend-wgpu's: one mip level, the shared LOD clamp, no anisotropy.
fn sampler_info(s: stratus_graph::plan::SamplerDesc) -> vk::SamplerCreateInfo<'static> {
    use stratus_graph::desc::{AddressMode, Filter};
    let filter = match s.filter {
        Filter::Linear => vk::Filter::LINEAR,
        Filter::Nearest => vk::Filter::NEAREST,
    };
    let address = match s.address {
        AddressMode::Repeat => vk::SamplerAddressMode::REPEAT,
        AddressMode::ClampToEdge => vk::SamplerAddressMode::CLAMP_TO_EDGE,
    };
    let [min_lod, max_lod] = stratus_graph::plan::SamplerDesc::LOD_CLAMP;
    vk::SamplerCreateInfo::default()
        .mag_filter(filter)
        .min_filter(filter)
        .mipmap_mode(vk::SamplerMipmapMode::NEAREST)
        .address_mode_u(address)
        .address_mode_v(address)
        .address_mode_w(address)
        .min_lod(min_lod)
        .max_lod(max_lod)
}

/// Every image format the program's graph uses and the features its passes need of it, so a
/// device that lacks one is passed over when the device is chosen (not found out mid-frame).
fn format_needs(program: &Program) -> Result<Vec<FormatNeed>, Error> {
    let plan = FramePlan::new(program, &Requirements(Default::default()), 1, 1)
        .map_err(|e| Error::Shader(e.to_string()))?;
    Ok(plan
        .resources
        .iter()
        .filter_map(|r| {
            let f = r.format?;
            Some(FormatNeed {
                resource: r.name.clone(),
                format: f,
                vk_format: vk_format(f),
                features: image_needs(r.usage, f).1,
            })
        })
        .collect())
}

impl Backend for Renderer {
    fn describe(&self) -> String {
        format!("ash (Vulkan) on {}", self.adapter())
    }
    fn has_timestamps(&self) -> bool {
        Renderer::has_timestamps(self)
    }
    fn render(&mut self, frame: &FrameInput<'_>) -> Result<FrameOutput, BackendError> {
        Ok(Renderer::render(self, frame)?)
    }
    fn objects_created(&self) -> u64 {
        self.created
    }
    fn finish(self: Box<Self>) -> Result<(), BackendError> {
        Ok(Renderer::finish(*self)?)
    }
    fn validated(&self) -> bool {
        self.gpu.validation()
    }
}

impl Drop for Renderer {
    fn drop(&mut self) {
        self.teardown();
        // Drop cannot fail; say what the layer reported (leaks included) where it can be seen.
        if let Err(e) = self.gpu.check_messages() {
            eprintln!("stratus-backend-ash: {e}");
        }
    }
}

#[cfg(test)]
mod tests {
    //! Proof that validation is really on: a leaked object and a missing barrier must both
    //! be reported (otherwise the "no validation message" assertions elsewhere prove nothing).

    use super::*;

    #[test]
    fn a_leaked_object_fails_finish() {
        let renderer = Renderer::new(Options { validation: true }).expect("renderer");
        let info = vk::SamplerCreateInfo::default();
        // SAFETY: valid device; the sampler is leaked on purpose (destroyed with the device).
        unsafe { renderer.gpu.device.create_sampler(&info, None) }.expect("sampler");
        match renderer.finish() {
            Err(Error::Validation(messages)) => assert!(
                messages.iter().any(|m| m.contains("VkSampler")),
                "{messages:#?}"
            ),
            other => panic!("the leak went unnoticed: {other:?}"),
        }
    }

    #[test]
    fn a_missing_barrier_is_a_synchronization_error() {
        let mut renderer = Renderer::new(Options { validation: true }).expect("renderer");
        let mut buffer = GpuBuffer::new(
            &renderer.gpu.device,
            &mut renderer.gpu.allocator,
            "hazard",
            256,
            vk::BufferUsageFlags::TRANSFER_DST,
            MemoryLocation::GpuOnly,
        )
        .expect("buffer");
        renderer.begin().expect("begin");
        let cb = renderer.gpu.command_buffer;
        // SAFETY: recording; the buffer lives until after the wait. Two writes with no
        // barrier between them: a write-after-write hazard.
        unsafe {
            renderer
                .gpu
                .device
                .cmd_fill_buffer(cb, buffer.buffer, 0, vk::WHOLE_SIZE, 1);
            renderer
                .gpu
                .device
                .cmd_fill_buffer(cb, buffer.buffer, 0, vk::WHOLE_SIZE, 2);
        }
        renderer.submit_and_wait().expect("submit");
        buffer.destroy(&renderer.gpu.device, &mut renderer.gpu.allocator);
        match renderer.gpu.check_messages() {
            Err(Error::Validation(messages)) => assert!(
                messages
                    .iter()
                    .any(|m| m.contains("SYNC-HAZARD-WRITE-AFTER-WRITE")),
                "{messages:#?}"
            ),
            other => panic!("the hazard went unnoticed: {other:?}"),
        }
        renderer.finish().expect("clean teardown");
    }
}
