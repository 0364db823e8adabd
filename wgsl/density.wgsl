// The cloud density field (thesis alg. 4.1 with HZD's noise, weather and cloud types).
//
// Positions are in metres: `p` is the world position (x, z horizontal) used for texture
// lookups, `alt` its altitude above the ground. Textures tile; wind offsets arrive already
// wrapped by each texture's period, so hours of animation lose no precision.

@group(0) @binding(1) var shape_tex: texture_3d<f32>;   // RGBA8: Perlin-Worley, Worley FBM x3
@group(0) @binding(2) var detail_tex: texture_3d<f32>;  // RGBA8: Worley FBM x3
@group(0) @binding(3) var weather_tex: texture_2d<f32>; // RGBA8: coverage, precipitation, cloud type, cells
@group(0) @binding(4) var curl_tex: texture_2d<f32>;    // RGBA8: curl xy encoded as 0.5 v + 0.5
@group(0) @binding(5) var noise_sampler: sampler;       // linear, repeat

// Work counters of one invocation, added to the statistics buffer once at the end.
struct Counters {
    view_steps: u32,
    density: u32,
    detail: u32,
    light: u32,
}

// One cloud layer: its altitude range and its weather. Layer 0 is the scene's main layer
// (`cloud_bottom`, `coverage`...), layers 1-3 are the extra ones (`layer1_*`..`layer3_*`). Layers never
// overlap in altitude (the scene is validated so), so a point lies in at most one.
struct Layer {
    bottom: f32,
    top: f32,
    coverage: f32,
    density: f32,
    cloud_type: f32,
    precipitation: f32,
    weather_offset: vec2<f32>, // where the layer reads the weather map (wind and its own shift)
    cirrus: f32,               // the cirrus share (cirrus_density), 0 for water cloud
    cellular: f32,             // the cellular share (cellular_base), 0 for the shape noise's
}

const MAX_LAYERS: u32 = 4u;
const NO_LAYER: u32 = 4u;

fn layer_count() -> u32 {
    return 1u + min(frame.extra_layers, MAX_LAYERS - 1u);
}

fn cloud_layer(i: u32) -> Layer {
    if i == 1u {
        return Layer(frame.layer1_bottom, frame.layer1_top, frame.layer1_coverage,
                     frame.layer1_density, frame.layer1_cloud_type, frame.layer1_precipitation,
                     frame.layer1_weather_offset, frame.layer1_cirrus,
                     frame.layer1_cellular);
    } else if i == 2u {
        return Layer(frame.layer2_bottom, frame.layer2_top, frame.layer2_coverage,
                     frame.layer2_density, frame.layer2_cloud_type, frame.layer2_precipitation,
                     frame.layer2_weather_offset, frame.layer2_cirrus,
                     frame.layer2_cellular);
    } else if i == 3u {
        return Layer(frame.layer3_bottom, frame.layer3_top, frame.layer3_coverage,
                     frame.layer3_density, frame.layer3_cloud_type, frame.layer3_precipitation,
                     frame.layer3_weather_offset, frame.layer3_cirrus,
                     frame.layer3_cellular);
    }
    return Layer(frame.cloud_bottom, frame.cloud_top, frame.coverage, frame.density,
                 frame.cloud_type, frame.precipitation, frame.weather_offset, frame.cirrus,
                 frame.cellular);
}

// Height fraction of altitude `alt` in layer `l` (inside where it lies in [0, 1]).
fn layer_height(l: Layer, alt: f32) -> f32 {
    return (alt - l.bottom) / (l.top - l.bottom);
}

// The layer that holds altitude `alt`, or NO_LAYER.
fn layer_at(alt: f32) -> u32 {
    for (var i = 0u; i < layer_count(); i++) {
        let h = layer_height(cloud_layer(i), alt);
        if h >= 0.0 && h <= 1.0 {
            return i;
        }
    }
    return NO_LAYER;
}

// The altitudes that hold every layer: (lowest bottom, highest top).
fn layers_span() -> vec2<f32> {
    var span = vec2<f32>(frame.cloud_bottom, frame.cloud_top);
    for (var i = 1u; i < layer_count(); i++) {
        let l = cloud_layer(i);
        span = vec2<f32>(min(span.x, l.bottom), max(span.y, l.top));
    }
    return span;
}

// What the weather map says at a point of layer `l`, after its controls.
struct Weather {
    coverage: f32,
    cloud_type: f32,
    precipitation: f32,
    top: f32, // the cloud's top here as a fraction of the layer (1 but on convective cells)
}

// Convective cells (`clouds.convective_cells`, the map's A channel), for cumulus layers (type
// 0.75 and up, fully at 1): how much the map's coverage scales a layer's local share of cloud
// (mesoscale variation: by up to 1 +- CELL_MESOSCALE); the span of the cell field's rank over
// which a cell's coverage rises from clear to full, wide so that the shape noise carves the
// cell's edge in three dimensions, as a smooth coverage does in HZD's map; and its dome: the
// cloud's top rises linearly from CELL_EDGE_TOP of the layer at the cell's edge to the whole
// layer CELL_TOWER (in rank) inside it, after the lesser of the field and the field smoothed
// over CELL_BLUR_M, so that the larger a cell, the taller its cloud (small humilis, large
// congestus). Tried: a top following the rough field drew spiky cones, its square root
// columns with flat tops; a narrow edge (0.06) drew vertical walls where the rough field
// crosses its threshold.
const CELL_MESOSCALE: f32 = 0.3;
const CELL_EDGE: f32 = 0.3;
const CELL_EDGE_TOP: f32 = 0.1;
const CELL_TOWER: f32 = 0.5;
const CELL_BLUR_M: f32 = 400.0;

fn sample_weather(p: vec3<f32>, l: Layer) -> Weather {
    let uv = (p.xz - l.weather_offset) / frame.weather_period;
    let w = textureSampleLevel(weather_tex, noise_sampler, uv, 0.0);
    // The layer's coverage shifts the map's local coverage: 0 clears the sky, 1 fills it.
    var coverage = saturate(w.r + 2.0 * (l.coverage - 0.5));
    // The layer's cloud type is the mean; the map varies it locally (HZD: B = cloud type).
    let cloud_type = saturate(l.cloud_type + (w.b - 0.5) * 0.5);
    var top = 1.0;
    // Cumulus layers only (the layer's own type: a deck of another type beside them keeps
    // the map's coverage however its local type varies).
    let cumulus = smoothstep(0.75, 1.0, l.cloud_type) * frame.convective_cells;
    if cumulus > 0.0 {
        // Cumulus stands where the cell field's rank is in the top `share` of the map: the
        // layer's coverage, scaled up or down by the map's (none at coverage 0).
        let share = saturate(l.coverage * (1.0 + CELL_MESOSCALE * (2.0 * w.r - 1.0)));
        let inside = w.a - (1.0 - share);
        coverage = mix(coverage, saturate(inside / CELL_EDGE), cumulus);
        // The dome follows the field smoothed over CELL_BLUR_M (four taps about the point):
        // the rough field's own peaks would stand as spikes.
        let r = CELL_BLUR_M / frame.weather_period;
        let blurred = 0.2 * (w.a
            + textureSampleLevel(weather_tex, noise_sampler, uv + vec2<f32>(r, 0.0), 0.0).a
            + textureSampleLevel(weather_tex, noise_sampler, uv - vec2<f32>(r, 0.0), 0.0).a
            + textureSampleLevel(weather_tex, noise_sampler, uv + vec2<f32>(0.0, r), 0.0).a
            + textureSampleLevel(weather_tex, noise_sampler, uv - vec2<f32>(0.0, r), 0.0).a);
        let dome = saturate(min(inside, blurred - (1.0 - share)) / CELL_TOWER);
        top = mix(1.0, mix(CELL_EDGE_TOP, 1.0, dome), cumulus);
    }
    let precipitation = l.precipitation * saturate(0.5 + w.g);
    return Weather(coverage, cloud_type, precipitation, top);
}

// The share of the region about `p` that layer `l`'s clouds cover, which feeds their multiply
// scattered light (lighting.wgsl `sun_scattering`): the weather map's coverage, but on
// convective cells the cells' share rather than their mask, which is 1 inside every cumulus.
// Fed the mask, fair cumulus were lit as decks: against the path tracer `few` measured 1.45
// times the truth's radiance where dense and `scattered` 1.24. The share is `sample_weather`'s,
// recomputed here rather than carried in `Weather`: the path tracer shares that struct, and a
// new member would change its code, and with it the key of every committed truth.
// A cellular layer's cloudlets (cellular_base) cover less of the region than the map's
// coverage c says, and never more than CELLULAR_SHARE: measured on the shape texture, the
// share of its cells the remap keeps is within 0.08 of c squared up to that cap. Fed c, the
// octaves lit `type altocumulus` 1.29 times the truth's radiance where dense (docs/fit-log.md).
const CELLULAR_SHARE: f32 = 0.75;

fn regional_coverage(p: vec3<f32>, l: Layer, weather: Weather) -> f32 {
    var share = weather.coverage;
    let cumulus = smoothstep(0.75, 1.0, l.cloud_type) * frame.convective_cells;
    if cumulus > 0.0 {
        let uv = (p.xz - l.weather_offset) / frame.weather_period;
        let r = textureSampleLevel(weather_tex, noise_sampler, uv, 0.0).r;
        let map = saturate(r + 2.0 * (l.coverage - 0.5));
        let cells = saturate(l.coverage * (1.0 + CELL_MESOSCALE * (2.0 * r - 1.0)));
        share = mix(map, cells, cumulus);
    }
    return mix(share, min(share * share, CELLULAR_SHARE), l.cellular);
}

// Cumulonimbus anvils (`clouds.anvil`; deep cumulus layers: type 0.75 and up, fully at 1, as
// for the cells, and deeper than ANVIL_DEPTH_M.x, fully at .y, so that a fair cumulus layer
// beside a storm keeps its domes: a towering cumulus METAR layer is 4 km deep, a
// cumulonimbus one 8 km). A storm's updraft rises until the stable air of the tropopause stops it; there
// the cloud spreads sideways into a flat plate many times the tower's width, carried downwind
// by the wind aloft (Houze 2014, Cloud Dynamics, 2nd ed., ch. 8). Above ANVIL_BASE of the
// layer the anvil's cover at a point follows the most cover the weather map has at seven
// taps, the point and six about it at a radius rising to ANVIL_SPREAD_M at the layer's top,
// all moved upwind by the shear's share at that height (`frame.anvil_shear`, its whole at the
// top): the map dilated, so each tower's top spreads into a plate whose underside rises away
// from the tower and which leans downwind. Only the map's cores spread (cover above
// ANVIL_CORE, rising to full at 1): dilated as it is, a storm layer of coverage 0.6 became one
// unbroken sheet seen from above. Its height profile is a slab, full between ANVIL_FULL and
// ANVIL_FALL of the layer (the top tenth to third of an 8 km storm layer, an anvil's 1-2 km).
// Returns (cover, profile), each 0 where there is no anvil; the density takes the greater of
// each and its own, so a scene without anvils computes what it did before.
const ANVIL_BASE: f32 = 0.7;
const ANVIL_FULL: f32 = 0.8;
const ANVIL_FALL: f32 = 0.93;
const ANVIL_SPREAD_M: f32 = 4000.0;
const ANVIL_CORE: f32 = 0.85;
const ANVIL_DEPTH_M: vec2<f32> = vec2<f32>(4000.0, 6000.0);

fn anvil_cover(p: vec3<f32>, h: f32, l: Layer) -> vec2<f32> {
    let a = anvil_weight(l);
    if a <= 0.0 || h <= ANVIL_BASE {
        return vec2<f32>(0.0);
    }
    let rise = smoothstep(ANVIL_BASE, 1.0, h);
    let centre = (p.xz - frame.anvil_shear * rise - l.weather_offset) / frame.weather_period;
    let r = ANVIL_SPREAD_M * rise / frame.weather_period;
    var m = textureSampleLevel(weather_tex, noise_sampler, centre, 0.0).r;
    for (var k = 0u; k < 6u; k++) {
        let angle = f32(k) * (PI / 3.0);
        let tap = centre + r * vec2<f32>(cos(angle), sin(angle));
        m = max(m, textureSampleLevel(weather_tex, noise_sampler, tap, 0.0).r);
    }
    let core = saturate((saturate(m + 2.0 * (l.coverage - 0.5)) - ANVIL_CORE) / (1.0 - ANVIL_CORE));
    let cover = core * a * smoothstep(ANVIL_BASE, ANVIL_FULL, h);
    return vec2<f32>(cover, a * gradient(h, ANVIL_BASE, ANVIL_FULL, ANVIL_FALL, 1.0));
}

// Layer `l`'s anvil weight: `clouds.anvil` on cumulonimbus (type toward 1) deep enough
// (ANVIL_DEPTH_M), 0 elsewhere. The anvil's profile peaks at it.
fn anvil_weight(l: Layer) -> f32 {
    return frame.anvil * smoothstep(0.75, 1.0, l.cloud_type)
        * smoothstep(ANVIL_DEPTH_M.x, ANVIL_DEPTH_M.y, l.top - l.bottom);
}

// Thesis eq. 5.1: a parabola with roots at the cloud's start and top, peak 1 between them.
// The cloud starts at the layer bottom; its height grows with cloud type (stratus low,
// cumulus the whole layer).
fn height_parabola(h: f32, cloud_type: f32) -> f32 {
    let height = mix(0.35, 1.0, cloud_type);
    return saturate(h * (h - height) * (-4.0 / (height * height)));
}

// Density-height gradient of one cloud type: rise over [r0, r1], fall over [f0, f1].
fn gradient(h: f32, r0: f32, r1: f32, f0: f32, f1: f32) -> f32 {
    return smoothstep(r0, r1, h) * (1.0 - smoothstep(f0, f1, h));
}

// HZD's cloud-type gradients (stratus, stratocumulus, cumulus), blended by type in [0, 1].
// The breakpoints follow the shapes of the HZD talk's gradient figure (seed 004).
fn height_cloud_types(h: f32, cloud_type: f32) -> f32 {
    let stratus = gradient(h, 0.0, 0.08, 0.15, 0.25);
    let stratocumulus = gradient(h, 0.0, 0.2, 0.4, 0.65);
    let cumulus = gradient(h, 0.0, 0.1, 0.6, 0.95);
    let lo = mix(stratus, stratocumulus, saturate(cloud_type * 2.0));
    return mix(lo, cumulus, saturate(cloud_type * 2.0 - 1.0));
}

// The height fraction in layer `l` where the cloud's height profile ends under `weather`: the
// parabola's top (or the cloud-type gradients'), times the cloud's own top on convective
// cells. Cirrus and cellular cloud have profiles of their own: for them the layer's top.
fn cloud_top_fraction(l: Layer, weather: Weather) -> f32 {
    let t = weather.cloud_type;
    var top = mix(0.35, 1.0, t);
    if frame.height_model == HEIGHT_CLOUD_TYPES {
        top = mix(mix(0.25, 0.65, saturate(t * 2.0)), 0.95, saturate(t * 2.0 - 1.0));
    }
    return mix(top * weather.top, 1.0, max(l.cirrus, l.cellular));
}

fn height_signal(h: f32, cloud_type: f32) -> f32 {
    if frame.height_model == HEIGHT_CLOUD_TYPES {
        return height_cloud_types(h, cloud_type);
    }
    return height_parabola(h, cloud_type);
}

// Density in [0, 1] at world position `p` with altitude `alt`, in whichever layer holds it.
// `counters` counts density and detail evaluations.
fn cloud_density(p: vec3<f32>, alt: f32, counters: ptr<function, Counters>) -> f32 {
    let i = layer_at(alt);
    if i == NO_LAYER {
        return 0.0;
    }
    return layer_density(p, alt, cloud_layer(i), counters);
}

// Density in [0, 1] at world position `p` with altitude `alt` in layer `l` (0 outside it).
fn layer_density(p: vec3<f32>, alt: f32, l: Layer, counters: ptr<function, Counters>) -> f32 {
    return layer_density_with(p, alt, l, true, counters);
}

// layer_density, with the detail erosion only if `with_detail` (the octaves' column goes
// without it: lighting.wgsl::octave_optical_depth).
fn layer_density_with(p: vec3<f32>, alt: f32, l: Layer, with_detail: bool,
                      counters: ptr<function, Counters>) -> f32 {
    let h = layer_height(l, alt); // height fraction in the layer
    if h < 0.0 || h > 1.0 {
        return 0.0;
    }
    (*counters).density += 1u;
    let weather = sample_weather(p, l);
    var ice = 0.0;
    if l.cirrus > 0.0 {
        ice = cirrus_density(p, alt, h, l, weather, counters);
        if l.cirrus >= 1.0 {
            return ice;
        }
    }
    return mix(water_density(p, alt, h, l, weather, with_detail, counters), ice, l.cirrus);
}

// Cirrus (`clouds.cirrus`, per layer): ice cloud, thin and high, whose look is fibres, streaks
// a few hundred metres across and kilometres long lying along the wind, with fall streaks of
// ice crystals trailing below the heads they fall from, left behind by the slower wind beneath
// (cirrus fibratus and uncinus: WMO International Cloud Atlas, 2017; Heymsfield 1975, J.
// Atmos. Sci. 32:799). The cumulus family's noise is read the same way in every direction and
// heaps into domes; a thin high layer of it was a few soft blobs. Here the same textures are
// read in the wind's frame:
// - strands: the shape noise at CIRRUS_SCALE of its period, CIRRUS_STRETCH times longer along
//   the wind than across, its ridges 1 - |2n - 1| (thin where it crosses its middle) widened
//   by its Worley FBM (CIRRUS_STRANDS); the weather map's coverage remaps them as it does the
//   other clouds, keeping their crests (thin strands) or, at full coverage, all of them (a
//   cirrostratus veil), and is 0 where the map's is, so the empty-space skip's bound holds;
// - fibres within them: the detail noise's ridges, CIRRUS_FIBRE_STRETCH times longer along the
//   wind, kept between CIRRUS_RIDGE, CIRRUS_FIBRE of the density between them taken away;
// - bends: the curl noise, read at CIRRUS_BEND_SCALE times its period, moves them sideways by
//   up to CIRRUS_BEND_M (at 1500 m they zigzagged, at 400 m they were ruled lines);
// - fall streaks: a fibre at height fraction h reads the noise CIRRUS_FALL_M (1 - h) further
//   downwind than the layer's top does, so its trail leans upwind below its head.
// The height profile is full from 0.35 to 0.75 of the layer. All chosen by eye, from below and
// above (docs/cloud-fields.md); the CPU twin's test holds the fibres along the wind.
const CIRRUS_STRETCH: f32 = 16.0;
const CIRRUS_FALL_M: f32 = 3000.0;
const CIRRUS_FIBRE: f32 = 0.95;
const CIRRUS_RIDGE: vec2<f32> = vec2<f32>(0.55, 0.95);
const CIRRUS_BEND_M: f32 = 800.0;
const CIRRUS_BEND_SCALE: f32 = 4.0;
const CIRRUS_STRANDS: f32 = 0.5;
const CIRRUS_SCALE: f32 = 0.5;
const CIRRUS_FIBRE_STRETCH: f32 = 30.0;

fn cirrus_density(p: vec3<f32>, alt: f32, h: f32, l: Layer, weather: Weather,
                  counters: ptr<function, Counters>) -> f32 {
    let signal = gradient(h, 0.0, 0.35, 0.75, 1.0);
    if weather.coverage <= 0.0 || signal <= 0.0 {
        return 0.0;
    }
    // The wind's frame, the curl noise bending the strands sideways. The wind carries the
    // strands and fibres along itself only, by offsets the host wraps by their own periods
    // along it (the textures' per-axis offsets, wrapped per axis, would make them jump).
    let wind = frame.wind_direction;
    let cuv = (p.xz - frame.cirrus_bend_offset) / (frame.curl_period * CIRRUS_BEND_SCALE);
    let curl = textureSampleLevel(curl_tex, noise_sampler, cuv, 0.0).xy * 2.0 - 1.0;
    let along = dot(p.xz, wind) + CIRRUS_FALL_M * (1.0 - h);
    let across = dot(p.xz, vec2<f32>(-wind.y, wind.x)) + CIRRUS_BEND_M * curl.x;
    let q = vec3<f32>((along - frame.cirrus_strand_offset) / CIRRUS_STRETCH, alt, across);
    let qf = vec3<f32>((along - frame.cirrus_fibre_offset) / CIRRUS_FIBRE_STRETCH, alt, across);

    // Strands: the shape noise's ridges, widened by its Worley FBM; the coverage keeps their
    // crests (thin strands) or all of them (a cirrostratus veil), as it keeps the other
    // clouds' densest parts.
    let dims = vec3<f32>(textureDimensions(shape_tex));
    let period = frame.shape_period * vec3<f32>(1.0, dims.y / dims.x, 1.0);
    let s = textureSampleLevel(shape_tex, noise_sampler, q / (period * CIRRUS_SCALE), 0.0);
    let low_fbm = s.g * 0.625 + s.b * 0.25 + s.a * 0.125;
    let strand = (1.0 - abs(2.0 * s.r - 1.0)) * mix(1.0, low_fbm, CIRRUS_STRANDS);
    let base = saturate(remap(strand * signal, 1.0 - weather.coverage, 1.0, 0.0, 1.0))
        * weather.coverage;
    if base <= 0.0 {
        return 0.0;
    }

    // Fibres within them: the detail noise's ridges.
    (*counters).detail += 1u;
    let dn = textureSampleLevel(detail_tex, noise_sampler, qf / frame.detail_period, 0.0);
    let ridge = 1.0 - abs(2.0 * (dn.r * 0.625 + dn.g * 0.25 + dn.b * 0.125) - 1.0);
    let fibre = smoothstep(CIRRUS_RIDGE.x, CIRRUS_RIDGE.y, ridge);
    return saturate(base * mix(1.0, fibre, CIRRUS_FIBRE) * l.density);
}

// Cellular layer cloud (`clouds.cellular`, per layer): stratocumulus and altocumulus are
// fields of cloudlets, rounded masses with clear or thin gaps between them, seen from below
// dark at their thick middles and light at their rims (WMO International Cloud Atlas, 2017).
// A thin layer stirred by convection (warmed from below or cooled at its top) overturns in
// cells whose width at onset is 2.016 times the layer's depth (Rayleigh-Benard convection
// between rigid boundaries: Chandrasekhar 1961, Hydrodynamic and Hydromagnetic Stability,
// ch. II), and cloud stands over their updrafts. Here each cell of the shape texture's
// Worley FBM (its G channel, CELLULAR_WORLEY cells across its period) is one cloudlet:
// - its width: the texture read at its period over k, k the power of two (at least 1) that
//   brings a cell nearest CELLULAR_ASPECT times the layer's depth (a power of two, so that the
//   wind's offset, wrapped by whole shape periods, is whole periods of the read);
// - a column through the layer: one slice of the texture (at the layer's bottom), so a cell
//   is the same cell at every height;
// - read in the wind's frame, `frame.cellular_stretch` times longer along the wind than across
//   (`clouds.cell_rolls`: rolls, cloud streets), the wind carrying them along itself by an
//   offset the host wraps by that many shape periods (whole periods of the read, for any k);
// - the channel spread over [0, 1] from CELLULAR_RANGE (its 10th and 99th percentiles);
// - the coverage keeps the cells' middles as it keeps the other clouds' densest parts, m
//   (0 at a cloudlet's rim, 1 at the strongest middles), but never their borders, below
//   CELLULAR_GAP: cloudlets stay apart where the map's coverage is full (a cellular layer
//   at coverage 1 is a deck of cloudlets, with thin lanes between them);
// - a dome over a flat base: from the layer's bottom up to a top that rises from
//   CELLULAR_TOP.x of the layer at the rim to CELLULAR_TOP.y at the strongest middles, both
//   softened over CELLULAR_SOFT, the density rising as the square root of m from the rim.
//   The base ramps up from the layer's bottom itself, and the density does not level off
//   inside (where it would be the weather map's coverage alone). With a cut at 0.05 of the
//   layer and a level-off, the CPU twin's detail lookups on `stress-cellular` were 580 from
//   lavapipe's against a counter spread of 35 (16.5 times; the cross-device model allows
//   12); as here, 694 against 118 (5.9 times).
// The detail noise then erodes the rims as it does the other clouds'. Chosen by eye from
// below and above (docs/cloud-fields.md).
const CELLULAR_ASPECT: f32 = 2.016;
const CELLULAR_WORLEY: f32 = 4.0;
const CELLULAR_RANGE: vec2<f32> = vec2<f32>(0.3, 0.75);
const CELLULAR_GAP: f32 = 0.15;
const CELLULAR_TOP: vec2<f32> = vec2<f32>(0.35, 1.0);
const CELLULAR_SOFT: f32 = 0.1;

// The cellular cloudlets' base density at `p`, height fraction `h` of layer `l`, under the
// weather's coverage `coverage` (> 0).
fn cellular_base(p: vec3<f32>, h: f32, l: Layer, coverage: f32) -> f32 {
    let width = frame.shape_period / CELLULAR_WORLEY;
    let k = exp2(max(round(log2(width / (CELLULAR_ASPECT * (l.top - l.bottom)))), 0.0));
    let dims = vec3<f32>(textureDimensions(shape_tex));
    let period = frame.shape_period / k * vec3<f32>(1.0, dims.y / dims.x, 1.0);
    // The wind's frame: rolls are cells drawn out along the wind.
    let wind = frame.wind_direction;
    let along = (dot(p.xz, wind) - frame.cellular_offset) / frame.cellular_stretch;
    let q = vec3<f32>(along, l.bottom, dot(p.xz, vec2<f32>(-wind.y, wind.x)));
    let g = textureSampleLevel(shape_tex, noise_sampler, q / period, 0.0).g;
    let cell = saturate((g - CELLULAR_RANGE.x) / (CELLULAR_RANGE.y - CELLULAR_RANGE.x));
    let m = saturate(remap(cell, max(1.0 - coverage, CELLULAR_GAP), 1.0, 0.0, 1.0));
    let top = mix(CELLULAR_TOP.x, CELLULAR_TOP.y, m);
    let dome = saturate((top - h) / CELLULAR_SOFT) * saturate(h / CELLULAR_SOFT);
    return sqrt(m) * dome * coverage;
}

// The water clouds' density (the cumulus family, stratus to cumulonimbus) at `p` of layer
// `l`, height fraction `h`, under `weather` (layer_density_with).
fn water_density(p: vec3<f32>, alt: f32, h: f32, l: Layer, weather: Weather, with_detail: bool,
                 counters: ptr<function, Counters>) -> f32 {
    let anvil = anvil_cover(p, h, l);
    let coverage = max(weather.coverage, anvil.x);
    let signal = max(height_signal(h / weather.top, weather.cloud_type), anvil.y);
    // A cellular layer's cloudlets have their own height profile.
    if coverage <= 0.0 || (signal <= 0.0 && l.cellular <= 0.0) {
        return 0.0;
    }

    var base = 0.0;
    if l.cellular < 1.0 {
        // Base shape: Perlin-Worley remapped by low-frequency Worley FBM (HZD), isotropic
        // texels: the texture's y period is its x period scaled by its aspect (128x32x128
        // thesis layout).
        let dims = vec3<f32>(textureDimensions(shape_tex));
        let period = frame.shape_period * vec3<f32>(1.0, dims.y / dims.x, 1.0);
        let shape_pos = vec3<f32>(p.x - frame.shape_offset.x, alt, p.z - frame.shape_offset.y);
        let s = textureSampleLevel(shape_tex, noise_sampler, shape_pos / period, 0.0);
        let low_fbm = s.g * 0.625 + s.b * 0.25 + s.a * 0.125;
        base = saturate(remap(s.r, low_fbm - 1.0, 1.0, 0.0, 1.0)) * signal;

        // Coverage (HZD): remap so that low coverage keeps only the densest parts, then
        // scale.
        base = saturate(remap(base, 1.0 - coverage, 1.0, 0.0, 1.0)) * coverage;
    }
    // A cellular layer's cloudlets; a wholly cellular one reads no shape noise besides.
    if l.cellular > 0.0 {
        base = mix(base, cellular_base(p, h, l, coverage), l.cellular);
    }
    if base <= 0.0 {
        return 0.0;
    }

    // Detail erosion at the edges only: below the threshold (thesis alg. 4.1). The amount
    // fades to zero at the threshold so the density stays continuous.
    var density = base;
    let strength = frame.detail_strength;
    let threshold = frame.erosion_threshold;
    if DETAIL && with_detail && strength > 0.0 && base < threshold {
        (*counters).detail += 1u;
        var detail_pos = vec3<f32>(p.x, alt, p.z);
        if CURL {
            // Curl noise distorts the detail lookup, more at the cloud base (HZD, seed 001).
            let cuv = (p.xz - frame.curl_offset) / frame.curl_period;
            let curl = textureSampleLevel(curl_tex, noise_sampler, cuv, 0.0).xy * 2.0 - 1.0;
            detail_pos = detail_pos + vec3<f32>(curl.x, 0.0, curl.y) * (frame.curl_strength * (1.0 - h));
        }
        detail_pos = detail_pos - vec3<f32>(frame.detail_offset.x, 0.0, frame.detail_offset.y);
        let dn = textureSampleLevel(detail_tex, noise_sampler, detail_pos / frame.detail_period, 0.0);
        let high_fbm = dn.r * 0.625 + dn.g * 0.25 + dn.b * 0.125;
        // Inverted Worley is billowy, plain Worley wispy. HZD turns wispy bases into billowy
        // tops over the lowest tenth of the cloud; `wispy_billowy` scales that (0.5: HZD's
        // ramp, 0: wispy everywhere, 1: billowy almost from the base). A constant blend would
        // not do: at 0.5 it cancels the detail noise entirely.
        let billowy = saturate(2.0 * frame.wispy_billowy * saturate(h * 10.0));
        let shape = mix(1.0 - high_fbm, high_fbm, billowy);
        let erosion = strength * shape * (1.0 - base / threshold);
        density = saturate(remap(base, erosion, 1.0, 0.0, 1.0));

        // Close-range detail: the edges eroded again, finer, near the camera.
        let near = close_detail_weight(p, alt);
        if near > 0.0 && density > 0.0 && density < threshold {
            (*counters).detail += 1u;
            density = close_erosion(p, h, detail_pos, density, near, billowy, threshold);
        }
    }

    // Denser toward the top (thesis 4.5.1), global density and precipitation, clamp.
    density = density * mix(1.0, h, frame.height_gradient);
    density = density * l.density * (1.0 + weather.precipitation);
    return clamp(density, 0.0, 1.0);
}

// Close-range detail (`clouds.close_detail`). The detail noise's 32 texels a tile are 37.5 m at
// its default 1200 m period: from tens of metres its edges are blur, and a cloud's fringe
// (density 0.05-0.4 rising over hundreds of metres, a mean free path of 60-500 m at the
// default scattering) is a fog the camera sits in. Near the camera the edges the first erosion
// left (density below the erosion threshold) are eroded again by the same texture read
// `frame.close_detail_scale` times finer (an integer, so that the detail's wind offset, wrapped
// by its period, is whole periods of this read), the lookup bent again by the curl noise read
// as much finer over a displacement as much smaller: the fringe's haze cleared into wisps and
// billows tens of metres across (finer ones, at a scale of 8, do not show through a fringe
// whose mean free path is longer), in the first erosion's form (fading out at the threshold,
// so the density stays continuous; wispy toward the base, billowy above as `wispy_billowy`
// says). A level of detail by the distance from the camera: full to half of
// `frame.close_detail_range`, none at it, so a cloud's look changes smoothly as the camera
// nears it and farther clouds pay nothing; the march takes steps of `frame.close_step` within
// that range (march.wgsl march_layer), which bounds the cost. The cores are left intact: inside
// a cloud's core there is nothing to see but the fog of it.
fn close_detail_weight(p: vec3<f32>, alt: f32) -> f32 {
    let s = frame.close_detail;
    if s <= 0.0 {
        return 0.0;
    }
    let c = frame.camera_position;
    let d = length(vec3<f32>(p.x - c.x, alt - c.y, p.z - c.z));
    let r = frame.close_detail_range;
    return s * (1.0 - smoothstep(0.5 * r, r, d));
}

// The density `density` (below `threshold`, after the first erosion) eroded by the finer read
// with weight `near` (close_detail_weight): `detail_pos` is the first erosion's lookup (curl
// and wind applied, m), `billowy` its wispy-to-billowy blend at height fraction `h`.
fn close_erosion(p: vec3<f32>, h: f32, detail_pos: vec3<f32>, density: f32, near: f32,
                 billowy: f32, threshold: f32) -> f32 {
    let k = frame.close_detail_scale;
    var pos = detail_pos;
    if CURL {
        let cuv = (p.xz - frame.curl_offset) * (k / frame.curl_period);
        let curl = textureSampleLevel(curl_tex, noise_sampler, cuv, 0.0).xy * 2.0 - 1.0;
        pos = pos + vec3<f32>(curl.x, 0.0, curl.y) * (frame.curl_strength / k * (1.0 - h));
    }
    let dn = textureSampleLevel(detail_tex, noise_sampler, pos * (k / frame.detail_period), 0.0);
    let fbm = dn.r * 0.625 + dn.g * 0.25 + dn.b * 0.125;
    let shape = mix(1.0 - fbm, fbm, billowy);
    let erosion = near * shape * (1.0 - density / threshold);
    return saturate(remap(density, erosion, 1.0, 0.0, 1.0));
}
