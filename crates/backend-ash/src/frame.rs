//! The resources of one frame (created per render, like backend-wgpu does, and destroyed when
//! the frame has been read back) and the barrier tracker that orders their uses.

use std::collections::HashMap;

use ash::vk;
use gpu_allocator::{
    MemoryLocation,
    vulkan::{Allocation, AllocationCreateDesc, AllocationScheme, Allocator},
};
use stratus_shaders::{Resource, plan::Binding};

use crate::error::{Error, memory, vk};

/// Every image the frame creates, with its name in messages.
pub(crate) const IMAGES: [(Resource, &str); 7] = [
    (Resource::Shape, "shape noise"),
    (Resource::Detail, "detail noise"),
    (Resource::Weather, "weather map"),
    (Resource::Curl, "curl noise"),
    (Resource::Cloud, "cloud"),
    (Resource::Depth, "depth"),
    (Resource::Image, "display"),
];

/// Whether `resource` is a noise texture (uploaded once per frame and only sampled).
pub(crate) fn is_noise(resource: Resource) -> bool {
    matches!(
        resource,
        Resource::Shape | Resource::Detail | Resource::Weather | Resource::Curl
    )
}

/// The usage an image resource is created with and the format features that needs. Noise is
/// uploaded and sampled (linearly, where the plan says it is filterable); the frame's images
/// are written as storage images, sampled by a later pass and copied out, as in backend-wgpu.
pub(crate) fn image_needs(resource: Resource) -> (vk::ImageUsageFlags, vk::FormatFeatureFlags) {
    let filter = if resource.filterable() {
        vk::FormatFeatureFlags::SAMPLED_IMAGE_FILTER_LINEAR
    } else {
        vk::FormatFeatureFlags::empty()
    };
    if is_noise(resource) {
        (
            vk::ImageUsageFlags::SAMPLED | vk::ImageUsageFlags::TRANSFER_DST,
            vk::FormatFeatureFlags::SAMPLED_IMAGE | vk::FormatFeatureFlags::TRANSFER_DST | filter,
        )
    } else {
        (
            vk::ImageUsageFlags::STORAGE
                | vk::ImageUsageFlags::SAMPLED
                | vk::ImageUsageFlags::TRANSFER_SRC,
            vk::FormatFeatureFlags::STORAGE_IMAGE
                | vk::FormatFeatureFlags::SAMPLED_IMAGE
                | vk::FormatFeatureFlags::TRANSFER_SRC,
        )
    }
}

/// The Vulkan format for a WGSL texel format.
pub(crate) fn vk_format(wgsl: &str) -> Option<vk::Format> {
    Some(match wgsl {
        "rgba8unorm" => vk::Format::R8G8B8A8_UNORM,
        "rgba32float" => vk::Format::R32G32B32A32_SFLOAT,
        "r32float" => vk::Format::R32_SFLOAT,
        "rgba16float" => vk::Format::R16G16B16A16_SFLOAT,
        _ => return None,
    })
}

/// Bytes per texel of a format the frame reads back.
pub(crate) fn texel_size(format: vk::Format) -> u64 {
    match format {
        vk::Format::R32G32B32A32_SFLOAT => 16,
        vk::Format::R16G16B16A16_SFLOAT => 8,
        _ => 4,
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

/// An image of the frame with its view.
#[derive(Clone, Copy)]
pub(crate) struct Image {
    pub image: vk::Image,
    pub view: vk::ImageView,
    pub format: vk::Format,
    pub extent: vk::Extent3D,
}

/// The objects of one frame. Everything is destroyed by [`Frame::destroy`], whatever step
/// failed; destroying null handles is a no-op.
#[derive(Default)]
pub(crate) struct Frame {
    buffers: Vec<(vk::Buffer, Allocation)>,
    images: Vec<(vk::Image, Allocation)>,
    views: Vec<vk::ImageView>,
    pub sampler: vk::Sampler,
    /// A nearest-filtering twin of `sampler`, for supplied modules that read non-filterable
    /// images through combined image samplers (null otherwise).
    pub nearest_sampler: vk::Sampler,
    pub descriptor_pool: vk::DescriptorPool,
    pub query_pool: vk::QueryPool,
}

/// A buffer of the frame: its handle and where its allocation is kept.
#[derive(Clone, Copy)]
pub(crate) struct Buffer {
    pub buffer: vk::Buffer,
    pub size: u64,
    index: usize,
}

impl Frame {
    /// Creates a buffer with memory from `location`.
    pub fn buffer(
        &mut self,
        device: &ash::Device,
        allocator: &mut Allocator,
        name: &str,
        size: u64,
        usage: vk::BufferUsageFlags,
        location: MemoryLocation,
    ) -> Result<Buffer, Error> {
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
        self.buffers.push((buffer, allocation));
        bound.map_err(vk("vkBindBufferMemory"))?;
        Ok(Buffer {
            buffer,
            size,
            index: self.buffers.len() - 1,
        })
    }

    /// The mapped bytes of a host-visible buffer.
    pub fn mapped(&mut self, buffer: Buffer) -> Result<&mut [u8], Error> {
        let size = buffer.size as usize;
        self.buffers[buffer.index]
            .1
            .mapped_slice_mut()
            .map(|s| &mut s[..size])
            .ok_or_else(|| Error::Memory {
                what: "a host-visible buffer".into(),
                message: "its memory is not mapped".into(),
            })
    }

    /// Creates an image (optimal tiling, one mip level) and a view of all of it.
    #[allow(clippy::too_many_arguments)]
    pub fn image(
        &mut self,
        device: &ash::Device,
        allocator: &mut Allocator,
        name: &str,
        view_type: vk::ImageViewType,
        format: vk::Format,
        extent: vk::Extent3D,
        usage: vk::ImageUsageFlags,
    ) -> Result<Image, Error> {
        let image_type = if view_type == vk::ImageViewType::TYPE_3D {
            vk::ImageType::TYPE_3D
        } else {
            vk::ImageType::TYPE_2D
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
                // SAFETY: not bound or used yet.
                unsafe { device.destroy_image(image, None) };
                return Err(e);
            }
        };
        // SAFETY: the allocation satisfies the requirements (gpu-allocator's contract).
        let bound =
            unsafe { device.bind_image_memory(image, allocation.memory(), allocation.offset()) };
        self.images.push((image, allocation));
        bound.map_err(vk("vkBindImageMemory"))?;
        let view_info = vk::ImageViewCreateInfo::default()
            .image(image)
            .view_type(view_type)
            .format(format)
            .subresource_range(COLOR);
        // SAFETY: the image is bound to memory; the view matches its type and format.
        let view = unsafe { device.create_image_view(&view_info, None) }
            .map_err(vk("vkCreateImageView"))?;
        self.views.push(view);
        Ok(Image {
            image,
            view,
            format,
            extent,
        })
    }

    /// Destroys every object and frees every allocation. The caller has waited for the GPU.
    pub fn destroy(&mut self, device: &ash::Device, allocator: &mut Allocator) {
        // SAFETY: the GPU no longer uses the frame (the caller waited); each object is
        // destroyed once (the vectors are drained, the handles reset).
        unsafe {
            device.destroy_query_pool(std::mem::take(&mut self.query_pool), None);
            // Frees the descriptor sets too.
            device.destroy_descriptor_pool(std::mem::take(&mut self.descriptor_pool), None);
            device.destroy_sampler(std::mem::take(&mut self.sampler), None);
            device.destroy_sampler(std::mem::take(&mut self.nearest_sampler), None);
            for view in self.views.drain(..) {
                device.destroy_image_view(view, None);
            }
            for (image, allocation) in self.images.drain(..) {
                device.destroy_image(image, None);
                // A failure here is a bookkeeping bug in gpu-allocator; nothing to act on.
                let _ = allocator.free(allocation);
            }
            for (buffer, allocation) in self.buffers.drain(..) {
                device.destroy_buffer(buffer, None);
                let _ = allocator.free(allocation);
            }
        }
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

    /// How a compute pass uses what `binding` names, from the manifest's reflection; `None`
    /// where no barrier is ever needed (the uniform block is written by the host before the
    /// submit, which makes it visible; samplers have no memory).
    pub fn of_binding(b: &Binding) -> Result<Option<Self>, Error> {
        let stage = vk::PipelineStageFlags::COMPUTE_SHADER;
        let (access, writes) = match b.info.access.as_deref() {
            Some("read") | None => (vk::AccessFlags::SHADER_READ, false),
            Some("write") => (vk::AccessFlags::SHADER_WRITE, true),
            Some("read-write") => (
                vk::AccessFlags::SHADER_READ | vk::AccessFlags::SHADER_WRITE,
                true,
            ),
            Some(other) => {
                return Err(Error::Shader(format!(
                    "binding `{}` has access `{other}`, which the ash backend does not know",
                    b.info.name
                )));
            }
        };
        Ok(match b.info.kind.as_str() {
            "uniform-buffer" | "sampler" => None,
            "sampled-texture" => Some(Self {
                stage,
                access: vk::AccessFlags::SHADER_READ,
                layout: vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL,
                writes: false,
            }),
            "storage-texture" => Some(Self {
                stage,
                access,
                layout: vk::ImageLayout::GENERAL,
                writes,
            }),
            "storage-buffer" => Some(Self {
                stage,
                access,
                layout: vk::ImageLayout::UNDEFINED,
                writes,
            }),
            other => {
                return Err(Error::Shader(format!(
                    "binding `{}` has kind `{other}`, which the ash backend cannot bind",
                    b.info.name
                )));
            }
        })
    }
}

#[derive(Clone, Copy)]
enum Target {
    Image(vk::Image),
    Buffer(vk::Buffer),
}

/// The last use of every image and GPU buffer of the frame. [`Tracker::barrier`] records the
/// one pipeline barrier that makes a set of new uses safe (memory dependencies after writes,
/// execution dependencies before overwriting what was read, layout transitions).
///
/// backend-wgpu gets this from wgpu's own tracking; here the plan's reflection (kind and
/// access of every binding) says what each pass does, so the barriers follow the plan.
#[derive(Default)]
pub(crate) struct Tracker {
    states: HashMap<Resource, (Target, Use)>,
}

impl Tracker {
    pub fn add_image(&mut self, resource: Resource, image: vk::Image, state: Use) {
        self.states.insert(resource, (Target::Image(image), state));
    }

    pub fn add_buffer(&mut self, resource: Resource, buffer: vk::Buffer, state: Use) {
        self.states
            .insert(resource, (Target::Buffer(buffer), state));
    }

    /// Records one barrier before the uses `wants` (untracked resources are skipped).
    pub fn barrier(
        &mut self,
        device: &ash::Device,
        cb: vk::CommandBuffer,
        wants: &[(Resource, Use)],
    ) {
        let mut src = vk::PipelineStageFlags::empty();
        let mut dst = vk::PipelineStageFlags::empty();
        let mut images = Vec::new();
        let mut buffers = Vec::new();
        for &(resource, want) in wants {
            let Some((target, have)) = self.states.get_mut(&resource) else {
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
                        .subresource_range(COLOR),
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
