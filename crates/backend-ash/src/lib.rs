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
        FrameState, Made, Readout, cpu_wall_timings, history_half, timings_from_ticks, uploads,
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
    gpu::{Gpu, format_needs},
    interface::{Descriptor, SlotContent as Content, descriptors},
    pipeline::{PassPipeline, PipelineKey, State, shader_stage},
    resources::{
        GpuBuffer, Key, Object, Resource, Tracker, Use, image_needs, sampler_info, vk_format,
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
    /// The scene depth uploaded last.
    scene_depth: Option<Arc<stratus_graph::SceneDepth>>,
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
    /// [`Backend::lose_device`] was called: the next submission reports the loss.
    injected_loss: bool,
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
            scene_depth: None,
            query_pool: vk::QueryPool::null(),
            query_count: 0,
            readbacks: HashMap::new(),
            frames: FrameState::default(),
            created: 0,
            cpu_timing: false,
            torn_down: false,
            lost: None,
            injected_loss: false,
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
        stratus_graph::backend::check_scene_depth(frame, false).map_err(Error::Shader)?;
        // Other host data than uploaded last (the scene depth changes every frame it moves).
        let uploads_stale = frame.uploads_changed(self.noise.as_ref(), self.scene_depth.as_ref());
        let plan_changed = self
            .state
            .as_ref()
            .is_none_or(|s| &s.plan != plan || &s.shaders != shaders);
        if !plan_changed && !uploads_stale {
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
            let want = Made::for_frame(r, frame).map_err(Error::Shader)?;
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
        if rebuilt || uploads_stale {
            self.upload(frame, rebuilt || noise_changed)?;
            self.noise = Some(frame.noise.clone());
            self.scene_depth = frame.scene_depth.cloned();
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
    fn lose_device(&mut self) -> bool {
        self.injected_loss = true;
        true
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
