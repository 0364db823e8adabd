//! GPU objects of the frame graph's resources (buffers, images and their views, created with
//! memory from the allocator, destroyed one by one when a new plan changes them), the graph's
//! formats and usages in Vulkan's terms, and the barrier tracker that orders their uses.
//!
//! The renderer's side of it lives here too: making a plan's resources (and dropping those a
//! new plan changes), uploading the noise, the device limits a pass must fit, and reading
//! results back (as wgpu's `resources.rs`).

use crate::*;

use std::collections::HashMap;

use ash::vk;
use gpu_allocator::{
    MemoryLocation,
    vulkan::{Allocation, AllocationCreateDesc, AllocationScheme, Allocator},
};
use stratus_graph::{
    desc::TexelFormat,
    manifest::{Access, BindingKind, Dimension},
    plan::{Binding, Usage},
};

use crate::error::{Error, memory, vk};

/// The Vulkan format of a graph format.
pub(crate) fn vk_format(f: TexelFormat) -> vk::Format {
    match f {
        TexelFormat::Rgba8Unorm => vk::Format::R8G8B8A8_UNORM,
        TexelFormat::Rgba16Float => vk::Format::R16G16B16A16_SFLOAT,
        TexelFormat::Rgba32Float => vk::Format::R32G32B32A32_SFLOAT,
        TexelFormat::R32Float => vk::Format::R32_SFLOAT,
        TexelFormat::Depth32Float => vk::Format::D32_SFLOAT,
    }
}

/// The image usage a resource is created with and the format features that needs, from what
/// the passes use it for. Colour images can also be copied out (readback on request).
pub(crate) fn image_needs(
    usage: Usage,
    f: TexelFormat,
) -> (vk::ImageUsageFlags, vk::FormatFeatureFlags) {
    let mut u = vk::ImageUsageFlags::empty();
    let mut need = vk::FormatFeatureFlags::empty();
    if usage.sampled {
        u |= vk::ImageUsageFlags::SAMPLED;
        need |= vk::FormatFeatureFlags::SAMPLED_IMAGE;
        if f.filterable() && usage.upload {
            need |= vk::FormatFeatureFlags::SAMPLED_IMAGE_FILTER_LINEAR;
        }
    }
    if usage.storage {
        u |= vk::ImageUsageFlags::STORAGE;
        need |= vk::FormatFeatureFlags::STORAGE_IMAGE;
    }
    if usage.color {
        u |= vk::ImageUsageFlags::COLOR_ATTACHMENT;
        need |= vk::FormatFeatureFlags::COLOR_ATTACHMENT;
    }
    if usage.depth {
        u |= vk::ImageUsageFlags::DEPTH_STENCIL_ATTACHMENT;
        need |= vk::FormatFeatureFlags::DEPTH_STENCIL_ATTACHMENT;
    }
    if usage.upload {
        u |= vk::ImageUsageFlags::TRANSFER_DST;
        need |= vk::FormatFeatureFlags::TRANSFER_DST;
    }
    if !f.is_depth() {
        u |= vk::ImageUsageFlags::TRANSFER_SRC;
        need |= vk::FormatFeatureFlags::TRANSFER_SRC;
    }
    (u, need)
}

/// The view type of a texture of this dimension.
pub(crate) fn view_type(d: Dimension) -> vk::ImageViewType {
    match d {
        Dimension::D1 => vk::ImageViewType::TYPE_1D,
        Dimension::D3 => vk::ImageViewType::TYPE_3D,
        Dimension::D2 | Dimension::Cube => vk::ImageViewType::TYPE_2D,
    }
}

/// The aspect of a format's images.
pub(crate) fn aspect(f: vk::Format) -> vk::ImageAspectFlags {
    if f == vk::Format::D32_SFLOAT {
        vk::ImageAspectFlags::DEPTH
    } else {
        vk::ImageAspectFlags::COLOR
    }
}

pub(crate) const COLOR: vk::ImageSubresourceRange = vk::ImageSubresourceRange {
    aspect_mask: vk::ImageAspectFlags::COLOR,
    base_mip_level: 0,
    level_count: 1,
    base_array_layer: 0,
    layer_count: 1,
};

pub(crate) const COLOR_LAYER: vk::ImageSubresourceLayers = vk::ImageSubresourceLayers {
    aspect_mask: vk::ImageAspectFlags::COLOR,
    mip_level: 0,
    base_array_layer: 0,
    layer_count: 1,
};

/// A buffer with its memory.
pub(crate) struct GpuBuffer {
    pub buffer: vk::Buffer,
    pub size: u64,
    allocation: Option<Allocation>,
}

impl GpuBuffer {
    /// Creates a buffer with memory from `location`.
    pub fn new(
        device: &ash::Device,
        allocator: &mut Allocator,
        name: &str,
        size: u64,
        usage: vk::BufferUsageFlags,
        location: MemoryLocation,
    ) -> Result<Self, Error> {
        let info = vk::BufferCreateInfo::default()
            .size(size)
            .usage(usage)
            .sharing_mode(vk::SharingMode::EXCLUSIVE);
        // SAFETY: valid device and info.
        let buffer = unsafe { device.create_buffer(&info, None) }.map_err(vk("vkCreateBuffer"))?;
        // SAFETY: `buffer` was just created from `device`.
        let requirements = unsafe { device.get_buffer_memory_requirements(buffer) };
        let allocation = allocator
            .allocate(&AllocationCreateDesc {
                name,
                requirements,
                location,
                linear: true,
                allocation_scheme: AllocationScheme::GpuAllocatorManaged,
            })
            .map_err(memory(name));
        let allocation = match allocation {
            Ok(a) => a,
            Err(e) => {
                // SAFETY: not bound or used yet.
                unsafe { device.destroy_buffer(buffer, None) };
                return Err(e);
            }
        };
        // SAFETY: the allocation satisfies the requirements (gpu-allocator's contract).
        let bound =
            unsafe { device.bind_buffer_memory(buffer, allocation.memory(), allocation.offset()) };
        let mut made = Self {
            buffer,
            size,
            allocation: Some(allocation),
        };
        if let Err(e) = bound {
            made.destroy(device, allocator);
            return Err(vk("vkBindBufferMemory")(e));
        }
        Ok(made)
    }

    /// The mapped bytes of a host-visible buffer.
    pub fn mapped(&mut self) -> Result<&mut [u8], Error> {
        let size = self.size as usize;
        self.allocation
            .as_mut()
            .and_then(|a| a.mapped_slice_mut())
            .map(|s| &mut s[..size])
            .ok_or_else(|| Error::Memory {
                what: "a host-visible buffer".into(),
                message: "its memory is not mapped".into(),
            })
    }

    /// Destroys the buffer and frees its memory. The caller has waited for the GPU.
    pub fn destroy(&mut self, device: &ash::Device, allocator: &mut Allocator) {
        // SAFETY: the GPU no longer uses it (the caller waited); destroyed once (taken).
        unsafe { device.destroy_buffer(std::mem::take(&mut self.buffer), None) };
        if let Some(a) = self.allocation.take() {
            // A failure here is a bookkeeping bug in gpu-allocator; nothing to act on.
            let _ = allocator.free(a);
        }
    }
}

/// An image (optimal tiling, one mip level) with a view of all of it.
pub(crate) struct GpuImage {
    pub image: vk::Image,
    pub view: vk::ImageView,
    pub format: vk::Format,
    pub extent: vk::Extent3D,
    allocation: Option<Allocation>,
}

impl GpuImage {
    /// Creates the image, its memory and its view.
    pub fn new(
        device: &ash::Device,
        allocator: &mut Allocator,
        name: &str,
        view_type: vk::ImageViewType,
        format: vk::Format,
        extent: vk::Extent3D,
        usage: vk::ImageUsageFlags,
    ) -> Result<Self, Error> {
        let image_type = match view_type {
            vk::ImageViewType::TYPE_3D => vk::ImageType::TYPE_3D,
            vk::ImageViewType::TYPE_1D => vk::ImageType::TYPE_1D,
            _ => vk::ImageType::TYPE_2D,
        };
        let info = vk::ImageCreateInfo::default()
            .image_type(image_type)
            .format(format)
            .extent(extent)
            .mip_levels(1)
            .array_layers(1)
            .samples(vk::SampleCountFlags::TYPE_1)
            .tiling(vk::ImageTiling::OPTIMAL)
            .usage(usage)
            .sharing_mode(vk::SharingMode::EXCLUSIVE)
            .initial_layout(vk::ImageLayout::UNDEFINED);
        // SAFETY: valid device and info.
        let image = unsafe { device.create_image(&info, None) }.map_err(vk("vkCreateImage"))?;
        let mut made = Self {
            image,
            view: vk::ImageView::null(),
            format,
            extent,
            allocation: None,
        };
        // SAFETY: `image` was just created from `device`.
        let requirements = unsafe { device.get_image_memory_requirements(image) };
        let allocation = allocator
            .allocate(&AllocationCreateDesc {
                name,
                requirements,
                location: MemoryLocation::GpuOnly,
                linear: false,
                allocation_scheme: AllocationScheme::GpuAllocatorManaged,
            })
            .map_err(memory(name));
        let allocation = match allocation {
            Ok(a) => a,
            Err(e) => {
                made.destroy(device, allocator);
                return Err(e);
            }
        };
        // SAFETY: the allocation satisfies the requirements (gpu-allocator's contract).
        let bound =
            unsafe { device.bind_image_memory(image, allocation.memory(), allocation.offset()) };
        made.allocation = Some(allocation);
        if let Err(e) = bound {
            made.destroy(device, allocator);
            return Err(vk("vkBindImageMemory")(e));
        }
        let view_info = vk::ImageViewCreateInfo::default()
            .image(image)
            .view_type(view_type)
            .format(format)
            .subresource_range(range(format));
        // SAFETY: the image is bound to memory; the view matches its type and format.
        match unsafe { device.create_image_view(&view_info, None) } {
            Ok(view) => made.view = view,
            Err(e) => {
                made.destroy(device, allocator);
                return Err(vk("vkCreateImageView")(e));
            }
        }
        Ok(made)
    }

    /// Destroys the view and image and frees the memory. The caller has waited for the GPU.
    pub fn destroy(&mut self, device: &ash::Device, allocator: &mut Allocator) {
        // SAFETY: the GPU no longer uses them; each is destroyed once (taken).
        unsafe {
            device.destroy_image_view(std::mem::take(&mut self.view), None);
            device.destroy_image(std::mem::take(&mut self.image), None);
        }
        if let Some(a) = self.allocation.take() {
            let _ = allocator.free(a);
        }
    }
}

/// The whole of an image of this format.
pub(crate) fn range(format: vk::Format) -> vk::ImageSubresourceRange {
    vk::ImageSubresourceRange {
        aspect_mask: aspect(format),
        ..COLOR
    }
}

/// How a resource is used: pipeline stage, access, image layout, and whether it writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Use {
    pub stage: vk::PipelineStageFlags,
    pub access: vk::AccessFlags,
    pub layout: vk::ImageLayout,
    pub writes: bool,
}

impl Use {
    /// Not used yet (a new image's contents are undefined).
    pub const NEW: Self = Self {
        stage: vk::PipelineStageFlags::TOP_OF_PIPE,
        access: vk::AccessFlags::empty(),
        layout: vk::ImageLayout::UNDEFINED,
        writes: false,
    };
    /// Destination of a copy.
    pub const COPY_DST: Self = Self {
        stage: vk::PipelineStageFlags::TRANSFER,
        access: vk::AccessFlags::TRANSFER_WRITE,
        layout: vk::ImageLayout::TRANSFER_DST_OPTIMAL,
        writes: true,
    };
    /// Source of a copy.
    pub const COPY_SRC: Self = Self {
        stage: vk::PipelineStageFlags::TRANSFER,
        access: vk::AccessFlags::TRANSFER_READ,
        layout: vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
        writes: false,
    };

    /// A raster pass's colour target (read too where it loads or blends).
    pub const COLOR_TARGET: Self = Self {
        stage: vk::PipelineStageFlags::COLOR_ATTACHMENT_OUTPUT,
        access: vk::AccessFlags::from_raw(
            vk::AccessFlags::COLOR_ATTACHMENT_READ.as_raw()
                | vk::AccessFlags::COLOR_ATTACHMENT_WRITE.as_raw(),
        ),
        layout: vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL,
        writes: true,
    };
    /// A raster pass's depth target.
    pub const DEPTH_TARGET: Self = Self {
        stage: vk::PipelineStageFlags::from_raw(
            vk::PipelineStageFlags::EARLY_FRAGMENT_TESTS.as_raw()
                | vk::PipelineStageFlags::LATE_FRAGMENT_TESTS.as_raw(),
        ),
        access: vk::AccessFlags::from_raw(
            vk::AccessFlags::DEPTH_STENCIL_ATTACHMENT_READ.as_raw()
                | vk::AccessFlags::DEPTH_STENCIL_ATTACHMENT_WRITE.as_raw(),
        ),
        layout: vk::ImageLayout::DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
        writes: true,
    };

    /// How a pass whose shaders run at `stage` uses what `binding` names, from the manifest's
    /// reflection; `None` where no barrier is ever needed (the uniform block is written by the
    /// host before the submit, which makes it visible; samplers have no memory).
    pub fn of_binding(b: &Binding, stage: vk::PipelineStageFlags) -> Option<Self> {
        let (access, writes) = match b.info.access {
            Some(Access::Read) | None => (vk::AccessFlags::SHADER_READ, false),
            Some(Access::Write) => (vk::AccessFlags::SHADER_WRITE, true),
            Some(Access::ReadWrite) => (
                vk::AccessFlags::SHADER_READ | vk::AccessFlags::SHADER_WRITE,
                true,
            ),
        };
        match b.info.kind {
            BindingKind::UniformBuffer | BindingKind::Sampler | BindingKind::Other => None,
            BindingKind::SampledTexture => Some(Self {
                stage,
                access: vk::AccessFlags::SHADER_READ,
                layout: vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL,
                writes: false,
            }),
            BindingKind::StorageTexture => Some(Self {
                stage,
                access,
                layout: vk::ImageLayout::GENERAL,
                writes,
            }),
            BindingKind::StorageBuffer => Some(Self {
                stage,
                access,
                layout: vk::ImageLayout::UNDEFINED,
                writes,
            }),
        }
    }
}

#[derive(Clone, Copy)]
enum Target {
    Image(vk::Image),
    Buffer(vk::Buffer),
}

/// What the tracker knows by: a resource's name and which half of a history pair (0 else).
pub(crate) type Key = (String, usize);

/// The last use of every image and GPU buffer. [`Tracker::barrier`] records the
/// one pipeline barrier that makes a set of new uses safe (memory dependencies after writes,
/// execution dependencies before overwriting what was read, layout transitions).
///
/// backend-wgpu gets this from wgpu's own tracking; here the plan's reflection (kind and
/// access of every binding) says what each pass does, so the barriers follow the plan.
#[derive(Default)]
pub(crate) struct Tracker {
    states: HashMap<Key, (Target, vk::ImageAspectFlags, Use)>,
}

impl Tracker {
    pub fn add_image(&mut self, key: Key, image: &GpuImage, state: Use) {
        self.states.insert(
            key,
            (Target::Image(image.image), aspect(image.format), state),
        );
    }

    pub fn add_buffer(&mut self, key: Key, buffer: vk::Buffer, state: Use) {
        self.states.insert(
            key,
            (Target::Buffer(buffer), vk::ImageAspectFlags::empty(), state),
        );
    }

    /// Forgets every resource called `name` (it was destroyed).
    pub fn remove(&mut self, name: &str) {
        self.states.retain(|(n, _), _| n != name);
    }

    /// Records one barrier before the uses `wants` (untracked resources are skipped).
    pub fn barrier(&mut self, device: &ash::Device, cb: vk::CommandBuffer, wants: &[(Key, Use)]) {
        let mut src = vk::PipelineStageFlags::empty();
        let mut dst = vk::PipelineStageFlags::empty();
        let mut images = Vec::new();
        let mut buffers = Vec::new();
        for (key, want) in wants {
            let want = *want;
            let Some((target, aspect_mask, have)) = self.states.get_mut(key) else {
                continue;
            };
            let relayout = matches!(target, Target::Image(_)) && have.layout != want.layout;
            let read_after_read = !(have.writes || want.writes || relayout);
            if read_after_read && have.stage.contains(want.stage) {
                // Read after read in the same layout, at stages already ordered after the last
                // write or layout transition: nothing to wait for.
                have.access |= want.access;
                continue;
            }
            // A read at a stage the last barrier did not reach (a vertex shader reading a
            // texture only compute passes have read since its upload) waits for the stages
            // that did, so that it chains to that barrier's write or layout transition.
            src |= have.stage;
            dst |= want.stage;
            // Only writes need to be made available; reads need just the execution order.
            let src_access = if have.writes {
                have.access
            } else {
                vk::AccessFlags::empty()
            };
            match *target {
                Target::Image(image) => images.push(
                    vk::ImageMemoryBarrier::default()
                        .src_access_mask(src_access)
                        .dst_access_mask(want.access)
                        .old_layout(have.layout)
                        .new_layout(want.layout)
                        .src_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
                        .dst_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
                        .image(image)
                        .subresource_range(vk::ImageSubresourceRange {
                            aspect_mask: *aspect_mask,
                            ..COLOR
                        }),
                ),
                Target::Buffer(buffer) => buffers.push(
                    vk::BufferMemoryBarrier::default()
                        .src_access_mask(src_access)
                        .dst_access_mask(want.access)
                        .src_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
                        .dst_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
                        .buffer(buffer)
                        .offset(0)
                        .size(vk::WHOLE_SIZE),
                ),
            }
            if read_after_read {
                // Its readers so far stay, for the barrier before the next write.
                have.stage |= want.stage;
                have.access |= want.access;
            } else {
                *have = want;
            }
        }
        if images.is_empty() && buffers.is_empty() {
            return;
        }
        // SAFETY: `cb` is recording; every handle is alive for the frame.
        unsafe {
            device.cmd_pipeline_barrier(
                cb,
                src,
                dst,
                vk::DependencyFlags::empty(),
                &[],
                &buffers,
                &images,
            );
        }
    }
}

// The renderer's resources: made when a plan needs them (and dropped when a new plan changes
// them), the noise uploaded, the device limits a pass must fit, results read back.

/// The GPU side of a resource of the plan.
pub(crate) struct Resource {
    /// What it was made from (kept while it serves the plan).
    pub(crate) made: Made,
    pub(crate) object: Object,
}

pub(crate) enum Object {
    /// The renderer's one uniform block.
    Uniform,
    Buffer(GpuBuffer),
    /// One image, or two for a history pair.
    Images(Vec<GpuImage>),
    Sampler(vk::Sampler),
}

/// As backend-wgpu's: one mip level, the shared LOD clamp, no anisotropy.
pub(crate) fn sampler_info(s: stratus_graph::plan::SamplerDesc) -> vk::SamplerCreateInfo<'static> {
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

impl Renderer {
    /// Destroys every resource (the GPU is idle).
    pub(crate) fn drop_resources(&mut self) {
        let names: Vec<String> = self.resources.keys().cloned().collect();
        for name in names {
            self.drop_resource(&name);
        }
        self.noise = None;
    }

    pub(crate) fn drop_resource(&mut self, name: &str) {
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

    pub(crate) fn create_resource(&mut self, made: &Made) -> Result<Object, Error> {
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

    /// Uploads what [`uploads`] lists through one staging buffer, in one submission.
    pub(crate) fn upload(&mut self, frame: &FrameInput<'_>, all: bool) -> Result<(), Error> {
        let mut list = Vec::new();
        let mut size = 0u64;
        for (r, _, data) in uploads(frame, all).map_err(Error::Shader)? {
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

    /// Records the copies a frame's readback asks for into persistent host-visible buffers
    /// (rows tightly packed: Vulkan, unlike WebGPU, needs no 256-byte row alignment).
    pub(crate) fn copy_readbacks(
        &mut self,
        frame: &FrameInput<'_>,
    ) -> Result<Vec<(usize, Readout)>, Error> {
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

    /// The image of texture resource `index` a frame of this parity writes (the current half
    /// of a history pair).
    pub(crate) fn target(
        &self,
        plan: &FramePlan,
        index: usize,
        parity: u64,
    ) -> Result<&GpuImage, Error> {
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
    pub(crate) fn key(&self, plan: &FramePlan, index: usize, previous: bool) -> Key {
        let r = &plan.resources[index];
        let half = if r.lifetime == Lifetime::History {
            history_half(self.frames.frame(), previous)
        } else {
            0
        };
        (r.name.clone(), half)
    }

    /// Fails with [`Error::Unsupported`] where the descriptors need more samplers per stage
    /// than the device allows, or index an array of samplers that the device cannot index:
    /// creating such a pipeline is invalid, and crashes some drivers (lavapipe).
    pub(crate) fn check_limits(&self, pass: &Pass, list: &[Descriptor<'_>]) -> Result<(), Error> {
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
}
