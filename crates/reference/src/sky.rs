//! The CPU twin of `atmosphere.wgsl`: the physical sky's lookup tables (Hillaire, "A Scalable
//! and Production Ready Sky and Atmosphere Rendering Technique", EGSR 2020) computed in f64 at
//! the GPU's sizes with the GPU's quadratures, and the lookups the march and the composite make
//! in them.
//!
//! Every table is built as its compute pass builds it: the same step counts and step
//! placement, the same spherical Fibonacci directions, the same parametrisations (Bruneton's
//! for the transmittance, "Precomputed Atmospheric Scattering", 2008, and its 2017
//! reimplementation; Hillaire's for the others) and the same bilinear interpolation with
//! clamped ends. What differs is the arithmetic: f64 here, f32 there, and lengths in metres
//! (the WGSL works in kilometres to keep f32's digits; the constants below say where a
//! kilometre constant became a metre one). The air itself is the direct integration's
//! [`AtmosphereModel`], filled from the uniform block's `air_*` members, so the coefficients,
//! profiles and phase functions are the ones the tables are measured against.
//!
//! Every table holds light per unit sun illuminance at the top of the atmosphere; a caller
//! multiplies by `frame.sun_illuminance`.

use std::time::Instant;

use rayon::prelude::*;
use stratus_graph::PassTiming;
use stratus_scene::FrameUniforms;

use crate::atmosphere::{AtmosphereModel, fibonacci_direction};
use crate::frame::{Frame, PI, xyz};
use crate::math::{V3, mix_v, saturate};
use crate::phase::phase_cornette_shanks;
use crate::rainbow;

// WGSL: composite.wgsl::SHAFT_STEPS, SHAFT_RANGE_KM, SHAFT_SALT, SHAFT_MIN_SUN_Y
/// Samples along a view ray of the light shafts.
const SHAFT_STEPS: usize = 48;
/// How far along the view ray the light shafts reach (m; the WGSL's 32 km).
const SHAFT_RANGE_M: f64 = 32_000.0;
/// The shafts' dither stream of `hash_unit`.
const SHAFT_SALT: u32 = 0x5AF7;
/// The key light's least height (its direction's y) with shafts: below it every shaded point
/// projects off the map.
const SHAFT_MIN_SUN_Y: f64 = 1e-3;
// WGSL: rainbow.wgsl::RAIN_STEPS, RAIN_RANGE_M, RAIN_EXTINCTION, MOISTURE_PEAK_M
const RAIN_STEPS: usize = 32;
const RAIN_RANGE_M: f64 = 15_000.0;
const RAIN_EXTINCTION: f64 = 5.59e-4;
const MOISTURE_PEAK_M: f64 = 2000.0;

// WGSL: rainbow.wgsl::moisture_profile
/// The moisture's weight at altitude `h` (m), 1 at 2 km.
fn moisture_profile(h: f64) -> f64 {
    let x = h.max(0.0) / MOISTURE_PEAK_M;
    x * (1.0 - x).exp()
}

// WGSL: atmosphere.wgsl (constants).
/// Transmittance table: texels along (distance to the top, radius).
pub const TRANSMITTANCE_SIZE: [usize; 2] = [256, 64];
/// Multi-scattering table: texels along (sun zenith cosine, altitude).
pub const MULTISCATTER_SIZE: [usize; 2] = [32, 32];
/// Sky-view table: texels along (azimuth from the sun, elevation).
pub const SKY_VIEW_SIZE: [usize; 2] = [192, 108];
/// Aerial perspective: depth slices of [`AERIAL_SLICE_M`] each.
pub const AERIAL_SLICES: usize = 32;
/// Aerial perspective: froxel columns along each screen axis.
pub const AERIAL_SIDE: usize = 32;
/// Depth of one aerial-perspective slice (m; the WGSL's `AERIAL_SLICE_KM`, 1 km).
pub const AERIAL_SLICE_M: f64 = 1000.0;
const TRANSMITTANCE_STEPS: u32 = 128; // even (Simpson)
const MULTISCATTER_DIRECTIONS: usize = 64;
const MULTISCATTER_STEPS: u32 = 32;
const SKY_VIEW_STEPS: u32 = 48;
const AMBIENT_DIRECTIONS: usize = 64;
const AMBIENT_STEPS: u32 = 24;
/// The sky-ambient table's texels along the sun's zenith cosine (per row: the layer's bottom,
/// its top).
pub const SKY_AMBIENT_SUNS: usize = 64;
/// The ground-irradiance table's texels (by the sun's zenith cosine).
pub const GROUND_IRRADIANCE_SIZE: usize = 64;
const GROUND_IRRADIANCE_DIRECTIONS: usize = 128;
/// The cloud-shadow map's side (texels).
pub const SHADOW_SIZE: usize = 128;
/// Half the side of the square the cloud-shadow map covers, centred below the camera (m).
pub const SHADOW_HALF_EXTENT_M: f64 = 20_000.0;
const SHADOW_FADE_START: f64 = 0.75;
/// Midpoint steps of the shadow map's march through each layer.
pub(crate) const SHADOW_STEPS: u32 = 16;
/// Four midpoint steps per aerial-perspective slice.
const AERIAL_SUBSTEPS: u32 = 4;
/// `transmittance_coords`' guard on the span of distances: 1e-6 km.
const MIN_SPAN_M: f64 = 1e-3;
/// `ground_radiance` looks at the sun from this far above the ground: 0.001 km.
const GROUND_LIFT_M: f64 = 1.0;

/// The names of the passes that compute the tables, in the frame graph's order; the CPU
/// renderer reports their times under these names.
pub const PASSES: [&str; 7] = [
    "transmittance-lut",
    "multiscatter-lut",
    "ground-irradiance",
    "sky-view-lut",
    "sky-ambient",
    "aerial-perspective",
    "cloud-shadow",
];

/// An rgba texel (the GPU's rgba32float, widened).
pub type Texel = [f64; 4];

fn mix4(a: Texel, b: Texel, t: f64) -> Texel {
    std::array::from_fn(|c| a[c] * (1.0 - t) + b[c] * t)
}

fn rgb(t: Texel) -> V3 {
    V3::new(t[0], t[1], t[2])
}

fn texel(v: V3, a: f64) -> Texel {
    [v.x, v.y, v.z, a]
}

/// A table as the GPU stores it: `width` x `height` rgba texels, row by row.
#[derive(Clone, Debug, PartialEq)]
pub struct Table {
    /// Texels per row.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// `texels[y * width + x]`.
    pub texels: Vec<Texel>,
}

impl Table {
    /// A table of `size` whose texel (x, y) is `f(x, y)`, rows in parallel.
    fn build(size: [usize; 2], f: impl Fn(usize, usize) -> Texel + Sync) -> Self {
        let [width, height] = size;
        let texels = (0..height)
            .into_par_iter()
            .flat_map_iter(|y| (0..width).map(move |x| (x, y)))
            .map(|(x, y)| f(x, y))
            .collect();
        Self {
            width,
            height,
            texels,
        }
    }

    /// Texel (x, y) (WGSL `textureLoad`).
    pub fn load(&self, x: usize, y: usize) -> Texel {
        self.texels[y * self.width + x]
    }

    // WGSL: atmosphere.wgsl::lut_bilinear
    /// Bilinear interpolation at `x` in `[0, 1]^2` (clamped), where texel i holds the value at
    /// `x = i / (size - 1)`, so both ends are sampled exactly.
    pub fn bilinear(&self, x: [f64; 2]) -> Texel {
        let size = [self.width, self.height];
        let last = size.map(|s| (s - 1) as f64);
        let f = [
            x[0].clamp(0.0, 1.0) * last[0],
            x[1].clamp(0.0, 1.0) * last[1],
        ];
        // `as usize` saturates (a NaN gives 0), as WGSL's u32 conversion clamps.
        let i0 = [0, 1].map(|a| (f[a].floor() as usize).min(size[a] - 1));
        let i1 = [0, 1].map(|a| (i0[a] + 1).min(size[a] - 1));
        let w = [f[0] - i0[0] as f64, f[1] - i0[1] as f64];
        let a = mix4(self.load(i0[0], i0[1]), self.load(i1[0], i0[1]), w[0]);
        let b = mix4(self.load(i0[0], i1[1]), self.load(i1[0], i1[1]), w[0]);
        mix4(a, b, w[1])
    }
}

// WGSL: atmosphere.wgsl::AirSample
/// The air at one altitude (per metre).
struct AirSample {
    rayleigh: V3,
    mie: f64,
    extinction: V3,
}

// WGSL: atmosphere.wgsl::Scattered
/// What `integrate_air` gathers along a ray.
struct Scattered {
    radiance: V3,
    // Read by no caller yet, as in the WGSL; kept so the two stay alike.
    #[allow(dead_code)]
    transmittance: V3,
}

// WGSL: atmosphere.wgsl::sphere_discriminant
/// `r^2 (mu^2 - 1) + R^2` for the sphere of radius R, with `R^2 - r^2` as `(R - r)(R + r)`.
fn sphere_discriminant(r: f64, mu: f64, radius: f64) -> f64 {
    (radius - r) * (radius + r) + r * r * mu * mu
}

// WGSL: atmosphere.wgsl::radius_after
/// Radius after `t` metres from radius `r` along zenith cosine `mu`.
fn radius_after(r: f64, mu: f64, t: f64) -> f64 {
    (r * r + t * t + 2.0 * r * mu * t).max(0.0).sqrt()
}

// WGSL: atmosphere.wgsl::phase_rayleigh
fn phase_rayleigh(cos_theta: f64) -> f64 {
    3.0 / (16.0 * PI) * (1.0 + cos_theta * cos_theta)
}

// WGSL: atmosphere.wgsl::sky_view_elevation
/// The sky-view table's elevation of coordinate `v` for a camera whose horizon lies at
/// elevation `horizon` (<= 0): v = 0.5 is the horizon, texels crowd toward it as the square of
/// the distance in v.
fn sky_view_elevation(v: f64, horizon: f64) -> f64 {
    if v >= 0.5 {
        let a = 2.0 * v - 1.0;
        return horizon + (0.5 * PI - horizon) * a * a;
    }
    let a = 1.0 - 2.0 * v;
    horizon - (horizon + 0.5 * PI) * a * a
}

// WGSL: atmosphere.wgsl::sky_view_v
fn sky_view_v(elevation: f64, horizon: f64) -> f64 {
    if elevation >= horizon {
        return 0.5 + 0.5 * saturate((elevation - horizon) / (0.5 * PI - horizon)).sqrt();
    }
    0.5 - 0.5 * saturate((horizon - elevation) / (horizon + 0.5 * PI)).sqrt()
}

// WGSL: atmosphere.wgsl::sun_azimuth
/// The sun's azimuth about the zenith (from +x toward +z).
fn sun_azimuth(f: &Frame) -> f64 {
    let s = f.sun();
    s.z.atan2(s.x)
}

// WGSL: atmosphere.wgsl::aerial_ray
/// The view direction through the centre of aerial froxel column `c`.
fn aerial_ray(f: &Frame, c: [usize; 2]) -> V3 {
    let side = AERIAL_SIDE as f64;
    let ndc = c.map(|c| (c as f64 + 0.5) / side * 2.0 - 1.0);
    let tan_half = f.tan_half_fov;
    let aspect = f.aspect;
    (xyz(f.camera_forward) + xyz(f.camera_right) * (ndc[0] * tan_half * aspect)
        - xyz(f.camera_up) * (ndc[1] * tan_half))
        .normalize()
}

/// The air of a uniform block: its air members (`rayleigh_*`, `mie_*`, `ozone_*`...) over the planet of `planet_radius`, as the
/// direct integration's model (the ground's albedo grey).
pub fn air_model(u: &FrameUniforms) -> AtmosphereModel {
    air_of(&Frame::from_uniforms(u))
}

fn air_of(f: &Frame) -> AtmosphereModel {
    AtmosphereModel {
        bottom_radius_m: f.planet_radius,
        top_radius_m: f.planet_radius + f.air_thickness,
        rayleigh_scattering: [
            f.rayleigh_scattering[0],
            f.rayleigh_scattering[1],
            f.rayleigh_scattering[2],
        ],
        rayleigh_scale_height_m: f.rayleigh_scale_height,
        mie_scattering: f.mie_scattering,
        mie_absorption: f.mie_absorption,
        mie_scale_height_m: f.mie_scale_height,
        mie_g: f.mie_g,
        ozone_absorption: [
            f.ozone_absorption[0],
            f.ozone_absorption[1],
            f.ozone_absorption[2],
        ],
        ozone_center_m: f.ozone_center,
        ozone_width_m: f.ozone_width,
        ground_albedo: [f.ground_albedo; 3],
    }
}

/// The physical sky's tables for one frame, and the air they were computed over.
#[derive(Clone, Debug)]
pub struct SkyTables {
    air: AtmosphereModel,
    /// Transmittance to the top of the air (rgb) by Bruneton's (distance to the top, radius)
    /// coordinates, [`TRANSMITTANCE_SIZE`].
    pub transmittance: Table,
    /// Hillaire's Psi_ms (rgb) by (sun zenith cosine, altitude), [`MULTISCATTER_SIZE`].
    pub multiscatter: Table,
    /// The sky's irradiance on the ground (rgb) by the sun's zenith cosine,
    /// [`GROUND_IRRADIANCE_SIZE`]x1.
    pub ground_irradiance: Table,
    /// The clouds' transmittance of the key light from the ground (r), [`SHADOW_SIZE`]^2 over
    /// a square [`SHADOW_HALF_EXTENT_M`] each way from the ground below the camera. Made by
    /// the renderer that knows the medium ([`SkyTables::shade`]); all 1 until then.
    pub cloud_shadow: Table,
    /// The sky's radiance around the camera (rgb) by (azimuth from the sun, elevation),
    /// ground included, [`SKY_VIEW_SIZE`].
    pub sky_view: Table,
    /// Cosine-weighted mean radiance (rgb) of the lower (row 0) and upper (row 1) hemispheres
    /// seen from the cloud layer's bottom, for a sun of zenith cosine t |t| there, t =
    /// 2 i / 63 - 1 (column i, `sky_ambient_x`), [`SKY_AMBIENT_SUNS`]x2.
    pub sky_ambient: Table,
    /// In-scattered light (rgb) and mean transmittance (a) from the camera to the far end of
    /// each slice, slice z of froxel column (x, y) at texel (z * 32 + x, y): 1024x32.
    pub aerial: Table,
    /// The rainbow's Lee-diagram row (`rainbow-lut`, 1024x1) when the frame draws a rainbow
    /// from its table.
    pub rainbow: Option<Table>,
    /// The weather map the rainbow's rain is read from (set with the cloud-shadow map, for a
    /// frame with a rainbow).
    pub(crate) weather: Option<stratus_noise::Texture2>,
    /// Wall-clock time of each table, named as the frame graph's passes ([`PASSES`]).
    pub timings: Vec<PassTiming>,
}

impl SkyTables {
    /// Every table for the frame of uniform block `u` (the camera, the sun and the air), in
    /// parallel on rayon's current pool.
    pub fn new(u: &FrameUniforms) -> Self {
        Self::for_frame(&Frame::from_uniforms(u))
    }

    /// The air the tables describe.
    pub fn air(&self) -> &AtmosphereModel {
        &self.air
    }

    /// Aerial perspective at `pixel` of a frame of `u` (its size and camera) for distance
    /// `distance_m` along the pixel's ray: (in-scattered light per unit key-light illuminance,
    /// mean transmittance), read from [`SkyTables::aerial`] as the shaders read theirs (the
    /// host helper `stratus_aerial_perspective` of `wgsl/host/aerial_perspective.wgsl` too).
    pub fn aerial_at(&self, u: &FrameUniforms, pixel: [u32; 2], distance_m: f64) -> [f64; 4] {
        self.aerial(&Frame::from_uniforms(u), pixel, distance_m)
    }

    pub(crate) fn for_frame(f: &Frame) -> Self {
        let empty = |size: [usize; 2]| Table {
            width: size[0],
            height: size[1],
            texels: vec![[0.0; 4]; size[0] * size[1]],
        };
        let mut sky = Self {
            air: air_of(f),
            transmittance: empty(TRANSMITTANCE_SIZE),
            multiscatter: empty(MULTISCATTER_SIZE),
            ground_irradiance: empty([GROUND_IRRADIANCE_SIZE, 1]),
            cloud_shadow: Table {
                width: SHADOW_SIZE,
                height: SHADOW_SIZE,
                texels: vec![[1.0; 4]; SHADOW_SIZE * SHADOW_SIZE],
            },
            sky_view: empty(SKY_VIEW_SIZE),
            sky_ambient: empty([SKY_AMBIENT_SUNS, 2]),
            aerial: empty([AERIAL_SLICES * AERIAL_SIDE, AERIAL_SIDE]),
            rainbow: None,
            weather: None,
            timings: Vec::new(),
        };
        // In the graph's order: each table reads the ones before it.
        let mut timings = Vec::with_capacity(PASSES.len());
        sky.transmittance = timed(&mut timings, PASSES[0], || {
            Table::build(TRANSMITTANCE_SIZE, |x, y| sky.transmittance_texel(x, y))
        });
        sky.multiscatter = timed(&mut timings, PASSES[1], || {
            Table::build(MULTISCATTER_SIZE, |x, y| sky.multiscatter_texel(x, y))
        });
        sky.ground_irradiance = timed(&mut timings, PASSES[2], || {
            Table::build([GROUND_IRRADIANCE_SIZE, 1], |x, _| {
                sky.ground_irradiance_texel(x)
            })
        });
        sky.sky_view = timed(&mut timings, PASSES[3], || {
            Table::build(SKY_VIEW_SIZE, |x, y| sky.sky_view_texel(f, x, y))
        });
        sky.sky_ambient = timed(&mut timings, PASSES[4], || {
            Table::build([SKY_AMBIENT_SUNS, 2], |x, y| sky.sky_ambient_texel(f, x, y))
        });
        sky.aerial = timed(&mut timings, PASSES[5], || sky.aerial_table(f));
        if rainbow::uses_table(f) {
            let sun_radius = f.sun_cos_radius.clamp(-1.0, 1.0).acos();
            sky.rainbow = Some(Table::build([rainbow::RAINBOW_TEXELS, 1], |x, _| {
                texel(
                    rainbow::rainbow_lut_texel(x, f.rainbow_drop_radius, sun_radius),
                    1.0,
                )
            }));
        }
        sky.timings = timings;
        sky
    }

    // WGSL: atmosphere.wgsl::air_bottom
    fn bottom(&self) -> f64 {
        self.air.bottom_radius_m
    }

    // WGSL: atmosphere.wgsl::air_top
    fn top(&self) -> f64 {
        self.air.top_radius_m
    }

    // WGSL: atmosphere.wgsl::air_at
    /// The air at altitude `h` (m): Rayleigh scattering, Mie scattering and extinction, per m.
    fn air_at(&self, h: f64) -> AirSample {
        let (rayleigh, mie) = self.air.scattering(h);
        AirSample {
            rayleigh: V3::from_array(rayleigh),
            mie,
            extinction: V3::from_array(self.air.extinction(h)),
        }
    }

    // WGSL: atmosphere.wgsl::distance_to_top
    /// Distance from radius `r` along zenith cosine `mu` to the top of the air.
    fn distance_to_top(&self, r: f64, mu: f64) -> f64 {
        (-r * mu + sphere_discriminant(r, mu, self.top()).max(0.0).sqrt()).max(0.0)
    }

    // WGSL: atmosphere.wgsl::meets_ground
    /// Whether the ray from radius `r` along zenith cosine `mu` meets the ground.
    pub(crate) fn meets_ground(&self, r: f64, mu: f64) -> bool {
        mu < 0.0 && sphere_discriminant(r, mu, self.bottom()) >= 0.0
    }

    // WGSL: atmosphere.wgsl::distance_to_ground
    fn distance_to_ground(&self, r: f64, mu: f64) -> f64 {
        (-r * mu - sphere_discriminant(r, mu, self.bottom()).max(0.0).sqrt()).max(0.0)
    }

    // WGSL: atmosphere.wgsl::transmittance_coords
    /// The transmittance table's coordinates of (r, mu): x from the distance to the top
    /// between its least and greatest at this radius, y from the distance to the horizon.
    fn transmittance_coords(&self, r: f64, mu: f64) -> [f64; 2] {
        let (bottom, top) = (self.bottom(), self.top());
        let h = ((top - bottom) * (top + bottom)).max(0.0).sqrt();
        let rho = ((r - bottom) * (r + bottom)).max(0.0).sqrt();
        let d = self.distance_to_top(r, mu);
        let d_min = top - r;
        let d_max = rho + h;
        [(d - d_min) / (d_max - d_min).max(MIN_SPAN_M), rho / h]
    }

    // WGSL: atmosphere.wgsl::transmittance_r_mu
    /// The inverse: (r, mu) of table coordinates `x`.
    fn transmittance_r_mu(&self, x: [f64; 2]) -> (f64, f64) {
        let (bottom, top) = (self.bottom(), self.top());
        let h = ((top - bottom) * (top + bottom)).max(0.0).sqrt();
        let rho = h * x[1];
        let r = (rho * rho + bottom * bottom).sqrt();
        let d_min = top - r;
        let d_max = rho + h;
        let d = d_min + x[0] * (d_max - d_min);
        let mu = if d > 0.0 {
            ((h * h - rho * rho - d * d) / (2.0 * r * d)).clamp(-1.0, 1.0)
        } else {
            1.0
        };
        (r, mu)
    }

    /// Transmittance (rgb) from radius `r_m` along zenith cosine `mu` to the top of the air,
    /// looked up in the table as the GPU does (the ground ignored).
    pub fn transmittance(&self, r_m: f64, mu: f64) -> [f64; 3] {
        self.transmittance_to_top(r_m, mu).to_array()
    }

    // WGSL: atmosphere.wgsl::transmittance_to_top
    /// Transmittance from radius `r` (m) along zenith cosine `mu` to the top of the air, from
    /// the table (the ground ignored: the caller decides whether the ray meets it).
    pub(crate) fn transmittance_to_top(&self, r: f64, mu: f64) -> V3 {
        rgb(self
            .transmittance
            .bilinear(self.transmittance_coords(r, mu)))
    }

    // WGSL: atmosphere.wgsl::sun_transmittance
    /// The sun's light left at radius `r` for a sun of zenith cosine `mu_s`: 0 behind the
    /// planet.
    pub(crate) fn sun_transmittance(&self, r: f64, mu_s: f64) -> V3 {
        if self.meets_ground(r, mu_s) {
            return V3::ZERO;
        }
        self.transmittance_to_top(r, mu_s)
    }

    // WGSL: atmosphere.wgsl::multiscatter
    /// Psi_ms at radius `r` for a sun of zenith cosine `mu_s`.
    fn multiscatter(&self, r: f64, mu_s: f64) -> V3 {
        let x = [
            mu_s * 0.5 + 0.5,
            (r - self.bottom()) / (self.top() - self.bottom()),
        ];
        rgb(self.multiscatter.bilinear(x))
    }

    // WGSL: atmosphere.wgsl::ground_radiance_sun
    /// The sun's part of the light leaving the lit, diffuse ground where the direction to the
    /// sun has zenith cosine `mu_s`: albedo / pi times the sun's cosine and the sun's light left
    /// there (read a metre up, so that the ray to the sun starts above the sphere it leaves).
    /// The multi-scattering table takes the ground as lit by the sun alone (Hillaire 2020).
    fn ground_radiance_sun(&self, mu_s: f64) -> V3 {
        self.sun_transmittance(self.bottom() + GROUND_LIFT_M, mu_s)
            * (self.air.ground_albedo[0] / PI * mu_s.max(0.0))
    }

    // WGSL: ground.wgsl::ground_radiance
    /// Light leaving the lit ground, sun and sky.
    fn ground_radiance(&self, mu_s: f64) -> V3 {
        self.ground_radiance_sun(mu_s)
            + self.sky_irradiance(mu_s) * (self.air.ground_albedo[0] / PI)
    }

    // WGSL: ground.wgsl::sky_irradiance
    /// The sky's irradiance on the ground for a sun of zenith cosine `mu_s` (the table).
    fn sky_irradiance(&self, mu_s: f64) -> V3 {
        rgb(self.ground_irradiance.bilinear([mu_s * 0.5 + 0.5, 0.0]))
    }

    // WGSL: ground.wgsl::ground_irradiance
    /// Ground-irradiance texel `i`: the cosine-weighted sky radiance over the upper half of 128
    /// Fibonacci directions, 24 steps each, for a sun of zenith cosine 2 i / 63 - 1 (Bruneton
    /// and Neyret 2008's irradiance, at the ground).
    fn ground_irradiance_texel(&self, i: usize) -> Texel {
        let mu_s = i as f64 / (GROUND_IRRADIANCE_SIZE - 1) as f64 * 2.0 - 1.0;
        let sun = V3::new((1.0 - mu_s * mu_s).max(0.0).sqrt(), mu_s, 0.0);
        let origin = V3::new(0.0, self.bottom() + GROUND_LIFT_M, 0.0);
        let mut sum = V3::ZERO;
        for k in 0..GROUND_IRRADIANCE_DIRECTIONS {
            let d = V3::from_array(fibonacci_direction(k, GROUND_IRRADIANCE_DIRECTIONS));
            if d.y <= 0.0 {
                continue;
            }
            let (length, _) = self.air_ray_end(origin, d);
            sum += self
                .integrate_air(origin, d, length, AMBIENT_STEPS, sun, false)
                .radiance
                * d.y;
        }
        texel(sum * (4.0 * PI / GROUND_IRRADIANCE_DIRECTIONS as f64), 1.0)
    }

    /// Computes the cloud-shadow map (the GPU's `cloud-shadow` pass) from `optical_depth`, the
    /// clouds' optical depth (per unit extinction) of the key light's way up from a
    /// camera-relative ground point, and adds its time.
    pub(crate) fn shade(&mut self, f: &Frame, optical_depth: impl Fn(V3) -> f64 + Sync) {
        let sigma_t = f.scattering + f.absorption;
        let map = timed(&mut self.timings, PASSES[6], || {
            Table::build([SHADOW_SIZE, SHADOW_SIZE], |x, y| {
                let rel = shadow_ground_point(f, [x, y]);
                let up = V3::new(rel.x, rel.y + f.planet_radius, rel.z).normalize();
                let tau = if up.dot(f.sun()) > 0.0 {
                    optical_depth(rel)
                } else {
                    0.0
                };
                [(-sigma_t * tau).exp(), 0.0, 0.0, 1.0]
            })
        });
        self.cloud_shadow = map;
    }

    // WGSL: ground.wgsl::ground_shadow
    /// The clouds' transmittance of the key light at camera-relative ground point `rel`: the
    /// map, fading to 1 toward its edge and beyond it.
    fn ground_shadow(&self, rel: V3) -> f64 {
        let edge = rel.x.abs().max(rel.z.abs()) / SHADOW_HALF_EXTENT_M;
        if edge >= 1.0 {
            return 1.0;
        }
        let x = [
            rel.x / (2.0 * SHADOW_HALF_EXTENT_M) + 0.5,
            rel.z / (2.0 * SHADOW_HALF_EXTENT_M) + 0.5,
        ];
        let t = self.cloud_shadow.bilinear(x)[0];
        let w = crate::math::smoothstep(SHADOW_FADE_START, 1.0, edge);
        t + (1.0 - t) * w
    }

    // WGSL: rainbow.wgsl::rainbow_phase_rgb
    /// The bows' phase function (rgb) at `phi` (rad) from the antisolar point.
    fn rainbow_phase_rgb(&self, f: &Frame, phi: f64) -> V3 {
        // The table is built exactly when the frame reads it (`rainbow::uses_table`).
        match &self.rainbow {
            Some(table) => {
                let x = (phi.to_degrees() - rainbow::RAINBOW_MIN_DEG)
                    / (rainbow::RAINBOW_MAX_DEG - rainbow::RAINBOW_MIN_DEG);
                rgb(table.bilinear([x, 0.0]))
            }
            _ => rainbow::cheap_phase_rgb(f, phi),
        }
    }

    // WGSL: rainbow.wgsl::rain_at
    /// The rain at world point `p` under the precipitating layers above it.
    fn rain_at(&self, f: &Frame, map: &stratus_noise::Texture2, p: V3) -> f64 {
        crate::density::cloud_layers(f)
            .filter(|l| l.precipitation > 0.0 && p.y < l.bottom)
            .map(|l| {
                let w = crate::density::sample_weather_map(f, map, p, &l);
                w.precipitation * crate::math::smoothstep(0.35, 0.65, w.coverage)
            })
            .sum()
    }

    // WGSL: rainbow.wgsl::rainbow_radiance
    /// The bows' radiance along unit `view` per unit key-light illuminance: the rain's single
    /// scattering into them where the clouds and the air let the light through, seen through
    /// the air and the rain in front (`RAIN_STEPS` midpoint steps).
    pub(crate) fn rainbow_radiance(&self, f: &Frame, view: V3) -> V3 {
        let Some(map) = self.weather.as_ref().filter(|_| f.rainbow_moisture > 0.0) else {
            return V3::ZERO;
        };
        let light = f.sun();
        let phi = (-view.dot(light)).clamp(-1.0, 1.0).acos();
        if phi < rainbow::RAINBOW_MIN_DEG.to_radians()
            || phi > rainbow::RAINBOW_MAX_DEG.to_radians()
            || light.y <= SHAFT_MIN_SUN_Y
        {
            return V3::ZERO;
        }
        let cam = f.camera_position;
        let top = crate::density::cloud_layers(f)
            .filter(|l| l.precipitation > 0.0)
            .map(|l| l.bottom)
            .fold(0.0, f64::max);
        let mut end = RAIN_RANGE_M;
        if view.y > 0.0 {
            end = end.min((top - cam[1]).max(0.0) / view.y);
        } else if view.y < 0.0 {
            end = end.min(cam[1] / -view.y);
        }
        if end.is_nan() || end <= 0.0 {
            return V3::ZERO;
        }
        let phase = self.rainbow_phase_rgb(f, phi);
        let origin = self.camera_air_origin(f);
        let dt = end / RAIN_STEPS as f64;
        let mut air_tau = V3::ZERO;
        let mut rain_tau = 0.0;
        let mut sum = V3::ZERO;
        for k in 0..RAIN_STEPS {
            let t = (k as f64 + 0.5) * dt;
            let rel = view * t + V3::new(0.0, cam[1], 0.0);
            let world = rel + V3::new(cam[0], 0.0, cam[2]);
            let air = self.air_at(rel.y);
            let beta = RAIN_EXTINCTION
                * f.rainbow_moisture
                * moisture_profile(rel.y)
                * self.rain_at(f, map, world);
            if beta > 0.0 {
                let q = origin + view * t;
                let r = q.length();
                let lit = self.sun_transmittance(r, (q / r).dot(light))
                    * self.ground_shadow(rel - light * (rel.y / light.y));
                let seen = exp_neg(air_tau + air.extinction * (0.5 * dt))
                    * (-(rain_tau + 0.5 * beta * dt)).exp();
                sum += lit.mul_v(seen) * (beta * dt);
            }
            air_tau += air.extinction * dt;
            rain_tau += beta * dt;
        }
        sum.mul_v(phase)
    }

    // WGSL: ground.wgsl::ground_shadow_loss
    /// The part of the sky-view table's ground light (per unit key-light illuminance) along
    /// `view` from the camera at radius `r` that the clouds' shadow takes away: the ground's
    /// sun term where the ray meets it, through the air back to the camera (the ratio of two
    /// transmittances to the top, Bruneton 2017), times the shadow's share.
    pub(crate) fn ground_shadow_loss(&self, f: &Frame, view: V3, r: f64) -> V3 {
        let t = self.distance_to_ground(r, view.y);
        let cam_alt = f.camera_position[1].max(0.0);
        let shadow = self.ground_shadow(view * t + V3::new(0.0, cam_alt, 0.0));
        if shadow >= 1.0 {
            return V3::ZERO;
        }
        let r_g = self.bottom();
        let sun = f.sun();
        let mu_g = ((r * view.y + t) / r_g).clamp(-1.0, 1.0);
        let mu_s = ((r * sun.y + t * view.dot(sun)) / r_g).clamp(-1.0, 1.0);
        let near = self.transmittance_to_top(r_g, -mu_g);
        let far = self.transmittance_to_top(r, -view.y);
        let ratio = |a: f64, b: f64| (a / b.max(1e-20)).min(1.0);
        let t_view = V3::new(
            ratio(near.x, far.x),
            ratio(near.y, far.y),
            ratio(near.z, far.z),
        );
        t_view.mul_v(self.ground_radiance_sun(mu_s)) * (1.0 - shadow)
    }

    // WGSL: composite.wgsl::shaft_shade
    /// The shade (1 - transmittance toward the key light) at camera-relative `rel` (m): the
    /// map's at the point's projection along the light onto the ground below the layers'
    /// lowest bottom, thinning linearly to none at their highest top (`span`, m).
    fn shaft_shade(&self, f: &Frame, rel: V3, span: (f64, f64)) -> f64 {
        if rel.y >= span.1 {
            return 0.0;
        }
        let sun = f.sun();
        let shade = 1.0 - self.ground_shadow(rel - sun * (rel.y / sun.y));
        shade * (1.0 - saturate((rel.y - span.0) / (span.1 - span.0)))
    }

    // WGSL: composite.wgsl::light_shafts
    /// Light shafts: the key light's single scattering by the air that the clouds shade along
    /// `view` from the camera, per unit illuminance, over the ray's first `split` m (the
    /// clouds' depth; `.0`) and to `end` m (`.1`): `SHAFT_STEPS` even segments over the first
    /// `SHAFT_RANGE_M` (looking up, not past the layers' top), one sample a segment at the
    /// pixel's dithered place; a segment the split cuts counts toward the front by its part in
    /// front.
    pub(crate) fn light_shafts(
        &self,
        f: &Frame,
        pixel: [u32; 2],
        view: V3,
        split: f64,
        end: f64,
    ) -> (V3, V3) {
        let mut front = V3::ZERO;
        let mut all = V3::ZERO;
        let sun = f.sun();
        let span = crate::density::layers_span(f);
        let cam_alt = f.camera_position[1].max(0.0);
        let mut end = end.min(SHAFT_RANGE_M);
        if view.y > 0.0 {
            end = end.min((span.1 - cam_alt).max(0.0) / view.y);
        }
        if sun.y <= SHAFT_MIN_SUN_Y || end.is_nan() || end <= 0.0 {
            return (front, all);
        }
        let origin = self.camera_air_origin(f);
        let cos_theta = view.dot(sun);
        let phase_r = phase_rayleigh(cos_theta);
        let phase_m = phase_cornette_shanks(cos_theta, self.air.mie_g);
        let dt = end / SHAFT_STEPS as f64;
        let offset = crate::frame::hash_unit(pixel, SHAFT_SALT);
        let mut tau = V3::ZERO;
        for k in 0..SHAFT_STEPS {
            let t = (k as f64 + offset) * dt;
            let p = origin + view * t;
            let r = p.length();
            let air = self.air_at(r - self.bottom());
            let shade = self.shaft_shade(f, view * t + V3::new(0.0, cam_alt, 0.0), span);
            if shade > 0.0 {
                let t_view = exp_neg(tau + air.extinction * (offset * dt));
                let single = self
                    .sun_transmittance(r, (p / r).dot(sun))
                    .mul_v(air.rayleigh * phase_r + V3::splat(air.mie * phase_m));
                let lost = t_view.mul_v(single) * (shade * dt);
                all += lost;
                front += lost * saturate((split - k as f64 * dt) / dt);
            }
            tau += air.extinction * dt;
        }
        (front, all)
    }

    // WGSL: atmosphere.wgsl::integrate_air
    /// In-scattered light and transmittance along the ray from `origin` (planet centre at the
    /// origin) along unit `d` for `distance` metres in `steps` segments whose ends go as the
    /// square of their index (short near the camera, where the air is dense), the sun along
    /// unit `sun`; with `ground`, the lit ground at the end is added through the air. Single
    /// scattering by the transmittance table and the higher orders by Psi_ms (Hillaire 2020,
    /// eq. 11).
    fn integrate_air(
        &self,
        origin: V3,
        d: V3,
        distance: f64,
        steps: u32,
        sun: V3,
        ground: bool,
    ) -> Scattered {
        let cos_theta = d.dot(sun);
        let phase_r = phase_rayleigh(cos_theta);
        let phase_m = phase_cornette_shanks(cos_theta, self.air.mie_g);
        let mut radiance = V3::ZERO;
        let mut tau = V3::ZERO;
        let mut t0 = 0.0;
        for i in 0..steps {
            let s1 = f64::from(i + 1) / f64::from(steps);
            let t1 = distance * s1 * s1;
            let dt = t1 - t0;
            let (air, inscatter) =
                self.inscatter(origin + d * (0.5 * (t0 + t1)), sun, phase_r, phase_m);
            // Transmittance to the segment's middle: the depth so far plus half the segment.
            let t_view = exp_neg(tau + air.extinction * (0.5 * dt));
            radiance += t_view.mul_v(inscatter) * dt;
            tau += air.extinction * dt;
            t0 = t1;
        }
        if ground {
            let end = origin + d * distance;
            radiance += exp_neg(tau).mul_v(self.ground_radiance(end.normalize().dot(sun)));
        }
        Scattered {
            radiance,
            transmittance: exp_neg(tau),
        }
    }

    // WGSL: atmosphere.wgsl::integrate_air and ::aerial_perspective (the loop's body)
    /// The air at point `p` (planet centre at the origin) and the light it scatters toward the
    /// viewer per unit length: single scattering of the sun through the transmittance table
    /// and the higher orders by Psi_ms (Hillaire 2020, eq. 11).
    fn inscatter(&self, p: V3, sun: V3, phase_r: f64, phase_m: f64) -> (AirSample, V3) {
        let r = p.length();
        let mu_s = (p / r).dot(sun);
        let air = self.air_at(r - self.bottom());
        let light = self
            .sun_transmittance(r, mu_s)
            .mul_v(air.rayleigh * phase_r + V3::splat(air.mie * phase_m))
            + self
                .multiscatter(r, mu_s)
                .mul_v(air.rayleigh + V3::splat(air.mie));
        (air, light)
    }

    // WGSL: atmosphere.wgsl::air_ray_end
    /// How far the ray from `origin` along `d` goes in the air and whether it ends on the
    /// ground; `(0, false)` from outside the air (no scene reaches there).
    pub(crate) fn air_ray_end(&self, origin: V3, d: V3) -> (f64, bool) {
        let r = origin.length();
        let mu = origin.dot(d) / r;
        if self.meets_ground(r, mu) {
            return (self.distance_to_ground(r, mu), true);
        }
        if r > self.top() {
            return (0.0, false);
        }
        (self.distance_to_top(r, mu), false)
    }

    // WGSL: atmosphere.wgsl::camera_air_origin
    /// The camera's place in the air: the planet's centre straight below it.
    pub(crate) fn camera_air_origin(&self, f: &Frame) -> V3 {
        V3::new(0.0, self.bottom() + f.camera_position[1].max(0.0), 0.0)
    }

    // WGSL: atmosphere.wgsl::transmittance_lut
    /// Transmittance texel (x, y): the composite Simpson rule on 128 intervals to the top.
    fn transmittance_texel(&self, x: usize, y: usize) -> Texel {
        let last = TRANSMITTANCE_SIZE.map(|s| (s - 1) as f64);
        let (r, mu) = self.transmittance_r_mu([x as f64 / last[0], y as f64 / last[1]]);
        let dt = self.distance_to_top(r, mu) / f64::from(TRANSMITTANCE_STEPS);
        let mut sum = V3::ZERO;
        for i in 0..=TRANSMITTANCE_STEPS {
            let w = if i == 0 || i == TRANSMITTANCE_STEPS {
                1.0
            } else if i & 1 == 1 {
                4.0
            } else {
                2.0
            };
            let ri = radius_after(r, mu, dt * f64::from(i));
            sum += self.air_at(ri - self.bottom()).extinction * w;
        }
        texel(exp_neg(sum * (dt / 3.0)), 1.0)
    }

    // WGSL: atmosphere.wgsl::multiscatter_lut
    /// Multi-scattering texel (x, y): Hillaire's Psi_ms = L2 / (1 - f_ms) (2020, eqs. 5-9)
    /// over 64 Fibonacci directions of 32 midpoint steps each, the sun's light read from the
    /// transmittance table.
    fn multiscatter_texel(&self, x: usize, y: usize) -> Texel {
        let last = MULTISCATTER_SIZE.map(|s| (s - 1) as f64);
        let u = [x as f64 / last[0], y as f64 / last[1]];
        let mu_s = u[0] * 2.0 - 1.0;
        let r = self.bottom() + u[1] * (self.top() - self.bottom());
        let origin = V3::new(0.0, r, 0.0);
        let sun = V3::new((1.0 - mu_s * mu_s).max(0.0).sqrt(), mu_s, 0.0);
        let isotropic = 1.0 / (4.0 * PI);
        let mut l2 = V3::ZERO;
        let mut f_ms = V3::ZERO;
        for k in 0..MULTISCATTER_DIRECTIONS {
            let d = V3::from_array(fibonacci_direction(k, MULTISCATTER_DIRECTIONS));
            let (length, ground) = self.air_ray_end(origin, d);
            let dt = length / f64::from(MULTISCATTER_STEPS);
            let mut tau = V3::ZERO;
            for i in 0..MULTISCATTER_STEPS {
                let p = origin + d * (dt * (f64::from(i) + 0.5));
                let rp = p.length();
                let air = self.air_at(rp - self.bottom());
                let t = exp_neg(tau + air.extinction * (0.5 * dt));
                let s = air.rayleigh + V3::splat(air.mie);
                let ts = t.mul_v(s);
                l2 += ts.mul_v(self.sun_transmittance(rp, (p / rp).dot(sun))) * (isotropic * dt);
                f_ms += ts * dt;
                tau += air.extinction * dt;
            }
            if ground {
                let g = origin + d * length;
                l2 += exp_neg(tau).mul_v(self.ground_radiance_sun(g.normalize().dot(sun)));
            }
        }
        let w = 1.0 / MULTISCATTER_DIRECTIONS as f64;
        let psi = |l2: f64, f_ms: f64| (l2 * w) / (1.0 - f_ms * w).max(1e-6);
        [psi(l2.x, f_ms.x), psi(l2.y, f_ms.y), psi(l2.z, f_ms.z), 1.0]
    }

    // WGSL: atmosphere.wgsl::horizon_elevation
    /// Elevation of the horizon seen from radius `r`.
    fn horizon_elevation(&self, r: f64) -> f64 {
        -(self.bottom() / r).clamp(-1.0, 1.0).acos()
    }

    // WGSL: atmosphere.wgsl::sky_view_lut
    /// Sky-view texel (x, y): 48 steps of `integrate_air` from the camera, azimuth relative to
    /// the sun in [0, pi] (the sky is symmetric about the sun's vertical).
    fn sky_view_texel(&self, f: &Frame, x: usize, y: usize) -> Texel {
        let last = SKY_VIEW_SIZE.map(|s| (s - 1) as f64);
        let u = [x as f64 / last[0], y as f64 / last[1]];
        let origin = self.camera_air_origin(f);
        let elevation = sky_view_elevation(u[1], self.horizon_elevation(origin.y));
        let phi = sun_azimuth(f) + u[0] * PI;
        let d = V3::new(
            elevation.cos() * phi.cos(),
            elevation.sin(),
            elevation.cos() * phi.sin(),
        );
        texel(self.sky_along(f, origin, d), 1.0)
    }

    // WGSL: atmosphere.wgsl::sky_along
    /// The sky's radiance (per unit sun illuminance) seen from `origin` (planet centre at the
    /// origin) along unit `d`, the lit ground included where the ray meets it: 48 steps of
    /// `integrate_air` to where the ray leaves the air. The sky-view table's texels from the
    /// camera, and the path tracer's environment from a path's last collision.
    fn sky_along(&self, f: &Frame, origin: V3, d: V3) -> V3 {
        let (length, ground) = self.air_ray_end(origin, d);
        self.integrate_air(origin, d, length, SKY_VIEW_STEPS, f.sun(), ground)
            .radiance
    }

    // WGSL: atmosphere.wgsl::sky_from
    /// The sky's radiance (per unit sun illuminance) seen from camera-relative `rel` (m) along
    /// unit `d` (`sky_along` from that point; `sun_through_air`'s coordinates).
    pub(crate) fn sky_from(&self, f: &Frame, rel: V3, d: V3) -> V3 {
        self.sky_along(f, V3::new(rel.x, rel.y + f.planet_radius, rel.z), d)
    }

    // WGSL: atmosphere.wgsl::sky_view
    /// The sky's radiance (per unit sun illuminance) seen from the camera along unit `d`: the
    /// sky-view table, ground included.
    pub(crate) fn sky_view(&self, f: &Frame, d: V3) -> V3 {
        let origin = self.camera_air_origin(f);
        let elevation = d.y.clamp(-1.0, 1.0).asin();
        let delta = d.z.atan2(d.x) - sun_azimuth(f);
        // WGSL's `round` breaks ties to even.
        let delta = (delta - 2.0 * PI * (delta / (2.0 * PI)).round_ties_even()).abs();
        let x = [
            delta / PI,
            sky_view_v(elevation, self.horizon_elevation(origin.y)),
        ];
        rgb(self.sky_view.bilinear(x))
    }

    // WGSL: atmosphere.wgsl::aerial_perspective
    /// Froxel column `c` marched through its 32 slices in order, four midpoint steps a slice,
    /// stopping where the ray leaves the air or meets the ground: slice z holds the light
    /// scattered toward the camera over the first (z + 1) km (rgb) and the mean transmittance
    /// over them (a).
    fn aerial_column(&self, f: &Frame, c: [usize; 2]) -> [Texel; AERIAL_SLICES] {
        let d = aerial_ray(f, c);
        let origin = self.camera_air_origin(f);
        let (end, _) = self.air_ray_end(origin, d);
        let sun = f.sun();
        let cos_theta = d.dot(sun);
        let phase_r = phase_rayleigh(cos_theta);
        let phase_m = phase_cornette_shanks(cos_theta, self.air.mie_g);
        let mut radiance = V3::ZERO;
        let mut tau = V3::ZERO;
        let sub = f64::from(AERIAL_SUBSTEPS);
        std::array::from_fn(|z| {
            for k in 0..AERIAL_SUBSTEPS {
                let t0 = AERIAL_SLICE_M * (z as f64 + f64::from(k) / sub);
                let dt = (AERIAL_SLICE_M / sub).min(end - t0).max(0.0);
                let (air, inscatter) =
                    self.inscatter(origin + d * (t0 + 0.5 * dt), sun, phase_r, phase_m);
                let t_view = exp_neg(tau + air.extinction * (0.5 * dt));
                radiance += t_view.mul_v(inscatter) * dt;
                tau += air.extinction * dt;
            }
            let t = exp_neg(tau);
            texel(radiance, (t.x + t.y + t.z) / 3.0)
        })
    }

    /// The aerial-perspective atlas: every froxel column (in parallel), slice z of column
    /// (x, y) at texel (z * 32 + x, y).
    fn aerial_table(&self, f: &Frame) -> Table {
        let columns: Vec<[Texel; AERIAL_SLICES]> = (0..AERIAL_SIDE * AERIAL_SIDE)
            .into_par_iter()
            .map(|i| self.aerial_column(f, [i % AERIAL_SIDE, i / AERIAL_SIDE]))
            .collect();
        let width = AERIAL_SLICES * AERIAL_SIDE;
        let mut texels = vec![[0.0; 4]; width * AERIAL_SIDE];
        for (i, column) in columns.iter().enumerate() {
            let (x, y) = (i % AERIAL_SIDE, i / AERIAL_SIDE);
            for (z, t) in column.iter().enumerate() {
                texels[y * width + z * AERIAL_SIDE + x] = *t;
            }
        }
        Table {
            width,
            height: AERIAL_SIDE,
            texels,
        }
    }

    // WGSL: atmosphere.wgsl::aerial
    /// Aerial perspective at `pixel` for depth `depth_m`: (in-scattered light per unit sun
    /// illuminance, mean transmittance), bilinear in the froxel grid and linear between slices
    /// (0 m is no air: nothing scattered, transmittance 1).
    pub(crate) fn aerial(&self, f: &Frame, pixel: [u32; 2], depth_m: f64) -> Texel {
        let side = AERIAL_SIDE as f64;
        let uv = [0, 1].map(|a| (f64::from(pixel[a]) + 0.5) / f64::from(f.size[a]));
        // Froxel centres sit at (c + 0.5) / side.
        let fc = uv.map(|u| (u * side - 0.5).clamp(0.0, side - 1.0));
        let c0 = fc.map(|v| (v.floor() as usize).min(AERIAL_SIDE - 1));
        let c1 = c0.map(|c| (c + 1).min(AERIAL_SIDE - 1));
        let w = [fc[0] - c0[0] as f64, fc[1] - c0[1] as f64];
        // Slice z holds depth (z + 1) km; depth 0 is the camera.
        let s = (depth_m / AERIAL_SLICE_M).clamp(0.0, AERIAL_SLICES as f64);
        let z1 = (s.ceil() as usize).min(AERIAL_SLICES);
        let z0 = z1.saturating_sub(1);
        let ws = s - z0 as f64;
        let clear = [0.0, 0.0, 0.0, 1.0];
        let near = if z0 > 0 {
            self.aerial_texel(c0, c1, w, z0 - 1)
        } else {
            clear
        };
        let far = if z1 > 0 {
            self.aerial_texel(c0, c1, w, z1 - 1)
        } else {
            clear
        };
        mix4(near, far, ws)
    }

    // WGSL: atmosphere.wgsl::aerial_texel
    fn aerial_texel(&self, c0: [usize; 2], c1: [usize; 2], w: [f64; 2], z: usize) -> Texel {
        let o = z * AERIAL_SIDE;
        let t = &self.aerial;
        let a = mix4(t.load(o + c0[0], c0[1]), t.load(o + c1[0], c0[1]), w[0]);
        let b = mix4(t.load(o + c0[0], c1[1]), t.load(o + c1[0], c1[1]), w[0]);
        mix4(a, b, w[1])
    }

    // WGSL: atmosphere.wgsl::sky_ambient
    /// Sky-ambient texel (i, j) (j = 0: from below, 1: from above): the cosine-weighted mean
    /// radiance of the lower or upper hemisphere seen from the cloud layer's bottom (the
    /// light from above includes the air between the layer's clouds), sky and lit ground,
    /// over 32 of 64 Fibonacci directions of 24 steps, for a sun of zenith cosine t |t|,
    /// t = 2 i / 63 - 1 (`sky_ambient_x`).
    fn sky_ambient_texel(&self, f: &Frame, i: usize, j: usize) -> Texel {
        let t = i as f64 / (SKY_AMBIENT_SUNS - 1) as f64 * 2.0 - 1.0;
        let mu_s = t * t.abs();
        let sun = V3::new((1.0 - mu_s * mu_s).max(0.0).sqrt(), mu_s, 0.0);
        let origin = V3::new(0.0, self.bottom() + f.cloud_bottom, 0.0);
        let mut sum = V3::ZERO;
        let mut weights = 0.0;
        // The hemisphere, cosine-weighted: the upper half of the Fibonacci directions (they
        // run from the zenith down) from above, the lower from below.
        let half = AMBIENT_DIRECTIONS / 2;
        let first = if j == 1 { 0 } else { half };
        for k in first..first + half {
            let d = V3::from_array(fibonacci_direction(k, AMBIENT_DIRECTIONS));
            let (length, ground) = self.air_ray_end(origin, d);
            let w = d.y.abs();
            sum += self
                .integrate_air(origin, d, length, AMBIENT_STEPS, sun, ground)
                .radiance
                * w;
            weights += w;
        }
        texel(sum / weights, 1.0)
    }

    // WGSL: atmosphere.wgsl::sun_through_air
    /// The sun's light (per unit illuminance at the top of the air) reaching a cloud sample at
    /// camera-relative `rel` (m).
    pub(crate) fn sun_through_air(&self, f: &Frame, rel: V3) -> V3 {
        let q = V3::new(rel.x, rel.y + f.planet_radius, rel.z);
        let r = q.length();
        self.sun_transmittance(r, (q / r).dot(f.sun()))
    }

    // WGSL: atmosphere.wgsl::sky_ambient_light
    /// The clouds' ambient light at height fraction `h` of the main layer at camera-relative
    /// `rel` (m): the sky-ambient table at the sun's zenith cosine there, times the sun's
    /// illuminance and the ambient strength.
    pub(crate) fn ambient_light(&self, f: &Frame, h: f64, rel: V3) -> V3 {
        let q = V3::new(rel.x, rel.y + f.planet_radius, rel.z);
        let x = sky_ambient_x(q.normalize().dot(f.sun()));
        let bottom = rgb(self.sky_ambient.bilinear([x, 0.0]));
        let top = rgb(self.sky_ambient.bilinear([x, 1.0]));
        mix_v(bottom, top, h).mul_v(f.sun_illuminance()) * f.ambient_strength
    }
}

// WGSL: atmosphere.wgsl::sky_ambient_x
/// The sky-ambient table's column coordinate (0 to 1) of a sun of zenith cosine `mu`: the square
/// root of |mu|, so that the columns lie densest at the horizon, where the sky's light changes
/// fastest with the sun's angle.
pub(crate) fn sky_ambient_x(mu: f64) -> f64 {
    0.5 + 0.5 * mu.signum() * mu.abs().sqrt()
}

// WGSL: ground.wgsl::shadow_ground_point
/// The ground point of shadow-map texel `c`, relative to the ground below the camera (m): on
/// the planet's surface, texel i at (2 i / (size - 1) - 1) times the half extent.
pub(crate) fn shadow_ground_point(f: &Frame, c: [usize; 2]) -> V3 {
    let s = |i: usize| (i as f64 / (SHADOW_SIZE - 1) as f64 * 2.0 - 1.0) * SHADOW_HALF_EXTENT_M;
    let (x, z) = (s(c[0]), s(c[1]));
    let rp = f.planet_radius;
    let s2 = x * x + z * z;
    V3::new(x, -s2 / ((rp * rp - s2).max(0.0).sqrt() + rp), z)
}

/// A CPU frame's pass times in the frame graph's order: the sky's tables (under the physical
/// sky), the cloud passes `clouds` (march, resolve, path tracer), the cloud-shadow map, then
/// `composite`. (The CPU makes the shadow map before the march; the graph after it.)
pub(crate) fn in_graph_order(
    sky: Option<&SkyTables>,
    clouds: impl IntoIterator<Item = PassTiming>,
    composite: PassTiming,
) -> Vec<PassTiming> {
    let tables = sky.map(|s| s.timings.as_slice()).unwrap_or_default();
    let (shadow, before): (Vec<PassTiming>, Vec<PassTiming>) =
        tables.iter().cloned().partition(|t| t.pass == PASSES[6]);
    before
        .into_iter()
        .chain(clouds)
        .chain(shadow)
        .chain([composite])
        .collect()
}

/// `build()`, its wall-clock time added to `timings` as `pass`.
fn timed<T>(timings: &mut Vec<PassTiming>, pass: &str, build: impl FnOnce() -> T) -> T {
    let t = Instant::now();
    let out = build();
    timings.push(PassTiming {
        pass: pass.to_string(),
        ms: t.elapsed().as_secs_f64() * 1e3,
        source: "cpu-wall",
    });
    out
}

/// `exp(-tau)` per channel.
fn exp_neg(tau: V3) -> V3 {
    V3::new((-tau.x).exp(), (-tau.y).exp(), (-tau.z).exp())
}

/// The tables when the frame is under the physical sky (the WGSL's `physical_sky()` guard,
/// `Frame::physical_sky`, with the tables it guards).
pub(crate) fn physical<'a>(f: &Frame, sky: Option<&'a SkyTables>) -> Option<&'a SkyTables> {
    sky.filter(|_| f.physical_sky())
}

// WGSL: atmosphere.wgsl::sun_through_air (its guard; the lookup is the method's)
/// The sun's light reaching a cloud sample at camera-relative `rel`: 1 without the physical
/// sky.
pub(crate) fn sun_through_air(f: &Frame, sky: Option<&SkyTables>, rel: V3) -> V3 {
    match physical(f, sky) {
        Some(sky) => sky.sun_through_air(f, rel),
        None => V3::splat(1.0),
    }
}

#[cfg(test)]
mod tests {
    use stratus_graph::{Backend, FrameInput, FramePlan};
    use stratus_scene::{Scene, SkyModel};

    use super::*;
    use crate::composite::physical_composite;
    use crate::geometry::view_ray;
    use crate::medium::{Medium, Model};

    // Small noise textures: the tests look at the sky, not at the clouds' detail.
    use crate::small_noise as noise;

    fn luminance(c: V3) -> f64 {
        0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
    }

    /// What a preset's clear sky looks like in linear radiance on the CPU: the mean radiance
    /// of the pixels above the horizon where the march left transmittance 1, composited as
    /// the CPU backend composites them.
    struct Look {
        clear_sky: V3,
        clear_pixels: usize,
    }

    /// Renders `preset` at 64x36 through the CPU backend (as `stratus render --backend cpu`
    /// does) and checks what every physical-sky frame must satisfy.
    fn render_preset(preset: &str) -> Look {
        let scene = Scene::preset(preset).expect("preset").with_size(64, 36);
        assert!(scene.atmosphere.sky.is_physical(), "{preset}");
        let noise = noise();
        let plan = FramePlan::for_scene(&scene, false).expect("plan");
        let mut cpu = crate::CpuBackend::default();
        let out = cpu
            .render(&FrameInput::new(&plan, &scene, &noise))
            .unwrap_or_else(|e| panic!("{preset}: the CPU refused the physical sky: {e}"));
        assert!(
            out.radiance.iter().all(|v| v.is_finite() && *v >= 0.0),
            "{preset}: a radiance is negative or not finite"
        );
        assert!(out.depth.iter().all(|v| v.is_finite() && *v >= 0.0));
        assert_eq!(out.image.len(), 64 * 36 * 4);
        // The tables are reported under the graph's pass names, before the march.
        let names: Vec<&str> = out.timings.iter().map(|t| t.pass.as_str()).collect();
        assert_eq!(names[..6], PASSES[..6], "{preset}: {names:?}");
        assert_eq!(
            names[6..],
            ["march", "cloud-shadow", "composite"],
            "{preset}: {names:?}"
        );
        for t in &out.timings[..7] {
            eprintln!("{preset}: {} {:.1} ms", t.pass, t.ms);
        }

        let model = Model::new(&scene, Medium::Clouds(&noise));
        let f = &model.f;
        let sky = model.sky().expect("the physical sky's tables");
        let r = sky.camera_air_origin(f).y;
        let mut sum = V3::ZERO;
        let mut clear_pixels = 0;
        for y in 0..36u32 {
            for x in 0..64u32 {
                let i = (y * 64 + x) as usize;
                let cloud = [0, 1, 2, 3].map(|c| f64::from(out.radiance[4 * i + c]));
                let view = view_ray(f, [x, y]);
                let l = physical_composite(
                    f,
                    sky,
                    [x, y],
                    view,
                    cloud,
                    f64::from(out.depth[i]),
                    false,
                    None,
                );
                assert!(
                    [l.x, l.y, l.z].iter().all(|v| v.is_finite() && *v >= 0.0),
                    "{preset}: pixel ({x}, {y}) composites to {l:?}"
                );
                if cloud[3] > 0.999 && !sky.meets_ground(r, view.y) {
                    sum += l;
                    clear_pixels += 1;
                }
            }
        }
        assert!(clear_pixels > 0, "{preset}: no clear sky in view");
        Look {
            clear_sky: sum / clear_pixels as f64,
            clear_pixels,
        }
    }

    #[test]
    fn the_cpu_renders_the_physical_sky_presets_plausibly() {
        let noon = render_preset("noon");
        let dawn = render_preset("dawn");
        let dusk = render_preset("dusk");
        let night = render_preset("night");
        for (name, l) in [
            ("noon", &noon),
            ("dawn", &dawn),
            ("dusk", &dusk),
            ("night", &night),
        ] {
            eprintln!(
                "{name}: clear sky {:?} (luminance {:.3e}) over {} pixels",
                l.clear_sky,
                luminance(l.clear_sky),
                l.clear_pixels
            );
        }
        let (noon_l, dusk_l, night_l) = (
            luminance(noon.clear_sky),
            luminance(dusk.clear_sky),
            luminance(night.clear_sky),
        );
        // Rayleigh's sky at noon is blue.
        assert!(
            noon.clear_sky.z > noon.clear_sky.x,
            "noon sky {:?}",
            noon.clear_sky
        );
        // The sun 4 degrees below the horizon lights the sky by twilight only, and the
        // moonlit sky (2e-6 of the sun's light at most) is far darker still.
        assert!(
            noon_l > 10.0 * dusk_l,
            "noon {noon_l:.3e}, dusk {dusk_l:.3e}"
        );
        assert!(dusk_l > night_l, "dusk {dusk_l:.3e}, night {night_l:.3e}");
        assert!(
            noon_l > 1e4 * night_l,
            "noon {noon_l:.3e}, night {night_l:.3e}"
        );
        // Toward a sun 2 degrees up the long light paths redden the sky.
        let redness = |c: V3| c.x / c.z;
        assert!(
            redness(dawn.clear_sky) > redness(noon.clear_sky),
            "dawn {:?}, noon {:?}",
            dawn.clear_sky,
            noon.clear_sky
        );
    }

    /// The night preset with the camera aimed at the moon through a 1-degree field of view,
    /// composited over a clear sky (no clouds in front): the disc is far brighter than the sky
    /// around it, its lit part is the moon's illuminated fraction, and that part faces the sun.
    #[test]
    fn the_moon_is_brighter_than_the_night_sky_and_lit_toward_the_sun() {
        let mut scene = Scene::preset("night").expect("preset").with_size(64, 36);
        let (moon, fraction) = scene.moon().expect("a moon at night");
        scene.camera.yaw_deg = moon[0].atan2(moon[2]).to_degrees();
        scene.camera.pitch_deg = moon[1].asin().to_degrees();
        scene.camera.fov_y_deg = 1.0;
        let noise = noise();
        let model = Model::new(&scene, Medium::Clouds(&noise));
        let f = &model.f;
        assert!(f.flags & crate::frame::FLAG_MOONLIT != 0);
        let sky = model.sky().expect("tables");
        let m = xyz(f.moon_direction);
        let clear = [0.0, 0.0, 0.0, 1.0];
        let mut disc = Vec::new();
        let mut outside = Vec::new();
        for y in 0..36u32 {
            for x in 0..64u32 {
                let view = view_ray(f, [x, y]);
                let l = luminance(physical_composite(
                    f,
                    sky,
                    [x, y],
                    view,
                    clear,
                    0.0,
                    false,
                    None,
                ));
                if view.dot(m) >= 0.999_989_78 {
                    disc.push((x, y, l));
                } else if view.dot(m) < 0.999_97 {
                    outside.push(l);
                }
            }
        }
        // A disc of radius 0.259 degrees is 9.3 pixels across here.
        assert!(disc.len() > 200, "{} disc pixels", disc.len());
        let brightest = disc.iter().map(|d| d.2).fold(0.0, f64::max);
        let sky_max = outside.iter().copied().fold(0.0, f64::max);
        assert!(
            brightest > 100.0 * sky_max,
            "moon {brightest:.3e}, sky around it {sky_max:.3e}"
        );
        let lit: Vec<_> = disc.iter().filter(|d| d.2 > 0.5 * brightest).collect();
        let lit_fraction = lit.len() as f64 / disc.len() as f64;
        eprintln!(
            "moon: {} disc pixels, lit {lit_fraction:.3} (illuminated fraction {fraction:.3}), \
             brightest {brightest:.3e} against the sky's {sky_max:.3e}",
            disc.len()
        );
        assert!(
            (lit_fraction - fraction).abs() < 0.06,
            "lit {lit_fraction:.3} of the disc, illuminated fraction {fraction:.3}"
        );
        // The lit part's centre lies toward the sun (on the image: x right, y down).
        let centre = |p: &[&(u32, u32, f64)]| {
            let n = p.len() as f64;
            [
                p.iter().map(|d| f64::from(d.0)).sum::<f64>() / n,
                p.iter().map(|d| f64::from(d.1)).sum::<f64>() / n,
            ]
        };
        let all: Vec<_> = disc.iter().collect();
        let (c_lit, c_disc) = (centre(&lit), centre(&all));
        let sun = xyz(f.real_sun_direction);
        let toward = [sun.dot(xyz(f.camera_right)), -sun.dot(xyz(f.camera_up))];
        let shift = [c_lit[0] - c_disc[0], c_lit[1] - c_disc[1]];
        assert!(
            shift[0] * toward[0] + shift[1] * toward[1] > 0.0,
            "lit part shifted by {shift:?}, the sun toward {toward:?}"
        );
    }

    /// The march's two lookups: the sun's light at a cloud sample is the air's transmittance
    /// toward the sun there (the direct integration's, within the table's interpolation), and
    /// the ambient is the sky-ambient table's; neither applies under the analytic sky.
    #[test]
    fn the_march_sees_the_sun_through_the_air_and_the_skys_ambient() {
        let mut scene = Scene::preset("dawn").expect("preset").with_size(16, 9);
        let noise = noise();
        let model = Model::new(&scene, Medium::Clouds(&noise));
        let f = &model.f;
        let sky = model.sky().expect("tables");
        let air = sky.air();
        for rel in [
            V3::new(0.0, 1500.0, 0.0),
            V3::new(20_000.0, 4000.0, -5000.0),
        ] {
            let got = sun_through_air(f, Some(sky), rel);
            let p = [rel.x, rel.y + f.planet_radius, rel.z];
            let want = air.transmittance_to_top(p, f.sun().to_array());
            for c in 0..3 {
                assert!(
                    (got.to_array()[c] - want[c]).abs() < 2e-3,
                    "{rel:?}: {got:?} against {want:?}"
                );
            }
        }
        // A low sun: red passes, blue much less.
        let t = sun_through_air(f, Some(sky), V3::new(0.0, 1500.0, 0.0));
        assert!(t.x > 2.0 * t.z, "{t:?}");
        // Below the camera the sun's zenith cosine is its direction's y: the ambient is the
        // table's bottom row there.
        let bottom = crate::lighting::ambient(f, Some(sky), 0.0, V3::ZERO);
        let x = sky_ambient_x(f.sun().y);
        let want =
            rgb(sky.sky_ambient.bilinear([x, 0.0])).mul_v(f.sun_illuminance()) * f.ambient_strength;
        assert_eq!(bottom, want);
        assert!(bottom.x > 0.0 && bottom.z > 0.0);
        // 200 km toward the sun it stands about 1.8 degrees higher: a brighter ambient.
        let toward = V3::new(f.sun().x, 0.0, f.sun().z).normalize() * 200_000.0;
        let there = crate::lighting::ambient(f, Some(sky), 0.0, toward);
        assert!(
            there.y > 1.2 * bottom.y,
            "{there:?} 200 km toward the sun against {bottom:?} below the camera"
        );

        scene.atmosphere.sky = SkyModel::Analytic;
        let analytic = Model::new(&scene, Medium::Clouds(&noise));
        assert!(analytic.sky().is_none());
        assert_eq!(
            sun_through_air(&analytic.f, None, V3::new(0.0, 1500.0, 0.0)),
            V3::splat(1.0)
        );
    }
}
