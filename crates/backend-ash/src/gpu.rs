//! The Vulkan instance, the validation messenger, the chosen device with its compute queue,
//! the command pool, the fence and the memory allocator: everything that lives as long as the
//! renderer, created in [`Gpu::new`] and destroyed in reverse order in [`Gpu::destroy`].
//!
//! The renderer's side of it lives here too: beginning its command buffer, submitting and
//! waiting, reading the timestamps, and tearing everything down in order (as wgpu's `gpu.rs`).

use crate::*;

use std::{
    ffi::{CStr, c_char, c_void},
    mem::ManuallyDrop,
    sync::{Arc, Mutex},
};

use ash::vk;
use gpu_allocator::vulkan::{Allocator, AllocatorCreateDesc};
use stratus_graph::{
    backend::{DeviceClass, best_device, describe_device},
    desc::TexelFormat,
};

use crate::error::{Error, vk};

/// A format the frame needs and the features it needs of it, with the resource it is for.
pub(crate) struct FormatNeed {
    pub resource: String,
    pub format: TexelFormat,
    pub vk_format: vk::Format,
    pub features: vk::FormatFeatureFlags,
}

const VALIDATION_LAYER: &CStr = c"VK_LAYER_KHRONOS_validation";

/// The Vulkan version the renderer asks for: 1.1 has storage buffers in SPIR-V
/// (`SPV_KHR_storage_buffer_storage_class`, which naga's SPIR-V declares) and the transfer
/// format features in core.
pub(crate) const API_VERSION: u32 = vk::API_VERSION_1_1;

/// Validation messages (warnings and errors), shared with the messenger callback.
pub(crate) type Messages = Arc<Mutex<Vec<String>>>;

/// Records every warning and error the validation layer (or the loader) reports.
///
/// # Safety
/// Called by the Vulkan loader with `user_data` pointing at the `Mutex<Vec<String>>` of a
/// [`Messages`] that [`Gpu`] keeps alive until the instance is destroyed.
unsafe extern "system" fn on_message(
    severity: vk::DebugUtilsMessageSeverityFlagsEXT,
    kind: vk::DebugUtilsMessageTypeFlagsEXT,
    data: *const vk::DebugUtilsMessengerCallbackDataEXT<'_>,
    user_data: *mut c_void,
) -> vk::Bool32 {
    if data.is_null() || user_data.is_null() {
        return vk::FALSE;
    }
    // SAFETY: see the function's contract; the layer passes a valid callback data pointer.
    let (sink, data) = unsafe { (&*(user_data as *const Mutex<Vec<String>>), &*data) };
    // SAFETY: the strings are NUL-terminated or null, as the spec requires.
    let text = |s: Option<&CStr>| s.map(|s| s.to_string_lossy().into_owned());
    let id = text(unsafe { data.message_id_name_as_c_str() }).unwrap_or_default();
    let message = text(unsafe { data.message_as_c_str() }).unwrap_or_default();
    if let Ok(mut sink) = sink.lock() {
        sink.push(format!("{severity:?} {kind:?} [{id}] {message}"));
    }
    vk::FALSE
}

fn messenger_info(messages: &Messages) -> vk::DebugUtilsMessengerCreateInfoEXT<'static> {
    vk::DebugUtilsMessengerCreateInfoEXT::default()
        .message_severity(
            vk::DebugUtilsMessageSeverityFlagsEXT::WARNING
                | vk::DebugUtilsMessageSeverityFlagsEXT::ERROR,
        )
        .message_type(
            vk::DebugUtilsMessageTypeFlagsEXT::GENERAL
                | vk::DebugUtilsMessageTypeFlagsEXT::VALIDATION
                | vk::DebugUtilsMessageTypeFlagsEXT::PERFORMANCE,
        )
        .pfn_user_callback(Some(on_message))
        .user_data(Arc::as_ptr(messages) as *mut c_void)
}

/// What the renderer needs to know about the chosen device.
pub(crate) struct DeviceInfo {
    /// The device in words, as backend-wgpu writes it: `name (Vulkan, Cpu)`.
    pub name: String,
    /// Nanoseconds per timestamp tick.
    pub timestamp_period: f64,
    /// Valid bits of a timestamp on the queue; 0 where the queue has no timestamps.
    pub timestamp_bits: u32,
    /// `maxImageDimension2D`.
    pub max_image_2d: u32,
    /// `maxPerStageDescriptorSamplers`.
    pub max_stage_samplers: u32,
    /// Whether arrays of samplers may be indexed by dynamically uniform values
    /// (`shaderSampledImageArrayDynamicIndexing`; enabled when offered).
    pub sampler_array_indexing: bool,
    /// Bytes of the largest device-local memory heap.
    pub device_memory: u64,
}

/// Everything that lives as long as the renderer.
pub(crate) struct Gpu {
    _entry: ash::Entry,
    pub instance: ash::Instance,
    debug: Option<(ash::ext::debug_utils::Instance, vk::DebugUtilsMessengerEXT)>,
    pub device: ash::Device,
    pub queue: vk::Queue,
    pub command_pool: vk::CommandPool,
    pub command_buffer: vk::CommandBuffer,
    pub fence: vk::Fence,
    pub allocator: ManuallyDrop<Allocator>,
    pub info: DeviceInfo,
    /// Validation messages; kept alive until after `vkDestroyInstance` (the callback holds a
    /// pointer into it).
    pub messages: Messages,
    destroyed: bool,
}

/// Objects created so far in [`Gpu::new`], destroyed in reverse order if a later step fails.
#[derive(Default)]
struct Unwind {
    instance: Option<ash::Instance>,
    debug: Option<(ash::ext::debug_utils::Instance, vk::DebugUtilsMessengerEXT)>,
    device: Option<ash::Device>,
    command_pool: vk::CommandPool,
    fence: vk::Fence,
}

impl Drop for Unwind {
    fn drop(&mut self) {
        // SAFETY: every object was created from these parents and is not in use (nothing was
        // submitted); destroying a null handle is a no-op.
        unsafe {
            if let Some(device) = self.device.take() {
                device.destroy_fence(self.fence, None);
                device.destroy_command_pool(self.command_pool, None);
                device.destroy_device(None);
            }
            if let Some((utils, messenger)) = self.debug.take() {
                utils.destroy_debug_utils_messenger(messenger, None);
            }
            if let Some(instance) = self.instance.take() {
                instance.destroy_instance(None);
            }
        }
    }
}

/// The device class, as the shared ranking and description know it.
fn class_of(t: vk::PhysicalDeviceType) -> DeviceClass {
    match t {
        vk::PhysicalDeviceType::DISCRETE_GPU => DeviceClass::Discrete,
        vk::PhysicalDeviceType::INTEGRATED_GPU => DeviceClass::Integrated,
        vk::PhysicalDeviceType::VIRTUAL_GPU => DeviceClass::Virtual,
        vk::PhysicalDeviceType::CPU => DeviceClass::Cpu,
        _ => DeviceClass::Other,
    }
}

fn version(v: u32) -> String {
    format!("{}.{}", vk::api_version_major(v), vk::api_version_minor(v))
}

struct Candidate {
    physical: vk::PhysicalDevice,
    family: u32,
    info: DeviceInfo,
}

/// Whether `physical` can run the frame: Vulkan 1.1, a compute queue, and every image format
/// with the features the frame uses (see [`image_needs`]).
fn candidate(
    instance: &ash::Instance,
    physical: vk::PhysicalDevice,
    needs: &[FormatNeed],
) -> Result<Candidate, Error> {
    // SAFETY: `physical` was enumerated from `instance`.
    let props = unsafe { instance.get_physical_device_properties(physical) };
    let device_name = props
        .device_name_as_c_str()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|_| "(unnamed)".into());
    let name = describe_device(&device_name, "Vulkan", class_of(props.device_type));
    if props.api_version < API_VERSION {
        return Err(Error::NoDevice(format!(
            " ({name} implements Vulkan {}, {} is needed)",
            version(props.api_version),
            version(API_VERSION)
        )));
    }
    // SAFETY: as above.
    let families = unsafe { instance.get_physical_device_queue_family_properties(physical) };
    // Compute and raster passes share one queue: prefer such a family with timestamps.
    let usable = |f: &vk::QueueFamilyProperties| {
        f.queue_flags
            .contains(vk::QueueFlags::COMPUTE | vk::QueueFlags::GRAPHICS)
            && f.queue_count > 0
    };
    let family = families
        .iter()
        .position(|f| usable(f) && f.timestamp_valid_bits > 0)
        .or_else(|| families.iter().position(usable))
        .ok_or_else(|| {
            Error::NoDevice(format!(
                " ({name} has no queue for both compute and graphics)"
            ))
        })?;
    for need in needs {
        // SAFETY: as above.
        let have =
            unsafe { instance.get_physical_device_format_properties(physical, need.vk_format) }
                .optimal_tiling_features;
        if !have.contains(need.features) {
            return Err(Error::Format {
                device: name,
                format: need.format.wgsl().to_string(),
                vk_format: need.vk_format,
                missing: describe_features(need.features & !have),
                resource: need.resource.clone(),
            });
        }
    }
    // SAFETY: as above.
    let features = unsafe { instance.get_physical_device_features(physical) };
    // SAFETY: as above.
    let memory = unsafe { instance.get_physical_device_memory_properties(physical) };
    let device_memory = memory.memory_heaps[..memory.memory_heap_count as usize]
        .iter()
        .filter(|h| h.flags.contains(vk::MemoryHeapFlags::DEVICE_LOCAL))
        .map(|h| h.size)
        .max()
        .unwrap_or(0);
    Ok(Candidate {
        physical,
        family: family as u32,
        info: DeviceInfo {
            name,
            timestamp_period: f64::from(props.limits.timestamp_period),
            timestamp_bits: families[family].timestamp_valid_bits,
            max_image_2d: props.limits.max_image_dimension2_d,
            max_stage_samplers: props.limits.max_per_stage_descriptor_samplers,
            sampler_array_indexing: features.shader_sampled_image_array_dynamic_indexing
                == vk::TRUE,
            device_memory,
        },
    })
}

fn describe_features(missing: vk::FormatFeatureFlags) -> String {
    let words = [
        (vk::FormatFeatureFlags::STORAGE_IMAGE, "as a storage image"),
        (vk::FormatFeatureFlags::SAMPLED_IMAGE, "as a sampled image"),
        (
            vk::FormatFeatureFlags::SAMPLED_IMAGE_FILTER_LINEAR,
            "with linear filtering",
        ),
        (
            vk::FormatFeatureFlags::COLOR_ATTACHMENT,
            "as a colour target",
        ),
        (
            vk::FormatFeatureFlags::DEPTH_STENCIL_ATTACHMENT,
            "as a depth target",
        ),
        (vk::FormatFeatureFlags::TRANSFER_SRC, "as a copy source"),
        (
            vk::FormatFeatureFlags::TRANSFER_DST,
            "as a copy destination",
        ),
    ];
    let list: Vec<&str> = words
        .iter()
        .filter(|(f, _)| missing.contains(*f))
        .map(|(_, w)| *w)
        .collect();
    list.join(" or ")
}

fn has_extension(list: &[vk::ExtensionProperties], name: &CStr) -> bool {
    list.iter()
        .any(|e| e.extension_name_as_c_str().is_ok_and(|n| n == name))
}

impl Gpu {
    /// Loads Vulkan, creates the instance (with validation and its messenger when asked),
    /// picks a device and creates the device, queue, command pool, fence and allocator.
    pub fn new(validation: bool, needs: &[FormatNeed]) -> Result<Self, Error> {
        // SAFETY: loading the system's Vulkan loader runs its initialisers; nothing else
        // holds it.
        let entry = unsafe { ash::Entry::load() }.map_err(|e| Error::NoLoader(e.to_string()))?;
        // SAFETY: plain global query.
        let found = unsafe { entry.try_enumerate_instance_version() }
            .map_err(vk("vkEnumerateInstanceVersion"))?
            .unwrap_or(vk::API_VERSION_1_0);
        if found < API_VERSION {
            return Err(Error::LoaderVersion {
                found: version(found),
                needed: version(API_VERSION),
            });
        }

        let messages: Messages = Arc::default();
        let mut layers: Vec<*const c_char> = Vec::new();
        let mut extensions: Vec<*const c_char> = Vec::new();
        if validation {
            // SAFETY: plain global queries.
            let available = unsafe { entry.enumerate_instance_layer_properties() }
                .map_err(vk("vkEnumerateInstanceLayerProperties"))?;
            if !available
                .iter()
                .any(|l| l.layer_name_as_c_str().is_ok_and(|n| n == VALIDATION_LAYER))
            {
                return Err(Error::NoValidationLayer);
            }
            layers.push(VALIDATION_LAYER.as_ptr());
            let mut offered = unsafe { entry.enumerate_instance_extension_properties(None) }
                .map_err(vk("vkEnumerateInstanceExtensionProperties"))?;
            offered.extend(
                unsafe { entry.enumerate_instance_extension_properties(Some(VALIDATION_LAYER)) }
                    .map_err(vk("vkEnumerateInstanceExtensionProperties"))?,
            );
            for name in [
                ash::ext::debug_utils::NAME,
                ash::ext::validation_features::NAME,
            ] {
                if !has_extension(&offered, name) {
                    return Err(Error::NoValidationExtension(
                        name.to_string_lossy().into_owned(),
                    ));
                }
                extensions.push(name.as_ptr());
            }
        }

        let app = vk::ApplicationInfo::default()
            .application_name(c"stratus")
            .engine_name(c"stratus-backend-ash")
            .api_version(API_VERSION);
        // Synchronization validation is off by default in the layer; the tests rely on it to
        // prove the barriers between passes and copies are right.
        let enables = [vk::ValidationFeatureEnableEXT::SYNCHRONIZATION_VALIDATION];
        let mut features =
            vk::ValidationFeaturesEXT::default().enabled_validation_features(&enables);
        // Chained to the instance info, this messenger also hears vkCreateInstance and
        // vkDestroyInstance.
        let mut instance_messenger = messenger_info(&messages);
        let mut info = vk::InstanceCreateInfo::default()
            .application_info(&app)
            .enabled_layer_names(&layers)
            .enabled_extension_names(&extensions);
        if validation {
            info = info
                .push_next(&mut features)
                .push_next(&mut instance_messenger);
        }
        let mut unwind = Unwind::default();
        // SAFETY: every pointer in `info` outlives the call.
        let instance = unsafe { entry.create_instance(&info, None) }.map_err(|e| match e {
            // The loader says this when it found no driver at all.
            vk::Result::ERROR_INCOMPATIBLE_DRIVER => {
                Error::NoDevice(" (the Vulkan loader found no driver)".into())
            }
            result => Error::Vulkan {
                call: "vkCreateInstance",
                result,
            },
        })?;
        unwind.instance = Some(instance.clone());
        if validation {
            let utils = ash::ext::debug_utils::Instance::new(&entry, &instance);
            // SAFETY: the extension is enabled; `messages` outlives the messenger.
            let messenger =
                unsafe { utils.create_debug_utils_messenger(&messenger_info(&messages), None) }
                    .map_err(vk("vkCreateDebugUtilsMessengerEXT"))?;
            unwind.debug = Some((utils, messenger));
        }

        // SAFETY: valid instance.
        let physicals = unsafe { instance.enumerate_physical_devices() }
            .map_err(vk("vkEnumeratePhysicalDevices"))?;
        let mut candidates: Vec<(DeviceClass, Result<Candidate, Error>)> = physicals
            .iter()
            .map(|&p| {
                // SAFETY: enumerated from this instance.
                let t = unsafe { instance.get_physical_device_properties(p) }.device_type;
                (class_of(t), candidate(&instance, p, needs))
            })
            .collect();
        // The best usable device in the shared order; else why the best device is unusable.
        let usable: Vec<usize> = (0..candidates.len())
            .filter(|&i| candidates[i].1.is_ok())
            .collect();
        let classes = |list: &[usize]| -> Vec<DeviceClass> {
            list.iter().map(|&i| candidates[i].0).collect()
        };
        let chosen = match best_device(&classes(&usable)) {
            Some(k) => candidates.swap_remove(usable[k]).1?,
            None => {
                let all: Vec<usize> = (0..candidates.len()).collect();
                return Err(match best_device(&classes(&all)) {
                    Some(i) => match candidates.swap_remove(i).1 {
                        Err(e) => e,
                        Ok(_) => Error::NoDevice(String::new()),
                    },
                    None => Error::NoDevice(String::new()),
                });
            }
        };

        let priorities = [1.0f32];
        let queues = [vk::DeviceQueueCreateInfo::default()
            .queue_family_index(chosen.family)
            .queue_priorities(&priorities)];
        // The committed shaders need no optional feature. (wgpu turns on robust buffer and
        // image access where offered; every access of these shaders is in bounds, so it
        // changes nothing here.) Supplied modules may index an array of samplers (naga's HLSL
        // sampler heap), so that is enabled where the device offers it.
        let features = vk::PhysicalDeviceFeatures::default()
            .shader_sampled_image_array_dynamic_indexing(chosen.info.sampler_array_indexing);
        let device_info = vk::DeviceCreateInfo::default()
            .queue_create_infos(&queues)
            .enabled_features(&features);
        // SAFETY: `chosen.physical` belongs to `instance`; the info outlives the call.
        let device = unsafe { instance.create_device(chosen.physical, &device_info, None) }
            .map_err(vk("vkCreateDevice"))?;
        unwind.device = Some(device.clone());
        // SAFETY: the family and index were requested above.
        let queue = unsafe { device.get_device_queue(chosen.family, 0) };
        let pool_info = vk::CommandPoolCreateInfo::default()
            .queue_family_index(chosen.family)
            .flags(
                vk::CommandPoolCreateFlags::RESET_COMMAND_BUFFER
                    | vk::CommandPoolCreateFlags::TRANSIENT,
            );
        // SAFETY: valid device and info.
        unwind.command_pool = unsafe { device.create_command_pool(&pool_info, None) }
            .map_err(vk("vkCreateCommandPool"))?;
        let alloc_info = vk::CommandBufferAllocateInfo::default()
            .command_pool(unwind.command_pool)
            .level(vk::CommandBufferLevel::PRIMARY)
            .command_buffer_count(1);
        // SAFETY: the pool was just created; the buffer is freed with it.
        let command_buffer = unsafe { device.allocate_command_buffers(&alloc_info) }
            .map_err(vk("vkAllocateCommandBuffers"))?[0];
        // SAFETY: valid device.
        unwind.fence = unsafe { device.create_fence(&vk::FenceCreateInfo::default(), None) }
            .map_err(vk("vkCreateFence"))?;
        let allocator = Allocator::new(&AllocatorCreateDesc {
            instance: instance.clone(),
            device: device.clone(),
            physical_device: chosen.physical,
            debug_settings: Default::default(),
            buffer_device_address: false,
            // Small blocks: a frame needs a few MiB, and lavapipe's "device memory" is host
            // memory that the default 256 MiB blocks would tie up for nothing.
            allocation_sizes: gpu_allocator::AllocationSizes::new(16 << 20, 16 << 20)
                .with_max_device_memblock_size(256 << 20)
                .with_max_host_memblock_size(256 << 20),
        })
        .map_err(crate::error::memory("the allocator"))?;

        let gpu = Self {
            _entry: entry,
            instance,
            debug: unwind.debug.take(),
            device,
            queue,
            command_pool: std::mem::take(&mut unwind.command_pool),
            command_buffer,
            fence: std::mem::take(&mut unwind.fence),
            allocator: ManuallyDrop::new(allocator),
            info: chosen.info,
            messages,
            destroyed: false,
        };
        unwind.device = None;
        unwind.instance = None;
        gpu.check_messages()?;
        Ok(gpu)
    }

    /// Whether the validation layer and its messenger are on.
    pub fn validation(&self) -> bool {
        self.debug.is_some()
    }

    /// Turns the validation messages gathered since the last check into an error.
    pub fn check_messages(&self) -> Result<(), Error> {
        let taken = match self.messages.lock() {
            Ok(mut m) => std::mem::take(&mut *m),
            Err(poisoned) => std::mem::take(&mut *poisoned.into_inner()),
        };
        if taken.is_empty() {
            Ok(())
        } else {
            Err(Error::Validation(taken))
        }
    }

    /// Destroys everything in reverse order of creation. Idempotent. The renderer destroys
    /// its pipelines first.
    pub fn destroy(&mut self) {
        if self.destroyed {
            return;
        }
        self.destroyed = true;
        // SAFETY: after waiting for the device to be idle nothing is in use; every object
        // was created from these parents and is destroyed exactly once (the flag above).
        unsafe {
            // Errors here (device lost) cannot be acted on: destroy regardless.
            let _ = self.device.device_wait_idle();
            self.device.destroy_fence(self.fence, None);
            self.device.destroy_command_pool(self.command_pool, None);
            // The allocator frees its memory blocks; it must go before the device.
            ManuallyDrop::drop(&mut self.allocator);
            // With validation on, objects still alive here are reported as leaks.
            self.device.destroy_device(None);
            if let Some((utils, messenger)) = self.debug.take() {
                utils.destroy_debug_utils_messenger(messenger, None);
            }
            self.instance.destroy_instance(None);
        }
    }
}

impl Drop for Gpu {
    fn drop(&mut self) {
        self.destroy();
    }
}

// The renderer's command buffer: begin, submit and wait, the timestamps it read, and
// tearing everything down in order.

/// Every image format the program's graph uses and the features its passes need of it, so a
/// device that lacks one is passed over when the device is chosen (not found out mid-frame).
pub(crate) fn format_needs(program: &Program) -> Result<Vec<FormatNeed>, Error> {
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

impl Renderer {
    /// Resets and begins the renderer's command buffer.
    pub(crate) fn begin(&self) -> Result<(), Error> {
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
    pub(crate) fn submit_and_wait(&self) -> Result<f64, Error> {
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
            if self.injected_loss {
                // `Backend::lose_device`: the driver's answer to a submission on a lost
                // device, without submitting.
                return Err(vk("vkQueueSubmit")(vk::Result::ERROR_DEVICE_LOST));
            }
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

    /// The time of every pass that ran, from the frame's timestamp queries (all complete:
    /// the caller waited for the fence).
    pub(crate) fn timestamps(&self, ran: &[&Pass]) -> Result<Vec<PassTiming>, Error> {
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

    pub(crate) fn teardown(&mut self) {
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
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn missing_format_features_are_named() {
        let missing = vk::FormatFeatureFlags::STORAGE_IMAGE | vk::FormatFeatureFlags::TRANSFER_SRC;
        assert_eq!(
            describe_features(missing),
            "as a storage image or as a copy source"
        );
        let e = Error::Format {
            device: "llvmpipe (Vulkan, Cpu)".into(),
            format: "rgba32float".into(),
            vk_format: vk::Format::R32G32B32A32_SFLOAT,
            missing: describe_features(missing),
            resource: "cloud".into(),
        };
        assert_eq!(
            e.to_string(),
            "the Vulkan device llvmpipe (Vulkan, Cpu) cannot use rgba32float \
             (R32G32B32A32_SFLOAT) as a storage image or as a copy source, which the cloud \
             image needs; use a device whose driver supports it"
        );
    }
}
