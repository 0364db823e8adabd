//! The CPU twin of `composite.wgsl`: the analytic sky and sun disk behind the clouds, exposure,
//! the ACES fitted curve and gamma 2.2, to 8 bits.

use rayon::prelude::*;

use crate::frame::{Frame, PI};
use crate::geometry::{hits_ground, view_ray};
use crate::lighting::phase_hg;
use crate::math::{V3, mix_v, saturate};

// WGSL: composite.wgsl::sky_radiance
/// Sky radiance along unit `d` for a camera at altitude `alt`.
pub(crate) fn sky_radiance(f: &Frame, d: V3, alt: f64) -> V3 {
    let sun = f.sun();
    let e = f.sun_illuminance();
    let day = saturate(sun.y * 4.0 + 0.3);
    if hits_ground(f, V3::new(0.0, alt, 0.0), alt, d) {
        let ground_albedo = V3::new(0.035, 0.035, 0.03);
        return ground_albedo.mul_v(e * (sun.y.max(0.0) / PI) + e * (0.05 * day));
    }
    let zenith = V3::new(0.018, 0.04, 0.1);
    let horizon = V3::new(0.07, 0.085, 0.11);
    let up = saturate(d.y);
    let gradient = mix_v(horizon, zenith, up.sqrt());
    let sunset = V3::new(0.25, 0.1, 0.0) * ((1.0 - day * 0.8) * (1.0 - up).powf(6.0));
    let glow = phase_hg(d.dot(sun), 0.76) * 0.02;
    e.mul_v(gradient * day + sunset * saturate(sun.y * 10.0 + 1.0) + V3::splat(glow * day))
}

// WGSL: composite.wgsl::sun_disk
/// Radiance of the sun's disk: illuminance over its solid angle.
pub(crate) fn sun_disk(f: &Frame, d: V3) -> V3 {
    let cos_r = f.sun_direction[3];
    if d.dot(f.sun()) < cos_r {
        return V3::ZERO;
    }
    f.sun_illuminance() / (2.0 * PI * (1.0 - cos_r).max(1e-6))
}

// WGSL: composite.wgsl::aces_fitted
/// Narkowicz's ACES fit, clamped to `[0, 1]`.
pub(crate) fn aces_fitted(x: V3) -> V3 {
    let curve = |x: f64| {
        let (a, b, c, d, e) = (2.51, 0.03, 2.43, 0.59, 0.14);
        ((x * (a * x + b)) / (x * (c * x + d) + e)).clamp(0.0, 1.0)
    };
    V3::new(curve(x.x), curve(x.y), curve(x.z))
}

/// `f32 -> rgba8unorm` store conversion: clamp, scale by 255, round to nearest.
fn unorm8(x: f64) -> u8 {
    (saturate(x) * 255.0).round() as u8
}

// WGSL: composite.wgsl::composite
/// The display pixel for march output `cloud` (radiance rgb, transmittance).
pub(crate) fn composite(f: &Frame, pixel: [u32; 2], cloud: [f64; 4]) -> [u8; 4] {
    let view = view_ray(f, pixel);
    let alt = f.camera_position[1];
    let mut background = sky_radiance(f, view, alt);
    if !hits_ground(f, V3::new(0.0, alt, 0.0), alt, view) {
        background += sun_disk(f, view);
    }
    let radiance = background * cloud[3] + V3::new(cloud[0], cloud[1], cloud[2]);
    let exposed = radiance * f.camera_right[3];
    let display = aces_fitted(exposed);
    let g = 1.0 / 2.2;
    [
        unorm8(display.x.powf(g)),
        unorm8(display.y.powf(g)),
        unorm8(display.z.powf(g)),
        255,
    ]
}

/// The display image of a `width` x `height` frame from its stored (f32) radiance and
/// transmittance, 4 floats a pixel, as the GPU's composite pass reads the march output.
pub(crate) fn composite_image(f: &Frame, width: u32, height: u32, radiance: &[f32]) -> Vec<u8> {
    (0..height)
        .into_par_iter()
        .flat_map_iter(|y| {
            (0..width).flat_map(move |x| {
                let i = 4 * (y * width + x) as usize;
                let cloud = [0, 1, 2, 3].map(|c| f64::from(radiance[i + c]));
                composite(f, [x, y], cloud)
            })
        })
        .collect()
}
