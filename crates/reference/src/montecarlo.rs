//! A volumetric path tracer through the same density field as the real-time model: the physical
//! medium (sigma_s, sigma_a scaled by density, the scene's phase function), lit by the sun as a
//! directional light and by the ambient as an environment.
//!
//! # Estimators
//!
//! * Free flight: delta tracking (Woodcock) with the majorant `sigma_max = (sigma_s + sigma_a) *
//!   d_max`, where `d_max` bounds the density (`min(1, multiplier * (1 + precipitation))` for the
//!   clouds, 1 for the homogeneous media).
//! * Transmittance (shadow rays, and the camera ray's transmittance output): residual ratio
//!   tracking (Novák et al. 2014) with the control extinction `sigma_t * d_min` and residual
//!   majorant `sigma_t * (d_max - d_min)`; for the clouds `d_min = 0` (plain ratio tracking), for
//!   a homogeneous medium `d_min = d_max = 1`, which makes it exact.
//! * At a real collision the path's throughput is multiplied by the single-scattering albedo
//!   `sigma_s / sigma_t` (no absorption roulette). Directions are sampled from Henyey-Greenstein:
//!   the two-lobe model samples its mixture (weight 1), Cornette-Shanks samples HG(g) and is
//!   weighted by CS/HG (<= 1.5). Russian roulette on the throughput after the third order.
//! * Next-event estimation toward the sun at every scattering vertex: `E * phase * T_sun`, with
//!   `T_sun` by ratio tracking along the sun ray through the layer (including re-entry after
//!   dipping below the layer), 0 if the sun ray hits the ground (like the WGSL's `hits_ground`).
//! * Ambient (see below): at every scattering vertex, one direction sampled from the phase
//!   function (weight 1 up to the CS ratio) and its transmittance by ratio tracking.
//!
//! # The ambient as an environment
//!
//! The real-time model adds `sigma_s * density * ambient(h)` per unit length at every view
//! sample: no phase function, no attenuation. For any normalised phase function that is the
//! in-scattering of a *uniform* environment of radiance `A = ambient(h)` seen *unoccluded*
//! (`sigma_s * integral of phase(w) * A dw = sigma_s * A`). The path tracer lights each
//! scattering vertex by a uniform environment of radiance `ambient(h)` (h = the vertex's height
//! fraction, as in the real-time term) *seen through the medium*: one direction sampled from the
//! phase function, its transmittance to the layer's boundary by ratio tracking. Correspondence
//! and limits (all measured in `tests/analytic.rs` on a homogeneous slab):
//!
//! * optically thin clouds, single scattering: the two agree (transmittance toward the
//!   environment near 1);
//! * all orders, no absorption, uniform `A`: the radiance field inside is `A` everywhere
//!   (equilibrium), so the camera sees `A (1 - T)`, which is *exactly* the real-time term at
//!   albedo 1. The real-time ambient is thus the all-orders answer of a conservative medium, and
//!   `orders = 0` is its physical counterpart;
//! * `orders = 1` in thick clouds is much darker than the real-time term (a slab of optical
//!   thickness 1.2: 35% of it), because the environment light is occluded and the light that
//!   occlusion removes comes back only through higher orders;
//! * with a bottom-to-top gradient the environment's radiance depends on the receiver's height,
//!   which no true environment does, and the equilibrium above is only approximate; it is kept
//!   so that thin clouds match the real-time term;
//! * downward directions see the same uniform radiance (the ground does not occlude the
//!   ambient, whose bottom colour stands for light from below), while the ground itself is black
//!   and ends scattered paths.
//!
//! Under the physical sky the sun's light at a vertex is what the air leaves of it (the
//! transmittance table there), and the environment is the sky itself, direction by direction:
//! the sky and the lit ground in the sampled direction as seen from the vertex (the sky-view
//! table's integral, from there instead of the camera), times the ambient strength. The
//! real-time model takes the cosine-weighted hemispheres facing the layer instead (the
//! sky-ambient table), unoccluded: the truth here says what that costs.
//!
//! A [`crate::Environment`] given to the model (`render_medium_lit`) replaces both of the sky's
//! lights: paths that leave the medium see its map, and its sun, already through the air,
//! lights every vertex. That is the physical sky frozen at one point, as another renderer's
//! emitters at infinity give it (`stratus export-volume` for the Mitsuba check).
//!
//! # Real-time-only terms the path tracer ignores
//!
//! The multiple-scattering octaves (`a`, `b`, `c`; the path tracer simulates higher orders
//! instead), the Beer-Powder factor, precipitation darkening (precipitation still raises the
//! density, which the path tracer sees), the light march's discretisation, the early exit and
//! jitter. Set octaves 0, Beer-Powder off and precipitation 0 and the real-time model *is*
//! single scattering; `orders = 1` is then its exact counterpart. The camera ray is cut to the
//! real-time interval (`layer_interval`, with the cut-off distance), so that the background seen
//! through the clouds is the same; scattered rays see the whole layer (no cut-off).
//!
//! # Determinism
//!
//! Every sample of every pixel has its own random stream seeded from `(pixel, sample, frame)`,
//! so the image does not depend on the number of threads or their scheduling.

use crate::density::{Counters, height_fraction};
use crate::frame::{Frame, PI};
use crate::geometry::{Interval, RayKind, altitude_of, hits_ground, layer_segments};
use crate::lighting::ambient;
use crate::march::medium_interval;
use crate::math::V3;
use crate::medium::Model;
use crate::phase::{phase, phase_hg};
use crate::sky::{SkyTables, sun_through_air};

/// Scattering orders beyond which a path is cut even if "all orders" are asked for (a path in a
/// conservative thick cloud needs thousands; this only bounds pathological cases).
pub(crate) const MAX_ORDERS: u32 = 100_000;

/// PCG32 (O'Neill): 64-bit LCG state, XSH-RR output. Small, fast and reproducible.
#[derive(Clone, Debug)]
pub(crate) struct Rng {
    state: u64,
}

const PCG_MUL: u64 = 6_364_136_223_846_793_005;
const PCG_INC: u64 = 1_442_695_040_888_963_407;

/// SplitMix64 finaliser: a bijective scrambling of a 64-bit key.
pub(crate) fn splitmix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

impl Rng {
    /// The stream of sample `sample` of the pixel (or ray) with key `key`, for frame `frame`.
    pub fn new(key: u64, sample: u64, frame: u64) -> Self {
        let seed = splitmix64(splitmix64(splitmix64(key) ^ sample) ^ frame);
        let mut r = Self {
            state: seed.wrapping_add(PCG_INC),
        };
        r.next_u32();
        r
    }

    pub fn next_u32(&mut self) -> u32 {
        let old = self.state;
        self.state = old.wrapping_mul(PCG_MUL).wrapping_add(PCG_INC);
        let xorshifted = (((old >> 18) ^ old) >> 27) as u32;
        let rot = (old >> 59) as u32;
        xorshifted.rotate_right(rot)
    }

    /// Uniform in `[0, 1)` with 53 random bits.
    pub fn next_f64(&mut self) -> f64 {
        let hi = u64::from(self.next_u32()) << 21;
        let lo = u64::from(self.next_u32()) >> 11;
        ((hi | lo) as f64) * (1.0 / (1u64 << 53) as f64)
    }

    /// An exponential distance with rate `sigma`.
    fn exponential(&mut self, sigma: f64) -> f64 {
        -(1.0 - self.next_f64()).ln() / sigma
    }
}

/// One sample of one pixel (or ray).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct PathSample {
    /// In-scattered radiance (every path that scattered at least once).
    pub radiance: V3,
    /// Ratio-tracking estimate of the camera ray's transmittance over its interval.
    pub transmittance: f64,
    /// Distance of the first real collision on the camera ray, if any.
    pub first_collision: Option<f64>,
}

/// A ray from camera-relative `origin` along unit `dir`, restricted to `segments`.
struct Ray<'s> {
    origin: V3,
    dir: V3,
    segments: &'s [(f64, f64)],
}

impl Model<'_> {
    /// World position of camera-relative `rel` (the WGSL's `p`).
    fn world(&self, rel: V3) -> V3 {
        V3::new(
            rel.x + self.f.camera_position[0],
            rel.y,
            rel.z + self.f.camera_position[2],
        )
    }

    /// Density at camera-relative `rel`.
    fn density_at(&self, rel: V3, counters: &mut Counters) -> f64 {
        let alt = altitude_of(&self.f, rel);
        self.density(self.world(rel), alt, counters)
    }

    /// The layer segments of a ray from `rel` along `dir`, clipped to the medium's support,
    /// and whether the ray ends on the ground.
    fn segments(&self, rel: V3, dir: V3) -> (Vec<(f64, f64)>, bool) {
        let alt = altitude_of(&self.f, rel);
        let (segs, ground) = layer_segments(&self.f, rel, alt, dir);
        let segs = segs
            .into_iter()
            .filter_map(|(a, b)| self.clip(rel, dir, a, b))
            .collect();
        (segs, ground)
    }

    /// Extinction at density 1.
    fn sigma_t(&self) -> f64 {
        self.f.scattering + self.f.absorption
    }
}

/// Delta tracking: the first real collision along the ray, `(distance, density)`.
fn delta_track(
    m: &Model,
    ray: &Ray,
    rng: &mut Rng,
    counters: &mut Counters,
    tentative: &mut u64,
) -> Option<(f64, f64)> {
    let d_max = m.density_bounds.1;
    let majorant = m.sigma_t() * d_max;
    if majorant <= 0.0 {
        return None;
    }
    for &(a, b) in ray.segments {
        let mut t = a;
        loop {
            t += rng.exponential(majorant);
            if t >= b {
                break;
            }
            *tentative += 1;
            let d = m.density_at(ray.origin + ray.dir * t, counters);
            if rng.next_f64() * d_max < d {
                return Some((t, d));
            }
        }
    }
    None
}

/// Residual ratio tracking: an unbiased estimate of the transmittance along the ray.
fn ratio_track(
    m: &Model,
    ray: &Ray,
    rng: &mut Rng,
    counters: &mut Counters,
    tentative: &mut u64,
) -> f64 {
    let (d_min, d_max) = m.density_bounds;
    let sigma_t = m.sigma_t();
    let control = sigma_t * d_min;
    let residual = sigma_t * (d_max - d_min);
    let mut tr = 1.0;
    for &(a, b) in ray.segments {
        tr *= (-control * (b - a)).exp();
        if residual <= 0.0 {
            continue;
        }
        let mut t = a;
        loop {
            t += rng.exponential(residual);
            if t >= b {
                break;
            }
            *tentative += 1;
            let d = m.density_at(ray.origin + ray.dir * t, counters);
            tr *= 1.0 - (sigma_t * d - control) / residual;
            if tr <= 0.0 {
                return 0.0;
            }
            // Russian roulette on nearly opaque shadow rays (unbiased).
            if tr < 0.01 {
                if rng.next_f64() < 0.75 {
                    return 0.0;
                }
                tr *= 4.0;
            }
        }
    }
    tr
}

/// Samples Henyey-Greenstein's cosine for eccentricity `g`.
fn sample_hg_cos(g: f64, u: f64) -> f64 {
    if g.abs() < 1e-4 {
        return 1.0 - 2.0 * u;
    }
    let s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
    ((1.0 + g * g - s * s) / (2.0 * g)).clamp(-1.0, 1.0)
}

/// A direction around `dir` drawn from the scene's phase function (in the WGSL's convention,
/// the cosine is `dot(dir, new)` where `dir` is the direction the path travels), and the weight
/// `phase / pdf`.
fn sample_phase(m: &Model, dir: V3, rng: &mut Rng) -> (V3, f64) {
    let f = &m.f;
    let (g, g2, blend) = (f.phase_g, f.phase_g2, f.phase_blend);
    let u_lobe = rng.next_f64();
    let u = rng.next_f64();
    let phi = 2.0 * PI * rng.next_f64();
    let (cos, pdf) = match f.phase_model {
        crate::frame::PHASE_TWO_LOBE_HG => {
            let c = sample_hg_cos(if u_lobe < blend { g2 } else { g }, u);
            (c, (1.0 - blend) * phase_hg(c, g) + blend * phase_hg(c, g2))
        }
        _ => {
            let c = sample_hg_cos(g, u);
            (c, phase_hg(c, g))
        }
    };
    let sin = (1.0 - cos * cos).max(0.0).sqrt();
    let (t, b) = dir.basis();
    let new = (t * (sin * phi.cos()) + b * (sin * phi.sin()) + dir * cos).normalize();
    let weight = if pdf > 0.0 {
        phase(f, cos, 1.0) / pdf
    } else {
        0.0
    };
    (new, weight)
}

/// One path of the camera ray `view` over its real-time interval `span`, with at most `orders`
/// scattering events contributing (0 = all).
pub(crate) fn trace(
    m: &Model,
    view: V3,
    span: &Interval,
    orders: u32,
    rng: &mut Rng,
    c: &mut Counters,
) -> PathSample {
    let f = &m.f;
    let cam = V3::new(0.0, f.camera_position[1], 0.0);
    let mut out = PathSample {
        transmittance: 1.0,
        ..PathSample::default()
    };
    if span.kind != RayKind::March {
        return out;
    }
    let primary = [(span.start, span.start + span.length)];
    let ray = Ray {
        origin: cam,
        dir: view,
        segments: &primary,
    };
    let mut view_tentative = 0;
    let mut light_tentative = 0;
    out.transmittance = ratio_track(m, &ray, rng, c, &mut view_tentative);
    let Some((t, _)) = delta_track(m, &ray, rng, c, &mut view_tentative) else {
        c.view_steps += view_tentative;
        return out;
    };
    out.first_collision = Some(t);

    let sun = f.sun();
    let sun_e = f.sun_illuminance();
    let albedo = if m.sigma_t() > 0.0 {
        f.scattering / m.sigma_t()
    } else {
        0.0
    };
    // Under the physical sky the ambient is the sky's own light (the sky and ground seen from
    // the vertex: `environment`).
    let ambient_on = m.environment.is_some()
        || f.ambient_strength > 0.0
            && (f.physical_sky()
                || f.ambient_bottom[..3].iter().any(|&v| v > 0.0)
                || f.ambient_top[..3].iter().any(|&v| v > 0.0));
    let max_orders = if orders == 0 {
        MAX_ORDERS
    } else {
        orders.min(MAX_ORDERS)
    };

    let mut pos = cam + view * t;
    let mut dir = view;
    let mut throughput = 1.0;
    let mut radiance = V3::ZERO;
    let mut order = 0;
    loop {
        // A real collision: scatter with probability albedo (as a weight).
        throughput *= albedo;
        order += 1;
        let alt = altitude_of(f, pos);
        let h = height_fraction(f, alt);

        // Next event toward the sun (a directional light of illuminance E).
        if !hits_ground(f, pos, alt, sun) {
            let (segs, _) = m.segments(pos, sun);
            let shadow = Ray {
                origin: pos,
                dir: sun,
                segments: &segs,
            };
            let tr = ratio_track(m, &shadow, rng, c, &mut light_tentative);
            // Under the physical sky, the sun's light left after the air (as the WGSL's).
            let lit = match m.environment {
                Some(env) => V3::new(env.sun[0], env.sun[1], env.sun[2]),
                None => sun_e.mul_v(sun_through_air(f, m.sky(), pos)),
            };
            radiance += lit * (throughput * phase(f, dir.dot(sun), 1.0) * tr);
        }
        // The ambient: a uniform environment of radiance ambient(h), seen through the medium.
        if ambient_on {
            let (w, weight) = sample_phase(m, dir, rng);
            let (segs, _) = m.segments(pos, w);
            let env = Ray {
                origin: pos,
                dir: w,
                segments: &segs,
            };
            let tr = ratio_track(m, &env, rng, c, &mut light_tentative);
            let env_light = match m.environment {
                Some(env) => env.along(w),
                None => environment(f, m.sky(), pos, w, h),
            };
            radiance += env_light * (throughput * weight * tr);
        }
        if order >= max_orders {
            break;
        }

        // Continue the path.
        let (w, weight) = sample_phase(m, dir, rng);
        throughput *= weight;
        dir = w;
        if order >= 3 && throughput < 0.1 {
            let survive = throughput / 0.1;
            if rng.next_f64() >= survive {
                break;
            }
            throughput = 0.1;
        }
        if throughput <= 0.0 {
            break;
        }
        let (segs, _) = m.segments(pos, dir);
        let next = Ray {
            origin: pos,
            dir,
            segments: &segs,
        };
        let mut scattered_tentative = 0;
        let hit = delta_track(m, &next, rng, c, &mut scattered_tentative);
        light_tentative += scattered_tentative;
        match hit {
            Some((t, _)) => pos += dir * t,
            None => break,
        }
    }
    c.view_steps += view_tentative;
    c.light += light_tentative;
    out.radiance = radiance;
    out
}

/// The camera-ray interval of the path tracer: the shell that holds every layer
/// (`cloud_interval`), clipped to the medium's support.
pub(crate) fn camera_interval(m: &Model, view: V3) -> Interval {
    medium_interval(m, m.f.camera_position[1], view, None)
}

/// Running mean and variance (Welford) of the four outputs of a pixel.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Accumulator {
    n: u64,
    mean: [f64; 4],
    m2: [f64; 4],
    depth_sum: f64,
    depth_n: u64,
}

impl Accumulator {
    pub fn add(&mut self, s: &PathSample) {
        self.n += 1;
        let x = [s.radiance.x, s.radiance.y, s.radiance.z, s.transmittance];
        let n = self.n as f64;
        for (i, &v) in x.iter().enumerate() {
            let delta = v - self.mean[i];
            self.mean[i] += delta / n;
            self.m2[i] += delta * (v - self.mean[i]);
        }
        if let Some(t) = s.first_collision {
            self.depth_sum += t;
            self.depth_n += 1;
        }
    }

    /// Mean of radiance rgb and transmittance.
    pub fn mean(&self) -> [f64; 4] {
        self.mean
    }

    /// Standard error of the mean of each output.
    pub fn std_error(&self) -> [f64; 4] {
        if self.n < 2 {
            return [0.0; 4];
        }
        let n = self.n as f64;
        self.m2.map(|m2| (m2 / (n - 1.0) / n).sqrt())
    }

    /// Mean distance of the first collision on the camera ray (0 if there was none).
    pub fn depth(&self) -> f64 {
        if self.depth_n == 0 {
            0.0
        } else {
            self.depth_sum / self.depth_n as f64
        }
    }
}

// WGSL: pathtrace.wgsl::environment
/// The light a path leaving the clouds from `pos` (camera-relative, m) along unit `d` sees:
/// the sky and lit ground in that direction seen from there under the physical sky, else the
/// uniform ambient(h).
fn environment(f: &Frame, sky: Option<&SkyTables>, pos: V3, d: V3, h: f64) -> V3 {
    if let Some(sky) = crate::sky::physical(f, sky) {
        return sky.sky_from(f, pos, d).mul_v(f.sun_illuminance()) * f.ambient_strength;
    }
    ambient(f, sky, h, pos)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::medium::{Medium, Shape};
    use stratus_scene::Scene;

    /// Ratio tracking and delta tracking with a majorant twice the extinction (so that they are
    /// stochastic, not exact) reproduce Beer-Lambert within 3 standard errors, and delta
    /// tracking's collision distances follow the truncated exponential.
    #[test]
    fn stochastic_trackers_are_unbiased() {
        let mut scene = Scene::default();
        scene.atmosphere.planet_radius_m = 1e14;
        scene.atmosphere.cloud_bottom_m = 1000.0;
        scene.atmosphere.cloud_top_m = 2000.0;
        scene.camera.position = [0.0, 500.0, 0.0];
        let medium = Medium::Homogeneous {
            sigma_s: 0.001,
            sigma_a: 0.0005,
            shape: Shape::Slab,
        };
        let mut m = Model::new(&scene, medium);
        m.density_bounds = (0.0, 2.0);
        let dir = V3::new(0.6, 0.8, 0.0);
        let cam = V3::new(0.0, 500.0, 0.0);
        let (segs, _) = m.segments(cam, dir);
        assert_eq!(segs.len(), 1);
        let len = segs[0].1 - segs[0].0;
        assert!((len - 1250.0).abs() < 1e-6, "{len}");
        let tau = 0.0015 * len;
        let expected = (-tau).exp();
        let ray = Ray {
            origin: cam,
            dir,
            segments: &segs,
        };
        let n = 40_000;
        let mut c = Counters::default();
        let mut tentative = 0;
        let (mut sum, mut sum2, mut misses, mut dist) = (0.0, 0.0, 0u32, 0.0);
        for i in 0..n {
            let mut rng = Rng::new(i, 0, 0);
            let t = ratio_track(&m, &ray, &mut rng, &mut c, &mut tentative);
            sum += t;
            sum2 += t * t;
            match delta_track(&m, &ray, &mut rng, &mut c, &mut tentative) {
                None => misses += 1,
                Some((t, d)) => {
                    assert_eq!(d, 1.0);
                    dist += t - segs[0].0;
                }
            }
        }
        let nf = f64::from(n as u32);
        let mean = sum / nf;
        let se = ((sum2 / nf - mean * mean) / nf).sqrt();
        assert!(
            (mean - expected).abs() < 3.0 * se,
            "ratio tracking {mean} +- {se} vs {expected}"
        );
        let p = f64::from(misses) / nf;
        let se_p = (expected * (1.0 - expected) / nf).sqrt();
        assert!(
            (p - expected).abs() < 3.0 * se_p,
            "delta tracking {p} vs {expected}"
        );
        // Mean free path inside the segment: E[t | t < L] for an exponential of rate sigma_t.
        let sigma = 0.0015;
        let mfp = 1.0 / sigma - len * expected / (1.0 - expected);
        let mean_dist = dist / (nf - f64::from(misses));
        assert!((mean_dist - mfp).abs() < 0.02 * mfp, "{mean_dist} vs {mfp}");
        // Twice the extinction: about 2 tau tentative points per ratio-tracked ray.
        assert!(tentative > 0);
    }

    #[test]
    fn rng_is_uniform_and_streams_differ() {
        let mut r = Rng::new(1, 0, 0);
        let n = 100_000;
        let mean: f64 = (0..n).map(|_| r.next_f64()).sum::<f64>() / n as f64;
        assert!((mean - 0.5).abs() < 0.005, "{mean}");
        let a: Vec<u32> = (0..4).map(|_| Rng::new(1, 0, 0).next_u32()).collect();
        assert!(a.windows(2).all(|w| w[0] == w[1]));
        assert_ne!(Rng::new(1, 0, 0).next_u32(), Rng::new(1, 1, 0).next_u32());
        assert_ne!(Rng::new(1, 0, 0).next_u32(), Rng::new(2, 0, 0).next_u32());
    }

    #[test]
    fn hg_sampling_has_mean_cosine_g() {
        for g in [-0.3, 0.0, 0.6, 0.9] {
            let mut r = Rng::new(7, 0, 0);
            let n = 200_000;
            let mean: f64 = (0..n).map(|_| sample_hg_cos(g, r.next_f64())).sum::<f64>() / n as f64;
            assert!((mean - g).abs() < 0.01, "g={g}: mean cos {mean}");
        }
    }
}
