//! Runs Stratus's frame plan on wgpu, headless: Vulkan first, GL (EGL) on request.
//!
//! The steps mirror the ash backend's, in the same order: pick an adapter, compile the
//! variant's pipelines, upload the uniforms and noise, create the frame's images and the
//! statistics buffer, record every pass of the plan with timestamps around it, read back.
//! wgpu compiles the WGSL itself (its own naga translation) with exactly the plan's override
//! values, so it runs the same code as the committed SPIR-V the ash backend loads.

#![deny(missing_docs)]

use std::{
    collections::HashMap,
    sync::{Arc, Mutex},
    time::Instant,
};

use stratus_noise::{NoiseSet, Texture2, Texture3};
use stratus_scene::FrameUniforms;
use stratus_shaders::{
    FrameOutput, FramePlan, PassTiming, Resource, ShaderTree,
    plan::{COUNTERS, Pass, named_counters},
};
use wgpu::util::DeviceExt;

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
    /// wgpu reported a validation or out-of-memory error.
    #[error("wgpu reported an error: {0}")]
    Wgpu(String),
    /// The shader tree or frame plan is unusable.
    #[error("{0}")]
    Shader(String),
}

struct Pipeline {
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
}

/// A wgpu device ready to render frames. Pipelines are cached per variant.
pub struct Renderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    info: wgpu::AdapterInfo,
    timestamps: bool,
    module: wgpu::ShaderModule,
    pipelines: HashMap<(String, String), Pipeline>,
    errors: Arc<Mutex<Vec<String>>>,
}

impl Renderer {
    /// Picks an adapter for `options.api` (a real GPU before a CPU driver) and creates the
    /// device and the shader module from the embedded WGSL.
    pub fn new(options: Options) -> Result<Self, Error> {
        let backends = match options.api {
            Api::Vulkan => wgpu::Backends::VULKAN,
            Api::Gl => wgpu::Backends::GL,
        };
        let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
        desc.backends = backends;
        desc.flags = if options.validation {
            wgpu::InstanceFlags::VALIDATION
        } else {
            wgpu::InstanceFlags::empty()
        };
        let instance = wgpu::Instance::new(desc);
        let mut adapters = pollster::block_on(instance.enumerate_adapters(backends));
        adapters.sort_by_key(|a| match a.get_info().device_type {
            wgpu::DeviceType::DiscreteGpu => 0,
            wgpu::DeviceType::IntegratedGpu => 1,
            wgpu::DeviceType::VirtualGpu => 2,
            wgpu::DeviceType::Other => 3,
            wgpu::DeviceType::Cpu => 4,
        });
        let adapter = adapters.into_iter().next().ok_or(Error::NoAdapter {
            api: options.api,
            hint: match options.api {
                Api::Vulkan => {
                    " (install a Vulkan driver: `apt-get install mesa-vulkan-drivers libvulkan1` gives lavapipe)"
                }
                Api::Gl => " (install EGL and a GL driver: `apt-get install libegl1 libgl1-mesa-dri`)",
            },
        })?;
        let info = adapter.get_info();
        let timestamps = adapter.features().contains(wgpu::Features::TIMESTAMP_QUERY);
        let mut required_features = wgpu::Features::empty();
        if timestamps {
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
            sink.lock().unwrap().push(e.to_string());
        }));

        let tree = ShaderTree::embedded().map_err(|e| Error::Shader(e.to_string()))?;
        let spec = tree
            .module(stratus_shaders::plan::MODULE)
            .ok_or_else(|| Error::Shader("the embedded WGSL has no `clouds` module".into()))?;
        let source = tree.compose(spec).text;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("clouds"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let renderer = Self {
            device,
            queue,
            info,
            timestamps,
            module,
            pipelines: HashMap::new(),
            errors,
        };
        renderer.check_errors()?;
        Ok(renderer)
    }

    /// The adapter in words, e.g. `llvmpipe (LLVM 15.0.6, 256 bits) (Vulkan, Cpu)`.
    pub fn adapter(&self) -> String {
        describe(&self.info)
    }

    /// Whether passes are timed with GPU timestamp queries (else by CPU wall time).
    pub fn has_timestamps(&self) -> bool {
        self.timestamps
    }

    fn check_errors(&self) -> Result<(), Error> {
        let errors = std::mem::take(&mut *self.errors.lock().unwrap());
        if errors.is_empty() {
            Ok(())
        } else {
            Err(Error::Wgpu(errors.join("\n")))
        }
    }

    /// Renders one frame of `plan` with these uniforms and noise textures.
    pub fn render(
        &mut self,
        plan: &FramePlan,
        uniforms: &FrameUniforms,
        noise: &NoiseSet,
    ) -> Result<FrameOutput, Error> {
        let scope = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let result = self.render_inner(plan, uniforms, noise);
        let scoped = pollster::block_on(scope.pop());
        self.check_errors()?;
        if let Some(e) = scoped {
            return Err(Error::Wgpu(e.to_string()));
        }
        result
    }

    fn render_inner(
        &mut self,
        plan: &FramePlan,
        uniforms: &FrameUniforms,
        noise: &NoiseSet,
    ) -> Result<FrameOutput, Error> {
        // 1. Pipelines for the plan's variant (cached).
        for pass in &plan.passes {
            self.pipeline(plan, pass);
        }

        // 2. Resources: uniforms, noise, the frame's images and the statistics buffer.
        let (w, h) = (plan.width, plan.height);
        let device = &self.device;
        let frame = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("frame"),
            contents: bytemuck::bytes_of(uniforms),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let shape = self.texture3("shape", &noise.shape);
        let detail = self.texture3("detail", &noise.detail);
        let weather = self.texture2("weather", &noise.weather);
        let curl = self.texture2("curl", &noise.curl);
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("noise"),
            address_mode_u: wgpu::AddressMode::Repeat,
            address_mode_v: wgpu::AddressMode::Repeat,
            address_mode_w: wgpu::AddressMode::Repeat,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            mipmap_filter: wgpu::MipmapFilterMode::Nearest,
            ..Default::default()
        });
        // COPY_DST lets wgpu zero-initialise these images with a copy. Without it wgpu clears
        // them with a render pass, which leaves a framebuffer bound in llvmpipe; lavapipe then
        // bins timestamps into its tiles and takes them at the next flush, so the march pass
        // measured ~0 ms and its cost landed in the composite pass (found with a perf probe on
        // clock_gettime; ash, which never binds a framebuffer, times the passes correctly).
        let image_usage = wgpu::TextureUsages::STORAGE_BINDING
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_SRC
            | wgpu::TextureUsages::COPY_DST;
        let cloud = self.image("cloud", w, h, wgpu::TextureFormat::Rgba32Float, image_usage);
        let depth = self.image("depth", w, h, wgpu::TextureFormat::R32Float, image_usage);
        let image = self.image("image", w, h, wgpu::TextureFormat::Rgba8Unorm, image_usage);
        let stats = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("stats"),
            contents: &[0u8; COUNTERS.len() * 4],
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        });
        let views: HashMap<Resource, wgpu::BindingResource> = HashMap::from([
            (Resource::Frame, frame.as_entire_binding()),
            (Resource::Shape, wgpu::BindingResource::TextureView(&shape)),
            (
                Resource::Detail,
                wgpu::BindingResource::TextureView(&detail),
            ),
            (
                Resource::Weather,
                wgpu::BindingResource::TextureView(&weather),
            ),
            (Resource::Curl, wgpu::BindingResource::TextureView(&curl)),
            (
                Resource::NoiseSampler,
                wgpu::BindingResource::Sampler(&sampler),
            ),
            (
                Resource::Cloud,
                wgpu::BindingResource::TextureView(&cloud.1),
            ),
            (
                Resource::Depth,
                wgpu::BindingResource::TextureView(&depth.1),
            ),
            (
                Resource::Image,
                wgpu::BindingResource::TextureView(&image.1),
            ),
            (Resource::Stats, stats.as_entire_binding()),
        ]);

        // 3. Passes, each bracketed by timestamps (or submitted alone and timed on the CPU).
        let queries = self.timestamps.then(|| {
            device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("pass times"),
                ty: wgpu::QueryType::Timestamp,
                count: 2 * plan.passes.len() as u32,
            })
        });
        let mut wall = Vec::new();
        let mut encoder = device.create_command_encoder(&Default::default());
        for (i, pass) in plan.passes.iter().enumerate() {
            let p = &self.pipelines[&(plan.variant.clone(), pass.entry_point.clone())];
            let entries: Vec<_> = pass
                .bindings
                .iter()
                .map(|b| wgpu::BindGroupEntry {
                    binding: b.binding,
                    resource: views[&b.resource].clone(),
                })
                .collect();
            let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(&pass.name),
                layout: &p.layout,
                entries: &entries,
            });
            {
                let mut cpass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some(&pass.name),
                    timestamp_writes: queries.as_ref().map(|q| wgpu::ComputePassTimestampWrites {
                        query_set: q,
                        beginning_of_pass_write_index: Some(2 * i as u32),
                        end_of_pass_write_index: Some(2 * i as u32 + 1),
                    }),
                });
                cpass.set_pipeline(&p.pipeline);
                cpass.set_bind_group(0, &group, &[]);
                let [x, y, z] = pass.dispatch;
                cpass.dispatch_workgroups(x, y, z);
            }
            if queries.is_none() {
                // No timestamps: submit this pass alone and time it on the CPU.
                let t = Instant::now();
                self.queue.submit([encoder.finish()]);
                self.wait()?;
                wall.push(t.elapsed().as_secs_f64() * 1e3);
                encoder = device.create_command_encoder(&Default::default());
            }
        }

        // 4. Read back images, statistics and timestamps.
        let cloud_rb = Readback::texture(device, &mut encoder, &cloud.0, 16);
        let depth_rb = Readback::texture(device, &mut encoder, &depth.0, 4);
        let image_rb = Readback::texture(device, &mut encoder, &image.0, 4);
        let stats_rb = Readback::buffer(device, &mut encoder, &stats, (COUNTERS.len() * 4) as u64);
        let time_rb = queries.as_ref().map(|q| {
            let n = 2 * plan.passes.len() as u32;
            let resolve = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("timestamps"),
                size: u64::from(n) * 8,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            encoder.resolve_query_set(q, 0..n, &resolve, 0);
            Readback::buffer(device, &mut encoder, &resolve, u64::from(n) * 8)
        });
        self.queue.submit([encoder.finish()]);
        self.wait()?;

        let radiance: Vec<f32> = bytemuck::cast_slice(&cloud_rb.read(device)?).to_vec();
        let depth: Vec<f32> = bytemuck::cast_slice(&depth_rb.read(device)?).to_vec();
        let image = image_rb.read(device)?;
        let raw_stats: Vec<u32> = bytemuck::cast_slice(&stats_rb.read(device)?).to_vec();
        let timings = match time_rb {
            Some(rb) => {
                let ticks: Vec<u64> = bytemuck::cast_slice(&rb.read(device)?).to_vec();
                let period_ns = f64::from(self.queue.get_timestamp_period());
                plan.passes
                    .iter()
                    .enumerate()
                    .map(|(i, p)| PassTiming {
                        pass: p.name.clone(),
                        ms: ticks[2 * i + 1].saturating_sub(ticks[2 * i]) as f64 * period_ns * 1e-6,
                        source: "gpu-timestamp",
                    })
                    .collect()
            }
            None => plan
                .passes
                .iter()
                .zip(wall)
                .map(|(p, ms)| PassTiming {
                    pass: p.name.clone(),
                    ms,
                    source: "cpu-wall",
                })
                .collect(),
        };
        Ok(FrameOutput {
            width: w,
            height: h,
            radiance,
            depth,
            image,
            stats: plan.stats.then(|| named_counters(&raw_stats)),
            timings,
            device: self.adapter(),
        })
    }

    fn wait(&self) -> Result<(), Error> {
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map(|_| ())
            .map_err(|e| Error::Wgpu(e.to_string()))
    }

    /// Creates (once per variant) the bind group layout and pipeline of a pass from the plan.
    fn pipeline(&mut self, plan: &FramePlan, pass: &Pass) {
        let key = (plan.variant.clone(), pass.entry_point.clone());
        if self.pipelines.contains_key(&key) {
            return;
        }
        let entries: Vec<_> = pass
            .bindings
            .iter()
            .map(|b| wgpu::BindGroupLayoutEntry {
                binding: b.binding,
                visibility: wgpu::ShaderStages::COMPUTE,
                ty: binding_type(b),
                count: None,
            })
            .collect();
        let layout = self
            .device
            .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some(&pass.name),
                entries: &entries,
            });
        let pipeline_layout = self
            .device
            .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(&pass.name),
                bind_group_layouts: &[Some(&layout)],
                immediate_size: 0,
            });
        // Exactly the variant's override values, so wgpu runs the code the SPIR-V holds.
        let constants: Vec<(&str, f64)> = plan
            .overrides
            .iter()
            .map(|(k, v)| (k.as_str(), *v))
            .collect();
        let pipeline = self
            .device
            .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(&pass.name),
                layout: Some(&pipeline_layout),
                module: &self.module,
                entry_point: Some(&pass.entry_point),
                compilation_options: wgpu::PipelineCompilationOptions {
                    constants: &constants,
                    zero_initialize_workgroup_memory: true,
                },
                cache: None,
            });
        self.pipelines.insert(key, Pipeline { layout, pipeline });
    }

    fn texture3(&self, label: &str, t: &Texture3) -> wgpu::TextureView {
        let [x, y, z] = t.size;
        self.upload(label, wgpu::TextureDimension::D3, [x, y, z], &t.data)
    }

    fn texture2(&self, label: &str, t: &Texture2) -> wgpu::TextureView {
        let [x, y] = t.size;
        self.upload(label, wgpu::TextureDimension::D2, [x, y, 1], &t.data)
    }

    fn upload(
        &self,
        label: &str,
        dimension: wgpu::TextureDimension,
        [x, y, z]: [u32; 3],
        data: &[u8],
    ) -> wgpu::TextureView {
        let texture = self.device.create_texture_with_data(
            &self.queue,
            &wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width: x,
                    height: y,
                    depth_or_array_layers: z,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension,
                format: wgpu::TextureFormat::Rgba8Unorm,
                usage: wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            },
            wgpu::util::TextureDataOrder::LayerMajor,
            data,
        );
        texture.create_view(&Default::default())
    }

    fn image(
        &self,
        label: &str,
        w: u32,
        h: u32,
        format: wgpu::TextureFormat,
        usage: wgpu::TextureUsages,
    ) -> (wgpu::Texture, wgpu::TextureView) {
        let texture = self.device.create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d {
                width: w,
                height: h,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage,
            view_formats: &[],
        });
        let view = texture.create_view(&Default::default());
        (texture, view)
    }
}

/// The wgpu binding type for a plan binding, from the manifest's reflection.
fn binding_type(b: &stratus_shaders::plan::Binding) -> wgpu::BindingType {
    let dim = match b.info.dimension.as_deref() {
        Some("3d") => wgpu::TextureViewDimension::D3,
        _ => wgpu::TextureViewDimension::D2,
    };
    match b.info.kind.as_str() {
        "uniform-buffer" => wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        "storage-buffer" => wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage {
                read_only: b.info.access.as_deref() == Some("read"),
            },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        "sampled-texture" => wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float {
                filterable: b.resource.filterable(),
            },
            view_dimension: dim,
            multisampled: false,
        },
        "storage-texture" => wgpu::BindingType::StorageTexture {
            access: match b.info.access.as_deref() {
                Some("read") => wgpu::StorageTextureAccess::ReadOnly,
                Some("read-write") => wgpu::StorageTextureAccess::ReadWrite,
                _ => wgpu::StorageTextureAccess::WriteOnly,
            },
            format: texture_format(b.info.format.as_deref().unwrap_or_default()),
            view_dimension: dim,
        },
        _ => wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
    }
}

fn texture_format(wgsl: &str) -> wgpu::TextureFormat {
    match wgsl {
        "rgba32float" => wgpu::TextureFormat::Rgba32Float,
        "r32float" => wgpu::TextureFormat::R32Float,
        "rgba16float" => wgpu::TextureFormat::Rgba16Float,
        _ => wgpu::TextureFormat::Rgba8Unorm,
    }
}

fn describe(info: &wgpu::AdapterInfo) -> String {
    format!("{} ({:?}, {:?})", info.name, info.backend, info.device_type)
}

/// A buffer that a copy lands in, to be mapped and read after the submit.
struct Readback {
    buffer: wgpu::Buffer,
    /// Row layout for textures: (bytes per row in the buffer, bytes per row of data, rows).
    rows: Option<(u32, u32, u32)>,
}

impl Readback {
    fn texture(
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        texture: &wgpu::Texture,
        texel: u32,
    ) -> Self {
        let (w, h) = (texture.width(), texture.height());
        let row = w * texel;
        let padded =
            row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size: u64::from(padded * h),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        encoder.copy_texture_to_buffer(
            texture.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(padded),
                    rows_per_image: Some(h),
                },
            },
            texture.size(),
        );
        Self {
            buffer,
            rows: Some((padded, row, h)),
        }
    }

    fn buffer(
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        src: &wgpu::Buffer,
        size: u64,
    ) -> Self {
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        encoder.copy_buffer_to_buffer(src, 0, &buffer, 0, size);
        Self { buffer, rows: None }
    }

    fn read(self, device: &wgpu::Device) -> Result<Vec<u8>, Error> {
        let slice = self.buffer.slice(..);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| Error::Wgpu(e.to_string()))?;
        rx.recv()
            .map_err(|e| Error::Wgpu(e.to_string()))?
            .map_err(|e| Error::Wgpu(e.to_string()))?;
        let data = slice
            .get_mapped_range()
            .map_err(|e| Error::Wgpu(e.to_string()))?;
        let out = match self.rows {
            Some((padded, row, h)) => (0..h)
                .flat_map(|y| {
                    let start = (y * padded) as usize;
                    data[start..start + row as usize].iter().copied()
                })
                .collect(),
            None => data.to_vec(),
        };
        drop(data);
        self.buffer.unmap();
        Ok(out)
    }
}
