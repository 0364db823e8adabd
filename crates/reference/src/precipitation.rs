//! The CPU twin of `precipitation.wgsl`'s rain: where it falls and its shafts in the composite
//! (the particles are in [`crate::particles`], the flash's light in [`crate::lightning`]).

use stratus_graph::SceneDepth;
use stratus_noise::NoiseSet;

use crate::density::{cloud_layers, sample_weather};
use crate::frame::{Frame, hash_unit, xyz};
use crate::lightning::lightning_light;
use crate::math::{V3, smoothstep};
use crate::medium::Model;
use crate::sky::SkyTables;

// WGSL: precipitation.wgsl (constants).
const RAIN_SHAFT_EXTINCTION: f64 = 1.3e-3;
const RAIN_SHAFT_STEPS: u32 = 24;
const RAIN_SHAFT_RANGE_M: f64 = 30000.0;
const RAIN_SHAFT_SALT: u32 = 0x7A1B;
const RAIN_CORE: [f64; 2] = [0.6, 0.9];

/// What the rain needs besides the frame: the weather map, the sky's tables (for the light
/// under the deck) and the host's geometry.
#[derive(Clone, Copy)]
pub(crate) struct Rain<'a> {
    pub noise: &'a NoiseSet,
    pub sky: Option<&'a SkyTables>,
    pub surface: Option<&'a SceneDepth>,
}

impl<'a> Rain<'a> {
    /// What `model`'s frame has for the rain (its clouds' medium only).
    pub fn of(model: &'a Model) -> Option<Self> {
        Some(Self {
            noise: model.noise()?,
            sky: model.sky(),
            surface: model.surface.as_deref(),
        })
    }
}

// WGSL: precipitation.wgsl::falling_rain
/// The rain falling at world point `p` (altitude `p.y`): under each precipitating layer
/// whose bottom is above it, its precipitation where the weather map has a core.
pub(crate) fn falling_rain(f: &Frame, noise: &NoiseSet, p: V3) -> f64 {
    cloud_layers(f)
        .filter(|l| l.precipitation > 0.0 && p.y < l.bottom)
        .map(|l| {
            let w = sample_weather(f, noise, p, &l);
            w.precipitation * smoothstep(RAIN_CORE[0], RAIN_CORE[1], w.coverage)
        })
        .sum()
}

// WGSL: rainbow.wgsl::rain_top
/// The highest bottom of a precipitating layer (m; 0 without one).
fn rain_top(f: &Frame) -> f64 {
    cloud_layers(f)
        .filter(|l| l.precipitation > 0.0)
        .map(|l| l.bottom)
        .fold(0.0, f64::max)
}

// WGSL: precipitation.wgsl::rain_in_front
/// Whether the rain lies in front of the clouds (the camera is below the rain's top).
pub(crate) fn rain_in_front(f: &Frame) -> bool {
    f.camera_position[1] <= rain_top(f)
}

// WGSL: march.wgsl::scene_surface
/// The distance to the host's geometry along `view` at `pixel` (m; infinite without it).
pub(crate) fn scene_surface(
    f: &Frame,
    surface: Option<&SceneDepth>,
    pixel: [u32; 2],
    view: V3,
) -> f64 {
    match surface.filter(|_| crate::march::surface_at(f, surface, pixel)) {
        Some(d) => {
            let axis = f.scene_depth_b / (f64::from(d.depth(pixel[0], pixel[1])) + f.scene_depth_a);
            axis / view.dot(xyz(f.camera_forward))
        }
        None => f64::INFINITY,
    }
}

// WGSL: precipitation.wgsl::rain_veil
/// The rain shafts along `view` at `pixel`: the light the rain scatters toward the camera and
/// the share of what is behind that it lets through.
pub(crate) fn rain_veil(f: &Frame, rain: &Rain, pixel: [u32; 2], view: V3) -> (V3, f64) {
    let mut veil = (V3::ZERO, 1.0);
    let top = rain_top(f);
    if f.rain_shafts <= 0.0 || top <= 0.0 {
        return veil;
    }
    let cam = f.camera_position;
    let mut start = 0.0;
    let mut end = RAIN_SHAFT_RANGE_M;
    if cam[1] > top {
        if view.y >= 0.0 {
            return veil;
        }
        start = (cam[1] - top) / -view.y;
    } else if view.y > 0.0 {
        end = end.min((top - cam[1]) / view.y);
    }
    if view.y < 0.0 {
        end = end.min(cam[1] / -view.y);
    }
    end = end.min(scene_surface(f, rain.surface, pixel, view));
    if end.partial_cmp(&start) != Some(std::cmp::Ordering::Greater) {
        return veil;
    }
    let dt = (end - start) / f64::from(RAIN_SHAFT_STEPS);
    let offset = hash_unit(pixel, RAIN_SHAFT_SALT);
    let k = RAIN_SHAFT_EXTINCTION * f.rain_shafts;
    for i in 0..RAIN_SHAFT_STEPS {
        let t = start + (f64::from(i) + offset) * dt;
        let rel = view * t + V3::new(0.0, cam[1], 0.0);
        let beta = k * falling_rain(f, rain.noise, rel + V3::new(cam[0], 0.0, cam[2]));
        if beta > 0.0 {
            let step_t = (-beta * dt).exp();
            let light = crate::lighting::ambient(f, rain.sky, 0.0, rel) + lightning_light(f, rel);
            veil.0 += light * (veil.1 * (1.0 - step_t));
            veil.1 *= step_t;
        }
    }
    veil
}

// WGSL: precipitation.wgsl::through_rain
/// `behind` seen through the rain in front of it.
pub(crate) fn through_rain(veil: (V3, f64), behind: V3) -> V3 {
    veil.0 + behind * veil.1
}
