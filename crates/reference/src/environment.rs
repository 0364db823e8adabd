//! A distant environment given as a latitude-longitude map and a sun of fixed colour: the light
//! of the physical sky frozen at one point, as an independent renderer's emitters at infinity
//! see it (`stratus export-volume` for `cargo xtask mitsuba-check`).
//!
//! The map follows Mitsuba 3's `envmap` convention, so that the same texels mean the same light
//! in both renderers: direction `d` (y up) maps to u = atan2(d.x, -d.z) / 2pi (wrapped to
//! [0, 1)) and v = acos(d.y) / pi; columns are centred on u = (i + 0.5) / width (wrapping
//! around), rows sit on v = j / (height - 1) (the first at the zenith, the last at the nadir),
//! and the lookup is bilinear between them. Measured against Mitsuba's own renders of the map
//! (`cargo xtask mitsuba-check -- --preset sunset`, the sun's glow at the horizon): 0.05% a
//! block; with the columns on u = i / width, 2%.

use crate::math::V3;
use crate::sky::SkyTables;
use crate::{frame::Frame, frame::PI};

/// A latitude-longitude map of radiance (row 0 the zenith, the last row the nadir) and the sun
/// it goes with.
#[derive(Clone, Debug, PartialEq)]
pub struct Environment {
    /// Columns (longitude samples over the full circle).
    pub width: usize,
    /// Rows (latitude samples from the zenith to the nadir, both included).
    pub height: usize,
    /// Linear RGB radiance, row-major from the zenith row.
    pub radiance: Vec<[f64; 3]>,
    /// The sun's illuminance (linear RGB) on a surface facing it.
    pub sun: [f64; 3],
}

impl Environment {
    /// The direction of texel column `i`, row `j`.
    pub fn direction(&self, i: usize, j: usize) -> [f64; 3] {
        let phi = 2.0 * PI * (i as f64 + 0.5) / self.width as f64;
        let theta = PI * j as f64 / (self.height - 1) as f64;
        [
            theta.sin() * phi.sin(),
            theta.cos(),
            -theta.sin() * phi.cos(),
        ]
    }

    /// The radiance seen along unit `d`: the map bilinearly between its grid points.
    pub fn radiance_along(&self, d: [f64; 3]) -> [f64; 3] {
        let u = d[0].atan2(-d[2]) / (2.0 * PI);
        let u = u - u.floor();
        let v = d[1].clamp(-1.0, 1.0).acos() / PI;
        let x = u * self.width as f64 - 0.5;
        let y = v * (self.height - 1) as f64;
        let (i, j) = (x.floor(), y.floor().min((self.height - 2) as f64));
        let (wx, wy) = (x - i, y - j);
        // Column -1 is the last.
        let (i, j) = ((i + self.width as f64) as usize % self.width, j as usize);
        let texel = |i: usize, j: usize| self.radiance[j * self.width + i % self.width];
        let mut out = [0.0; 3];
        for (c, o) in out.iter_mut().enumerate() {
            let top = texel(i, j)[c] * (1.0 - wx) + texel(i + 1, j)[c] * wx;
            let bottom = texel(i, j + 1)[c] * (1.0 - wx) + texel(i + 1, j + 1)[c] * wx;
            *o = top * (1.0 - wy) + bottom * wy;
        }
        out
    }

    /// [`Environment::radiance_along`] as a [`V3`].
    pub(crate) fn along(&self, d: V3) -> V3 {
        let [x, y, z] = self.radiance_along([d.x, d.y, d.z]);
        V3::new(x, y, z)
    }

    /// The environment behind each pixel of `scene`'s frame (row-major), along the camera's
    /// ray through the pixel's centre: what the camera sees where nothing is in front.
    pub fn behind_pixels(&self, scene: &stratus_scene::Scene) -> Vec<[f64; 3]> {
        let f = Frame::from_uniforms(&scene.uniforms());
        let mut out = Vec::with_capacity((f.size[0] * f.size[1]) as usize);
        for y in 0..f.size[1] {
            for x in 0..f.size[0] {
                let d = crate::geometry::view_ray(&f, [x, y]);
                out.push(self.radiance_along([d.x, d.y, d.z]));
            }
        }
        out
    }

    /// The physical sky of `scene` seen from `altitude_m` above the ground under the camera: the
    /// sky and lit ground along every direction (the path tracer's environment there: the
    /// sky's integral from that point, times the sun's illuminance and the ambient strength),
    /// and the sun's illuminance after the air down to there. `None` under the analytic sky.
    pub fn physical_sky(
        scene: &stratus_scene::Scene,
        altitude_m: f64,
        width: usize,
        height: usize,
    ) -> Option<Self> {
        let u = scene.uniforms();
        let f = Frame::from_uniforms(&u);
        if !f.physical_sky() {
            return None;
        }
        let sky = SkyTables::new(&u);
        let at = V3::new(0.0, altitude_m, 0.0);
        let e = f.sun_illuminance();
        let mut env = Self {
            width,
            height,
            radiance: Vec::with_capacity(width * height),
            sun: [0.0; 3],
        };
        for j in 0..height {
            for i in 0..width {
                let [x, y, z] = env.direction(i, j);
                let l = sky.sky_from(&f, at, V3::new(x, y, z)).mul_v(e) * f.ambient_strength;
                env.radiance.push([l.x, l.y, l.z]);
            }
        }
        let sun = e.mul_v(sky.sun_through_air(&f, at));
        env.sun = [sun.x, sun.y, sun.z];
        Some(env)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A constant map equal to the analytic sky's uniform ambient, with the scene's own sun,
    /// renders the Monte Carlo image the analytic sky does (the same random streams): the
    /// override replaces exactly the sky's two lights.
    #[test]
    fn a_constant_environment_renders_as_the_uniform_sky() {
        use crate::{Integrator, Medium, RenderOptions, Shape, render_medium, render_medium_lit};
        let mut scene = stratus_scene::Scene::default().with_size(8, 6);
        scene.atmosphere.planet_radius_m = 1e14;
        scene.lighting.ambient_top = scene.lighting.ambient_bottom;
        let u = scene.uniforms();
        let ambient = u
            .ambient_bottom
            .map(|c| f64::from(c) * f64::from(u.ambient_strength));
        let medium = || Medium::Homogeneous {
            sigma_s: 0.004,
            sigma_a: 0.0004,
            shape: Shape::Slab,
        };
        let options = RenderOptions::default();
        let env = Environment {
            width: 4,
            height: 3,
            radiance: vec![ambient; 12],
            sun: u.sun_illuminance.map(f64::from),
        };
        let mc = Integrator::MonteCarlo { spp: 4, orders: 0 };
        let sky = render_medium(&scene, medium(), &mc, &options);
        let lit = render_medium_lit(&scene, medium(), &env, 4, 0, &options);
        let (a, b) = (&sky.output.radiance, &lit.output.radiance);
        assert!(a.iter().any(|v| *v > 0.0), "nothing rendered");
        for (i, (x, y)) in a.iter().zip(b).enumerate() {
            assert!((x - y).abs() <= 1e-5 * x.abs().max(1e-3), "{i}: {x} {y}");
        }
        // And a brighter map lights the medium more.
        let brighter = Environment {
            radiance: vec![ambient.map(|c| 2.0 * c); 12],
            ..env
        };
        let more = render_medium_lit(&scene, medium(), &brighter, 4, 0, &options);
        let sum = |r: &[f32]| r.chunks(4).map(|p| f64::from(p[0])).sum::<f64>();
        assert!(sum(&more.output.radiance) > sum(a) * 1.01);
    }

    /// Every texel's own direction reads back that texel, and between two texels the lookup is
    /// their mean: the map's convention and its inverse agree.
    #[test]
    fn texel_directions_read_back_their_texels() {
        let (width, height) = (8, 5);
        let env = Environment {
            width,
            height,
            radiance: (0..width * height)
                .map(|k| [k as f64, 2.0 * k as f64, 1.0])
                .collect(),
            sun: [0.0; 3],
        };
        for j in 1..height - 1 {
            for i in 0..width {
                let got = env.radiance_along(env.direction(i, j));
                let want = env.radiance[j * width + i];
                for c in 0..3 {
                    assert!((got[c] - want[c]).abs() < 1e-9, "{i},{j}: {got:?} {want:?}");
                }
            }
        }
        // Halfway between columns 7 and 0 (the wrap, at u = 0) on row 2.
        let phi = 0.0f64;
        let theta = PI * 2.0 / 4.0;
        let d = [
            theta.sin() * phi.sin(),
            theta.cos(),
            -theta.sin() * phi.cos(),
        ];
        let got = env.radiance_along(d)[0];
        let want = 0.5 * (env.radiance[2 * width + 7][0] + env.radiance[2 * width][0]);
        assert!((got - want).abs() < 1e-9, "{got} {want}");
    }
}
