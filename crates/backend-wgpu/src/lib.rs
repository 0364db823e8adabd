//! Runs Stratus's frame graph on wgpu: on a device of its own (Vulkan first, GL on request),
//! or on an application's device, recording into the application's command encoder.
//!
//! The renderer is persistent. The first frame of a plan creates what the plan needs (resources
//! by name, a pipeline per pass and variant, bind groups, timestamp queries); later frames only
//! write the uniform block and record commands. A new plan (another size or variant) rebuilds
//! only the resources whose size, format or usage changed, and the pipelines it lacks. Noise is
//! uploaded when a different `Arc<NoiseSet>` arrives. History resources ping-pong: frame N's
//! `name.previous` is what frame N-1 wrote as `name`.
//!
//! The steps mirror the ash backend's: the same plan, the same order, the same shared helpers
//! from `stratus-graph`. wgpu compiles the composed WGSL itself with exactly the plan's
//! override values, so it runs the code the committed SPIR-V (which ash loads) holds.

#![deny(missing_docs)]

mod convert;

use std::{
    collections::HashMap,
    sync::{Arc, Mutex},
    time::Instant,
};

use stratus_graph::{
    Backend, BackendError, FrameInput, FrameOutput, FramePlan, Program,
    backend::{
        DeviceClass, FrameState, Made, Readout, best_device, cpu_wall_timings, describe_device,
        history_half, timings_from_ticks, upload_data,
    },
    desc::{Lifetime, ResourceKind},
    plan::PassKind,
};
use stratus_noise::NoiseSet;
use stratus_scene::FrameUniforms;

/// Which graphics API wgpu runs on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Api {
    /// Vulkan (lavapipe on machines without a GPU).
    Vulkan,
    /// OpenGL ES through EGL (llvmpipe on machines without a GPU).
    Gl,
}

/// How to create the renderer.
#[derive(Clone, Copy, Debug)]
pub struct Options {
    /// The API to run on.
    pub api: Api,
    /// Turn on wgpu's validation (and the Vulkan validation layer where installed). wgpu's
    /// DEBUG flag stays off: Debian's validation layer misreads the WGSL debug info it adds.
    pub validation: bool,
}

/// Everything that can go wrong, each with a sentence a user can act on.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// No adapter for the API.
    #[error("no {api:?} adapter found by wgpu{hint}")]
    NoAdapter {
        /// The API asked for.
        api: Api,
        /// What to install.
        hint: &'static str,
    },
    /// Device creation failed.
    #[error("could not create a wgpu device on {adapter}: {message}")]
    Device {
        /// The adapter.
        adapter: String,
        /// wgpu's message.
        message: String,
    },
    /// The adapter has no compute shaders (NVIDIA's EGL gives wgpu such a GL context).
    #[error(
        "could not create a wgpu device on {adapter}: it has no compute shaders, which every Stratus frame needs (GL needs 4.3 or GLES 3.1; use the Vulkan backend)"
    )]
    NoCompute {
        /// The adapter.
        adapter: String,
    },
    /// wgpu reported a validation or out-of-memory error.
    #[error("wgpu reported an error: {0}")]
    Wgpu(String),
    /// The shaders, graph or plan are unusable, or a frame asks for what the plan lacks.
    #[error("{0}")]
    Shader(String),
    /// The frame needs more than the device allows (found before allocating anything).
    #[error("{0}")]
    Limit(String),
    /// The device was lost: a GPU hang or driver reset, or the device destroyed. Nothing more
    /// can run on it; a new renderer (on a new device) can.
    #[error(
        "the wgpu device {adapter} was lost ({reason}); nothing more can render on it: create a new renderer (a GPU hang or a driver reset loses a device)"
    )]
    DeviceLost {
        /// The adapter, in words.
        adapter: String,
        /// wgpu's reason and message.
        reason: String,
    },
    /// Validation was asked for, but the Vulkan validation layer is not installed (wgpu would
    /// go on without it, silently validating less).
    #[error(
        "Vulkan validation was requested but the layer VK_LAYER_KHRONOS_validation is not installed; install it with `apt-get install vulkan-validationlayers` or turn validation off"
    )]
    NoValidationLayer,
}

/// A pipeline of one pass of one variant, with its bind group layout.
struct Pipeline {
    layout: wgpu::BindGroupLayout,
    kind: PipelineKind,
}

enum PipelineKind {
    Compute(wgpu::ComputePipeline),
    Raster(wgpu::RenderPipeline),
}

/// Module, variant, pass, and the formats of its colour targets (an external target may
/// differ from the graph's).
type PipelineKey = (String, String, String, Vec<wgpu::TextureFormat>);

/// The GPU side of a resource of the plan.
struct Resource {
    /// What it was made from (kept while it serves the plan).
    made: Made,
    object: Object,
}

enum Object {
    Buffer(wgpu::Buffer),
    /// One texture, or two for a history pair.
    Textures(Vec<(wgpu::Texture, wgpu::TextureView)>),
    Sampler(wgpu::Sampler),
}

/// Timestamp queries and the buffers their results travel through.
struct Queries {
    set: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    read: wgpu::Buffer,
    count: u32,
}

/// A wgpu device ready to render frames of Stratus's frame graph.
pub struct Renderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    description: String,
    timestamps: bool,
    program: Arc<Program>,
    modules: HashMap<String, wgpu::ShaderModule>,
    pipelines: HashMap<PipelineKey, Pipeline>,
    resources: HashMap<String, Resource>,
    /// The plan the bind groups were built for.
    plan: Option<FramePlan>,
    /// Per pass of `plan`, one bind group per history parity.
    groups: Vec<Vec<wgpu::BindGroup>>,
    /// Per pass of `plan`, its pipeline's key (with the graph's own target formats), made
    /// once per plan so that recording a frame builds no key.
    keys: Vec<PipelineKey>,
    uniform: Option<wgpu::Buffer>,
    noise: Option<Arc<NoiseSet>>,
    /// Frame count, history validity, computed persistent resources (the shared rules).
    frames: FrameState,
    queries: Option<Queries>,
    readbacks: HashMap<String, wgpu::Buffer>,
    /// Uncaptured errors, where the renderer owns the device (an application keeps its own
    /// handler).
    errors: Option<Arc<Mutex<Vec<String>>>>,
    /// Why the device was lost, once it is, where the renderer owns the device (an application
    /// keeps its own callback; its errors then say "lost" instead).
    lost: Arc<Mutex<Option<String>>>,
    /// Whether the renderer's own instance has validation on.
    validation: bool,
    created: u64,
}

impl Renderer {
    /// Picks an adapter for `options.api` (a real GPU before a CPU driver), creates a device of
    /// its own, and runs the embedded shaders.
    pub fn new(options: Options) -> Result<Self, Error> {
        let program = Program::embedded().map_err(|e| Error::Shader(e.to_string()))?;
        Self::with_program(options, program)
    }

    /// As [`Renderer::new`], running `program` (a test's own graph and shaders).
    pub fn with_program(options: Options, program: Arc<Program>) -> Result<Self, Error> {
        let backends = match options.api {
            Api::Vulkan => wgpu::Backends::VULKAN,
            Api::Gl => wgpu::Backends::GL,
        };
        // wgpu goes on without the layer when it is missing; a caller who asked for
        // validation is told instead, as backend-ash tells it.
        if options.validation && options.api == Api::Vulkan && !validation_layer_installed() {
            return Err(Error::NoValidationLayer);
        }
        let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
        desc.backends = backends;
        desc.flags = if options.validation {
            wgpu::InstanceFlags::VALIDATION
        } else {
            wgpu::InstanceFlags::empty()
        };
        let instance = wgpu::Instance::new(desc);
        let mut adapters = pollster::block_on(instance.enumerate_adapters(backends));
        let classes: Vec<DeviceClass> = adapters
            .iter()
            .map(|a| class_of(a.get_info().device_type))
            .collect();
        let adapter = best_device(&classes)
            .map(|i| adapters.swap_remove(i))
            .ok_or(Error::NoAdapter {
                api: options.api,
                hint: match options.api {
                    Api::Vulkan => {
                        " (install a Vulkan driver: `apt-get install mesa-vulkan-drivers libvulkan1` gives lavapipe)"
                    }
                    Api::Gl => {
                        " (install EGL and a GL driver: `apt-get install libegl1 libgl1-mesa-dri`)"
                    }
                },
            })?;
        let info = adapter.get_info();
        // Every frame is compute passes: a device without them (NVIDIA's EGL gives wgpu a GL
        // context without compute shaders) is refused here, by name, so that `auto` moves on.
        if !adapter
            .get_downlevel_capabilities()
            .flags
            .contains(wgpu::DownlevelFlags::COMPUTE_SHADERS)
        {
            return Err(Error::NoCompute {
                adapter: describe(&info),
            });
        }
        let mut required_features = wgpu::Features::empty();
        if adapter.features().contains(wgpu::Features::TIMESTAMP_QUERY) {
            required_features |= wgpu::Features::TIMESTAMP_QUERY;
        }
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("stratus"),
            required_features,
            required_limits: adapter.limits(),
            ..Default::default()
        }))
        .map_err(|e| Error::Device {
            adapter: describe(&info),
            message: e.to_string(),
        })?;
        let errors = Arc::new(Mutex::new(Vec::new()));
        let sink = errors.clone();
        device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
            sink.lock()
                .unwrap_or_else(|e| e.into_inner())
                .push(e.to_string());
        }));
        let lost = Arc::new(Mutex::new(None));
        let lost_sink = lost.clone();
        device.set_device_lost_callback(move |reason, message| {
            *lost_sink.lock().unwrap_or_else(|e| e.into_inner()) =
                Some(format!("{reason:?}: {message}"));
        });
        let mut renderer = Self::build(device, queue, describe(&info), program);
        renderer.errors = Some(errors);
        renderer.lost = lost;
        renderer.validation = options.validation;
        renderer.check_errors()?;
        Ok(renderer)
    }

    /// A renderer on an application's device and queue (the application keeps them, its own
    /// error handler and its device-lost callback: a lost device then shows as a failed
    /// read-back that says the device may be lost). Passes are timed where the device has
    /// `TIMESTAMP_QUERY`.
    pub fn from_device(
        device: wgpu::Device,
        queue: wgpu::Queue,
        program: Arc<Program>,
    ) -> Result<Self, Error> {
        Ok(Self::build(
            device,
            queue,
            "the application's wgpu device".into(),
            program,
        ))
    }

    fn build(
        device: wgpu::Device,
        queue: wgpu::Queue,
        description: String,
        program: Arc<Program>,
    ) -> Self {
        let timestamps = device.features().contains(wgpu::Features::TIMESTAMP_QUERY);
        Self {
            device,
            queue,
            description,
            timestamps,
            program,
            modules: HashMap::new(),
            pipelines: HashMap::new(),
            resources: HashMap::new(),
            plan: None,
            groups: Vec::new(),
            keys: Vec::new(),
            uniform: None,
            noise: None,
            frames: FrameState::default(),
            queries: None,
            readbacks: HashMap::new(),
            errors: None,
            lost: Arc::new(Mutex::new(None)),
            validation: false,
            created: 0,
        }
    }

    /// The device the renderer runs on (its own, or the application's).
    pub fn device(&self) -> &wgpu::Device {
        &self.device
    }

    /// The adapter in words, e.g. `llvmpipe (LLVM 15.0.6, 256 bits) (Vulkan, Cpu)`.
    pub fn adapter(&self) -> String {
        self.description.clone()
    }

    /// Whether passes are timed with GPU timestamp queries (else by CPU wall time).
    pub fn has_timestamps(&self) -> bool {
        self.timestamps
    }

    /// Times every pass by submitting it alone and waiting for it on the CPU (`cpu-wall`),
    /// as devices without timestamp queries do (as backend-ash's). On lavapipe a raster pass's
    /// timestamps, and those of every pass after it on the device, are not exact.
    pub fn set_cpu_wall_timing(&mut self, on: bool) {
        self.timestamps = !on
            && self
                .device
                .features()
                .contains(wgpu::Features::TIMESTAMP_QUERY);
    }

    /// GPU objects this renderer has created so far.
    pub fn objects_created(&self) -> u64 {
        self.created
    }

    /// The program the renderer runs.
    pub fn program(&self) -> &Arc<Program> {
        &self.program
    }

    fn check_errors(&self) -> Result<(), Error> {
        self.check_lost()?;
        let Some(errors) = &self.errors else {
            return Ok(());
        };
        let errors = std::mem::take(&mut *errors.lock().unwrap_or_else(|e| e.into_inner()));
        if errors.is_empty() {
            Ok(())
        } else {
            Err(self.classify(errors.join("\n")))
        }
    }

    /// [`Error::DeviceLost`] once the device is lost.
    fn check_lost(&self) -> Result<(), Error> {
        match &*self.lost.lock().unwrap_or_else(|e| e.into_inner()) {
            Some(reason) => Err(Error::DeviceLost {
                adapter: self.description.clone(),
                reason: reason.clone(),
            }),
            None => Ok(()),
        }
    }

    /// A wgpu error message as an [`Error`]: the device's loss once our callback has seen it
    /// (wgpu reports a loss through the callback alone, never through its errors), else the
    /// message.
    fn classify(&self, message: String) -> Error {
        if let Err(lost) = self.check_lost() {
            return lost;
        }
        Error::Wgpu(message)
    }

    /// Renders one frame on the renderer's queue, waits for it, and reads back what
    /// `frame.readback` asks for. Without timestamp queries every pass is submitted alone and
    /// timed on the CPU.
    pub fn render(&mut self, frame: &FrameInput<'_>) -> Result<FrameOutput, Error> {
        self.check_lost()?;
        let scope = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let result = self.render_inner(frame);
        let scoped = pollster::block_on(scope.pop());
        self.check_errors()?;
        if let Some(e) = scoped {
            return Err(self.classify(e.to_string()));
        }
        result.map_err(|e| match e {
            Error::Wgpu(m) => self.classify(m),
            other => other,
        })
    }

    /// Records one frame into the application's `encoder`, drawing passes whose colour target
    /// is an external resource (the graph's `display`) into `target` where one is given. The
    /// application submits; [`Renderer::last_timings`] reads the pass times after that.
    pub fn record(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameInput<'_>,
        target: Option<&wgpu::TextureView>,
    ) -> Result<Vec<String>, Error> {
        self.check_lost()?;
        let scope = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let result = self.record_frame(encoder, frame, target);
        let scoped = pollster::block_on(scope.pop());
        if let Some(e) = scoped {
            return Err(self.classify(e.to_string()));
        }
        result
    }

    /// The GPU time of every pass of the last recorded frame, once the application has
    /// submitted it (this waits for the GPU). Empty without timestamp queries.
    pub fn last_timings(
        &mut self,
        passes: &[String],
    ) -> Result<Vec<stratus_graph::PassTiming>, Error> {
        let Some(plan) = &self.plan else {
            return Ok(Vec::new());
        };
        if !self.timestamps || passes.is_empty() {
            return Ok(Vec::new());
        }
        let ran: Vec<&stratus_graph::plan::Pass> = plan
            .passes
            .iter()
            .filter(|p| passes.contains(&p.name))
            .collect();
        let q = self
            .queries
            .as_ref()
            .expect("queries exist with timestamps");
        let bytes = read_buffer(&self.device, &q.read, None)?;
        let ticks: Vec<u64> = bytes
            .chunks_exact(8)
            .map(|c| u64::from_le_bytes(c.try_into().expect("8 bytes")))
            .collect();
        let period_ns = f64::from(self.queue.get_timestamp_period());
        Ok(timings_from_ticks(&ran, &ticks, period_ns, 64))
    }

    fn record_frame(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameInput<'_>,
        target: Option<&wgpu::TextureView>,
    ) -> Result<Vec<String>, Error> {
        let target_format = target.map(|t| t.texture().format());
        self.prepare(frame, target_format)?;
        let plan = frame.plan;
        let run = self.frames.passes(frame);
        let uniforms = self.begin_frame(encoder, frame);
        for (k, &i) in run.iter().enumerate() {
            self.record_pass(encoder, i, Some(k as u32), target, target_format)?;
        }
        self.resolve_queries(encoder, run.len() as u32);
        self.frames.finished(frame, &run, &uniforms);
        Ok(run.iter().map(|&i| plan.passes[i].name.clone()).collect())
    }

    fn render_inner(&mut self, frame: &FrameInput<'_>) -> Result<FrameOutput, Error> {
        let t0 = Instant::now();
        self.prepare(frame, None)?;
        let plan = frame.plan;
        let indices = self.frames.passes(frame);
        let run: Vec<&stratus_graph::plan::Pass> =
            indices.iter().map(|&i| &plan.passes[i]).collect();
        let mut encoder = self.device.create_command_encoder(&Default::default());
        let uniforms = self.begin_frame(&mut encoder, frame);
        let mut wall = Vec::new();
        // CPU time of recording and submitting: the waits of the CPU-wall fallback excluded.
        let mut waited = 0.0;
        if self.timestamps {
            for (k, &i) in indices.iter().enumerate() {
                self.record_pass(&mut encoder, i, Some(k as u32), None, None)?;
            }
            self.resolve_queries(&mut encoder, indices.len() as u32);
        } else {
            // No timestamps: submit every pass alone and time it on the CPU.
            for &i in &indices {
                self.queue.submit([encoder.finish()]);
                let t = Instant::now();
                self.wait()?;
                waited += t.elapsed().as_secs_f64() * 1e3;
                let t = Instant::now();
                encoder = self.device.create_command_encoder(&Default::default());
                self.record_pass(&mut encoder, i, None, None, None)?;
                self.queue.submit([encoder.finish()]);
                self.wait()?;
                let ms = t.elapsed().as_secs_f64() * 1e3;
                wall.push(ms);
                waited += ms;
                encoder = self.device.create_command_encoder(&Default::default());
            }
        }
        let copies = self.copy_readbacks(&mut encoder, frame)?;
        self.queue.submit([encoder.finish()]);
        let cpu_ms = t0.elapsed().as_secs_f64() * 1e3 - waited;
        self.frames.finished(frame, &indices, &uniforms);
        self.wait()?;

        let mut out = FrameOutput {
            width: plan.width,
            height: plan.height,
            cpu_ms,
            device: self.adapter(),
            ..Default::default()
        };
        for Copied {
            index,
            readout,
            rows,
        } in copies
        {
            let name = &plan.resources[index].name;
            let bytes = read_buffer(&self.device, &self.readbacks[name], rows)?;
            out.store(plan, index, readout, bytes);
        }
        out.timings = if self.timestamps {
            let q = self
                .queries
                .as_ref()
                .expect("queries exist with timestamps");
            let bytes = read_buffer(&self.device, &q.read, None)?;
            let ticks: Vec<u64> = bytemuck::pod_collect_to_vec(&bytes);
            let period_ns = f64::from(self.queue.get_timestamp_period());
            timings_from_ticks(&run, &ticks, period_ns, 64)
        } else {
            cpu_wall_timings(&run, &wall)
        };
        Ok(out)
    }

    fn wait(&self) -> Result<(), Error> {
        poll(&self.device)?;
        self.check_lost()
    }

    /// Writes the uniforms and clears the counters of a counting frame; returns the uniforms.
    fn begin_frame(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameInput<'_>,
    ) -> FrameUniforms {
        let uniforms: FrameUniforms = self.frames.uniforms(frame);
        if let Some(u) = &self.uniform {
            self.queue.write_buffer(u, 0, bytemuck::bytes_of(&uniforms));
        }
        if frame.plan.stats {
            for r in self.resources.values() {
                if let (ResourceKind::Counters, Object::Buffer(b)) = (r.made.desc.kind, &r.object) {
                    encoder.clear_buffer(b, 0, None);
                }
            }
        }
        uniforms
    }

    /// Creates or updates what `frame` needs: resources, pipelines, bind groups, uploads.
    fn prepare(
        &mut self,
        frame: &FrameInput<'_>,
        target_format: Option<wgpu::TextureFormat>,
    ) -> Result<(), Error> {
        let plan = frame.plan;
        if self.plan.as_ref() != Some(plan) {
            self.check_limits(plan)?;
        }
        let noise_changed = !self
            .noise
            .as_ref()
            .is_some_and(|n| Arc::ptr_eq(n, frame.noise));
        let plan_changed = self.plan.as_ref() != Some(plan);
        if !plan_changed && !noise_changed {
            if let Some(format) = target_format {
                // Another external target format needs its own raster pipelines.
                for (i, pass) in plan.passes.iter().enumerate() {
                    if matches!(pass.kind, PassKind::Raster { .. }) {
                        self.pipeline(plan, i, Some(format))?;
                    }
                }
            }
            return Ok(());
        }
        if plan_changed {
            self.groups.clear();
            self.plan = None;
            if self.uniform.is_none() {
                self.uniform = Some(self.device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("frame"),
                    size: std::mem::size_of::<FrameUniforms>() as u64,
                    usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                }));
                self.created += 1;
            }
        }
        let mut rebuilt = false;
        for r in &plan.resources {
            let want = Made::for_frame(r, frame.noise).map_err(Error::Shader)?;
            let keep = self
                .resources
                .get(&r.name)
                .is_some_and(|have| have.made.serves(&want));
            if !keep {
                let object = self.create_resource(&want)?;
                self.resources
                    .insert(r.name.clone(), Resource { made: want, object });
                rebuilt = true;
                self.frames.created(r);
            }
        }
        self.resources
            .retain(|name, _| plan.resources.iter().any(|r| &r.name == name));
        if rebuilt || noise_changed {
            for r in plan.resources.iter().filter(|r| r.usage.upload) {
                let src = r.upload.as_deref().unwrap_or_default();
                let (size, data) = upload_data(src, frame.noise)
                    .map_err(|e| Error::Shader(format!("resource `{}`: {e}", r.name)))?;
                let Object::Textures(t) = &self.resources[&r.name].object else {
                    continue;
                };
                self.queue.write_texture(
                    t[0].0.as_image_copy(),
                    data,
                    wgpu::TexelCopyBufferLayout {
                        offset: 0,
                        bytes_per_row: Some(size[0] * 4),
                        rows_per_image: Some(size[1]),
                    },
                    extent3d(size),
                );
            }
            self.noise = Some(frame.noise.clone());
        }
        if plan_changed || rebuilt {
            for i in 0..plan.passes.len() {
                self.pipeline(plan, i, None)?;
                if let Some(format) = target_format {
                    self.pipeline(plan, i, Some(format))?;
                }
            }
            self.keys = (0..plan.passes.len())
                .map(|i| Self::pipeline_key(plan, i, None))
                .collect();
            self.build_groups(plan)?;
            self.ensure_queries(2 * plan.passes.len() as u32);
            self.plan = Some(plan.clone());
        }
        Ok(())
    }

    fn create_resource(&mut self, made: &Made) -> Result<Object, Error> {
        let r = &made.desc;
        Ok(match r.kind {
            ResourceKind::Uniform => {
                // The one uniform block, created with the renderer's first plan.
                Object::Buffer(self.uniform.clone().expect("created before resources"))
            }
            ResourceKind::Counters => {
                self.created += 1;
                Object::Buffer(self.device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some(&r.name),
                    size: r.buffer_size().max(4),
                    usage: wgpu::BufferUsages::STORAGE
                        | wgpu::BufferUsages::COPY_SRC
                        | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                }))
            }
            ResourceKind::Sampler => {
                self.created += 1;
                let s = r
                    .sampler
                    .ok_or_else(|| Error::Shader(format!("sampler `{}` has no state", r.name)))?;
                Object::Sampler(self.device.create_sampler(&convert::sampler(s)))
            }
            ResourceKind::Texture => {
                let size = made.size().map_err(Error::Shader)?;
                let f = r
                    .format
                    .ok_or_else(|| Error::Shader(format!("texture `{}` has no format", r.name)))?;
                let (dimension, view_dimension) = convert::dimension(r.dimension);
                let count = if r.lifetime == Lifetime::History {
                    2
                } else {
                    1
                };
                let mut list = Vec::new();
                for half in 0..count {
                    let label = if count == 2 {
                        format!("{}[{half}]", r.name)
                    } else {
                        r.name.clone()
                    };
                    let texture = self.device.create_texture(&wgpu::TextureDescriptor {
                        label: Some(&label),
                        size: extent3d(size),
                        mip_level_count: 1,
                        sample_count: 1,
                        dimension,
                        format: convert::format(f),
                        usage: convert::texture_usage(r.usage, f),
                        view_formats: &[],
                    });
                    let view = texture.create_view(&wgpu::TextureViewDescriptor {
                        dimension: Some(view_dimension),
                        ..Default::default()
                    });
                    self.created += 2;
                    list.push((texture, view));
                }
                Object::Textures(list)
            }
        })
    }

    fn ensure_queries(&mut self, count: u32) {
        if !self.timestamps || count == 0 || self.queries.as_ref().is_some_and(|q| q.count >= count)
        {
            return;
        }
        let size = u64::from(count) * 8;
        let set = self.device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("pass times"),
            ty: wgpu::QueryType::Timestamp,
            count,
        });
        let resolve = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("timestamps"),
            size,
            usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let read = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("timestamps readback"),
            size,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        self.created += 3;
        self.queries = Some(Queries {
            set,
            resolve,
            read,
            count,
        });
    }

    fn resolve_queries(&self, encoder: &mut wgpu::CommandEncoder, passes: u32) {
        if let Some(q) = &self.queries
            && passes > 0
        {
            let n = 2 * passes;
            encoder.resolve_query_set(&q.set, 0..n, &q.resolve, 0);
            encoder.copy_buffer_to_buffer(&q.resolve, 0, &q.read, 0, u64::from(n) * 8);
        }
    }

    /// The shader module of a WGSL module (created once).
    fn module(&mut self, name: &str) -> Result<wgpu::ShaderModule, Error> {
        if let Some(m) = self.modules.get(name) {
            return Ok(m.clone());
        }
        let source = self
            .program
            .wgsl
            .get(name)
            .ok_or_else(|| Error::Shader(format!("the program has no WGSL module `{name}`")))?;
        let m = self
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(name),
                source: wgpu::ShaderSource::Wgsl(source.clone().into()),
            });
        self.created += 1;
        self.modules.insert(name.into(), m.clone());
        Ok(m)
    }

    fn pipeline_key(
        plan: &FramePlan,
        i: usize,
        target: Option<wgpu::TextureFormat>,
    ) -> PipelineKey {
        let pass = &plan.passes[i];
        let variant = plan
            .modules
            .get(&pass.module)
            .map(|m| m.variant.clone())
            .unwrap_or_default();
        let formats = match &pass.kind {
            PassKind::Compute { .. } => Vec::new(),
            PassKind::Raster { colors, .. } => colors
                .iter()
                .map(|c| {
                    let r = &plan.resources[c.resource];
                    match target {
                        Some(f) if r.external => f,
                        _ => convert::format(
                            r.format
                                .unwrap_or(stratus_graph::desc::TexelFormat::Rgba8Unorm),
                        ),
                    }
                })
                .collect(),
        };
        (pass.module.clone(), variant, pass.pipeline_name(), formats)
    }

    /// Creates (once per module variant, pass and target formats) a pass's pipeline.
    fn pipeline(
        &mut self,
        plan: &FramePlan,
        i: usize,
        target: Option<wgpu::TextureFormat>,
    ) -> Result<(), Error> {
        let key = Self::pipeline_key(plan, i, target);
        if self.pipelines.contains_key(&key) {
            return Ok(());
        }
        let pass = &plan.passes[i];
        let module = self.module(&pass.module)?;
        let visibility = match pass.kind {
            PassKind::Compute { .. } => wgpu::ShaderStages::COMPUTE,
            PassKind::Raster { .. } => wgpu::ShaderStages::VERTEX_FRAGMENT,
        };
        if let Some(b) = pass.bindings.iter().find(|b| b.group != 0) {
            return Err(Error::Shader(format!(
                "pass `{}`: `{}` is in @group({}); the backends bind group 0 only",
                pass.name, b.info.name, b.group
            )));
        }
        let entries: Vec<_> = pass
            .bindings
            .iter()
            .map(|b| wgpu::BindGroupLayoutEntry {
                binding: b.binding,
                visibility,
                ty: convert::binding_type(b, plan),
                count: None,
            })
            .collect();
        // A pipeline for another target format shares the pass's bind group layout, so the
        // pass's bind groups serve both.
        let base = Self::pipeline_key(plan, i, None);
        let layout = match self.pipelines.get(&base) {
            Some(p) if base != key => p.layout.clone(),
            _ => self
                .device
                .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                    label: Some(&pass.name),
                    entries: &entries,
                }),
        };
        let pipeline_layout = self
            .device
            .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(&pass.name),
                bind_group_layouts: &[Some(&layout)],
                immediate_size: 0,
            });
        // Exactly the variant's override values, so wgpu runs the code the SPIR-V holds.
        let overrides = plan.modules.get(&pass.module).map(|m| &m.overrides);
        let constants: Vec<(&str, f64)> = overrides
            .into_iter()
            .flatten()
            .map(|(k, v)| (k.as_str(), *v))
            .collect();
        let options = || wgpu::PipelineCompilationOptions {
            constants: &constants,
            zero_initialize_workgroup_memory: true,
        };
        let kind = match &pass.kind {
            PassKind::Compute { entry, .. } => PipelineKind::Compute(
                self.device
                    .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                        label: Some(&pass.name),
                        layout: Some(&pipeline_layout),
                        module: &module,
                        entry_point: Some(entry),
                        compilation_options: options(),
                        cache: None,
                    }),
            ),
            PassKind::Raster {
                vertex,
                fragment,
                colors,
                depth,
                ..
            } => {
                let targets: Vec<Option<wgpu::ColorTargetState>> = colors
                    .iter()
                    .zip(&key.3)
                    .map(|(c, &format)| {
                        Some(wgpu::ColorTargetState {
                            format,
                            blend: convert::blend(c.blend),
                            write_mask: wgpu::ColorWrites::ALL,
                        })
                    })
                    .collect();
                let depth_stencil = depth.as_ref().map(|d| wgpu::DepthStencilState {
                    format: wgpu::TextureFormat::Depth32Float,
                    depth_write_enabled: Some(d.write),
                    depth_compare: Some(convert::compare(d.compare)),
                    stencil: Default::default(),
                    bias: Default::default(),
                });
                PipelineKind::Raster(self.device.create_render_pipeline(
                    &wgpu::RenderPipelineDescriptor {
                        label: Some(&pass.name),
                        layout: Some(&pipeline_layout),
                        vertex: wgpu::VertexState {
                            module: &module,
                            entry_point: Some(vertex),
                            compilation_options: options(),
                            buffers: &[],
                        },
                        primitive: wgpu::PrimitiveState::default(),
                        depth_stencil,
                        multisample: wgpu::MultisampleState::default(),
                        fragment: Some(wgpu::FragmentState {
                            module: &module,
                            entry_point: Some(fragment),
                            compilation_options: options(),
                            targets: &targets,
                        }),
                        multiview_mask: None,
                        cache: None,
                    },
                ))
            }
        };
        self.created += 3;
        self.pipelines.insert(key, Pipeline { layout, kind });
        Ok(())
    }

    /// One bind group per pass and history parity (two where the plan has history resources:
    /// frame N binds half N % 2 as `name` and the other as `name.previous`).
    fn build_groups(&mut self, plan: &FramePlan) -> Result<(), Error> {
        let parities = if plan.has_history() { 2 } else { 1 };
        let mut groups = Vec::new();
        for (i, pass) in plan.passes.iter().enumerate() {
            let layout = &self.pipelines[&self.keys[i]].layout;
            let mut per_parity = Vec::new();
            for parity in 0..parities {
                let mut entries = Vec::new();
                for b in &pass.bindings {
                    let r = &plan.resources[b.resource];
                    let object = &self.resources[&r.name].object;
                    let resource = match object {
                        Object::Buffer(buf) => buf.as_entire_binding(),
                        Object::Sampler(s) => wgpu::BindingResource::Sampler(s),
                        Object::Textures(t) => {
                            let half = if r.lifetime == Lifetime::History {
                                history_half(parity, b.previous)
                            } else {
                                0
                            };
                            wgpu::BindingResource::TextureView(&t[half].1)
                        }
                    };
                    entries.push(wgpu::BindGroupEntry {
                        binding: b.binding,
                        resource,
                    });
                }
                per_parity.push(self.device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some(&pass.name),
                    layout,
                    entries: &entries,
                }));
                self.created += 1;
            }
            groups.push(per_parity);
        }
        self.groups = groups;
        Ok(())
    }

    /// The view of a texture resource for this frame (the current half of a history pair).
    fn view(&self, plan: &FramePlan, index: usize) -> Result<&wgpu::TextureView, Error> {
        let r = &plan.resources[index];
        match &self.resources[&r.name].object {
            Object::Textures(t) => {
                let half = if r.lifetime == Lifetime::History {
                    history_half(self.frames.frame(), false)
                } else {
                    0
                };
                Ok(&t[half].1)
            }
            _ => Err(Error::Shader(format!("`{}` is not a texture", r.name))),
        }
    }

    /// Records pass `i` of the current plan, with timestamps at `query` (pair index).
    fn record_pass(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        i: usize,
        query: Option<u32>,
        target: Option<&wgpu::TextureView>,
        target_format: Option<wgpu::TextureFormat>,
    ) -> Result<(), Error> {
        let plan = self.plan.as_ref().expect("prepared");
        let pass = &plan.passes[i];
        let parity = if plan.has_history() {
            (self.frames.frame() % 2) as usize
        } else {
            0
        };
        let group = &self.groups[i][parity];
        // Only a raster pass drawing into a host's target of another format has another key.
        let external;
        let key = match (&pass.kind, target_format) {
            (PassKind::Raster { .. }, Some(format)) => {
                external = Self::pipeline_key(plan, i, Some(format));
                &external
            }
            _ => &self.keys[i],
        };
        let pipeline = &self.pipelines[key];
        let queries = query.and_then(|k| self.queries.as_ref().map(|q| (k, &q.set)));
        match (&pass.kind, &pipeline.kind) {
            (PassKind::Compute { dispatch, .. }, PipelineKind::Compute(p)) => {
                let mut cpass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some(&pass.name),
                    timestamp_writes: queries.map(|(k, set)| wgpu::ComputePassTimestampWrites {
                        query_set: set,
                        beginning_of_pass_write_index: Some(2 * k),
                        end_of_pass_write_index: Some(2 * k + 1),
                    }),
                });
                cpass.set_pipeline(p);
                cpass.set_bind_group(0, group, &[]);
                let [x, y, z] = *dispatch;
                cpass.dispatch_workgroups(x, y, z);
            }
            (
                PassKind::Raster {
                    vertices,
                    colors,
                    depth,
                    ..
                },
                PipelineKind::Raster(p),
            ) => {
                let mut attachments = Vec::new();
                for c in colors {
                    let view = match target {
                        Some(t) if plan.resources[c.resource].external => t,
                        _ => self.view(plan, c.resource)?,
                    };
                    attachments.push(Some(wgpu::RenderPassColorAttachment {
                        view,
                        depth_slice: None,
                        resolve_target: None,
                        ops: wgpu::Operations {
                            load: convert::color_load(c.load),
                            store: wgpu::StoreOp::Store,
                        },
                    }));
                }
                let depth_view = match depth {
                    Some(d) => Some((d, self.view(plan, d.resource)?)),
                    None => None,
                };
                let mut rpass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some(&pass.name),
                    color_attachments: &attachments,
                    depth_stencil_attachment: depth_view.map(|(d, view)| {
                        wgpu::RenderPassDepthStencilAttachment {
                            view,
                            depth_ops: Some(wgpu::Operations {
                                load: convert::depth_load(d.load),
                                store: wgpu::StoreOp::Store,
                            }),
                            stencil_ops: None,
                        }
                    }),
                    timestamp_writes: queries.map(|(k, set)| wgpu::RenderPassTimestampWrites {
                        query_set: set,
                        beginning_of_pass_write_index: Some(2 * k),
                        end_of_pass_write_index: Some(2 * k + 1),
                    }),
                    occlusion_query_set: None,
                    multiview_mask: None,
                });
                let [w, h] = pass.extent;
                rpass.set_viewport(0.0, 0.0, w as f32, h as f32, 0.0, 1.0);
                rpass.set_pipeline(p);
                rpass.set_bind_group(0, group, &[]);
                rpass.draw(0..*vertices, 0..1);
            }
            _ => {
                return Err(Error::Shader(format!(
                    "pass `{}`: pipeline kind does not match the pass",
                    pass.name
                )));
            }
        }
        Ok(())
    }

    /// Records the copies a frame's readback asks for into persistent readback buffers.
    fn copy_readbacks(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameInput<'_>,
    ) -> Result<Vec<Copied>, Error> {
        let plan = frame.plan;
        let wanted = frame.readback.targets(plan).map_err(Error::Shader)?;
        let mut out = Vec::new();
        for (i, readout) in wanted {
            let r = &plan.resources[i];
            let buffer = match &self.resources[&r.name].object {
                Object::Buffer(b) => Some(b.clone()),
                _ => None,
            };
            match &self.resources[&r.name].object {
                Object::Buffer(_) => {
                    let b = buffer.expect("a buffer");
                    let size = b.size();
                    let rb = self.readback_buffer(&r.name, size);
                    encoder.copy_buffer_to_buffer(&b, 0, &rb, 0, size);
                    out.push(Copied {
                        index: i,
                        readout,
                        rows: None,
                    });
                }
                Object::Textures(_) => {
                    let texture = self.view(plan, i)?.texture().clone();
                    let f = r
                        .format
                        .unwrap_or(stratus_graph::desc::TexelFormat::Rgba8Unorm);
                    let [w, h, d] = self.resources[&r.name].made.size().map_err(Error::Shader)?;
                    let row = w * f.texel_size();
                    let padded = row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT)
                        * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
                    let rb = self.readback_buffer(&r.name, u64::from(padded * h * d));
                    encoder.copy_texture_to_buffer(
                        texture.as_image_copy(),
                        wgpu::TexelCopyBufferInfo {
                            buffer: &rb,
                            layout: wgpu::TexelCopyBufferLayout {
                                offset: 0,
                                bytes_per_row: Some(padded),
                                rows_per_image: Some(h),
                            },
                        },
                        texture.size(),
                    );
                    out.push(Copied {
                        index: i,
                        readout,
                        rows: Some((padded, row, h * d)),
                    });
                }
                Object::Sampler(_) => {
                    return Err(Error::Shader(format!(
                        "readback of `{}`: a sampler holds no data",
                        r.name
                    )));
                }
            }
        }
        Ok(out)
    }

    /// Every texture of `plan` within the device's dimension limits, and every output's
    /// read-back within its buffer size limit: a clear error before anything is allocated
    /// (wgpu would otherwise hand back an invalid, empty buffer).
    fn check_limits(&self, plan: &FramePlan) -> Result<(), Error> {
        let limits = self.device.limits();
        let gib = |b: u64| b as f64 / f64::from(1u32 << 30);
        for r in &plan.resources {
            let (Some([w, h, d]), Some(format)) = (r.extent, r.format) else {
                continue;
            };
            let (max, what) = if r.dimension == stratus_graph::manifest::Dimension::D3 {
                (limits.max_texture_dimension_3d, "max_texture_dimension_3d")
            } else {
                (limits.max_texture_dimension_2d, "max_texture_dimension_2d")
            };
            if w.max(h).max(d) > max {
                return Err(Error::Limit(format!(
                    "`{}` would be {w}x{h}x{d} texels; this device allows at most {max} a side ({what}): render a smaller image",
                    r.name
                )));
            }
            let bytes = u64::from(w) * u64::from(h) * u64::from(d) * u64::from(format.texel_size());
            if r.output.is_some() && bytes > limits.max_buffer_size {
                return Err(Error::Limit(format!(
                    "reading back `{}` ({w}x{h} {}) needs a {:.1} GiB buffer; this device allows at most {:.1} GiB (max_buffer_size): render a smaller image",
                    r.name,
                    format.wgsl(),
                    gib(bytes),
                    gib(limits.max_buffer_size)
                )));
            }
        }
        Ok(())
    }

    fn readback_buffer(&mut self, name: &str, size: u64) -> wgpu::Buffer {
        if let Some(b) = self.readbacks.get(name)
            && b.size() == size
        {
            return b.clone();
        }
        let b = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        self.created += 1;
        self.readbacks.insert(name.into(), b.clone());
        b
    }
}

/// A copy recorded for readback: the resource (by index into the plan's; its readback buffer
/// goes by its name), where it goes in the output, and the row layout of a texture (padded row
/// bytes, row bytes, rows).
struct Copied {
    index: usize,
    readout: Readout,
    rows: Option<(u32, u32, u32)>,
}

impl Backend for Renderer {
    fn describe(&self) -> String {
        format!("wgpu on {}", self.adapter())
    }
    fn has_timestamps(&self) -> bool {
        self.timestamps
    }
    fn render(&mut self, frame: &FrameInput<'_>) -> Result<FrameOutput, BackendError> {
        Ok(Renderer::render(self, frame)?)
    }
    fn objects_created(&self) -> u64 {
        self.created
    }
    fn validated(&self) -> bool {
        self.validation
    }
}

fn extent3d([width, height, depth_or_array_layers]: [u32; 3]) -> wgpu::Extent3d {
    wgpu::Extent3d {
        width,
        height,
        depth_or_array_layers,
    }
}

fn class_of(t: wgpu::DeviceType) -> DeviceClass {
    match t {
        wgpu::DeviceType::DiscreteGpu => DeviceClass::Discrete,
        wgpu::DeviceType::IntegratedGpu => DeviceClass::Integrated,
        wgpu::DeviceType::VirtualGpu => DeviceClass::Virtual,
        wgpu::DeviceType::Other => DeviceClass::Other,
        wgpu::DeviceType::Cpu => DeviceClass::Cpu,
    }
}

/// Waits for the device. wgpu 30's `Device::poll` panics on any error but a timeout (a real
/// device loss among them, after the lost callback has run), so the panic is caught and
/// turned into an error; the caller then finds the loss the callback recorded.
fn poll(device: &wgpu::Device) -> Result<(), Error> {
    let waited = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        device.poll(wgpu::PollType::wait_indefinitely())
    }));
    match waited {
        Ok(Ok(_)) => Ok(()),
        Ok(Err(e)) => Err(Error::Wgpu(e.to_string())),
        Err(panic) => {
            let what = panic
                .downcast_ref::<String>()
                .map(String::as_str)
                .or_else(|| panic.downcast_ref::<&str>().copied())
                .unwrap_or("no message");
            Err(Error::Wgpu(format!(
                "waiting for the device failed ({what}): the device was lost"
            )))
        }
    }
}

/// Whether the Vulkan loader lists the Khronos validation layer (the check backend-ash makes
/// before asking for it). Without a loader this says yes, so that the missing loader is what
/// the caller hears about (wgpu then finds no Vulkan adapter).
fn validation_layer_installed() -> bool {
    // SAFETY: loads the system's Vulkan loader as any Vulkan use does; the entry is dropped at
    // the end of this function and nothing created from it outlives it.
    let Ok(entry) = (unsafe { ash::Entry::load() }) else {
        return true;
    };
    // SAFETY: a global command of a loaded entry, with no handles involved.
    let layers = unsafe { entry.enumerate_instance_layer_properties() }.unwrap_or_default();
    layers.iter().any(|l| {
        l.layer_name_as_c_str()
            .is_ok_and(|n| n == c"VK_LAYER_KHRONOS_validation")
    })
}

fn describe(info: &wgpu::AdapterInfo) -> String {
    describe_device(
        &info.name,
        &format!("{:?}", info.backend),
        class_of(info.device_type),
    )
}

/// Maps a readback buffer, copies its data out (dropping row padding), and unmaps it.
fn read_buffer(
    device: &wgpu::Device,
    buffer: &wgpu::Buffer,
    rows: Option<(u32, u32, u32)>,
) -> Result<Vec<u8>, Error> {
    let slice = buffer.slice(..);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    poll(device)?;
    rx.recv()
        .map_err(|e| Error::Wgpu(e.to_string()))?
        // wgpu drops "device lost" errors in favour of the device-lost callback, so on an
        // application's device (whose callback is the application's) a failed map is all
        // that shows of a loss.
        .map_err(|e| {
            Error::Wgpu(format!(
                "mapping a read-back buffer failed ({e}): the device was lost, or could not create the buffer"
            ))
        })?;
    let data = slice
        .get_mapped_range()
        .map_err(|e| Error::Wgpu(e.to_string()))?;
    // An invalid buffer (one wgpu could not create) maps as empty: say so, never index it.
    let needed = match rows {
        Some((padded, row, h)) => {
            u64::from(padded) * u64::from(h.saturating_sub(1)) + u64::from(row)
        }
        None => 0,
    };
    if (data.len() as u64) < needed {
        return Err(Error::Wgpu(format!(
            "a read-back buffer mapped {} bytes of the {needed} it should hold (the device could not create it)",
            data.len()
        )));
    }
    let out = match rows {
        Some((padded, row, h)) => (0..h)
            .flat_map(|y| {
                let start = (y * padded) as usize;
                data[start..start + row as usize].iter().copied()
            })
            .collect(),
        None => data.to_vec(),
    };
    drop(data);
    buffer.unmap();
    Ok(out)
}
