//! What fills the cloud layer: the scene's clouds (the WGSL's density field) or an analytic
//! homogeneous medium for tests against closed forms. Both integrators run on either.

use stratus_noise::NoiseSet;
use stratus_scene::Scene;

use crate::density::{
    Counters, Layer, Weather, cloud_density, cloud_layers, layer_density_with, sample_weather,
    uniform_weather,
};
use crate::frame::Frame;
use crate::geometry::{altitude_of, ray_shell_from, solve_sphere};
use crate::math::V3;
use crate::sky::SkyTables;

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
    /// A gridded density (e.g. the clouds sampled by [`sample_density_grid`]) with the scene's
    /// `sigma_s` and `sigma_a`, 0 outside its box. The weather is the scene's global values, as
    /// for [`Medium::Homogeneous`].
    Grid(&'a DensityGrid),
}

/// A dense density grid over an axis-aligned box in the world's flat coordinates (see
/// [`Shape::Sphere`] for the axes), looked up like Mitsuba 3's `gridvolume`: cell-centred
/// trilinear interpolation with clamped edges.
#[derive(Clone, Debug, PartialEq)]
pub struct DensityGrid {
    /// Cells along x, y, z.
    pub dims: [usize; 3],
    /// Lower corner `[x, y, z]` of the box, metres.
    pub min: [f64; 3],
    /// Upper corner `[x, y, z]` of the box, metres.
    pub max: [f64; 3],
    /// Densities, x fastest, then y, then z (`data[(z * ny + y) * nx + x]`).
    pub data: Vec<f32>,
}

impl DensityGrid {
    /// The largest density in the grid (0 for an empty grid).
    pub fn max_density(&self) -> f64 {
        self.data.iter().fold(0.0f64, |m, &v| m.max(f64::from(v)))
    }

    /// The density at world position `p` (`[x, y, z]`, metres): trilinear between cell centres,
    /// clamped to the edge cells inside the box, 0 outside it.
    pub fn lookup(&self, p: [f64; 3]) -> f64 {
        let mut i0 = [0usize; 3];
        let mut i1 = [0usize; 3];
        let mut t = [0.0f64; 3];
        for a in 0..3 {
            let u = (p[a] - self.min[a]) / (self.max[a] - self.min[a]);
            if !(0.0..=1.0).contains(&u) {
                return 0.0;
            }
            let n = self.dims[a];
            let x = u * n as f64 - 0.5;
            let lo = x.floor();
            t[a] = x - lo;
            let clamp = |i: f64| i.clamp(0.0, (n - 1) as f64) as usize;
            i0[a] = clamp(lo);
            i1[a] = clamp(lo + 1.0);
        }
        let [nx, ny, _] = self.dims;
        let at = |x: usize, y: usize, z: usize| f64::from(self.data[(z * ny + y) * nx + x]);
        let mut v = 0.0;
        for (cz, wz) in [(i0[2], 1.0 - t[2]), (i1[2], t[2])] {
            for (cy, wy) in [(i0[1], 1.0 - t[1]), (i1[1], t[1])] {
                for (cx, wx) in [(i0[0], 1.0 - t[0]), (i1[0], t[0])] {
                    v += wx * wy * wz * at(cx, cy, cz);
                }
            }
        }
        v
    }

    /// The world position of the centre of cell `[x, y, z]`.
    pub fn cell_center(&self, cell: [usize; 3]) -> [f64; 3] {
        std::array::from_fn(|a| {
            self.min[a] + (cell[a] as f64 + 0.5) / self.dims[a] as f64 * (self.max[a] - self.min[a])
        })
    }
}

/// Samples the scene's cloud density (`density.wgsl::cloud_density` over `noise`) at the cell
/// centres of a `dims` grid over the box `min`..`max` (world flat coordinates, metres; with a
/// very large planet radius y is the altitude).
pub fn sample_density_grid(
    scene: &Scene,
    noise: &NoiseSet,
    min: [f64; 3],
    max: [f64; 3],
    dims: [usize; 3],
) -> DensityGrid {
    let f = Frame::from_uniforms(&scene.uniforms());
    let mut grid = DensityGrid {
        dims,
        min,
        max,
        data: Vec::with_capacity(dims[0] * dims[1] * dims[2]),
    };
    for z in 0..dims[2] {
        for y in 0..dims[1] {
            for x in 0..dims[0] {
                let p = V3::from_array(grid.cell_center([x, y, z]));
                // Altitude of the camera-relative point (x/z relative to the camera's ground
                // point), as the integrators compute it.
                let rel = V3::new(p.x - f.camera_position[0], p.y, p.z - f.camera_position[2]);
                let alt = altitude_of(&f, rel);
                let d = cloud_density(&f, noise, p, alt, &mut Counters::default());
                grid.data.push(d as f32);
            }
        }
    }
    grid
}

// WGSL: skip.wgsl::OCCUPANCY_CELLS
const OCCUPANCY_CELLS: u32 = 64;

// WGSL: skip.wgsl::occupancy
/// Per cell of a 64x64 grid over the weather map: the largest R texel (as unorm) a bilinear
/// lookup inside the cell can touch (the cell's texels and a one-texel border, wrapping).
fn occupancy_grid(weather: &stratus_noise::Texture2) -> Vec<f64> {
    let [w, h] = weather.size.map(|v| v as i64);
    let cells = i64::from(OCCUPANCY_CELLS);
    let mut grid = Vec::with_capacity((cells * cells) as usize);
    for cy in 0..cells {
        for cx in 0..cells {
            let (lo_x, hi_x) = (cx * w / cells - 1, (cx + 1) * w / cells);
            let (lo_y, hi_y) = (cy * h / cells - 1, (cy + 1) * h / cells);
            let mut m = 0u8;
            for y in lo_y..=hi_y {
                for x in lo_x..=hi_x {
                    let (tx, ty) = (x.rem_euclid(w), y.rem_euclid(h));
                    m = m.max(weather.data[((ty * w + tx) * 4) as usize]);
                }
            }
            grid.push(f64::from(m) / 255.0);
        }
    }
    grid
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
    /// The weather map's occupancy grid (max coverage per cell), for empty-space skipping.
    occupancy: Option<Vec<f64>>,
    /// Lower and upper bound of the density anywhere inside the medium's support.
    pub density_bounds: (f64, f64),
    /// The physical sky's tables for this frame (the GPU's `*-lut`, `sky-ambient` and
    /// `aerial-perspective` resources), under the physical sky only.
    sky: Option<SkyTables>,
    /// The host's scene depth (`FLAG_SCENE_DEPTH`): the march stops at its surfaces.
    pub surface: Option<std::sync::Arc<stratus_graph::SceneDepth>>,
    /// A distant environment and sun that replace the sky's for the Monte Carlo integrator
    /// (the physical sky frozen at one point, as another renderer sees it).
    pub environment: Option<&'a crate::environment::Environment>,
}

impl<'a> Model<'a> {
    /// The frame of `scene` (its uniforms widened to f64) and the medium. A homogeneous medium
    /// replaces the scene's sigma_s and sigma_a in the frame.
    pub fn new(scene: &Scene, medium: Medium<'a>) -> Self {
        Self::with_uniforms(&scene.uniforms(), medium)
    }

    /// [`Model::with_uniforms`] with the host's scene depth: its projection terms go into the
    /// block (as every GPU backend puts them) and the march stops at its surfaces.
    pub fn with_scene_depth(
        mut u: stratus_scene::FrameUniforms,
        medium: Medium<'a>,
        depth: Option<&std::sync::Arc<stratus_graph::SceneDepth>>,
    ) -> Self {
        if let Some(d) = depth {
            d.apply(&mut u);
        }
        let mut model = Self::with_uniforms(&u, medium);
        model.surface = depth.cloned();
        model
    }

    /// [`Model::new`] from a uniform block (a renderer's, with last frame's camera).
    pub fn with_uniforms(u: &stratus_scene::FrameUniforms, medium: Medium<'a>) -> Self {
        let mut f = Frame::from_uniforms(u);
        let density_bounds = match medium {
            Medium::Clouds(_) => {
                // density = eroded base (<= 1) * height gradient (<= 1) * multiplier *
                // (1 + precipitation), precipitation <= the layer's; then clamped to [0, 1].
                // WGSL: pathtrace.wgsl::density_max.
                let max = cloud_layers(&f)
                    .map(|l| l.density * (1.0 + l.precipitation))
                    .fold(0.0, f64::max);
                (0.0, max.clamp(0.0, 1.0))
            }
            Medium::Homogeneous {
                sigma_s, sigma_a, ..
            } => {
                f.scattering = sigma_s;
                f.absorption = sigma_a;
                (1.0, 1.0)
            }
            Medium::Grid(grid) => (0.0, grid.max_density()),
        };
        let occupancy = match medium {
            Medium::Clouds(noise) => Some(occupancy_grid(&noise.weather)),
            _ => None,
        };
        // Once per frame, as the GPU's passes before the march.
        let sky = f.physical_sky().then(|| SkyTables::for_frame(&f));
        let mut model = Self {
            f,
            medium,
            occupancy,
            density_bounds,
            sky,
            surface: None,
            environment: None,
        };
        // The shadow map reads the medium, so it is made once the model stands.
        if let Some(mut sky) = model.sky.take() {
            sky.shade(&model.f, |rel| model.shadow_optical_depth(rel));
            if let Medium::Clouds(noise) = &model.medium
                && model.f.rainbow_moisture > 0.0
            {
                sky.weather = Some(noise.weather.clone());
            }
            model.sky = Some(sky);
        }
        model
    }

    // WGSL: ground.wgsl::cloud_shadow (its march)
    /// The clouds' density integrated along the key light's way up from camera-relative ground
    /// point `rel` through every layer, 16 midpoint steps a layer (not counted: the counters
    /// measure the march).
    fn shadow_optical_depth(&self, rel: V3) -> f64 {
        self.sun_optical_depth(rel, 0.0, crate::sky::SHADOW_STEPS)
    }

    /// The clouds' density integrated along the key light's way up from camera-relative point
    /// `rel` at altitude `alt` (m) through every layer above it, `steps` midpoint steps a
    /// layer (from below a layer's bottom; a point inside a layer gets the part above it).
    pub fn sun_optical_depth(&self, rel: V3, alt: f64, steps: u32) -> f64 {
        let f = &self.f;
        let sun = f.sun();
        let cam = V3::new(f.camera_position[0], 0.0, f.camera_position[2]);
        let mut counters = Counters::default();
        let mut tau = 0.0;
        for l in cloud_layers(f) {
            // From below a shell, the far root is where the ray leaves it upward.
            let start = ray_shell_from(f, rel, alt, sun, l.bottom).t1.max(0.0);
            let end = ray_shell_from(f, rel, alt, sun, l.top).t1;
            let dt = (end - start) / f64::from(steps);
            // Also skips a NaN (a shell the ray does not meet).
            if dt.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
                continue;
            }
            for k in 0..steps {
                let q = rel + sun * (start + (f64::from(k) + 0.5) * dt);
                tau += self.layer_density(q + cam, altitude_of(f, q), &l, &mut counters) * dt;
            }
        }
        tau
    }

    /// The clouds' noise (their medium only).
    pub(crate) fn noise(&self) -> Option<&'a NoiseSet> {
        match self.medium {
            Medium::Clouds(noise) => Some(noise),
            Medium::Homogeneous { .. } | Medium::Grid(_) => None,
        }
    }

    /// The physical sky's tables (`None` under the analytic sky).
    pub fn sky(&self) -> Option<&SkyTables> {
        self.sky.as_ref()
    }

    // WGSL: skip.wgsl::empty_cell_exit
    /// At world position `p` on a ray along unit `d`: the distance to the edge of p's
    /// occupancy cell if the weather leaves the cell empty, else 0.
    pub fn empty_cell_exit(&self, p: V3, d: V3) -> f64 {
        let Some(grid) = &self.occupancy else {
            return 0.0;
        };
        let f = &self.f;
        // WGSL: the grid knows the map's coverage alone, not the convective cells nor the
        // anvils spread beyond it.
        if f.convective_cells > 0.0 || f.anvil > 0.0 {
            return 0.0;
        }
        let cells = f64::from(OCCUPANCY_CELLS);
        let fract = |x: f64| x - x.floor();
        let uv = [
            fract((p.x - f.weather_offset[0]) / f.weather_period) * cells,
            fract((p.z - f.weather_offset[1]) / f.weather_period) * cells,
        ];
        let cell = uv.map(|c| (c as u32).min(OCCUPANCY_CELLS - 1));
        let m = grid[(cell[1] * OCCUPANCY_CELLS + cell[0]) as usize];
        if m + 2.0 * (f.coverage - 0.5) > -1.0 / 255.0 {
            return 0.0;
        }
        let cell_m = f.weather_period / cells;
        let inside = [
            (uv[0] - f64::from(cell[0])) * cell_m,
            (uv[1] - f64::from(cell[1])) * cell_m,
        ];
        let mut exit = 1e30f64;
        for (dir, pos) in [(d.x, inside[0]), (d.z, inside[1])] {
            if dir > 1e-6 {
                exit = exit.min((cell_m - pos) / dir);
            } else if dir < -1e-6 {
                exit = exit.min(pos / -dir);
            }
        }
        exit.max(0.0)
    }

    /// Density at world position `p` (altitude `alt`); counts like `cloud_density`.
    pub fn density(&self, p: V3, alt: f64, counters: &mut Counters) -> f64 {
        match self.medium {
            Medium::Clouds(noise) => cloud_density(&self.f, noise, p, alt, counters),
            Medium::Homogeneous { shape, .. } => {
                let f = &self.f;
                let h = (alt - f.cloud_bottom) / (f.cloud_top - f.cloud_bottom);
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
            Medium::Grid(grid) => {
                counters.density += 1;
                grid.lookup(p.to_array())
            }
        }
    }

    /// Density at world position `p` (altitude `alt`) in layer `l` (0 outside it); counts like
    /// `layer_density`. The analytic media fill the main layer only, as [`Model::density`].
    pub(crate) fn layer_density(&self, p: V3, alt: f64, l: &Layer, counters: &mut Counters) -> f64 {
        self.layer_density_with(p, alt, l, true, counters)
    }

    /// [`Model::layer_density`], with the clouds' detail erosion only if `with_detail`.
    pub(crate) fn layer_density_with(
        &self,
        p: V3,
        alt: f64,
        l: &Layer,
        with_detail: bool,
        counters: &mut Counters,
    ) -> f64 {
        match self.medium {
            Medium::Clouds(noise) => {
                layer_density_with(&self.f, noise, p, alt, l, with_detail, counters)
            }
            _ => self.density(p, alt, counters),
        }
    }

    /// The weather at `p` in layer `l` (the weather map for clouds, the scene's values
    /// otherwise).
    pub(crate) fn weather(&self, p: V3, l: &Layer) -> Weather {
        match self.medium {
            Medium::Clouds(noise) => sample_weather(&self.f, noise, p, l),
            Medium::Homogeneous { .. } | Medium::Grid(_) => uniform_weather(&self.f),
        }
    }

    /// Layer `l`'s anvil weight (0 for analytic media, which have no anvils).
    pub(crate) fn anvil_weight(&self, l: &Layer) -> f64 {
        match self.medium {
            Medium::Clouds(_) => crate::density::anvil_weight(&self.f, l),
            Medium::Homogeneous { .. } | Medium::Grid(_) => 0.0,
        }
    }

    /// The share of the region about `p` that layer `l`'s clouds cover, for their multiply
    /// scattered light (the weather's own coverage but for clouds on convective cells).
    pub(crate) fn regional_coverage(&self, p: V3, l: &Layer, weather: &Weather) -> f64 {
        match self.medium {
            Medium::Clouds(noise) => {
                crate::density::regional_coverage(&self.f, &noise.weather, p, l, weather)
            }
            Medium::Homogeneous { .. } | Medium::Grid(_) => weather.coverage,
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
            Medium::Grid(grid) => {
                // The box relative to the camera's ground point; slab test.
                let cam = [self.f.camera_position[0], 0.0, self.f.camera_position[2]];
                let (o, d) = (origin.to_array(), d.to_array());
                let (mut lo, mut hi) = (t0, t1);
                for a in 0..3 {
                    let (bmin, bmax) = (grid.min[a] - cam[a], grid.max[a] - cam[a]);
                    if d[a] == 0.0 {
                        if o[a] < bmin || o[a] > bmax {
                            return None;
                        }
                    } else {
                        let (ta, tb) = ((bmin - o[a]) / d[a], (bmax - o[a]) / d[a]);
                        lo = lo.max(ta.min(tb));
                        hi = hi.min(ta.max(tb));
                    }
                }
                (lo, hi)
            }
            _ => (t0, t1),
        };
        (hi > lo).then_some((lo, hi))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 4x3x2 grid over [0, 4] x [10, 16] x [-2, 2] whose cell values are a linear function
    /// of the cell centre.
    fn grid() -> (DensityGrid, impl Fn([f64; 3]) -> f64) {
        let linear = |p: [f64; 3]| 0.5 + 0.1 * p[0] - 0.03 * p[1] + 0.07 * p[2];
        let mut g = DensityGrid {
            dims: [4, 3, 2],
            min: [0.0, 10.0, -2.0],
            max: [4.0, 16.0, 2.0],
            data: Vec::new(),
        };
        for z in 0..2 {
            for y in 0..3 {
                for x in 0..4 {
                    g.data.push(linear(g.cell_center([x, y, z])) as f32);
                }
            }
        }
        (g, linear)
    }

    #[test]
    fn grid_lookup_is_cell_centred_trilinear_with_clamped_edges() {
        let (g, linear) = grid();
        // x fastest, then y, then z.
        assert_eq!(g.cell_center([1, 2, 1]), [1.5, 15.0, 1.0]);
        assert_eq!(g.data[(2 * 4) + 1 + 4 * 3], linear([1.5, 15.0, 1.0]) as f32);
        // Cell centres give the cell's value; between centres, trilinear reproduces a linear
        // function exactly.
        for p in [
            [0.5, 11.0, -1.0],
            [3.5, 15.0, 1.0],
            [1.0, 12.0, 0.0],
            [2.3, 13.7, -0.4],
        ] {
            assert!((g.lookup(p) - linear(p)).abs() < 1e-6, "{p:?}");
        }
        // Within half a cell of the box's faces the edge cells' values hold (clamped).
        let edge = g.lookup([0.5, 11.0, -1.0]);
        assert!((g.lookup([0.0, 10.0, -2.0]) - edge).abs() < 1e-9);
        assert!((g.lookup([0.2, 10.4, -1.7]) - edge).abs() < 1e-9);
        let (lo, hi) = (g.lookup([3.5, 12.0, 0.0]), g.lookup([4.0, 12.0, 0.0]));
        assert!((lo - hi).abs() < 1e-9);
        // Outside the box: 0.
        assert_eq!(g.lookup([-0.01, 12.0, 0.0]), 0.0);
        assert_eq!(g.lookup([2.0, 16.5, 0.0]), 0.0);
        assert!(
            (g.max_density() - f64::from(g.data.iter().copied().fold(0.0, f32::max))).abs() < 1e-12
        );
    }
}
