//! The CPU twin of `density.wgsl`: the cloud density field (thesis alg. 4.1 with HZD's noise,
//! weather and cloud types), in f64 over the same 8-bit texels.
//!
//! The WGSL's feature switches (`DETAIL`, `CURL`) are not needed here: the frame plan always
//! picks a variant whose switches are on for every feature the scene uses, and a feature the
//! scene does not use has a zero strength, for which the switched-on code computes the same value
//! (a curl displacement times 0, a detail branch skipped by `strength > 0`).

use stratus_noise::{NoiseSet, Texture2};

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

// WGSL: density.wgsl::Layer
/// One cloud layer: its altitudes and weather. Layer 0 is the main layer (`atmosphere`,
/// `clouds`), layers 1-3 the extra ones.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Layer {
    pub bottom: f64,
    pub top: f64,
    pub coverage: f64,
    pub density: f64,
    pub cloud_type: f64,
    pub precipitation: f64,
    pub weather_offset: [f64; 2],
    /// The cirrus share ([`cirrus_density`]), 0 for water cloud.
    pub cirrus: f64,
    /// The cellular share ([`cellular_base`]), 0 for the shape noise's clouds.
    pub cellular: f64,
}

// WGSL: density.wgsl::MAX_LAYERS
const MAX_LAYERS: u32 = 4;

// WGSL: density.wgsl::layer_count
pub(crate) fn layer_count(f: &Frame) -> u32 {
    1 + f.extra_layers.min(MAX_LAYERS - 1)
}

// WGSL: density.wgsl::cloud_layer
pub(crate) fn cloud_layer(f: &Frame, i: u32) -> Layer {
    match i {
        1 => Layer {
            bottom: f.layer1_bottom,
            top: f.layer1_top,
            coverage: f.layer1_coverage,
            density: f.layer1_density,
            cloud_type: f.layer1_cloud_type,
            precipitation: f.layer1_precipitation,
            weather_offset: f.layer1_weather_offset,
            cirrus: f.layer1_cirrus,
            cellular: f.layer1_cellular,
        },
        2 => Layer {
            bottom: f.layer2_bottom,
            top: f.layer2_top,
            coverage: f.layer2_coverage,
            density: f.layer2_density,
            cloud_type: f.layer2_cloud_type,
            precipitation: f.layer2_precipitation,
            weather_offset: f.layer2_weather_offset,
            cirrus: f.layer2_cirrus,
            cellular: f.layer2_cellular,
        },
        3 => Layer {
            bottom: f.layer3_bottom,
            top: f.layer3_top,
            coverage: f.layer3_coverage,
            density: f.layer3_density,
            cloud_type: f.layer3_cloud_type,
            precipitation: f.layer3_precipitation,
            weather_offset: f.layer3_weather_offset,
            cirrus: f.layer3_cirrus,
            cellular: f.layer3_cellular,
        },
        _ => Layer {
            bottom: f.cloud_bottom,
            top: f.cloud_top,
            coverage: f.coverage,
            density: f.density,
            cloud_type: f.cloud_type,
            precipitation: f.precipitation,
            weather_offset: f.weather_offset,
            cirrus: f.cirrus,
            cellular: f.cellular,
        },
    }
}

/// Every layer of the frame, main first.
pub(crate) fn cloud_layers(f: &Frame) -> impl Iterator<Item = Layer> + '_ {
    (0..layer_count(f)).map(move |i| cloud_layer(f, i))
}

// WGSL: density.wgsl::layer_height
pub(crate) fn layer_height(l: &Layer, alt: f64) -> f64 {
    (alt - l.bottom) / (l.top - l.bottom)
}

// WGSL: density.wgsl::layer_at
/// The layer that holds altitude `alt`.
pub(crate) fn layer_at(f: &Frame, alt: f64) -> Option<Layer> {
    cloud_layers(f).find(|l| (0.0..=1.0).contains(&layer_height(l, alt)))
}

// WGSL: density.wgsl::layers_span
/// `(lowest bottom, highest top)` of the layers.
pub(crate) fn layers_span(f: &Frame) -> (f64, f64) {
    cloud_layers(f).fold((f.cloud_bottom, f.cloud_top), |(lo, hi), l| {
        (lo.min(l.bottom), hi.max(l.top))
    })
}

// WGSL: lighting.wgsl::height_fraction
/// Height fraction of `alt` in the layer that holds it (the main layer's if none does).
pub(crate) fn height_fraction(f: &Frame, alt: f64) -> f64 {
    let l = layer_at(f, alt).unwrap_or_else(|| cloud_layer(f, 0));
    saturate(layer_height(&l, alt))
}

// WGSL: density.wgsl::Weather
/// What the weather map says at a point, after its layer's controls.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Weather {
    pub coverage: f64,
    pub cloud_type: f64,
    pub precipitation: f64,
    /// The cloud's top here as a fraction of the layer (1 but on convective cells).
    pub top: f64,
}

// WGSL: density.wgsl::CELL_MESOSCALE, CELL_EDGE, CELL_EDGE_TOP, CELL_TOWER, CELL_BLUR_M
const CELL_MESOSCALE: f64 = 0.3;
const CELL_EDGE: f64 = 0.3;
const CELL_EDGE_TOP: f64 = 0.1;
const CELL_TOWER: f64 = 0.5;
const CELL_BLUR_M: f64 = 400.0;

// WGSL: density.wgsl::sample_weather
pub(crate) fn sample_weather(f: &Frame, noise: &NoiseSet, p: V3, l: &Layer) -> Weather {
    sample_weather_map(f, &noise.weather, p, l)
}

/// [`sample_weather`] from the weather map alone.
pub(crate) fn sample_weather_map(f: &Frame, map: &Texture2, p: V3, l: &Layer) -> Weather {
    let uv = [
        (p.x - l.weather_offset[0]) / f.weather_period,
        (p.z - l.weather_offset[1]) / f.weather_period,
    ];
    let w = sample2(map, uv);
    let mut coverage = saturate(w[0] + 2.0 * (l.coverage - 0.5));
    let cloud_type = saturate(l.cloud_type + (w[2] - 0.5) * 0.5);
    let mut top = 1.0;
    let cumulus = smoothstep(0.75, 1.0, l.cloud_type) * f.convective_cells;
    if cumulus > 0.0 {
        let share = saturate(l.coverage * (1.0 + CELL_MESOSCALE * (2.0 * w[0] - 1.0)));
        let inside = w[3] - (1.0 - share);
        coverage = mix(coverage, saturate(inside / CELL_EDGE), cumulus);
        let r = CELL_BLUR_M / f.weather_period;
        let tap = |du: f64, dv: f64| sample2(map, [uv[0] + du, uv[1] + dv])[3];
        let blurred = 0.2 * (w[3] + tap(r, 0.0) + tap(-r, 0.0) + tap(0.0, r) + tap(0.0, -r));
        let dome = saturate(inside.min(blurred - (1.0 - share)) / CELL_TOWER);
        top = mix(1.0, mix(CELL_EDGE_TOP, 1.0, dome), cumulus);
    }
    let precipitation = l.precipitation * saturate(0.5 + w[1]);
    Weather {
        coverage,
        cloud_type,
        precipitation,
        top,
    }
}

// WGSL: density.wgsl::regional_coverage
/// The share of the region about `p` that layer `l`'s clouds cover, which feeds their
/// multiply scattered light: the map's coverage, but on convective cells the cells' share
/// rather than their mask, and for a cellular layer the cloudlets' share (see the WGSL for
/// why).
pub(crate) fn regional_coverage(
    f: &Frame,
    map: &Texture2,
    p: V3,
    l: &Layer,
    weather: &Weather,
) -> f64 {
    let mut share = weather.coverage;
    let cumulus = smoothstep(0.75, 1.0, l.cloud_type) * f.convective_cells;
    if cumulus > 0.0 {
        let uv = [
            (p.x - l.weather_offset[0]) / f.weather_period,
            (p.z - l.weather_offset[1]) / f.weather_period,
        ];
        let r = sample2(map, uv)[0];
        let coverage = saturate(r + 2.0 * (l.coverage - 0.5));
        let cells = saturate(l.coverage * (1.0 + CELL_MESOSCALE * (2.0 * r - 1.0)));
        share = mix(coverage, cells, cumulus);
    }
    mix(share, (share * share).min(CELLULAR_SHARE), l.cellular)
}

// WGSL: density.wgsl::CELLULAR_SHARE
/// The most of a region a cellular layer's cloudlets cover (see the WGSL).
const CELLULAR_SHARE: f64 = 0.75;

/// The weather of a scene without a weather map (analytic media): the scene's global values.
pub(crate) fn uniform_weather(f: &Frame) -> Weather {
    Weather {
        coverage: 1.0,
        cloud_type: f.cloud_type,
        precipitation: f.precipitation,
        top: 1.0,
    }
}

// WGSL: density.wgsl::ANVIL_BASE, ANVIL_FULL, ANVIL_FALL, ANVIL_SPREAD_M, ANVIL_CORE,
// ANVIL_DEPTH_M
pub(crate) const ANVIL_BASE: f64 = 0.7;
pub(crate) const ANVIL_FULL: f64 = 0.8;
const ANVIL_FALL: f64 = 0.93;
const ANVIL_SPREAD_M: f64 = 4000.0;
const ANVIL_CORE: f64 = 0.85;
const ANVIL_DEPTH_M: [f64; 2] = [4000.0, 6000.0];

// WGSL: density.wgsl::anvil_weight
/// Layer `l`'s anvil weight: `clouds.anvil` on deep cumulonimbus, 0 elsewhere.
pub(crate) fn anvil_weight(f: &Frame, l: &Layer) -> f64 {
    f.anvil
        * smoothstep(0.75, 1.0, l.cloud_type)
        * smoothstep(ANVIL_DEPTH_M[0], ANVIL_DEPTH_M[1], l.top - l.bottom)
}

// WGSL: density.wgsl::anvil_cover
/// `(cover, profile)` of a cumulonimbus anvil at `p`, height fraction `h` in layer `l`: the
/// weather map dilated over the layer's top, moved downwind (see the WGSL for why); zeros
/// where there is none.
pub(crate) fn anvil_cover(f: &Frame, map: &Texture2, p: V3, h: f64, l: &Layer) -> (f64, f64) {
    let a = anvil_weight(f, l);
    if a <= 0.0 || h <= ANVIL_BASE {
        return (0.0, 0.0);
    }
    let rise = smoothstep(ANVIL_BASE, 1.0, h);
    let centre = [
        (p.x - f.anvil_shear[0] * rise - l.weather_offset[0]) / f.weather_period,
        (p.z - f.anvil_shear[1] * rise - l.weather_offset[1]) / f.weather_period,
    ];
    let r = ANVIL_SPREAD_M * rise / f.weather_period;
    let m = (0..6).fold(sample2(map, centre)[0], |m, k| {
        let angle = f64::from(k) * (std::f64::consts::PI / 3.0);
        let tap = [centre[0] + r * angle.cos(), centre[1] + r * angle.sin()];
        m.max(sample2(map, tap)[0])
    });
    let core = saturate((saturate(m + 2.0 * (l.coverage - 0.5)) - ANVIL_CORE) / (1.0 - ANVIL_CORE));
    let cover = core * a * smoothstep(ANVIL_BASE, ANVIL_FULL, h);
    (
        cover,
        a * gradient(h, ANVIL_BASE, ANVIL_FULL, ANVIL_FALL, 1.0),
    )
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

// WGSL: density.wgsl::cloud_top_fraction
/// The height fraction in layer `l` where the cloud's height profile ends under `weather`
/// (the layer's top for cirrus and cellular cloud).
pub(crate) fn cloud_top_fraction(f: &Frame, l: &Layer, weather: &Weather) -> f64 {
    let t = weather.cloud_type;
    let top = if f.height_model == HEIGHT_CLOUD_TYPES {
        mix(
            mix(0.25, 0.65, saturate(t * 2.0)),
            0.95,
            saturate(t * 2.0 - 1.0),
        )
    } else {
        mix(0.35, 1.0, t)
    };
    mix(top * weather.top, 1.0, l.cirrus.max(l.cellular))
}

// WGSL: density.wgsl::height_signal
pub(crate) fn height_signal(f: &Frame, h: f64, cloud_type: f64) -> f64 {
    if f.height_model == HEIGHT_CLOUD_TYPES {
        return height_cloud_types(h, cloud_type);
    }
    height_parabola(h, cloud_type)
}

// WGSL: density.wgsl::cloud_density
// Must agree with the WGSL step by step, including where `counters` are incremented (the
// density counter after the layer test, the detail counter inside the erosion branch).
/// Density in `[0, 1]` at world position `p` with altitude `alt`, in whichever layer holds it.
pub(crate) fn cloud_density(
    f: &Frame,
    noise: &NoiseSet,
    p: V3,
    alt: f64,
    counters: &mut Counters,
) -> f64 {
    match layer_at(f, alt) {
        Some(l) => layer_density(f, noise, p, alt, &l, counters),
        None => 0.0,
    }
}

// WGSL: density.wgsl::layer_density
/// Density in `[0, 1]` at world position `p` with altitude `alt` in layer `l` (0 outside it).
pub(crate) fn layer_density(
    f: &Frame,
    noise: &NoiseSet,
    p: V3,
    alt: f64,
    l: &Layer,
    counters: &mut Counters,
) -> f64 {
    layer_density_with(f, noise, p, alt, l, true, counters)
}

// WGSL: density.wgsl::layer_density_with
/// [`layer_density`], with the detail erosion only if `with_detail`.
pub(crate) fn layer_density_with(
    f: &Frame,
    noise: &NoiseSet,
    p: V3,
    alt: f64,
    l: &Layer,
    with_detail: bool,
    counters: &mut Counters,
) -> f64 {
    let h = layer_height(l, alt);
    if !(0.0..=1.0).contains(&h) {
        return 0.0;
    }
    counters.density += 1;
    let weather = sample_weather(f, noise, p, l);
    let mut ice = 0.0;
    if l.cirrus > 0.0 {
        ice = cirrus_density(f, noise, p, alt, h, l, &weather, counters);
        if l.cirrus >= 1.0 {
            return ice;
        }
    }
    mix(
        water_density(f, noise, (p, alt, h), l, &weather, with_detail, counters),
        ice,
        l.cirrus,
    )
}

// WGSL: density.wgsl::CIRRUS_STRETCH, CIRRUS_FALL_M, CIRRUS_FIBRE, CIRRUS_RIDGE,
// CIRRUS_BEND_M, CIRRUS_BEND_SCALE, CIRRUS_STRANDS, CIRRUS_SCALE, CIRRUS_FIBRE_STRETCH
const CIRRUS_STRETCH: f64 = 16.0;
const CIRRUS_FALL_M: f64 = 3000.0;
const CIRRUS_FIBRE: f64 = 0.95;
const CIRRUS_RIDGE: [f64; 2] = [0.55, 0.95];
const CIRRUS_BEND_M: f64 = 800.0;
const CIRRUS_BEND_SCALE: f64 = 4.0;
const CIRRUS_STRANDS: f64 = 0.5;
const CIRRUS_SCALE: f64 = 0.5;
const CIRRUS_FIBRE_STRETCH: f64 = 30.0;

// WGSL: density.wgsl::cirrus_density
// Must agree: the wind's frame, bent by the curl noise; the strands from the shape noise's
// ridges at CIRRUS_SCALE of its period, remapped by the coverage; the fibres from the detail
// noise's ridges; one detail evaluation counted.
/// Cirrus: fibres along the wind with fall streaks below their heads (see the WGSL for why).
#[allow(clippy::too_many_arguments)]
pub(crate) fn cirrus_density(
    f: &Frame,
    noise: &NoiseSet,
    p: V3,
    alt: f64,
    h: f64,
    l: &Layer,
    weather: &Weather,
    counters: &mut Counters,
) -> f64 {
    let signal = gradient(h, 0.0, 0.35, 0.75, 1.0);
    if weather.coverage <= 0.0 || signal <= 0.0 {
        return 0.0;
    }
    // The wind carries strands and fibres along itself by offsets wrapped by their own
    // periods along it (see the WGSL).
    let wind = f.wind_direction;
    let cuv = [
        (p.x - f.cirrus_bend_offset[0]) / (f.curl_period * CIRRUS_BEND_SCALE),
        (p.z - f.cirrus_bend_offset[1]) / (f.curl_period * CIRRUS_BEND_SCALE),
    ];
    let c = sample2(&noise.curl, cuv);
    let curl_x = c[0] * 2.0 - 1.0;
    let along = p.x * wind[0] + p.z * wind[1] + CIRRUS_FALL_M * (1.0 - h);
    let across = -p.x * wind[1] + p.z * wind[0] + CIRRUS_BEND_M * curl_x;

    let [dx, dy, _] = noise.shape.size;
    let period = [
        f.shape_period * CIRRUS_SCALE,
        f.shape_period * (f64::from(dy) / f64::from(dx)) * CIRRUS_SCALE,
        f.shape_period * CIRRUS_SCALE,
    ];
    let s = sample3(
        &noise.shape,
        [
            (along - f.cirrus_strand_offset) / CIRRUS_STRETCH / period[0],
            alt / period[1],
            across / period[2],
        ],
    );
    let low_fbm = s[1] * 0.625 + s[2] * 0.25 + s[3] * 0.125;
    let strand = (1.0 - (2.0 * s[0] - 1.0).abs()) * mix(1.0, low_fbm, CIRRUS_STRANDS);
    let base = saturate(remap(
        strand * signal,
        1.0 - weather.coverage,
        1.0,
        0.0,
        1.0,
    )) * weather.coverage;
    if base <= 0.0 {
        return 0.0;
    }

    counters.detail += 1;
    let dn = sample3(
        &noise.detail,
        [
            (along - f.cirrus_fibre_offset) / CIRRUS_FIBRE_STRETCH / f.detail_period,
            alt / f.detail_period,
            across / f.detail_period,
        ],
    );
    let ridge = 1.0 - (2.0 * (dn[0] * 0.625 + dn[1] * 0.25 + dn[2] * 0.125) - 1.0).abs();
    let fibre = smoothstep(CIRRUS_RIDGE[0], CIRRUS_RIDGE[1], ridge);
    saturate(base * mix(1.0, fibre, CIRRUS_FIBRE) * l.density)
}

// WGSL: density.wgsl::CELLULAR_ASPECT, CELLULAR_WORLEY, CELLULAR_RANGE, CELLULAR_GAP,
// CELLULAR_TOP, CELLULAR_SOFT
const CELLULAR_ASPECT: f64 = 2.016;
const CELLULAR_WORLEY: f64 = 4.0;
const CELLULAR_RANGE: [f64; 2] = [0.3, 0.75];
const CELLULAR_GAP: f64 = 0.15;
const CELLULAR_TOP: [f64; 2] = [0.35, 1.0];
const CELLULAR_SOFT: f64 = 0.1;

// WGSL: density.wgsl::cellular_base
/// The cellular cloudlets' base density at `p`, height fraction `h` of layer `l`, under the
/// weather's coverage (> 0): one domed cloudlet on each cell of the shape texture's Worley
/// FBM, read so that a cell is about CELLULAR_ASPECT times the layer's depth across (see the
/// WGSL for why).
pub(crate) fn cellular_base(
    f: &Frame,
    noise: &NoiseSet,
    (p, h): (V3, f64),
    l: &Layer,
    coverage: f64,
) -> f64 {
    let width = f.shape_period / CELLULAR_WORLEY;
    let k = (width / (CELLULAR_ASPECT * (l.top - l.bottom)))
        .log2()
        .round()
        .max(0.0)
        .exp2();
    let [dx, dy, _] = noise.shape.size;
    let period = f.shape_period / k;
    let wind = f.wind_direction;
    let along = (p.x * wind[0] + p.z * wind[1] - f.cellular_offset) / f.cellular_stretch;
    let across = -p.x * wind[1] + p.z * wind[0];
    let s = sample3(
        &noise.shape,
        [
            along / period,
            l.bottom / (period * (f64::from(dy) / f64::from(dx))),
            across / period,
        ],
    );
    let cell = saturate((s[1] - CELLULAR_RANGE[0]) / (CELLULAR_RANGE[1] - CELLULAR_RANGE[0]));
    let m = saturate(remap(
        cell,
        (1.0 - coverage).max(CELLULAR_GAP),
        1.0,
        0.0,
        1.0,
    ));
    let top = mix(CELLULAR_TOP[0], CELLULAR_TOP[1], m);
    let dome = saturate((top - h) / CELLULAR_SOFT) * saturate(h / CELLULAR_SOFT);
    m.sqrt() * dome * coverage
}

// WGSL: density.wgsl::water_density
/// The water clouds' density (the cumulus family) at `p` (altitude, height fraction) of
/// layer `l` under `weather`.
fn water_density(
    f: &Frame,
    noise: &NoiseSet,
    (p, alt, h): (V3, f64, f64),
    l: &Layer,
    weather: &Weather,
    with_detail: bool,
    counters: &mut Counters,
) -> f64 {
    let (anvil, profile) = anvil_cover(f, &noise.weather, p, h, l);
    let coverage = weather.coverage.max(anvil);
    let signal = height_signal(f, h / weather.top, weather.cloud_type).max(profile);
    // A cellular layer's cloudlets have their own height profile.
    if coverage <= 0.0 || (signal <= 0.0 && l.cellular <= 0.0) {
        return 0.0;
    }

    let mut base = 0.0;
    if l.cellular < 1.0 {
        // Base shape, isotropic texels: the y period is the x period times the texture's
        // aspect.
        let [dx, dy, _] = noise.shape.size;
        let period = [
            f.shape_period,
            f.shape_period * (f64::from(dy) / f64::from(dx)),
            f.shape_period,
        ];
        let shape_pos = [p.x - f.shape_offset[0], alt, p.z - f.shape_offset[1]];
        let s = sample3(
            &noise.shape,
            [
                shape_pos[0] / period[0],
                shape_pos[1] / period[1],
                shape_pos[2] / period[2],
            ],
        );
        let low_fbm = s[1] * 0.625 + s[2] * 0.25 + s[3] * 0.125;
        base = saturate(remap(s[0], low_fbm - 1.0, 1.0, 0.0, 1.0)) * signal;

        // Coverage (HZD).
        base = saturate(remap(base, 1.0 - coverage, 1.0, 0.0, 1.0)) * coverage;
    }
    // A cellular layer's cloudlets; a wholly cellular one reads no shape noise besides.
    if l.cellular > 0.0 {
        base = mix(
            base,
            cellular_base(f, noise, (p, h), l, coverage),
            l.cellular,
        );
    }
    if base <= 0.0 {
        return 0.0;
    }

    // Detail erosion at the edges only.
    let mut density = base;
    let strength = f.detail_strength;
    let threshold = f.erosion_threshold;
    if with_detail && strength > 0.0 && base < threshold {
        counters.detail += 1;
        let mut detail_pos = V3::new(p.x, alt, p.z);
        // CURL: always compiled in here (see the module comment).
        let cuv = [
            (p.x - f.curl_offset[0]) / f.curl_period,
            (p.z - f.curl_offset[1]) / f.curl_period,
        ];
        let c = sample2(&noise.curl, cuv);
        let curl = [c[0] * 2.0 - 1.0, c[1] * 2.0 - 1.0];
        detail_pos += V3::new(curl[0], 0.0, curl[1]) * (f.curl_strength * (1.0 - h));
        detail_pos = detail_pos - V3::new(f.detail_offset[0], 0.0, f.detail_offset[1]);
        let dn = sample3(
            &noise.detail,
            [
                detail_pos.x / f.detail_period,
                detail_pos.y / f.detail_period,
                detail_pos.z / f.detail_period,
            ],
        );
        let high_fbm = dn[0] * 0.625 + dn[1] * 0.25 + dn[2] * 0.125;
        // Must agree: the wispy-to-billowy ramp of the WGSL.
        let billowy = saturate(2.0 * f.wispy_billowy * saturate(h * 10.0));
        let shape = mix(1.0 - high_fbm, high_fbm, billowy);
        let erosion = strength * shape * (1.0 - base / threshold);
        density = saturate(remap(base, erosion, 1.0, 0.0, 1.0));

        // Close-range detail: the edges eroded again, finer, near the camera.
        let near = close_detail_weight(f, p, alt);
        if near > 0.0 && density > 0.0 && density < threshold {
            counters.detail += 1;
            let fine = CloseErosion {
                detail_pos,
                near,
                billowy,
                threshold,
            };
            density = close_erosion(f, noise, (p, h), &fine, density);
        }
    }

    density *= mix(1.0, h, f.height_gradient);
    density = density * l.density * (1.0 + weather.precipitation);
    density.clamp(0.0, 1.0)
}

// WGSL: density.wgsl::close_detail_weight
/// Close-range detail's weight at `p` (altitude `alt`): `close_detail`, full to half of its
/// range from the camera, none at it.
pub(crate) fn close_detail_weight(f: &Frame, p: V3, alt: f64) -> f64 {
    let s = f.close_detail;
    if s <= 0.0 {
        return 0.0;
    }
    let c = f.camera_position;
    let d = V3::new(p.x - c[0], alt - c[1], p.z - c[2]).length();
    let r = f.close_detail_range;
    s * (1.0 - smoothstep(0.5 * r, r, d))
}

/// The first erosion's part of a close-range erosion (density.wgsl close_erosion's
/// arguments): its lookup (curl and wind applied, m), the weight, the wispy-to-billowy blend
/// and the erosion threshold.
struct CloseErosion {
    detail_pos: V3,
    near: f64,
    billowy: f64,
    threshold: f64,
}

// WGSL: density.wgsl::close_erosion
/// `density` (below the threshold, after the first erosion) eroded by the detail noise read
/// `close_detail_scale` times finer.
fn close_erosion(
    f: &Frame,
    noise: &NoiseSet,
    (p, h): (V3, f64),
    e: &CloseErosion,
    density: f64,
) -> f64 {
    let k = f.close_detail_scale;
    // CURL: always compiled in here (see the module comment).
    let cuv = [
        (p.x - f.curl_offset[0]) * (k / f.curl_period),
        (p.z - f.curl_offset[1]) * (k / f.curl_period),
    ];
    let c = sample2(&noise.curl, cuv);
    let curl = [c[0] * 2.0 - 1.0, c[1] * 2.0 - 1.0];
    let pos = e.detail_pos + V3::new(curl[0], 0.0, curl[1]) * (f.curl_strength / k * (1.0 - h));
    let scale = k / f.detail_period;
    let dn = sample3(&noise.detail, [pos.x * scale, pos.y * scale, pos.z * scale]);
    let fbm = dn[0] * 0.625 + dn[1] * 0.25 + dn[2] * 0.125;
    let shape = mix(1.0 - fbm, fbm, e.billowy);
    let erosion = e.near * shape * (1.0 - density / e.threshold);
    saturate(remap(density, erosion, 1.0, 0.0, 1.0))
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

    /// A map of one tower (cover `tower` within 1.5 km of the origin, none elsewhere) under a
    /// storm layer 1-9 km with the wind toward +x; `anvil` and `shear` as given.
    fn storm(anvil: f64, shear: f64, tower: u8) -> (Frame, Texture2, Layer) {
        let mut scene = stratus_scene::Scene::default();
        scene.atmosphere.cloud_bottom_m = 1000.0;
        scene.atmosphere.cloud_top_m = 9000.0;
        scene.clouds.cloud_type = 1.0;
        scene.clouds.coverage = 0.5;
        scene.clouds.wind_direction_deg = 90.0;
        scene.clouds.anvil = anvil;
        scene.clouds.anvil_shear_m = shear;
        let f = Frame::from_uniforms(&scene.uniforms());
        // 64 texels over the 60 km period: about 940 m each.
        let n = 64u32;
        let texel_m = f.weather_period / f64::from(n);
        let mut data = vec![0u8; (n * n * 4) as usize];
        for y in 0..n {
            for x in 0..n {
                // Texel centres, wrapped so that the origin's neighbours on both sides count.
                let d = |i: u32| {
                    let c = (f64::from(i) + 0.5) * texel_m;
                    c.min(f.weather_period - c)
                };
                if d(x).hypot(d(y)) < 1500.0 {
                    data[((y * n + x) * 4) as usize] = tower;
                }
            }
        }
        let map = Texture2 { size: [n, n], data };
        let l = cloud_layer(&f, 0);
        (f, map, l)
    }

    /// The renderer's own noise textures, generated once for the tests that read them.
    fn noise() -> &'static stratus_noise::NoiseSet {
        static NOISE: std::sync::OnceLock<stratus_noise::NoiseSet> = std::sync::OnceLock::new();
        NOISE.get_or_init(|| stratus_noise::NoiseSet::generate(&Default::default()))
    }

    /// The mean absolute change of `scene`'s main layer's density over `step` metres along and
    /// across its wind, at altitude `alt` over a 24 km square, and its mean density.
    fn variation(scene: &stratus_scene::Scene, alt: f64, step: f64) -> (f64, f64, f64) {
        let f = Frame::from_uniforms(&scene.uniforms());
        let l = cloud_layer(&f, 0);
        let (sx, sz) = scene.clouds.wind_direction_deg.to_radians().sin_cos();
        let mut c = Counters::default();
        let mut at = |x: f64, z: f64| {
            layer_density_with(&f, noise(), V3::new(x, alt, z), alt, &l, true, &mut c)
        };
        let (mut along, mut across, mut mean, mut n) = (0.0, 0.0, 0.0, 0.0);
        for i in 0..60 {
            for j in 0..60 {
                let (x, z) = (f64::from(i) * 400.0 - 12e3, f64::from(j) * 400.0 - 12e3);
                let d = at(x, z);
                along += (at(x + sx * step, z + sz * step) - d).abs();
                across += (at(x + sz * step, z - sx * step) - d).abs();
                mean += d;
                n += 1.0;
            }
        }
        (along / n, across / n, mean / n)
    }

    /// [`variation`] of a high layer (wind toward `wind_deg`) with its cirrus share `cirrus`.
    fn cirrus_variation(wind_deg: f64, cirrus: f64, step: f64) -> (f64, f64, f64) {
        let mut scene = stratus_scene::Scene::default();
        scene.atmosphere.cloud_bottom_m = 8000.0;
        scene.atmosphere.cloud_top_m = 9500.0;
        scene.clouds.cloud_type = 0.0;
        scene.clouds.coverage = 0.6;
        scene.clouds.density = stratus_scene::DEFAULT_CIRRUS_DENSITY;
        scene.clouds.cirrus = cirrus;
        scene.clouds.wind_direction_deg = wind_deg;
        // The middle of the cirrus profile; the water cloud's stratus fills the bottom quarter.
        let alt = if cirrus > 0.0 { 8900.0 } else { 8200.0 };
        variation(&scene, alt, step)
    }

    /// Cirrus lies in fibres along the wind: its density changes over 100 m at least twice as
    /// fast across the wind as along it, whichever way the wind blows (measured 2.6-3.9 times
    /// with the fibres bent by CIRRUS_BEND_M 800; 4.1-5.9 at 400), while the same layer as
    /// water cloud (cirrus 0) changes alike both ways; and it is there at all.
    #[test]
    fn cirrus_fibres_lie_along_the_wind() {
        for wind in [90.0, 0.0, 30.0] {
            let (along, across, mean) = cirrus_variation(wind, 1.0, 100.0);
            eprintln!("wind {wind}: across / along {:.2}", across / along);
            assert!(mean > 1e-3, "wind {wind}: mean density {mean}");
            assert!(
                across > 2.0 * along,
                "wind {wind}: along {along}, across {across}"
            );
        }
        let (along, across, mean) = cirrus_variation(90.0, 0.0, 100.0);
        assert!(mean > 1e-3, "water cloud: mean density {mean}");
        assert!(
            across < 1.5 * along && along < 1.5 * across,
            "water cloud: along {along}, across {across}"
        );
    }

    /// How far `base`'s main layer (under a wind of 10 m/s toward 30 degrees) strays from
    /// being carried by the wind: the mean absolute difference, at altitude `alt` over a 20 km
    /// square, between the first frame and each of four later ones (1500-9000 s) moved back upwind, over
    /// the first frame's mean density (which is returned first).
    fn carried_change(base: &stratus_scene::Scene, alt: f64) -> (f64, Vec<f64>) {
        let noise = noise();
        let field = |time_s: f64| {
            let mut scene = base.clone();
            scene.clouds.wind_direction_deg = 30.0;
            scene.clouds.wind_speed_m_s = 10.0;
            scene.clouds.time_s = time_s;
            let f = Frame::from_uniforms(&scene.uniforms());
            let l = cloud_layer(&f, 0);
            let d = 10.0 * time_s;
            let (sx, sz) = 30f64.to_radians().sin_cos();
            let mut c = Counters::default();
            let mut out = Vec::new();
            for i in 0..40 {
                for j in 0..40 {
                    let (x, z) = (f64::from(i) * 500.0 - 10e3, f64::from(j) * 500.0 - 10e3);
                    let p = V3::new(x + sx * d, alt, z + sz * d);
                    out.push(layer_density_with(&f, noise, p, alt, &l, true, &mut c));
                }
            }
            out
        };
        let first = field(0.0);
        let n = first.len() as f64;
        let mean = first.iter().sum::<f64>() / n;
        let changes = [1500.0, 2500.0, 4000.0, 9000.0]
            .iter()
            .map(|&t| {
                let later = field(t);
                first
                    .iter()
                    .zip(&later)
                    .map(|(a, b)| (a - b).abs())
                    .sum::<f64>()
                    / n
                    / mean
            })
            .collect();
        (mean, changes)
    }

    /// The wind carries cirrus without a jump: hours on (1500, 2500, 4000 and 9000 s), the
    /// layer's density is the first frame's moved downwind, after the shape, detail and curl
    /// offsets have wrapped (the shape's per-axis wrap at 1108 s and 1920 s, the strands' own
    /// at 7680 s, the fibres' at 3600 s, the bends' at 2400 s). Read through the per-axis
    /// shape offset, the strands jumped at the first of those.
    #[test]
    fn the_wind_carries_cirrus_without_a_jump() {
        let mut scene = stratus_scene::Scene::default();
        scene.atmosphere.cloud_bottom_m = 8000.0;
        scene.atmosphere.cloud_top_m = 9500.0;
        scene.clouds.coverage = 0.6;
        scene.clouds.density = stratus_scene::DEFAULT_CIRRUS_DENSITY;
        scene.clouds.cirrus = 1.0;
        let (mean, changes) = carried_change(&scene, 8900.0);
        assert!(mean > 1e-3, "mean density {mean}");
        assert!(changes.iter().all(|&c| c < 1e-3), "{changes:?}");
    }

    /// The wind carries a cellular layer's cells, round or in rolls, without a jump: their
    /// read's offset wraps by whole periods of it.
    #[test]
    fn the_wind_carries_cells_and_rolls_without_a_jump() {
        for rolls in [0.0, 1.0] {
            let mut scene = stratocumulus(1000.0, 1500.0, 0.6, 1.0);
            scene.clouds.cell_rolls = rolls;
            let (mean, changes) = carried_change(&scene, 1200.0);
            assert!(mean > 1e-3, "rolls {rolls}: mean density {mean}");
            assert!(
                changes.iter().all(|&c| c < 1e-3),
                "rolls {rolls}: {changes:?}"
            );
        }
    }

    /// The default scene with its main layer a stratocumulus (type 0.5) at `bottom..top` m of
    /// coverage `coverage` and cellular share `cellular`.
    fn stratocumulus(bottom: f64, top: f64, coverage: f64, cellular: f64) -> stratus_scene::Scene {
        let mut scene = stratus_scene::Scene::default();
        scene.atmosphere.cloud_bottom_m = bottom;
        scene.atmosphere.cloud_top_m = top;
        scene.clouds.cloud_type = 0.5;
        scene.clouds.coverage = coverage;
        scene.clouds.cellular = cellular;
        scene
    }

    /// A 24 km square of layer `bottom..top` at coverage `coverage` (`cellular` its cellular
    /// share), seen at height fraction 0.3 on a 100 m grid: the number of separate clouds
    /// (4-connected runs of cells with density) and the share of the square they cover.
    fn cloudlets(bottom: f64, top: f64, coverage: f64, cellular: f64) -> (usize, f64) {
        let noise = noise();
        let scene = stratocumulus(bottom, top, coverage, cellular);
        let f = Frame::from_uniforms(&scene.uniforms());
        let l = cloud_layer(&f, 0);
        let alt = mix(bottom, top, 0.3);
        let n = 240;
        let mut c = Counters::default();
        let cloud: Vec<bool> = (0..n * n)
            .map(|k| {
                let (x, z) = ((k % n) as f64 * 100.0, (k / n) as f64 * 100.0);
                layer_density_with(&f, noise, V3::new(x, alt, z), alt, &l, true, &mut c) > 0.0
            })
            .collect();
        let mut seen = vec![false; n * n];
        let mut count = 0;
        for start in 0..n * n {
            if !cloud[start] || seen[start] {
                continue;
            }
            count += 1;
            let mut stack = vec![start];
            seen[start] = true;
            while let Some(k) = stack.pop() {
                let (i, j) = (k % n, k / n);
                let near = [
                    (i > 0).then(|| k - 1),
                    (i + 1 < n).then(|| k + 1),
                    (j > 0).then(|| k - n),
                    (j + 1 < n).then(|| k + n),
                ];
                for m in near.into_iter().flatten() {
                    if cloud[m] && !seen[m] {
                        seen[m] = true;
                        stack.push(m);
                    }
                }
            }
        }
        let share = cloud.iter().filter(|&&c| c).count() as f64 / (n * n) as f64;
        (count, share)
    }

    /// A cellular layer is a field of separate cloudlets where the same layer on the shape
    /// noise is a few large clouds (measured: 124 against 19 in a 24 km square, 500 m deep at
    /// coverage 0.6); its cells widen with the layer's depth (about CELLULAR_ASPECT times it:
    /// 31 cloudlets 1000 m deep); and where the map's coverage is full it keeps lanes between
    /// them (0.78 covered), where the shape noise's cloud closes into a deck.
    #[test]
    fn a_cellular_layer_is_a_field_of_cloudlets_as_wide_as_it_is_deep() {
        let (cells, _) = cloudlets(1000.0, 1500.0, 0.6, 1.0);
        let (blobs, _) = cloudlets(1000.0, 1500.0, 0.6, 0.0);
        eprintln!("500 m deep at coverage 0.6: {cells} cloudlets, {blobs} shape-noise clouds");
        assert!(
            cells > 100 && cells > 4 * blobs,
            "{cells} cloudlets, {blobs} clouds"
        );
        let (deep, _) = cloudlets(1000.0, 2000.0, 0.6, 1.0);
        eprintln!("1000 m deep: {deep} cloudlets");
        assert!((deep as f64) < 0.6 * cells as f64, "{deep} against {cells}");
        let (_, open) = cloudlets(1000.0, 1500.0, 1.0, 1.0);
        let (_, deck) = cloudlets(1000.0, 1500.0, 1.0, 0.0);
        eprintln!("coverage 1: cellular covers {open:.3}, the shape noise {deck:.3}");
        assert!(open < 0.95 && deck > 0.99, "{open} {deck}");
    }

    /// `cell_rolls` lines a cellular layer's cloudlets up along the wind: its density changes
    /// over 300 m at least twice as fast across the wind as along it (measured: 3.2-3.5),
    /// whichever way the wind blows, where round cells change about as fast both ways
    /// (1.03-1.08).
    #[test]
    fn cell_rolls_line_the_cloudlets_up_along_the_wind() {
        let ratio = |wind_deg: f64, rolls: f64| {
            let mut scene = stratocumulus(1000.0, 1500.0, 0.6, 1.0);
            scene.clouds.cell_rolls = rolls;
            scene.clouds.wind_direction_deg = wind_deg;
            let (along, across, _) = variation(&scene, 1150.0, 300.0);
            across / along
        };
        for wind in [90.0, 0.0, 30.0] {
            let rolls = ratio(wind, 1.0);
            let round = ratio(wind, 0.0);
            eprintln!("wind {wind}: across / along {rolls:.2} in rolls, {round:.2} round");
            assert!(rolls > 2.0, "wind {wind}: rolls {rolls}");
            assert!(round > 0.7 && round < 1.4, "wind {wind}: round {round}");
        }
    }

    #[test]
    fn an_anvil_spreads_a_towers_top_downwind_and_nothing_else() {
        let at = |x: f64, z: f64| V3::new(x, 0.0, z);
        let (f, map, l) = storm(1.0, 6000.0, 255);
        // Over the tower the anvil is full at the layer's top...
        let (cover, profile) = anvil_cover(&f, &map, at(0.0, 0.0), 0.85, &l);
        assert!(cover > 0.99 && profile > 0.99, "{cover} {profile}");
        // ...and none below its base, nor on a layer too shallow for one.
        assert_eq!(anvil_cover(&f, &map, at(0.0, 0.0), 0.6, &l), (0.0, 0.0));
        let shallow = Layer { top: 4000.0, ..l };
        assert_eq!(
            anvil_cover(&f, &map, at(0.0, 0.0), 0.85, &shallow),
            (0.0, 0.0)
        );
        // 6 km downwind of the tower, near the top, the plate is there; 6 km upwind it is not.
        let downwind = anvil_cover(&f, &map, at(6000.0, 0.0), 0.95, &l).0;
        let upwind = anvil_cover(&f, &map, at(-6000.0, 0.0), 0.95, &l).0;
        assert!(downwind > 0.9 && upwind == 0.0, "{downwind} {upwind}");
        // Without anvils nothing changes anywhere.
        let (f0, map0, l0) = storm(0.0, 6000.0, 255);
        for x in [-6000.0, 0.0, 6000.0] {
            assert_eq!(anvil_cover(&f0, &map0, at(x, 0.0), 0.95, &l0), (0.0, 0.0));
        }
        // Only the map's cores spread (cover above ANVIL_CORE, as in the WGSL): a tower of
        // cover 0.8 gets none.
        let (f8, map8, l8) = storm(1.0, 6000.0, 204);
        assert_eq!(anvil_cover(&f8, &map8, at(0.0, 0.0), 0.95, &l8).0, 0.0);
    }

    /// A 3 km square at 2700 m about a camera at its middle (inside a cumulus's fringe), 25 m
    /// apart: each point's distance from the camera, its density with close-range detail off
    /// and on (strength 1, the default scale and range), and the density 40 m east of it off
    /// and on.
    fn close_samples() -> Vec<(f64, [f64; 4])> {
        let noise = noise();
        let alt = 2700.0;
        let camera = [0.0, alt, -11750.0];
        let frame = |close: f64| {
            let mut scene = stratus_scene::Scene::default();
            // scenes/close-detail.toml: the fringe of one of the weather map's clouds.
            scene.clouds.convective_cells = 0.0;
            scene.camera.position = camera;
            scene.clouds.close_detail = close;
            Frame::from_uniforms(&scene.uniforms())
        };
        let (off, on) = (frame(0.0), frame(1.0));
        let (lo, l1) = (cloud_layer(&off, 0), cloud_layer(&on, 0));
        let mut c = Counters::default();
        let mut out = Vec::new();
        for i in 0..120 {
            for j in 0..120 {
                let (x, z) = (
                    camera[0] + f64::from(i) * 25.0 - 1500.0,
                    camera[2] + f64::from(j) * 25.0 - 1500.0,
                );
                let p = V3::new(x, alt, z);
                let d = V3::new(x - camera[0], 0.0, z - camera[2]).length();
                let q = p + V3::new(40.0, 0.0, 0.0);
                out.push((
                    d,
                    [
                        layer_density(&off, noise, p, alt, &lo, &mut c),
                        layer_density(&on, noise, p, alt, &l1, &mut c),
                        layer_density(&off, noise, q, alt, &lo, &mut c),
                        layer_density(&on, noise, q, alt, &l1, &mut c),
                    ],
                ));
            }
        }
        out
    }

    /// Close-range detail only takes density away (the path tracer's majorant holds), leaves
    /// every point beyond its range and every core as it was, and near the camera erodes the
    /// clouds' fringe: within half its range the fringe (density below the erosion threshold)
    /// loses density and varies over 40 m more than it did.
    #[test]
    fn close_detail_erodes_the_fringe_near_the_camera_alone() {
        let samples = close_samples();
        let range = stratus_scene::DEFAULT_CLOSE_DETAIL_RANGE_M;
        let threshold = stratus_scene::Clouds::default().erosion_threshold;
        assert!(samples.iter().all(|(_, d)| d[1] <= d[0] + 1e-12));
        assert!(
            samples
                .iter()
                .filter(|s| s.0 > range)
                .all(|(_, d)| d[0] == d[1])
        );
        let near: Vec<_> = samples.iter().filter(|s| s.0 < 0.5 * range).collect();
        assert!(
            near.iter()
                .filter(|s| s.1[0] >= threshold)
                .all(|(_, d)| d[0] == d[1])
        );
        let fringe: Vec<_> = near
            .iter()
            .filter(|s| s.1[0] > 0.0 && s.1[0] < threshold)
            .map(|s| s.1)
            .collect();
        let n = fringe.len() as f64;
        let mean = |k: usize| fringe.iter().map(|d| d[k]).sum::<f64>() / n;
        let change =
            |a: usize, b: usize| fringe.iter().map(|d| (d[b] - d[a]).abs()).sum::<f64>() / n;
        let (off, on) = (mean(0), mean(1));
        let (var_off, var_on) = (change(0, 2), change(1, 3));
        eprintln!(
            "fringe points {n}: mean density {off:.4} -> {on:.4}, mean change over 40 m {var_off:.4} -> {var_on:.4}"
        );
        // Measured: 1245 points, mean 0.236 -> 0.178, change over 40 m 0.0057 -> 0.0122.
        assert!(n > 500.0, "{n} fringe points");
        assert!(on < 0.85 * off, "{off} -> {on}");
        assert!(var_on > 1.6 * var_off, "{var_off} -> {var_on}");
    }

    /// A cloud's top in its layer: the parabola's for water cloud (a stratus's at 0.35, a
    /// cumulus's at 1), a convective cell's share of it, the cloud-type gradients' under that
    /// model, and the layer's top for cirrus and cellular cloud, whose profiles are their own.
    #[test]
    fn the_cloud_top_follows_the_height_profile() {
        let f = Frame::from_uniforms(&stratus_scene::Scene::default().uniforms());
        let mut l = cloud_layer(&f, 0);
        let w = |cloud_type: f64, top: f64| Weather {
            coverage: 1.0,
            cloud_type,
            precipitation: 0.0,
            top,
        };
        assert!((cloud_top_fraction(&f, &l, &w(0.0, 1.0)) - 0.35).abs() < 1e-12);
        assert!((cloud_top_fraction(&f, &l, &w(1.0, 1.0)) - 1.0).abs() < 1e-12);
        assert!((cloud_top_fraction(&f, &l, &w(1.0, 0.4)) - 0.4).abs() < 1e-12);
        let mut types = f.clone();
        types.height_model = HEIGHT_CLOUD_TYPES;
        assert!((cloud_top_fraction(&types, &l, &w(0.0, 1.0)) - 0.25).abs() < 1e-12);
        assert!((cloud_top_fraction(&types, &l, &w(0.5, 1.0)) - 0.65).abs() < 1e-12);
        l.cirrus = 1.0;
        assert_eq!(cloud_top_fraction(&f, &l, &w(0.0, 1.0)), 1.0);
    }

    /// The wind carries close-range detail without a jump: its reads are whole periods of the
    /// detail noise's and the curl noise's, whose offsets wrap by their own periods (its range
    /// here covers the square, so the camera's place does not matter).
    #[test]
    fn the_wind_carries_close_detail_without_a_jump() {
        let mut scene = stratus_scene::Scene::default();
        scene.clouds.close_detail = 1.0;
        scene.clouds.close_detail_range_m = 1e7;
        let (mean, changes) = carried_change(&scene, 2700.0);
        assert!(mean > 1e-3, "mean density {mean}");
        assert!(changes.iter().all(|&c| c < 1e-3), "{changes:?}");
    }
}
