//! The CPU twin of `lighting.wgsl`: the light march toward the sun, multiple-scattering
//! octaves, ambient and precipitation darkening (its phase functions are in [`crate::phase`]).

use crate::density::{
    ANVIL_BASE, Counters, Layer, cloud_layers, cloud_top_fraction, height_signal, layer_height,
};
use crate::frame::{FLAG_BEER_POWDER, Frame, PI};
use crate::geometry::{altitude_of, hits_ground, ray_shell_from};
use crate::math::{V3, mix, mix_v, saturate};
use crate::medium::Model;
use crate::phase::{phase, phase_hg};
use crate::sky::{SkyTables, physical, sun_through_air};

/// How the light march toward the sun is discretised.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct LightMarch {
    /// Number of segments (`frame.light_steps` in the WGSL).
    pub steps: u32,
    /// Each segment is this many times longer than the previous (`frame.light_step_growth`).
    pub growth: f64,
    /// Length of the first segment, metres (`frame.first_light_step`); ignored with `to_layer_exit`.
    pub first: f64,
    /// Not in the WGSL (converged reference): the `steps` segments cover exactly the sun ray's
    /// path to where it leaves the layer, the first one sized so that they add up to it.
    pub to_layer_exit: bool,
}

/// Distance from camera-relative `rel` (altitude `alt`) along unit `d` to where the ray leaves
/// cloud layer `l` (through the top, or through the bottom if it goes down into it).
pub(crate) fn distance_to_layer_exit(f: &Frame, rel: V3, alt: f64, d: V3, l: &Layer) -> f64 {
    let inner = ray_shell_from(f, rel, alt, d, l.bottom);
    if inner.hit && inner.t0 > 0.0 {
        return inner.t0;
    }
    let outer = ray_shell_from(f, rel, alt, d, l.top);
    outer.t1.max(0.0)
}

// WGSL: lighting.wgsl::sun_optical_depth
// Must agree: midpoint samples of segments growing by `growth`, the loop ends at the first
// sample outside the layer, each evaluated sample counts one light sample.
/// Optical depth toward the sun from camera-relative `rel` (world position `p`) in layer `l`
/// (the layers above: [`optical_depth_above`]).
pub(crate) fn sun_optical_depth(
    m: &Model,
    lm: &LightMarch,
    rel: V3,
    p: V3,
    l: &Layer,
    counters: &mut Counters,
) -> f64 {
    let f = &m.f;
    let sun = f.sun();
    let (steps, growth) = (lm.steps, lm.growth);
    let mut seg = lm.first;
    if lm.to_layer_exit {
        let len = distance_to_layer_exit(f, rel, altitude_of(f, rel), sun, l);
        seg = if growth == 1.0 {
            len / f64::from(steps)
        } else {
            len * (growth - 1.0) / (growth.powi(steps as i32) - 1.0)
        };
    }
    segment_optical_depth(m, rel, p, l, sun, (seg, growth, steps), true, counters)
}

// WGSL: lighting.wgsl::ABOVE_SAMPLES
const ABOVE_SAMPLES: u32 = 4;

// WGSL: lighting.wgsl::optical_depth_above
// Must agree: ABOVE_SAMPLES midpoint samples of equal stretches of the sun ray's crossing of
// each layer above, each counting one light sample.
/// The sun ray's optical depth through the layers above layer `l`.
pub(crate) fn optical_depth_above(
    m: &Model,
    rel: V3,
    p: V3,
    l: &Layer,
    counters: &mut Counters,
) -> f64 {
    let f = &m.f;
    let sun = f.sun();
    let sigma_t = f.scattering + f.absorption;
    let mut tau = 0.0;
    let alt0 = altitude_of(f, rel);
    for above in cloud_layers(f) {
        if above.bottom <= l.top {
            continue;
        }
        let enter = ray_shell_from(f, rel, alt0, sun, above.bottom);
        let exit = ray_shell_from(f, rel, alt0, sun, above.top);
        // WGSL: `!(exit.t1 > enter.t1)` also catches NaN.
        if !enter.hit
            || !exit.hit
            || exit.t1.partial_cmp(&enter.t1) != Some(std::cmp::Ordering::Greater)
            || enter.t1 <= 0.0
        {
            continue;
        }
        let step = (exit.t1 - enter.t1) / f64::from(ABOVE_SAMPLES);
        for k in 0..ABOVE_SAMPLES {
            let s = enter.t1 + (f64::from(k) + 0.5) * step;
            counters.light += 1;
            tau += m.layer_density(p + sun * s, altitude_of(f, rel + sun * s), &above, counters)
                * sigma_t
                * step;
        }
    }
    tau
}

// WGSL: lighting.wgsl::segment_optical_depth
// Must agree: midpoint samples of segments growing by `growth`, the loop ends at the first
// sample outside the layer, each evaluated sample counts one light sample.
/// Optical depth from camera-relative `rel` (world position `p`) along unit `d` in layer `l`:
/// `steps` segments, the first `first` metres long, each `growth` times the one before (the
/// clouds' detail erosion only if `with_detail`).
#[allow(clippy::too_many_arguments)]
pub(crate) fn segment_optical_depth(
    m: &Model,
    rel: V3,
    p: V3,
    l: &Layer,
    d: V3,
    (first, growth, steps): (f64, f64, u32),
    with_detail: bool,
    counters: &mut Counters,
) -> f64 {
    let f = &m.f;
    let sigma_t = f.scattering + f.absorption;
    let mut seg = first;
    let mut dist = 0.0;
    let mut tau = 0.0;
    for _ in 0..steps {
        let s = dist + 0.5 * seg;
        let alt = altitude_of(f, rel + d * s);
        if alt > l.top || alt < l.bottom {
            break;
        }
        counters.light += 1;
        tau += m.layer_density_with(p + d * s, alt, l, with_detail, counters) * sigma_t * seg;
        dist += seg;
        seg *= growth;
    }
    tau
}

// WGSL: lighting.wgsl::COLUMN_STEPS
/// The octaves' column in a closed deck: equal steps from the sample to the layer's top.
const COLUMN_STEPS: u32 = 3;

// WGSL: lighting.wgsl::octave_optical_depth
// Must agree: the column goes straight up (away from the planet's centre) to the layer's top
// sphere in COLUMN_STEPS equal segments of the density without detail erosion.
/// The octaves' optical depth at a sample of layer `l` whose sun ray has optical depth `tau`,
/// `above` of it in the layers above: in a closed deck the scaled vertical column above the
/// sample mixed in for the deck's own part (lighting.wgsl says why).
pub(crate) fn octave_optical_depth(
    m: &Model,
    rel: V3,
    p: V3,
    l: &Layer,
    (tau, above): (f64, f64),
    counters: &mut Counters,
) -> f64 {
    let f = &m.f;
    let deck = saturate((l.coverage - 0.8) / 0.1);
    let w = f.steep_light * deck;
    // WGSL: not below a deck weight of 1e-3 (f32 rounding at a coverage of 0.8).
    if deck < 1e-3 || w <= 0.0 || f.light_steps == 0 {
        return tau;
    }
    let up = V3::new(rel.x, rel.y + f.planet_radius, rel.z).normalize();
    let top = ray_shell_from(f, rel, altitude_of(f, rel), up, l.top);
    let len = if top.hit && top.t1 > 0.0 { top.t1 } else { 0.0 };
    let column = segment_optical_depth(
        m,
        rel,
        p,
        l,
        up,
        (len / f64::from(COLUMN_STEPS), 1.0, COLUMN_STEPS),
        false,
        counters,
    );
    mix(tau, f.steep_light_scale * column + above, w)
}

// WGSL: lighting.wgsl::far_optical_depth
// Must agree: the reach is the real-time light march's (its segments' total length, from the
// uniforms), the stretch ends where the sun ray enters an anvil's band, each quarter of it a
// mixture of the weather map's coverage times the height signal at its middle; a cirrus
// layer's share takes none.
/// The far shadow: the statistical optical depth (a binary Markov mixture's) of the sun ray's
/// stretch inside layer `l` beyond the light march's reach and short of an anvil's band
/// (`band`, [`anvil_band_entry`]), 0 with the far shadow off.
pub(crate) fn far_optical_depth(m: &Model, rel: V3, p: V3, l: &Layer, band: f64) -> f64 {
    let f = &m.f;
    let chord = f.far_chord;
    if chord <= 0.0 || f.light_steps == 0 {
        return 0.0;
    }
    let reach = light_march_reach(f);
    let sun = f.sun();
    let exit = ray_shell_from(f, rel, altitude_of(f, rel), sun, l.top);
    let end = if band >= 0.0 {
        exit.t1.min(band.max(reach))
    } else {
        exit.t1
    };
    let len = end - reach;
    // WGSL: `!(len > 0.0)` also catches NaN.
    if !exit.hit || len.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return 0.0;
    }
    (0..4)
        .map(|i| {
            let t = reach + (f64::from(i) + 0.5) * 0.25 * len;
            let h = saturate(layer_height(l, altitude_of(f, rel + sun * t)));
            let w = m.weather(p + sun * t, l);
            let cover = (w.coverage * height_signal(f, h / w.top, l.cloud_type)).min(0.95);
            0.25 * len * cover / ((1.0 - cover) * chord)
        })
        .sum::<f64>()
        * (1.0 - l.cirrus)
}

// WGSL: lighting.wgsl::light_march_reach
/// The real-time light march's reach: its segments' total length (m).
fn light_march_reach(f: &Frame) -> f64 {
    let growth = f.light_step_growth;
    let steps = f64::from(f.light_steps);
    if growth == 1.0 {
        f.first_light_step * steps
    } else {
        f.first_light_step * (growth.powf(steps) - 1.0) / (growth - 1.0)
    }
}

// WGSL: lighting.wgsl::anvil_band_entry
/// Where the sun ray from camera-relative `rel` enters layer `l`'s anvil
/// band: 0 from inside it, -1 where the layer has no anvil or the ray does not reach it.
pub(crate) fn anvil_band_entry(m: &Model, rel: V3, l: &Layer) -> f64 {
    if m.anvil_weight(l) <= 0.0 {
        return -1.0;
    }
    let f = &m.f;
    let alt = altitude_of(f, rel);
    let base = mix(l.bottom, l.top, ANVIL_BASE);
    if alt >= base {
        return 0.0;
    }
    let enter = ray_shell_from(f, rel, alt, f.sun(), base);
    // WGSL: `!(enter.t1 > 0.0)` also catches NaN.
    if !enter.hit || enter.t1.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return -1.0;
    }
    enter.t1
}

// WGSL: lighting.wgsl::anvil_optical_depth
// Must agree: from the later of the band's entry and the light march's reach to the layer's
// top, ABOVE_SAMPLES midpoint samples of equal stretches, each counting one light sample.
/// An anvil's shade: the sun ray's optical depth through layer `l`'s anvil band beyond the
/// real-time light march's reach (`band` from [`anvil_band_entry`]).
pub(crate) fn anvil_optical_depth(
    m: &Model,
    rel: V3,
    p: V3,
    l: &Layer,
    band: f64,
    counters: &mut Counters,
) -> f64 {
    let f = &m.f;
    if band < 0.0 || f.light_steps == 0 {
        return 0.0;
    }
    let sun = f.sun();
    let exit = ray_shell_from(f, rel, altitude_of(f, rel), sun, l.top);
    let start = band.max(light_march_reach(f));
    // WGSL: `!(exit.t1 > start)` also catches NaN.
    if !exit.hit || exit.t1.partial_cmp(&start) != Some(std::cmp::Ordering::Greater) {
        return 0.0;
    }
    let sigma_t = f.scattering + f.absorption;
    let step = (exit.t1 - start) / f64::from(ABOVE_SAMPLES);
    (0..ABOVE_SAMPLES)
        .map(|k| {
            let s = start + (f64::from(k) + 0.5) * step;
            counters.light += 1;
            m.layer_density(p + sun * s, altitude_of(f, rel + sun * s), l, counters)
                * sigma_t
                * step
        })
        .sum()
}

// WGSL: lighting.wgsl::sun_scattering
// The WGSL passes one `far` for both: the converged march (`LightMarch::to_layer_exit`)
// samples the whole sun ray in the layer, so its single scattering takes no far shadow
// (`far_direct` 0) while the side light keeps the model's (`far_side`). The weather map's
// coverage, the height fraction at the sample, its layer's coverage and the sun ray's optical
// depth through the layers above travel together (clippy's argument limit).
/// Sun light scattered toward the viewer per unit illuminance and unit sigma_s, summed over
/// octaves fed through the cloud's top and sides, with the optional Beer-Powder factor: the
/// whole and the octaves' part of it (the WGSL's `SunScattering`).
pub(crate) fn sun_scattering(
    f: &Frame,
    cos_theta: f64,
    view_y: f64,
    (tau, tau_oct): (f64, f64),
    (far_direct, far_side): (f64, f64),
    build: f64,
    (coverage, h, layer_coverage, above): (f64, f64, f64, f64),
) -> (f64, f64) {
    let a = f.ms_contribution;
    let b = f.ms_extinction;
    let c = f.ms_eccentricity;
    // WGSL: min(frame.octaves, MAX_OCTAVES); the plan always picks a variant with MAX_OCTAVES
    // >= the scene's octaves, and the largest variant compiles 8.
    let octaves = f.octaves.min(8);
    let mut octave_sum = 0.0;
    let (mut ka, mut kb, mut kc) = (1.0, 1.0, 1.0);
    for _ in 0..octaves {
        ka *= a;
        kb *= b;
        kc *= c;
        // Two-stream-like fall-off of the diffuse light with depth (lighting.wgsl says why).
        octave_sum += ka * phase(f, cos_theta, kc) / (1.0 + kb * tau_oct);
    }
    // The octaves stand for the diffuse field, fed by the flux through a deck's top and a
    // broken layer's sides, and leaking out of small clouds (lighting.wgsl says why).
    let mu0 = saturate(f.sun().y);
    let side = (1.0 - mu0 * mu0).max(0.0).sqrt() * (1.0 - saturate(coverage)) * (-far_side).exp();
    let mut feed = mu0 + f.side_light * side;
    if f.coverage_exponent > 0.0 {
        feed *= coverage.max(1e-6).powf(f.coverage_exponent);
    }
    feed *= diffuse_limb(f, view_y, coverage)
        * vertical_anisotropy(f, view_y, coverage, h)
        * deck_escape(f, mu0, layer_coverage, above)
        * downward_dimming(f, view_y, coverage, h, tau * mu0);
    let mut octaves_part = feed * build * octave_sum;
    let mut total = phase(f, cos_theta, 1.0) * (-tau - far_direct).exp() + octaves_part;
    if f.flags & FLAG_BEER_POWDER != 0 {
        let powder = 1.0 - (-f.powder_strength * tau).exp();
        total *= powder;
        octaves_part *= powder;
    }
    (total, octaves_part)
}

// WGSL: lighting.wgsl::FORWARD_LOBE_THIN
/// The pixel transmittance at and above which the forward lobe has its full strength.
const FORWARD_LOBE_THIN: f64 = 0.1;

// WGSL: lighting.wgsl::forward_lobe
/// The factor on a pixel's octave light for the cosine between its view ray and the sun and
/// its transmittance: `1 + w (4 pi HG(cos, g_f) - 1)`, `w = k min(T / 0.1, 1)` (lighting.wgsl
/// says why).
pub(crate) fn forward_lobe(f: &Frame, cos_theta: f64, transmittance: f64) -> f64 {
    let k = f.forward_lobe;
    if k <= 0.0 {
        return 1.0;
    }
    let w = k * saturate(transmittance / FORWARD_LOBE_THIN);
    1.0 + w * (4.0 * PI * phase_hg(cos_theta, f.forward_lobe_g) - 1.0)
}

// WGSL: lighting.wgsl::vertical_anisotropy
/// The octaves' vertical anisotropy at height fraction `h`: `1 + s view_y coverage (1 - h)`,
/// brighter looking up than down in a layer lit from above (lighting.wgsl says why).
pub(crate) fn vertical_anisotropy(f: &Frame, view_y: f64, coverage: f64, h: f64) -> f64 {
    1.0 + f.vertical_anisotropy * view_y * saturate(coverage) * (1.0 - saturate(h))
}

// WGSL: lighting.wgsl::DECK_POWER
/// The power of the layer's coverage that weights the octaves' deck escape.
const DECK_POWER: f64 = 8.0;

// WGSL: lighting.wgsl::downward_dimming
/// The octaves' dimming looking down: `1 - k |view_y| coverage (1 - h) tau_v / (tau_v + 1)`
/// for a view ray going down, clamped at 0 (lighting.wgsl says why).
pub(crate) fn downward_dimming(f: &Frame, view_y: f64, coverage: f64, h: f64, tau_v: f64) -> f64 {
    let k = f.downward_dimming * (-view_y).max(0.0) * saturate(coverage) * (1.0 - saturate(h));
    (1.0 - k * tau_v / (tau_v + 1.0)).max(0.0)
}

// WGSL: lighting.wgsl::DIFFUSE_MU
/// The flux-weighted mean cosine of light arriving alike from every direction of a hemisphere.
const DIFFUSE_MU: f64 = 2.0 / 3.0;

// WGSL: lighting.wgsl::DECK_ESCAPE_MAX
/// The most the deck escape's strength `e w` may be: the Eddington approximation's 6/7.
const DECK_ESCAPE_MAX: f64 = 0.857142857;

// WGSL: lighting.wgsl::deck_escape
/// The octaves' escape from a deck for a sun of zenith cosine `mu0`: `1 + e w (mu - 1/2)`, `w`
/// the layer's coverage to the 8th power, `e w` at most `DECK_ESCAPE_MAX`, `mu` the zenith
/// cosine of the light entering the deck: `mu0` for the direct beam, `DIFFUSE_MU` for what the
/// layers above (optical depth `above` along the sun ray) have made diffuse (lighting.wgsl says
/// why).
pub(crate) fn deck_escape(f: &Frame, mu0: f64, layer_coverage: f64, above: f64) -> f64 {
    let ew = f.deck_escape * saturate(layer_coverage).powf(DECK_POWER);
    let mu = mix(DIFFUSE_MU, mu0, (-above).exp());
    1.0 + ew.min(DECK_ESCAPE_MAX) * (mu - 0.5)
}

// WGSL: lighting.wgsl::diffuse_limb
/// The octaves' limb darkening toward grazing views of a deck: `(1 + k mu) / (1 + 2k/3)`, mu =
/// `|view_y|`, k the fitted strength, weighted by the coverage (lighting.wgsl says why).
pub(crate) fn diffuse_limb(f: &Frame, view_y: f64, coverage: f64) -> f64 {
    let k = f.limb_darkening;
    let layer = (1.0 + k * view_y.abs()) / (1.0 + 2.0 * k / 3.0);
    mix(1.0, layer, saturate(coverage))
}

// WGSL: lighting.wgsl::octave_buildup
/// The octaves' share at a sample of `density`: `1 - exp(-sigma_t density l)`, `l` the build-up
/// length, 1 where `l` is 0 (lighting.wgsl says why).
pub(crate) fn octave_buildup(f: &Frame, density: f64) -> f64 {
    let l = f.ms_buildup;
    if l <= 0.0 {
        return 1.0;
    }
    1.0 - (-(f.scattering + f.absorption) * density * l).exp()
}

// WGSL: lighting.wgsl::CELLULAR_OCTAVES
/// The share of the octaves a wholly cellular layer's cloudlets keep (see the WGSL for why).
const CELLULAR_OCTAVES: f64 = 0.75;

// WGSL: lighting.wgsl::cellular_octaves
/// The share of the octaves layer `l`'s clouds keep: `mix(1, CELLULAR_OCTAVES, cellular)`.
pub(crate) fn cellular_octaves(l: &Layer) -> f64 {
    mix(1.0, CELLULAR_OCTAVES, l.cellular)
}

// WGSL: lighting.wgsl::ambient
/// Ambient light at height fraction `h`: a gradient from the bottom to the top colour, or under
/// the physical sky the sky's cosine-weighted radiance from below and from above, seen from the
/// layer's bottom (the sky-ambient table, for the sun's angle at camera-relative `rel`, m).
pub(crate) fn ambient(f: &Frame, sky: Option<&SkyTables>, h: f64, rel: V3) -> V3 {
    if let Some(sky) = physical(f, sky) {
        return sky.ambient_light(f, h, rel);
    }
    let bottom = V3::new(
        f.ambient_bottom[0],
        f.ambient_bottom[1],
        f.ambient_bottom[2],
    );
    let top = V3::new(f.ambient_top[0], f.ambient_top[1], f.ambient_top[2]);
    mix_v(bottom, top, h) * f.ambient_strength
}

// WGSL: lighting.wgsl::PRECIPITATION_DEPTH
const PRECIPITATION_DEPTH: f64 = 10.0;

// WGSL: lighting.wgsl::scattered_light
/// In-scattered radiance per unit length at a view sample of layer `l`: sigma_s * density *
/// (sun + ambient + a lightning flash's light), darkened toward the base of raining clouds; and, apart, the octaves' part
/// of it (the WGSL's `ScatteredLight`).
// The WGSL's parameters plus the model and the light-march settings (uniforms there).
#[allow(clippy::too_many_arguments)]
pub(crate) fn scattered_light(
    m: &Model,
    lm: &LightMarch,
    rel: V3,
    p: V3,
    alt: f64,
    density: f64,
    view: V3,
    l: &Layer,
    counters: &mut Counters,
) -> (V3, V3) {
    let f = &m.f;
    let sun = f.sun();
    let h = saturate(layer_height(l, alt));
    let mut sun_light = V3::ZERO;
    let mut octave_light = V3::ZERO;
    let weather = m.weather(p, l);
    // The share of the darkening the sun ray's cloud gives (PRECIPITATION_DEPTH).
    let mut load = 1.0;
    if !hits_ground(f, rel, alt, sun) {
        // LIGHT_MARCH: with 0 light steps the layer's own march returns 0, as the switched-off
        // WGSL does (and so does its far shadow); the layers above still shade it, as in the
        // WGSL's shadowed variants with 0 light steps (the unshadowed variant skips them too).
        // The converged march samples the whole sun ray in the layer, the anvil's band too.
        let above = optical_depth_above(m, rel, p, l, counters);
        let band = anvil_band_entry(m, rel, l);
        let anvil = if lm.to_layer_exit {
            0.0
        } else {
            anvil_optical_depth(m, rel, p, l, band, counters)
        };
        let tau = sun_optical_depth(m, lm, rel, p, l, counters) + above + anvil;
        let far = far_optical_depth(m, rel, p, l, band);
        let far_direct = if lm.to_layer_exit { 0.0 } else { far };
        let tau_oct = if lm.steps == 0 {
            tau
        } else {
            octave_optical_depth(m, rel, p, l, (tau, above), counters)
        };
        let (s, octaves) = sun_scattering(
            f,
            view.dot(sun),
            view.y,
            (tau, tau_oct),
            (far_direct, far),
            octave_buildup(f, density) * cellular_octaves(l),
            (
                m.regional_coverage(p, l, &weather),
                saturate(h / cloud_top_fraction(f, l, &weather)),
                l.coverage,
                above,
            ),
        );
        let lit = f.sun_illuminance().mul_v(sun_through_air(f, m.sky(), rel));
        sun_light = lit * s;
        octave_light = lit * octaves;
        load = 1.0 - (-tau / PRECIPITATION_DEPTH).exp();
    }
    let darkening =
        saturate(1.0 - f.precipitation_darkening * weather.precipitation * (1.0 - h) * load);
    // The sky's light is not darkened (lighting.wgsl::scattered_light says why).
    let k = f.scattering * density;
    let dark = darkening * k;
    (
        (sun_light + crate::lightning::lightning_light(f, rel)) * dark
            + ambient(f, m.sky(), h, rel) * k,
        octave_light * dark,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::medium::Medium;
    use crate::phase::tests::integral;
    use stratus_scene::Scene;

    /// The far shadow's optical depth 100 m above the main layer's bottom under a sun
    /// `elevation_deg` up, in the default scene changed by `edit`.
    fn far_at(elevation_deg: f64, edit: impl Fn(&mut Scene)) -> f64 {
        // Only the weather map's coverage matters here.
        let noise = crate::small_noise();
        let mut scene = Scene::default();
        // On the default's convective cells the far shadow reads the cells' mask, 0 in the gaps
        // (docs/fit-log.md, "Low sun on convective cells").
        scene.clouds.convective_cells = 0.0;
        scene.sun.elevation_deg = elevation_deg;
        edit(&mut scene);
        let m = Model::new(&scene, Medium::Clouds(&noise));
        let l = cloud_layers(&m.f).next().expect("the main layer");
        let rel = V3::new(0.0, l.bottom + 100.0, 0.0);
        far_optical_depth(&m, rel, rel, &l, anvil_band_entry(&m, rel, &l))
    }

    /// A storm layer (1-9 km, cumulus, coverage 0.6, as `weather thunderstorm`'s) under a sun
    /// 60 degrees up, with `anvil`.
    fn storm_model(noise: &stratus_noise::NoiseSet, anvil: f64) -> Model<'_> {
        let mut scene = Scene::default();
        // The state's towers stand on the weather map, not on convective cells.
        scene.clouds.convective_cells = 0.0;
        scene.sun.elevation_deg = 60.0;
        scene.atmosphere.cloud_bottom_m = 1000.0;
        scene.atmosphere.cloud_top_m = 9000.0;
        scene.clouds.coverage = 0.6;
        scene.clouds.cloud_type = 1.0;
        scene.clouds.anvil = anvil;
        Model::new(&scene, Medium::Clouds(noise))
    }

    /// An anvil shades the cloud under it beyond the light march's reach: the sun ray's stretch
    /// through its band is sampled (tens of optical depths under a plate, where the far
    /// shadow's broken-cloud statistics gave a few), the far shadow stops where the band
    /// begins, and a layer without an anvil takes neither.
    #[test]
    fn an_anvil_shades_the_cloud_under_it_beyond_the_light_march() {
        let noise = crate::small_noise();
        let (m, m0) = (storm_model(&noise, 1.0), storm_model(&noise, 0.0));
        let l = cloud_layers(&m.f).next().expect("the storm layer");
        // 3.4 km up (height fraction 0.3): the band (from 6.6 km) is 3.7 km along a sun 60
        // degrees up, beyond the light march's 3.15 km.
        let at = |x: f64, z: f64| V3::new(x, 3400.0, z);
        let mut deepest: f64 = 0.0;
        for i in -20..20 {
            for j in -20..20 {
                let rel = at(f64::from(i) * 1500.0, f64::from(j) * 1500.0);
                let band = anvil_band_entry(&m, rel, &l);
                let rise = 6600.0 - altitude_of(&m.f, rel);
                assert!(
                    (band - rise / 60f64.to_radians().sin()).abs() < 20.0,
                    "{band}"
                );
                assert!(band > light_march_reach(&m.f));
                let mut c = Counters::default();
                let tau = anvil_optical_depth(&m, rel, rel, &l, band, &mut c);
                assert_eq!(
                    c.light,
                    u64::from(ABOVE_SAMPLES),
                    "one light sample per band sample"
                );
                deepest = deepest.max(tau);
                // Without an anvil: no band, no samples, the far shadow to the layer's top.
                assert_eq!(anvil_band_entry(&m0, rel, &l), -1.0);
                let mut c0 = Counters::default();
                assert_eq!(anvil_optical_depth(&m0, rel, rel, &l, -1.0, &mut c0), 0.0);
                assert_eq!(c0.light, 0);
                // The far shadow stops at the band: never more than without it.
                assert!(
                    far_optical_depth(&m, rel, rel, &l, band)
                        <= far_optical_depth(&m, rel, rel, &l, -1.0)
                );
            }
        }
        assert!(
            deepest > 10.0,
            "the deepest plate's optical depth: {deepest}"
        );
        // Inside the band the band begins at once; where the light march reaches the layer's
        // top there is nothing beyond it to sample.
        let high = at(0.0, 0.0) + V3::new(0.0, 3800.0, 0.0);
        assert_eq!(anvil_band_entry(&m, high, &l), 0.0);
        let mut c = Counters::default();
        assert_eq!(anvil_optical_depth(&m, high, high, &l, 0.0, &mut c), 0.0);
        assert_eq!(c.light, 0);
    }

    /// Nothing where the light march reaches the layer's top (a high sun), more the lower the
    /// sun (a longer stretch beyond the march), in inverse proportion to the chord; none when
    /// off or without a light march.
    #[test]
    fn far_shadow_covers_what_the_light_march_does_not_reach() {
        assert_eq!(far_at(60.0, |_| {}), 0.0);
        let (ten, three) = (far_at(10.0, |_| {}), far_at(3.0, |_| {}));
        assert!(
            ten > 0.0 && three > 2.0 * ten,
            "10 deg: {ten}, 3 deg: {three}"
        );
        let half_chord = far_at(3.0, |s| {
            s.lighting.multiple_scattering.far_chord_m /= 2.0;
        });
        assert!(
            (half_chord / three - 2.0).abs() < 1e-9,
            "{half_chord} {three}"
        );
        let off = far_at(3.0, |s| s.lighting.multiple_scattering.far_chord_m = 0.0);
        assert_eq!(off, 0.0);
        assert_eq!(far_at(3.0, |s| s.quality.light_steps = 0), 0.0);
        // A clear layer casts none.
        assert_eq!(far_at(3.0, |s| s.clouds.coverage = 0.0), 0.0);
    }

    /// The limb darkening keeps the diffuse flux through a deck (its cosine-weighted mean over
    /// the hemisphere is 1), favours views along the normal, up or down, over grazing ones, and
    /// leaves a clear sample's octaves, or all of them when switched off, as they were.
    #[test]
    fn limb_darkening_keeps_the_flux_and_favours_the_normal() {
        let noise = crate::small_noise();
        let mut scene = Scene::default();
        scene.lighting.multiple_scattering.limb_darkening = 1.5;
        let m = Model::new(&scene, Medium::Clouds(&noise));
        let n = 100_000;
        let flux: f64 = (0..n)
            .map(|i| {
                let mu = (f64::from(i) + 0.5) / f64::from(n);
                2.0 * mu * diffuse_limb(&m.f, mu, 1.0) / f64::from(n)
            })
            .sum();
        assert!((flux - 1.0).abs() < 1e-6, "{flux}");
        let (normal, grazing) = (diffuse_limb(&m.f, 1.0, 1.0), diffuse_limb(&m.f, 0.0, 1.0));
        assert!(normal > 1.0 && grazing < 1.0, "{normal} {grazing}");
        assert_eq!(diffuse_limb(&m.f, -1.0, 1.0), normal);
        assert_eq!(diffuse_limb(&m.f, 0.3, 0.0), 1.0);
        scene.lighting.multiple_scattering.limb_darkening = 0.0;
        let off = Model::new(&scene, Medium::Clouds(&noise));
        assert_eq!(diffuse_limb(&off.f, 0.3, 1.0), 1.0);
    }

    /// The forward lobe moves a thin pixel's octave light toward the sun without adding any
    /// (its mean over the sphere is 1), never goes negative, grows with the transmittance up
    /// to its threshold, and is 1 through opaque cloud or when off.
    #[test]
    fn forward_lobe_moves_light_toward_the_sun_and_adds_none() {
        let noise = crate::small_noise();
        let mut scene = Scene::default();
        scene.lighting.multiple_scattering.forward_lobe = 1.0;
        scene.lighting.multiple_scattering.forward_lobe_g = 0.6;
        let m = Model::new(&scene, Medium::Clouds(&noise));
        for t in [0.05, 0.1, 0.7] {
            let mean = integral(|c| forward_lobe(&m.f, c, t)) / (4.0 * PI);
            assert!((mean - 1.0).abs() < 1e-6, "T {t}: mean {mean}");
        }
        let (ahead, behind) = (forward_lobe(&m.f, 1.0, 0.5), forward_lobe(&m.f, -1.0, 0.5));
        assert!(
            ahead > 1.0 && (0.0..1.0).contains(&behind),
            "{ahead} {behind}"
        );
        assert!(forward_lobe(&m.f, 1.0, 0.05) < ahead);
        assert_eq!(forward_lobe(&m.f, 1.0, 0.5), forward_lobe(&m.f, 1.0, 0.9));
        assert_eq!(forward_lobe(&m.f, 1.0, 0.0), 1.0);
        scene.lighting.multiple_scattering.forward_lobe = 0.0;
        let off = Model::new(&scene, Medium::Clouds(&noise));
        assert_eq!(forward_lobe(&off.f, 1.0, 0.5), 1.0);
    }

    /// The vertical anisotropy brightens the octaves seen looking up and darkens them looking
    /// down by as much (its mean over the sphere is 1), most at a deck's base, not at its top
    /// nor in clear surroundings, stays positive at its largest strength, and is 1 when off.
    #[test]
    fn vertical_anisotropy_favours_light_going_down_and_adds_none() {
        let noise = crate::small_noise();
        let mut scene = Scene::default();
        scene.lighting.multiple_scattering.vertical_anisotropy = 1.0;
        let m = Model::new(&scene, Medium::Clouds(&noise));
        for h in [0.0, 0.4, 1.0] {
            let mean = integral(|y| vertical_anisotropy(&m.f, y, 0.8, h)) / (4.0 * PI);
            assert!((mean - 1.0).abs() < 1e-6, "h {h}: mean {mean}");
        }
        let (up, down) = (
            vertical_anisotropy(&m.f, 0.5, 1.0, 0.2),
            vertical_anisotropy(&m.f, -0.5, 1.0, 0.2),
        );
        assert!(up > 1.0 && down < 1.0, "{up} {down}");
        assert!(vertical_anisotropy(&m.f, 0.5, 1.0, 0.0) > up);
        assert_eq!(vertical_anisotropy(&m.f, -1.0, 1.0, 0.0), 0.0);
        assert_eq!(vertical_anisotropy(&m.f, 0.5, 1.0, 1.0), 1.0);
        assert_eq!(vertical_anisotropy(&m.f, 0.5, 0.0, 0.2), 1.0);
        scene.lighting.multiple_scattering.vertical_anisotropy = 0.0;
        let off = Model::new(&scene, Medium::Clouds(&noise));
        assert_eq!(vertical_anisotropy(&off.f, 0.5, 1.0, 0.2), 1.0);
    }

    /// The downward dimming leaves light going down, and light going up with no cloud above
    /// or at the layer's top, alone; it dims more under more cloud, for steeper views down and
    /// lower samples, and never below 0.
    #[test]
    fn downward_dimming_dims_light_going_up_under_cloud() {
        let noise = crate::small_noise();
        let mut scene = Scene::default();
        scene.lighting.multiple_scattering.downward_dimming = 2.0;
        let m = Model::new(&scene, Medium::Clouds(&noise));
        let f = &m.f;
        // Looking up, at a cloud's lit top (no cloud above) or at the layer's top: none.
        assert_eq!(downward_dimming(f, 0.5, 1.0, 0.2, 10.0), 1.0);
        assert_eq!(downward_dimming(f, -0.5, 1.0, 0.2, 0.0), 1.0);
        assert_eq!(downward_dimming(f, -0.5, 1.0, 1.0, 10.0), 1.0);
        // More the more cloud above, the steeper the view down and the lower the sample.
        let under = |tau_v, view_y, h| downward_dimming(f, view_y, 1.0, h, tau_v);
        assert!(under(1.0, -0.2, 0.2) > under(10.0, -0.2, 0.2));
        assert!(under(10.0, -0.2, 0.2) > under(10.0, -0.6, 0.2));
        assert!(under(10.0, -0.6, 0.8) > under(10.0, -0.6, 0.2));
        // Clamped at 0 (2 |view_y| (1 - h) tau_v / (tau_v + 1) exceeds 1 straight down).
        assert_eq!(under(100.0, -1.0, 0.0), 0.0);
        scene.lighting.multiple_scattering.downward_dimming = 0.0;
        let off = Model::new(&scene, Medium::Clouds(&noise));
        assert_eq!(downward_dimming(&off.f, -1.0, 1.0, 0.0, 100.0), 1.0);
    }

    /// The octaves' column changes their optical depth in a closed deck only, and costs its
    /// light samples there (from the layer's middle every step lies inside it).
    #[test]
    fn the_column_is_a_closed_decks_alone() {
        let noise = crate::small_noise();
        let at = |coverage: f64, steep: f64| {
            let mut scene = Scene::default();
            scene.clouds.coverage = coverage;
            scene.lighting.multiple_scattering.steep_light = steep;
            let m = Model::new(&scene, Medium::Clouds(&noise));
            let l = cloud_layers(&m.f).next().expect("the main layer");
            let rel = V3::new(0.0, 0.5 * (l.bottom + l.top), 0.0);
            let mut counters = Counters::default();
            let tau = octave_optical_depth(&m, rel, rel, &l, (7.0, 0.0), &mut counters);
            // The layers above keep their part of the sun ray's optical depth in a deck.
            let mut more = Counters::default();
            let with_above = octave_optical_depth(&m, rel, rel, &l, (9.0, 2.0), &mut more);
            let deck = steep * saturate((coverage - 0.8) / 0.1);
            assert!(
                (with_above - (tau + 2.0)).abs() < 1e-9 * (1.0 + tau),
                "{with_above} {tau} (deck weight {deck})"
            );
            (tau, counters.light)
        };
        assert_eq!(at(0.5, 1.0), (7.0, 0));
        assert_eq!(at(1.0, 0.0), (7.0, 0));
        let (deck, light) = at(1.0, 1.0);
        assert!(deck != 7.0 && deck >= 0.0, "{deck}");
        assert_eq!(light, u64::from(COLUMN_STEPS), "{light}");
        // Half the weight, half way.
        let (half, _) = at(1.0, 0.5);
        assert!((half - 0.5 * (7.0 + deck)).abs() < 1e-9, "{half} {deck}");
    }

    /// The deck escape brightens a full deck's octaves under a high sun and darkens them under
    /// a low one (1 at 60 degrees from the zenith), leaves a broken layer nearly alone, is
    /// never stronger than the Eddington ratio's 6/7 (a sun at the horizon keeps 4/7 of a full
    /// deck's octaves, a sun overhead adds 3/7), takes diffuse light's cosine under a thick
    /// layer above, and is 1 when off.
    #[test]
    fn deck_escape_favours_a_high_sun_over_a_deck() {
        let noise = crate::small_noise();
        let mut scene = Scene::default();
        scene.lighting.multiple_scattering.deck_escape = 2.0;
        let m = Model::new(&scene, Medium::Clouds(&noise));
        let (high, low) = (
            deck_escape(&m.f, 1.0, 1.0, 0.0),
            deck_escape(&m.f, 0.1, 1.0, 0.0),
        );
        assert!(high > 1.0 && (0.0..1.0).contains(&low), "{high} {low}");
        assert_eq!(deck_escape(&m.f, 0.5, 1.0, 0.0), 1.0);
        assert!((deck_escape(&m.f, 0.0, 1.0, 0.0) - 4.0 / 7.0).abs() < 1e-8);
        assert!((deck_escape(&m.f, 1.0, 1.0, 0.0) - 10.0 / 7.0).abs() < 1e-8);
        // Below the bound (storm's coverage 0.9: 2 x 0.9^8 = 0.861, at it) the fitted strength.
        let w = 0.8f64.powi(8);
        assert!((deck_escape(&m.f, 1.0, 0.8, 0.0) - (1.0 + 2.0 * w * 0.5)).abs() < 1e-12);
        // A layer of coverage 0.5 is weighted 1/256 as a deck.
        assert!((deck_escape(&m.f, 1.0, 0.5, 0.0) - 1.0).abs() < 0.005);
        assert!(deck_escape(&m.f, 1.0, 0.9, 0.0) > deck_escape(&m.f, 1.0, 0.8, 0.0));
        // Under a thick layer above, the light entering the deck is diffuse: the sun's
        // elevation no longer matters, and the escape is that of zenith cosine 2/3.
        let diffuse = 1.0 + 6.0 / 7.0 * (2.0 / 3.0 - 0.5);
        for mu0 in [0.1, 0.5, 1.0] {
            assert!(
                (deck_escape(&m.f, mu0, 1.0, 60.0) - diffuse).abs() < 1e-9,
                "{mu0}"
            );
        }
        let half = deck_escape(&m.f, 1.0, 1.0, std::f64::consts::LN_2);
        assert!((half - 0.5 * (10.0 / 7.0 + diffuse)).abs() < 1e-8, "{half}");
        scene.lighting.multiple_scattering.deck_escape = 0.0;
        let off = Model::new(&scene, Medium::Clouds(&noise));
        assert_eq!(deck_escape(&off.f, 1.0, 1.0, 0.0), 1.0);
        assert_eq!(deck_escape(&off.f, 1.0, 1.0, 5.0), 1.0);
    }
}
