// Shared declarations of the `clouds` module: the resources, the feature switches and small
// math helpers.
//
// `Frame`, the per-frame uniform block, is declared once in crates/scene/src/uniforms.rs
// (`frame_members!`) and generated into frame.wgsl, composed before this file.

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
const FLAG_SCENE_DEPTH: u32 = 128u; // the host's scene depth is bound: the march stops at its surfaces
const FLAG_HDR_SKY: u32 = 256u;     // the HDR output carries the sky where the host has no geometry
const FLAG_LIGHT_SHAFTS: u32 = 512u; // the clouds' shadows in the air (composite.wgsl::light_shafts)
const FLAG_LEE_DIAGRAM: u32 = 1024u; // the rainbow from its table (rainbow.wgsl), else three wavelengths
const FLAG_MOON_MSAA: u32 = 2048u;   // the moon's disc at four samples a pixel (night.wgsl), else its edge spread
const FLAG_SNOW: u32 = 4096u;        // the particles are snowflakes (precipitation.wgsl), else raindrops

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
