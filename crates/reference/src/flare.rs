//! The CPU twin of `flare.wgsl`: the lens's ghosts and halo along the line from the sun's image
//! through the image's centre, each a fixed share of the sun's light that reaches the lens.

use crate::frame::{FLAG_MOONLIT, Frame, PI};
use crate::math::{V3, saturate, smoothstep};

// WGSL: flare.wgsl (constants)
const FLARE_TAPS: f64 = 5.0;
const FLARE_EDGES: [[f64; 2]; 3] = [
    [
        std::f64::consts::FRAC_1_SQRT_2,
        std::f64::consts::FRAC_1_SQRT_2,
    ],
    [-0.258_819_05, 0.965_925_83],
    [-0.965_925_83, 0.258_819_05],
];
const FLARE_HALO_RADIUS: f64 = 0.42;
const FLARE_HALO_WIDTH: f64 = 0.012;
const FLARE_HALO_SHARE: f64 = 0.6e-3;
const FLARE_HALO_FRINGE: f64 = 0.01;

/// The ghosts: position along the axis (1 at the sun), circumradius (image heights), share of
/// the sun's light per channel at intensity 1.
// WGSL: flare.wgsl::lens_flare (its ghost calls)
const GHOSTS: [(f64, f64, [f64; 3]); 6] = [
    (0.55, 0.035, [1.0e-4, 2.0e-4, 1.2e-4]),
    (0.25, 0.018, [2.5e-4, 1.5e-4, 0.6e-4]),
    (-0.2, 0.05, [1.2e-4, 1.6e-4, 2.4e-4]),
    (-0.45, 0.025, [2.4e-4, 1.0e-4, 2.2e-4]),
    (-0.8, 0.07, [1.6e-4, 2.6e-4, 1.4e-4]),
    (-1.25, 0.11, [4.0e-4, 3.0e-4, 2.0e-4]),
];

// WGSL: flare.wgsl::sun_image
/// The sun's image centre in pixels (continuous), `None` with the sun behind the camera.
fn sun_image(f: &Frame) -> Option<[f64; 2]> {
    let sun = f.sun();
    let (forward, right, up) = f.camera_axes();
    let z = sun.dot(forward);
    if z <= 0.0 {
        return None;
    }
    let ndc = [
        sun.dot(right) / (z * f.tan_half_fov * f.aspect),
        -sun.dot(up) / (z * f.tan_half_fov),
    ];
    Some([
        (ndc[0] * 0.5 + 0.5) * f64::from(f.size[0]),
        (ndc[1] * 0.5 + 0.5) * f64::from(f.size[1]),
    ])
}

// WGSL: flare.wgsl::flare_source
/// The sun's illuminance that reaches the lens: `direct` (through the air alone) times the
/// mean over five taps of the sun's disc of `seen(pixel)` (the clouds' transmittance, 0 over
/// the host's geometry), a tap off screen seeing nothing.
pub(crate) fn flare_source(f: &Frame, direct: V3, seen: impl Fn([u32; 2]) -> f64) -> V3 {
    if f.lens_flare_intensity <= 0.0 || f.flags & FLAG_MOONLIT != 0 {
        return V3::ZERO;
    }
    let Some(at) = sun_image(f) else {
        return V3::ZERO;
    };
    let cos_r = f.sun_cos_radius;
    let tan_r = (1.0 - cos_r * cos_r).max(0.0).sqrt() / cos_r;
    let radius_px = (tan_r / f.tan_half_fov * 0.5 * f64::from(f.size[1])).max(1.0);
    let taps = [
        [0.0, 0.0],
        [-radius_px, 0.0],
        [radius_px, 0.0],
        [0.0, -radius_px],
        [0.0, radius_px],
    ];
    let mut total = 0.0;
    for [dx, dy] in taps {
        let p = [(at[0] + dx).floor(), (at[1] + dy).floor()];
        if p[0] >= 0.0 && p[1] >= 0.0 && p[0] < f64::from(f.size[0]) && p[1] < f64::from(f.size[1])
        {
            total += seen([p[0] as u32, p[1] as u32]);
        }
    }
    direct * (total / FLARE_TAPS)
}

// WGSL: flare.wgsl::aperture_distance
/// Signed distance from `p` to the hexagonal aperture of circumradius `r`.
fn aperture_distance(p: [f64; 2], r: f64) -> f64 {
    let apothem = r * 0.866_025_4;
    FLARE_EDGES
        .iter()
        .map(|n| (p[0] * n[0] + p[1] * n[1]).abs())
        .fold(0.0, f64::max)
        - apothem
}

// WGSL: flare.wgsl::lens_flare
/// The flare's radiance at `pixel` for `source` (from [`flare_source`]).
pub(crate) fn lens_flare(f: &Frame, pixel: [u32; 2], source: V3) -> V3 {
    if source.x <= 0.0 && source.y <= 0.0 && source.z <= 0.0 {
        return V3::ZERO;
    }
    let Some(at) = sun_image(f) else {
        return V3::ZERO;
    };
    let (w, h) = (f64::from(f.size[0]), f64::from(f.size[1]));
    let p = [
        (f64::from(pixel[0]) + 0.5 - w * 0.5) / h,
        (f64::from(pixel[1]) + 0.5 - h * 0.5) / h,
    ];
    let s = [(at[0] - w * 0.5) / h, (at[1] - h * 0.5) / h];
    let height_angle = 2.0 * f.tan_half_fov;
    let mut flare = V3::ZERO;
    for (along, r, share) in GHOSTS {
        let q = [p[0] - s[0] * along, p[1] - s[1] * along];
        if q[0] * q[0] + q[1] * q[1] > 1.5625 * r * r {
            continue;
        }
        let d = aperture_distance(q, r);
        let soft = 0.2 * r;
        let inside = 1.0 - smoothstep(-soft, soft, d);
        let rim = 0.75 + 0.5 * smoothstep(-0.5 * r, 0.0, d);
        let apothem = r * 0.866_025_4;
        let area = 2.0 * 3f64.sqrt() * apothem * apothem;
        let k = inside * rim / (area * height_angle * height_angle);
        flare += V3::new(share[0], share[1], share[2]) * k;
    }
    let r = (p[0] * p[0] + p[1] * p[1]).sqrt();
    if (r - FLARE_HALO_RADIUS).abs() > FLARE_HALO_FRINGE + 6.0 * FLARE_HALO_WIDTH {
        return flare.mul_v(source) * f.lens_flare_intensity;
    }
    let ls = (s[0] * s[0] + s[1] * s[1]).sqrt();
    let side = saturate((p[0] * s[0] + p[1] * s[1]) / (r * ls).max(1e-4));
    let profile = |radius: f64| {
        let x = (r - radius) / FLARE_HALO_WIDTH;
        (-0.5 * x * x).exp()
    };
    let ring_area = 2.0 * PI * FLARE_HALO_RADIUS * FLARE_HALO_WIDTH * (2.0 * PI).sqrt();
    let halo = FLARE_HALO_SHARE * (4.0 * side * side) / (ring_area * height_angle * height_angle);
    flare += V3::new(
        profile(FLARE_HALO_RADIUS + FLARE_HALO_FRINGE),
        profile(FLARE_HALO_RADIUS),
        profile(FLARE_HALO_RADIUS - FLARE_HALO_FRINGE),
    ) * halo;
    flare.mul_v(source) * f.lens_flare_intensity
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame(yaw_offset: f64) -> Frame {
        let mut scene = stratus_scene::Scene::preset("lens-flare")
            .unwrap()
            .with_size(96, 54);
        scene.camera.yaw_deg += yaw_offset;
        Frame::from_uniforms(&scene.uniforms())
    }

    /// The flare's light is the sun's through the clouds over its disc: half the transmittance,
    /// half the light; none with the disc hidden or off screen; and the flare scales with it.
    #[test]
    fn the_flare_follows_the_light_seen_over_the_suns_disc() {
        let f = frame(0.0);
        let direct = V3::new(2.0, 1.5, 1.0);
        let clear = flare_source(&f, direct, |_| 1.0);
        let half = flare_source(&f, direct, |_| 0.5);
        assert!(clear.x > 0.0 && (half.x - 0.5 * clear.x).abs() < 1e-12);
        assert_eq!(flare_source(&f, direct, |_| 0.0), V3::ZERO);
        assert_eq!(flare_source(&frame(100.0), direct, |_| 1.0), V3::ZERO);
        let at = sun_image(&f).unwrap();
        let ghost = [
            (f64::from(f.size[0]) - at[0]) as u32,
            (f64::from(f.size[1]) - at[1]) as u32,
        ];
        let full = lens_flare(&f, ghost, clear);
        let halved = lens_flare(&f, ghost, half);
        assert!(full.x > 0.0, "the pixel mirroring the sun lies in a ghost");
        assert!((halved.x - 0.5 * full.x).abs() < 1e-9 * full.x);
    }
}
