//! The CPU twin of the phase functions in `lighting.wgsl`. Their own module because the sky
//! (Mie scattering) and the composite (the analytic sky's sun glow) use them as well as the
//! clouds' lighting, and the sky must not depend on the clouds' lighting.

use crate::frame::{Frame, PHASE_CORNETTE_SHANKS, PHASE_TWO_LOBE_HG, PI};
use crate::math::mix;

// WGSL: lighting.wgsl::phase_hg
/// Henyey-Greenstein, normalised over the sphere (thesis eq. 5.4).
pub(crate) fn phase_hg(cos_theta: f64, g: f64) -> f64 {
    let g2 = g * g;
    let denom = (1.0 + g2 - 2.0 * g * cos_theta).max(1e-6);
    (1.0 - g2) / (4.0 * PI * denom * denom.sqrt())
}

// WGSL: lighting.wgsl::phase_cornette_shanks
/// Cornette-Shanks (thesis eq. 5.5).
pub(crate) fn phase_cornette_shanks(cos_theta: f64, g: f64) -> f64 {
    let g2 = g * g;
    let denom = (1.0 + g2 - 2.0 * g * cos_theta).max(1e-6);
    3.0 * (1.0 - g2) * (1.0 + cos_theta * cos_theta)
        / (8.0 * PI * (2.0 + g2) * denom * denom.sqrt())
}

// WGSL: lighting.wgsl::phase
/// The scene's phase model with eccentricities scaled by `scale`.
pub(crate) fn phase(f: &Frame, cos_theta: f64, scale: f64) -> f64 {
    let g = f.phase_g * scale;
    match f.phase_model {
        PHASE_TWO_LOBE_HG => {
            let g2 = f.phase_g2 * scale;
            mix(
                phase_hg(cos_theta, g),
                phase_hg(cos_theta, g2),
                f.phase_blend,
            )
        }
        PHASE_CORNETTE_SHANKS => phase_cornette_shanks(cos_theta, g),
        _ => phase_hg(cos_theta, g),
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// Integral over the sphere of a phase function of cos(theta), by the midpoint rule in cos.
    pub(crate) fn integral(p: impl Fn(f64) -> f64) -> f64 {
        let n = 200_000;
        (0..n)
            .map(|i| {
                let c = -1.0 + (i as f64 + 0.5) * 2.0 / n as f64;
                p(c) * 2.0 * PI * 2.0 / n as f64
            })
            .sum()
    }

    #[test]
    fn phase_functions_are_normalised() {
        for g in [-0.5, 0.0, 0.3, 0.76] {
            assert!(
                (integral(|c| phase_hg(c, g)) - 1.0).abs() < 1e-6,
                "HG g={g}"
            );
            assert!(
                (integral(|c| phase_cornette_shanks(c, g)) - 1.0).abs() < 1e-6,
                "CS g={g}"
            );
        }
    }
}
