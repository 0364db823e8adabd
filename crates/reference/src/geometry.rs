//! The CPU twin of `geometry.wgsl`: camera rays, ray-sphere intersection, altitude and the ray's
//! interval in the cloud layer, camera-relative like the WGSL (the planet's centre at
//! `(0, -Rp, 0)`, the camera at `(0, altitude, 0)`). In f64 the WGSL's cancellation-free forms
//! are not needed, but they are kept so the two read alike; the interval logic is the same.
//!
//! [`layer_segments`] (not in the WGSL) generalises the interval to any start point inside or
//! outside the layer, for the Monte Carlo path tracer's scattered rays.

use crate::density::{Layer, cloud_layer, cloud_layers, layers_span};
use crate::frame::Frame;
use crate::math::V3;

// WGSL: geometry.wgsl::view_ray
/// The view ray through the centre of `pixel` (y down in the image).
pub(crate) fn view_ray(f: &Frame, pixel: [u32; 2]) -> V3 {
    view_ray_at(f, [f64::from(pixel[0]) + 0.5, f64::from(pixel[1]) + 0.5])
}

// WGSL: geometry.wgsl::view_ray_at
/// The view ray through image point `at` (pixels, continuous: pixel p's centre is p + 0.5).
pub(crate) fn view_ray_at(f: &Frame, at: [f64; 2]) -> V3 {
    let size = [f64::from(f.size[0]), f64::from(f.size[1])];
    let ndc = [at[0] / size[0] * 2.0 - 1.0, at[1] / size[1] * 2.0 - 1.0];
    let tan_half = f.tan_half_fov;
    let aspect = f.aspect;
    let (forward, right, up) = f.camera_axes();
    let d = forward + right * (ndc[0] * tan_half * aspect) - up * (ndc[1] * tan_half);
    d.normalize()
}

// WGSL: geometry.wgsl::Roots
/// Roots `t0 <= t1` of a ray-sphere equation, and whether there are any.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Roots {
    pub t0: f64,
    pub t1: f64,
    pub hit: bool,
}

// WGSL: geometry.wgsl::solve_sphere
/// Roots of `t^2 + 2 b t + c = 0`, stable form.
pub(crate) fn solve_sphere(b: f64, c: f64) -> Roots {
    let disc = b * b - c;
    if disc < 0.0 {
        return Roots {
            t0: 0.0,
            t1: 0.0,
            hit: false,
        };
    }
    let s = disc.sqrt();
    // WGSL: select(-s, s, b >= 0.0).
    let q = -(b + if b >= 0.0 { s } else { -s });
    if q == 0.0 {
        return Roots {
            t0: 0.0,
            t1: 0.0,
            hit: true,
        };
    }
    let r0 = q;
    let r1 = c / q;
    Roots {
        t0: r0.min(r1),
        t1: r0.max(r1),
        hit: true,
    }
}

// WGSL: geometry.wgsl::ray_shell
/// Intersection of the ray from the camera (altitude `alt`) along unit `d` with the sphere of
/// altitude `radius_alt`.
pub(crate) fn ray_shell(f: &Frame, alt: f64, d: V3, radius_alt: f64) -> Roots {
    let rp = f.planet_radius;
    let b = d.y * (alt + rp);
    let c = (alt - radius_alt) * (alt + radius_alt + 2.0 * rp);
    solve_sphere(b, c)
}

/// [`ray_shell`] from any camera-relative point `p` of altitude `alt` (not in the WGSL: the
/// camera is always at `(0, alt, 0)` there).
pub(crate) fn ray_shell_from(f: &Frame, p: V3, alt: f64, d: V3, radius_alt: f64) -> Roots {
    let rp = f.planet_radius;
    let b = d.dot(V3::new(p.x, p.y + rp, p.z));
    let c = (alt - radius_alt) * (alt + radius_alt + 2.0 * rp);
    solve_sphere(b, c)
}

// WGSL: geometry.wgsl::altitude_of
/// Altitude of a camera-relative point, without cancellation.
pub(crate) fn altitude_of(f: &Frame, p: V3) -> f64 {
    let rp = f.planet_radius;
    let n = p.x * p.x + p.z * p.z + p.y * (p.y + 2.0 * rp);
    let q = V3::new(p.x, p.y + rp, p.z);
    n / (q.length() + rp)
}

// WGSL: geometry.wgsl::hits_ground
/// Whether the ray from camera-relative `p` (altitude `alt`) along unit `d` hits the ground.
pub(crate) fn hits_ground(f: &Frame, p: V3, alt: f64, d: V3) -> bool {
    let rp = f.planet_radius;
    let b = d.dot(V3::new(p.x, p.y + rp, p.z));
    let c = alt * (alt + 2.0 * rp);
    b < 0.0 && b * b >= c
}

// WGSL: geometry.wgsl::RAY_MARCH, RAY_MISSES_LAYER, RAY_HITS_GROUND
/// Why a ray does or does not march the layer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum RayKind {
    March,
    MissesLayer,
    HitsGround,
}

// WGSL: geometry.wgsl::Interval
/// The part of a view ray inside the cloud layer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Interval {
    pub start: f64,
    pub length: f64,
    pub kind: RayKind,
}

const MISSES: Interval = Interval {
    start: 0.0,
    length: 0.0,
    kind: RayKind::MissesLayer,
};

// WGSL: geometry.wgsl::layer_interval
/// The view ray's interval in cloud layer `l`.
pub(crate) fn layer_interval(f: &Frame, alt: f64, d: V3, l: &Layer) -> Interval {
    shell_interval(f, alt, d, l.bottom, l.top)
}

// WGSL: geometry.wgsl::cloud_interval
/// The view ray's interval in the shell that holds every layer.
pub(crate) fn cloud_interval(f: &Frame, alt: f64, d: V3) -> Interval {
    let (bottom, top) = layers_span(f);
    shell_interval(f, alt, d, bottom, top)
}

// WGSL: geometry.wgsl::nearest_layer_interval
/// The interval of the layer the view ray meets first (the lowest index of equal starts).
pub(crate) fn nearest_layer_interval(f: &Frame, alt: f64, d: V3) -> Interval {
    let mut best = layer_interval(f, alt, d, &cloud_layer(f, 0));
    for l in cloud_layers(f).skip(1) {
        let s = layer_interval(f, alt, d, &l);
        if s.kind == RayKind::March && (best.kind != RayKind::March || s.start < best.start) {
            best = s;
        }
    }
    best
}

// WGSL: geometry.wgsl::shell_interval
/// The part of the view ray inside the shell between altitudes `bottom` and `top`, cut to
/// the cut-off distance.
pub(crate) fn shell_interval(f: &Frame, alt: f64, d: V3, bottom: f64, top: f64) -> Interval {
    let cutoff = f.cutoff_distance;
    let inner = ray_shell(f, alt, d, bottom);
    let outer = ray_shell(f, alt, d, top);
    let mut start = 0.0;
    let mut end;
    if alt < bottom {
        if hits_ground(f, V3::new(0.0, alt, 0.0), alt, d) {
            return Interval {
                start: 0.0,
                length: 0.0,
                kind: RayKind::HitsGround,
            };
        }
        start = inner.t1;
        end = outer.t1;
    } else if alt <= top {
        end = outer.t1;
        if inner.hit && inner.t0 > 0.0 {
            end = end.min(inner.t0);
        }
    } else {
        if !outer.hit || outer.t1 <= 0.0 {
            return MISSES;
        }
        start = outer.t0.max(0.0);
        end = outer.t1;
        if inner.hit && inner.t0 > 0.0 {
            end = end.min(inner.t0);
        }
    }
    let len = (end - start).min(cutoff);
    // WGSL: `!(len > 0.0)` also catches NaN.
    if len.is_nan() || len <= 0.0 {
        return MISSES;
    }
    Interval {
        start,
        length: len,
        kind: RayKind::March,
    }
}

/// The parts `[t0, t1]` of the whole ray from camera-relative `p` (altitude `alt`) along unit
/// `d` that lie inside the cloud layer, in order (at most two: the ray may leave through the
/// bottom, pass below the layer and come back up), and whether the ray ends on the ground. No
/// cut-off: this is the physical medium, for the path tracer's scattered and shadow rays.
pub(crate) fn layer_segments(f: &Frame, p: V3, alt: f64, d: V3) -> (Vec<(f64, f64)>, bool) {
    // The shell that holds every layer; between layers the density is 0.
    let (bottom, top) = layers_span(f);
    let inner = ray_shell_from(f, p, alt, d, bottom);
    let outer = ray_shell_from(f, p, alt, d, top);
    let ground = hits_ground(f, p, alt, d);
    let mut segs = Vec::with_capacity(2);
    // Distance at which the ray leaves the top shell (None: never inside it ahead).
    if !outer.hit || outer.t1 <= 0.0 {
        return (segs, ground);
    }
    let entry = outer.t0.max(0.0);
    if inner.hit && inner.t0 > 0.0 && alt >= bottom {
        // Going down into the bottom shell: first part ends there ...
        if inner.t0 > entry {
            segs.push((entry, inner.t0));
        }
        // ... and unless the ground stops it, the ray comes back up through the layer.
        if !ground && outer.t1 > inner.t1 {
            segs.push((inner.t1.max(entry), outer.t1));
        }
    } else if alt < bottom {
        if !ground && inner.hit {
            segs.push((inner.t1.max(0.0), outer.t1));
        }
    } else {
        segs.push((entry, outer.t1));
    }
    segs.retain(|(a, b)| b > a);
    (segs, ground)
}

#[cfg(test)]
mod tests {
    use super::*;
    use stratus_scene::Scene;

    fn frame() -> Frame {
        Frame::from_uniforms(&Scene::default().uniforms())
    }

    #[test]
    fn altitude_matches_the_naive_formula() {
        let f = frame();
        let rp = f.planet_radius;
        for p in [
            V3::new(0.0, 200.0, 0.0),
            V3::new(30_000.0, 1500.0, -20_000.0),
            V3::new(1.0, -3.0, 2.0),
        ] {
            let naive = (p + V3::new(0.0, rp, 0.0)).length() - rp;
            assert!((altitude_of(&f, p) - naive).abs() < 1e-6, "{p:?}");
        }
    }

    #[test]
    fn camera_below_looking_up_enters_at_the_bottom() {
        let f = frame();
        let iv = cloud_interval(&f, 200.0, V3::new(0.0, 1.0, 0.0));
        assert_eq!(iv.kind, RayKind::March);
        assert!((iv.start - 1300.0).abs() < 1e-6);
        assert!((iv.length - 2500.0).abs() < 1e-6);
        let iv = cloud_interval(&f, 200.0, V3::new(0.0, -1.0, 0.0));
        assert_eq!(iv.kind, RayKind::HitsGround);
    }

    #[test]
    fn segments_from_inside_going_down_come_back_up() {
        let f = frame();
        // From the layer bottom, slightly downward: leaves through the bottom, misses the ground
        // (it bottoms out near 1280 m) and re-enters far away.
        let alt = 1600.0;
        let p = V3::new(0.0, alt, 0.0);
        let d = V3::new(1.0, -0.01, 0.0).normalize();
        let (segs, ground) = layer_segments(&f, p, alt, d);
        assert!(!ground);
        assert_eq!(segs.len(), 2, "{segs:?}");
        assert!(segs[0].0 == 0.0 && segs[0].1 < segs[1].0);
        // Straight down: hits the ground after one segment.
        let (segs, ground) = layer_segments(&f, p, alt, V3::new(0.0, -1.0, 0.0));
        assert!(ground);
        assert_eq!(segs.len(), 1);
        assert!((segs[0].1 - 100.0).abs() < 1e-6);
        // Straight up from below the layer.
        let (segs, _) = layer_segments(&f, V3::new(0.0, 200.0, 0.0), 200.0, V3::new(0.0, 1.0, 0.0));
        assert_eq!(segs.len(), 1);
        assert!((segs[0].0 - 1300.0).abs() < 1e-6 && (segs[0].1 - 3800.0).abs() < 1e-6);
    }
}
