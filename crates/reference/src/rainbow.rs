//! The CPU twin of `rainbow.wgsl`'s optics: Airy theory's primary and secondary bows of a
//! raindrop, their Lee-diagram row over the spectrum and the sun's disc, and the cheap
//! three-wavelength path. The rain along a view ray is `SkyTables::rainbow_radiance`.

use crate::frame::{FLAG_LEE_DIAGRAM, Frame, PI};
use crate::math::{V3, smoothstep};

// WGSL: rainbow.wgsl::RAINBOW_TEXELS, RAINBOW_MIN_DEG, RAINBOW_MAX_DEG
/// Texels of the table, and the angles from the antisolar point its ends hold (degrees).
pub(crate) const RAINBOW_TEXELS: usize = 1024;
pub(crate) const RAINBOW_MIN_DEG: f64 = 8.0;
pub(crate) const RAINBOW_MAX_DEG: f64 = 68.0;
// WGSL: rainbow.wgsl::RAINBOW_FADE_DEG
const RAINBOW_FADE_DEG: f64 = 10.0;
// WGSL: rainbow.wgsl::RAINBOW_WAVELENGTHS, RAINBOW_SUN_TAPS, RAINBOW_RGB_NM
const RAINBOW_WAVELENGTHS: usize = 30;
const RAINBOW_SUN_TAPS: usize = 5;
const RAINBOW_RGB_NM: [f64; 3] = [610.0, 550.0, 465.0];

// WGSL: rainbow.wgsl::water_index
/// Water's refractive index at `nm` (Cauchy's form fitted to Hale and Querry 1973).
pub(crate) fn water_index(nm: f64) -> f64 {
    1.3271 + 1900.0 / (nm * nm)
}

// WGSL: rainbow.wgsl::airy_ai
/// The Airy function Ai(x): the Maclaurin series on [-4, 3], the asymptotic expansions beyond
/// to their terms in u1, u2 (and u3 on the bright side) (DLMF 9.4, 9.7).
pub(crate) fn airy_ai(x: f64) -> f64 {
    if x > 3.0 {
        let z = 2.0 / 3.0 * x * x.sqrt();
        let series = 1.0 - 0.069_444_444 / z + 0.037_133_487 / (z * z);
        return (-z).exp() / (2.0 * PI.sqrt() * x.sqrt().sqrt()) * series;
    }
    if x < -4.0 {
        let w = -x;
        let z = 2.0 / 3.0 * w * w.sqrt();
        let phase = z - 0.25 * PI;
        let even = 1.0 - 0.037_133_487 / (z * z);
        let odd = 0.069_444_444 / z - 0.037_993_059 / (z * z * z);
        return (phase.cos() * even + phase.sin() * odd) / (PI.sqrt() * w.sqrt().sqrt());
    }
    let x3 = x * x * x;
    let (mut f, mut g, mut tf, mut tg) = (1.0, x, 1.0, x);
    for k in 0..10 {
        let k3 = 3.0 * f64::from(k);
        tf *= x3 / ((k3 + 2.0) * (k3 + 3.0));
        tg *= x3 / ((k3 + 3.0) * (k3 + 4.0));
        f += tf;
        g += tg;
    }
    0.355_028_053_887_817 * f - 0.258_819_403_792_807 * g
}

// WGSL: rainbow.wgsl::Bow
/// A bow of water of one index: its angle from the antisolar point (rad), 2 b T_k 2 pi / sqrt(c)
/// and c^(-1/3).
pub(crate) struct Bow {
    pub(crate) angle: f64,
    scale: f64,
    c_cbrt_inv: f64,
}

// WGSL: rainbow.wgsl::rainbow_bow
/// The bow of `k` internal reflections in water of index `n`.
pub(crate) fn rainbow_bow(n: f64, k: u32) -> Bow {
    let kf = f64::from(k);
    let p2 = (kf + 1.0) * (kf + 1.0);
    let cos_i = ((n * n - 1.0) / (p2 - 1.0)).sqrt();
    let sin_i = (1.0 - cos_i * cos_i).sqrt();
    let sin_r = sin_i / n;
    let cos_r = (1.0 - sin_r * sin_r).sqrt();
    let (i, r) = (cos_i.acos(), sin_r.asin());
    let deviation = 2.0 * (i - r) + kf * (PI - 2.0 * r);
    let r1 = cos_i / (n * cos_r);
    let r2 = (-sin_i * cos_r + cos_i * sin_r * r1) / (n * cos_r * cos_r);
    let c = -(kf + 1.0) * r2 / (cos_i * cos_i);
    let rs = (cos_i - n * cos_r) / (cos_i + n * cos_r);
    let rp = (n * cos_i - cos_r) / (n * cos_i + cos_r);
    let (big_rs, big_rp) = (rs * rs, rp * rp);
    let t =
        0.5 * ((1.0 - big_rs).powi(2) * big_rs.powf(kf) + (1.0 - big_rp).powi(2) * big_rp.powf(kf));
    Bow {
        angle: (PI - deviation).abs(),
        scale: 2.0 * sin_i * t * 2.0 * PI / c.sqrt(),
        c_cbrt_inv: c.powf(-1.0 / 3.0),
    }
}

// WGSL: rainbow.wgsl::rainbow_phase
/// The two bows' phase function at `phi` (rad) from the antisolar point, drops of radius `a`
/// (m), wavelength `nm`: per steradian, per unit extinction of the rain.
pub(crate) fn rainbow_phase(phi: f64, a: f64, nm: f64) -> f64 {
    let deg = phi.to_degrees();
    let window = smoothstep(RAINBOW_MIN_DEG, RAINBOW_MIN_DEG + RAINBOW_FADE_DEG, deg)
        * (1.0 - smoothstep(RAINBOW_MAX_DEG - RAINBOW_FADE_DEG, RAINBOW_MAX_DEG, deg));
    let n = water_index(nm);
    let x23 = (2.0 * PI * a / (nm * 1e-9)).powf(2.0 / 3.0);
    let mut sum = 0.0;
    for k in 1..=2 {
        let bow = rainbow_bow(n, k);
        let s = x23 * bow.c_cbrt_inv;
        let eps = if k == 1 {
            bow.angle - phi
        } else {
            phi - bow.angle
        };
        let ai = airy_ai(-s * eps);
        sum += bow.scale * s.sqrt() * ai * ai;
    }
    window * 0.5 * sum / (2.0 * PI * phi.sin())
}

// WGSL: rainbow.wgsl::cie_lobe
fn cie_lobe(nm: f64, mu: f64, below: f64, above: f64) -> f64 {
    let t = (nm - mu) / if nm < mu { below } else { above };
    (-0.5 * t * t).exp()
}

// WGSL: rainbow.wgsl::spectral_rgb
/// Linear sRGB of a unit of light at `nm` (CIE 1931 by Wyman, Sloan and Shirley 2013's fit).
fn spectral_rgb(nm: f64) -> V3 {
    let x = 1.056 * cie_lobe(nm, 599.8, 37.9, 31.0) + 0.362 * cie_lobe(nm, 442.0, 16.0, 26.7)
        - 0.065 * cie_lobe(nm, 501.1, 20.4, 26.2);
    let y = 0.821 * cie_lobe(nm, 568.8, 46.9, 40.5) + 0.286 * cie_lobe(nm, 530.9, 16.3, 31.1);
    let z = 1.217 * cie_lobe(nm, 437.0, 11.8, 36.0) + 0.681 * cie_lobe(nm, 459.0, 26.0, 13.8);
    V3::new(
        3.2406 * x - 1.5372 * y - 0.4986 * z,
        -0.9689 * x + 1.8758 * y + 0.0415 * z,
        0.0557 * x - 0.2040 * y + 1.0570 * z,
    )
}

// WGSL: rainbow.wgsl::rainbow_lut
/// Texel `x` of the Lee diagram's row for drops of radius `a` (m) and a sun of angular radius
/// `sun_radius` (rad): the bows' phase function over the spectrum (white 1) and the disc.
pub(crate) fn rainbow_lut_texel(x: usize, a: f64, sun_radius: f64) -> V3 {
    let span = (RAINBOW_MAX_DEG - RAINBOW_MIN_DEG).to_radians();
    let phi = RAINBOW_MIN_DEG.to_radians() + span * x as f64 / (RAINBOW_TEXELS - 1) as f64;
    let mut sum = V3::ZERO;
    let mut white = V3::ZERO;
    for j in 0..RAINBOW_WAVELENGTHS {
        let nm = 400.0 + 300.0 * (j as f64 + 0.5) / RAINBOW_WAVELENGTHS as f64;
        let rgb = spectral_rgb(nm);
        white += rgb;
        let (mut p, mut weights) = (0.0, 0.0);
        for m in 1..=RAINBOW_SUN_TAPS {
            let u = m as f64 * PI / (RAINBOW_SUN_TAPS + 1) as f64;
            let w = u.sin() * u.sin();
            p += w * rainbow_phase(phi + u.cos() * sun_radius, a, nm);
            weights += w;
        }
        sum += rgb * (p / weights);
    }
    V3::new(
        (sum.x / white.x).max(0.0),
        (sum.y / white.y).max(0.0),
        (sum.z / white.z).max(0.0),
    )
}

// WGSL: rainbow.wgsl::rainbow_phase_rgb (its cheap path)
/// The cheap path's phase function: three wavelengths, one a channel.
pub(crate) fn cheap_phase_rgb(f: &Frame, phi: f64) -> V3 {
    let a = f.rainbow_drop_radius;
    let [r, g, b] = RAINBOW_RGB_NM.map(|nm| rainbow_phase(phi, a, nm));
    V3::new(r, g, b)
}

/// Whether the frame's rainbow reads its table (the uniforms set `FLAG_LEE_DIAGRAM` only for a
/// scene whose `Rainbow::uses_table`).
pub(crate) fn uses_table(f: &Frame) -> bool {
    f.flags & FLAG_LEE_DIAGRAM != 0
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The series and the asymptotic forms meet within 0.1% (DLMF's values: Ai(0) = 0.35503,
    /// Ai(-2.3381) = 0, the first zero, Ai(1) = 0.13529, Ai(-1) = 0.53556).
    #[test]
    fn airy_matches_known_values_and_joins_smoothly() {
        assert!((airy_ai(0.0) - 0.355_028).abs() < 1e-6);
        assert!(airy_ai(-2.338_107).abs() < 1e-5);
        assert!((airy_ai(1.0) - 0.135_292).abs() < 1e-5);
        assert!((airy_ai(-1.0) - 0.535_561).abs() < 1e-5);
        for x in [3.0, -4.0] {
            let (a, b) = (airy_ai(x - 1e-9), airy_ai(x + 1e-9));
            assert!(
                (a - b).abs() < 1e-3 * a.abs().max(1e-3),
                "Ai jumps at {x}: {a} {b}"
            );
        }
    }

    /// Descartes's angles: the primary near 42 degrees (red outside blue), the secondary
    /// near 51 (red inside).
    #[test]
    fn the_bows_lie_where_descartes_puts_them() {
        let red = |k| rainbow_bow(water_index(650.0), k).angle.to_degrees();
        let blue = |k| rainbow_bow(water_index(450.0), k).angle.to_degrees();
        assert!(
            red(1) > blue(1) && (40.0..43.5).contains(&red(1)) && (40.0..43.5).contains(&blue(1)),
            "{} {}",
            red(1),
            blue(1)
        );
        assert!(
            red(2) < blue(2) && (49.5..54.0).contains(&red(2)) && (49.5..54.0).contains(&blue(2)),
            "{} {}",
            red(2),
            blue(2)
        );
    }
}
