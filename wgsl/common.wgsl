// Shared declarations of the `clouds` module: the per-frame uniforms, the resources, the
// feature switches and small math helpers.
//
// `Frame` mirrors `FrameUniforms` in crates/scene/src/uniforms.rs member for member (a test
// compares naga's reflection of this struct with the Rust one). Every member is a vec4, so the
// layout is the same under WGSL, std140 and HLSL cbuffer rules.

struct Frame {
    camera_position: vec4<f32>,     // x, altitude, z (m); w = tan(fov_y / 2)
    camera_forward: vec4<f32>,      // unit; w = width / height
    camera_right: vec4<f32>,        // unit; w = exposure
    camera_up: vec4<f32>,           // unit; w = 0
    sun_direction: vec4<f32>,       // unit, toward the sun; w = cos(sun angular radius)
    sun_illuminance: vec4<f32>,     // linear rgb
    atmosphere: vec4<f32>,          // planet radius, layer bottom, layer top (altitudes), cut-off distance (m)
    clouds: vec4<f32>,              // coverage, density multiplier, cloud type, precipitation
    erosion: vec4<f32>,             // detail strength, erosion threshold, curl strength (m), height gradient strength
    periods: vec4<f32>,             // weather, shape (x axis), detail, curl periods (m)
    wind_offsets0: vec4<f32>,       // weather offset xz, shape offset xz (m, wrapped by the period)
    wind_offsets1: vec4<f32>,       // detail offset xz, curl offset xz (m, wrapped by the period)
    extinction: vec4<f32>,          // sigma_s, sigma_a (1/m at density 1), precipitation darkening, wispy/billowy
    phase: vec4<f32>,               // g, g2, blend (weight of the g2 lobe), powder strength
    multiple_scattering: vec4<f32>, // a (contribution), b (extinction), c (eccentricity) per octave, w = octave build-up length (m)
    ambient_bottom: vec4<f32>,      // linear rgb; w = ambient strength
    ambient_top: vec4<f32>,         // linear rgb
    march: vec4<f32>,               // step length (m, 0 = from view steps), light step growth, first light step (m), early-exit transmittance
    counts: vec4<u32>,              // width, height, view steps, light steps
    modes: vec4<u32>,               // phase model, integration, height model, flags
    misc: vec4<u32>,                // octaves beyond single scattering, frame (jitter seed), path orders, extra cloud layers (0-3)
    previous_position: vec4<f32>,   // last frame's camera (as camera_position): reprojection
    previous_forward: vec4<f32>,    // last frame's forward; w = aspect
    previous_right: vec4<f32>,      // last frame's right
    previous_up: vec4<f32>,         // last frame's up
    temporal: vec4<u32>,            // block side (1 off, 2 = 1/4, 4 = 1/16), history valid (0/1)
    layer1: vec4<f32>,              // extra cloud layer 1: bottom, top (altitudes, m), coverage, density multiplier
    layer1_weather: vec4<f32>,      // its cloud type, precipitation, weather-map offset xz (m, wrapped)
    layer2: vec4<f32>,              // extra cloud layer 2 (as layer1)
    layer2_weather: vec4<f32>,
    layer3: vec4<f32>,              // extra cloud layer 3 (as layer1)
    layer3_weather: vec4<f32>,
    air_rayleigh: vec4<f32>,        // physical sky: Rayleigh scattering rgb (1/m at the ground); w = scale height (m)
    air_mie: vec4<f32>,             // Mie scattering, absorption (1/m at the ground), scale height (m), g
    air_ozone: vec4<f32>,           // ozone absorption rgb at its peak (1/m); w = peak altitude (m)
    air_misc: vec4<f32>,            // atmosphere thickness (m), ozone tent width (m), ground albedo, 0
    moon: vec4<f32>,                // unit direction to the moon; w = full-moon illuminance (0: no moon)
    night: vec4<f32>,               // the real sun's unit direction; w = a magnitude-0 star's illuminance (0: no stars)
    light_model: vec4<f32>,         // side light, coverage exponent, far-shadow chord (m, 0 = off), limb darkening
    octave_direction: vec4<f32>,    // the octaves' forward lobe through thin cloud (strength, 0 = off; eccentricity), vertical anisotropy (0 = off), deck escape (0 = off)
    octave_depth: vec4<f32>,        // the octaves' column's weight in a closed deck (0 = off), its scale, downward dimming (0 = off), 0
}

// Codes shared with the scene crate (`PhaseModel::code`, `Integration::code`, ...).
const PHASE_HG: u32 = 0u;
const PHASE_TWO_LOBE_HG: u32 = 1u;
const PHASE_CORNETTE_SHANKS: u32 = 2u;
const INTEGRATION_ANALYTIC: u32 = 0u;
const INTEGRATION_RIEMANN: u32 = 1u;
const HEIGHT_PARABOLA: u32 = 0u;
const HEIGHT_CLOUD_TYPES: u32 = 1u;
const FLAG_BEER_POWDER: u32 = 1u;
const FLAG_JITTER: u32 = 2u;
const FLAG_DYNAMIC_STEP: u32 = 4u;  // double the view step after 8 empty samples (seed 001)
const FLAG_CHECKERBOARD: u32 = 8u;  // skip clear-history pixels every other turn (thesis 6.2.2)
const FLAG_EMPTY_SKIP: u32 = 16u;   // jump over empty cells of the weather occupancy grid
const FLAG_PHYSICAL_SKY: u32 = 32u; // Hillaire 2020's atmosphere behind the clouds
const FLAG_MOONLIT: u32 = 64u;      // the key light (sun_direction, sun_illuminance) is the moon

// Feature switches. A variant in modules.toml sets these; code behind a `false` switch is
// removed by naga before translation, so a scene that does not use a feature pays nothing.
override LIGHT_MARCH: bool = true;  // march toward the sun for self-shadowing (thesis 5.5.2)
override MAX_OCTAVES: u32 = 8u;     // multiple-scattering octaves compiled in (0 = single scattering)
override DETAIL: bool = true;       // detail-noise erosion of the base shape (thesis alg. 4.1)
override CURL: bool = true;         // curl-noise distortion of the detail lookup (HZD, seed 001)
override STATS: bool = false;       // count work with atomics (the statistics variant)

const PI: f32 = 3.14159265358979;
const MAX_VIEW_STEPS: u32 = 1024u;  // bound for step-length mode, so a pixel's work is finite

@group(0) @binding(0) var<uniform> frame: Frame;

fn saturate(x: f32) -> f32 {
    return clamp(x, 0.0, 1.0);
}

// Linear remap of `x` from [lo0, hi0] to [lo1, hi1] (HZD's remap), unclamped.
fn remap(x: f32, lo0: f32, hi0: f32, lo1: f32, hi1: f32) -> f32 {
    return lo1 + (x - lo0) * (hi1 - lo1) / (hi0 - lo0);
}

// PCG hash (O'Neill), used for per-pixel jitter: deterministic on every backend.
fn pcg(v: u32) -> u32 {
    let state = v * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// The base-2 van der Corput sequence (the radical inverse of n): the thesis's start offsets
// for successive marches of one pixel. 24 bits so the conversion is exact.
fn van_der_corput(n: u32) -> f32 {
    return f32(reverseBits(n) >> 8u) * (1.0 / 16777216.0);
}

// A value in [0, 1) from a pixel and a frame index; 24 bits so the conversion is exact.
fn hash_unit(pixel: vec2<u32>, frame_index: u32) -> f32 {
    let h = pcg(pixel.x ^ pcg(pixel.y ^ pcg(frame_index)));
    return f32(h >> 8u) * (1.0 / 16777216.0);
}
