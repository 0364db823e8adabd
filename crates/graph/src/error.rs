//! Why no frame plan could be made: shared by [`crate::program`] (the embedded shaders are
//! unusable) and [`crate::plan`] (no variant, or a size out of range), so that neither needs
//! the other's module for it.

use stratus_scene::MAX_RESOLUTION;

/// Why no plan could be made.
#[derive(Debug, thiserror::Error)]
pub enum PlanError {
    /// The manifest or graph is missing or unreadable.
    #[error("the shaders are unusable ({0}); run `cargo xtask build-shaders`")]
    Manifest(String),
    /// No exported variant has every feature the scene uses.
    #[error(
        "no exported variant of module `{module}` has every feature this scene uses ({wanted}); add one to wgsl/modules.toml"
    )]
    NoVariant {
        /// The module.
        module: String,
        /// What the scene needs.
        wanted: String,
    },
    /// The image size is out of range.
    #[error("image size {0}x{1}: width and height must be within [1, {MAX_RESOLUTION}]")]
    Size(u32, u32),
}
