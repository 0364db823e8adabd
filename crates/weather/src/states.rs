//! Weather states as data (seed 001's weather control: each state a set of render
//! parameters) and smooth transitions between them.
//!
//! A state sets the main cloud layer (altitudes, coverage, type, density, precipitation), the
//! wind speed, an optional ground fog layer, and the light the sky gives the clouds (ambient
//! colours, exposure). The sun's illuminance at the top of the layers is the same in every
//! state: the clouds' own light march is what dims it under a deck.

use stratus_scene::{CloudLayer, Scene};

use crate::WeatherError;

/// The render parameters of one weather state. Every field interpolates linearly, so a
/// transition is [`WeatherParams::mix`] with a smoothstep-eased weight.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct WeatherParams {
    /// Main layer coverage within [0, 1] (`clouds.coverage`).
    pub coverage: f64,
    /// Main layer cloud type within [0, 1]: 0 stratus, 0.5 stratocumulus, 1 cumulus.
    pub cloud_type: f64,
    /// Main layer density multiplier (`clouds.density`).
    pub density: f64,
    /// Precipitation within [0, 1] (`clouds.precipitation`).
    pub precipitation: f64,
    /// Main layer bottom, metres above the ground.
    pub cloud_bottom_m: f64,
    /// Main layer top, metres above the ground.
    pub cloud_top_m: f64,
    /// Wind speed, m/s (the direction stays the scene's).
    pub wind_speed_m_s: f64,
    /// Ground fog: the top of a stratus layer from the ground up, metres (0 = no fog).
    pub fog_top_m: f64,
    /// Ground fog density multiplier (0 = no fog).
    pub fog_density: f64,
    /// Ambient (sky) light at the bottom of a layer, linear RGB.
    pub ambient_bottom: [f64; 3],
    /// Ambient light at the top of a layer, linear RGB.
    pub ambient_top: [f64; 3],
    /// Exposure multiplier (`camera.exposure`): darker skies are exposed longer.
    pub exposure: f64,
    /// The share of cumulus on convective cells (`clouds.convective_cells`): 1 for the fair
    /// states, whose coverage then follows [`CELL_COVER_FRACTION`], 0 for the others.
    pub convective_cells: f64,
    /// Cumulonimbus anvils (`clouds.anvil`): 1 for the thunderstorm, 0 for the others.
    pub anvil: f64,
}

/// A named weather state.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct WeatherState {
    /// Name on the command line (`--from`, `--to`, `--state`).
    pub name: &'static str,
    /// What it looks like.
    pub about: &'static str,
    /// Its parameters.
    pub params: WeatherParams,
}

// Ambient colours: a clear sky's blue above, darker below (the preset's defaults); under
// decks the sky light turns grey and dim.
const BLUE_TOP: [f64; 3] = [0.6, 0.75, 1.0];
const BLUE_BOTTOM: [f64; 3] = [0.25, 0.3, 0.4];
const GREY_TOP: [f64; 3] = [0.5, 0.54, 0.6];
const GREY_BOTTOM: [f64; 3] = [0.24, 0.26, 0.29];
const DARK_TOP: [f64; 3] = [0.32, 0.34, 0.4];
const DARK_BOTTOM: [f64; 3] = [0.12, 0.13, 0.16];

const fn state(name: &'static str, about: &'static str, params: WeatherParams) -> WeatherState {
    WeatherState {
        name,
        about,
        params,
    }
}

/// A fair-weather state with coverage `coverage` (the others start from it).
const fn fair(coverage: f64) -> WeatherParams {
    WeatherParams {
        coverage,
        cloud_type: 1.0,
        density: 1.0,
        precipitation: 0.0,
        cloud_bottom_m: 1500.0,
        cloud_top_m: 4000.0,
        wind_speed_m_s: 6.0,
        fog_top_m: 0.0,
        fog_density: 0.0,
        ambient_bottom: BLUE_BOTTOM,
        ambient_top: BLUE_TOP,
        exposure: 1.0,
        convective_cells: 1.0,
        anvil: 0.0,
    }
}

/// Every state, from clear to stormy. Coverages follow the oktas of METAR's cover classes
/// (FEW 1-2, SCT 3-4, BKN 5-7, OVC 8 eighths): the fair states' cumulus, on convective
/// cells, through [`cell_coverage_for_fraction`] of the middle of their class (few 0.37 for
/// 0.1875, scattered and mist 0.61 for 0.4375), the others through
/// [`coverage_for_fraction`].
pub const STATES: [WeatherState; 10] = [
    state("clear", "no clouds, blue sky", fair(0.0)),
    state("few", "a few fair-weather cumulus (1-2 oktas)", fair(0.37)),
    state("scattered", "scattered cumulus (3-4 oktas)", fair(0.61)),
    state(
        "broken",
        "broken stratocumulus (5-7 oktas)",
        WeatherParams {
            cloud_type: 0.6,
            cloud_bottom_m: 1200.0,
            cloud_top_m: 3000.0,
            wind_speed_m_s: 8.0,
            ambient_bottom: GREY_BOTTOM,
            ambient_top: [0.55, 0.65, 0.8],
            exposure: 1.1,
            convective_cells: 0.0,
            ..fair(0.6)
        },
    ),
    state(
        "overcast",
        "a closed stratocumulus deck (8 oktas)",
        WeatherParams {
            cloud_type: 0.4,
            cloud_bottom_m: 900.0,
            cloud_top_m: 2400.0,
            wind_speed_m_s: 8.0,
            ambient_bottom: GREY_BOTTOM,
            ambient_top: GREY_TOP,
            exposure: 1.2,
            convective_cells: 0.0,
            ..fair(0.85)
        },
    ),
    state(
        "rain",
        "nimbostratus with rain: a low, dark, closed deck",
        WeatherParams {
            cloud_type: 0.25,
            density: 1.0,
            precipitation: 0.7,
            cloud_bottom_m: 600.0,
            cloud_top_m: 3000.0,
            wind_speed_m_s: 10.0,
            ambient_bottom: DARK_BOTTOM,
            ambient_top: GREY_TOP,
            exposure: 1.1,
            convective_cells: 0.0,
            ..fair(0.9)
        },
    ),
    state(
        "thunderstorm",
        "towering cumulonimbus with heavy rain",
        WeatherParams {
            cloud_type: 1.0,
            density: 1.0,
            precipitation: 1.0,
            cloud_bottom_m: 1000.0,
            cloud_top_m: 9000.0,
            wind_speed_m_s: 14.0,
            ambient_bottom: DARK_BOTTOM,
            ambient_top: DARK_TOP,
            exposure: 1.2,
            convective_cells: 0.0,
            anvil: 1.0,
            ..fair(0.6)
        },
    ),
    state(
        "fog",
        "fog at the ground (visibility about 300 m) under a grey deck",
        WeatherParams {
            cloud_type: 0.2,
            cloud_bottom_m: 1200.0,
            cloud_top_m: 2400.0,
            wind_speed_m_s: 2.0,
            fog_top_m: 1000.0,
            fog_density: fog_density_for_visibility(300.0),
            ambient_bottom: GREY_BOTTOM,
            ambient_top: GREY_TOP,
            exposure: 1.2,
            convective_cells: 0.0,
            ..fair(0.7)
        },
    ),
    state(
        "mist",
        "mist (visibility about 3 km) under scattered cloud",
        WeatherParams {
            wind_speed_m_s: 3.0,
            fog_top_m: 1000.0,
            fog_density: fog_density_for_visibility(3000.0),
            ambient_bottom: GREY_BOTTOM,
            exposure: 1.1,
            ..fair(0.61)
        },
    ),
    state(
        "snow",
        "a snowing stratus deck: even, bright grey",
        WeatherParams {
            cloud_type: 0.1,
            precipitation: 0.5,
            cloud_bottom_m: 700.0,
            cloud_top_m: 2800.0,
            wind_speed_m_s: 6.0,
            ambient_bottom: [0.3, 0.32, 0.36],
            ambient_top: [0.6, 0.64, 0.7],
            exposure: 1.2,
            convective_cells: 0.0,
            ..fair(0.9)
        },
    ),
];

/// The cloud scattering coefficient the states assume (`lighting.scattering` of the presets),
/// 1/m at density 1.
pub const SCATTERING_PER_M: f64 = 0.04;

/// Koschmieder's relation (visibility = 3.912 / extinction, for a 2% contrast threshold)
/// solved for the density multiplier of a fog layer with the presets' scattering coefficient.
/// The stratus profile peaks at 1, so this is the densest part of the fog.
pub const fn fog_density_for_visibility(visibility_m: f64) -> f64 {
    3.912 / (visibility_m * SCATTERING_PER_M)
}

/// Measured: the fraction of the sky a single cumulus layer covers, seen straight down from
/// 30 km over a 120-degree view (about 100 km across), at coverage 0.0, 0.1, ..., 1.0.
/// Command: `stratus render --backend cpu` of `cumulus-noon` with `camera.position = [0,
/// 30000, 0]`, `pitch_deg = -90`, counting pixels that differ from the clear ground.
const COVER_FRACTION: [f64; 11] = [
    0.0, 0.0, 0.057, 0.226, 0.396, 0.586, 0.769, 0.937, 0.999, 1.0, 1.0,
];

/// Measured: the fraction of the ground a cumulus layer on convective cells
/// (`clouds.convective_cells = 1`) hides, seen straight down, at coverage 0.0, 0.1, ..., 1.0.
/// Command (100 km at 1024 px): `stratus measure-field --extent-m 100000 --size 1024` of the default scene
/// (`cumulus-noon`) with `clouds.convective_cells = 1` and each coverage (a pixel is cloud
/// where the transmittance is below 0.5). The crate's test
/// `the_cell_cover_curve_is_what_the_renderer_draws` (crates/cli/tests) re-measures it.
pub const CELL_COVER_FRACTION: [f64; 11] = [
    0.0, 0.0, 0.03, 0.113, 0.213, 0.317, 0.424, 0.531, 0.633, 0.709, 0.763,
];

/// The coverage whose layer covers `fraction` of the sky (the inverse of the measured
/// [`COVER_FRACTION`] curve, linear between its points).
pub fn coverage_for_fraction(fraction: f64) -> f64 {
    invert_cover(&COVER_FRACTION, fraction)
}

/// The coverage whose cumulus layer on convective cells covers `fraction` of the sky (the
/// inverse of the measured [`CELL_COVER_FRACTION`] curve, linear between its points; 1 above
/// its last point).
pub fn cell_coverage_for_fraction(fraction: f64) -> f64 {
    let f = fraction.clamp(0.0, 1.0);
    if f >= CELL_COVER_FRACTION[10] {
        return 1.0;
    }
    invert_cover(&CELL_COVER_FRACTION, f)
}

/// The coverage at which a measured cover `curve` (at coverage 0.0, 0.1, ..., 1.0) reaches
/// `fraction`, linear between its points; 0.85 where the curve never reaches it.
fn invert_cover(curve: &[f64; 11], fraction: f64) -> f64 {
    let f = fraction.clamp(0.0, 1.0);
    if f <= 0.0 {
        return 0.0;
    }
    for i in 1..curve.len() {
        let (a, b) = (curve[i - 1], curve[i]);
        if f <= b && b > a {
            let c0 = (i - 1) as f64 / 10.0;
            return c0 + 0.1 * (f - a) / (b - a);
        }
    }
    // Full cover: the first coverage that closes the layer, with margin for thinner types.
    0.85
}

/// The state named `name`.
pub fn find(name: &str) -> Result<&'static WeatherState, WeatherError> {
    STATES
        .iter()
        .find(|s| s.name == name)
        .ok_or_else(|| WeatherError::UnknownState {
            name: name.to_owned(),
            known: STATES.iter().map(|s| s.name).collect::<Vec<_>>().join(", "),
        })
}

fn lerp(a: f64, b: f64, t: f64) -> f64 {
    a + (b - a) * t
}

/// `smoothstep(0, 1, x)`: the transition's easing (seed 001: transitions between weather
/// states are smoothstep-eased).
pub fn smoothstep(x: f64) -> f64 {
    let x = x.clamp(0.0, 1.0);
    x * x * (3.0 - 2.0 * x)
}

impl WeatherParams {
    /// `self` blended toward `other` by `t` in [0, 1] (0: `self`), every field linearly. Fog
    /// blends its coverage, not its density: fog that clears thins out over the whole layer.
    pub fn mix(&self, other: &WeatherParams, t: f64) -> WeatherParams {
        let t = t.clamp(0.0, 1.0);
        let l = |a: f64, b: f64| lerp(a, b, t);
        let l3 = |a: [f64; 3], b: [f64; 3]| [0, 1, 2].map(|i| lerp(a[i], b[i], t));
        WeatherParams {
            coverage: l(self.coverage, other.coverage),
            cloud_type: l(self.cloud_type, other.cloud_type),
            density: l(self.density, other.density),
            precipitation: l(self.precipitation, other.precipitation),
            cloud_bottom_m: l(self.cloud_bottom_m, other.cloud_bottom_m),
            cloud_top_m: l(self.cloud_top_m, other.cloud_top_m),
            wind_speed_m_s: l(self.wind_speed_m_s, other.wind_speed_m_s),
            fog_top_m: self.fog_top_m.max(other.fog_top_m),
            fog_density: l(self.fog_density, other.fog_density),
            ambient_bottom: l3(self.ambient_bottom, other.ambient_bottom),
            ambient_top: l3(self.ambient_top, other.ambient_top),
            exposure: l(self.exposure, other.exposure),
            convective_cells: l(self.convective_cells, other.convective_cells),
            anvil: l(self.anvil, other.anvil),
        }
    }

    /// The parameters `t_s` seconds into a transition of `duration_s` seconds from `from` to
    /// `to`, smoothstep-eased; before 0 `from`, after the end `to`.
    pub fn transition(from: &WeatherParams, to: &WeatherParams, t_s: f64, duration_s: f64) -> Self {
        let x = if duration_s > 0.0 {
            t_s / duration_s
        } else {
            1.0
        };
        from.mix(to, smoothstep(x))
    }

    /// Distance in metres the wind has carried the clouds `t_s` seconds into a transition
    /// from `from` to `to` lasting `duration_s`: the integral of the eased wind speed, so the
    /// clouds move on smoothly while the speed changes. `smoothstep` integrates to
    /// `x^3 - x^4 / 2`.
    pub fn wind_distance(
        from: &WeatherParams,
        to: &WeatherParams,
        t_s: f64,
        duration_s: f64,
    ) -> f64 {
        let (a, b) = (from.wind_speed_m_s, to.wind_speed_m_s);
        if t_s <= 0.0 {
            return a * t_s;
        }
        if duration_s <= 0.0 {
            return b * t_s;
        }
        let x = (t_s / duration_s).min(1.0);
        let eased = a * x * duration_s + (b - a) * duration_s * (x * x * x - 0.5 * x * x * x * x);
        eased + b * (t_s - duration_s).max(0.0)
    }

    /// Writes these parameters into `scene`: the main layer, wind speed, ambient and
    /// exposure, and the fog layer (as the first extra layer, replacing any extra layers).
    pub fn apply(&self, scene: &mut Scene) {
        let c = &mut scene.clouds;
        c.coverage = self.coverage;
        c.cloud_type = self.cloud_type;
        c.density = self.density;
        c.precipitation = self.precipitation;
        c.wind_speed_m_s = self.wind_speed_m_s;
        c.layers.clear();
        scene.atmosphere.cloud_bottom_m = self.cloud_bottom_m;
        scene.atmosphere.cloud_top_m = self.cloud_top_m;
        scene.lighting.ambient_bottom = self.ambient_bottom;
        scene.lighting.ambient_top = self.ambient_top;
        scene.camera.exposure = self.exposure;
        scene.clouds.convective_cells = self.convective_cells;
        scene.clouds.anvil = self.anvil;
        // The states' decks are the shape noise's water cloud, whatever the scene they are
        // applied to was.
        scene.clouds.cirrus = 0.0;
        scene.clouds.cellular = 0.0;
        if self.fog_density > 0.0 && self.fog_top_m > 0.0 {
            scene
                .clouds
                .layers
                .push(fog_layer(self.fog_top_m, self.fog_density));
        }
    }
}

/// A ground fog layer: stratus from the ground to `top_m` (the stratus profile fills its
/// lowest third) with full coverage.
pub fn fog_layer(top_m: f64, density: f64) -> CloudLayer {
    CloudLayer {
        bottom_m: 0.0,
        top_m,
        coverage: 1.0,
        density,
        cloud_type: 0.0,
        precipitation: 0.0,
        cirrus: 0.0,
        cellular: 0.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_state_gives_a_valid_scene() {
        for s in &STATES {
            let mut scene = Scene::default();
            s.params.apply(&mut scene);
            scene
                .validate()
                .unwrap_or_else(|e| panic!("state {}: {e}", s.name));
        }
    }

    #[test]
    fn transitions_start_end_and_ease() {
        let (a, b) = (
            &find("clear").unwrap().params,
            &find("rain").unwrap().params,
        );
        assert_eq!(WeatherParams::transition(a, b, -1.0, 10.0), *a);
        assert_eq!(WeatherParams::transition(a, b, 0.0, 10.0), *a);
        assert_eq!(WeatherParams::transition(a, b, 10.0, 10.0), *b);
        let mid = WeatherParams::transition(a, b, 5.0, 10.0);
        assert!((mid.coverage - (a.coverage + b.coverage) / 2.0).abs() < 1e-12);
        // Eased: a tenth of the time covers less than a tenth of the way.
        let early = WeatherParams::transition(a, b, 1.0, 10.0);
        assert!(early.coverage - a.coverage < 0.1 * (b.coverage - a.coverage));
    }

    #[test]
    fn the_wind_distance_integrates_the_eased_speed() {
        let (a, b) = (
            &find("clear").unwrap().params,
            &find("thunderstorm").unwrap().params,
        );
        let (duration, n) = (60.0, 60_000);
        let dt = duration / n as f64;
        let numeric: f64 = (0..n)
            .map(|i| {
                WeatherParams::transition(a, b, (i as f64 + 0.5) * dt, duration).wind_speed_m_s * dt
            })
            .sum();
        let exact = WeatherParams::wind_distance(a, b, duration, duration);
        assert!(
            (numeric - exact).abs() < 1e-6 * exact,
            "{numeric} vs {exact}"
        );
        assert_eq!(
            WeatherParams::wind_distance(a, b, 70.0, 60.0),
            exact + 10.0 * b.wind_speed_m_s
        );
    }

    #[test]
    fn coverage_inverts_the_measured_curve() {
        assert_eq!(coverage_for_fraction(0.0), 0.0);
        assert!((coverage_for_fraction(0.396) - 0.4).abs() < 1e-9);
        let mut last = 0.0;
        for i in 1..=20 {
            let c = coverage_for_fraction(i as f64 / 20.0);
            assert!(c >= last && c <= 1.0, "{c}");
            last = c;
        }
    }

    /// The fair states stand on convective cells with the coverage that covers the middle
    /// of their cover class by the measured cell curve; the decks do not.
    #[test]
    fn fair_states_cover_their_oktas_on_cells() {
        for (name, oktas) in [("few", 1.5), ("scattered", 3.5), ("mist", 3.5)] {
            let p = find(name).unwrap().params;
            assert_eq!(p.convective_cells, 1.0, "{name}");
            let want = cell_coverage_for_fraction(oktas / 8.0);
            assert!(
                (p.coverage - want).abs() < 0.005,
                "{name}: {} against {want}",
                p.coverage
            );
        }
        for name in ["broken", "overcast", "rain", "thunderstorm", "fog", "snow"] {
            assert_eq!(find(name).unwrap().params.convective_cells, 0.0, "{name}");
        }
        assert_eq!(cell_coverage_for_fraction(0.0), 0.0);
        assert_eq!(cell_coverage_for_fraction(0.9), 1.0);
        for i in 0..=16 {
            let f = f64::from(i) / 20.0;
            let c = cell_coverage_for_fraction(f);
            assert!(c >= cell_coverage_for_fraction((f - 0.05).max(0.0)), "{f}");
        }
    }

    #[test]
    fn unknown_states_are_named_with_the_known_ones() {
        let e = find("sunny").unwrap_err().to_string();
        assert!(e.contains("sunny") && e.contains("thunderstorm"), "{e}");
    }
}
