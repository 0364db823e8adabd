//! Aerial perspective for the host's geometry: the physical sky's froxel table of this frame's
//! view (the frame graph's `aerial-perspective`, wgsl/atmosphere.wgsl), which the host's shaders
//! read with `stratus_aerial_perspective` (`wgsl/host/aerial_perspective.wgsl`) to give their
//! geometry the haze Stratus gives its clouds.

use stratus_scene::Scene;

/// Froxel columns a side (`AERIAL_SIDE` in wgsl/atmosphere.wgsl).
pub const AERIAL_SIDE: u32 = 32;
/// Slices along each column (`AERIAL_SLICES`).
pub const AERIAL_SLICES: u32 = 32;
/// The depth of a slice (m; `AERIAL_SLICE_KM`).
pub const AERIAL_SLICE_M: f64 = 1000.0;

/// The aerial-perspective table of the last frame and how to read it
/// ([`crate::Clouds::aerial_perspective`]).
pub struct AerialPerspective<'a> {
    /// The table: rgba32float, [`AERIAL_SIDE`] * [`AERIAL_SLICES`] by [`AERIAL_SIDE`] texels,
    /// slice z of column (x, y) at texel (z * side + x, y): the light the air scatters toward
    /// the camera per unit key-light illuminance (rgb) and its mean transmittance (a) from the
    /// camera to the slice's far end. Bind it as an unfilterable-float texture.
    pub view: &'a wgpu::TextureView,
    /// The uniform block `StratusAerial` of the helper.
    pub uniform: [f32; 8],
}

/// The helper's uniform for `scene`'s frame: its key light's illuminance, the slice depth and
/// the grid.
pub(crate) fn uniform(scene: &Scene) -> [f32; 8] {
    let e = scene.uniforms().sun_illuminance;
    [
        e[0],
        e[1],
        e[2],
        AERIAL_SLICE_M as f32,
        AERIAL_SIDE as f32,
        AERIAL_SLICES as f32,
        0.0,
        0.0,
    ]
}
