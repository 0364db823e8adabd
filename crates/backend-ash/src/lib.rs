//! Runs Stratus's frame plan on raw Vulkan (ash), from the committed SPIR-V in `spirv-out/`.
//!
//! The steps mirror backend-wgpu's, in the same order: pick a device, build the variant's
//! pipelines, upload the uniforms and noise, create the frame's images and the statistics
//! buffer, record every pass of the plan with timestamps around it, read back. The one
//! difference in what runs: wgpu translates the WGSL itself (with the plan's override values),
//! while this backend loads the exact bytes of `spirv-out/<module>.<variant>.spv`, where
//! `cargo xtask build-shaders` baked the same values in. The descriptor set layouts come
//! from the plan's bindings, which are the manifest's reflection of the WGSL; nothing here
//! keeps a copy of the shader interface by hand.
//!
//! [`Renderer::render_with`] runs the same frame from SPIR-V supplied per pass instead (naga's
//! GLSL or HLSL compiled by glslang, in the conformance suite); each [`PassShader`] lists the
//! descriptors its module declares (see [`Shaders`]).
//!
//! With [`Options::validation`] the Khronos validation layer runs with synchronization
//! validation, and every warning or error it reports (leaked objects at device destruction
//! included) turns into an [`Error::Validation`] from [`Renderer::new`], [`Renderer::render`]
//! or [`Renderer::finish`].

#![deny(missing_docs)]

mod error;
mod frame;
mod gpu;
mod interface;
mod pipeline;

use std::{
    collections::HashMap,
    hash::{Hash, Hasher},
    time::Instant,
};

use ash::vk;
use gpu_allocator::MemoryLocation;
use stratus_noise::NoiseSet;
use stratus_scene::FrameUniforms;
use stratus_shaders::{
    FrameOutput, FramePlan, PassTiming, Resource,
    plan::{COUNTERS, Pass, named_counters},
};

pub use crate::{
    error::Error,
    interface::{PassShader, Shaders, Slot, SlotContent},
};
use crate::{
    error::vk,
    frame::{COLOR_LAYER, Frame, Image, Tracker, Use, image_needs, texel_size},
    gpu::Gpu,
    interface::{Descriptor, descriptors},
    pipeline::{PassPipeline, module_from_words, shader_module, view_type},
};

/// How to create the renderer.
#[derive(Clone, Copy, Debug, Default)]
pub struct Options {
    /// Turn on the Khronos validation layer with synchronization validation; any warning or
    /// error it reports makes the call that caused it fail with [`Error::Validation`].
    pub validation: bool,
}

/// The stage of the timestamps written before and after every dispatch: BOTTOM_OF_PIPE, as
/// wgpu-hal writes its pass timestamps, so both backends measure the same span.
///
/// On lavapipe (llvmpipe) a dispatch runs synchronously and a non-TOP_OF_PIPE timestamp
/// flushes first, so these stamps bracket the dispatch exactly, as long as llvmpipe has no
/// framebuffer bound. With a framebuffer bound (any render pass, e.g. wgpu's zero-initialising
/// clear of a texture that lacks COPY_DST), llvmpipe bins the timestamp into the rasteriser's
/// tiles and only takes the time at the *next* flush, which moves a pass's cost out of its
/// window. This backend never begins a render pass, so its stamps stay exact; measured on
/// lavapipe against each pass submitted alone (`examples/timestamps.rs`).
const TIMESTAMP_STAGE: vk::PipelineStageFlags = vk::PipelineStageFlags::BOTTOM_OF_PIPE;

/// What a frame binds besides the samplers (which the [`Frame`] holds).
struct Bound<'a> {
    uniform: frame::Buffer,
    stats: frame::Buffer,
    /// Zeros for naga's HLSL sampler index buffers, where a supplied module has one.
    indices: Option<frame::Buffer>,
    images: &'a HashMap<Resource, Image>,
}

/// Which pipeline a pass runs: the committed SPIR-V's, by variant and entry point, or a
/// supplied module's, by a hash of the [`PassShader`] (words, entry point and slots).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
enum PipelineKey {
    Committed { variant: String, entry: String },
    Supplied(u64),
}

impl PipelineKey {
    fn of(plan: &FramePlan, pass: &Pass, shader: Option<&PassShader>) -> Self {
        match shader {
            None => Self::Committed {
                variant: plan.variant.clone(),
                entry: pass.entry_point.clone(),
            },
            Some(s) => {
                let mut h = std::collections::hash_map::DefaultHasher::new();
                s.hash(&mut h);
                Self::Supplied(h.finish())
            }
        }
    }
}

/// The supplied module of pass `i`, if the frame runs supplied modules.
fn pass_shader(shaders: &Shaders, i: usize) -> Option<&PassShader> {
    match shaders {
        Shaders::Committed => None,
        Shaders::PerPass(list) => list.get(i),
    }
}

/// A Vulkan device ready to render frames. Pipelines are cached per (variant, entry point),
/// and per supplied module.
pub struct Renderer {
    modules: HashMap<String, vk::ShaderModule>,
    pipelines: HashMap<PipelineKey, PassPipeline>,
    cpu_timing: bool,
    torn_down: bool,
    gpu: Gpu,
}

impl Renderer {
    /// Loads the Vulkan loader, creates an instance (with validation when asked), picks a
    /// device (a real GPU before a CPU driver such as lavapipe, as backend-wgpu does) that
    /// has a compute queue and every image format the frame needs, and creates the device,
    /// its command pool and memory allocator.
    pub fn new(options: Options) -> Result<Self, Error> {
        let gpu = Gpu::new(options.validation)?;
        Ok(Self {
            modules: HashMap::new(),
            pipelines: HashMap::new(),
            cpu_timing: false,
            torn_down: false,
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

    /// Renders one frame of `plan` with these uniforms and noise textures, from the committed
    /// SPIR-V.
    pub fn render(
        &mut self,
        plan: &FramePlan,
        uniforms: &FrameUniforms,
        noise: &NoiseSet,
    ) -> Result<FrameOutput, Error> {
        self.render_with(plan, &Shaders::Committed, uniforms, noise)
    }

    /// Renders one frame of `plan` from `shaders`: the committed SPIR-V (as
    /// [`Renderer::render`]) or one supplied module per pass. Everything but the modules and
    /// their descriptor layouts is the same frame: resources, barriers, timestamps, readback.
    pub fn render_with(
        &mut self,
        plan: &FramePlan,
        shaders: &Shaders,
        uniforms: &FrameUniforms,
        noise: &NoiseSet,
    ) -> Result<FrameOutput, Error> {
        match shaders {
            Shaders::PerPass(list) if list.len() != plan.passes.len() => {
                return Err(Error::Shader(format!(
                    "{} supplied shader module(s) for a plan of {} passes",
                    list.len(),
                    plan.passes.len()
                )));
            }
            _ => {}
        }
        self.gpu.check_messages()?;
        let mut frame = Frame::default();
        let result = self.render_inner(&mut frame, plan, shaders, uniforms, noise);
        if result.is_err() {
            // SAFETY: valid device. The frame may still be in flight after a failed step;
            // nothing can be done about a failure to wait but destroy regardless.
            unsafe {
                let _ = self.gpu.device.device_wait_idle();
                let _ = self.gpu.device.reset_command_buffer(
                    self.gpu.command_buffer,
                    vk::CommandBufferResetFlags::empty(),
                );
            }
        }
        frame.destroy(&self.gpu.device, &mut self.gpu.allocator);
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
            for (_, mut p) in self.pipelines.drain() {
                p.destroy(&self.gpu.device);
            }
            for (_, m) in self.modules.drain() {
                self.gpu.device.destroy_shader_module(m, None);
            }
        }
        self.gpu.destroy();
    }

    fn render_inner(
        &mut self,
        frame: &mut Frame,
        plan: &FramePlan,
        shaders: &Shaders,
        uniforms: &FrameUniforms,
        noise: &NoiseSet,
    ) -> Result<FrameOutput, Error> {
        // 1. Pipelines for the plan's variant or the supplied modules (cached).
        let mut keys = Vec::new();
        for (i, pass) in plan.passes.iter().enumerate() {
            keys.push(self.pipeline(plan, pass, pass_shader(shaders, i))?);
        }
        let (w, h) = (plan.width, plan.height);
        let info = &self.gpu.info;
        if w.max(h) > info.max_image_2d {
            return Err(Error::Size {
                width: w,
                height: h,
                max: info.max_image_2d,
                device: info.name.clone(),
            });
        }
        let timestamps = self.has_timestamps();

        // 2. Resources: uniforms, noise, the frame's images and the statistics buffer.
        let device = &self.gpu.device;
        let allocator = &mut *self.gpu.allocator;
        let host = MemoryLocation::CpuToGpu;
        let bytes = bytemuck::bytes_of(uniforms);
        let uniform = frame.buffer(
            device,
            allocator,
            "frame",
            bytes.len() as u64,
            vk::BufferUsageFlags::UNIFORM_BUFFER,
            host,
        )?;
        frame.mapped(uniform)?.copy_from_slice(bytes);

        // backend-wgpu's `create_texture_with_data` stages through a buffer too; here all
        // four textures share one staging buffer and are copied in one command buffer.
        let uploads: [(Resource, [u32; 3], &[u8]); 4] = [
            (Resource::Shape, noise.shape.size, &noise.shape.data),
            (Resource::Detail, noise.detail.size, &noise.detail.data),
            (
                Resource::Weather,
                [noise.weather.size[0], noise.weather.size[1], 1],
                &noise.weather.data,
            ),
            (
                Resource::Curl,
                [noise.curl.size[0], noise.curl.size[1], 1],
                &noise.curl.data,
            ),
        ];
        let mut offsets = Vec::new();
        let mut staging_size = 0u64;
        for (resource, [x, y, z], data) in &uploads {
            let expected = u64::from(*x) * u64::from(*y) * u64::from(*z) * 4;
            if data.len() as u64 != expected || expected == 0 {
                return Err(Error::Shader(format!(
                    "the {resource:?} noise texture has {} bytes, {expected} expected for {x}x{y}x{z} RGBA8",
                    data.len()
                )));
            }
            offsets.push(staging_size);
            staging_size += expected;
        }
        let staging = frame.buffer(
            device,
            allocator,
            "noise staging",
            staging_size,
            vk::BufferUsageFlags::TRANSFER_SRC,
            host,
        )?;
        {
            let mapped = frame.mapped(staging)?;
            for ((_, _, data), &offset) in uploads.iter().zip(&offsets) {
                let start = offset as usize;
                mapped[start..start + data.len()].copy_from_slice(data);
            }
        }
        let mut images: HashMap<Resource, Image> = HashMap::new();
        for (resource, [x, y, z], _) in &uploads {
            let image = frame.image(
                device,
                allocator,
                &format!("{resource:?}"),
                view_type(*resource),
                Gpu::format_of(*resource)?,
                vk::Extent3D {
                    width: *x,
                    height: *y,
                    depth: *z,
                },
                image_needs(*resource).0,
            )?;
            images.insert(*resource, image);
        }
        // As backend-wgpu: linear, repeating, one mip level, lod clamp [0, 32], no anisotropy.
        let sampler_info = vk::SamplerCreateInfo::default()
            .mag_filter(vk::Filter::LINEAR)
            .min_filter(vk::Filter::LINEAR)
            .mipmap_mode(vk::SamplerMipmapMode::NEAREST)
            .address_mode_u(vk::SamplerAddressMode::REPEAT)
            .address_mode_v(vk::SamplerAddressMode::REPEAT)
            .address_mode_w(vk::SamplerAddressMode::REPEAT)
            .min_lod(0.0)
            .max_lod(32.0);
        // SAFETY: valid device and info.
        frame.sampler =
            unsafe { device.create_sampler(&sampler_info, None) }.map_err(vk("vkCreateSampler"))?;
        let supplied = matches!(shaders, Shaders::PerPass(_));
        if supplied {
            // For images that a supplied module reads through a combined image sampler but
            // that are not filterable (GLSL has no image without a sampler to load from).
            let nearest = sampler_info
                .mag_filter(vk::Filter::NEAREST)
                .min_filter(vk::Filter::NEAREST);
            // SAFETY: valid device and info.
            frame.nearest_sampler =
                unsafe { device.create_sampler(&nearest, None) }.map_err(vk("vkCreateSampler"))?;
        }
        // Zeros for naga's HLSL sampler index buffers: every sampler is heap element 0.
        let index_words = match shaders {
            Shaders::Committed => 0,
            Shaders::PerPass(list) => list
                .iter()
                .flat_map(|s| &s.slots)
                .filter_map(|slot| match slot.content {
                    SlotContent::SamplerIndices(n) => Some(n),
                    _ => None,
                })
                .max()
                .unwrap_or(0),
        };
        let indices = if index_words > 0 {
            let size = u64::from(index_words) * 4;
            let buffer = frame.buffer(
                device,
                allocator,
                "sampler indices",
                size,
                vk::BufferUsageFlags::STORAGE_BUFFER,
                host,
            )?;
            frame.mapped(buffer)?.fill(0);
            Some(buffer)
        } else {
            None
        };
        let targets = [Resource::Cloud, Resource::Depth, Resource::Image];
        for resource in targets {
            let image = frame.image(
                device,
                allocator,
                &format!("{resource:?}"),
                vk::ImageViewType::TYPE_2D,
                Gpu::format_of(resource)?,
                vk::Extent3D {
                    width: w,
                    height: h,
                    depth: 1,
                },
                image_needs(resource).0,
            )?;
            images.insert(resource, image);
        }
        let stats_size = (COUNTERS.len() * 4) as u64;
        let stats = frame.buffer(
            device,
            allocator,
            "stats",
            stats_size,
            vk::BufferUsageFlags::STORAGE_BUFFER
                | vk::BufferUsageFlags::TRANSFER_DST
                | vk::BufferUsageFlags::TRANSFER_SRC,
            MemoryLocation::GpuOnly,
        )?;
        // Readback buffers, rows tightly packed (Vulkan, unlike WebGPU, needs no 256-byte
        // row alignment, so there is nothing to strip when reading).
        let mut readbacks = Vec::new();
        for resource in targets {
            let image = images[&resource];
            let size = u64::from(w) * u64::from(h) * texel_size(image.format);
            let buffer = frame.buffer(
                device,
                allocator,
                "readback",
                size,
                vk::BufferUsageFlags::TRANSFER_DST,
                MemoryLocation::GpuToCpu,
            )?;
            readbacks.push((image, buffer));
        }
        let stats_rb = frame.buffer(
            device,
            allocator,
            "stats readback",
            stats_size,
            vk::BufferUsageFlags::TRANSFER_DST,
            MemoryLocation::GpuToCpu,
        )?;
        let query_count = 2 * plan.passes.len() as u32;
        if timestamps && query_count > 0 {
            let info = vk::QueryPoolCreateInfo::default()
                .query_type(vk::QueryType::TIMESTAMP)
                .query_count(query_count);
            // SAFETY: valid device and info.
            frame.query_pool = unsafe { device.create_query_pool(&info, None) }
                .map_err(vk("vkCreateQueryPool"))?;
        }

        let sets = self.descriptor_sets(
            frame,
            plan,
            shaders,
            &keys,
            &Bound {
                uniform,
                stats,
                indices,
                images: &images,
            },
        )?;

        // 3. Record: uploads, then every pass with barriers between and timestamps around.
        let cb = self.gpu.command_buffer;
        let mut tracker = Tracker::default();
        for (&resource, image) in &images {
            tracker.add_image(resource, image.image, Use::NEW);
        }
        tracker.add_buffer(Resource::Stats, stats.buffer, Use::NEW);
        self.begin()?;
        let device = &self.gpu.device;
        // SAFETY (this block and the recording below): `cb` is recording; every handle
        // belongs to this device and lives until the frame is destroyed after the wait.
        unsafe {
            if timestamps && query_count > 0 {
                device.cmd_reset_query_pool(cb, frame.query_pool, 0, query_count);
            }
            let wants: Vec<_> = uploads.iter().map(|u| (u.0, Use::COPY_DST)).collect();
            tracker.barrier(device, cb, &wants);
            for ((resource, _, _), &offset) in uploads.iter().zip(&offsets) {
                let image = images[resource];
                let region = vk::BufferImageCopy::default()
                    .buffer_offset(offset)
                    .image_subresource(COLOR_LAYER)
                    .image_extent(image.extent);
                device.cmd_copy_buffer_to_image(
                    cb,
                    staging.buffer,
                    image.image,
                    vk::ImageLayout::TRANSFER_DST_OPTIMAL,
                    &[region],
                );
            }
            let fill = Use {
                layout: vk::ImageLayout::UNDEFINED,
                ..Use::COPY_DST
            };
            tracker.barrier(device, cb, &[(Resource::Stats, fill)]);
            device.cmd_fill_buffer(cb, stats.buffer, 0, vk::WHOLE_SIZE, 0);
        }
        let mut wall = Vec::new();
        if !timestamps {
            // Unlike backend-wgpu, the upload is submitted on its own first, so that the
            // first pass's CPU time is the pass alone.
            self.submit_and_wait()?;
            self.begin()?;
        }
        for (i, pass) in plan.passes.iter().enumerate() {
            let wants = pass
                .bindings
                .iter()
                .filter_map(|b| Use::of_binding(b).transpose().map(|u| Ok((b.resource, u?))))
                .collect::<Result<Vec<_>, Error>>()?;
            let p = self.pass_pipeline(&keys[i], pass)?;
            let device = &self.gpu.device;
            let query = 2 * i as u32;
            // SAFETY: as above.
            unsafe {
                tracker.barrier(device, cb, &wants);
                if timestamps {
                    device.cmd_write_timestamp(cb, TIMESTAMP_STAGE, frame.query_pool, query);
                }
                device.cmd_bind_pipeline(cb, vk::PipelineBindPoint::COMPUTE, p.pipeline);
                if !sets[i].is_empty() {
                    device.cmd_bind_descriptor_sets(
                        cb,
                        vk::PipelineBindPoint::COMPUTE,
                        p.layout,
                        0,
                        &sets[i],
                        &[],
                    );
                }
                let [x, y, z] = pass.dispatch;
                device.cmd_dispatch(cb, x, y, z);
                if timestamps {
                    device.cmd_write_timestamp(cb, TIMESTAMP_STAGE, frame.query_pool, query + 1);
                }
            }
            if !timestamps {
                // No timestamps: submit this pass alone and time it on the CPU.
                let t = Instant::now();
                self.submit_and_wait()?;
                wall.push(t.elapsed().as_secs_f64() * 1e3);
                self.begin()?;
            }
        }

        // 4. Copy the images and counters to host-visible buffers, submit, wait, read back.
        let device = &self.gpu.device;
        let mut wants: Vec<_> = targets.iter().map(|&r| (r, Use::COPY_SRC)).collect();
        wants.push((
            Resource::Stats,
            Use {
                layout: vk::ImageLayout::UNDEFINED,
                ..Use::COPY_SRC
            },
        ));
        // SAFETY: as above.
        unsafe {
            tracker.barrier(device, cb, &wants);
            for (image, buffer) in &readbacks {
                let region = vk::BufferImageCopy::default()
                    .image_subresource(COLOR_LAYER)
                    .image_extent(image.extent);
                device.cmd_copy_image_to_buffer(
                    cb,
                    image.image,
                    vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
                    buffer.buffer,
                    &[region],
                );
            }
            let region = vk::BufferCopy::default().size(stats_size);
            device.cmd_copy_buffer(cb, stats.buffer, stats_rb.buffer, &[region]);
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
        self.submit_and_wait()?;

        // gpu-allocator picks HOST_COHERENT memory for GpuToCpu, so no invalidation is needed.
        let radiance = bytemuck::pod_collect_to_vec::<u8, f32>(frame.mapped(readbacks[0].1)?);
        let depth = bytemuck::pod_collect_to_vec::<u8, f32>(frame.mapped(readbacks[1].1)?);
        let image = frame.mapped(readbacks[2].1)?.to_vec();
        let raw_stats = bytemuck::pod_collect_to_vec::<u8, u32>(frame.mapped(stats_rb)?);
        let timings = if timestamps {
            self.timestamps(frame, plan)?
        } else {
            plan.passes
                .iter()
                .zip(wall)
                .map(|(p, ms)| PassTiming {
                    pass: p.name.clone(),
                    ms,
                    source: "cpu-wall",
                })
                .collect()
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

    /// Creates the frame's descriptor pool and one descriptor set per pass and set number, and
    /// writes every descriptor: what is bound where comes from the plan (the manifest's
    /// reflection) or from a supplied module's slots, the image layouts from
    /// [`Use::of_binding`].
    fn descriptor_sets(
        &self,
        frame: &mut Frame,
        plan: &FramePlan,
        shaders: &Shaders,
        keys: &[PipelineKey],
        bound: &Bound<'_>,
    ) -> Result<Vec<Vec<vk::DescriptorSet>>, Error> {
        let device = &self.gpu.device;
        let per_pass = plan
            .passes
            .iter()
            .enumerate()
            .map(|(i, pass)| descriptors(pass, pass_shader(shaders, i).map(|s| &s.slots[..])))
            .collect::<Result<Vec<_>, Error>>()?;
        let mut counts: HashMap<vk::DescriptorType, u32> = HashMap::new();
        let mut max_sets = 0;
        for (i, (pass, list)) in plan.passes.iter().zip(&per_pass).enumerate() {
            for d in list {
                *counts.entry(d.ty).or_default() += d.count;
            }
            max_sets += self.pass_pipeline(&keys[i], pass)?.set_layouts.len() as u32;
        }
        let sizes: Vec<vk::DescriptorPoolSize> = counts
            .iter()
            .map(|(&ty, &n)| vk::DescriptorPoolSize::default().ty(ty).descriptor_count(n))
            .collect();
        let mut sets: Vec<Vec<vk::DescriptorSet>> = Vec::new();
        if max_sets > 0 && !sizes.is_empty() {
            let info = vk::DescriptorPoolCreateInfo::default()
                .max_sets(max_sets)
                .pool_sizes(&sizes);
            // SAFETY: valid device and info.
            frame.descriptor_pool = unsafe { device.create_descriptor_pool(&info, None) }
                .map_err(vk("vkCreateDescriptorPool"))?;
        }
        for (i, pass) in plan.passes.iter().enumerate() {
            let layouts = &self.pass_pipeline(&keys[i], pass)?.set_layouts;
            if layouts.is_empty() {
                sets.push(Vec::new());
                continue;
            }
            let info = vk::DescriptorSetAllocateInfo::default()
                .descriptor_pool(frame.descriptor_pool)
                .set_layouts(layouts);
            // SAFETY: the pool has room for every set of the plan.
            sets.push(
                unsafe { device.allocate_descriptor_sets(&info) }
                    .map_err(vk("vkAllocateDescriptorSets"))?,
            );
        }
        enum Info {
            Buffer(vk::DescriptorBufferInfo),
            Images(Vec<vk::DescriptorImageInfo>),
        }
        let buffer = |buf: &frame::Buffer| {
            Info::Buffer(
                vk::DescriptorBufferInfo::default()
                    .buffer(buf.buffer)
                    .offset(0)
                    .range(vk::WHOLE_SIZE),
            )
        };
        let mut infos = Vec::new();
        for ((pass, pass_sets), list) in plan.passes.iter().zip(&sets).zip(&per_pass) {
            for d in list {
                let missing = |what: String| {
                    Error::Shader(format!(
                        "set {} binding {} of pass `{}` needs {what}, which the frame does not have",
                        d.set, d.binding, pass.name
                    ))
                };
                // The image view and layout of a plan binding that names an image.
                let image = |r: Resource| -> Result<vk::DescriptorImageInfo, Error> {
                    let image = bound
                        .images
                        .get(&r)
                        .ok_or_else(|| missing(format!("{r:?}")))?;
                    let b = d.plan.ok_or_else(|| missing(format!("{r:?}")))?;
                    let layout = Use::of_binding(b)?
                        .ok_or_else(|| missing(format!("{r:?}")))?
                        .layout;
                    Ok(vk::DescriptorImageInfo::default()
                        .image_view(image.view)
                        .image_layout(layout))
                };
                let info = match d.content {
                    SlotContent::Plan(Resource::Frame) => buffer(&bound.uniform),
                    SlotContent::Plan(Resource::Stats) => buffer(&bound.stats),
                    SlotContent::Plan(Resource::NoiseSampler) => Info::Images(vec![
                        vk::DescriptorImageInfo::default().sampler(frame.sampler),
                    ]),
                    SlotContent::Plan(r) => Info::Images(vec![image(r)?]),
                    SlotContent::CombinedWithSampler(r) => {
                        let sampler = if r.filterable() {
                            frame.sampler
                        } else {
                            frame.nearest_sampler
                        };
                        Info::Images(vec![image(r)?.sampler(sampler)])
                    }
                    SlotContent::SamplerArray(n) => Info::Images(vec![
                        vk::DescriptorImageInfo::default()
                            .sampler(frame.sampler);
                        n as usize
                    ]),
                    SlotContent::SamplerIndices(_) => buffer(
                        bound
                            .indices
                            .as_ref()
                            .ok_or_else(|| missing("a sampler index buffer".into()))?,
                    ),
                };
                let set = *pass_sets
                    .get(d.set as usize)
                    .ok_or_else(|| missing(format!("descriptor set {}", d.set)))?;
                infos.push((set, d.binding, d.ty, info));
            }
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
        Ok(sets)
    }

    /// The time of every pass from the frame's timestamp queries (all complete: the caller
    /// waited for the fence).
    fn timestamps(&self, frame: &Frame, plan: &FramePlan) -> Result<Vec<PassTiming>, Error> {
        let mut ticks = vec![0u64; 2 * plan.passes.len()];
        // SAFETY: the pool has one query per entry of `ticks`, all written and complete.
        unsafe {
            self.gpu.device.get_query_pool_results(
                frame.query_pool,
                0,
                &mut ticks,
                vk::QueryResultFlags::TYPE_64 | vk::QueryResultFlags::WAIT,
            )
        }
        .map_err(vk("vkGetQueryPoolResults"))?;
        // Only the valid bits count, and the counter may wrap between the two stamps
        // (backend-wgpu subtracts with saturation instead; the same for all but a wrap).
        let bits = self.gpu.info.timestamp_bits;
        let mask = if bits >= 64 {
            u64::MAX
        } else {
            (1u64 << bits) - 1
        };
        let period_ns = self.gpu.info.timestamp_period;
        Ok(plan
            .passes
            .iter()
            .enumerate()
            .map(|(i, p)| PassTiming {
                pass: p.name.clone(),
                ms: (ticks[2 * i + 1].wrapping_sub(ticks[2 * i]) & mask) as f64 * period_ns * 1e-6,
                source: "gpu-timestamp",
            })
            .collect())
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

    /// Ends the command buffer, submits it and waits for the fence.
    fn submit_and_wait(&self) -> Result<(), Error> {
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
            gpu.device
                .wait_for_fences(&[gpu.fence], true, u64::MAX)
                .map_err(vk("vkWaitForFences"))
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
                .any(|d| matches!(d.content, SlotContent::SamplerArray(n) if n > 1))
        {
            return Err(unsupported(
                "it indexes an array of samplers, and the device cannot (no shaderSampledImageArrayDynamicIndexing)".into(),
            ));
        }
        Ok(())
    }

    fn pass_pipeline(&self, key: &PipelineKey, pass: &Pass) -> Result<&PassPipeline, Error> {
        self.pipelines
            .get(key)
            .ok_or_else(|| Error::Shader(format!("no pipeline for pass `{}`", pass.name)))
    }

    /// Creates (once per variant and entry point, or per supplied module) the shader module,
    /// the descriptor set layouts (from the plan's bindings or the module's slots) and the
    /// compute pipeline of a pass. Returns its key.
    fn pipeline(
        &mut self,
        plan: &FramePlan,
        pass: &Pass,
        shader: Option<&PassShader>,
    ) -> Result<PipelineKey, Error> {
        let key = PipelineKey::of(plan, pass, shader);
        if self.pipelines.contains_key(&key) {
            return Ok(key);
        }
        let list = descriptors(pass, shader.map(|s| &s.slots[..]))?;
        self.check_limits(pass, &list)?;
        let device = &self.gpu.device;
        let p = match shader {
            None => {
                let module = match self.modules.get(&plan.spv_file) {
                    Some(&m) => m,
                    None => {
                        let m = shader_module(device, &plan.spv_file)?;
                        self.modules.insert(plan.spv_file.clone(), m);
                        m
                    }
                };
                PassPipeline::new(device, module, &pass.entry_point, &list)?
            }
            Some(s) => {
                // The pipeline keeps what it needs; the module can go right away.
                let module = module_from_words(device, &s.spirv)?;
                let p = PassPipeline::new(device, module, &s.entry, &list);
                // SAFETY: only the pipeline creation used the module.
                unsafe { device.destroy_shader_module(module, None) };
                p?
            }
        };
        self.pipelines.insert(key.clone(), p);
        Ok(key)
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
        let mut frame = Frame::default();
        let buffer = frame
            .buffer(
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
        frame.destroy(&renderer.gpu.device, &mut renderer.gpu.allocator);
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
