//! Everything that can go wrong, each with a sentence a user can act on.

use crate::*;

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
