//! The CPU twin of `precipitation.wgsl`'s lightning: a flash's light in the clouds (and in
//! the rain and on the particles), from the flash the frame's uniforms carry.

use crate::frame::{Frame, PI, xyz};
use crate::math::V3;

// WGSL: precipitation.wgsl (constants).
const LIGHTNING_DIFFUSION_M: f64 = 1500.0;
const LIGHTNING_CORE_M: f64 = 200.0;
const LIGHTNING_COLOUR: V3 = V3::new(0.85, 0.9, 1.0);

// WGSL: precipitation.wgsl::lightning_light
/// The flash's in-scattered radiance per unit scattering coefficient at camera-relative `rel`.
pub(crate) fn lightning_light(f: &Frame, rel: V3) -> V3 {
    if f.lightning_illuminance <= 0.0 {
        return V3::ZERO;
    }
    let cam = f.camera_position;
    let to = rel + V3::new(cam[0], 0.0, cam[2]) - xyz(f.lightning_position);
    let r = to.length().max(LIGHTNING_CORE_M);
    let q = 1000.0 / r;
    let e = f.lightning_illuminance * q * q * ((1000.0 - r) / LIGHTNING_DIFFUSION_M).exp();
    LIGHTNING_COLOUR * (e / (4.0 * PI))
}
