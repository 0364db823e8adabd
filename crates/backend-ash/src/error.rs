//! Everything that can go wrong, each with a sentence a user can act on.

use ash::vk;

/// Everything that can go wrong, each with a sentence a user can act on.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The Vulkan loader (`libvulkan.so.1`) could not be loaded.
    #[error(
        "the Vulkan loader could not be loaded ({0}); install it with `apt-get install libvulkan1`"
    )]
    NoLoader(String),
    /// The loader implements an older Vulkan than the renderer needs.
    #[error(
        "the Vulkan loader implements Vulkan {found}, and Stratus needs {needed}; install a newer one with `apt-get install libvulkan1`"
    )]
    LoaderVersion {
        /// What the loader implements, e.g. `1.0`.
        found: String,
        /// What is needed, e.g. `1.1`.
        needed: String,
    },
    /// Validation was requested but the Khronos validation layer is not installed.
    #[error(
        "Vulkan validation was requested but the layer VK_LAYER_KHRONOS_validation is not installed; install it with `apt-get install vulkan-validationlayers` or turn validation off"
    )]
    NoValidationLayer,
    /// Validation was requested but an instance extension it needs is missing.
    #[error(
        "Vulkan validation needs the instance extension {0}, which neither the loader nor the validation layer offers; reinstall `vulkan-validationlayers` or turn validation off"
    )]
    NoValidationExtension(String),
    /// No usable Vulkan device.
    #[error(
        "no usable Vulkan device found{0}; install a Vulkan driver (`apt-get install mesa-vulkan-drivers` gives lavapipe, a CPU driver)"
    )]
    NoDevice(String),
    /// The device lacks a format capability the frame needs.
    #[error(
        "the Vulkan device {device} cannot use {format} ({vk_format:?}) {missing}, which the {resource} image needs; use a device whose driver supports it"
    )]
    Format {
        /// The device, in words.
        device: String,
        /// The format's WGSL spelling, e.g. `rgba32float`.
        format: String,
        /// The Vulkan format.
        vk_format: vk::Format,
        /// What is missing, in words, e.g. `as a storage image`.
        missing: String,
        /// The resource that needs it, e.g. `cloud`.
        resource: String,
    },
    /// The frame is larger than the device allows.
    #[error(
        "the frame is {width}x{height}, larger than the {max}x{max} images the Vulkan device {device} allows; render a smaller image"
    )]
    Size {
        /// Plan width.
        width: u32,
        /// Plan height.
        height: u32,
        /// `maxImageDimension2D`.
        max: u32,
        /// The device, in words.
        device: String,
    },
    /// The frame's images need more memory than the device has.
    #[error(
        "the frame at {width}x{height} needs {needed_gib:.1} GiB of images; the Vulkan device {device} has {heap_gib:.1} GiB of device memory: render a smaller image"
    )]
    TooLarge {
        /// Plan width.
        width: u32,
        /// Plan height.
        height: u32,
        /// What the plan's resources take, GiB.
        needed_gib: f64,
        /// The largest device-local heap, GiB.
        heap_gib: f64,
        /// The device, in words.
        device: String,
    },
    /// The validation layer reported warnings or errors (leaked objects included).
    #[error("the Vulkan validation layer reported {} problem(s):\n{}", .0.len(), .0.join("\n"))]
    Validation(Vec<String>),
    /// The device was lost (`VK_ERROR_DEVICE_LOST`): a GPU hang, a driver reset or a fault.
    /// Nothing more runs on it; a new renderer (a new device) can.
    #[error(
        "the Vulkan device was lost ({call} returned VK_ERROR_DEVICE_LOST); nothing more can render on it: create a new renderer (a GPU hang, a driver reset or a GPU fault loses a device)"
    )]
    DeviceLost {
        /// The Vulkan function that reported it.
        call: &'static str,
    },
    /// A Vulkan call failed.
    #[error("{call} failed: {result}")]
    Vulkan {
        /// The Vulkan function.
        call: &'static str,
        /// Its result code.
        result: vk::Result,
    },
    /// gpu-allocator could not allocate memory.
    #[error("GPU memory allocation for {what} failed: {message}")]
    Memory {
        /// What was being allocated.
        what: String,
        /// gpu-allocator's message.
        message: String,
    },
    /// The device cannot bind what a supplied shader module declares.
    #[error(
        "the Vulkan device {device} cannot run pass `{pass}` of the supplied shaders: {reason}"
    )]
    Unsupported {
        /// The device, in words.
        device: String,
        /// The pass.
        pass: String,
        /// Which limit or feature is missing, in words.
        reason: String,
    },
    /// The committed SPIR-V, the manifest or the frame plan is unusable.
    #[error("{0}")]
    Shader(String),
}

/// Maps a failed Vulkan call to [`Error::Vulkan`]: `vk(call)` is the `map_err` argument.
/// `VK_ERROR_DEVICE_LOST` becomes [`Error::DeviceLost`], which says what to do about it.
pub(crate) fn vk(call: &'static str) -> impl Fn(vk::Result) -> Error {
    move |result| {
        if result == vk::Result::ERROR_DEVICE_LOST {
            Error::DeviceLost { call }
        } else {
            Error::Vulkan { call, result }
        }
    }
}

/// Maps a gpu-allocator failure to [`Error::Memory`].
pub(crate) fn memory(what: &str) -> impl Fn(gpu_allocator::AllocationError) -> Error + '_ {
    move |e| Error::Memory {
        what: what.to_string(),
        message: e.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// lavapipe cannot be made to lose its device, so the mapping every Vulkan call's result
    /// goes through is what is tested: a lost device is named, anything else keeps its code.
    #[test]
    fn a_lost_device_is_named_by_every_call() {
        let lost = vk("vkWaitForFences")(vk::Result::ERROR_DEVICE_LOST);
        assert!(matches!(
            lost,
            Error::DeviceLost {
                call: "vkWaitForFences"
            }
        ));
        let text = lost.to_string();
        assert!(
            text.contains("device was lost") && text.contains("new renderer"),
            "{text}"
        );
        let other = vk("vkQueueSubmit")(vk::Result::ERROR_OUT_OF_DEVICE_MEMORY);
        assert_eq!(
            other.to_string(),
            "vkQueueSubmit failed: A device memory allocation has failed"
        );
    }
}
