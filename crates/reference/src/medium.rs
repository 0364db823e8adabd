//! What fills the cloud layer: the scene's clouds (the WGSL's density field) or an analytic
//! homogeneous medium for tests against closed forms. Both integrators run on either.

use stratus_noise::NoiseSet;
use stratus_scene::Scene;

use crate::density::{Counters, Weather, cloud_density, sample_weather, uniform_weather};
use crate::frame::Frame;
use crate::geometry::solve_sphere;
use crate::math::V3;

/// The participating medium a render integrates.
#[derive(Clone, Copy, Debug)]
pub enum Medium<'a> {
    /// The scene's clouds: `density.wgsl::cloud_density` over these noise textures, with the
    /// scene's `sigma_s` and `sigma_a`.
    Clouds(&'a NoiseSet),
    /// Density 1 inside `shape` and 0 outside, with these coefficients (1/m) instead of the
    /// scene's. The weather is the scene's global values (coverage 1, the scene's cloud type and
    /// precipitation), so every lighting term of the real-time model still applies.
    Homogeneous {
        /// Scattering coefficient sigma_s (1/m).
        sigma_s: f64,
        /// Absorption coefficient sigma_a (1/m).
        sigma_a: f64,
        /// Where the medium is.
        shape: Shape,
    },
}

/// The support of a [`Medium::Homogeneous`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// The whole cloud layer (between the scene's cloud bottom and top). With a very large
    /// planet radius (e.g. 1e12 m) this is a flat slab of thickness `top - bottom`.
    Slab,
    /// A ball (intersected with the cloud layer), centre `[x, y, z]` in the world's flat
    /// coordinates (the `p` of the WGSL: x east, y the camera-relative height coordinate, z
    /// north; with a large planet radius y is the altitude) and radius in metres.
    Sphere {
        /// Centre `[x, y, z]`, metres.
        center: [f64; 3],
        /// Radius, metres.
        radius: f64,
    },
}

/// The frame (as the GPU sees it) together with the medium: everything an integrator reads.
pub(crate) struct Model<'a> {
    pub f: Frame,
    medium: Medium<'a>,
    /// Lower and upper bound of the density anywhere inside the medium's support.
    pub density_bounds: (f64, f64),
}

impl<'a> Model<'a> {
    /// The frame of `scene` (its uniforms widened to f64) and the medium. A homogeneous medium
    /// replaces the scene's sigma_s and sigma_a in the frame.
    pub fn new(scene: &Scene, medium: Medium<'a>) -> Self {
        let mut f = Frame::from_uniforms(&scene.uniforms());
        let density_bounds = match medium {
            Medium::Clouds(_) => {
                // density = eroded base (<= 1) * height gradient (<= 1) * multiplier *
                // (1 + precipitation), precipitation <= clouds.w; then clamped to [0, 1].
                (0.0, (f.clouds[1] * (1.0 + f.clouds[3])).clamp(0.0, 1.0))
            }
            Medium::Homogeneous {
                sigma_s, sigma_a, ..
            } => {
                f.extinction[0] = sigma_s;
                f.extinction[1] = sigma_a;
                (1.0, 1.0)
            }
        };
        Self {
            f,
            medium,
            density_bounds,
        }
    }

    /// Density at world position `p` (altitude `alt`); counts like `cloud_density`.
    pub fn density(&self, p: V3, alt: f64, counters: &mut Counters) -> f64 {
        match self.medium {
            Medium::Clouds(noise) => cloud_density(&self.f, noise, p, alt, counters),
            Medium::Homogeneous { shape, .. } => {
                let f = &self.f;
                let h = (alt - f.atmosphere[1]) / (f.atmosphere[2] - f.atmosphere[1]);
                if !(0.0..=1.0).contains(&h) {
                    return 0.0;
                }
                counters.density += 1;
                match shape {
                    Shape::Slab => 1.0,
                    Shape::Sphere { center, radius } => {
                        let c = V3::from_array(center);
                        if (p - c).length() <= radius { 1.0 } else { 0.0 }
                    }
                }
            }
        }
    }

    /// The weather at `p` (the weather map for clouds, the scene's values otherwise).
    pub fn weather(&self, p: V3) -> Weather {
        match self.medium {
            Medium::Clouds(noise) => sample_weather(&self.f, noise, p),
            Medium::Homogeneous { .. } => uniform_weather(&self.f),
        }
    }

    /// Clips the ray interval `[t0, t1]` (ray from camera-relative `origin` along unit `d`) to
    /// the medium's support beyond the layer: the ball of a [`Shape::Sphere`].
    pub fn clip(&self, origin: V3, d: V3, t0: f64, t1: f64) -> Option<(f64, f64)> {
        let (lo, hi) = match self.medium {
            Medium::Homogeneous {
                shape: Shape::Sphere { center, radius },
                ..
            } => {
                // Centre relative to the camera's ground point (world x/z minus camera x/z).
                let c = V3::from_array(center)
                    - V3::new(self.f.camera_position[0], 0.0, self.f.camera_position[2]);
                let o = origin - c;
                let b = d.dot(o);
                let cc = o.dot(o) - radius * radius;
                let r = solve_sphere(b, cc);
                if !r.hit {
                    return None;
                }
                (t0.max(r.t0), t1.min(r.t1))
            }
            _ => (t0, t1),
        };
        (hi > lo).then_some((lo, hi))
    }
}
