//! GPU objects of the frame graph's resources (buffers, images and their views, created with
//! memory from the allocator, destroyed one by one when a new plan changes them), the graph's
//! formats and usages in Vulkan's terms, and the barrier tracker that orders their uses.

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
            if !(have.writes || want.writes || relayout) {
                // Read after read in the same layout: nothing to wait for.
                have.stage |= want.stage;
                have.access |= want.access;
                continue;
            }
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
            *have = want;
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
