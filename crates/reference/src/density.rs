//! The CPU twin of `density.wgsl`: the cloud density field (thesis alg. 4.1 with HZD's noise,
//! weather and cloud types), in f64 over the same 8-bit texels.
//!
//! The WGSL's feature switches (`DETAIL`, `CURL`) are not needed here: the frame plan always
//! picks a variant whose switches are on for every feature the scene uses, and a feature the
//! scene does not use has a zero strength, for which the switched-on code computes the same value
//! (a curl displacement times 0, a detail branch skipped by `strength > 0`).

use stratus_noise::NoiseSet;

use crate::frame::{Frame, HEIGHT_CLOUD_TYPES};
use crate::math::{V3, mix, remap, saturate, smoothstep};
use crate::texture::{sample2, sample3};

// WGSL: density.wgsl::Counters
/// Work counters of one pixel (the WGSL's `Counters`, widened to u64).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Counters {
    pub view_steps: u64,
    pub density: u64,
    pub detail: u64,
    pub light: u64,
}

// WGSL: density.wgsl::Weather
/// What the weather map says at a point, after the scene's global controls.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Weather {
    pub coverage: f64,
    pub cloud_type: f64,
    pub precipitation: f64,
}

// WGSL: density.wgsl::sample_weather
pub(crate) fn sample_weather(f: &Frame, noise: &NoiseSet, p: V3) -> Weather {
    let uv = [
        (p.x - f.wind_offsets0[0]) / f.periods[0],
        (p.z - f.wind_offsets0[1]) / f.periods[0],
    ];
    let w = sample2(&noise.weather, uv);
    let coverage = saturate(w[0] + 2.0 * (f.clouds[0] - 0.5));
    let cloud_type = saturate(f.clouds[2] + (w[2] - 0.5) * 0.5);
    let precipitation = f.clouds[3] * saturate(0.5 + w[1]);
    Weather {
        coverage,
        cloud_type,
        precipitation,
    }
}

/// The weather of a scene without a weather map (analytic media): the scene's global values.
pub(crate) fn uniform_weather(f: &Frame) -> Weather {
    Weather {
        coverage: 1.0,
        cloud_type: f.clouds[2],
        precipitation: f.clouds[3],
    }
}

// WGSL: density.wgsl::height_parabola
pub(crate) fn height_parabola(h: f64, cloud_type: f64) -> f64 {
    let height = mix(0.35, 1.0, cloud_type);
    saturate(h * (h - height) * (-4.0 / (height * height)))
}

// WGSL: density.wgsl::gradient
fn gradient(h: f64, r0: f64, r1: f64, f0: f64, f1: f64) -> f64 {
    smoothstep(r0, r1, h) * (1.0 - smoothstep(f0, f1, h))
}

// WGSL: density.wgsl::height_cloud_types
pub(crate) fn height_cloud_types(h: f64, cloud_type: f64) -> f64 {
    let stratus = gradient(h, 0.0, 0.08, 0.15, 0.25);
    let stratocumulus = gradient(h, 0.0, 0.2, 0.4, 0.65);
    let cumulus = gradient(h, 0.0, 0.1, 0.6, 0.95);
    let lo = mix(stratus, stratocumulus, saturate(cloud_type * 2.0));
    mix(lo, cumulus, saturate(cloud_type * 2.0 - 1.0))
}

// WGSL: density.wgsl::height_signal
pub(crate) fn height_signal(f: &Frame, h: f64, cloud_type: f64) -> f64 {
    if f.modes[2] == HEIGHT_CLOUD_TYPES {
        return height_cloud_types(h, cloud_type);
    }
    height_parabola(h, cloud_type)
}

// WGSL: density.wgsl::cloud_density
// Must agree with the WGSL step by step, including where `counters` are incremented (the
// density counter after the layer test, the detail counter inside the erosion branch).
/// Density in `[0, 1]` at world position `p` with altitude `alt`.
pub(crate) fn cloud_density(
    f: &Frame,
    noise: &NoiseSet,
    p: V3,
    alt: f64,
    counters: &mut Counters,
) -> f64 {
    let bottom = f.atmosphere[1];
    let top = f.atmosphere[2];
    let h = (alt - bottom) / (top - bottom);
    if !(0.0..=1.0).contains(&h) {
        return 0.0;
    }
    counters.density += 1;
    let weather = sample_weather(f, noise, p);
    let signal = height_signal(f, h, weather.cloud_type);
    if weather.coverage <= 0.0 || signal <= 0.0 {
        return 0.0;
    }

    // Base shape, isotropic texels: the y period is the x period times the texture's aspect.
    let [dx, dy, _] = noise.shape.size;
    let period = [
        f.periods[1],
        f.periods[1] * (f64::from(dy) / f64::from(dx)),
        f.periods[1],
    ];
    let shape_pos = [p.x - f.wind_offsets0[2], alt, p.z - f.wind_offsets0[3]];
    let s = sample3(
        &noise.shape,
        [
            shape_pos[0] / period[0],
            shape_pos[1] / period[1],
            shape_pos[2] / period[2],
        ],
    );
    let low_fbm = s[1] * 0.625 + s[2] * 0.25 + s[3] * 0.125;
    let mut base = saturate(remap(s[0], low_fbm - 1.0, 1.0, 0.0, 1.0)) * signal;

    // Coverage (HZD).
    base = saturate(remap(base, 1.0 - weather.coverage, 1.0, 0.0, 1.0)) * weather.coverage;
    if base <= 0.0 {
        return 0.0;
    }

    // Detail erosion at the edges only.
    let mut density = base;
    let strength = f.erosion[0];
    let threshold = f.erosion[1];
    if strength > 0.0 && base < threshold {
        counters.detail += 1;
        let mut detail_pos = V3::new(p.x, alt, p.z);
        // CURL: always compiled in here (see the module comment).
        let cuv = [
            (p.x - f.wind_offsets1[2]) / f.periods[3],
            (p.z - f.wind_offsets1[3]) / f.periods[3],
        ];
        let c = sample2(&noise.curl, cuv);
        let curl = [c[0] * 2.0 - 1.0, c[1] * 2.0 - 1.0];
        detail_pos += V3::new(curl[0], 0.0, curl[1]) * (f.erosion[2] * (1.0 - h));
        detail_pos = detail_pos - V3::new(f.wind_offsets1[0], 0.0, f.wind_offsets1[1]);
        let dn = sample3(
            &noise.detail,
            [
                detail_pos.x / f.periods[2],
                detail_pos.y / f.periods[2],
                detail_pos.z / f.periods[2],
            ],
        );
        let high_fbm = dn[0] * 0.625 + dn[1] * 0.25 + dn[2] * 0.125;
        // Must agree: the wispy-to-billowy ramp of the WGSL.
        let billowy = saturate(2.0 * f.extinction[3] * saturate(h * 10.0));
        let shape = mix(1.0 - high_fbm, high_fbm, billowy);
        let erosion = strength * shape * (1.0 - base / threshold);
        density = saturate(remap(base, erosion, 1.0, 0.0, 1.0));
    }

    density *= mix(1.0, h, f.erosion[3]);
    density = density * f.clouds[1] * (1.0 + weather.precipitation);
    density.clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn height_signals_peak_and_vanish_at_the_ends() {
        assert_eq!(height_parabola(0.0, 1.0), 0.0);
        assert_eq!(height_parabola(1.0, 1.0), 0.0);
        assert!((height_parabola(0.5, 1.0) - 1.0).abs() < 1e-12);
        // Stratus (type 0): height 0.35, peak at 0.175.
        assert!((height_parabola(0.175, 0.0) - 1.0).abs() < 1e-12);
        assert_eq!(height_parabola(0.5, 0.0), 0.0);
        for t in [0.0, 0.5, 1.0] {
            assert_eq!(height_cloud_types(0.0, t), 0.0);
            assert_eq!(height_cloud_types(1.0, t), 0.0);
        }
        assert!(height_cloud_types(0.3, 1.0) > 0.99);
        assert_eq!(height_cloud_types(0.5, 0.0), 0.0);
    }
}
