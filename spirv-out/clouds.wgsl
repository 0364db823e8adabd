// Generated from crates/scene/src/uniforms.rs (`frame_members!`) by `cargo xtask
// build-shaders`; edit the declaration there, not this file.
//
// The per-frame uniform block. No member crosses a 16-byte row, so the layout is the
// same under WGSL, std140 and HLSL cbuffer rules.

struct Frame {
    // Camera position: x, altitude, z (m).
    camera_position: vec3<f32>,
    // tan(fov_y / 2).
    tan_half_fov: f32,
    // Unit view direction.
    camera_forward: vec3<f32>,
    // Image width / height.
    aspect: f32,
    // Unit, image right.
    camera_right: vec3<f32>,
    // Exposure (`camera.exposure`, times auto exposure's factor).
    exposure: f32,
    // Unit, image up.
    camera_up: vec3<f32>,
    // Padding (0).
    _pad0: f32,
    // Unit vector toward the key light (the sun; the moon under `FLAG_MOONLIT`).
    sun_direction: vec3<f32>,
    // cos(the sun's angular radius).
    sun_cos_radius: f32,
    // The key light's illuminance, linear rgb.
    sun_illuminance: vec3<f32>,
    // Padding (0).
    _pad1: f32,
    // Planet radius (m).
    planet_radius: f32,
    // The main cloud layer's bottom (altitude, m).
    cloud_bottom: f32,
    // The main cloud layer's top (altitude, m).
    cloud_top: f32,
    // The march's cut-off distance (m).
    cutoff_distance: f32,
    // The main layer's coverage.
    coverage: f32,
    // The main layer's density multiplier.
    density: f32,
    // The main layer's cloud type (`clouds.cloud_type`).
    cloud_type: f32,
    // The main layer's precipitation.
    precipitation: f32,
    // Detail-noise strength.
    detail_strength: f32,
    // Erosion threshold.
    erosion_threshold: f32,
    // Curl-noise displacement (m).
    curl_strength: f32,
    // Height-gradient strength.
    height_gradient: f32,
    // Weather-map period (m).
    weather_period: f32,
    // Shape-noise period along x (m).
    shape_period: f32,
    // Detail-noise period (m).
    detail_period: f32,
    // Curl-noise period (m).
    curl_period: f32,
    // Weather-map wind offset xz (m, within [0, period)).
    weather_offset: vec2<f32>,
    // Shape-noise wind offset xz (m, within [0, period)).
    shape_offset: vec2<f32>,
    // Detail-noise wind offset xz (m, within [0, period)).
    detail_offset: vec2<f32>,
    // Curl-noise wind offset xz (m, within [0, period)).
    curl_offset: vec2<f32>,
    // sigma_s (1/m at density 1).
    scattering: f32,
    // sigma_a (1/m at density 1).
    absorption: f32,
    // Darkening by precipitation.
    precipitation_darkening: f32,
    // Wispy (0) to billowy (1) erosion.
    wispy_billowy: f32,
    // Phase function: the first lobe's g.
    phase_g: f32,
    // Phase function: the second lobe's g.
    phase_g2: f32,
    // Phase function: the blend of the two lobes.
    phase_blend: f32,
    // The powder term's strength.
    powder_strength: f32,
    // Multiple-scattering octaves: contribution attenuation a per octave.
    ms_contribution: f32,
    // Multiple-scattering octaves: extinction attenuation b per octave.
    ms_extinction: f32,
    // Multiple-scattering octaves: eccentricity attenuation c per octave.
    ms_eccentricity: f32,
    // Multiple-scattering octaves: build-up length (m).
    ms_buildup: f32,
    // Ambient light at the layer's bottom, linear rgb.
    ambient_bottom: vec3<f32>,
    // Ambient strength.
    ambient_strength: f32,
    // Ambient light at the layer's top, linear rgb.
    ambient_top: vec3<f32>,
    // The share of cumulus standing on the weather map's convective cells.
    convective_cells: f32,
    // View step length (m; 0 = derive it from `view_steps`).
    step_length: f32,
    // Growth factor of each light step over the last.
    light_step_growth: f32,
    // First light step (m).
    first_light_step: f32,
    // Transmittance below which the view march stops.
    early_exit_transmittance: f32,
    // Image width and height (pixels).
    size: vec2<u32>,
    // View steps.
    view_steps: u32,
    // Light steps.
    light_steps: u32,
    // [`PhaseModel::code`](crate::PhaseModel::code).
    phase_model: u32,
    // [`Integration::code`](crate::Integration::code).
    integration: u32,
    // [`HeightModel::code`](crate::HeightModel::code).
    height_model: u32,
    // `FLAG_*` bits ([`FrameUniforms::FLAG_BEER_POWDER`], ...).
    flags: u32,
    // Multiple-scattering octaves beyond single scattering.
    octaves: u32,
    // Frame index: the jitter seed and the path tracer's random streams.
    frame_index: u32,
    // The path tracer's scattering orders (0 = all).
    path_orders: u32,
    // Extra cloud layers (0-3).
    extra_layers: u32,
    // Last frame's camera position: temporal upsampling reprojects through last frame's
    // camera. [`Scene::uniforms`] sets the current camera; a renderer that keeps history
    // replaces it with the one it rendered last.
    previous_position: vec3<f32>,
    // Last frame's tan(fov_y / 2).
    previous_tan_half_fov: f32,
    // Last frame's unit view direction.
    previous_forward: vec3<f32>,
    // Last frame's width / height.
    previous_aspect: f32,
    // Last frame's unit image right.
    previous_right: vec3<f32>,
    // Last frame's exposure (a change of exposure, like a move, ends the history's exact
    // reuse).
    previous_exposure: f32,
    // Last frame's unit image up.
    previous_up: vec3<f32>,
    // Padding (0).
    _pad4: f32,
    // Temporal upsampling's block side (1 = off, 2 = 1/4, 4 = 1/16).
    block_side: u32,
    // 1 when the history holds a frame to reproject (the renderer sets it), else 0.
    history_valid: u32,
    // Padding (0).
    _pad5: u32,
    // Padding (0).
    _pad6: u32,
    // Extra cloud layer 1 (`clouds.layers[0]`; zero when absent): bottom (altitude, m).
    layer1_bottom: f32,
    // Extra cloud layer 1: top (altitude, m).
    layer1_top: f32,
    // Extra cloud layer 1: coverage.
    layer1_coverage: f32,
    // Extra cloud layer 1: density multiplier.
    layer1_density: f32,
    // Extra cloud layer 1: cloud type.
    layer1_cloud_type: f32,
    // Extra cloud layer 1: precipitation.
    layer1_precipitation: f32,
    // Extra cloud layer 1: weather-map offset xz (m, within [0, period)).
    layer1_weather_offset: vec2<f32>,
    // Extra cloud layer 2 (`clouds.layers[1]`; zero when absent): bottom (altitude, m).
    layer2_bottom: f32,
    // Extra cloud layer 2: top (altitude, m).
    layer2_top: f32,
    // Extra cloud layer 2: coverage.
    layer2_coverage: f32,
    // Extra cloud layer 2: density multiplier.
    layer2_density: f32,
    // Extra cloud layer 2: cloud type.
    layer2_cloud_type: f32,
    // Extra cloud layer 2: precipitation.
    layer2_precipitation: f32,
    // Extra cloud layer 2: weather-map offset xz (m, within [0, period)).
    layer2_weather_offset: vec2<f32>,
    // Extra cloud layer 3 (`clouds.layers[2]`; zero when absent): bottom (altitude, m).
    layer3_bottom: f32,
    // Extra cloud layer 3: top (altitude, m).
    layer3_top: f32,
    // Extra cloud layer 3: coverage.
    layer3_coverage: f32,
    // Extra cloud layer 3: density multiplier.
    layer3_density: f32,
    // Extra cloud layer 3: cloud type.
    layer3_cloud_type: f32,
    // Extra cloud layer 3: precipitation.
    layer3_precipitation: f32,
    // Extra cloud layer 3: weather-map offset xz (m, within [0, period)).
    layer3_weather_offset: vec2<f32>,
    // The physical sky's air: Rayleigh scattering at the ground (rgb, 1/m).
    rayleigh_scattering: vec3<f32>,
    // Rayleigh scale height (m).
    rayleigh_scale_height: f32,
    // Mie scattering at the ground (1/m).
    mie_scattering: f32,
    // Mie absorption at the ground (1/m).
    mie_absorption: f32,
    // Mie scale height (m).
    mie_scale_height: f32,
    // Mie phase asymmetry g.
    mie_g: f32,
    // Ozone absorption at its peak (rgb, 1/m).
    ozone_absorption: vec3<f32>,
    // The ozone peak's altitude (m).
    ozone_center: f32,
    // Thickness of the atmosphere (m).
    air_thickness: f32,
    // The ozone tent's full width (m).
    ozone_width: f32,
    // The ground's albedo.
    ground_albedo: f32,
    // Padding (0).
    _pad7: f32,
    // Unit vector toward the moon (physical sky with a date and place). Its phase follows
    // from its direction and the real sun's.
    moon_direction: vec3<f32>,
    // The full moon's illuminance (luminance, in the units of `sun_illuminance`; 0 without
    // a moon).
    moon_illuminance: f32,
    // The real sun's unit direction (the moon's lit side faces it; `sun_direction` is the
    // moon's when it is the key light).
    real_sun_direction: vec3<f32>,
    // The illuminance of a magnitude-0 star, in the units of `sun_illuminance` (0: no
    // stars).
    star_illuminance: f32,
    // Fitted light model (`MultipleScattering`): side light.
    side_light: f32,
    // Fitted light model: coverage exponent.
    coverage_exponent: f32,
    // Fitted light model: far-shadow chord (m, 0 = off).
    far_chord: f32,
    // Fitted light model: limb darkening.
    limb_darkening: f32,
    // The octaves' forward lobe through thin cloud: strength (0 = off).
    forward_lobe: f32,
    // The octaves' forward lobe: eccentricity.
    forward_lobe_g: f32,
    // The octaves' vertical anisotropy (0 = off).
    vertical_anisotropy: f32,
    // The octaves' escape from a deck (0 = off).
    deck_escape: f32,
    // The octaves' optical depth in a closed deck: the column's weight (0 = off).
    steep_light: f32,
    // The octaves' optical depth in a closed deck: its scale.
    steep_light_scale: f32,
    // The octaves' dimming looking down (0 = off).
    downward_dimming: f32,
    // Padding (0).
    _pad8: f32,
    // The host's scene depth (`FLAG_SCENE_DEPTH`): its projection's term A. A
    // depth d lies at distance B / (d + A) along the view axis (m).
    scene_depth_a: f32,
    // The scene depth's projection term B.
    scene_depth_b: f32,
    // The scene depth of a pixel without geometry (the far plane's: 1 standard, 0
    // reversed Z).
    scene_depth_clear: f32,
    // Saturation of the display image (`post.saturation`; 1 leaves it).
    saturation: f32,
    // The Kuwahara filter's window radius, a fraction of the image's height
    // (`post.kuwahara_radius`; 0 without the filter).
    kuwahara_radius: f32,
    // The rainbow's moisture (`rainbow.moisture`; 0: no rainbow).
    rainbow_moisture: f32,
    // The raindrops' radius (m).
    rainbow_drop_radius: f32,
    // The lens flare's strength (`post.lens_flare_intensity`; 0: none).
    lens_flare_intensity: f32,
    // The world direction of the J2000 equinox (the star catalogue's x axis) at the
    // scene's date and place (0 without them).
    celestial_x: vec3<f32>,
    // The stars' least Gaussian deviation (`night.star_min_radius_px`, pixels).
    star_min_radius: f32,
    // The world direction of the J2000 catalogue's y axis (right ascension 6 h on
    // the equator).
    celestial_y: vec3<f32>,
    // The stars' growth with brightness (`night.star_radius_scale`, pixels).
    star_radius_scale: f32,
    // The world direction of the J2000 north celestial pole.
    celestial_z: vec3<f32>,
    // The bright stars' glare (`night.star_glare_scale`).
    star_glare_scale: f32,
    // The Milky Way's brightness (`night.milky_way_intensity`).
    milky_way_intensity: f32,
    // cos(the moon's angular radius), `night.moon_size` applied.
    moon_cos_radius: f32,
    // The stars' brightness over the real sky's (`night.star_intensity`).
    star_intensity: f32,
    // The rain shafts' extinction in units of heavy rain's (`precipitation.shafts`; 0:
    // none).
    rain_shafts: f32,
    // The lit flash's place (world metres: x, altitude, z; [`crate::lightning`]).
    lightning_position: vec3<f32>,
    // The lit flash's illuminance 1 km from it, in the units of `sun_illuminance` (0:
    // no flash this frame).
    lightning_illuminance: f32,
    // How far the particles have fallen and drifted (m, each within [0,
    // `precip_box`)): they move with it through the box about the camera.
    precip_offset: vec3<f32>,
    // The particles' share drawn (`precipitation.particles`; 0: none).
    precip_density: f32,
    // The particles' velocity (m/s): their fall and the wind's drift.
    precip_velocity: vec3<f32>,
    // The side of the box of particles about the camera (m).
    precip_box: f32,
    // Where a cumulonimbus anvil's top lies downwind of its tower (xz, m at the
    // layer's top; `clouds.anvil_shear_m` along the wind's direction).
    anvil_shear: vec2<f32>,
    // Cumulonimbus anvils on cumulus layers, within [0, 1] (`clouds.anvil`; 0: none).
    anvil: f32,
    // Padding (0).
    _pad9: f32,
    // The main layer's cirrus share, within [0, 1] (`clouds.cirrus`).
    cirrus: f32,
    // Extra layer 1's cirrus share (`[[clouds.layers]] cirrus`; 0 where there is
    // no such layer).
    layer1_cirrus: f32,
    // Extra layer 2's cirrus share.
    layer2_cirrus: f32,
    // Extra layer 3's cirrus share.
    layer3_cirrus: f32,
    // The wind's direction (unit xz, toward which it blows): cirrus fibres lie along
    // it.
    wind_direction: vec2<f32>,
    // How far the wind has carried the cirrus strands along itself (m), wrapped by
    // their period along it (CIRRUS_STRETCH * CIRRUS_SCALE shape periods): the shape
    // offset wraps per axis, which in the wind's stretched frame is no period.
    cirrus_strand_offset: f32,
    // How far the wind has carried the cirrus fibres along itself (m), wrapped by
    // CIRRUS_FIBRE_STRETCH detail periods.
    cirrus_fibre_offset: f32,
    // The wind's offset of the curl noise bending cirrus strands (xz, m), wrapped per
    // axis by CIRRUS_BEND_SCALE curl periods, the period it is read at.
    cirrus_bend_offset: vec2<f32>,
    // How many times longer along the wind than across cellular layers' cells are
    // (1 to CELLULAR_ROLL, from `clouds.cell_rolls`).
    cellular_stretch: f32,
    // How far the wind has carried the cellular layers' cells along itself (m),
    // wrapped by `cellular_stretch` shape periods: whole periods of every layer's
    // read, whose period is the shape's over a power of two.
    cellular_offset: f32,
    // The main layer's cellular share, within [0, 1] (`clouds.cellular`).
    cellular: f32,
    // Extra layer 1's cellular share (`[[clouds.layers]] cellular`; 0 where there
    // is no such layer).
    layer1_cellular: f32,
    // Extra layer 2's cellular share.
    layer2_cellular: f32,
    // Extra layer 3's cellular share.
    layer3_cellular: f32,
    // Close-range detail's strength, within [0, 1] (`clouds.close_detail`; 0: off).
    close_detail: f32,
    // How many times finer than the detail noise close-range detail reads it (an
    // integer, `clouds.close_detail_scale`).
    close_detail_scale: f32,
    // How far from the camera close-range detail reaches (m,
    // `clouds.close_detail_range_m`).
    close_detail_range: f32,
    // The march's step within that range (m, `quality.close_step_m`).
    close_step: f32,
}
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
// Geometry at planet scale in f32: camera rays, ray-sphere intersection in the stable
// quadratic form, altitude without cancellation, and the ray's interval in the cloud layer.
//
// Everything is relative to the point on the planet's surface straight below the camera: the
// planet's centre is at (0, -Rp, 0) in these coordinates and the camera at (0, altitude, 0), so
// no quantity of size Rp is ever subtracted from another of size Rp.

// The view ray through the centre of pixel `pixel` (y down in the image).
fn view_ray(pixel: vec2<u32>) -> vec3<f32> {
    return view_ray_at(vec2<f32>(pixel) + 0.5);
}

// The view ray through the image point `at` (pixels, continuous: pixel p's centre is p + 0.5).
fn view_ray_at(at: vec2<f32>) -> vec3<f32> {
    let size = vec2<f32>(frame.size);
    let ndc = at / size * 2.0 - 1.0;
    let tan_half = frame.tan_half_fov;
    let aspect = frame.aspect;
    let d = frame.camera_forward
        + frame.camera_right * (ndc.x * tan_half * aspect)
        - frame.camera_up * (ndc.y * tan_half);
    return normalize(d);
}

// Roots of |o + t d - centre|^2 = R^2 for a unit `d`, written t^2 + 2 b t + c = 0 with
// b = dot(d, o - centre) and c = |o - centre|^2 - R^2 passed in precomputed (so that the caller
// can form c without cancellation). Returns (t0, t1), t0 <= t1, or (-inf... ) via `hit`.
struct Roots {
    t0: f32,
    t1: f32,
    hit: bool,
}

fn solve_sphere(b: f32, c: f32) -> Roots {
    let disc = b * b - c;
    if disc < 0.0 {
        return Roots(0.0, 0.0, false);
    }
    // Stable form: q = -(b + sign(b) sqrt(disc)); the roots are q and c / q (no subtraction
    // of nearly equal numbers, which would lose the near root at grazing angles).
    let s = sqrt(disc);
    let q = -(b + select(-s, s, b >= 0.0));
    if q == 0.0 {
        return Roots(0.0, 0.0, true);
    }
    let r0 = q;
    let r1 = c / q;
    return Roots(min(r0, r1), max(r0, r1), true);
}

// Intersection of the ray from the camera (altitude `alt`) along unit `d` with the sphere of
// altitude `radius_alt` (radius Rp + radius_alt). c = (alt - r)(alt + r + 2 Rp) exactly.
fn ray_shell(alt: f32, d: vec3<f32>, radius_alt: f32) -> Roots {
    let rp = frame.planet_radius;
    let b = d.y * (alt + rp);
    let c = (alt - radius_alt) * (alt + radius_alt + 2.0 * rp);
    return solve_sphere(b, c);
}

// Altitude of a point given relative to the ground point below the camera:
// |q|^2 - Rp^2 = x^2 + z^2 + y (y + 2 Rp) with q = p + (0, Rp, 0), divided by |q| + Rp.
fn altitude_of(p: vec3<f32>) -> f32 {
    let rp = frame.planet_radius;
    let n = p.x * p.x + p.z * p.z + p.y * (p.y + 2.0 * rp);
    let q = vec3<f32>(p.x, p.y + rp, p.z);
    return n / (length(q) + rp);
}

// Whether the ray from `p` (camera-relative, altitude `alt`) along unit `d` hits the ground.
fn hits_ground(p: vec3<f32>, alt: f32, d: vec3<f32>) -> bool {
    let rp = frame.planet_radius;
    let b = dot(d, vec3<f32>(p.x, p.y + rp, p.z));
    let c = alt * (alt + 2.0 * rp);
    return b < 0.0 && b * b >= c;
}

// Why a ray does or does not march the layer.
const RAY_MARCH: u32 = 0u;
const RAY_MISSES_LAYER: u32 = 1u;
const RAY_HITS_GROUND: u32 = 2u;

struct Interval {
    start: f32,
    length: f32,
    kind: u32,
}

// The part of the view ray inside the shell between altitudes `bottom` and `top`, cut to the
// cut-off distance (thesis alg. 5.1: march min(layer depth, cut-off)). Handles cameras below,
// inside and above the layer (thesis 5.2). Of a ray that passes down through the shell and
// back up, the first part.
fn shell_interval(alt: f32, d: vec3<f32>, bottom: f32, top: f32) -> Interval {
    let cutoff = frame.cutoff_distance;
    let inner = ray_shell(alt, d, bottom);
    let outer = ray_shell(alt, d, top);
    var start = 0.0;
    var end = 0.0;
    if alt < bottom {
        // Below: the ground is inside the inner shell, so a ray that meets it never enters.
        if hits_ground(vec3<f32>(0.0, alt, 0.0), alt, d) {
            return Interval(0.0, 0.0, RAY_HITS_GROUND);
        }
        start = inner.t1;
        end = outer.t1;
    } else if alt <= top {
        end = outer.t1;
        if inner.hit && inner.t0 > 0.0 {
            end = min(end, inner.t0);
        }
    } else {
        if !outer.hit || outer.t1 <= 0.0 {
            return Interval(0.0, 0.0, RAY_MISSES_LAYER);
        }
        start = max(outer.t0, 0.0);
        end = outer.t1;
        if inner.hit && inner.t0 > 0.0 {
            end = min(end, inner.t0);
        }
    }
    let len = min(end - start, cutoff);
    if !(len > 0.0) {
        return Interval(0.0, 0.0, RAY_MISSES_LAYER);
    }
    return Interval(start, len, RAY_MARCH);
}

// The view ray's interval in cloud layer `l`.
fn layer_interval(alt: f32, d: vec3<f32>, l: Layer) -> Interval {
    return shell_interval(alt, d, l.bottom, l.top);
}

// The view ray's interval in the shell that holds every layer (the path tracer's medium,
// and the baselines, which draw one layer).
fn cloud_interval(alt: f32, d: vec3<f32>) -> Interval {
    let span = layers_span();
    return shell_interval(alt, d, span.x, span.y);
}

// The interval of the layer the view ray meets first (the lowest index of equal starts).
fn nearest_layer_interval(alt: f32, d: vec3<f32>) -> Interval {
    var best = layer_interval(alt, d, cloud_layer(0u));
    for (var i = 1u; i < layer_count(); i++) {
        let s = layer_interval(alt, d, cloud_layer(i));
        if s.kind == RAY_MARCH && (best.kind != RAY_MARCH || s.start < best.start) {
            best = s;
        }
    }
    return best;
}

// `ray_shell` from any camera-relative point `p` of altitude `alt`.
fn ray_shell_from(p: vec3<f32>, alt: f32, d: vec3<f32>, radius_alt: f32) -> Roots {
    let rp = frame.planet_radius;
    let b = dot(d, vec3<f32>(p.x, p.y + rp, p.z));
    let c = (alt - radius_alt) * (alt + radius_alt + 2.0 * rp);
    return solve_sphere(b, c);
}
// The physical sky (`atmosphere.sky = "physical"`): Hillaire's lookup tables ("A Scalable
// and Production Ready Sky and Atmosphere Rendering Technique", EGSR 2020) over the air of
// `frame.air_*` (Rayleigh, Mie and ozone; Bruneton 2017's Earth by default).
//
// - transmittance (256x64): transmittance to the top of the atmosphere by radius and cosine
//   of the zenith angle, Bruneton's parametrisation ("Precomputed Atmospheric Scattering",
//   2008, and its 2017 reimplementation). Computed when the air changes.
// - multi-scattering (32x32): Hillaire's Psi_ms by altitude and the sun's zenith cosine: the
//   second order from isotropic scattering over every direction, over 1 - f_ms for the higher
//   orders. Computed when the air changes.
// - sky-view (192x108): the sky's radiance around the camera, by azimuth from the sun and
//   elevation (denser toward the horizon). Every frame: it follows the sun and the camera.
// - aerial perspective (32x32 froxels x 32 slices of 1 km, as a 1024x32 atlas): light
//   scattered and transmitted between the camera and each depth. Every frame.
// - sky ambient (64x2): the cosine-weighted mean radiance of the lower and upper hemispheres
//   seen from the cloud layer's bottom by the cosine of the sun's zenith angle there, the
//   clouds' ambient light under this sky. Computed when the air or the layer changes.
//
// Every table holds light per unit sun illuminance at the top of the atmosphere; the user of
// a value multiplies by `frame.sun_illuminance`. Lengths here are kilometres (the planet's
// radius is exact enough in f32), coefficients per kilometre. The CPU reference integrates the
// same air in f64 directly (crates/reference/src/atmosphere.rs); tests measure these tables
// against it. Tables are rgba32float read with textureLoad and interpolated here, so no
// backend needs filterable float textures.

@group(0) @binding(27) var transmittance_lut_in: texture_2d<f32>;
@group(0) @binding(28) var multiscatter_lut_in: texture_2d<f32>;
@group(0) @binding(29) var sky_view_in: texture_2d<f32>;
@group(0) @binding(30) var aerial_in: texture_2d<f32>;
@group(0) @binding(31) var sky_ambient_in: texture_2d<f32>;
@group(0) @binding(32) var transmittance_lut_out: texture_storage_2d<rgba32float, write>;
@group(0) @binding(33) var multiscatter_lut_out: texture_storage_2d<rgba32float, write>;
@group(0) @binding(34) var sky_view_out: texture_storage_2d<rgba32float, write>;
@group(0) @binding(35) var aerial_out: texture_storage_2d<rgba32float, write>;
@group(0) @binding(36) var sky_ambient_out: texture_storage_2d<rgba32float, write>;

const TRANSMITTANCE_SIZE: vec2<u32> = vec2<u32>(256u, 64u);
const MULTISCATTER_SIZE: vec2<u32> = vec2<u32>(32u, 32u);
const SKY_VIEW_SIZE: vec2<u32> = vec2<u32>(192u, 108u);
const AERIAL_SLICES: u32 = 32u;
const AERIAL_SIDE: u32 = 32u;
const AERIAL_SLICE_KM: f32 = 1.0;
const TRANSMITTANCE_STEPS: u32 = 128u; // even (Simpson)
const MULTISCATTER_DIRECTIONS: u32 = 64u;
const MULTISCATTER_STEPS: u32 = 32u;
const SKY_VIEW_STEPS: u32 = 48u;
const AMBIENT_DIRECTIONS: u32 = 64u;
const AMBIENT_STEPS: u32 = 24u;
const SKY_AMBIENT_SUNS: u32 = 64u;

fn physical_sky() -> bool {
    return (frame.flags & FLAG_PHYSICAL_SKY) != 0u;
}

// Radii (km) of the ground and of the top of the atmosphere.
fn air_bottom() -> f32 {
    return frame.planet_radius * 1e-3;
}

fn air_top() -> f32 {
    return (frame.planet_radius + frame.air_thickness) * 1e-3;
}

// The air at altitude `h_km`: Rayleigh scattering (rgb), Mie scattering and total extinction
// (rgb), per km.
struct AirSample {
    rayleigh: vec3<f32>,
    mie: f32,
    extinction: vec3<f32>,
}

fn air_at(h_km: f32) -> AirSample {
    let h = max(h_km, 0.0) * 1000.0;
    let rayleigh_density = exp(-h / frame.rayleigh_scale_height);
    let mie_density = exp(-h / frame.mie_scale_height);
    let ozone_density = max(1.0 - abs(h - frame.ozone_center) / (0.5 * frame.ozone_width), 0.0);
    let rayleigh = frame.rayleigh_scattering * (rayleigh_density * 1000.0);
    let mie = frame.mie_scattering * mie_density * 1000.0;
    let mie_extinction = (frame.mie_scattering + frame.mie_absorption) * mie_density * 1000.0;
    let ozone = frame.ozone_absorption * (ozone_density * 1000.0);
    return AirSample(rayleigh, mie, rayleigh + vec3<f32>(mie_extinction) + ozone);
}

// r^2 (mu^2 - 1) + R^2 for the sphere of radius R, with R^2 - r^2 formed as (R - r)(R + r) so
// that it keeps its digits when r is close to R.
fn sphere_discriminant(r: f32, mu: f32, radius: f32) -> f32 {
    return (radius - r) * (radius + r) + r * r * mu * mu;
}

// Distance from radius `r` along a direction of zenith cosine `mu` to the top of the air.
fn distance_to_top(r: f32, mu: f32) -> f32 {
    return max(-r * mu + sqrt(max(sphere_discriminant(r, mu, air_top()), 0.0)), 0.0);
}

// Whether that ray meets the ground, and how far away.
fn meets_ground(r: f32, mu: f32) -> bool {
    return mu < 0.0 && sphere_discriminant(r, mu, air_bottom()) >= 0.0;
}

fn distance_to_ground(r: f32, mu: f32) -> f32 {
    return max(-r * mu - sqrt(max(sphere_discriminant(r, mu, air_bottom()), 0.0)), 0.0);
}

// Radius after `t` km from radius `r` along zenith cosine `mu`.
fn radius_after(r: f32, mu: f32, t: f32) -> f32 {
    return sqrt(max(r * r + t * t + 2.0 * r * mu * t, 0.0));
}

// Bilinear interpolation of table `lut` of `size` texels at `x` in [0, 1]^2, where texel i
// holds the value at x = i / (size - 1) (so both ends are sampled exactly).
fn lut_bilinear(lut: texture_2d<f32>, x: vec2<f32>, size: vec2<u32>) -> vec4<f32> {
    let last = vec2<f32>(size - 1u);
    let f = clamp(x, vec2<f32>(0.0), vec2<f32>(1.0)) * last;
    let i0 = min(vec2<u32>(floor(f)), size - 1u);
    let i1 = min(i0 + 1u, size - 1u);
    let w = f - vec2<f32>(i0);
    let a = mix(textureLoad(lut, vec2<u32>(i0.x, i0.y), 0), textureLoad(lut, vec2<u32>(i1.x, i0.y), 0), w.x);
    let b = mix(textureLoad(lut, vec2<u32>(i0.x, i1.y), 0), textureLoad(lut, vec2<u32>(i1.x, i1.y), 0), w.x);
    return mix(a, b, w.y);
}

// The transmittance table's coordinates of (r, mu): x from the distance to the top between
// its least and greatest at this radius, y from the distance to the horizon (Bruneton).
fn transmittance_coords(r: f32, mu: f32) -> vec2<f32> {
    let bottom = air_bottom();
    let top = air_top();
    let h = sqrt(max((top - bottom) * (top + bottom), 0.0));
    let rho = sqrt(max((r - bottom) * (r + bottom), 0.0));
    let d = distance_to_top(r, mu);
    let d_min = top - r;
    let d_max = rho + h;
    return vec2<f32>((d - d_min) / max(d_max - d_min, 1e-6), rho / h);
}

// The inverse: (r, mu) of table coordinates `x`.
fn transmittance_r_mu(x: vec2<f32>) -> vec2<f32> {
    let bottom = air_bottom();
    let top = air_top();
    let h = sqrt(max((top - bottom) * (top + bottom), 0.0));
    let rho = h * x.y;
    let r = sqrt(rho * rho + bottom * bottom);
    let d_min = top - r;
    let d_max = rho + h;
    let d = d_min + x.x * (d_max - d_min);
    var mu = 1.0;
    if d > 0.0 {
        mu = clamp((h * h - rho * rho - d * d) / (2.0 * r * d), -1.0, 1.0);
    }
    return vec2<f32>(r, mu);
}

// Transmittance from radius r along zenith cosine mu to the top of the air (the ground
// ignored: the caller decides whether the ray meets it).
fn transmittance_to_top(r: f32, mu: f32) -> vec3<f32> {
    return lut_bilinear(transmittance_lut_in, transmittance_coords(r, mu), TRANSMITTANCE_SIZE).rgb;
}

// The sun's light left at radius r for a sun of zenith cosine mu_s: 0 behind the planet.
fn sun_transmittance(r: f32, mu_s: f32) -> vec3<f32> {
    if meets_ground(r, mu_s) {
        return vec3<f32>(0.0);
    }
    return transmittance_to_top(r, mu_s);
}

// Psi_ms at radius r for a sun of zenith cosine mu_s.
fn multiscatter(r: f32, mu_s: f32) -> vec3<f32> {
    let x = vec2<f32>(mu_s * 0.5 + 0.5, (r - air_bottom()) / (air_top() - air_bottom()));
    return lut_bilinear(multiscatter_lut_in, x, MULTISCATTER_SIZE).rgb;
}

fn phase_rayleigh(cos_theta: f32) -> f32 {
    return 3.0 / (16.0 * PI) * (1.0 + cos_theta * cos_theta);
}

// Cornette-Shanks, the Mie phase function of Hillaire 2020 and Bruneton 2017.
fn phase_cornette_shanks_air(cos_theta: f32, g: f32) -> f32 {
    let g2 = g * g;
    return 3.0 / (8.0 * PI) * (1.0 - g2) * (1.0 + cos_theta * cos_theta)
        / ((2.0 + g2) * pow(max(1.0 + g2 - 2.0 * g * cos_theta, 1e-6), 1.5));
}

// Direction k of n spread evenly over the sphere (spherical Fibonacci), as the reference.
fn fibonacci_direction(k: u32, n: u32) -> vec3<f32> {
    let golden = PI * (3.0 - sqrt(5.0));
    let z = 1.0 - (2.0 * f32(k) + 1.0) / f32(n);
    let s = sqrt(max(1.0 - z * z, 0.0));
    let phi = golden * f32(k);
    return vec3<f32>(s * cos(phi), z, s * sin(phi));
}

// The sun's part of the light leaving the lit, diffuse ground where the direction to the sun
// has zenith cosine mu_s: albedo / pi times the sun's cosine and its light left there. The
// multi-scattering table takes the ground as lit by the sun alone (Hillaire 2020, 5.5.2);
// the sky's part is `ground_radiance`'s (wgsl/ground.wgsl).
fn ground_radiance_sun(mu_s: f32) -> vec3<f32> {
    return frame.ground_albedo / PI * max(mu_s, 0.0) * sun_transmittance(air_bottom() + 0.001, mu_s);
}

// In-scattered light and transmittance along a ray from `origin` (km, planet centre at the
// origin) along unit `d` for `distance_km` km in `steps` segments whose ends go as the square of
// their index (short near the camera, where the air is dense), the sun along unit `sun`. A
// caller whose ray ends on the ground adds the ground's light times the transmittance
// (`with_ground`).
struct Scattered {
    radiance: vec3<f32>,
    transmittance: vec3<f32>,
}

fn integrate_air(origin: vec3<f32>, d: vec3<f32>, distance_km: f32, steps: u32, sun: vec3<f32>) -> Scattered {
    let cos_theta = dot(d, sun);
    let phase_r = phase_rayleigh(cos_theta);
    let phase_m = phase_cornette_shanks_air(cos_theta, frame.mie_g);
    var radiance = vec3<f32>(0.0);
    var tau = vec3<f32>(0.0);
    var t0 = 0.0;
    for (var i = 0u; i < steps; i++) {
        let s1 = f32(i + 1u) / f32(steps);
        let t1 = distance_km * s1 * s1;
        let dt = t1 - t0;
        let p = origin + d * (0.5 * (t0 + t1));
        let r = length(p);
        let up = p / r;
        let mu_s = dot(up, sun);
        let air = air_at(r - air_bottom());
        // Transmittance to the segment's middle: the depth so far plus half the segment.
        let t_view = exp(-(tau + 0.5 * air.extinction * dt));
        let t_sun = sun_transmittance(r, mu_s);
        let ms = multiscatter(r, mu_s);
        let inscatter = t_sun * (air.rayleigh * phase_r + vec3<f32>(air.mie * phase_m))
            + ms * (air.rayleigh + vec3<f32>(air.mie));
        radiance += t_view * inscatter * dt;
        tau += air.extinction * dt;
        t0 = t1;
    }
    return Scattered(radiance, exp(-tau));
}

// The light of `integrate_air`'s ray with the lit ground (sun and sky) at its end through the
// air when `ground` (the ray ends there).
fn with_ground(s: Scattered, origin: vec3<f32>, d: vec3<f32>, distance_km: f32, sun: vec3<f32>,
               ground: bool) -> vec3<f32> {
    if !ground {
        return s.radiance;
    }
    let end = origin + d * distance_km;
    return s.radiance + s.transmittance * ground_radiance(dot(normalize(end), sun));
}

// The ray from `origin` along `d`: how far it goes in the air and whether it ends on the
// ground; (0, false) for a ray that misses the air.
fn air_ray_end(origin: vec3<f32>, d: vec3<f32>) -> vec2<f32> {
    let r = length(origin);
    let mu = dot(origin, d) / r;
    if meets_ground(r, mu) {
        return vec2<f32>(distance_to_ground(r, mu), 1.0);
    }
    if r > air_top() {
        // From outside the air (not a case the scenes reach): no light gathered.
        return vec2<f32>(0.0, 0.0);
    }
    return vec2<f32>(distance_to_top(r, mu), 0.0);
}

// The camera's place in the air: the planet's centre straight below it.
fn camera_air_origin() -> vec3<f32> {
    return vec3<f32>(0.0, air_bottom() + max(frame.camera_position.y, 0.0) * 1e-3, 0.0);
}

@compute @workgroup_size(8, 8, 1)
fn transmittance_lut(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= TRANSMITTANCE_SIZE) {
        return;
    }
    let rm = transmittance_r_mu(vec2<f32>(id.xy) / vec2<f32>(TRANSMITTANCE_SIZE - 1u));
    // Composite Simpson rule (as the reference): the densities are smooth, and a horizontal
    // ray's steps of several kilometres are long against the Rayleigh scale height.
    let dt = distance_to_top(rm.x, rm.y) / f32(TRANSMITTANCE_STEPS);
    var sum = vec3<f32>(0.0);
    for (var i = 0u; i <= TRANSMITTANCE_STEPS; i++) {
        var w = select(2.0, 4.0, (i & 1u) == 1u);
        if i == 0u || i == TRANSMITTANCE_STEPS {
            w = 1.0;
        }
        let r = radius_after(rm.x, rm.y, dt * f32(i));
        sum += w * air_at(r - air_bottom()).extinction;
    }
    textureStore(transmittance_lut_out, id.xy, vec4<f32>(exp(-sum * (dt / 3.0)), 1.0));
}

@compute @workgroup_size(8, 8, 1)
fn multiscatter_lut(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= MULTISCATTER_SIZE) {
        return;
    }
    let x = vec2<f32>(id.xy) / vec2<f32>(MULTISCATTER_SIZE - 1u);
    let mu_s = x.x * 2.0 - 1.0;
    let r = air_bottom() + x.y * (air_top() - air_bottom());
    let origin = vec3<f32>(0.0, r, 0.0);
    let sun = vec3<f32>(sqrt(max(1.0 - mu_s * mu_s, 0.0)), mu_s, 0.0);
    let isotropic = 1.0 / (4.0 * PI);
    var l2 = vec3<f32>(0.0);
    var f_ms = vec3<f32>(0.0);
    for (var k = 0u; k < MULTISCATTER_DIRECTIONS; k++) {
        let d = fibonacci_direction(k, MULTISCATTER_DIRECTIONS);
        let end = air_ray_end(origin, d);
        let dt = end.x / f32(MULTISCATTER_STEPS);
        var tau = vec3<f32>(0.0);
        for (var i = 0u; i < MULTISCATTER_STEPS; i++) {
            let p = origin + d * (dt * (f32(i) + 0.5));
            let rp = length(p);
            let air = air_at(rp - air_bottom());
            let t = exp(-(tau + 0.5 * air.extinction * dt));
            let s = air.rayleigh + vec3<f32>(air.mie);
            l2 += t * s * isotropic * sun_transmittance(rp, dot(p / rp, sun)) * dt;
            f_ms += t * s * dt;
            tau += air.extinction * dt;
        }
        if end.y > 0.5 {
            let g = origin + d * end.x;
            l2 += exp(-tau) * ground_radiance_sun(dot(normalize(g), sun));
        }
    }
    let w = 1.0 / f32(MULTISCATTER_DIRECTIONS);
    let psi = (l2 * w) / max(vec3<f32>(1.0) - f_ms * w, vec3<f32>(1e-6));
    textureStore(multiscatter_lut_out, id.xy, vec4<f32>(psi, 1.0));
}

// The sky-view table's elevation of coordinate v for a camera whose horizon lies at
// elevation `horizon` (radians, <= 0): v = 0.5 is the horizon, the texels crowd toward it as
// the square of the distance in v.
fn sky_view_elevation(v: f32, horizon: f32) -> f32 {
    if v >= 0.5 {
        let a = 2.0 * v - 1.0;
        return horizon + (0.5 * PI - horizon) * a * a;
    }
    let a = 1.0 - 2.0 * v;
    return horizon - (horizon + 0.5 * PI) * a * a;
}

fn sky_view_v(elevation: f32, horizon: f32) -> f32 {
    if elevation >= horizon {
        return 0.5 + 0.5 * sqrt(saturate((elevation - horizon) / (0.5 * PI - horizon)));
    }
    return 0.5 - 0.5 * sqrt(saturate((horizon - elevation) / (horizon + 0.5 * PI)));
}

// Elevation of the horizon seen from radius r.
fn horizon_elevation(r: f32) -> f32 {
    return -acos(clamp(air_bottom() / r, -1.0, 1.0));
}

// The sun's azimuth about the zenith (radians, from +x toward +z).
fn sun_azimuth() -> f32 {
    let s = frame.sun_direction;
    return atan2(s.z, s.x);
}

@compute @workgroup_size(8, 8, 1)
fn sky_view_lut(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= SKY_VIEW_SIZE) {
        return;
    }
    let x = vec2<f32>(id.xy) / vec2<f32>(SKY_VIEW_SIZE - 1u);
    let origin = camera_air_origin();
    let elevation = sky_view_elevation(x.y, horizon_elevation(origin.y));
    // Azimuth relative to the sun in [0, pi]: the sky is symmetric about the sun's vertical.
    let phi = sun_azimuth() + x.x * PI;
    let d = vec3<f32>(cos(elevation) * cos(phi), sin(elevation), cos(elevation) * sin(phi));
    textureStore(sky_view_out, id.xy, vec4<f32>(sky_along(origin, d), 1.0));
}

// The sky's radiance (per unit sun illuminance) seen from `origin` (km, planet centre at the
// origin) along unit `d`, the lit ground included where the ray meets it: SKY_VIEW_STEPS of
// `integrate_air` to where the ray leaves the air. The sky-view table's texels from the
// camera, and the path tracer's environment from a path's last collision.
fn sky_along(origin: vec3<f32>, d: vec3<f32>) -> vec3<f32> {
    let end = air_ray_end(origin, d);
    let sun = frame.sun_direction;
    let s = integrate_air(origin, d, end.x, SKY_VIEW_STEPS, sun);
    return with_ground(s, origin, d, end.x, sun, end.y > 0.5);
}

// The sky's radiance (per unit sun illuminance) seen from camera-relative `rel` (m) along
// unit `d` (`sky_along` from that point; `sun_through_air`'s coordinates).
fn sky_from(rel: vec3<f32>, d: vec3<f32>) -> vec3<f32> {
    return sky_along(vec3<f32>(rel.x, rel.y + frame.planet_radius, rel.z) * 1e-3, d);
}

// The sky's radiance (per unit sun illuminance) seen from the camera along unit `d`: the
// sky-view table, ground included.
fn sky_view(d: vec3<f32>) -> vec3<f32> {
    let origin = camera_air_origin();
    let elevation = asin(clamp(d.y, -1.0, 1.0));
    var delta = atan2(d.z, d.x) - sun_azimuth();
    delta = abs(delta - 2.0 * PI * round(delta / (2.0 * PI)));
    let x = vec2<f32>(delta / PI, sky_view_v(elevation, horizon_elevation(origin.y)));
    return lut_bilinear(sky_view_in, x, SKY_VIEW_SIZE).rgb;
}

// The view direction through the centre of aerial froxel column `c` (of AERIAL_SIDE^2).
fn aerial_ray(c: vec2<u32>) -> vec3<f32> {
    let ndc = (vec2<f32>(c) + 0.5) / f32(AERIAL_SIDE) * 2.0 - 1.0;
    let tan_half = frame.tan_half_fov;
    let aspect = frame.aspect;
    return normalize(frame.camera_forward
        + frame.camera_right * (ndc.x * tan_half * aspect)
        - frame.camera_up * (ndc.y * tan_half));
}

// Froxel column (x, y) marches its 32 slices in order; slice z is stored at texel
// (z * 32 + x, y), holding the light scattered toward the camera over the first (z + 1) km
// (rgb) and the mean transmittance over them (a).
@compute @workgroup_size(8, 8, 1)
fn aerial_perspective(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= vec2<u32>(AERIAL_SIDE)) {
        return;
    }
    let d = aerial_ray(id.xy);
    let origin = camera_air_origin();
    let end = air_ray_end(origin, d);
    let sun = frame.sun_direction;
    let cos_theta = dot(d, sun);
    let phase_r = phase_rayleigh(cos_theta);
    let phase_m = phase_cornette_shanks_air(cos_theta, frame.mie_g);
    var radiance = vec3<f32>(0.0);
    var tau = vec3<f32>(0.0);
    // Four midpoint steps a slice, stopping where the ray leaves the air or meets the ground.
    let sub = 4u;
    for (var z = 0u; z < AERIAL_SLICES; z++) {
        for (var k = 0u; k < sub; k++) {
            let t0 = AERIAL_SLICE_KM * (f32(z) + f32(k) / f32(sub));
            let dt = max(min(AERIAL_SLICE_KM / f32(sub), end.x - t0), 0.0);
            let p = origin + d * (t0 + 0.5 * dt);
            let r = length(p);
            let mu_s = dot(p / r, sun);
            let air = air_at(r - air_bottom());
            let t_view = exp(-(tau + 0.5 * air.extinction * dt));
            let inscatter = sun_transmittance(r, mu_s) * (air.rayleigh * phase_r + vec3<f32>(air.mie * phase_m))
                + multiscatter(r, mu_s) * (air.rayleigh + vec3<f32>(air.mie));
            radiance += t_view * inscatter * dt;
            tau += air.extinction * dt;
        }
        let t = exp(-tau);
        textureStore(aerial_out, vec2<u32>(z * AERIAL_SIDE + id.x, id.y),
                     vec4<f32>(radiance, (t.r + t.g + t.b) / 3.0));
    }
}

// Aerial perspective at pixel `pixel` for depth `depth_m`: (in-scattered light per unit sun
// illuminance, mean transmittance), interpolated in the froxel grid and between slices (0 m
// is no air: nothing scattered, transmittance 1).
fn aerial(pixel: vec2<u32>, depth_m: f32) -> vec4<f32> {
    let uv = (vec2<f32>(pixel) + 0.5) / vec2<f32>(frame.size);
    // Froxel centres sit at (c + 0.5) / side.
    let f = clamp(uv * f32(AERIAL_SIDE) - 0.5, vec2<f32>(0.0), vec2<f32>(f32(AERIAL_SIDE - 1u)));
    let c0 = min(vec2<u32>(floor(f)), vec2<u32>(AERIAL_SIDE - 1u));
    let c1 = min(c0 + 1u, vec2<u32>(AERIAL_SIDE - 1u));
    let w = f - vec2<f32>(c0);
    // Slice z holds depth (z + 1) km; depth 0 is the camera.
    let s = clamp(depth_m * 1e-3 / AERIAL_SLICE_KM, 0.0, f32(AERIAL_SLICES));
    let z1 = min(u32(ceil(s)), AERIAL_SLICES);
    let z0 = select(0u, z1 - 1u, z1 > 0u);
    let ws = s - f32(z0);
    var near = vec4<f32>(0.0, 0.0, 0.0, 1.0);
    if z0 > 0u {
        near = aerial_texel(c0, c1, w, z0 - 1u);
    }
    var far = vec4<f32>(0.0, 0.0, 0.0, 1.0);
    if z1 > 0u {
        far = aerial_texel(c0, c1, w, z1 - 1u);
    }
    return mix(near, far, ws);
}

fn aerial_texel(c0: vec2<u32>, c1: vec2<u32>, w: vec2<f32>, z: u32) -> vec4<f32> {
    let o = z * AERIAL_SIDE;
    let a = mix(textureLoad(aerial_in, vec2<u32>(o + c0.x, c0.y), 0), textureLoad(aerial_in, vec2<u32>(o + c1.x, c0.y), 0), w.x);
    let b = mix(textureLoad(aerial_in, vec2<u32>(o + c0.x, c1.y), 0), textureLoad(aerial_in, vec2<u32>(o + c1.x, c1.y), 0), w.x);
    return mix(a, b, w.y);
}

// Texel (i, j) holds the cosine-weighted mean radiance of the lower (j = 0, from below) or
// upper (j = 1, from above) hemisphere seen from the cloud layer's bottom, sky and lit ground,
// per unit sun illuminance, for a sun of zenith cosine t |t| there (t = 2 i / 63 - 1,
// sky_ambient_x): the irradiance through a horizontal surface over pi, the clouds' ambient
// light. The diffuse light inside a layer is fed by the fluxes through its boundaries (as the
// octaves' mu0 says for the sun), so the light near the horizon, which crosses the layer
// lengthwise, counts for little. With the mean over the whole sphere a dawn's deck was lit by
// the glow along the horizon: 2.3 times brighter than the path tracer (docs/fit). A uniform
// environment gives the same ambient either way.
// Both hemispheres from the bottom: the light from above includes the air between the
// layer's clouds, which the sun lights too (the path tracer's paths see the sky from where
// they leave the clouds, inside the layer). Under a low sun that air's light is the reddened
// sun's: against the path tracer (256 paths a pixel, its sky term alone, split by the
// direction the paths left in) the light from above of `dawn`'s dense deck was 0.92 / 0.87 /
// 0.79 (red / green / blue) of the upper hemisphere seen from the layer's top, `sunset`'s
// 1.51 / 1.38 / 1.17. Seen from the bottom, the presets' mean FLIP went from 0.0449 to 0.0437
// (`dawn` 0.058 to 0.052, `noon` 0.043 to 0.040; from half-way up, 0.0441) and the training
// scenes' from 0.0446 to 0.0444. The lower hemisphere stays at the bottom: seen from half-way
// up as well, `dawn`'s deck was 1.10 times the truth's brightness (FLIP 0.080).
// By the sun's angle, not for the camera's place: the sun's zenith angle changes by a degree
// every 111 km, and a twilight sky by much more than that degree's share of its light:
// computed above the camera, the ambient of `dusk`'s clouds toward the afterglow, tens of
// kilometres off, was a third to a half too dark against the path tracer's (whose paths see
// the sky from where they leave the clouds). The table so depends on the air and the layer's
// bottom alone.
@compute @workgroup_size(8, 8, 1)
fn sky_ambient(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= SKY_AMBIENT_SUNS || id.y >= 2u {
        return;
    }
    let top = id.y == 1u;
    let t = f32(id.x) / f32(SKY_AMBIENT_SUNS - 1u) * 2.0 - 1.0;
    let mu_s = sign(t) * t * t;
    let sun = vec3<f32>(sqrt(max(1.0 - mu_s * mu_s, 0.0)), mu_s, 0.0);
    let origin = vec3<f32>(0.0, air_bottom() + frame.cloud_bottom * 1e-3, 0.0);
    var sum = vec3<f32>(0.0);
    var weights = 0.0;
    // Fibonacci directions run from the zenith down: the first half is the upper hemisphere.
    let half = AMBIENT_DIRECTIONS / 2u;
    let first = select(half, 0u, top);
    for (var k = first; k < first + half; k++) {
        let d = fibonacci_direction(k, AMBIENT_DIRECTIONS);
        let end = air_ray_end(origin, d);
        let s = integrate_air(origin, d, end.x, AMBIENT_STEPS, sun);
        let w = abs(d.y);
        sum += w * with_ground(s, origin, d, end.x, sun, end.y > 0.5);
        weights += w;
    }
    textureStore(sky_ambient_out, id.xy, vec4<f32>(sum / weights, 1.0));
}

// The sun's light (per unit illuminance at the top of the air) reaching a cloud sample at
// `rel` (m, relative to the ground below the camera): 1 without the physical sky.
fn sun_through_air(rel: vec3<f32>) -> vec3<f32> {
    if !physical_sky() {
        return vec3<f32>(1.0);
    }
    let q = vec3<f32>(rel.x, rel.y + frame.planet_radius, rel.z) * 1e-3;
    let r = length(q);
    return sun_transmittance(r, dot(q / r, frame.sun_direction));
}

// The sky-ambient table's column coordinate (0 to 1) of a sun of zenith cosine `mu`: the
// square root of |mu|, so that the columns lie densest at the horizon, where the sky's light
// changes fastest with the sun's angle (texel i holds mu = t |t|, t = 2 i / 63 - 1: 0.7
// degrees apart at a sun 2 degrees up, 1.8 with mu spread evenly). Linear in mu, the table
// blended a dawn's sun 2 degrees up with 0.9 and 2.7 degrees: `dawn` measured FLIP 0.052
// against 0.049 now (the presets' mean 0.0437 against 0.0434; the training scenes, none under
// a sun below 3 degrees in the physical sky, unchanged).
fn sky_ambient_x(mu: f32) -> f32 {
    return 0.5 + 0.5 * sign(mu) * sqrt(abs(mu));
}

// The clouds' ambient light at height fraction `h` of the main layer under the physical sky,
// at camera-relative `rel` (m): the sky-ambient table at the sun's zenith cosine there, times
// the sun's illuminance and the ambient strength.
fn sky_ambient_light(h: f32, rel: vec3<f32>) -> vec3<f32> {
    let q = vec3<f32>(rel.x, rel.y + frame.planet_radius, rel.z);
    let x = sky_ambient_x(dot(normalize(q), frame.sun_direction));
    let size = vec2<u32>(SKY_AMBIENT_SUNS, 2u);
    let bottom = lut_bilinear(sky_ambient_in, vec2<f32>(x, 0.0), size).rgb;
    let top = lut_bilinear(sky_ambient_in, vec2<f32>(x, 1.0), size).rgb;
    return mix(bottom, top, h) * frame.sun_illuminance * frame.ambient_strength;
}
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
// Light: phase functions, the light march toward the sun, multiple-scattering octaves,
// ambient and precipitation darkening (thesis 5.5, Hillaire 2016, Wrenninge 2013).

// Henyey-Greenstein (thesis eq. 5.4), normalised over the sphere.
fn phase_hg(cos_theta: f32, g: f32) -> f32 {
    let g2 = g * g;
    let denom = max(1.0 + g2 - 2.0 * g * cos_theta, 1e-6);
    return (1.0 - g2) / (4.0 * PI * denom * sqrt(denom));
}

// Cornette-Shanks (thesis eq. 5.5).
fn phase_cornette_shanks(cos_theta: f32, g: f32) -> f32 {
    let g2 = g * g;
    let denom = max(1.0 + g2 - 2.0 * g * cos_theta, 1e-6);
    return 3.0 * (1.0 - g2) * (1.0 + cos_theta * cos_theta)
        / (8.0 * PI * (2.0 + g2) * denom * sqrt(denom));
}

// The scene's phase model with eccentricities scaled by `scale` (c^i for octave i).
fn phase(cos_theta: f32, scale: f32) -> f32 {
    let g = frame.phase_g * scale;
    switch frame.phase_model {
        case PHASE_TWO_LOBE_HG: {
            // Two lobes for the silver lining (seed 001): forward g and backward g2.
            let g2 = frame.phase_g2 * scale;
            return mix(phase_hg(cos_theta, g), phase_hg(cos_theta, g2), frame.phase_blend);
        }
        case PHASE_CORNETTE_SHANKS: {
            return phase_cornette_shanks(cos_theta, g);
        }
        default: {
            return phase_hg(cos_theta, g);
        }
    }
}

// Optical depth toward the sun from `rel` (camera-relative position, world position `p`) in
// layer `l`: `light_steps` segments of exponentially growing length (thesis 5.5.2), density
// sampled at each segment's midpoint; the march ends where it leaves the layer. The layers
// above add `optical_depth_above`.
// Toward a sun a few degrees up the light crosses tens of kilometres of layer, which the
// march does not see: far_optical_depth stands in for that stretch.
fn sun_optical_depth(rel: vec3<f32>, p: vec3<f32>, l: Layer, counters: ptr<function, Counters>) -> f32 {
    return segment_optical_depth(rel, p, l, frame.sun_direction, frame.first_light_step,
                                 frame.light_step_growth, frame.light_steps, true, counters);
}

// The sun ray's optical depth through the layers above layer `l`: each one it crosses adds
// ABOVE_SAMPLES midpoint samples of equal stretches of the crossing, the Beer shadow of a high
// deck on the clouds below, which the few kilometres of the light march would not reach. One
// sample at the crossing's middle missed a stratus deck, whose cloud fills the lowest quarter
// of its layer: under `weather fog`'s deck the fog measured FLIP 0.230 (2.78 times the truth's
// brightness where dense), with four samples 0.149 (1.34), `weather mist` 0.095 and 0.074;
// with eight 0.161 and 0.068 (these two states chose the count: docs/fit-log.md).
const ABOVE_SAMPLES: u32 = 4u;

fn optical_depth_above(rel: vec3<f32>, p: vec3<f32>, l: Layer, counters: ptr<function, Counters>) -> f32 {
    let sun = frame.sun_direction;
    let sigma_t = frame.scattering + frame.absorption;
    var tau = 0.0;
    let alt0 = altitude_of(rel);
    for (var j = 0u; j < layer_count(); j++) {
        let above = cloud_layer(j);
        if above.bottom <= l.top {
            continue;
        }
        // From below both spheres, the ray leaves each through its far root.
        let enter = ray_shell_from(rel, alt0, sun, above.bottom);
        let exit = ray_shell_from(rel, alt0, sun, above.top);
        if !enter.hit || !exit.hit || !(exit.t1 > enter.t1) || enter.t1 <= 0.0 {
            continue;
        }
        let step = (exit.t1 - enter.t1) / f32(ABOVE_SAMPLES);
        for (var k = 0u; k < ABOVE_SAMPLES; k++) {
            let s = enter.t1 + (f32(k) + 0.5) * step;
            (*counters).light += 1u;
            tau += layer_density(p + sun * s, altitude_of(rel + sun * s), above, counters)
                * sigma_t * step;
        }
    }
    return tau;
}

// Optical depth from `rel` (world position `p`) along unit `d` in layer `l`: `steps` segments,
// the first `first` metres long, each `growth` times the one before, density sampled at each
// segment's midpoint (its detail erosion only if `with_detail`), one light sample each; the
// march ends where it leaves the layer. The sun's light march and the octaves' column.
fn segment_optical_depth(rel: vec3<f32>, p: vec3<f32>, l: Layer, d: vec3<f32>, first: f32,
                         growth: f32, steps: u32, with_detail: bool,
                         counters: ptr<function, Counters>) -> f32 {
    let sigma_t = frame.scattering + frame.absorption;
    var seg = first;
    var dist = 0.0;
    var tau = 0.0;
    for (var i = 0u; i < steps; i++) {
        let s = dist + 0.5 * seg;
        let alt = altitude_of(rel + d * s);
        if alt > l.top || alt < l.bottom {
            break;
        }
        (*counters).light += 1u;
        tau += layer_density_with(p + d * s, alt, l, with_detail, counters) * sigma_t * seg;
        dist += seg;
        seg *= growth;
    }
    return tau;
}

// The octaves' column in a closed deck (octave_optical_depth): three equal steps straight up
// from the sample to the layer's top, of the density without its detail erosion, which shapes
// edges metres across while multiply scattered light gathers over kilometres. Four steps
// fitted a training mean of 0.0446 against three's 0.0448 (`storm` 0.042 against 0.044) for
// 10.5% more march time on `storm` against 7.5% (lavapipe, 256x144).
const COLUMN_STEPS: u32 = 3u;

// The octaves' optical depth at a sample of layer `l` whose sun ray has optical depth `tau`.
// In a closed deck the truth's multiply scattered sun light follows the cloud above the
// sample (its height in the layer, correlation 0.92 over `storm`'s upper third against the
// path tracer; the vertical optical depth above it, -0.89), which the slant sun ray, kilometres
// long through a thick deck, passes by: over that part of `storm` the sun ray's optical depth
// was 100-112 at every pixel while the truth's light varied three times as much as the
// march's. Deep in a thick plane-parallel layer the diffuse light falls with the optical depth
// from the top (two-stream theory, Meador and Weaver 1980), whatever the sun's angle once the
// direct beam is spent: diffuse light crosses a slab along an effective path about 1.66 times
// the vertical (the diffusivity factor, Elsasser 1942). So in a deck the octaves see the
// vertical column above the sample, to the layer's top, times s (steep_light_scale, fitted: 1.5),
// mixed in with weight m w (m: steep_light, fitted: 1, the column and the layers above alone;
// 0 = off), w = (coverage - 0.8) / 0.1 clamped, the layer's weight as a closed deck (set by
// hand: `storm`'s 0.9 gets 1, `stratocumulus-overcast`'s 0.8 none). The layers above the deck keep their part
// of `tau` (`above`): the column stands in for the deck's own cloud alone (without them the
// mist under `weather mist`'s cumulus took no shade from them in its octaves: FLIP 0.098, with
// them 0.095, at one sample per layer above). Decks only: broken cloud's light comes in
// through the sides as well (side light). Against the 8192-path truths (docs/fit) the column
// took the training mean from 0.0525 to 0.0448 and `storm` from 0.055 to 0.044; over mu0 (the
// direct beam's slant) it fitted 0.0522 (the storm deck under a 25-degree sun 0.047 to 0.102),
// over mu0^(1/2) 0.0477 (both with four steps). A steeper march of two steps toward
// normalize(sun + up), scaled by a fitted 3.6 for the column it did not reach, had fitted
// 0.0525 (`storm` 0.055).
fn octave_optical_depth(rel: vec3<f32>, p: vec3<f32>, l: Layer, tau: f32, above: f32,
                        counters: ptr<function, Counters>) -> f32 {
    let w = saturate((l.coverage - 0.8) / 0.1);
    let m = frame.steep_light * w;
    // Not below a weight of 1e-3: a layer of coverage 0.8 (`stratocumulus-overcast`'s) got a
    // weight of about 1e-7 from f32 rounding on lavapipe, and the march's work for nothing.
    if w < 1e-3 || m <= 0.0 || frame.light_steps == 0u {
        return tau;
    }
    let up = normalize(vec3<f32>(rel.x, rel.y + frame.planet_radius, rel.z));
    // From inside the layer's top sphere the ray leaves it through the far root.
    let top = ray_shell_from(rel, altitude_of(rel), up, l.top);
    let len = select(0.0, top.t1, top.hit && top.t1 > 0.0);
    let column = segment_optical_depth(rel, p, l, up, len / f32(COLUMN_STEPS), 1.0,
                                       COLUMN_STEPS, false, counters);
    return mix(tau, frame.steep_light_scale * column + above, m);
}

// The far shadow: optical depth of the sun ray's stretch inside layer `l` beyond the light
// march's reach (its segments' total length), taken statistically instead of sampled. Broken
// cloud along a line is a binary Markov mixture (Levermore and Pomraning 1986): with cloud
// fraction f and opaque clouds of mean chord lambda, the clear gaps have mean length
// lambda (1 - f) / f and a ray of length L gets through with probability exp(-L f / ((1 - f)
// lambda)). The stretch is cut into four quarters, each its own mixture: f is the weather
// map's coverage times the height profile at the quarter's middle (a cumulus layer's thin top
// lets a low sun's light through; the map says where the cloud fields and the gaps between
// them lie), lambda the fitted chord (far_chord; 0 = off). Toward a sun a few degrees up,
// the light crosses tens of kilometres of layer; sampling them with five more growing light
// steps (to about 100 km) cost 45% more density evaluations on `dawn` and made the fit's
// training error worse (0.0570 to 0.0608, README). The weather map is a 2D texture read, not
// a density evaluation: against the converged quadrature of the same model (single
// scattering) it took `dawn` from FLIP 0.038 to 0.026 and `sunset` from 0.070 to 0.050 over
// the layer's mean coverage.
// The stretch ends where the sun ray enters an anvil's band, at `band` (anvil_band_entry;
// anvil_optical_depth samples the band). A cirrus layer's share (l.cirrus) takes none: the
// mixture's clouds are opaque, and cirrus an optical depth or so through.
fn far_optical_depth(rel: vec3<f32>, p: vec3<f32>, l: Layer, band: f32) -> f32 {
    let chord = frame.far_chord;
    if chord <= 0.0 || frame.light_steps == 0u {
        // Off, or no light march: 0 light steps leave the clouds unshadowed.
        return 0.0;
    }
    let reach = light_march_reach();
    let sun = frame.sun_direction;
    let exit = ray_shell_from(rel, altitude_of(rel), sun, l.top);
    var end = exit.t1;
    if band >= 0.0 {
        end = min(end, max(band, reach));
    }
    let len = end - reach;
    if !exit.hit || !(len > 0.0) {
        return 0.0;
    }
    var tau = 0.0;
    for (var i = 0u; i < 4u; i++) {
        let t = reach + (f32(i) + 0.5) * 0.25 * len;
        let h = saturate(layer_height(l, altitude_of(rel + sun * t)));
        let w = sample_weather(p + sun * t, l);
        let f = min(w.coverage * height_signal(h / w.top, l.cloud_type), 0.95);
        tau += 0.25 * len * f / ((1.0 - f) * chord);
    }
    return tau * (1.0 - l.cirrus);
}

// The light march's reach: its segments' total length (m).
fn light_march_reach() -> f32 {
    let growth = frame.light_step_growth;
    let steps = f32(frame.light_steps);
    if growth == 1.0 {
        return frame.first_light_step * steps;
    }
    return frame.first_light_step * (pow(growth, steps) - 1.0) / (growth - 1.0);
}

// Where the sun ray from camera-relative `rel` enters layer `l`'s anvil band (height
// fraction ANVIL_BASE and up): 0 from inside it, -1 where the layer has no anvil or the ray
// does not reach the band.
fn anvil_band_entry(rel: vec3<f32>, l: Layer) -> f32 {
    if anvil_weight(l) <= 0.0 {
        return -1.0;
    }
    let alt = altitude_of(rel);
    let base = mix(l.bottom, l.top, ANVIL_BASE);
    if alt >= base {
        return 0.0;
    }
    // From below the band's sphere the ray leaves it through the far root.
    let enter = ray_shell_from(rel, alt, frame.sun_direction, base);
    if !enter.hit || !(enter.t1 > 0.0) {
        return -1.0;
    }
    return enter.t1;
}

// An anvil's shade: the sun ray's optical depth through layer `l`'s anvil band beyond the
// light march's reach, ABOVE_SAMPLES midpoint samples of the density (the layers above's
// sampling). Under a storm's anvil the light march (3.2 km at the defaults) ends kilometres
// below the plate and the far shadow took it for broken cloud of the fitted chord, so the
// octaves, which do not read the far shadow, saw none of it and single scattering little:
// `weather thunderstorm` measured FLIP 0.186 against its truth, the dense cloud under the
// anvil 1.15 times the truth's brightness (docs/fit-log.md). A plate is a slab, not broken
// cloud: sampled, its tens of optical depths reach both (FLIP 0.186 still, but the dense
// cloud 0.85 of the truth's brightness, RMSE 0.159 to 0.114). The octaves see all of it. A
// share of it alone, for light that would come around the plate's edges and through its gaps,
// had been chosen while the precipitation darkening also dimmed the sky's light (0.75: FLIP
// 0.136 against 0.139 for all); since the darkening takes the sun's light alone, shares of
// 0.5, 0.75, 1 and 1.25 measure 0.142, 0.126, 0.118 and 0.118 (docs/fit-log.md), so the
// octaves take the plate's shade as single scattering does. Only layers with an anvil pay:
// four density evaluations per lit sample.
fn anvil_optical_depth(rel: vec3<f32>, p: vec3<f32>, l: Layer, band: f32,
                       counters: ptr<function, Counters>) -> f32 {
    if band < 0.0 || frame.light_steps == 0u {
        return 0.0;
    }
    let sun = frame.sun_direction;
    let exit = ray_shell_from(rel, altitude_of(rel), sun, l.top);
    let start = max(band, light_march_reach());
    if !exit.hit || !(exit.t1 > start) {
        return 0.0;
    }
    let sigma_t = frame.scattering + frame.absorption;
    let step = (exit.t1 - start) / f32(ABOVE_SAMPLES);
    var tau = 0.0;
    for (var k = 0u; k < ABOVE_SAMPLES; k++) {
        let s = start + (f32(k) + 0.5) * step;
        (*counters).light += 1u;
        tau += layer_density(p + sun * s, altitude_of(rel + sun * s), l, counters) * sigma_t * step;
    }
    return tau;
}

// Sun light scattered toward the viewer per unit illuminance and unit sigma_s: single
// scattering plus the octaves F build sum_{i>=1} a^i phase(cos, c^i) / (1 + b^i tau_oct) (a:
// contribution, b: extinction, c: eccentricity; F their feeding, below; `build` from
// octave_buildup; `tau_oct` from octave_optical_depth, `tau` the sun ray's; fitted to the path
// tracer, docs/fit). `far` (far_optical_depth) shadows
// single scattering beyond the light march and the side light; `coverage` is the region's
// cover about the sample (density.wgsl regional_coverage: the weather map's, or on convective
// cells the cells' share), `view_y` the view ray's vertical component (diffuse_limb), `h` the
// sample's height fraction in its cloud (vertical_anisotropy, downward_dimming: in its layer
// over the profile's top, density.wgsl cloud_top_fraction; a stratus fills the lowest third of
// its layer, and in the layer's fraction the top of `weather fog`'s ground fog was taken for
// its base, its light looking down dimmed away: FLIP 0.114, with the cloud's 0.094),
// `layer_coverage` its layer's coverage and `above` the sun ray's optical depth through the
// layers above it (deck_escape).
// Wrenninge's octaves attenuate by exp(-b^i tau). The diffuse light deep in a thick layer falls
// off far more slowly: as 1 / (1 + (3/4)(1 - g) tau) in two-stream theory for conservative
// scattering (Meador and Weaver 1980), and the path tracer agrees (storm's bases were 2.3 times
// too dark). The two forms agree to first order in tau, where clouds are thin.
// Returns the whole and, apart, the octaves' part of it (the march gives that part a forward
// lobe once it knows the pixel's transmittance: forward_lobe).
struct SunScattering {
    total: f32,
    octaves: f32,
}

fn sun_scattering(cos_theta: f32, view_y: f32, tau: f32, tau_oct: f32, far: f32, build: f32,
                  coverage: f32, h: f32, layer_coverage: f32, above: f32) -> SunScattering {
    let a = frame.ms_contribution;
    let b = frame.ms_extinction;
    let c = frame.ms_eccentricity;
    let octaves = min(frame.octaves, MAX_OCTAVES);
    var octave_sum = 0.0;
    var ka = 1.0;
    var kb = 1.0;
    var kc = 1.0;
    for (var i = 0u; i < octaves; i++) {
        ka *= a;
        kb *= b;
        kc *= c;
        octave_sum += ka * phase(cos_theta, kc) / (1.0 + kb * tau_oct);
    }
    // The octaves stand for the multiply scattered, diffuse light of the cloud, which the sun's
    // flux into it feeds: through a deck's top, E mu0 per unit area (mu0 the cosine of the
    // sun's zenith angle; without it the octaves lit a sunset as brightly as noon). A broken
    // layer's clouds also take light through their sides, in proportion to sin(zenith) and to
    // the clear share (1 - coverage) around them, unless far cloud shadows them (`far`).
    let mu0 = saturate(frame.sun_direction.y);
    let side = sqrt(max(1.0 - mu0 * mu0, 0.0)) * (1.0 - saturate(coverage)) * exp(-far);
    var feed = mu0 + frame.side_light * side;
    // Multiply scattered light leaks out of a small cloud through its sides but stays in a
    // deck: the octaves scale with the region's coverage (to a fitted power) as well as
    // with the local density (`build`). Against the path tracer the octaves alone lit high-sun
    // cumulus up to 1.4 times too brightly while decks stayed 7% too dark (docs/fit).
    if frame.coverage_exponent > 0.0 {
        feed *= pow(max(coverage, 1e-6), frame.coverage_exponent);
    }
    feed *= diffuse_limb(view_y, coverage) * vertical_anisotropy(view_y, coverage, h)
        * deck_escape(mu0, layer_coverage, above);
    feed *= downward_dimming(view_y, coverage, h, tau * mu0);
    var octaves_part = feed * build * octave_sum;
    var total = phase(cos_theta, 1.0) * exp(-tau - far) + octaves_part;
    if (frame.flags & FLAG_BEER_POWDER) != 0u {
        // Beer-Powder (HZD): in-scattering builds up with depth into the cloud, darkening
        // the thin edges. Kept <= 1 so it only removes energy.
        let powder = 1.0 - exp(-frame.powder_strength * tau);
        total *= powder;
        octaves_part *= powder;
    }
    return SunScattering(total, octaves_part);
}

// The pixel transmittance at and above which the forward lobe has its full strength.
const FORWARD_LOBE_THIN: f32 = 0.1;

// The octaves' forward lobe through thin cloud: the factor on a pixel's octave light, given
// the cosine between its view ray and the sun and its transmittance. The octaves' own
// eccentricities (c^i g, c = 0.15 before this term) make their light nearly isotropic, right
// for the diffuse light of a thick cloud but not for light that crossed a thin one: scattered
// a few times, it still leans toward the sun (the eccentricity of n scatterings of HG(g) is
// g^n). Against the path tracer's truth (8192 paths a pixel, 20 scenes) the octave light of
// pixels of transmittance 0.05-0.5 was 1.70 times the truth's looking away from the sun
// (cosine below -0.6) and 0.59 times looking toward it (above 0.6), and 1.52 and 0.49 at
// 0.5-0.95, while in pixels below 0.05 it was 0.90-0.97 at every angle (docs/fit). A view
// sample does not know how thin the cloud is; the pixel's transmittance, once the march
// ends, does. So 1 + w (4 pi HG(cos, g_f) - 1): its mean over the sphere is 1 (light moved
// between directions, none added), w = k min(T / 0.1, 1) (k: frame.forward_lobe, 0 = off;
// g_f: .y). Thresholds of 0.05, 0.2 and 0.5 and g_f of 0.3-0.6 fitted within 0.0006 of
// each other. Per pixel, not per sample: a phase function and a second accumulator.
fn forward_lobe(cos_theta: f32, transmittance: f32) -> f32 {
    let k = frame.forward_lobe;
    if k <= 0.0 {
        return 1.0;
    }
    let w = k * saturate(transmittance / FORWARD_LOBE_THIN);
    return 1.0 + w * (4.0 * PI * phase_hg(cos_theta, frame.forward_lobe_g) - 1.0);
}

// The diffuse light leaving a thick plane-parallel layer is limb-darkened: brighter along the
// layer's normal than at grazing angles, I(mu) proportional to 1 + (3/2) mu in the Eddington
// approximation (Chandrasekhar 1950, Radiative Transfer, ch. 1), mu the cosine of the angle to
// the normal. The octaves know no normal, and against the path tracer (8192 paths a pixel)
// decks seen 20-40 degrees up were darker, relative to the truth, than near the horizon
// (`stratocumulus-overcast` 0.86-0.91 of its brightness against 0.94-1.04, `storm` 0.76-0.95
// against 0.96-1.10). Here with a fitted strength k (limb_darkening; 0 = off) in place of 3/2,
// normalised to keep the flux through the layer ((1 + k mu) / (1 + 2k/3)), mu = |view_y| the
// view ray's cosine to the vertical, and weighted by the region's coverage: a deck is a
// layer, a small cumulus has no one normal. The factor is 1 at mu = 2/3: it darkens grazing
// views and brightens steep ones, and the refit raised the octaves' a with it (1.15 to 1.2).
// Fitted k = 0.5 took the training scenes' mean FLIP from 0.0505 to 0.0486 and the presets'
// from 0.0583 to 0.0572 (that fit's docs/fit; since vertical_anisotropy, which takes the
// up-down part, k = 0.25 and a = 1.15); one abs, a division and a mix per lit sample.
fn diffuse_limb(view_y: f32, coverage: f32) -> f32 {
    let k = frame.limb_darkening;
    let layer = (1.0 + k * abs(view_y)) / (1.0 + 2.0 * k / 3.0);
    return mix(1.0, layer, saturate(coverage));
}

// The octaves' vertical anisotropy: the factor on their light at a sample of height fraction
// `h` in its layer, seen along a view ray of vertical component `view_y` (up positive). In a
// layer lit from above the diffuse light's net flux runs down: in two-stream theory for
// conservative scattering the downward flux exceeds the upward one by the same net flux at
// every depth, the upward stream falling to the ground's reflection at the base while near a
// thick layer's top the two are nearly equal (Meador and Weaver 1980). So light seen looking
// up (going down) outshines light seen looking down (going up), most toward the base. The
// octaves know neither stream: diffuse_limb's |view_y| treats up and down alike. Against the
// path tracer (8192 paths a pixel) decks seen from below were 0.86-0.95 of the truth's
// brightness looking 20-40 degrees up (`stratocumulus-overcast`, `storm`), and the layer below
// a camera inside it 1.2-1.3 times it looking down (`inside-layer`). Hence 1 + s view_y
// coverage (1 - h): its mean over the sphere is 1 (no light added), a deck's (coverage) and
// strongest at its base (1 - h, the simplest stand-in for the optical depth below the sample,
// which the march does not know; with s held at 0.5 and the rest refit, no weight by height
// fitted 0.0005 worse). s: frame.vertical_anisotropy (0 = off); one multiply-add per lit
// sample.
fn vertical_anisotropy(view_y: f32, coverage: f32, h: f32) -> f32 {
    return 1.0 + frame.vertical_anisotropy * view_y * saturate(coverage) * (1.0 - saturate(h));
}

// The octaves' dimming looking down: the factor on their light at a sample of height fraction
// `h` whose sun ray's optical depth projected on the vertical is `tau_v` (tau mu0), seen along
// a view ray of vertical component `view_y`. The light going up through a layer falls with the
// cloud above the sample that shields it from the light coming down, which the vertical
// anisotropy's height fraction does not see. Against the path tracer (8192 paths a pixel) a
// camera inside a layer saw the cloud 5-20 degrees below it at 1.15-1.25 times the truth's
// brightness, the octaves 0.61 of the truth's luminance against its 0.46 of multiply
// scattered light, where the vertical anisotropy is 0.97-0.99 (`inside-layer`). Hence 1 - k
// |view_y| coverage (1 - h) tau_v / (tau_v + 1) looking down (k: downward_dimming, fitted, 0 =
// off), clamped at 0: the weights of the vertical anisotropy times the cloud above (0 at a
// cloud's lit top under any sun). Looking up it is 1. One division per lit sample.
fn downward_dimming(view_y: f32, coverage: f32, h: f32, tau_v: f32) -> f32 {
    let k = frame.downward_dimming * max(-view_y, 0.0) * saturate(coverage) * (1.0 - saturate(h));
    return max(1.0 - k * tau_v / (tau_v + 1.0), 0.0);
}

// The octaves' escape from a deck: the factor on their feed for a sun of zenith cosine `mu0`
// over a layer of coverage `layer_coverage`. The diffuse light a thick conservative layer
// lets through its base is (2/3 + mu0) / (4/3 + (1 - g) tau) of the flux mu0 through its top
// in the Eddington approximation (Meador and Weaver 1980): light that enters steeply goes
// deeper before it turns and is likelier to come out of the base than light that enters at a
// grazing angle. The octaves attenuate along the sun ray and do not know that. Against the
// path tracer's truth (8192 paths a pixel) decks were darker under a high sun than under a
// low one: dense cloud 0.95 of the truth's brightness at 45-60 degrees (`stratocumulus,
// high sun`, `stratocumulus-overcast`), 0.97 at 40 (`storm`), 1.02 at 25 (`storm deck`),
// while cumulus stayed at 0.95-0.96 at every elevation. Hence 1 + e w (mu0 - 1/2): the ratio
// (2/3 + mu0) / (2/3 + 1/2) is 1 + (6/7)(mu0 - 1/2), here with a fitted strength e
// (frame.deck_escape, 0 = off) in place of 6/7, 1 at 60 degrees from the zenith, and
// w = layer_coverage^8 (DECK_POWER) the layer's weight as a deck: a closed layer's clouds are
// far wider than they are thick, a broken one's are not. The weather map's coverage at the
// sample does not tell them apart (it is high inside a cumulus as well: weighted by it,
// `denser cumulus` went from FLIP 0.063 to 0.071), nor did the layer's coverage to the 4th
// power (training mean 0.0474 against 0.0453 for the 8th; e = 1.5, before a refit). One power
// and a multiply-add per lit sample.
// e w is held to the Eddington ratio's own 6/7 (DECK_ESCAPE_MAX), which it stands for: the fit
// took e to 2, the top of its range, where `storm`'s coverage of 0.9 (w 0.43) gives 0.86, but a
// full layer (w 1) got 2, 2.3 times the ratio's. No training scene or preset is that full; the
// ground fog of `weather fog` (coverage 1) was lit 1.34 times the truth's brightness where
// dense, FLIP 0.149, and is 1.13 and 0.114 with the bound (`weather mist`'s 0.074 to 0.071; the
// training scene closed to 0.92, w 0.51, 0.040 to 0.042; nothing else moved: docs/fit-log.md).
// Under a layer above, of optical depth `above` along the sun ray, the light that reaches the
// deck's top is only exp(-above) the direct beam; the rest comes diffuse, from every direction
// of the sky above it, and enters as light of zenith cosine DIFFUSE_MU does (the Eddington
// ratio averaged over that light: (2/3 + 2/3) / (4/3 + (1 - g) tau)). So the escape takes
// mix(DIFFUSE_MU, mu0, exp(-above)) for mu0. The ground fog under `weather fog`'s deck (a
// sun 60 degrees up, zenith cosine 0.87, its escape 1.32) was lit 1.15 times the truth's
// brightness where dense, FLIP 0.094; with the diffuse light's 1.14, 1.06 and 0.077
// (`weather mist`, under broken cumulus, 0.070 to 0.072; a single layer does not move:
// docs/fit-log.md).
fn deck_escape(mu0: f32, layer_coverage: f32, above: f32) -> f32 {
    let e = frame.deck_escape;
    let mu = mix(DIFFUSE_MU, mu0, exp(-above));
    return 1.0 + min(e * pow(saturate(layer_coverage), DECK_POWER), DECK_ESCAPE_MAX) * (mu - 0.5);
}

// The power of the layer's coverage that weights the octaves' deck escape (deck_escape).
const DECK_POWER: f32 = 8.0;

// The mean cosine, weighted by the flux, of light arriving alike from every direction of a
// hemisphere (the integral of mu 2 mu over [0, 1]): the zenith cosine the deck escape takes for
// the diffuse light that a layer above has made of the sun's.
const DIFFUSE_MU: f32 = 2.0 / 3.0;

// The most the deck escape's strength may be (deck_escape): the Eddington approximation's 6/7.
const DECK_ESCAPE_MAX: f32 = 0.857142857;

// The share of the octaves at a sample of density `density`: 1 - exp(-sigma_t density l), l
// the build-up length (ms_buildup; 0: 1, Wrenninge's octaves everywhere). Light
// scatters many times only where there is cloud around to scatter it: against the path
// tracer the octaves lit thin wisps and edges up to 2.5 times too brightly while the cores
// stayed too dark (docs/fit, brightness by the truth's transmittance). The local density
// stands for the cloud around the sample; it costs no sample.
fn octave_buildup(density: f32) -> f32 {
    let l = frame.ms_buildup;
    if l <= 0.0 {
        return 1.0;
    }
    return 1.0 - exp(-(frame.scattering + frame.absorption) * density * l);
}

// The share of the octaves a cellular layer's cloudlets keep (`clouds.cellular`, per layer):
// mix(1, CELLULAR_OCTAVES, cellular). A cloudlet a few hundred metres deep and about twice
// that across (density.wgsl: cellular_base) loses its multiply scattered light through its
// top, base and sides sooner than the cumulus and decks the octaves were fitted on. Fed by the
// cloudlets' share of the region (regional_coverage), `type altocumulus` was still lit 1.16 /
// 1.29 / 1.28 times the truth's brightness (dense / mid / thin), FLIP 0.062. The share was
// chosen on that scene alone (0.6, 0.68, 0.75, 0.82, 1: FLIP 0.054, 0.045, 0.044, 0.047,
// 0.062) and checked on `type stratocumulus`, held out: 0.112 to 0.081 (docs/fit-log.md).
// The path tracer knows no octaves: no truth moved.
const CELLULAR_OCTAVES: f32 = 0.75;

fn cellular_octaves(l: Layer) -> f32 {
    return mix(1.0, CELLULAR_OCTAVES, l.cellular);
}

// Ambient light at height fraction `h` (thesis 5.5.3): a gradient from bottom to top colour,
// or under the physical sky the sky's cosine-weighted radiance from below and from above,
// seen from the layer's bottom (the sky-ambient table, for the sun's angle at camera-relative
// `rel`, m).
fn ambient(h: f32, rel: vec3<f32>) -> vec3<f32> {
    if physical_sky() {
        return sky_ambient_light(h, rel);
    }
    return mix(frame.ambient_bottom, frame.ambient_top, h) * frame.ambient_strength;
}

// Height fraction of altitude `alt` in the layer that holds it (ambient and precipitation
// darkening are per layer).
fn height_fraction(alt: f32) -> f32 {
    return saturate(layer_height(cloud_layer(layer_at(alt)), alt));
}

// In-scattered radiance per unit length at a view sample of layer `l`: sigma_s * density *
// (sun + ambient + a lightning flash's light), the sun's and the flash's light darkened toward
// the base of raining clouds (thesis 4.4.1); and, apart, the octaves' part of it. The darkening
// stands for the light a raining cloud's heavier water load takes on its way down to the base;
// the sky's light is not darkened, for the reason the ambient takes no occlusion: in a nearly
// uniform environment a conservative medium's diffuse radiance stays the environment's however
// thick the cloud (docs/fit-log.md). Darkening it as well left the rain states' shaded bases
// darker than the truth's (`weather rain` FLIP 0.0722, `rainbow` 0.0789; with the sun's light
// alone darkened, and the strength chosen again, 0.0606 and 0.0646). The water load is met
// along the light's way through the cloud: a sample the sun ray reaches through little cloud
// (a thin edge, a shaft's side) takes little of it, so the darkening grows with the sun ray's
// optical depth tau as 1 - exp(-tau / PRECIPITATION_DEPTH), in full where the ray meets the
// ground. Chosen by the mean FLIP of `weather rain`, `weather snow` and `weather thunderstorm`
// (the scenes that chose the strength, which stayed 0.6): depths of 4, 6, 8, 10 and 20 measured
// 0.0729, 0.0716, 0.0704, 0.0699 and 0.0723, without the depth 0.0738 (`rain` 0.0606 to
// 0.0577, `snow` 0.0429 to 0.0342, `thunderstorm` 0.1179 to 0.1177; `rainbow`, held out, 0.0646
// to 0.0665: docs/fit-log.md).
const PRECIPITATION_DEPTH: f32 = 10.0;

struct ScatteredLight {
    total: vec3<f32>,
    octaves: vec3<f32>,
}

fn scattered_light(rel: vec3<f32>, p: vec3<f32>, alt: f32, density: f32, view: vec3<f32>,
                   l: Layer, counters: ptr<function, Counters>) -> ScatteredLight {
    let sun = frame.sun_direction;
    let h = saturate(layer_height(l, alt));
    var sun_light = vec3<f32>(0.0);
    var octave_light = vec3<f32>(0.0);
    let weather = sample_weather(p, l);
    // The share of the darkening the sun ray's cloud gives (PRECIPITATION_DEPTH).
    var load = 1.0;
    if !hits_ground(rel, alt, sun) {
        var tau = 0.0;
        var above = 0.0;
        var far = 0.0;
        var tau_oct = 0.0;
        if LIGHT_MARCH {
            above = optical_depth_above(rel, p, l, counters);
            let band = anvil_band_entry(rel, l);
            tau = sun_optical_depth(rel, p, l, counters) + above
                + anvil_optical_depth(rel, p, l, band, counters);
            far = far_optical_depth(rel, p, l, band);
            tau_oct = octave_optical_depth(rel, p, l, tau, above, counters);
        }
        let s = sun_scattering(dot(view, sun), view.y, tau, tau_oct, far,
                               octave_buildup(density) * cellular_octaves(l),
                               regional_coverage(p, l, weather),
                               saturate(h / cloud_top_fraction(l, weather)), l.coverage, above);
        let lit = frame.sun_illuminance * sun_through_air(rel);
        sun_light = lit * s.total;
        octave_light = lit * s.octaves;
        load = 1.0 - exp(-tau / PRECIPITATION_DEPTH);
    }
    let darkening = saturate(1.0 - frame.precipitation_darkening * weather.precipitation * (1.0 - h)
                                   * load);
    let k = frame.scattering * density;
    let dark = darkening * k;
    return ScatteredLight((sun_light + lightning_light(rel)) * dark + ambient(h, rel) * k,
                          octave_light * dark);
}
// The lit ground under the physical sky: the sky's irradiance on it and the clouds' shadows
// on it.
//
// - ground irradiance (64x1): the irradiance the sky (not the sun's disc) gives a horizontal
//   ground per unit sun illuminance, by the sun's zenith cosine: the cosine-weighted integral
//   of the sky's radiance over the upper hemisphere (Bruneton and Neyret 2008's irradiance
//   table, for one altitude). The ground's light is albedo / pi times sun plus sky. It depends
//   on the air only, so it is computed when the air changes.
// - cloud shadow (128x128): the transmittance of the key light's way through every cloud layer
//   from the ground, on a square 40 km wide centred below the camera, every frame (it follows
//   the wind, the sun and the camera). A transmittance map and not a Beer shadow map
//   (Hillaire 2016: front depth, mean extinction and maximum optical depth, to be evaluated
//   at any depth): the only receiver is the ground, at one height, so the transmittance there
//   is the whole answer, with no reconstruction error. Its texels are 313 m, finer than a
//   cumulus; the shadow fades out over the outer quarter of the square, where the map ends.

@group(0) @binding(38) var ground_irradiance_in: texture_2d<f32>;
@group(0) @binding(39) var ground_irradiance_out: texture_storage_2d<rgba32float, write>;
@group(0) @binding(40) var cloud_shadow_in: texture_2d<f32>;
@group(0) @binding(41) var cloud_shadow_out: texture_storage_2d<r32float, write>;
@group(0) @binding(43) var host_shadow_out: texture_storage_2d<r32float, write>;

const GROUND_IRRADIANCE_SIZE: u32 = 64u;
const GROUND_IRRADIANCE_DIRECTIONS: u32 = 128u; // over the sphere; the upper half counts
const SHADOW_SIZE: u32 = 128u;
const SHADOW_HALF_EXTENT: f32 = 20000.0;        // m
const SHADOW_FADE_START: f32 = 0.75;            // of the half extent
const SHADOW_STEPS: u32 = 16u;                  // per layer crossed
// The host's map (its geometry's shadows, `Clouds::cloud_shadow`): 64 steps a layer are
// within 0.004 of the converged column where 16 are 0.09 off (cumulus under a noon sun).
const HOST_SHADOW_STEPS: u32 = 64u;

// Texel i of the irradiance table holds the sun's zenith cosine 2 i / (size - 1) - 1.
@compute @workgroup_size(8, 8, 1)
fn ground_irradiance(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= GROUND_IRRADIANCE_SIZE || id.y >= 1u {
        return;
    }
    let mu_s = f32(id.x) / f32(GROUND_IRRADIANCE_SIZE - 1u) * 2.0 - 1.0;
    let sun = vec3<f32>(sqrt(max(1.0 - mu_s * mu_s, 0.0)), mu_s, 0.0);
    // A metre above the ground, so that no upward ray starts below it.
    let origin = vec3<f32>(0.0, air_bottom() + 0.001, 0.0);
    var sum = vec3<f32>(0.0);
    for (var k = 0u; k < GROUND_IRRADIANCE_DIRECTIONS; k++) {
        let d = fibonacci_direction(k, GROUND_IRRADIANCE_DIRECTIONS);
        if d.y <= 0.0 {
            continue;
        }
        let end = air_ray_end(origin, d);
        sum += integrate_air(origin, d, end.x, AMBIENT_STEPS, sun).radiance * d.y;
    }
    let e = sum * (4.0 * PI / f32(GROUND_IRRADIANCE_DIRECTIONS));
    textureStore(ground_irradiance_out, id.xy, vec4<f32>(e, 1.0));
}

// The sky's irradiance on the ground for a sun of zenith cosine mu_s.
fn sky_irradiance(mu_s: f32) -> vec3<f32> {
    let x = vec2<f32>(mu_s * 0.5 + 0.5, 0.0);
    return lut_bilinear(ground_irradiance_in, x, vec2<u32>(GROUND_IRRADIANCE_SIZE, 1u)).rgb;
}

// Light leaving the lit, diffuse ground where the sun's zenith cosine is mu_s, sun and sky.
fn ground_radiance(mu_s: f32) -> vec3<f32> {
    return ground_radiance_sun(mu_s) + frame.ground_albedo / PI * sky_irradiance(mu_s);
}

// The ground point of shadow-map texel `c`, relative to the ground below the camera (m): on
// the planet's surface, texel i at (2 i / (size - 1) - 1) times the half extent.
fn shadow_ground_point(c: vec2<u32>) -> vec3<f32> {
    let xz = (vec2<f32>(c) / f32(SHADOW_SIZE - 1u) * 2.0 - 1.0) * SHADOW_HALF_EXTENT;
    let rp = frame.planet_radius;
    let s2 = dot(xz, xz);
    // sqrt(Rp^2 - s^2) - Rp without cancellation.
    let y = -s2 / (sqrt(max(rp * rp - s2, 0.0)) + rp);
    return vec3<f32>(xz.x, y, xz.y);
}

@compute @workgroup_size(8, 8, 1)
fn cloud_shadow(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= vec2<u32>(SHADOW_SIZE)) {
        return;
    }
    textureStore(cloud_shadow_out, id.xy, vec4<f32>(shadow_transmittance(id.xy, SHADOW_STEPS), 0.0, 0.0, 1.0));
}

// The same map for the host's geometry, with more steps (`host-shadow`, the `shadow` flag).
@compute @workgroup_size(8, 8, 1)
fn host_cloud_shadow(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= vec2<u32>(SHADOW_SIZE)) {
        return;
    }
    textureStore(host_shadow_out, id.xy, vec4<f32>(shadow_transmittance(id.xy, HOST_SHADOW_STEPS), 0.0, 0.0, 1.0));
}

// The key light's transmittance from the ground at shadow-map texel `c` up through every
// cloud layer, `steps` midpoint steps a layer.
fn shadow_transmittance(c: vec2<u32>, steps: u32) -> f32 {
    let rel = shadow_ground_point(c);
    let sun = frame.sun_direction;
    let rp = frame.planet_radius;
    let up = normalize(vec3<f32>(rel.x, rel.y + rp, rel.z));
    var tau = 0.0;
    // Where the key light is below the ground's horizon the ground is unlit anyway.
    if dot(up, sun) > 0.0 {
        let cam_xz = frame.camera_position.xz;
        // Not counted: the counters measure the march's work, the same with and without the
        // physical sky.
        var counters = Counters(0u, 0u, 0u, 0u);
        for (var i = 0u; i < layer_count(); i++) {
            let l = cloud_layer(i);
            // From below a shell, the far root is where the ray leaves it upward.
            let start = max(ray_shell_from(rel, 0.0, sun, l.bottom).t1, 0.0);
            let end = ray_shell_from(rel, 0.0, sun, l.top).t1;
            let dt = (end - start) / f32(steps);
            if !(dt > 0.0) {
                continue;
            }
            for (var k = 0u; k < steps; k++) {
                let q = rel + sun * (start + (f32(k) + 0.5) * dt);
                let p = vec3<f32>(q.x + cam_xz.x, q.y, q.z + cam_xz.y);
                tau += layer_density(p, altitude_of(q), l, &counters) * dt;
            }
        }
    }
    let sigma_t = frame.scattering + frame.absorption;
    return exp(-sigma_t * tau);
}

// The clouds' transmittance of the key light at ground point `rel` (m, relative to the ground
// below the camera): the map, fading to 1 toward its edge and 1 beyond it.
fn ground_shadow(rel: vec3<f32>) -> f32 {
    let edge = max(abs(rel.x), abs(rel.z)) / SHADOW_HALF_EXTENT;
    if edge >= 1.0 {
        return 1.0;
    }
    let x = rel.xz / (2.0 * SHADOW_HALF_EXTENT) + 0.5;
    let t = lut_bilinear(cloud_shadow_in, x, vec2<u32>(SHADOW_SIZE)).r;
    return mix(t, 1.0, smoothstep(SHADOW_FADE_START, 1.0, edge));
}

// The part of the sky-view table's ground light (per unit key-light illuminance) along `view`
// from the camera at radius `r` (km) that the clouds' shadow takes away: the ground's sun
// term at the point the ray meets, times the air's transmittance back to the camera
// (Bruneton 2017: the ratio of two transmittances to the top), times the shadow's share.
fn ground_shadow_loss(view: vec3<f32>, r: f32) -> vec3<f32> {
    let t = distance_to_ground(r, view.y);
    let cam_alt = max(frame.camera_position.y, 0.0);
    let shadow = ground_shadow(view * (t * 1000.0) + vec3<f32>(0.0, cam_alt, 0.0));
    if shadow >= 1.0 {
        return vec3<f32>(0.0);
    }
    let r_g = air_bottom();
    // Zenith cosines at the ground point of the view ray and of the sun (Bruneton 2008).
    let mu_g = clamp((r * view.y + t) / r_g, -1.0, 1.0);
    let mu_s = clamp((r * frame.sun_direction.y + t * dot(view, frame.sun_direction)) / r_g, -1.0, 1.0);
    let t_view = min(transmittance_to_top(r_g, -mu_g) / max(transmittance_to_top(r, -view.y), vec3<f32>(1e-20)),
                     vec3<f32>(1.0));
    return (1.0 - shadow) * t_view * ground_radiance_sun(mu_s);
}
// The rainbow (`[rainbow]`, seed 001's rainbow effect): the primary and secondary bows of
// sunlight in the falling rain below precipitating cloud layers, under the physical sky.
//
// Light leaving a drop after k internal reflections is deviated by D(i) = 2 (i - r) + k (pi - 2 r)
// (incidence i, refraction r, sin i = n sin r). D has a minimum at cos^2 i = (n^2 - 1) /
// ((k + 1)^2 - 1) (Descartes): the bow, at pi - D from the antisolar point for the primary
// (k = 1, about 42 degrees) and D - pi for the secondary (k = 2, about 51 degrees); the primary
// is bright inside, the secondary outside, and Alexander's dark band lies between. Near the
// bow the outgoing wavefront is cubic, so a drop of radius a scatters, per radian of
// deviation, the share of the light that falls on it
//   dP/dtheta = 2 b T_k 2 pi sqrt(s / c) Ai^2(-s eps),   s = (2 pi a / lambda)^(2/3) / c^(1/3)
// (Airy 1838; van de Hulst 1957, section 13.24): eps the angle into the bright side, b = sin i
// the impact parameter, c half of d^2 D / db^2 at the bow, T_k the Fresnel transmission in,
// k reflections and out (the mean of the two polarisations). Far from the bow Ai^2 averages to
// the two geometric rays' 1 / sqrt(c eps), which fixes the scale. Small drops widen and
// overlap the wavelengths' bows into a whitish fog bow; large ones separate them, with
// supernumerary bows inside the primary. Airy theory is good for drops above about 50 um;
// below it, a guide to the shape only.

@group(0) @binding(46) var rainbow_lut_out: texture_storage_2d<rgba32float, write>;
@group(0) @binding(47) var rainbow_lut_in: texture_2d<f32>;

// The table: the bows' phase function (per steradian, per unit extinction of the rain, rgb for
// a white sun) at angles RAINBOW_MIN_DEG to RAINBOW_MAX_DEG from the antisolar point. The
// primary's light fills the sky inside it and the secondary's outside it; Airy theory is a
// bow's neighbourhood's, so both fade out over the table's last RAINBOW_FADE_DEG at either end
// (where they are a few percent of the bows' peaks) instead of ending at an edge.
const RAINBOW_TEXELS: u32 = 1024u;
const RAINBOW_MIN_DEG: f32 = 8.0;
const RAINBOW_MAX_DEG: f32 = 68.0;
const RAINBOW_FADE_DEG: f32 = 10.0;
// The visible spectrum's samples (400-700 nm) and the sun's disc's (Gauss-Chebyshev nodes of
// the second kind: the disc's chord lengths as weights).
const RAINBOW_WAVELENGTHS: u32 = 30u;
const RAINBOW_SUN_TAPS: u32 = 5u;
// The cheap path's three wavelengths (nm), one a channel.
const RAINBOW_RGB_NM: vec3<f32> = vec3<f32>(610.0, 550.0, 465.0);
// The rain's march along a view ray: steps and reach (m).
const RAIN_STEPS: u32 = 32u;
const RAIN_RANGE_M: f32 = 15000.0;
// Moderate rain's extinction (1/m): 3.912 / 7 km, a 7 km visibility by Koschmieder's law.
// `rainbow_moisture` 1 is this much rain under a layer precipitating at 1.
const RAIN_EXTINCTION: f32 = 5.59e-4;
// The moisture profile's peak altitude (m), as the seed describes.
const MOISTURE_PEAK_M: f32 = 2000.0;

// Water's refractive index at `nm`: Cauchy's form A + B / lambda^2 fitted to Hale and Querry
// 1973's 1.339 at 400 nm and 1.331 at 700 nm (within 0.0003 at 500 and 600 nm).
fn water_index(nm: f32) -> f32 {
    return 1.3271 + 1900.0 / (nm * nm);
}

// The Airy function Ai(x) (DLMF 9.4 and 9.7): the Maclaurin series on [-4, 3], the asymptotic
// expansions beyond to their terms in u1 = 5/72, u2 = 385/10368 (and u3 = 85085/2239488 on the
// bright side), within 0.1% at the joins.
fn airy_ai(x: f32) -> f32 {
    if x > 3.0 {
        let z = 2.0 / 3.0 * x * sqrt(x);
        let series = 1.0 - 0.069444444 / z + 0.037133487 / (z * z);
        return exp(-z) / (2.0 * sqrt(PI) * sqrt(sqrt(x))) * series;
    }
    if x < -4.0 {
        let w = -x;
        let z = 2.0 / 3.0 * w * sqrt(w);
        let phase = z - 0.25 * PI;
        let even = 1.0 - 0.037133487 / (z * z);
        let odd = 0.069444444 / z - 0.037993059 / (z * z * z);
        return (cos(phase) * even + sin(phase) * odd) / (sqrt(PI) * sqrt(sqrt(w)));
    }
    let x3 = x * x * x;
    var f = 1.0;
    var g = x;
    var tf = 1.0;
    var tg = x;
    for (var k = 0u; k < 10u; k++) {
        let k3 = 3.0 * f32(k);
        tf *= x3 / ((k3 + 2.0) * (k3 + 3.0));
        tg *= x3 / ((k3 + 3.0) * (k3 + 4.0));
        f += tf;
        g += tg;
    }
    return 0.355028053887817 * f - 0.258819403792807 * g;
}

// The bow of `k` internal reflections in water of index `n`: its angle from the antisolar
// point (rad), and 2 b T_k 2 pi sqrt(1 / c) and c^(-1/3) (see the top of this file).
struct Bow {
    angle: f32,
    scale: f32,
    c_cbrt_inv: f32,
}

fn rainbow_bow(n: f32, k: u32) -> Bow {
    let kf = f32(k);
    let p2 = (kf + 1.0) * (kf + 1.0);
    let cos_i = sqrt((n * n - 1.0) / (p2 - 1.0));
    let sin_i = sqrt(1.0 - cos_i * cos_i);
    let sin_r = sin_i / n;
    let cos_r = sqrt(1.0 - sin_r * sin_r);
    let i = acos(cos_i);
    let r = asin(sin_r);
    let deviation = 2.0 * (i - r) + kf * (PI - 2.0 * r);
    // d^2 D / db^2 = D''(i) / cos^2 i, D''(i) = -2 (k + 1) r''(i).
    let r1 = cos_i / (n * cos_r);
    let r2 = (-sin_i * cos_r + cos_i * sin_r * r1) / (n * cos_r * cos_r);
    let c = -(kf + 1.0) * r2 / (cos_i * cos_i);
    // Fresnel at the surface (the same angles going in and coming out).
    let rs = (cos_i - n * cos_r) / (cos_i + n * cos_r);
    let rp = (n * cos_i - cos_r) / (n * cos_i + cos_r);
    let big_rs = rs * rs;
    let big_rp = rp * rp;
    let t = 0.5 * ((1.0 - big_rs) * (1.0 - big_rs) * pow(big_rs, kf) + (1.0 - big_rp) * (1.0 - big_rp) * pow(big_rp, kf));
    return Bow(abs(PI - deviation), 2.0 * sin_i * t * 2.0 * PI / sqrt(c), pow(c, -1.0 / 3.0));
}

// The primary and secondary bows' phase function at `phi` (rad) from the antisolar point
// (faded out toward the table's ends) for drops of radius `a` (m) at wavelength `nm`: per steradian, per unit extinction of the rain
// (half of a large drop's extinction is diffraction into the forward peak, Q_ext = 2).
fn rainbow_phase(phi: f32, a: f32, nm: f32) -> f32 {
    let deg = degrees(phi);
    let window = smoothstep(RAINBOW_MIN_DEG, RAINBOW_MIN_DEG + RAINBOW_FADE_DEG, deg)
        * (1.0 - smoothstep(RAINBOW_MAX_DEG - RAINBOW_FADE_DEG, RAINBOW_MAX_DEG, deg));
    let n = water_index(nm);
    let x23 = pow(2.0 * PI * a / (nm * 1e-9), 2.0 / 3.0);
    var sum = 0.0;
    for (var k = 1u; k <= 2u; k++) {
        let bow = rainbow_bow(n, k);
        let s = x23 * bow.c_cbrt_inv;
        // Into the bright side: inside the primary, outside the secondary.
        let eps = select(phi - bow.angle, bow.angle - phi, k == 1u);
        let ai = airy_ai(-s * eps);
        sum += bow.scale * sqrt(s) * ai * ai;
    }
    return window * 0.5 * sum / (2.0 * PI * sin(phi));
}

// CIE 1931 colour matching functions, Wyman, Sloan and Shirley 2013's multi-lobe fit.
fn cie_lobe(nm: f32, mu: f32, below: f32, above: f32) -> f32 {
    let t = (nm - mu) / select(above, below, nm < mu);
    return exp(-0.5 * t * t);
}

// Linear sRGB (D65) of a unit of light at `nm`.
fn spectral_rgb(nm: f32) -> vec3<f32> {
    let x = 1.056 * cie_lobe(nm, 599.8, 37.9, 31.0) + 0.362 * cie_lobe(nm, 442.0, 16.0, 26.7) - 0.065 * cie_lobe(nm, 501.1, 20.4, 26.2);
    let y = 0.821 * cie_lobe(nm, 568.8, 46.9, 40.5) + 0.286 * cie_lobe(nm, 530.9, 16.3, 31.1);
    let z = 1.217 * cie_lobe(nm, 437.0, 11.8, 36.0) + 0.681 * cie_lobe(nm, 459.0, 26.0, 13.8);
    return vec3<f32>(
        3.2406 * x - 1.5372 * y - 0.4986 * z,
        -0.9689 * x + 1.8758 * y + 0.0415 * z,
        0.0557 * x - 0.2040 * y + 1.0570 * z,
    );
}

// The Lee diagram's row for this scene's drops (Lee 1998, "Mie theory, Airy theory, and the
// natural rainbow"): each texel's angle, the bows' phase function summed over the spectrum
// (rgb, normalised so that a flat spectrum is white 1, 1, 1) and averaged over the sun's disc.
@compute @workgroup_size(8, 8, 1)
fn rainbow_lut(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= RAINBOW_TEXELS || id.y >= 1u {
        return;
    }
    let span = radians(RAINBOW_MAX_DEG - RAINBOW_MIN_DEG);
    let phi = radians(RAINBOW_MIN_DEG) + span * f32(id.x) / f32(RAINBOW_TEXELS - 1u);
    let sun_radius = acos(frame.sun_cos_radius);
    let a = frame.rainbow_drop_radius;
    var sum = vec3<f32>(0.0);
    var white = vec3<f32>(0.0);
    for (var j = 0u; j < RAINBOW_WAVELENGTHS; j++) {
        let nm = 400.0 + 300.0 * (f32(j) + 0.5) / f32(RAINBOW_WAVELENGTHS);
        let rgb = spectral_rgb(nm);
        white += rgb;
        var p = 0.0;
        var weights = 0.0;
        for (var m = 1u; m <= RAINBOW_SUN_TAPS; m++) {
            let u = f32(m) * PI / f32(RAINBOW_SUN_TAPS + 1u);
            let w = sin(u) * sin(u);
            p += w * rainbow_phase(phi + cos(u) * sun_radius, a, nm);
            weights += w;
        }
        sum += rgb * (p / weights);
    }
    textureStore(rainbow_lut_out, id.xy, vec4<f32>(max(sum / white, vec3<f32>(0.0)), 1.0));
}

// The bows' phase function (rgb) at `phi` (rad) from the antisolar point: the table's, or the
// cheap path's three wavelengths.
fn rainbow_phase_rgb(phi: f32) -> vec3<f32> {
    if (frame.flags & FLAG_LEE_DIAGRAM) != 0u {
        let x = (degrees(phi) - RAINBOW_MIN_DEG) / (RAINBOW_MAX_DEG - RAINBOW_MIN_DEG);
        return lut_bilinear(rainbow_lut_in, vec2<f32>(x, 0.0), vec2<u32>(RAINBOW_TEXELS, 1u)).rgb;
    }
    let a = frame.rainbow_drop_radius;
    return vec3<f32>(
        rainbow_phase(phi, a, RAINBOW_RGB_NM.r),
        rainbow_phase(phi, a, RAINBOW_RGB_NM.g),
        rainbow_phase(phi, a, RAINBOW_RGB_NM.b),
    );
}

// The moisture's weight at altitude `h` (m): (h / h0) e^(1 - h / h0), 1 at h0 = 2 km.
fn moisture_profile(h: f32) -> f32 {
    let x = max(h, 0.0) / MOISTURE_PEAK_M;
    return x * exp(1.0 - x);
}

// The rain at world point `p` (altitude p.y): under each precipitating layer whose bottom is
// above it, where the weather map has cloud, its precipitation.
fn rain_at(p: vec3<f32>) -> f32 {
    var rain = 0.0;
    for (var i = 0u; i < layer_count(); i++) {
        let l = cloud_layer(i);
        if l.precipitation > 0.0 && p.y < l.bottom {
            let w = sample_weather(p, l);
            rain += w.precipitation * smoothstep(0.35, 0.65, w.coverage);
        }
    }
    return rain;
}

// The highest bottom of a precipitating layer (m; 0 without one): rain falls below it.
fn rain_top() -> f32 {
    var top = 0.0;
    for (var i = 0u; i < layer_count(); i++) {
        let l = cloud_layer(i);
        if l.precipitation > 0.0 {
            top = max(top, l.bottom);
        }
    }
    return top;
}

// The bows' radiance along unit `view` from the camera (per unit key-light illuminance at the
// top of the air, rgb): the rain's single scattering of the key light into the bows, where the
// clouds (the cloud-shadow map, projected along the light) and the air let it through, seen
// through the air and the rain in front. Midpoint steps over the ray's first RAIN_RANGE_M m,
// until it rises above the rain or meets the ground. The rain is in front of the clouds above
// it, so the bows add to whatever the pixel shows behind them.
fn rainbow_radiance(view: vec3<f32>) -> vec3<f32> {
    if frame.rainbow_moisture <= 0.0 {
        return vec3<f32>(0.0);
    }
    let light = frame.sun_direction;
    let phi = acos(clamp(-dot(view, light), -1.0, 1.0));
    if phi < radians(RAINBOW_MIN_DEG) || phi > radians(RAINBOW_MAX_DEG) || light.y <= SHAFT_MIN_SUN_Y {
        return vec3<f32>(0.0);
    }
    let cam = frame.camera_position;
    let top = rain_top();
    var end = RAIN_RANGE_M;
    if view.y > 0.0 {
        end = min(end, max(top - cam.y, 0.0) / view.y);
    } else if view.y < 0.0 {
        end = min(end, cam.y / -view.y);
    }
    if !(end > 0.0) {
        return vec3<f32>(0.0);
    }
    let phase = rainbow_phase_rgb(phi);
    let origin = camera_air_origin();
    let dt = end / f32(RAIN_STEPS);
    var air_tau = vec3<f32>(0.0);
    var rain_tau = 0.0;
    var sum = vec3<f32>(0.0);
    for (var k = 0u; k < RAIN_STEPS; k++) {
        let t = (f32(k) + 0.5) * dt;
        let rel = view * t + vec3<f32>(0.0, cam.y, 0.0);
        let world = rel + vec3<f32>(cam.x, 0.0, cam.z);
        let air = air_at(rel.y * 1e-3);
        let beta = RAIN_EXTINCTION * frame.rainbow_moisture * moisture_profile(rel.y) * rain_at(world);
        if beta > 0.0 {
            let q = origin + view * (t * 1e-3);
            let r = length(q);
            let lit = ground_shadow(rel - light * (rel.y / light.y)) * sun_transmittance(r, dot(q / r, light));
            let seen = exp(-(air_tau + air.extinction * (0.5 * dt * 1e-3))) * exp(-(rain_tau + 0.5 * beta * dt));
            sum += lit * seen * (beta * dt);
        }
        air_tau += air.extinction * (dt * 1e-3);
        rain_tau += beta * dt;
    }
    return sum * phase;
}
// Empty-space skipping: a coarse occupancy grid over one tile of the weather map. Each cell
// holds the largest coverage value (the map's R) that a bilinear lookup inside the cell can
// return; where even that leaves no cloud under the scene's coverage, the density is 0 in the
// whole cell, at every altitude, and the view ray jumps to the cell's edge.

const OCCUPANCY_CELLS: u32 = 64u; // cells per side of the grid (one weather-map tile)

@group(0) @binding(11) var occupancy_in: texture_2d<f32>;                         // max coverage per cell
@group(0) @binding(12) var occupancy_out: texture_storage_2d<r32float, write>;   // the same, written once

// Builds the grid (a computed persistent resource: once, and again only when invalidated).
@compute @workgroup_size(8, 8, 1)
fn occupancy(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= vec2<u32>(OCCUPANCY_CELLS)) {
        return;
    }
    let size = vec2<i32>(textureDimensions(weather_tex));
    let cells = i32(OCCUPANCY_CELLS);
    // Texels whose bilinear footprint reaches into the cell: the cell's own and a one-texel
    // border (wrapping, as the sampler repeats).
    let lo = vec2<i32>(id.xy) * size / cells - 1;
    let hi = (vec2<i32>(id.xy) + 1) * size / cells;
    var m = 0.0;
    for (var y = lo.y; y <= hi.y; y++) {
        for (var x = lo.x; x <= hi.x; x++) {
            let t = (vec2<i32>(x, y) % size + size) % size;
            m = max(m, textureLoad(weather_tex, t, 0).r);
        }
    }
    textureStore(occupancy_out, id.xy, vec4<f32>(m, 0.0, 0.0, 0.0));
}

// At world position `p` on a ray along unit `d`: the distance to the edge of p's cell if
// the cell is empty (no cloud at any altitude), else 0.
fn empty_cell_exit(p: vec3<f32>, d: vec3<f32>) -> f32 {
    // The grid holds the map's coverage (R) alone: cumulus on convective cells stands where
    // the cell field (A) says, with or without it, and an anvil spreads kilometres beyond
    // its tower's cell, so no cell is known empty then.
    if frame.convective_cells > 0.0 || frame.anvil > 0.0 {
        return 0.0;
    }
    let cells = f32(OCCUPANCY_CELLS);
    let uv = fract((p.xz - frame.weather_offset) / frame.weather_period) * cells;
    let cell = min(vec2<u32>(uv), vec2<u32>(OCCUPANCY_CELLS - 1u));
    let m = textureLoad(occupancy_in, cell, 0).r;
    // sample_weather's coverage: saturate(r + 2 (coverage - 0.5)); a margin of one 8-bit
    // step covers rounding in the filtered lookup.
    if m + 2.0 * (frame.coverage - 0.5) > -1.0 / 255.0 {
        return 0.0;
    }
    // The ray's horizontal motion is linear in t: the nearer of the two cell walls it heads to.
    let cell_m = frame.weather_period / cells;
    let inside = (uv - vec2<f32>(cell)) * cell_m; // metres from the cell's low corner
    var exit = 1e30;
    if d.x > 1e-6 {
        exit = min(exit, (cell_m - inside.x) / d.x);
    } else if d.x < -1e-6 {
        exit = min(exit, inside.x / -d.x);
    }
    if d.z > 1e-6 {
        exit = min(exit, (cell_m - inside.y) / d.z);
    } else if d.z < -1e-6 {
        exit = min(exit, inside.y / -d.z);
    }
    return max(exit, 0.0);
}
// The view march (thesis alg. 5.1): one invocation per pixel marches its ray through the
// cloud layer and writes linear in-scattered radiance and transmittance.

@group(0) @binding(6) var cloud_out: texture_storage_2d<rgba32float, write>; // radiance rgb, transmittance
@group(0) @binding(7) var depth_out: texture_storage_2d<r32float, write>;    // transmittance-weighted depth (m), 0 where no cloud
@group(0) @binding(42) var scene_depth_in: texture_2d<f32>;                  // the host's clip-space depth (FLAG_SCENE_DEPTH)

// The distance along a view ray where nothing stops it.
const NO_SURFACE: f32 = 3.0e38;

// Whether the host's geometry covers `pixel` (its depth is not the far plane's).
fn has_surface(pixel: vec2<u32>) -> bool {
    if (frame.flags & FLAG_SCENE_DEPTH) == 0u {
        return false;
    }
    return textureLoad(scene_depth_in, pixel, 0).r != frame.scene_depth_clear;
}

// The distance along the view ray `view` of `pixel` to the host's geometry (m), NO_SURFACE
// where there is none. The depth d lies at B / (d + A) along the view axis (the projection's
// terms); the ray is longer by 1 / cos of its angle to the axis.
fn scene_surface(pixel: vec2<u32>, view: vec3<f32>) -> f32 {
    if !has_surface(pixel) {
        return NO_SURFACE;
    }
    let d = textureLoad(scene_depth_in, pixel, 0).r;
    let axis = frame.scene_depth_b / (d + frame.scene_depth_a);
    return axis / dot(view, frame.camera_forward);
}

// `s` cut at the surface at distance `surface`: shortened where the surface is inside it,
// missed where the surface is in front of it.
fn clip_to_surface(s: Interval, surface: f32) -> Interval {
    if s.kind != RAY_MARCH || s.start + s.length <= surface {
        return s;
    }
    if s.start >= surface {
        return Interval(0.0, 0.0, RAY_MISSES_LAYER);
    }
    return Interval(s.start, surface - s.start, RAY_MARCH);
}

// Work counters (the statistics variant). Indices are named by the `stats` resource in the
// frame graph (wgsl/graph.toml), checked against these values at build time.
const STAT_PIXELS: u32 = 0u;           // pixels processed
const STAT_MARCHED: u32 = 1u;          // pixels whose ray marched the layer
const STAT_VIEW_STEPS: u32 = 2u;       // view-ray steps taken
const STAT_DENSITY: u32 = 3u;          // density evaluations (view and light)
const STAT_DETAIL: u32 = 4u;           // detail-noise evaluations
const STAT_LIGHT: u32 = 5u;            // light-march samples
const STAT_EXIT_TRANSMITTANCE: u32 = 6u; // marches ended early: transmittance below threshold
const STAT_EXIT_MISSED: u32 = 7u;      // rays that miss the layer (nothing to march)
const STAT_EXIT_GROUND: u32 = 8u;      // rays that hit the ground before the layer
const STAT_COUNT: u32 = 9u;

struct Stats {
    counters: array<atomic<u32>, STAT_COUNT>,
}

@group(0) @binding(8) var<storage, read_write> stats: Stats;

fn count(index: u32, value: u32) {
    if STATS && value != 0u {
        atomicAdd(&stats.counters[index], value);
    }
}

// Scattering integrated over one step of length `dt` with extinction `sigma_t`, for a source
// `source` (radiance per unit length) that is constant over the step.
fn step_integral(source: vec3<f32>, sigma_t: f32, dt: f32) -> vec3<f32> {
    if frame.integration == INTEGRATION_RIEMANN {
        // Naive Riemann sum: overshoots when sigma_t * dt is large (kept to show where it fails).
        return source * dt;
    }
    // Hillaire's energy-conserving form (thesis alg. 5.4): (S - S Tr) / sigma_t, written as
    // S dt (1 - e^-x) / x with x = sigma_t dt and a series near 0, so it never divides by 0.
    let x = sigma_t * dt;
    let f = select((1.0 - exp(-x)) / x, 1.0 - 0.5 * x, x < 1e-3);
    return source * (dt * f);
}

// What the march of one view ray produced.
struct MarchResult {
    radiance: vec3<f32>,   // in-scattered radiance
    transmittance: f32,
    depth: f32,            // transmittance-weighted depth (m), 0 where no cloud
}

// The view march's start offset (in steps, [0, 1)) for `pixel`. Without temporal upsampling:
// 0.5, or the per-pixel, per-frame hash with jitter. With it, the thesis's van der Corput
// sequence over the pixel's successive marches (one per `block^2` frames), shifted by a fixed
// per-pixel hash with jitter: each pixel's marches stratify its step interval.
fn start_offset(pixel: vec2<u32>) -> f32 {
    let jitter = (frame.flags & FLAG_JITTER) != 0u;
    let k = frame.block_side;
    if k <= 1u {
        return select(0.5, hash_unit(pixel, frame.frame_index), jitter);
    }
    let base = select(0.5, hash_unit(pixel, 0u), jitter);
    return fract(base + van_der_corput(frame.frame_index / (k * k)));
}

// What a view march has gathered so far (across layers).
struct MarchState {
    radiance: vec3<f32>,
    transmittance: f32,
    depth_sum: f32,  // sum of t * (fraction of the light removed at t)
    octaves: vec3<f32>,  // the octaves' part of `radiance` (forward_lobe)
}

// The view march (thesis alg. 5.1) of the ray through `pixel`, counting its work. Each cloud
// layer is marched on its own interval with the full step count, nearest first: the ray's
// intervals in different layers never overlap because the layers' altitude ranges do not.
// The host's geometry ends the ray: each interval is cut at its surface (a layer behind it is
// not marched), so geometry inside a cloud gets the transmittance and light up to it.
fn march_pixel(pixel: vec2<u32>) -> MarchResult {
    let view = view_ray(pixel);
    let surface = scene_surface(pixel, view);
    let cam_alt = frame.camera_position.y;
    var counters = Counters(0u, 0u, 0u, 0u);
    count(STAT_PIXELS, 1u);

    var state = MarchState(vec3<f32>(0.0), 1.0, 0.0, vec3<f32>(0.0));
    let jitter = start_offset(pixel);
    let n = layer_count();
    var marched = false;
    var ground = false;
    var last_start = -1.0;
    var last_index = NO_LAYER;
    var exited = false;
    for (var k = 0u; k < n; k++) {
        // The nearest layer not marched yet: the smallest (start, index) after the last one.
        var next = NO_LAYER;
        var span = Interval(0.0, 0.0, RAY_MISSES_LAYER);
        for (var i = 0u; i < n; i++) {
            let s = clip_to_surface(layer_interval(cam_alt, view, cloud_layer(i)), surface);
            ground = ground || s.kind == RAY_HITS_GROUND;
            let after = s.start > last_start || (s.start == last_start && i > last_index);
            if s.kind == RAY_MARCH && after && (next == NO_LAYER || s.start < span.start) {
                next = i;
                span = s;
            }
        }
        if next == NO_LAYER {
            break;
        }
        marched = true;
        last_start = span.start;
        last_index = next;
        if march_layer(view, span, cloud_layer(next), jitter, &state, &counters) {
            count(STAT_EXIT_TRANSMITTANCE, 1u);
            exited = true;
            break;
        }
    }
    if marched {
        count(STAT_MARCHED, 1u);
    } else if ground {
        count(STAT_EXIT_GROUND, 1u);
    } else {
        count(STAT_EXIT_MISSED, 1u);
    }

    count(STAT_VIEW_STEPS, counters.view_steps);
    count(STAT_DENSITY, counters.density);
    count(STAT_DETAIL, counters.detail);
    count(STAT_LIGHT, counters.light);
    var depth = 0.0;
    if state.transmittance < 1.0 {
        depth = state.depth_sum / (1.0 - state.transmittance);
    }
    // A march that ends early ends the pixel: nothing behind the cloud may show through the
    // transmittance left (up to the threshold, 1%), least of all the sun's or the moon's disc,
    // whose radiance is 10^5 times the sky's.
    let transmittance = select(state.transmittance, 0.0, exited);
    // The octaves' forward lobe, weighted by the transmittance the march reached.
    let lobe = forward_lobe(dot(view, frame.sun_direction), state.transmittance);
    let radiance = state.radiance + state.octaves * (lobe - 1.0);
    return MarchResult(radiance, transmittance, depth);
}

// The most view steps within close-range detail's range (scene MAX_CLOSE_STEPS, which
// validation holds `clouds.close_detail_range_m / quality.close_step_m` to).
const MAX_CLOSE_STEPS: u32 = 256u;

// The march of the view ray's interval `span` in layer `l`, added to `state`. True when the
// transmittance fell below the early-exit threshold (the pixel is done).
// With close-range detail on (density.wgsl close_detail_weight) the part of the interval
// within `frame.close_detail_range` of the camera is marched first in steps of
// `frame.close_step` (at most MAX_CLOSE_STEPS of them, never coarser than the steps beyond), so
// that its wisps metres across are sampled and not aliased into noise by steps of tens or
// hundreds of metres; the rest of the interval keeps the step it would have had.
fn march_layer(view: vec3<f32>, span: Interval, l: Layer, jitter: f32,
               state: ptr<function, MarchState>, counters: ptr<function, Counters>) -> bool {
    var steps = frame.view_steps;
    if frame.step_length > 0.0 {
        steps = clamp(u32(ceil(span.length / frame.step_length)), 1u, MAX_VIEW_STEPS);
    }
    let near = frame.close_detail_range - span.start;
    if frame.close_detail <= 0.0 || !(near > 0.0) {
        return march_segment(view, span.start, span.length, steps, l, jitter, state, counters);
    }
    let dt = span.length / f32(steps);
    let near_length = min(near, span.length);
    // The bound caps the close steps alone: where the ray's own steps are finer still (a short
    // `quality.step_length_m`, a converged reference) they stay, at most `steps` of them.
    let close = min(ceil(near_length / frame.close_step), f32(MAX_CLOSE_STEPS));
    let near_steps = max(u32(max(close, ceil(near_length / dt))), 1u);
    if march_segment(view, span.start, near_length, near_steps, l, jitter, state, counters) {
        return true;
    }
    let rest = span.length - near_length;
    if !(rest > 0.0) {
        return false;
    }
    let far_steps = clamp(u32(ceil(rest / dt)), 1u, steps);
    return march_segment(view, span.start + near_length, rest, far_steps, l, jitter, state,
                         counters);
}

// The march of `steps` equal steps of the view ray from `start` over `extent` (m) in layer
// `l`, added to `state`; true when the transmittance fell below the early-exit threshold.
fn march_segment(view: vec3<f32>, start: f32, extent: f32, steps: u32, l: Layer, jitter: f32,
                 state: ptr<function, MarchState>, counters: ptr<function, Counters>) -> bool {
    let cam_alt = frame.camera_position.y;
    let cam_xz = frame.camera_position.xz;
    let dt = extent / f32(steps);
    let sigma_e = frame.scattering + frame.absorption;
    let dynamic_step = (frame.flags & FLAG_DYNAMIC_STEP) != 0u;
    let empty_skip = (frame.flags & FLAG_EMPTY_SKIP) != 0u;
    // Samples lie on one grid, t_i = start + (i + jitter) dt; the cheap-march techniques
    // only choose which i to visit, so they never move a sample.
    var i = 0u;
    var stride = 1u;   // 2 after 8 empty samples with the dynamic step
    var empty = 0u;    // empty samples in a row
    loop {
        if i >= steps {
            break;
        }
        (*counters).view_steps += 1u;
        let t = start + (f32(i) + jitter) * dt;
        let rel = view * t + vec3<f32>(0.0, cam_alt, 0.0);
        let p = vec3<f32>(rel.x + cam_xz.x, rel.y, rel.z + cam_xz.y);
        if empty_skip {
            // In a cell where the weather leaves no cloud: jump to the first sample past
            // the cell's edge.
            let exit = empty_cell_exit(p, view);
            if exit > 0.0 {
                let next = u32(clamp(ceil((t + exit - start) / dt - jitter), 0.0, f32(steps)));
                i = max(i + 1u, next);
                continue;
            }
        }
        let alt = altitude_of(rel);
        let density = layer_density(p, alt, l, counters);
        if density <= 0.0 {
            empty += 1u;
            if dynamic_step && empty >= 8u {
                stride = 2u;
            }
            i += stride;
            continue;
        }
        if stride > 1u {
            // Entered cloud on a long step: go back to the sample skipped over and
            // continue at the fine step.
            i -= stride - 1u;
            stride = 1u;
            empty = 0u;
            continue;
        }
        empty = 0u;
        let sigma_t = sigma_e * density;
        let source = scattered_light(rel, p, alt, density, view, l, counters);
        let transmittance = (*state).transmittance;
        (*state).radiance += transmittance * step_integral(source.total, sigma_t, dt);
        (*state).octaves += transmittance * step_integral(source.octaves, sigma_t, dt);
        let step_t = exp(-sigma_t * dt);
        (*state).depth_sum += t * transmittance * (1.0 - step_t);
        (*state).transmittance = transmittance * step_t;
        if (*state).transmittance < frame.early_exit_transmittance {
            return true;
        }
        i += 1u;
    }
    return false;
}

// Every pixel, every frame.
@compute @workgroup_size(8, 8, 1)
fn march(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.size) {
        return;
    }
    let r = march_pixel(id.xy);
    textureStore(cloud_out, id.xy, vec4<f32>(r.radiance, r.transmittance));
    textureStore(depth_out, id.xy, vec4<f32>(r.depth, 0.0, 0.0, 0.0));
}
// Temporal upsampling (thesis 6.1; Horizon Zero Dawn's 1-in-16 update). Each frame marches
// one pixel of every k x k block (k = frame.block_side), visiting the block's pixels in Bayer
// order, each march with the next van der Corput start offset. The resolve pass rebuilds the
// full-resolution image: the marched pixel blends into its history; every other pixel takes
// last frame's result, reprojected through last frame's camera at the clouds' transmittance-
// weighted depth and clamped to the current frame's neighbourhood while the camera moves;
// pixels whose history is off screen or disoccluded are marched in full.

@group(0) @binding(13) var history_in: texture_2d<f32>;                         // last frame: radiance, transmittance
@group(0) @binding(14) var meta_in: texture_2d<f32>;                            // last frame: depth (m), samples
@group(0) @binding(15) var sparse_in: texture_2d<f32>;                          // this frame's marched pixels
@group(0) @binding(16) var sparse_depth_in: texture_2d<f32>;                    // their depth
@group(0) @binding(17) var history_out: texture_storage_2d<rgba32float, write>; // this frame: radiance, transmittance
@group(0) @binding(18) var meta_out: texture_storage_2d<rgba32float, write>;    // this frame: depth, samples, 1 where the host's geometry cut the march

// Samples a pixel's history averages at most: a running mean of its marches (so a still
// camera converges to the mean over the van der Corput offsets), then an exponential blend of
// 1/16, near the thesis's 5% (its appendix B). While the camera moves, 2 (and history that was
// only resampled counts as none, so a march replaces it): new marches weigh more, so less
// ghosting.
const HISTORY_SAMPLES: f32 = 16.0;
const HISTORY_SAMPLES_MOVING: f32 = 2.0;
// History whose depth differs from the reprojected point's by more than this fraction is
// something else: disoccluded, marched again. (0.2 re-marched much of every cloud edge while
// moving, where the block's depth is another pixel's: at 1/16 the resolve cost more than the
// sparse march.)
const DISOCCLUSION_DEPTH: f32 = 0.5;

// The position in a 2 x 2 block of the pixel with Bayer rank `v` (the ordered-dither matrix
// [[0, 2], [3, 1]]: rank 0 at (0, 0), 1 at (1, 1), 2 at (1, 0), 3 at (0, 1)).
fn bayer2(v: u32) -> vec2<u32> {
    return vec2<u32>((v ^ (v >> 1u)) & 1u, v & 1u);
}

// The pixel of each k x k block marched in frame `f`: Bayer order, so consecutive frames
// spread over the block. The 4 x 4 matrix is 4 M2(x mod 2, y mod 2) + M2(x / 2, y / 2), so
// rank b sits at bayer2(b / 4) + 2 bayer2(b mod 4). (Arithmetic, not a table: lavapipe
// crashed compiling glslang's SPIR-V for a dynamically indexed local array.)
fn block_offset(f: u32, k: u32) -> vec2<u32> {
    if k == 2u {
        return bayer2(f % 4u);
    }
    if k == 4u {
        let b = f % 16u;
        return bayer2(b >> 2u) + 2u * bayer2(b & 3u);
    }
    return vec2<u32>(0u);
}

// Whether this frame's camera is last frame's: same place, orientation, field of view, aspect
// and exposure (a moved camera restarts the path tracer's accumulation).
fn camera_still() -> bool {
    return all(frame.camera_position == frame.previous_position)
        && frame.tan_half_fov == frame.previous_tan_half_fov
        && all(frame.camera_forward == frame.previous_forward)
        && frame.aspect == frame.previous_aspect
        && all(frame.camera_right == frame.previous_right)
        && frame.exposure == frame.previous_exposure
        && all(frame.camera_up == frame.previous_up);
}

// Where the point at distance `depth` along the current view ray of `pixel` was in last
// frame's image (pixel coordinates, centres at integers + 0.5 - 0.5 = integers). `depth` 0:
// a point at infinity (only the direction moves). x = -1e9 when it was behind the camera.
fn reproject(pixel: vec2<u32>, depth: f32) -> vec2<f32> {
    let same = camera_still();
    if same {
        // A still camera reprojects exactly onto itself (no resampling blur).
        return vec2<f32>(pixel);
    }
    let view = view_ray(pixel);
    var dir = view;
    if depth > 0.0 {
        dir = view * depth + (frame.camera_position - frame.previous_position);
    }
    let z = dot(dir, frame.previous_forward);
    if z <= 0.0 {
        return vec2<f32>(-1e9);
    }
    let tan_half = frame.previous_tan_half_fov;
    let aspect = frame.previous_aspect;
    let ndc = vec2<f32>(
        dot(dir, frame.previous_right) / (z * tan_half * aspect),
        -dot(dir, frame.previous_up) / (z * tan_half),
    );
    return (ndc * 0.5 + 0.5) * vec2<f32>(frame.size) - 0.5;
}

fn on_screen(q: vec2<f32>) -> bool {
    let size = vec2<f32>(frame.size);
    return all(q >= vec2<f32>(-0.5)) && all(q <= size - 0.5);
}

// Catmull-Rom weights of the four taps around a sample at fraction `t` past the second.
fn catmull_rom(t: f32) -> vec4<f32> {
    return vec4<f32>(
        t * (-0.5 + t * (1.0 - 0.5 * t)),
        1.0 + t * t * (-2.5 + 1.5 * t),
        t * (0.5 + t * (2.0 - 1.5 * t)),
        t * t * (-0.5 + 0.5 * t),
    );
}

// Last frame's radiance and transmittance at `q`: Catmull-Rom over 4 x 4 texels (by hand:
// loads, the same on every backend and for float formats that cannot be filtered). A bicubic
// keeps the detail that bilinear resampling would blur away a little more every frame the
// camera moves; its overshoot is clamped to the physical range.
fn history_at(q: vec2<f32>) -> vec4<f32> {
    let size = vec2<i32>(frame.size);
    let c = clamp(q, vec2<f32>(0.0), vec2<f32>(size - 1));
    let base = vec2<i32>(floor(c));
    let f = c - vec2<f32>(base);
    let wx = catmull_rom(f.x);
    let wy = catmull_rom(f.y);
    // Written out, no dynamically indexed vectors (lavapipe crashed compiling glslang's
    // SPIR-V for those).
    let sum = history_row(base, -1, wx) * wy.x + history_row(base, 0, wx) * wy.y
        + history_row(base, 1, wx) * wy.z + history_row(base, 2, wx) * wy.w;
    return vec4<f32>(max(sum.rgb, vec3<f32>(0.0)), saturate(sum.a));
}

// One row (`dy` from `base`) of the Catmull-Rom footprint, weighted by `wx`; clamped at the
// image's edges.
fn history_row(base: vec2<i32>, dy: i32, wx: vec4<f32>) -> vec4<f32> {
    let size = vec2<i32>(frame.size);
    let y = clamp(base.y + dy, 0, size.y - 1);
    let x0 = clamp(base.x - 1, 0, size.x - 1);
    let x1 = clamp(base.x, 0, size.x - 1);
    let x2 = clamp(base.x + 1, 0, size.x - 1);
    let x3 = clamp(base.x + 2, 0, size.x - 1);
    return textureLoad(history_in, vec2<i32>(x0, y), 0) * wx.x
        + textureLoad(history_in, vec2<i32>(x1, y), 0) * wx.y
        + textureLoad(history_in, vec2<i32>(x2, y), 0) * wx.z
        + textureLoad(history_in, vec2<i32>(x3, y), 0) * wx.w;
}

fn history_nearest(q: vec2<f32>) -> vec4<f32> {
    let size = vec2<i32>(frame.size);
    let p = clamp(vec2<i32>(round(q)), vec2<i32>(0), size - 1);
    return textureLoad(history_in, p, 0);
}

fn meta_at(q: vec2<f32>) -> vec4<f32> {
    let size = vec2<i32>(frame.size);
    let p = clamp(vec2<i32>(round(q)), vec2<i32>(0), size - 1);
    return textureLoad(meta_in, p, 0);
}

// Whether any texel of the Catmull-Rom footprint at `q` (history_at's 4 x 4) was cut by the
// host's geometry last frame: resampled there, the geometry's hole in the clouds would trail
// the geometry as a halo.
fn footprint_cut(q: vec2<f32>) -> bool {
    let size = vec2<i32>(frame.size);
    let base = vec2<i32>(floor(clamp(q, vec2<f32>(0.0), vec2<f32>(size - 1))));
    var cut = 0.0;
    for (var dy = -1; dy <= 2; dy++) {
        for (var dx = -1; dx <= 2; dx++) {
            let p = clamp(base + vec2<i32>(dx, dy), vec2<i32>(0), size - 1);
            cut = max(cut, textureLoad(meta_in, p, 0).z);
        }
    }
    return cut > 0.0;
}

// The marching pass: one pixel per block (`march_sparse`), or the same with thesis 6.2.2's
// checkerboard skipping (`march_sparse_checkerboard`). Two entry points rather than a runtime
// switch: the skipping code alone, never run, made the whole march 2.5 times slower on
// lavapipe (128x72: 10.3 ms against 4.0 ms).

// Whether block `id` is inside the sparse target.
fn in_blocks(id: vec2<u32>) -> bool {
    let k = frame.block_side;
    return all(id < (frame.size + k - 1u) / k);
}

// The pixel block `id` marches this frame.
fn sparse_pixel(id: vec2<u32>) -> vec2<u32> {
    let k = frame.block_side;
    return id * k + block_offset(frame.frame_index, k);
}

fn store_sparse(id: vec2<u32>, r: MarchResult) {
    textureStore(cloud_out, id, vec4<f32>(r.radiance, r.transmittance));
    textureStore(depth_out, id, vec4<f32>(r.depth, 0.0, 0.0, 0.0));
}

@compute @workgroup_size(8, 8, 1)
fn march_sparse(@builtin(global_invocation_id) id: vec3<u32>) {
    if !in_blocks(id.xy) {
        return;
    }
    let pixel = sparse_pixel(id.xy);
    var r = MarchResult(vec3<f32>(0.0), 1.0, 0.0);
    if all(pixel < frame.size) {
        r = march_pixel(pixel);
    }
    store_sparse(id.xy, r);
}

@compute @workgroup_size(8, 8, 1)
fn march_sparse_checkerboard(@builtin(global_invocation_id) id: vec3<u32>) {
    if !in_blocks(id.xy) {
        return;
    }
    let pixel = sparse_pixel(id.xy);
    var r = MarchResult(vec3<f32>(0.0), 1.0, 0.0);
    var skip = any(pixel >= frame.size);
    if !skip && frame.history_valid != 0u && !has_surface(pixel) {
        // Where last frame saw clear sky in this direction (the nearest texel), skip the
        // march in every other turn of the pixel, alternating between neighbouring blocks,
        // so clouds that the wind moves in are found within two turns. (Not where the host's
        // geometry is: its pixels are marched every frame.)
        let k = frame.block_side;
        let turn = frame.frame_index / (k * k);
        let q = reproject(pixel, 0.0);
        if ((id.x + id.y + turn) & 1u) == 0u && on_screen(q) && history_nearest(q).a >= 1.0 {
            skip = true;
        }
    }
    if !skip {
        r = march_pixel(pixel);
    }
    store_sparse(id.xy, r);
}

// The resolve pass: every pixel of the output.
@compute @workgroup_size(8, 8, 1)
fn resolve(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.size) {
        return;
    }
    let pixel = id.xy;
    let k = frame.block_side;
    let block = pixel / k;
    let marched = all(pixel == block * k + block_offset(frame.frame_index, k));
    let current = textureLoad(sparse_in, block, 0);
    let current_depth = textureLoad(sparse_depth_in, block, 0).r;

    // The depth to reproject at: this block's march; where it saw no cloud, the middle of
    // the layer along the ray (where clouds would be); a ray that misses the layer has only
    // sky, which moves with the direction.
    var depth = current_depth;
    if depth <= 0.0 {
        let span = nearest_layer_interval(frame.camera_position.y, view_ray(pixel));
        if span.kind == RAY_MARCH {
            depth = span.start + 0.5 * span.length;
        }
    }
    let q = reproject(pixel, depth);
    // The host's geometry: a pixel it covers is marched every frame (its march is cut at the
    // surface, so history from any other depth would be wrong, and in front of the layer the
    // march costs nothing), and history cut by last frame's geometry is not resampled.
    let surface = has_surface(pixel);
    let moving = any(q != vec2<f32>(pixel));
    var valid = frame.history_valid != 0u && on_screen(q) && !surface;
    if valid && (frame.flags & FLAG_SCENE_DEPTH) != 0u {
        valid = !select(meta_at(q).z > 0.0, footprint_cut(q), moving);
    }
    var history = vec4<f32>(0.0, 0.0, 0.0, 1.0);
    var past = vec4<f32>(0.0);
    if valid {
        history = history_at(q);
        past = meta_at(q);
        // Disoccluded: while the camera moves, history seen at another depth than where this
        // frame's march puts the cloud. (A still camera uncovers nothing; and this block's
        // depth is another pixel's, which at cloud edges would reject good history.)
        if moving && current_depth > 0.0 && past.x > 0.0 {
            let expected = distance(frame.camera_position + view_ray(pixel) * current_depth,
                frame.previous_position);
            valid = abs(past.x - expected) <= DISOCCLUSION_DEPTH * expected;
        }
    }
    if valid && moving {
        // Neighbourhood clamp: last frame's value may not leave the range of this frame's
        // marches around the pixel (3 x 3 blocks), which rejects stale, ghosting history.
        let blocks = vec2<i32>((frame.size + k - 1u) / k);
        let b = vec2<i32>(block);
        let x0 = max(b.x - 1, 0);
        let x2 = min(b.x + 1, blocks.x - 1);
        let y0 = max(b.y - 1, 0);
        let y2 = min(b.y + 1, blocks.y - 1);
        let s00 = textureLoad(sparse_in, vec2<i32>(x0, y0), 0);
        let s10 = textureLoad(sparse_in, vec2<i32>(b.x, y0), 0);
        let s20 = textureLoad(sparse_in, vec2<i32>(x2, y0), 0);
        let s01 = textureLoad(sparse_in, vec2<i32>(x0, b.y), 0);
        let s11 = textureLoad(sparse_in, b, 0);
        let s21 = textureLoad(sparse_in, vec2<i32>(x2, b.y), 0);
        let s02 = textureLoad(sparse_in, vec2<i32>(x0, y2), 0);
        let s12 = textureLoad(sparse_in, vec2<i32>(b.x, y2), 0);
        let s22 = textureLoad(sparse_in, vec2<i32>(x2, y2), 0);
        let lo = min(min(min(s00, s10), min(s20, s01)), min(min(s11, s21), min(min(s02, s12), s22)));
        let hi = max(max(max(s00, s10), max(s20, s01)), max(max(s11, s21), max(max(s02, s12), s22)));
        history = clamp(history, lo, hi);
    }

    var result: vec4<f32>;
    var samples: f32;
    var out_depth: f32;
    if marched {
        if valid {
            samples = min(past.y + 1.0, select(HISTORY_SAMPLES, HISTORY_SAMPLES_MOVING, moving));
            result = mix(history, current, 1.0 / samples);
        } else {
            samples = 1.0;
            result = current;
        }
        out_depth = select(past.x, current_depth, current_depth > 0.0 || !valid);
    } else if valid {
        // History resampled while the camera moves counts as no march: the pixel's next
        // march replaces it. (Counted on, a blurred history outweighed the marches after a
        // stop: at 1/16 more than 128 frames to come within FLIP 0.01 of the still.)
        samples = select(past.y, 0.0, moving);
        result = history;
        out_depth = past.x;
    } else {
        // Off screen or disoccluded, and not this pixel's turn: march it now.
        let r = march_pixel(pixel);
        samples = 1.0;
        result = vec4<f32>(r.radiance, r.transmittance);
        out_depth = r.depth;
    }
    textureStore(history_out, pixel, result);
    textureStore(meta_out, pixel, vec4<f32>(out_depth, samples, select(0.0, 1.0, surface), 0.0));
    textureStore(cloud_out, pixel, result);
    textureStore(depth_out, pixel, vec4<f32>(out_depth, 0.0, 0.0, 0.0));
}
// A volumetric path tracer through the same density field as the march: the all-orders truth
// the march's multiple-scattering approximation is measured against, accumulated over frames.
//
// Estimators (Novák et al. 2018, "Monte Carlo methods for volumetric light transport
// simulation"; the CPU path tracer, crates/reference/src/montecarlo.rs, is the same algorithm
// in f64 and explains each choice at length):
// * free flight: delta tracking (Woodcock) with the majorant sigma_t * d_max, d_max bounding
//   the density (multiplier * (1 + precipitation), at most 1);
// * transmittance (toward the sun, toward the environment, and the camera ray's alpha): ratio
//   tracking (Novák et al. 2014), with Russian roulette once below 0.01;
// * at a collision the throughput takes the single-scattering albedo; next-event estimation
//   to the sun; the path goes on along a phase-sampled direction, and where it leaves the
//   layer it sees the environment (`environment`: the sky and lit ground in its direction
//   seen from the collision it left under the physical sky, else a uniform ambient(h), h
//   that collision's height); Russian roulette on the throughput after the third order;
// * directions from Henyey-Greenstein (the two-lobe model samples its mixture; Cornette-Shanks
//   samples HG(g) weighted by CS/HG).
// The octaves, Beer-Powder and precipitation darkening are the march's approximations and are
// not used here; `orders` (path_orders) caps the scattering orders (0 = all, up to MAX_PATH_ORDERS).
//
// Progressive: each frame adds PATHS_PER_FRAME paths per pixel (their random streams seeded by
// the frame, frame_index, and the lane) to the running means in `history` (radiance,
// transmittance) and `history-meta` (depth, paths, mean squared luminance, paths that hit
// cloud). A cut, a new plan or a moved camera starts over; a host that changes anything else
// (sun, wind) cuts the history itself.

// A path of more orders than this ends (a conservative thick cloud needs hundreds; this only
// bounds pathological cases so that an invocation's work is finite).
const MAX_PATH_ORDERS: u32 = 16384u;

// One random stream per path: a 32-bit LCG with PCG's RXS-M-XS output (O'Neill 2014), seeded
// by the pixel and the path's index (frame and lane).
fn rng_seed(pixel: vec2<u32>, path_index: u32) -> u32 {
    return pcg(pixel.x ^ pcg(pixel.y ^ pcg(path_index)));
}

// Uniform in [0, 1), 24 bits.
fn rng_next(rng: ptr<function, u32>) -> f32 {
    *rng = *rng * 747796405u + 2891336453u;
    let s = *rng;
    let word = ((s >> ((s >> 28u) + 4u)) ^ s) * 277803737u;
    return f32(((word >> 22u) ^ word) >> 8u) * (1.0 / 16777216.0);
}

// An exponential distance of rate `sigma` (1 - u > 0 always).
fn rng_exponential(rng: ptr<function, u32>, sigma: f32) -> f32 {
    return -log(1.0 - rng_next(rng)) / sigma;
}

// Up to two parts of a ray inside the cloud layer (a ray from inside that dips below the
// layer without meeting the ground comes back up through it).
struct Segments {
    a: vec2<f32>,   // starts
    b: vec2<f32>,   // ends
    count: u32,
}

// The parts of the ray from `p` along unit `d` inside the shell that holds every layer (no
// cut-off: scattered light sees the whole medium; between layers the density is 0).
fn layer_segments(p: vec3<f32>, alt: f32, d: vec3<f32>) -> Segments {
    var s = Segments(vec2<f32>(0.0), vec2<f32>(0.0), 0u);
    let span = layers_span();
    let bottom = span.x;
    let inner = ray_shell_from(p, alt, d, bottom);
    let outer = ray_shell_from(p, alt, d, span.y);
    let ground = hits_ground(p, alt, d);
    if !outer.hit || outer.t1 <= 0.0 {
        return s;
    }
    let entry = max(outer.t0, 0.0);
    var a = vec2<f32>(0.0);
    var b = vec2<f32>(0.0);
    var n = 0u;
    if inner.hit && inner.t0 > 0.0 && alt >= bottom {
        // Down into the bottom shell; back up unless the ground stops it.
        a[n] = entry;
        b[n] = inner.t0;
        n += u32(inner.t0 > entry);
        if !ground && outer.t1 > inner.t1 {
            a[n] = max(inner.t1, entry);
            b[n] = outer.t1;
            n += 1u;
        }
    } else if alt < bottom {
        if !ground && inner.hit {
            a[0] = max(inner.t1, 0.0);
            b[0] = outer.t1;
            n = 1u;
        }
    } else {
        a[0] = entry;
        b[0] = outer.t1;
        n = 1u;
    }
    s.a = a;
    s.b = b;
    s.count = n;
    return s;
}

// Density at camera-relative `rel`.
fn density_at(rel: vec3<f32>, counters: ptr<function, Counters>) -> f32 {
    let p = vec3<f32>(rel.x + frame.camera_position.x, rel.y, rel.z + frame.camera_position.z);
    return cloud_density(p, altitude_of(rel), counters);
}

// How far the ray from camera-relative `origin` along `dir` may jump from distance `t`: past
// the edge of an empty occupancy cell (no cloud at any altitude), else 0. Both trackers sample
// distances afresh after a jump, which the exponential's lack of memory allows. The jump ends
// 5 cm inside the next cell so that rounding cannot leave the ray on the wall (the density of
// those 5 cm is not sampled: a bias below 0.2% of one mean free path per wall). The grid
// covers the main layer's weather only, so with several layers nothing is skipped.
fn empty_cell_skip(origin: vec3<f32>, dir: vec3<f32>, t: f32) -> f32 {
    if layer_count() > 1u {
        return 0.0;
    }
    let rel = origin + dir * t;
    let p = vec3<f32>(rel.x + frame.camera_position.x, rel.y, rel.z + frame.camera_position.z);
    let exit = empty_cell_exit(p, dir);
    if exit <= 0.0 {
        return 0.0;
    }
    return exit + 0.05;
}

// The bound of the density delta and ratio tracking rely on.
fn density_max() -> f32 {
    var m = 0.0;
    for (var i = 0u; i < layer_count(); i++) {
        let l = cloud_layer(i);
        m = max(m, l.density * (1.0 + l.precipitation));
    }
    return clamp(m, 0.0, 1.0);
}

// Delta tracking: the distance of the first real collision along the ray, or -1.
fn free_flight(origin: vec3<f32>, dir: vec3<f32>, segs: Segments, rng: ptr<function, u32>,
               counters: ptr<function, Counters>) -> f32 {
    let d_max = density_max();
    let majorant = (frame.scattering + frame.absorption) * d_max;
    if majorant <= 0.0 {
        return -1.0;
    }
    for (var k = 0u; k < segs.count; k++) {
        var t = segs.a[k];
        loop {
            let skip = empty_cell_skip(origin, dir, t);
            if skip > 0.0 {
                t += skip;
                if t >= segs.b[k] {
                    break;
                }
                continue;
            }
            t += rng_exponential(rng, majorant);
            if t >= segs.b[k] {
                break;
            }
            (*counters).view_steps += 1u;
            let d = density_at(origin + dir * t, counters);
            if rng_next(rng) * d_max < d {
                return t;
            }
        }
    }
    return -1.0;
}

// Ratio tracking: an unbiased estimate of the transmittance along the ray.
fn transmittance_along(origin: vec3<f32>, dir: vec3<f32>, segs: Segments,
                       rng: ptr<function, u32>, counters: ptr<function, Counters>) -> f32 {
    let sigma_t = frame.scattering + frame.absorption;
    let majorant = sigma_t * density_max();
    if majorant <= 0.0 {
        return 1.0;
    }
    var tr = 1.0;
    for (var k = 0u; k < segs.count; k++) {
        var t = segs.a[k];
        loop {
            let skip = empty_cell_skip(origin, dir, t);
            if skip > 0.0 {
                t += skip;
                if t >= segs.b[k] {
                    break;
                }
                continue;
            }
            t += rng_exponential(rng, majorant);
            if t >= segs.b[k] {
                break;
            }
            (*counters).light += 1u;
            let d = density_at(origin + dir * t, counters);
            tr *= 1.0 - sigma_t * d / majorant;
            if tr <= 0.0 {
                return 0.0;
            }
            if tr < 0.01 {
                // Russian roulette on nearly opaque rays (unbiased).
                if rng_next(rng) < 0.75 {
                    return 0.0;
                }
                tr *= 4.0;
            }
        }
    }
    return tr;
}

// Henyey-Greenstein's cosine for eccentricity `g` from a uniform `u`.
fn sample_hg_cos(g: f32, u: f32) -> f32 {
    if abs(g) < 1e-4 {
        return 1.0 - 2.0 * u;
    }
    let s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
    return clamp((1.0 + g * g - s * s) / (2.0 * g), -1.0, 1.0);
}

// A direction drawn from the scene's phase function around `dir` (the direction the path
// travels) and its weight phase / pdf.
struct PhaseSample {
    dir: vec3<f32>,
    weight: f32,
}

fn sample_phase(dir: vec3<f32>, rng: ptr<function, u32>) -> PhaseSample {
    let u_lobe = rng_next(rng);
    let u = rng_next(rng);
    let phi = 2.0 * PI * rng_next(rng);
    var cos_theta = 0.0;
    var pdf = 0.0;
    if frame.phase_model == PHASE_TWO_LOBE_HG {
        let g = select(frame.phase_g, frame.phase_g2, u_lobe < frame.phase_blend);
        cos_theta = sample_hg_cos(g, u);
        pdf = mix(phase_hg(cos_theta, frame.phase_g), phase_hg(cos_theta, frame.phase_g2),
                  frame.phase_blend);
    } else {
        cos_theta = sample_hg_cos(frame.phase_g, u);
        pdf = phase_hg(cos_theta, frame.phase_g);
    }
    let sin_theta = sqrt(max(1.0 - cos_theta * cos_theta, 0.0));
    // An orthonormal basis around `dir` (Duff et al. 2017).
    let sign = select(-1.0, 1.0, dir.z >= 0.0);
    let a = -1.0 / (sign + dir.z);
    let bb = dir.x * dir.y * a;
    let t = vec3<f32>(1.0 + sign * dir.x * dir.x * a, sign * bb, -sign * dir.x);
    let b = vec3<f32>(bb, sign + dir.y * dir.y * a, -dir.y);
    let w = normalize(t * (sin_theta * cos(phi)) + b * (sin_theta * sin(phi)) + dir * cos_theta);
    return PhaseSample(w, select(0.0, phase(cos_theta, 1.0) / pdf, pdf > 0.0));
}

// The light a path that leaves the clouds from `pos` (camera-relative, m; its last
// collision) along unit `d` sees: under the physical sky the sky and the lit ground in that
// direction seen from there (`sky_from`: the air between the clouds and the ground, or above
// the clouds, lit by the sun), else the ambient's uniform environment ambient(h). Seen from
// the camera instead (the sky-view table, as before), a path leaving a layer's base downward
// saw the ground at once, without the kilometre or two of air below the layer, which a low
// sun lights brightly. The march takes the cosine-weighted hemispheres facing the layer (the
// sky-ambient table). Neither knows the clouds' shadow on that air and ground.
fn environment(pos: vec3<f32>, d: vec3<f32>, h: f32) -> vec3<f32> {
    if physical_sky() {
        return sky_from(pos, d) * frame.sun_illuminance * frame.ambient_strength;
    }
    return ambient(h, pos);
}

// One path through `pixel`'s ray over the march's interval.
struct PathResult {
    radiance: vec3<f32>,
    transmittance: f32,
    depth: f32,          // distance of the first collision, -1 if none
}

fn trace_path(view: vec3<f32>, span: Interval, rng: ptr<function, u32>,
              counters: ptr<function, Counters>) -> PathResult {
    var out = PathResult(vec3<f32>(0.0), 1.0, -1.0);
    if span.kind != RAY_MARCH {
        return out;
    }
    let cam = vec3<f32>(0.0, frame.camera_position.y, 0.0);
    let primary = Segments(vec2<f32>(span.start, 0.0), vec2<f32>(span.start + span.length, 0.0), 1u);
    out.transmittance = transmittance_along(cam, view, primary, rng, counters);
    let first = free_flight(cam, view, primary, rng, counters);
    if first < 0.0 {
        return out;
    }
    out.depth = first;

    let sun = frame.sun_direction;
    let sigma_t = frame.scattering + frame.absorption;
    let albedo = select(0.0, frame.scattering / sigma_t, sigma_t > 0.0);
    let ambient_on = frame.ambient_strength > 0.0
        && (physical_sky() || any(frame.ambient_bottom > vec3<f32>(0.0))
            || any(frame.ambient_top > vec3<f32>(0.0)));
    var max_orders = MAX_PATH_ORDERS;
    if frame.path_orders > 0u {
        max_orders = min(frame.path_orders, MAX_PATH_ORDERS);
    }

    var pos = cam + view * first;
    var dir = view;
    var throughput = 1.0;
    var order = 0u;
    loop {
        throughput *= albedo;
        order += 1u;
        let alt = altitude_of(pos);
        let h = height_fraction(alt);
        // Next event toward the sun (a directional light).
        if !hits_ground(pos, alt, sun) {
            let tr = transmittance_along(pos, sun, layer_segments(pos, alt, sun), rng, counters);
            out.radiance += frame.sun_illuminance * sun_through_air(pos)
                * (throughput * phase(dot(dir, sun), 1.0) * tr);
        }
        // The next direction, from the phase function. Its free flight also estimates the
        // ambient (an environment seen through the medium): a path that leaves the layer along
        // it sees `environment` (ambient(h), or the sky from there). That is the expectation of the CPU path tracer's
        // separate ratio-tracked ray toward the environment, for one tracked ray instead of
        // two per collision.
        let next = sample_phase(dir, rng);
        let t = free_flight(pos, next.dir, layer_segments(pos, alt, next.dir), rng, counters);
        if t < 0.0 {
            if ambient_on {
                out.radiance += environment(pos, next.dir, h) * (throughput * next.weight);
            }
            break;
        }
        if order >= max_orders {
            break;
        }
        throughput *= next.weight;
        dir = next.dir;
        if order >= 3u && throughput < 0.1 {
            if rng_next(rng) >= throughput / 0.1 {
                break;
            }
            throughput = 0.1;
        }
        if throughput <= 0.0 {
            break;
        }
        pos += dir * t;
    }
    return out;
}

fn luminance(c: vec3<f32>) -> f32 {
    return dot(c, vec3<f32>(0.2126, 0.7152, 0.0722));
}

// Paths per pixel per frame: a pixel is one workgroup of this many invocations, one path each,
// summed in workgroup memory. One path per pixel a frame left a GPU nearly idle at the small
// sizes the fit and the bench use (64x36 on an H100: 20 ms a frame for 2304 paths, each frame
// as long as its longest path); the host reads this from the entry point's workgroup size. The
// lanes run along x: llvmpipe vectorises a workgroup along x only (along z this ran 6x slower).
const PATHS_PER_FRAME: u32 = 32u;

// Each lane's path: radiance and transmittance, and (luminance squared, depth, hit, 0). Every
// lane writes its element before the barrier and lane 0 reads them after: nothing reads the
// initial value (the HLSL leaves workgroup memory uninitialised, crates/shaders).
var<workgroup> lane_sums: array<vec4<f32>, PATHS_PER_FRAME>;
var<workgroup> lane_moments: array<vec4<f32>, PATHS_PER_FRAME>;

// PATHS_PER_FRAME more paths for every pixel, joined to the running means.
@compute @workgroup_size(PATHS_PER_FRAME, 1, 1)
fn pathtrace(@builtin(workgroup_id) group: vec3<u32>,
             @builtin(local_invocation_index) lane: u32) {
    // The workgroup is the pixel, so this test is uniform across it (the barriers below).
    if any(group.xy >= frame.size) {
        return;
    }
    let pixel = group.xy;
    let view = view_ray(pixel);
    let span = cloud_interval(frame.camera_position.y, view);
    var counters = Counters(0u, 0u, 0u, 0u);
    if lane == 0u {
        count(STAT_PIXELS, 1u);
        count(STAT_MARCHED, u32(span.kind == RAY_MARCH));
        count(STAT_EXIT_MISSED, u32(span.kind == RAY_MISSES_LAYER));
        count(STAT_EXIT_GROUND, u32(span.kind == RAY_HITS_GROUND));
    }

    // One path per invocation. Tracing several in a loop of one invocation gave wrong images
    // on lavapipe from about 10 paths an invocation on (8x8 blocks too dark, the same bits
    // whichever single path was kept), so a frame's paths are the workgroup's lanes.
    var rng = rng_seed(pixel, frame.frame_index * PATHS_PER_FRAME + lane);
    let r = trace_path(view, span, &rng, &counters);
    let l = luminance(r.radiance);
    let hit = r.depth >= 0.0;
    lane_sums[lane] = vec4<f32>(r.radiance, r.transmittance);
    lane_moments[lane] = vec4<f32>(l * l, select(0.0, r.depth, hit), select(0.0, 1.0, hit), 0.0);
    workgroupBarrier();

    if lane == 0u {
        // Lane 0 sums the lanes' paths. (A tree sum, a barrier in each round of a loop, lost
        // whole frames of some pixels on lavapipe: their history was not written.)
        var sum = vec4<f32>(0.0);
        var sum_moments = vec4<f32>(0.0);
        for (var i = 0u; i < PATHS_PER_FRAME; i++) {
            sum += lane_sums[i];
            sum_moments += lane_moments[i];
        }
        var mean = vec4<f32>(0.0);
        var moments = vec4<f32>(0.0);
        if frame.history_valid == 1u && camera_still() {
            mean = textureLoad(history_in, pixel, 0);
            moments = textureLoad(meta_in, pixel, 0);
        }
        let k = f32(PATHS_PER_FRAME);
        let n = moments.y + k;
        // Running means over every path so far: this frame's k paths weigh k / n.
        mean += (sum - k * mean) / n;
        moments.z += (sum_moments.x - k * moments.z) / n;
        let hits = sum_moments.z;
        if hits > 0.0 {
            moments.w += hits;
            moments.x += (sum_moments.y - hits * moments.x) / moments.w;
        }
        moments.y = n;
        textureStore(history_out, pixel, mean);
        textureStore(meta_out, pixel, moments);
        textureStore(cloud_out, pixel, mean);
        textureStore(depth_out, pixel, vec4<f32>(moments.x, 0.0, 0.0, 0.0));
    }

    count(STAT_VIEW_STEPS, counters.view_steps);
    count(STAT_DENSITY, counters.density);
    count(STAT_DETAIL, counters.detail);
    count(STAT_LIGHT, counters.light);
}
// The basic ray marcher of the volumetric-cloud tutorials (GPU Pro 7's "Real-Time Volumetric
// Cloudscapes" as popularised in Real-Time Rendering, 4th ed., ch. 14): a measured baseline for
// the model in march.wgsl, drawing the same density field (`cloud_density`, whose base shape
// is the Worley FBM with weights 0.625 / 0.25 / 0.125).
//
// Per view sample at the start of each of `view_steps` equal steps (no jitter), a Riemann sum
//   L += E_sun * BeerPowder(tau_sun) * HG(cos theta, g) * Beer(tau_view) * sigma_s * rho * dt
// where tau_sun is a Riemann sum of the density along the sun ray through the layer
// (`light_steps` equal steps) and Beer-Powder is Schneider's 2 e^-tau (1 - e^-2 tau). What it
// leaves out, the chart measures: no ambient, no multiple scattering, no energy-conserving step
// integral, no early exit.

// The optical depth toward the sun from `rel` (camera-relative, altitude `alt`) to the top of
// the layer, at most three layer thicknesses, in `frame.light_steps` equal Riemann steps.
fn basic_sun_depth(rel: vec3<f32>, alt: f32, counters: ptr<function, Counters>) -> f32 {
    let steps = frame.light_steps;
    if steps == 0u {
        return 0.0;
    }
    let sun = frame.sun_direction;
    let rp = frame.planet_radius;
    let top = frame.cloud_top;
    let thickness = top - frame.cloud_bottom;
    // The sun ray's exit through the top shell, from a point at altitude `alt` (c < 0 inside).
    let exit = solve_sphere(dot(sun, vec3<f32>(rel.x, rel.y + rp, rel.z)), (alt - top) * (alt + top + 2.0 * rp));
    let length = min(max(exit.t1, 0.0), 3.0 * thickness);
    let dt = length / f32(steps);
    let sigma_t = frame.scattering + frame.absorption;
    let cam_xz = frame.camera_position.xz;
    var tau = 0.0;
    for (var i = 1u; i <= steps; i += 1u) {
        (*counters).light += 1u;
        let q = rel + sun * (f32(i) * dt);
        let p = vec3<f32>(q.x + cam_xz.x, q.y, q.z + cam_xz.y);
        tau += sigma_t * cloud_density(p, altitude_of(q), counters) * dt;
    }
    return tau;
}

fn basic_pixel(pixel: vec2<u32>) -> MarchResult {
    let view = view_ray(pixel);
    let cam_alt = frame.camera_position.y;
    let cam_xz = frame.camera_position.xz;
    var counters = Counters(0u, 0u, 0u, 0u);
    count(STAT_PIXELS, 1u);

    var radiance = vec3<f32>(0.0);
    var transmittance = 1.0;
    var depth_sum = 0.0;
    let span = cloud_interval(cam_alt, view);
    if span.kind == RAY_MISSES_LAYER {
        count(STAT_EXIT_MISSED, 1u);
    } else if span.kind == RAY_HITS_GROUND {
        count(STAT_EXIT_GROUND, 1u);
    } else {
        count(STAT_MARCHED, 1u);
        let steps = frame.view_steps;
        let dt = span.length / f32(steps);
        let sigma_s = frame.scattering;
        let sigma_t = sigma_s + frame.absorption;
        let sun_phase = frame.sun_illuminance * phase_hg(dot(view, frame.sun_direction), frame.phase_g);
        for (var i = 0u; i < steps; i += 1u) {
            counters.view_steps += 1u;
            let t = span.start + f32(i) * dt;
            let rel = view * t + vec3<f32>(0.0, cam_alt, 0.0);
            let p = vec3<f32>(rel.x + cam_xz.x, rel.y, rel.z + cam_xz.y);
            let alt = altitude_of(rel);
            let density = cloud_density(p, alt, &counters);
            if density <= 0.0 {
                continue;
            }
            let tau = basic_sun_depth(rel, alt, &counters);
            let beer_powder = 2.0 * exp(-tau) * (1.0 - exp(-2.0 * tau));
            radiance += sun_phase * (beer_powder * transmittance * sigma_s * density * dt);
            let step_t = exp(-sigma_t * density * dt);
            depth_sum += t * transmittance * (1.0 - step_t);
            transmittance *= step_t;
        }
    }

    count(STAT_VIEW_STEPS, counters.view_steps);
    count(STAT_DENSITY, counters.density);
    count(STAT_DETAIL, counters.detail);
    count(STAT_LIGHT, counters.light);
    var depth = 0.0;
    if transmittance < 1.0 {
        depth = depth_sum / (1.0 - transmittance);
    }
    return MarchResult(radiance, transmittance, depth);
}

// Every pixel, every frame (quality.method = "basic").
@compute @workgroup_size(8, 8, 1)
fn march_basic(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.size) {
        return;
    }
    let r = basic_pixel(id.xy);
    textureStore(cloud_out, id.xy, vec4<f32>(r.radiance, r.transmittance));
    textureStore(depth_out, id.xy, vec4<f32>(r.depth, 0.0, 0.0, 0.0));
}
// Sprite clouds (Wang 2003, "Realistic and Fast Cloud Rendering", Microsoft Flight Simulator
// 2004): alpha-blended camera-facing sprites in boxes, sorted back to front, shaded by artist
// colour levels rather than light transport. A measured baseline for the volumetric model.
//
// The paper's artists place boxes in a modelling tool; here the boxes are the cells of a
// world-anchored grid around the camera (4 rings of 8x8 cells, each ring's cells twice the
// size of the ring inside it, so sprites keep about the same size on screen), and the clouds
// come from the same weather map and density field the march draws (`cloud_density`): every
// cell holds 16 sprites at fixed (hashed) places, and each sprite's alpha follows the density
// at its centre, so clouds form and dissipate through alpha as the weather moves (the paper's
// inner sprites first, outer ones with wider transitions). A cell is one shading group.
//
// Passes (wgsl/graph.toml): `sprite_atlas` draws the 16 sprite textures once; `sprite_build`
// places the sprites; `sprite_sort` orders them back to front (a rank sort); `sprite_draw` rasterises them (premultiplied "over" blending); and
// `sprite_resolve` turns the blended opacity into the transmittance the composite expects.

@group(0) @binding(19) var sprites_out: texture_storage_2d<rgba32float, write>;
@group(0) @binding(20) var sprites_in: texture_2d<f32>;
@group(0) @binding(21) var sprite_order_out: texture_storage_2d<r32float, write>;
@group(0) @binding(22) var sprite_order_in: texture_2d<f32>;
@group(0) @binding(23) var sprite_atlas_out: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(24) var sprite_atlas_in: texture_2d<f32>;
@group(0) @binding(25) var sprite_radiance_in: texture_2d<f32>;
@group(0) @binding(26) var sprite_depth_in: texture_2d<f32>;

const SPRITE_LEVELS: u32 = 4u;          // rings of cells
const SPRITE_CELLS_PER_SIDE: i32 = 8;   // cells per ring side
const SPRITES_PER_CELL: u32 = 16u;      // sprites per cell (box)
const SPRITE_COUNT: u32 = 4096u;        // 4 x 64 cells x 16; the sort holds them all
const SPRITE_CELL0: f32 = 1500.0;       // innermost cell side (m); ring k: 1500 * 2^k
const SPRITE_ALPHA: f32 = 0.7;          // a fully formed sprite's alpha
const SPRITE_MAX_DISTANCE: f32 = 131072.0; // sort keys quantise distances up to this (m)
const ATLAS_TILE: u32 = 64u;            // texels per sprite texture side; 4x4 tiles
// Sun shading levels (the paper's Cmin, Cmed, Cmax, fractions of the sun's light) for the
// far side, the rim and the near side of a shading group.
const SPRITE_C_MIN: f32 = 0.22;
const SPRITE_C_MED: f32 = 0.55;
const SPRITE_C_MAX: f32 = 1.0;
const SPRITE_SKY: f32 = 0.35;           // skylight at noon, as a fraction of the sun's light

// ---------------------------------------------------------------------------------------
// Sprite textures: 16 procedural alpha masks in a 4x4 atlas (0-3 wispy streaks, 4 flat-
// bottomed, 5-15 puffy billows), deterministic from the tile index.

fn atlas_hash(a: u32, b: u32) -> f32 {
    return f32(pcg(a ^ pcg(b)) >> 8u) * (1.0 / 16777216.0);
}

// Value noise on the integer lattice, smoothly interpolated.
fn value_noise(p: vec2<f32>, seed: u32) -> f32 {
    let i = vec2<u32>(floor(p));
    let f = fract(p);
    let s = f * f * (3.0 - 2.0 * f);
    let h = seed * 7919u;
    let a = atlas_hash(i.x + h, i.y);
    let b = atlas_hash(i.x + 1u + h, i.y);
    let c = atlas_hash(i.x + h, i.y + 1u);
    let d = atlas_hash(i.x + 1u + h, i.y + 1u);
    return mix(mix(a, b, s.x), mix(c, d, s.x), s.y);
}

fn value_fbm(p: vec2<f32>, seed: u32) -> f32 {
    var sum = 0.0;
    var weight = 0.5;
    var q = p;
    for (var o = 0u; o < 4u; o += 1u) {
        sum += weight * value_noise(q, seed + o);
        q = q * 2.0;
        weight *= 0.5;
    }
    return sum / 0.9375;
}

// Alpha of sprite texture `tile` at `uv` in [0, 1]^2 (v down). Zero beyond radius 0.48, so
// bilinear filtering never bleeds between tiles.
fn sprite_texture(tile: u32, uv: vec2<f32>) -> f32 {
    let c = uv - 0.5;
    let mask = smoothstep(0.48, 0.36, length(c));
    let noise = value_fbm(uv * 6.0 + vec2<f32>(f32(tile) * 13.0), tile);
    if tile < 4u {
        // Wispy: a stretched streak, broken up by noise stretched the same way.
        let q = c * vec2<f32>(1.0, 3.2);
        let streak = 1.0 - smoothstep(0.05, 0.45, length(q));
        let n = value_fbm(uv * vec2<f32>(3.0, 12.0) + vec2<f32>(f32(tile) * 5.0), tile + 16u);
        return mask * streak * saturate(n * 1.6 - 0.3) * 0.8;
    }
    var billow = 0.0;
    let blobs = 5u + (tile % 4u);
    for (var i = 0u; i < blobs; i += 1u) {
        let centre = vec2<f32>(atlas_hash(tile, 2u * i), atlas_hash(tile, 2u * i + 1u)) - 0.5;
        var at = 0.5 + centre * 0.34;
        if tile == 4u {
            at.y = 0.5 + (centre.y - 0.5) * 0.24; // flat-bottomed: the blobs sit above the base
        }
        let r = 0.14 + 0.1 * atlas_hash(tile, 100u + i);
        let d = length(uv - at) / r;
        billow = max(billow, saturate(1.0 - d * d));
    }
    var a = mask * saturate(billow * 1.5) * (0.55 + 0.45 * noise);
    if tile == 4u {
        a *= smoothstep(0.62, 0.54, uv.y); // a flat base
    }
    return a;
}

@compute @workgroup_size(8, 8, 1)
fn sprite_atlas(@builtin(global_invocation_id) id: vec3<u32>) {
    let tile = (id.y / ATLAS_TILE) * 4u + id.x / ATLAS_TILE;
    let uv = (vec2<f32>(id.xy % ATLAS_TILE) + 0.5) / f32(ATLAS_TILE);
    let a = sprite_texture(tile, uv);
    textureStore(sprite_atlas_out, id.xy, vec4<f32>(a, a, a, a));
}

// ---------------------------------------------------------------------------------------
// Placement.

// The camera-relative position (relative to the ground point below the camera, as the march's
// `rel`) of the point at world `xz` and altitude `alt` on the curved planet: y solves
// x^2 + z^2 + y (y + 2 Rp) = alt (alt + 2 Rp), in the form without cancellation.
fn sprite_rel(xz: vec2<f32>, alt: f32) -> vec3<f32> {
    let rp = frame.planet_radius;
    let d = xz - frame.camera_position.xz;
    let k = alt * (alt + 2.0 * rp) - dot(d, d);
    let y = k / (rp + sqrt(max(rp * rp + k, 0.0)));
    return vec3<f32>(d.x, y, d.y);
}

// A cell of the grid: its world index, side (m) and whether the ring inside covers it.
struct SpriteCell {
    index: vec2<i32>,
    size: f32,
    covered: bool,
}

// Cell `cell` (0..255: ring = cell / 64, then 8x8 in the ring) around the camera. Ring k
// starts at `start`; the ring inside it covers its cells [2, 6)^2 exactly.
fn sprite_cell(cell: u32) -> SpriteCell {
    let level = cell / 64u;
    let local = vec2<i32>(i32(cell % 8u), i32((cell / 8u) % 8u));
    let coarsest = SPRITE_CELL0 * f32(1u << (SPRITE_LEVELS - 1u));
    var start = vec2<i32>(floor(frame.camera_position.xz / coarsest)) - SPRITE_CELLS_PER_SIDE / 2;
    for (var k = SPRITE_LEVELS - 1u; k > level; k -= 1u) {
        start = 2 * (start + 2);
    }
    let covered = level > 0u && all(local >= vec2<i32>(2)) && all(local < vec2<i32>(6));
    return SpriteCell(start + local, SPRITE_CELL0 * f32(1u << level), covered);
}

// One sprite's place and hashed choices, and the density there.
struct SpriteCandidate {
    xz: vec2<f32>,
    alt: f32,
    h: f32,         // height fraction in the layer
    size_hash: f32,
    texture_hash: f32,
    rotation_hash: f32,
    density: f32,
    precipitation: f32,
}

// Sprite `s` of cell `c`: a fixed (hashed) place in the cell, the same every frame, at a
// height where the cell's cloud type puts cloud (stratus low, cumulus through the layer).
fn sprite_candidate(c: SpriteCell, level: u32, s: u32, counters: ptr<function, Counters>) -> SpriteCandidate {
    let seed = pcg(bitcast<u32>(c.index.x) ^ pcg(bitcast<u32>(c.index.y) ^ pcg(level)));
    let u = vec4<f32>(atlas_hash(seed, 8u * s), atlas_hash(seed, 8u * s + 1u), atlas_hash(seed, 8u * s + 2u), atlas_hash(seed, 8u * s + 3u));
    let v = vec2<f32>(atlas_hash(seed, 8u * s + 4u), atlas_hash(seed, 8u * s + 5u));
    let xz = (vec2<f32>(c.index) + u.xy) * c.size;
    let w = sample_weather(vec3<f32>(xz.x, 0.0, xz.y), cloud_layer(0u));
    let h = 0.04 + u.z * (mix(0.3, 0.95, w.cloud_type) - 0.04);
    let alt = frame.cloud_bottom + h * (frame.cloud_top - frame.cloud_bottom);
    var density = 0.0;
    if !c.covered {
        let rel = sprite_rel(xz, alt);
        density = cloud_density(vec3<f32>(xz.x, rel.y, xz.y), alt, counters);
    }
    return SpriteCandidate(xz, alt, h, u.w, v.x, v.y, density, w.precipitation);
}

// One invocation per sprite; each evaluates its whole cell (16 density samples) for the
// shading group's centre rather than share them through workgroup memory, whose WGSL zero
// initialisation naga writes in HLSL as `(float4[16])0`, which glslang's HLSL front end
// rejects. Writes four texels per sprite: row 0 (x, altitude, z, half width), row 1 (group
// centre x, altitude, z; alpha, 0 = not drawn), row 2 (texture, rotation, half height, colour
// level), row 3 (sort key: 0 when not drawn, else 2^20 - quantised distance; far first).
@compute @workgroup_size(64, 1, 1)
fn sprite_build(@builtin(global_invocation_id) id: vec3<u32>) {
    let slot = id.x;
    let cell_index = slot / SPRITES_PER_CELL;
    let level = cell_index / 64u;
    let cell = sprite_cell(cell_index);
    let own = slot % SPRITES_PER_CELL;
    var counters = Counters(0u, 0u, 0u, 0u);

    // The shading group's centre: the density-weighted mean of its sprites.
    var sum = vec4<f32>(0.0);
    var me = sprite_candidate(cell, level, own, &counters);
    for (var i = 0u; i < SPRITES_PER_CELL; i += 1u) {
        let c = sprite_candidate(cell, level, i, &counters);
        sum += vec4<f32>(c.xz.x, c.alt, c.xz.y, 1.0) * c.density;
    }
    count(STAT_DENSITY, counters.density);
    count(STAT_DETAIL, counters.detail);
    let bottom = frame.cloud_bottom;
    let thickness = frame.cloud_top - bottom;
    let middle = (vec2<f32>(cell.index) + 0.5) * cell.size;
    var centre = vec3<f32>(middle.x, bottom + 0.4 * thickness, middle.y);
    if sum.w > 0.0 {
        centre = sum.xyz / sum.w;
    }

    // Forming and dissipating through alpha: inner sprites appear at lower density than outer
    // ones, whose transition is also wider.
    let inner = length(me.xz - centre.xz) < 0.25 * cell.size;
    let morph = select(smoothstep(0.03, 0.15, me.density), smoothstep(0.0, 0.06, me.density), inner);
    let alpha = SPRITE_ALPHA * morph;
    let half_width = 0.5 * cell.size * (0.7 + 0.6 * me.size_hash);
    let half_height = min(half_width, 0.35 * thickness);
    var tile = 5u + min(u32(me.texture_hash * 11.0), 10u);
    var rotation = me.rotation_hash * 2.0 * PI;
    if me.h < 0.12 {
        tile = 4u; // flat bottoms, rotated by at most 5 degrees
        rotation = (me.rotation_hash - 0.5) * (10.0 * PI / 180.0);
    } else if !inner && me.density < 0.1 {
        tile = min(u32(me.texture_hash * 4.0), 3u);
    }
    var key = 0.0;
    if alpha > 0.0 {
        let rel = sprite_rel(me.xz, me.alt) - vec3<f32>(0.0, frame.camera_position.y, 0.0);
        key = 1048576.0 - floor(saturate(length(rel) / SPRITE_MAX_DISTANCE) * 1048575.0);
    }
    textureStore(sprites_out, vec2<u32>(slot, 0u), vec4<f32>(me.xz.x, me.alt, me.xz.y, half_width));
    textureStore(sprites_out, vec2<u32>(slot, 1u), vec4<f32>(centre, alpha));
    // Wang's artists pick darker colour levels for rain clouds; here the weather's
    // precipitation picks them: a fifth of the brightness at precipitation 0.7 (storm).
    let colour_level = 1.0 / (1.0 + 6.0 * max(me.precipitation, 0.0));
    textureStore(sprites_out, vec2<u32>(slot, 2u), vec4<f32>(f32(tile), rotation, half_height, colour_level));
    textureStore(sprites_out, vec2<u32>(slot, 3u), vec4<f32>(key, 0.0, 0.0, 0.0));
}

// ---------------------------------------------------------------------------------------
// Back-to-front order.

// A rank sort: each sprite counts the sprites that come before it (a lower key, or the same
// key and a lower slot, so the ranks are a permutation and ties order the same way every
// time) and writes its slot at its rank. O(n^2) independent comparisons and no sort network,
// which in one workgroup would need 16 KiB of workgroup memory (see sprite_build on why
// there is none). Keys are whole numbers below 2^21: exact in f32.
@compute @workgroup_size(64, 1, 1)
fn sprite_sort(@builtin(global_invocation_id) id: vec3<u32>) {
    let slot = id.x;
    let key = textureLoad(sprites_in, vec2<u32>(slot, 3u), 0).x;
    var rank = 0u;
    for (var j = 0u; j < SPRITE_COUNT; j += 1u) {
        let other = textureLoad(sprites_in, vec2<u32>(j, 3u), 0).x;
        rank += select(0u, 1u, other < key || (other == key && j < slot));
    }
    textureStore(sprite_order_out, vec2<u32>(rank, 0u), vec4<f32>(f32(slot), 0.0, 0.0, 0.0));
}

// ---------------------------------------------------------------------------------------
// Drawing.

struct SpriteVertex {
    @builtin(position) position: vec4<f32>,
    @location(0) uv: vec2<f32>,                    // [-1, 1]^2 in the (rotated) texture
    @location(1) @interpolate(flat) tile: u32,
    @location(2) colour: vec4<f32>,                // radiance; alpha
    @location(3) distance: f32,                    // from the camera (m)
}

struct SpriteTargets {
    @location(0) radiance: vec4<f32>,              // premultiplied radiance; opacity
    @location(1) depth: vec4<f32>,                 // premultiplied distance; opacity
}

// Sky colour by height in the layer, the paper's five artist levels (bases grey-blue, tops
// white), before the time-of-day factor. (Levels as separate constants and a chain of
// branches rather than a constant array: naga writes a module-scope array constant in HLSL as
// a call that glslang's HLSL front end mistakes for recursion.)
const SKY_LEVEL0: vec3<f32> = vec3<f32>(0.42, 0.46, 0.55);
const SKY_LEVEL1: vec3<f32> = vec3<f32>(0.55, 0.59, 0.67);
const SKY_LEVEL2: vec3<f32> = vec3<f32>(0.70, 0.73, 0.80);
const SKY_LEVEL3: vec3<f32> = vec3<f32>(0.84, 0.86, 0.90);
const SKY_LEVEL4: vec3<f32> = vec3<f32>(0.95, 0.96, 0.98);

fn sprite_sky_level(h: f32) -> vec3<f32> {
    let x = saturate(h) * 4.0;
    if x < 1.0 {
        return mix(SKY_LEVEL0, SKY_LEVEL1, x);
    }
    if x < 2.0 {
        return mix(SKY_LEVEL1, SKY_LEVEL2, x - 1.0);
    }
    if x < 3.0 {
        return mix(SKY_LEVEL2, SKY_LEVEL3, x - 2.0);
    }
    return mix(SKY_LEVEL3, SKY_LEVEL4, x - 3.0);
}

// Wang's sun shading: the cosine between (group centre -> vertex) and (group centre -> sun)
// mapped [-1, 0] to [Cmin, Cmed] and [0, 1] to [Cmed, Cmax].
fn sprite_sun_level(cos_angle: f32) -> f32 {
    if cos_angle < 0.0 {
        return mix(SPRITE_C_MIN, SPRITE_C_MED, cos_angle + 1.0);
    }
    return mix(SPRITE_C_MED, SPRITE_C_MAX, cos_angle);
}

// Corner `k` (0..5) of a sprite's two triangles: (-1, -1), (1, -1), (1, 1), (-1, -1), (1, 1),
// (-1, 1), through quad vertices 0, 1, 2, 0, 2, 3.
fn sprite_corner(k: u32) -> vec2<f32> {
    let q = select(k, select(k - 2u, 0u, k == 3u), k >= 3u);
    return vec2<f32>(select(-1.0, 1.0, q == 1u || q == 2u), select(-1.0, 1.0, q >= 2u));
}

@vertex
fn sprite_vertex(@builtin(vertex_index) index: u32) -> SpriteVertex {
    var out: SpriteVertex;
    let slot = u32(textureLoad(sprite_order_in, vec2<u32>(index / 6u, 0u), 0).x);
    let a = textureLoad(sprites_in, vec2<u32>(slot, 0u), 0);
    let b = textureLoad(sprites_in, vec2<u32>(slot, 1u), 0);
    let c = textureLoad(sprites_in, vec2<u32>(slot, 2u), 0);
    if b.w <= 0.0 {
        // Not drawn: a degenerate triangle behind the camera (clipped).
        out.position = vec4<f32>(0.0, 0.0, -1.0, 1.0);
        return out;
    }
    let cam = vec3<f32>(0.0, frame.camera_position.y, 0.0);
    let rel = sprite_rel(a.xz, a.y);
    let to_sprite = rel - cam;
    let distance = length(to_sprite);
    // Facing the camera; within half its width the sprite stops turning toward the camera
    // (Wang: its rotation is obvious up close) and faces the view plane instead, which does
    // not turn as the camera moves through it.
    let half_width = a.w;
    let facing = smoothstep(0.5 * half_width, half_width, distance);
    let to_camera = -to_sprite / max(distance, 1e-3);
    let n = normalize(mix(-frame.camera_forward, to_camera, facing));
    let radial = normalize(rel + vec3<f32>(0.0, frame.planet_radius, 0.0));
    var right = cross(radial, n);
    if length(right) < 1e-3 {
        right = frame.camera_right; // looking straight up or down at it
    }
    right = normalize(right);
    let up = cross(n, right);
    let corner = sprite_corner(index % 6u);
    let offset = right * (corner.x * half_width) + up * (corner.y * c.z);
    let vertex = to_sprite + offset;

    // Camera space to clip space: x right, y up, w = depth along the view (z in [0, w]).
    let x = dot(vertex, frame.camera_right);
    let y = dot(vertex, frame.camera_up);
    let z = dot(vertex, frame.camera_forward);
    let tan_half = frame.tan_half_fov;
    out.position = vec4<f32>(x / (tan_half * frame.aspect), y / tan_half, 0.5 * z, z);

    // Texture coordinates: v down, turned by the sprite's rotation.
    let cs = vec2<f32>(cos(c.y), sin(c.y));
    let t = vec2<f32>(corner.x, -corner.y);
    out.uv = vec2<f32>(t.x * cs.x - t.y * cs.y, t.x * cs.y + t.y * cs.x);
    out.tile = u32(c.x);

    // Shading per vertex: C = (C_sky + C_sun) * alpha_morph.
    let sun = frame.sun_direction;
    let centre = sprite_rel(b.xz, b.y) - cam;
    let from_centre = vertex - centre;
    let cos_angle = dot(from_centre, sun) / max(length(from_centre), 1e-3);
    let day = saturate(sun.y * 4.0 + 0.3);
    let h = saturate((altitude_of(vertex + cam) - frame.cloud_bottom) / (frame.cloud_top - frame.cloud_bottom));
    let e = frame.sun_illuminance;
    let light = e * (sprite_sky_level(h) * (SPRITE_SKY * day) + sprite_sun_level(cos_angle)) * (c.w / PI);
    out.colour = vec4<f32>(light, b.w);
    out.distance = length(vertex);
    return out;
}

@fragment
fn sprite_fragment(in: SpriteVertex) -> SpriteTargets {
    var out: SpriteTargets;
    var a = 0.0;
    if all(abs(in.uv) <= vec2<f32>(1.0)) {
        let tile = vec2<f32>(f32(in.tile % 4u), f32(in.tile / 4u));
        let uv = (tile + 0.5 + 0.5 * in.uv) * 0.25;
        a = textureSampleLevel(sprite_atlas_in, noise_sampler, uv, 0.0).r * in.colour.a;
    }
    out.radiance = vec4<f32>(in.colour.rgb * a, a);
    out.depth = vec4<f32>(in.distance * a, 0.0, 0.0, a);
    return out;
}

// The blended sprites as the march's output: radiance, transmittance = 1 - opacity, and the
// opacity-weighted distance.
@compute @workgroup_size(8, 8, 1)
fn sprite_resolve(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.size) {
        return;
    }
    count(STAT_PIXELS, 1u);
    let c = textureLoad(sprite_radiance_in, id.xy, 0);
    let d = textureLoad(sprite_depth_in, id.xy, 0);
    let opacity = saturate(c.a);
    textureStore(cloud_out, id.xy, vec4<f32>(c.rgb, 1.0 - opacity));
    textureStore(depth_out, id.xy, vec4<f32>(select(0.0, d.r / d.a, d.a > 1e-4), 0.0, 0.0, 0.0));
}
// Composite: a simple analytic sky and sun disk behind the clouds, the clouds over it,
// exposure, the ACES fitted tone curve and gamma (seed 001), to an 8-bit image.

@group(0) @binding(9) var cloud_in: texture_2d<f32>;                          // march output
@group(0) @binding(10) var image_out: texture_storage_2d<rgba8unorm, write>; // display image
@group(0) @binding(44) var hdr_out: texture_storage_2d<rgba16float, write>;   // HDR output, before the host's target
@group(0) @binding(37) var depth_in: texture_2d<f32>;                         // clouds' depth (m), 0 where none

// Sky radiance along unit `d` for a camera at altitude `alt`: a zenith-to-horizon gradient
// scaled by the sun's illuminance and elevation, a forward glow around the sun, and a dark
// ground below the horizon. Deliberately simple (DESIGN: a simple analytic sky first).
fn sky_radiance(d: vec3<f32>, alt: f32) -> vec3<f32> {
    let sun = frame.sun_direction;
    let e = frame.sun_illuminance;
    let day = saturate(sun.y * 4.0 + 0.3);
    if hits_ground(vec3<f32>(0.0, alt, 0.0), alt, d) {
        let ground_albedo = vec3<f32>(0.035, 0.035, 0.03);
        return ground_albedo * (e * max(sun.y, 0.0) / PI + 0.05 * e * day);
    }
    let zenith = vec3<f32>(0.018, 0.04, 0.1);
    let horizon = vec3<f32>(0.07, 0.085, 0.11);
    let up = saturate(d.y);
    let gradient = mix(horizon, zenith, sqrt(up));
    // Warm the horizon as the sun sets (longer light paths redden it).
    let sunset = (1.0 - day * 0.8) * pow(1.0 - up, 6.0) * vec3<f32>(0.25, 0.1, 0.0);
    let glow = phase_hg(dot(d, sun), 0.76) * 0.02;
    return e * (gradient * day + sunset * saturate(sun.y * 10.0 + 1.0) + glow * day);
}

// Radiance of the sun's disk: illuminance over its solid angle 2 pi (1 - cos r).
fn sun_disk(d: vec3<f32>) -> vec3<f32> {
    let cos_r = frame.sun_cos_radius;
    if dot(d, frame.sun_direction) < cos_r {
        return vec3<f32>(0.0);
    }
    return frame.sun_illuminance / (2.0 * PI * max(1.0 - cos_r, 1e-6));
}

// The clouds in the physical sky: the sky-view table (the lit ground included, with the
// clouds' shadows on it) and the sun's disc
// through the air behind them; in front of them the air between the camera and their depth
// (aerial perspective), which dims their light and adds its own. Where a cloud leaves
// transmittance a, the sky behind it shows through as a, and the air in front of the cloud
// stands for the rest: L = a S + (1 - a) S_ap + T_ap C (Hillaire 2020, section 5.4's use of
// the aerial-perspective volume on opaque surfaces, with partly transparent clouds).
// With light shafts the air in front of the clouds and behind them lacks what the clouds'
// shadows take from it (`light_shafts`). The rainbow, in the rain below the clouds, adds in
// front of them (not yet over the host's geometry).
fn physical_composite(pixel: vec2<u32>, view: vec3<f32>, cloud: vec4<f32>) -> vec3<f32> {
    let surface = has_surface(pixel);
    let shafts = composite_shafts(pixel, view, cloud.a, surface);
    var sky = surface_radiance();
    var bow = vec3<f32>(0.0);
    if !surface {
        sky = max(physical_background(pixel, view) - shafts.all * frame.sun_illuminance, vec3<f32>(0.0));
        bow = rainbow_radiance(view) * frame.sun_illuminance;
    }
    if frame.rain_shafts <= 0.0 {
        return sky * cloud.a + physical_over(pixel, cloud, shafts.front) + bow;
    }
    // The rain shafts: in front of everything from below the rain's top, behind the clouds
    // (over the sky and ground only) from above it.
    let veil = rain_veil(pixel, view);
    if rain_in_front() {
        return through_rain(veil, sky * cloud.a + physical_over(pixel, cloud, shafts.front)) + bow;
    }
    return through_rain(veil, sky) * cloud.a + physical_over(pixel, cloud, shafts.front) + bow;
}

// What shows behind the clouds where the host has no geometry: the sky-view table, the lit
// ground below the horizon, and the sun, moon and stars above it.
fn physical_background(pixel: vec2<u32>, view: vec3<f32>) -> vec3<f32> {
    let e = frame.sun_illuminance;
    let r = camera_air_origin().y;
    var sky = sky_view(view) * e;
    if meets_ground(r, view.y) {
        // The table's ground is lit everywhere; where the clouds shade it, less.
        sky = max(sky - ground_shadow_loss(view, r) * e, vec3<f32>(0.0));
    } else {
        var space = night_sky(pixel, view);
        if (frame.flags & FLAG_MOONLIT) == 0u {
            space += sun_disk(view);
        }
        sky += space * transmittance_to_top(r, view.y);
    }
    return sky;
}

// The clouds' light in front of the background, and the air between the camera and them:
// (1 - a) S_ap + T_ap C, the air's light less `shaded` (per unit sun illuminance: what the
// clouds' shadows take from it, `ShaftLoss::front`).
fn physical_over(pixel: vec2<u32>, cloud: vec4<f32>, shaded: vec3<f32>) -> vec3<f32> {
    if cloud.a >= 1.0 {
        return vec3<f32>(0.0);
    }
    let ap = aerial(pixel, textureLoad(depth_in, pixel, 0).r);
    let air = max(ap.rgb - shaded, vec3<f32>(0.0));
    return air * frame.sun_illuminance * (1.0 - cloud.a) + cloud.rgb * ap.a;
}

// Light shafts (crepuscular rays, `atmosphere.light_shafts`). The sky-view and
// aerial-perspective tables hold the air's light as if all of it saw the sun; where a cloud
// shades the air between the camera and what it sees, that air scatters none of the sun's
// light (single scattering: its multiple scattering, lit from the whole sky, stays), and the
// shade shows as dark shafts beside the lit air between them. The loss is the sun's single
// scattering (the tables' own terms, Hillaire 2020 eq. 11's first) times each point's shade,
// integrated along the view ray: what Bruneton and Neyret 2008's light shafts
// remove through a shadow volume's length, here sampled from the cloud-shadow map. A point's
// transmittance toward the sun is the map's at its projection along the sun onto the ground:
// exact below the cloud layers, where shafts are seen; inside them the shade thins linearly to
// none at their top (the clouds' own march lights the air between them there). The map covers
// 40 km around the camera, so a low sun's shafts fade where they project beyond it.
const SHAFT_STEPS: u32 = 48u;
const SHAFT_RANGE_KM: f32 = 32.0;   // as far as the aerial-perspective table reaches
const SHAFT_SALT: u32 = 0x5AF7u;    // the dither's own stream of hash_unit
const SHAFT_MIN_SUN_Y: f32 = 1e-3;  // the sun's least height (its direction's y) with shafts

// The sun's single scattering by the air that the clouds shade, per unit sun illuminance:
// `front` over the ray's first `split_m` m (the clouds' depth), `all` to `end_km`.
struct ShaftLoss {
    front: vec3<f32>,
    all: vec3<f32>,
}

// The shafts of the composite at `pixel` along `view` (none without FLAG_LIGHT_SHAFTS): over
// the host's geometry the air up to the clouds' depth only, which is all of the air the
// composite draws there; elsewhere to where the ray meets the ground or leaves the air.
fn composite_shafts(pixel: vec2<u32>, view: vec3<f32>, alpha: f32, surface: bool) -> ShaftLoss {
    if (frame.flags & FLAG_LIGHT_SHAFTS) == 0u || (surface && alpha >= 1.0) {
        return ShaftLoss(vec3<f32>(0.0), vec3<f32>(0.0));
    }
    let depth = textureLoad(depth_in, pixel, 0).r;
    var end_km = depth * 1e-3;
    if !surface {
        end_km = air_ray_end(camera_air_origin(), view).x;
    }
    return light_shafts(pixel, view, depth, end_km);
}

// The shade (1 - transmittance toward the sun) at camera-relative `rel` (m) between the
// layers' lowest bottom and highest top `span` (m).
fn shaft_shade(rel: vec3<f32>, span: vec2<f32>) -> f32 {
    if rel.y >= span.y {
        return 0.0;
    }
    let sun = frame.sun_direction;
    let shade = 1.0 - ground_shadow(rel - sun * (rel.y / sun.y));
    return shade * (1.0 - saturate((rel.y - span.x) / (span.y - span.x)));
}

// SHAFT_STEPS even segments over the ray's first SHAFT_RANGE_KM (and, looking up, not past the
// layers' top), one sample a segment at a dithered place (the same for every segment of a
// pixel, and every frame), so that the segments' banding turns to fine noise; a segment the
// split cuts counts toward `front` by the part of it in front.
fn light_shafts(pixel: vec2<u32>, view: vec3<f32>, split_m: f32, end_km: f32) -> ShaftLoss {
    var loss = ShaftLoss(vec3<f32>(0.0), vec3<f32>(0.0));
    let sun = frame.sun_direction;
    let span = layers_span();
    let cam_alt = max(frame.camera_position.y, 0.0);
    var end = min(end_km, SHAFT_RANGE_KM);
    if view.y > 0.0 {
        end = min(end, max(span.y - cam_alt, 0.0) * 1e-3 / view.y);
    }
    // A sun within 0.06 degrees of the horizon projects every shaded point off the map (and
    // the projection's division would overflow).
    if sun.y <= SHAFT_MIN_SUN_Y || !(end > 0.0) {
        return loss;
    }
    let origin = camera_air_origin();
    let cos_theta = dot(view, sun);
    let phase_r = phase_rayleigh(cos_theta);
    let phase_m = phase_cornette_shanks_air(cos_theta, frame.mie_g);
    let dt = end / f32(SHAFT_STEPS);
    let offset = hash_unit(pixel, SHAFT_SALT);
    let split_km = split_m * 1e-3;
    var tau = vec3<f32>(0.0);
    for (var k = 0u; k < SHAFT_STEPS; k++) {
        let t = (f32(k) + offset) * dt;
        let p = origin + view * t;
        let r = length(p);
        let air = air_at(r - air_bottom());
        let shade = shaft_shade(view * (t * 1000.0) + vec3<f32>(0.0, cam_alt, 0.0), span);
        if shade > 0.0 {
            let t_view = exp(-(tau + air.extinction * (offset * dt)));
            let single = sun_transmittance(r, dot(p / r, sun)) * (air.rayleigh * phase_r + vec3<f32>(air.mie * phase_m));
            let lost = t_view * single * (shade * dt);
            loss.all += lost;
            // The segment's part in front of the split, so that the front moves smoothly
            // with the clouds' depth (a sample flipping sides would flicker).
            loss.front += lost * saturate((split_km - f32(k) * dt) / dt);
        }
        tau += air.extinction * dt;
    }
    return loss;
}

// ACES filmic curve fitted by Narkowicz (seed 001), input pre-exposed so 1 maps to ~0.8.
fn aces_fitted(x: vec3<f32>) -> vec3<f32> {
    let a = 2.51;
    let b = 0.03;
    let c = 2.43;
    let d = 0.59;
    let e = 0.14;
    return clamp((x * (a * x + b)) / (x * (c * x + d) + e), vec3<f32>(0.0), vec3<f32>(1.0));
}

// The host's geometry as the display image shows it (the CLI and examples; a host composites
// the clouds over its own shading instead): a grey surface (albedo 0.3) facing up, lit as the
// analytic sky's ground is.
fn surface_radiance() -> vec3<f32> {
    let sun = frame.sun_direction;
    let e = frame.sun_illuminance;
    let day = saturate(sun.y * 4.0 + 0.3);
    return vec3<f32>(0.3) * (e * max(sun.y, 0.0) / PI + 0.05 * e * day);
}

// Exposure, tone curve, saturation and gamma of a pixel's radiance, to the display image.
fn store_display(pixel: vec2<u32>, radiance: vec3<f32>) {
    let exposed = radiance * frame.exposure;
    let display = pow(saturated(aces_fitted(exposed)), vec3<f32>(1.0 / 2.2));
    textureStore(image_out, pixel, vec4<f32>(display, 1.0));
}

// The tone-mapped colour `c` with its saturation scaled by `frame.saturation` (`post.saturation`,
// seed 001's "Saturability"): moved away from its luminance (Rec. 709 weights) by that factor,
// within [0, 1]. At 1 it is `c` itself, bit for bit.
fn saturated(c: vec3<f32>) -> vec3<f32> {
    let s = frame.saturation;
    if s == 1.0 {
        return c;
    }
    let y = dot(c, vec3<f32>(0.2126, 0.7152, 0.0722));
    return clamp(vec3<f32>(y) + (c - vec3<f32>(y)) * s, vec3<f32>(0.0), vec3<f32>(1.0));
}

@compute @workgroup_size(8, 8, 1)
fn composite(
    @builtin(global_invocation_id) id: vec3<u32>,
    @builtin(local_invocation_index) local: u32,
) {
    var flare = vec3<f32>(0.0);
    if frame.lens_flare_intensity > 0.0 {
        flare = shared_flare_source(local, analytic_sun());
    }
    if any(id.xy >= frame.size) {
        return;
    }
    let pixel = id.xy;
    let cloud = textureLoad(cloud_in, pixel, 0);
    var background = surface_radiance();
    if !has_surface(pixel) {
        background = analytic_background(view_ray(pixel));
    }
    var radiance = background * cloud.a + cloud.rgb;
    if frame.rain_shafts > 0.0 {
        let veil = rain_veil(pixel, view_ray(pixel));
        if rain_in_front() {
            radiance = through_rain(veil, radiance);
        } else {
            radiance = through_rain(veil, background) * cloud.a + cloud.rgb;
        }
    }
    if frame.lens_flare_intensity > 0.0 {
        radiance += lens_flare(pixel, flare);
    }
    store_display(pixel, radiance);
}

// The sun's illuminance reaching the camera through the analytic sky's air (which does not
// dim it): 0 below the horizon.
fn analytic_sun() -> vec3<f32> {
    let alt = frame.camera_position.y;
    if hits_ground(vec3<f32>(0.0, alt, 0.0), alt, frame.sun_direction) {
        return vec3<f32>(0.0);
    }
    return frame.sun_illuminance;
}

// What shows behind the clouds in the analytic sky where the host has no geometry: the sky's
// gradient, and the sun's disc above the horizon.
fn analytic_background(view: vec3<f32>) -> vec3<f32> {
    let alt = frame.camera_position.y;
    var background = sky_radiance(view, alt);
    if !hits_ground(vec3<f32>(0.0, alt, 0.0), alt, view) {
        background += sun_disk(view);
    }
    return background;
}

// The same in the physical sky (plan option `physical_sky`).
@compute @workgroup_size(8, 8, 1)
fn composite_physical(
    @builtin(global_invocation_id) id: vec3<u32>,
    @builtin(local_invocation_index) local: u32,
) {
    var flare = vec3<f32>(0.0);
    if frame.lens_flare_intensity > 0.0 {
        // The sun's light through the air to the camera: 0 below the horizon.
        let air = sun_transmittance(camera_air_origin().y, frame.sun_direction.y);
        flare = shared_flare_source(local, frame.sun_illuminance * air);
    }
    if any(id.xy >= frame.size) {
        return;
    }
    let pixel = id.xy;
    let cloud = textureLoad(cloud_in, pixel, 0);
    var radiance = physical_composite(pixel, view_ray(pixel), cloud);
    if frame.lens_flare_intensity > 0.0 {
        radiance += lens_flare(pixel, flare);
    }
    store_display(pixel, radiance);
}

// The HDR output (`Clouds::render_hdr`): linear radiance, premultiplied (the host adds it over
// its image times alpha), and transmittance in alpha, before any exposure or tone curve.
// Without FLAG_HDR_SKY it is the march's radiance and transmittance as they are: the host draws
// its own sky. With it (the host asked for the sky, `Clouds::set_hdr_sky`), wherever the host
// has no geometry the sky is drawn behind the clouds and the pixel is opaque (alpha 0): the same
// radiance the display image tone-maps, so a host that draws no sky of its own gets Stratus's.
@compute @workgroup_size(8, 8, 1)
fn hdr_composite(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.size) {
        return;
    }
    let pixel = id.xy;
    let cloud = textureLoad(cloud_in, pixel, 0);
    var out = cloud;
    if (frame.flags & FLAG_HDR_SKY) != 0u && !has_surface(pixel) {
        let view = view_ray(pixel);
        var background = analytic_background(view);
        if frame.rain_shafts > 0.0 && !rain_in_front() {
            // From above the rain's top: the rain veils the sky and ground behind the clouds.
            background = through_rain(rain_veil(pixel, view), background);
        }
        out = vec4<f32>(background * cloud.a + cloud.rgb, 0.0);
    }
    textureStore(hdr_out, pixel, rain_over_hdr(pixel, out));
}

// The same in the physical sky: with FLAG_HDR_SKY the air in front of the clouds dims and
// adds to them over the host's geometry too, as it does over the sky.
@compute @workgroup_size(8, 8, 1)
fn hdr_composite_physical(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.size) {
        return;
    }
    let pixel = id.xy;
    let cloud = textureLoad(cloud_in, pixel, 0);
    var out = cloud;
    if (frame.flags & FLAG_HDR_SKY) != 0u {
        if has_surface(pixel) {
            let shafts = composite_shafts(pixel, view_ray(pixel), cloud.a, true);
            out = vec4<f32>(physical_over(pixel, cloud, shafts.front), cloud.a);
        } else {
            out = vec4<f32>(physical_composite(pixel, view_ray(pixel), cloud), 0.0);
        }
    }
    textureStore(hdr_out, pixel, rain_over_hdr(pixel, out));
}

// The HDR output with the rain shafts in front (premultiplied radiance, transmittance): where
// the camera is below the rain's top the rain veils whatever the host draws behind too, so it
// dims the transmittance; from above it the rain lies behind the clouds, over the background:
// the sky's where the output holds it (`hdr_composite`, `physical_composite`), the host's own
// otherwise, left to the host. A pixel that already holds the physical sky (alpha 0) got it in
// `physical_composite`; the analytic sky's gets it here.
fn rain_over_hdr(pixel: vec2<u32>, out: vec4<f32>) -> vec4<f32> {
    let has_sky = (frame.flags & FLAG_HDR_SKY) != 0u && !has_surface(pixel);
    if frame.rain_shafts <= 0.0 || !rain_in_front() || (physical_sky() && has_sky) {
        return out;
    }
    let veil = rain_veil(pixel, view_ray(pixel));
    return vec4<f32>(through_rain(veil, out.rgb), out.a * veil.transmittance);
}
// The night sky behind the air (seed 001's night parameters, `[night]`): the moon's disc, the
// catalogue's stars and the Milky Way. The physical composite adds them above the horizon
// through the air's transmittance. Stars and the Milky Way live in J2000 equatorial
// coordinates; `frame.celestial_x/y/z` (the J2000 axes' world directions at the scene's date
// and place) turn a view direction into them.

@group(0) @binding(48) var star_table_in: texture_2d<f32>;  // stratus_astro::stars::gpu_table

// The table's layout (stratus_astro::stars): cells along a cube face's edge, the texture's
// width, and the first record's float index (two floats a cell before it).
const STAR_CELLS: u32 = 16u;
const STAR_TABLE_WIDTH: u32 = 1024u;
const STAR_RECORDS_AT: u32 = 3072u;
// How far from its cell a listed star may lie (radians, 1 degree): a star's light is drawn
// out to here and no farther.
const STAR_MARGIN: f32 = 0.017453293;
// The glare's share of a star's light per unit `star_glare_scale`, and its width over the
// core's.
const STAR_GLARE_SHARE: f32 = 0.02;
const STAR_GLARE_WIDTH: f32 = 4.0;

fn star_float(i: u32) -> f32 {
    return textureLoad(star_table_in, vec2<u32>(i % STAR_TABLE_WIDTH, i / STAR_TABLE_WIDTH), 0).r;
}

// `d` (world) in J2000 equatorial axes.
fn to_celestial(d: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(dot(d, frame.celestial_x), dot(d, frame.celestial_y), dot(d, frame.celestial_z));
}

// The cube-map cell that unit `v` falls in (as stratus_astro::stars::cell_of).
fn star_cell(v: vec3<f32>) -> u32 {
    let a = abs(v);
    var face = 0u;
    var uv = vec2<f32>(0.0);
    var major = 0.0;
    if a.x >= a.y && a.x >= a.z {
        face = select(1u, 0u, v.x > 0.0);
        uv = v.zy;
        major = a.x;
    } else if a.y >= a.z {
        face = select(3u, 2u, v.y > 0.0);
        uv = v.xz;
        major = a.y;
    } else {
        face = select(5u, 4u, v.z > 0.0);
        uv = v.xy;
        major = a.z;
    }
    let st = clamp((uv / major) * 0.5 + 0.5, vec2<f32>(0.0), vec2<f32>(0.999999));
    let cell = vec2<u32>(st * f32(STAR_CELLS));
    return (face * STAR_CELLS + cell.y) * STAR_CELLS + cell.x;
}

// The linear sRGB colour, of luminance 1, of a star of colour index `bv`: its temperature by
// Ballesteros 2012 (EPL 97, 34008), T = 4600 (1 / (0.92 bv + 1.7) + 1 / (0.92 bv + 0.62)),
// and the Planckian locus's chromaticity at T by Kim et al. 2002's cubic spline (IEEE Trans.
// Consumer Electronics 48, 1667-25000 K).
fn star_colour(bv: f32) -> vec3<f32> {
    let t = clamp(4600.0 * (1.0 / (0.92 * bv + 1.7) + 1.0 / (0.92 * bv + 0.62)), 1667.0, 25000.0);
    let k = 1000.0 / t;  // the spline in 1e3 / T keeps its powers in range in f32
    var x = 0.0;
    if t <= 4000.0 {
        x = -0.2661239 * k * k * k - 0.2343589 * k * k + 0.8776956 * k + 0.179910;
    } else {
        x = -3.0258469 * k * k * k + 2.1070379 * k * k + 0.2226347 * k + 0.240390;
    }
    var y = 0.0;
    if t <= 2222.0 {
        y = -1.1063814 * x * x * x - 1.34811020 * x * x + 2.18555832 * x - 0.20219683;
    } else if t <= 4000.0 {
        y = -0.9549476 * x * x * x - 1.37418593 * x * x + 2.09137015 * x - 0.16748867;
    } else {
        y = 3.0817580 * x * x * x - 5.87338670 * x * x + 3.75112997 * x - 0.37001483;
    }
    let xyz = vec3<f32>(x / y, 1.0, (1.0 - x - y) / y);
    let rgb = max(vec3<f32>(
        3.2406 * xyz.x - 1.5372 * xyz.y - 0.4986 * xyz.z,
        -0.9689 * xyz.x + 1.8758 * xyz.y + 0.0415 * xyz.z,
        0.0557 * xyz.x - 0.2040 * xyz.y + 1.0570 * xyz.z,
    ), vec3<f32>(0.0));
    return rgb / dot(rgb, vec3<f32>(0.2126, 0.7152, 0.0722));
}

// A normalised 2D Gaussian of deviation `sigma` at distance `r` (pixels).
fn splat(r: f32, sigma: f32) -> f32 {
    return exp(-r * r / (2.0 * sigma * sigma)) / (2.0 * PI * sigma * sigma);
}

// The stars' radiance along unit world direction `d`: each catalogue star of the direction's
// cell a point of illuminance E0 10^(-0.4 m) (`frame.star_illuminance` the magnitude-0 star's,
// times `frame.star_intensity`), spread over a Gaussian of at least `star_min_radius`
// pixels, growing by `star_radius_scale` with the fourth root of its light, 2% of it times
// `star_glare_scale` in a glare four times as wide; the light does not depend on the size.
fn stars(d: vec3<f32>) -> vec3<f32> {
    let e0 = frame.star_illuminance * frame.star_intensity;
    if e0 <= 0.0 {
        return vec3<f32>(0.0);
    }
    let v = to_celestial(d);
    let cell = star_cell(v);
    let start = u32(star_float(2u * cell));
    let count = u32(star_float(2u * cell + 1u));
    // Angular size of a pixel at the image centre.
    let pixel_angle = 2.0 * frame.tan_half_fov / f32(frame.size.y);
    let glare = min(STAR_GLARE_SHARE * frame.star_glare_scale, 1.0);
    var sum = vec3<f32>(0.0);
    for (var k = 0u; k < count; k++) {
        let at = STAR_RECORDS_AT + 4u * (start + k);
        let s = vec3<f32>(star_float(at), star_float(at + 1u), star_float(at + 2u));
        // The angle from its chord: accurate where acos of a dot product near 1 is not.
        let angle = 2.0 * asin(min(0.5 * length(v - s), 1.0));
        if angle > STAR_MARGIN {
            continue;
        }
        let packed = u32(star_float(at + 3u));
        let magnitude = f32(packed / 1024u) * 0.01 - 2.0;
        let bv = f32(packed % 1024u) / 300.0 - 0.5;
        let r = angle / pixel_angle;
        let sigma = max(frame.star_min_radius, frame.star_radius_scale * pow(10.0, -0.1 * (magnitude - 6.5)));
        let weight = (1.0 - glare) * splat(r, sigma) + glare * splat(r, STAR_GLARE_WIDTH * sigma);
        sum += star_colour(bv) * (pow(10.0, -0.4 * magnitude) * weight);
    }
    return sum * (e0 / (pixel_angle * pixel_angle));
}

// The J2000 equatorial axes' galactic coordinates (rows: toward the galactic centre, l = 90,
// and the north galactic pole; stratus_astro::celestial::equatorial_to_galactic, the
// Hipparcos definition).
const GALACTIC_X: vec3<f32> = vec3<f32>(-0.05487556, -0.87343709, -0.48383502);
const GALACTIC_Y: vec3<f32> = vec3<f32>(0.49410943, -0.44482963, 0.74698224);
const GALACTIC_Z: vec3<f32> = vec3<f32>(-0.86766615, -0.19807637, 0.45598378);
// One S10 (a tenth-magnitude star per square degree) in units of a magnitude-0 star's
// illuminance per steradian: 1e-4 / (pi / 180)^2.
const S10: f32 = 0.32828063;
// Value noise over the sphere (cells of about 2 degrees): the star clouds' mottling.
const MILKY_WAY_CELLS: f32 = 28.0;

fn sky_lattice(c: vec3<i32>) -> f32 {
    let h = pcg((u32(c.x) * 73856093u) ^ (u32(c.y) * 19349663u) ^ (u32(c.z) * 83492791u));
    return f32(h >> 8u) * (1.0 / 16777216.0);
}

// Trilinear value noise in [0, 1) at `p`.
fn sky_noise(p: vec3<f32>) -> f32 {
    let i = floor(p);
    let f = p - i;
    let u = f * f * (3.0 - 2.0 * f);
    let c = vec3<i32>(i);
    let x00 = mix(sky_lattice(c), sky_lattice(c + vec3<i32>(1, 0, 0)), u.x);
    let x10 = mix(sky_lattice(c + vec3<i32>(0, 1, 0)), sky_lattice(c + vec3<i32>(1, 1, 0)), u.x);
    let x01 = mix(sky_lattice(c + vec3<i32>(0, 0, 1)), sky_lattice(c + vec3<i32>(1, 0, 1)), u.x);
    let x11 = mix(sky_lattice(c + vec3<i32>(0, 1, 1)), sky_lattice(c + vec3<i32>(1, 1, 1)), u.x);
    return mix(mix(x00, x10, u.y), mix(x01, x11, u.y), u.z);
}

// The Milky Way's surface brightness in S10 at galactic longitude `l` and latitude `b`
// (degrees, l in (-180, 180]), the starlight of the stars fainter than the catalogue's: a
// floor of 30 at the galactic poles, a disc 8 degrees thick (Gaussian) of 200 toward the
// centre falling to 90 toward the anticentre, the bulge of 900 more around the centre
// (14 by 8 degrees), shaped after Leinert et al. 1998 (A&AS 127, 1, figure 35's map of the
// integrated starlight). The Great Rift's dust dims a lane just north of the plane between
// l = 10 and 60 degrees by up to half.
fn milky_way_s10(l: f32, b: f32) -> f32 {
    let disc = 200.0 * exp(-(b / 8.0) * (b / 8.0)) * (0.45 + 0.55 * exp(-(l / 70.0) * (l / 70.0)));
    let bulge = 900.0 * exp(-(l / 14.0) * (l / 14.0) - (b / 8.0) * (b / 8.0));
    let rift = 0.5 * exp(-((b - 1.5) / 2.2) * ((b - 1.5) / 2.2))
        * smoothstep(5.0, 10.0, l) * (1.0 - smoothstep(55.0, 60.0, l));
    return 30.0 + (disc + bulge) * (1.0 - rift);
}

// The Milky Way's radiance along unit world direction `d` (`night.milky_way_intensity`
// times the model's): warm white (integrated starlight's colour index, about 0.75), mottled
// by +-15% of value noise on the sphere into star clouds.
fn milky_way(d: vec3<f32>) -> vec3<f32> {
    let e0 = frame.star_illuminance * frame.milky_way_intensity;
    if e0 <= 0.0 {
        return vec3<f32>(0.0);
    }
    let v = to_celestial(d);
    let g = vec3<f32>(dot(v, GALACTIC_X), dot(v, GALACTIC_Y), dot(v, GALACTIC_Z));
    let b = degrees(asin(clamp(g.z, -1.0, 1.0)));
    let l = degrees(atan2(g.y, g.x));
    let clouds = 0.7 * sky_noise(v * MILKY_WAY_CELLS) + 0.3 * sky_noise(v * (2.0 * MILKY_WAY_CELLS));
    let s10 = milky_way_s10(l, b) * (0.85 + 0.3 * clouds);
    return star_colour(0.75) * (e0 * S10 * s10);
}

// The moon's disc at `pixel` (view direction `d`): the full moon's illuminance over the
// disc's solid angle where the sun lights the moon's sphere, 0 on its night side and off the
// disc. The full moon shows almost no limb darkening, so the lit part is of even brightness;
// the terminator is softened over 2% of the radius. The limb is anti-aliased by
// `night.moon_msaa`: four samples of the pixel on a rotated grid, or (default) the disc's
// edge spread over one pixel.
fn moon_disc(pixel: vec2<u32>, d: vec3<f32>) -> vec3<f32> {
    let m = frame.moon_direction;
    let cos_r = frame.moon_cos_radius;
    let pixel_angle = 2.0 * frame.tan_half_fov / f32(frame.size.y);
    if frame.moon_illuminance <= 0.0 || dot(d, m) < cos(acos(cos_r) + 2.0 * pixel_angle) {
        return vec3<f32>(0.0);
    }
    let solid_angle = 2.0 * PI * (1.0 - cos_r);
    if (frame.flags & FLAG_MOON_MSAA) != 0u {
        var lit = 0.0;
        // The rotated grid: (1/8, 3/8) of a pixel from its centre, turned by quarter turns.
        var o = vec2<f32>(0.125, 0.375);
        for (var k = 0u; k < 4u; k++) {
            let s = view_ray_at(vec2<f32>(pixel) + 0.5 + o);
            o = vec2<f32>(-o.y, o.x);
            if dot(s, m) >= cos_r {
                lit += moon_lit(s, m, cos_r);
            }
        }
        return vec3<f32>(frame.moon_illuminance / solid_angle * 0.25 * lit);
    }
    let angle = 2.0 * asin(min(0.5 * length(d - m), 1.0));
    let coverage = saturate((acos(cos_r) - angle) / pixel_angle + 0.5);
    return vec3<f32>(frame.moon_illuminance / solid_angle * coverage * moon_lit(d, m, cos_r));
}

// How lit the moon's sphere is where direction `d` meets it (`m` its centre, `cos_r` its
// radius): 1 on the day side, 0 on the night side, over 2% of the radius between.
fn moon_lit(d: vec3<f32>, m: vec3<f32>, cos_r: f32) -> f32 {
    let sin_r = sqrt(1.0 - cos_r * cos_r);
    let offset = (d - m * dot(d, m)) / sin_r;   // in units of the disc's radius
    let x2 = min(dot(offset, offset), 1.0);
    let normal = offset - m * sqrt(1.0 - x2);  // the visible hemisphere faces the camera
    return smoothstep(-0.02, 0.02, dot(normal, frame.real_sun_direction));
}

// Everything of the night sky along `d` at `pixel`, before the air's transmittance.
fn night_sky(pixel: vec2<u32>, d: vec3<f32>) -> vec3<f32> {
    return moon_disc(pixel, d) + stars(d) + milky_way(d);
}
// Lens flare (`post.lens_flare_intensity`, seed 001 section 5.2): light of the sun reflected
// between a lens's surfaces reaches the sensor as ghosts, images of the aperture spread along
// the line from the sun's image through the optical centre, and as a halo around the centre.
// Each ghost here is the hexagonal aperture (six blades) drawn by its signed distance, and
// carries a fixed share of the sun's illuminance that reaches the lens, spread evenly over its
// solid angle: its radiance follows the sun's through the air and through the clouds in front
// of it (the march's transmittance over the sun's disc), and a thick cloud over the sun, the
// host's geometry or the sun's leaving the screen removes it. Shares are per colour channel
// (the coatings tint each ghost); at intensity 1 a ghost carries 1e-4 to 4e-4 of the light,
// the order of a multi-coated lens's double reflections (Hullin et al. 2011, "Physically-based
// real-time lens flare rendering", section 2). Positions are in units of the image's height
// from its centre, y down, so the flare keeps its shape at every resolution.

// A disc is sampled at its centre and four points on its rim.
const FLARE_TAPS: f32 = 5.0;
// The aperture's edge normals: a hexagon turned 15 degrees (its blades' angle in the lens),
// its normals at 45, 105 and 165 degrees (and their opposites).
const FLARE_EDGE_0: vec2<f32> = vec2<f32>(0.70710678, 0.70710678);
const FLARE_EDGE_1: vec2<f32> = vec2<f32>(-0.25881905, 0.96592583);
const FLARE_EDGE_2: vec2<f32> = vec2<f32>(-0.96592583, 0.25881905);
// The halo: its radius and width (image heights), and its share of the sun's light.
const FLARE_HALO_RADIUS: f32 = 0.42;
const FLARE_HALO_WIDTH: f32 = 0.012;
const FLARE_HALO_SHARE: f32 = 0.6e-3;
// The halo's colour fringe: its red ring lies this far outside its blue (image heights).
const FLARE_HALO_FRINGE: f32 = 0.01;

// The sun's image centre on the screen, in pixels (continuous: pixel p spans [p, p + 1)), and
// whether it lies in front of the camera.
struct SunImage {
    at: vec2<f32>,
    ahead: bool,
}

fn sun_image() -> SunImage {
    let sun = frame.sun_direction;
    let z = dot(sun, frame.camera_forward);
    if z <= 0.0 {
        return SunImage(vec2<f32>(0.0), false);
    }
    // view_ray's mapping, inverted: ndc = (pixel + 0.5) / size * 2 - 1, y down.
    let ndc = vec2<f32>(
        dot(sun, frame.camera_right) / (z * frame.tan_half_fov * frame.aspect),
        -dot(sun, frame.camera_up) / (z * frame.tan_half_fov),
    );
    return SunImage((ndc * 0.5 + 0.5) * vec2<f32>(frame.size), true);
}

// The sun's illuminance that reaches the lens, given `direct` (what arrives through the air
// alone): `direct` times the share of the sun's disc that is on screen and unhidden, and the
// clouds' transmittance there. 0 without flare, under the moon as key light, or with the sun
// behind the camera.
fn flare_source(direct: vec3<f32>) -> vec3<f32> {
    if frame.lens_flare_intensity <= 0.0 || (frame.flags & FLAG_MOONLIT) != 0u {
        return vec3<f32>(0.0);
    }
    let image = sun_image();
    if !image.ahead {
        return vec3<f32>(0.0);
    }
    let cos_r = frame.sun_cos_radius;
    let tan_r = sqrt(max(1.0 - cos_r * cos_r, 0.0)) / cos_r;
    let radius_px = max(tan_r / frame.tan_half_fov * 0.5 * f32(frame.size.y), 1.0);
    var seen = 0.0;
    for (var i = 0u; i < 5u; i++) {
        var offset = vec2<f32>(0.0);
        if i > 0u {
            let axis = select(vec2<f32>(0.0, 1.0), vec2<f32>(1.0, 0.0), i < 3u);
            offset = axis * select(-radius_px, radius_px, (i & 1u) == 1u);
        }
        let p = floor(image.at + offset);
        if all(p >= vec2<f32>(0.0)) && all(p < vec2<f32>(frame.size)) {
            let pixel = vec2<u32>(p);
            if !has_surface(pixel) {
                seen += textureLoad(cloud_in, pixel, 0).a;
            }
        }
    }
    return direct * (seen / FLARE_TAPS);
}

// The sun's light reaching the lens, shared by a workgroup: it is the same for every pixel,
// and measuring it reads five texels of the march output (and as many of the scene depth), so
// one invocation in 64 does it.
var<workgroup> flare_light: vec3<f32>;

// `flare_source(direct)`, measured by the workgroup's first invocation. Every invocation of the
// workgroup must call it (it holds a barrier), before any returns.
fn shared_flare_source(local: u32, direct: vec3<f32>) -> vec3<f32> {
    if local == 0u {
        flare_light = flare_source(direct);
    }
    workgroupBarrier();
    return flare_light;
}

// Signed distance (image heights) from `p` to a regular hexagon of circumradius `r` about the
// origin, its edges' normals FLARE_EDGE_*: the largest distance past its three pairs of edges
// (exact inside and beside the edges, a little short beyond corners).
fn aperture_distance(p: vec2<f32>, r: f32) -> f32 {
    let apothem = r * 0.8660254;
    let d0 = abs(dot(p, FLARE_EDGE_0));
    let d1 = abs(dot(p, FLARE_EDGE_1));
    let d2 = abs(dot(p, FLARE_EDGE_2));
    return max(d0, max(d1, d2)) - apothem;
}

// One ghost's radiance per unit sun illuminance at `p`: at `along` times the sun's position
// `s` (1 at the sun, negative across the centre), circumradius `r`, carrying `share` of the
// light over its solid angle (its area in image heights times (2 tan(fov / 2))^2 per unit
// area). Its edge is soft over a fifth of its radius and a little brighter than its middle,
// as a defocused aperture's image is.
fn ghost(p: vec2<f32>, s: vec2<f32>, along: f32, r: f32, share: vec3<f32>) -> vec3<f32> {
    let q = p - s * along;
    // Beyond the soft edge (which ends 0.2 r past the edges, inside 1.25 r): nothing.
    if dot(q, q) > 1.5625 * r * r {
        return vec3<f32>(0.0);
    }
    let d = aperture_distance(q, r);
    let soft = 0.2 * r;
    let inside = 1.0 - smoothstep(-soft, soft, d);
    let rim = 0.75 + 0.5 * smoothstep(-0.5 * r, 0.0, d);
    let apothem = r * 0.8660254;
    let area = 2.0 * sqrt(3.0) * apothem * apothem;
    let height_angle = 2.0 * frame.tan_half_fov;
    return share * (inside * rim / (area * height_angle * height_angle));
}

// The flare's radiance at `pixel` for `source`, the sun's illuminance reaching the lens
// (`flare_source`), times `lens_flare_intensity`.
fn lens_flare(pixel: vec2<u32>, source: vec3<f32>) -> vec3<f32> {
    if all(source <= vec3<f32>(0.0)) {
        return vec3<f32>(0.0);
    }
    let size = vec2<f32>(frame.size);
    let centre = size * 0.5;
    let p = (vec2<f32>(pixel) + 0.5 - centre) / size.y;
    let s = (sun_image().at - centre) / size.y;
    var flare = vec3<f32>(0.0);
    flare += ghost(p, s, 0.55, 0.035, vec3<f32>(1.0e-4, 2.0e-4, 1.2e-4));
    flare += ghost(p, s, 0.25, 0.018, vec3<f32>(2.5e-4, 1.5e-4, 0.6e-4));
    flare += ghost(p, s, -0.2, 0.05, vec3<f32>(1.2e-4, 1.6e-4, 2.4e-4));
    flare += ghost(p, s, -0.45, 0.025, vec3<f32>(2.4e-4, 1.0e-4, 2.2e-4));
    flare += ghost(p, s, -0.8, 0.07, vec3<f32>(1.6e-4, 2.6e-4, 1.4e-4));
    flare += ghost(p, s, -1.25, 0.11, vec3<f32>(4.0e-4, 3.0e-4, 2.0e-4));
    // The halo: a ring about the centre, brightest where the axis crosses it on the sun's
    // side, its red outside its blue (the coatings' dispersion). Its share spreads over the
    // ring's area 2 pi R w sqrt(2 pi) (a Gaussian profile of width w).
    let r = length(p);
    if abs(r - FLARE_HALO_RADIUS) > FLARE_HALO_FRINGE + 6.0 * FLARE_HALO_WIDTH {
        return flare * source * frame.lens_flare_intensity;
    }
    let side = saturate(dot(p, s) / max(r * length(s), 1e-4));
    let ring = vec3<f32>(
        r - (FLARE_HALO_RADIUS + FLARE_HALO_FRINGE),
        r - FLARE_HALO_RADIUS,
        r - (FLARE_HALO_RADIUS - FLARE_HALO_FRINGE),
    ) / FLARE_HALO_WIDTH;
    let profile = exp(-0.5 * ring * ring);
    let ring_area = 2.0 * PI * FLARE_HALO_RADIUS * FLARE_HALO_WIDTH * sqrt(2.0 * PI);
    let height_angle = 2.0 * frame.tan_half_fov;
    // side^2 averages 1/4 around the ring when the sun is off-centre: x4 keeps the share.
    flare += FLARE_HALO_SHARE * profile * (4.0 * side * side)
        / (ring_area * height_angle * height_angle);
    return flare * source * frame.lens_flare_intensity;
}
// Precipitation and lightning (section `[precipitation]`, `[lightning]`): the rain's shafts in
// the composite, rain or snow particles near the camera drawn over the display image by a
// raster pass, and the light of a lightning flash inside the clouds.

// --- Rain shafts -------------------------------------------------------------------------
// The rain below a raining cell (`rain_at`: a precipitating layer's precipitation where the
// weather map has a cell's core above, `falling_rain`) dims what is behind it and scatters the light under the deck
// (the march's ambient at the layer's bottom, and a lightning flash's) toward the camera; lit from below a dark deck
// while the air about it sees the sky, a distant cell hangs a darker, greyer column. Heavy
// rain's extinction is what Koschmieder's law gives for the visibility a report of heavy rain
// carries, about 3 km (3.912 / 3 km); `rain_shafts` scales it. Steps at a dithered place a
// pixel over the part of the ray below the rain's top within RAIN_SHAFT_RANGE_M m of the camera.
const RAIN_SHAFT_EXTINCTION: f32 = 1.3e-3;
const RAIN_SHAFT_STEPS: u32 = 24u;
const RAIN_SHAFT_RANGE_M: f32 = 30000.0;
const RAIN_SHAFT_SALT: u32 = 0x7A1Bu;

// What the rain between the camera and a pixel's end does: the light it scatters toward the
// camera and the share of what is behind it that it lets through.
struct RainVeil {
    radiance: vec3<f32>,
    transmittance: f32,
}

// Rain falls from the cells' dense cores, not from all of their cloud: a convective cell's
// precipitation covers a fraction of its cloud's area. Where the weather map's coverage (after
// the layer's) passes RAIN_CORE.x rain begins, and is full at RAIN_CORE.y.
const RAIN_CORE: vec2<f32> = vec2<f32>(0.6, 0.9);

// The rain falling at world point `p` (altitude p.y), for the shafts and the particles: under
// each precipitating layer whose bottom is above it, its precipitation where the weather map
// has a core.
fn falling_rain(p: vec3<f32>) -> f32 {
    var rain = 0.0;
    for (var i = 0u; i < layer_count(); i++) {
        let l = cloud_layer(i);
        if l.precipitation > 0.0 && p.y < l.bottom {
            let w = sample_weather(p, l);
            rain += w.precipitation * smoothstep(RAIN_CORE.x, RAIN_CORE.y, w.coverage);
        }
    }
    return rain;
}

// Whether the rain lies in front of the clouds along every ray (the camera is below the
// highest raining layer's bottom), or behind them (the camera is above it).
fn rain_in_front() -> bool {
    return frame.camera_position.y <= rain_top();
}

// The rain shafts along `view` from the camera at `pixel` (none without `rain_shafts`), to the
// host's geometry, the ground, or where the ray leaves the rain.
fn rain_veil(pixel: vec2<u32>, view: vec3<f32>) -> RainVeil {
    var veil = RainVeil(vec3<f32>(0.0), 1.0);
    let top = rain_top();
    if frame.rain_shafts <= 0.0 || top <= 0.0 {
        return veil;
    }
    let cam = frame.camera_position;
    var start = 0.0;
    var end = RAIN_SHAFT_RANGE_M;
    if cam.y > top {
        if view.y >= 0.0 {
            return veil;
        }
        start = (cam.y - top) / -view.y;
    } else if view.y > 0.0 {
        end = min(end, (top - cam.y) / view.y);
    }
    if view.y < 0.0 {
        end = min(end, cam.y / -view.y);
    }
    end = min(end, scene_surface(pixel, view));
    if !(end > start) {
        return veil;
    }
    let dt = (end - start) / f32(RAIN_SHAFT_STEPS);
    let offset = hash_unit(pixel, RAIN_SHAFT_SALT);
    let k = RAIN_SHAFT_EXTINCTION * frame.rain_shafts;
    for (var i = 0u; i < RAIN_SHAFT_STEPS; i++) {
        let t = start + (f32(i) + offset) * dt;
        let rel = view * t + vec3<f32>(0.0, cam.y, 0.0);
        let beta = k * falling_rain(rel + vec3<f32>(cam.x, 0.0, cam.z));
        if beta > 0.0 {
            let step_t = exp(-beta * dt);
            veil.radiance += (ambient(0.0, rel) + lightning_light(rel)) * (veil.transmittance * (1.0 - step_t));
            veil.transmittance *= step_t;
        }
    }
    return veil;
}

// `behind` seen through the rain in front of it.
fn through_rain(veil: RainVeil, behind: vec3<f32>) -> vec3<f32> {
    return veil.radiance + behind * veil.transmittance;
}

// --- Lightning -----------------------------------------------------------------------------
// A flash (`lightning_position`, `lightning_illuminance` 1 km from it; the host draws when
// and where, crates/scene/src/lightning.rs) lights the cloud about it through the cloud: its
// light, scattered many times, leaves the channel diffused, isotropic, and dimmed with
// distance beyond the inverse square over a diffusion length of about a kilometre (light
// diffusing through cloud of extinction ~0.05/m has a transport length of some hundred
// metres; Koshak et al. 1994 model lightning's light leaving a cloud this way). Within
// LIGHTNING_CORE_M of the channel the light stays at its core's.
const LIGHTNING_DIFFUSION_M: f32 = 1500.0;
const LIGHTNING_CORE_M: f32 = 200.0;
// A flash's colour, linear rgb: the channel's light is white to blue-white (its spectrum is
// rich in the nitrogen and hydrogen lines of 500-660 nm and the continuum; Orville 1968).
const LIGHTNING_COLOUR: vec3<f32> = vec3<f32>(0.85, 0.9, 1.0);

// The flash's in-scattered radiance per unit scattering coefficient at camera-relative `rel`
// (isotropic after many scatterings): its illuminance there over 4 pi.
fn lightning_light(rel: vec3<f32>) -> vec3<f32> {
    if frame.lightning_illuminance <= 0.0 {
        return vec3<f32>(0.0);
    }
    let cam = frame.camera_position;
    let to = rel + vec3<f32>(cam.x, 0.0, cam.z) - frame.lightning_position;
    let r = max(length(to), LIGHTNING_CORE_M);
    let q = 1000.0 / r;
    let e = frame.lightning_illuminance * q * q * exp((1000.0 - r) / LIGHTNING_DIFFUSION_M);
    return LIGHTNING_COLOUR * (e / (4.0 * PI));
}

// --- Particles -----------------------------------------------------------------------------
// Rain or snow near the camera: PRECIP_PARTICLES x `precip_density` particles, each at a
// random place in a box of side `precip_box` that moves with the fall and the wind
// (`precip_offset`) and wraps about the camera, drawn where the rain at its place
// (`falling_rain`) is at least its own random share (so the density follows the layer's
// precipitation and the weather map). A raindrop is a streak along its velocity over
// PRECIP_SHUTTER_S (the eye's and a camera's exposure blurs drops into streaks); a snowflake a
// round flake that sways as it falls. Each is lit by the light under the deck (the march's
// ambient at the layer's bottom), and drawn over the display image: its coverage of a pixel
// (its width in pixels, at most one) times its opacity, premultiplied.
const PRECIP_PARTICLES: u32 = 8192u;   // at `precip_density` 1; the pass draws 4x this
const PRECIP_SALT: u32 = 0xD40Bu;
const PRECIP_SHUTTER_S: f32 = 0.033;
const PRECIP_NEAR_M: f32 = 0.25;       // nearer than this a particle is not drawn
const RAIN_WIDTH_M: f32 = 0.004;       // a drop's streak, its glints included
const SNOW_WIDTH_M: f32 = 0.01;        // an aggregate flake
const RAIN_OPACITY: f32 = 0.6;         // a drop is mostly clear: it shows the light above it bent
const SNOW_OPACITY: f32 = 0.9;
const RAIN_GLINT: f32 = 1.6;           // a drop's light over the deck's ambient: it gathers the sky above
const PRECIP_MIN_COVERAGE: f32 = 0.4;  // the least share of a pixel a far particle keeps
const SNOW_SWAY_M: f32 = 0.3;          // the flakes' sway, one turn each 2 m of fall
const PRECIP_MIN_WIDTH_PX: f32 = 1.5;  // thinner particles are drawn this wide, fainter

struct PrecipVertex {
    @builtin(position) position: vec4<f32>,
    // Across the particle (-1 to 1) and along it (0 at its head, 1 at its tail).
    @location(0) uv: vec2<f32>,
    // Premultiplied display colour at full coverage, and its opacity.
    @location(1) @interpolate(flat) colour: vec4<f32>,
    // Its distance from the camera (m).
    @location(2) @interpolate(flat) distance: f32,
}

// Four random numbers in [0, 1) for particle `id`.
fn precip_random(id: u32) -> vec4<f32> {
    let a = pcg(id ^ pcg(PRECIP_SALT));
    let b = pcg(a);
    let c = pcg(b);
    let d = pcg(c);
    return vec4<f32>(vec4<u32>(a, b, c, d) >> vec4<u32>(8u)) * (1.0 / 16777216.0);
}

// A camera-relative point in normalised device coordinates (x right, y up) and its depth.
fn precip_project(rel: vec3<f32>) -> vec3<f32> {
    let z = dot(rel, frame.camera_forward);
    let t = frame.tan_half_fov;
    return vec3<f32>(dot(rel, frame.camera_right) / (z * t * frame.aspect), dot(rel, frame.camera_up) / (z * t), z);
}

@vertex
fn precip_vertex(@builtin(vertex_index) index: u32) -> PrecipVertex {
    var out: PrecipVertex;
    // Not drawn: a degenerate triangle behind the camera (clipped).
    out.position = vec4<f32>(0.0, 0.0, -1.0, 1.0);
    let id = index / 6u;
    if f32(id) >= frame.precip_density * f32(PRECIP_PARTICLES) {
        return out;
    }
    let rnd = precip_random(id);
    let box = frame.precip_box;
    let cam = frame.camera_position;
    let snow = (frame.flags & FLAG_SNOW) != 0u;
    // The particle's place: its random place in the box moved by the fall and drift, wrapped
    // into the box about the camera.
    var rel = (fract((rnd.xyz * box + frame.precip_offset - cam) / box) - 0.5) * box;
    if snow {
        let turn = 2.0 * PI * (frame.precip_offset.y * 0.5 + rnd.w);
        rel += vec3<f32>(cos(turn), 0.0, sin(turn)) * SNOW_SWAY_M;
    }
    let world = rel + cam;
    let share = fract(rnd.w * 7.0);
    if world.y <= 0.0 || falling_rain(world) <= share {
        return out;
    }
    // The head now and the tail where the particle was a shutter ago.
    let tail = rel - frame.precip_velocity * PRECIP_SHUTTER_S;
    let a = precip_project(rel);
    let b = precip_project(tail);
    if min(a.z, b.z) < PRECIP_NEAR_M {
        return out;
    }
    let half = vec2<f32>(frame.size) * 0.5;
    let a_px = a.xy * half;
    var b_px = b.xy * half;
    var width = select(RAIN_WIDTH_M, SNOW_WIDTH_M, snow);
    var opacity = select(RAIN_OPACITY, SNOW_OPACITY, snow);
    if snow {
        b_px = a_px; // a flake: round, its fall in a shutter shorter than it is wide
    }
    let width_px = width / (a.z * frame.tan_half_fov) * half.y;
    let drawn_px = max(width_px, PRECIP_MIN_WIDTH_PX);
    let axis = b_px - a_px;
    let length_px = length(axis);
    var along = vec2<f32>(0.0, -1.0);
    if length_px > 1e-3 {
        along = axis / length_px;
    }
    let across = vec2<f32>(-along.y, along.x);
    let k = index % 6u;
    // Two triangles: (head, -), (head, +), (tail, -); (tail, -), (head, +), (tail, +).
    let at_tail = k == 2u || k == 3u || k == 5u;
    let side = select(-1.0, 1.0, k == 1u || k == 4u || k == 5u);
    let end = select(a_px - along * (0.5 * drawn_px), b_px + along * (0.5 * drawn_px), at_tail);
    let corner = end + across * (side * 0.5 * drawn_px);
    out.position = vec4<f32>(corner / half, 0.5, 1.0);
    out.uv = vec2<f32>(side, select(0.0, 1.0, at_tail));
    // Lit where it is: camera-relative across, its altitude up (as the march's `rel`).
    let at = rel + vec3<f32>(0.0, cam.y, 0.0);
    let light = (ambient(0.0, at) + lightning_light(at)) * select(RAIN_GLINT, 1.0, snow);
    let alpha = opacity * clamp(width_px / drawn_px, PRECIP_MIN_COVERAGE, 1.0);
    let exposed = light * frame.exposure;
    let display = pow(saturated(aces_fitted(exposed)), vec3<f32>(1.0 / 2.2));
    out.colour = vec4<f32>(display, alpha);
    out.distance = length(rel);
    return out;
}

@fragment
fn precip_fragment(in: PrecipVertex) -> @location(0) vec4<f32> {
    let pixel = vec2<u32>(in.position.xy);
    // Behind the host's geometry: hidden.
    if scene_surface(pixel, view_ray(pixel)) < in.distance {
        discard;
    }
    // A drop: soft across (its round section), fading toward the tail. A flake: a soft disc.
    var profile = (1.0 - in.uv.x * in.uv.x) * (1.0 - 0.5 * in.uv.y);
    if (frame.flags & FLAG_SNOW) != 0u {
        let v = 2.0 * in.uv.y - 1.0;
        profile = saturate(1.0 - in.uv.x * in.uv.x - v * v);
    }
    let alpha = in.colour.a * profile;
    return vec4<f32>(in.colour.rgb * alpha, alpha);
}
// Post effects on the display image (`[post]`): the stylised Kuwahara filter (seed 001's
// stylised presets). The composite writes the tone-mapped image into `unstyled_in`; this pass
// writes the display image from it.

@group(0) @binding(45) var unstyled_in: texture_2d<f32>;   // the composite's display image

// Taps from the centre to the window's edge along each axis: a quadrant is (TAPS + 1)^2
// samples, whatever the resolution.
const KUWAHARA_TAPS: i32 = 4;

// The quadrants' weights: 1 / (1 + (v / KUWAHARA_FLAT)^4) for a quadrant whose channels'
// variances sum to v (levels^2). Quadrants flatter than about 2 levels' deviation a channel
// weigh alike, so a smooth gradient stays smooth (their means average to the centre's);
// a quadrant across an edge weighs next to nothing beside one on either side.
const KUWAHARA_FLAT: f32 = 12.0;

// The 8-bit levels (0-255) of a display texel's red, green and blue.
fn display_levels(texel: vec2<i32>) -> vec3<u32> {
    let c = round(clamp(textureLoad(unstyled_in, texel, 0).rgb, vec3<f32>(0.0), vec3<f32>(1.0)) * 255.0);
    return vec3<u32>(u32(c.x), u32(c.y), u32(c.z));
}

// The Kuwahara filter (Kuwahara et al. 1976), with smooth weights (Papari et al. 2007): of the
// four square windows that have the pixel at a corner (left-up, right-up, left-down,
// right-down), the pixel takes the mean colour of those whose colours vary least (the sum of
// the channels' variances), weighted as KUWAHARA_FLAT says. Inside a noisy flat region the
// means smooth it to an even patch; at an edge the windows that straddle it vary most, so the
// pixel takes its colour from its own side and the edge stays; a smooth gradient, which the
// classic filter's choice of one window breaks into terraces, stays smooth.
// The window's radius is `kuwahara_radius` of the image's height, so the taps' offsets are
// UV distances turned to whole texels (rounded, one product of exact floats, the same on
// every backend); where the radius is under TAPS texels several taps share a texel. The sums
// are integers of the 8-bit levels, exact on every backend and in the CPU reference.
@compute @workgroup_size(8, 8, 1)
fn kuwahara(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.size) {
        return;
    }
    let radius_px = frame.kuwahara_radius * f32(frame.size.y);
    let last = vec2<i32>(frame.size) - 1;
    let centre = vec2<i32>(id.xy);
    // Per channel, the four quadrants' sums and sums of squares, quadrant q in component q:
    // bit 0 of q the right half (i >= 0), bit 1 the lower half (j >= 0); the centre row and
    // column belong to both sides. (Vectors, not arrays: naga's HLSL writes an array's zero
    // value as a cast that glslang's HLSL front end refuses.)
    var sum_r = vec4<u32>(0u);
    var sum_g = vec4<u32>(0u);
    var sum_b = vec4<u32>(0u);
    var sq_r = vec4<u32>(0u);
    var sq_g = vec4<u32>(0u);
    var sq_b = vec4<u32>(0u);
    for (var j = -KUWAHARA_TAPS; j <= KUWAHARA_TAPS; j++) {
        let dy = i32(floor(f32(j) * radius_px * 0.25 + 0.5));
        for (var i = -KUWAHARA_TAPS; i <= KUWAHARA_TAPS; i++) {
            let dx = i32(floor(f32(i) * radius_px * 0.25 + 0.5));
            let c = display_levels(clamp(centre + vec2<i32>(dx, dy), vec2<i32>(0), last));
            let left = i <= 0;
            let right = i >= 0;
            let up = j <= 0;
            let down = j >= 0;
            let m = vec4<u32>(vec4<bool>(left && up, right && up, left && down, right && down));
            sum_r += m * c.r;
            sum_g += m * c.g;
            sum_b += m * c.b;
            sq_r += m * (c.r * c.r);
            sq_g += m * (c.g * c.g);
            sq_b += m * (c.b * c.b);
        }
    }
    let n = u32((KUWAHARA_TAPS + 1) * (KUWAHARA_TAPS + 1));
    let nf = f32(n);
    // n^2 times each quadrant's variance, summed over the channels (at most 3 x 25 x 25 x
    // 255^2, well within a u32).
    let spread = (n * sq_r - sum_r * sum_r) + (n * sq_g - sum_g * sum_g) + (n * sq_b - sum_b * sum_b);
    let v = vec4<f32>(spread) / (nf * nf) / KUWAHARA_FLAT;
    let v2 = v * v;
    let w = 1.0 / (1.0 + v2 * v2);
    let colour = vec3<f32>(dot(w, vec4<f32>(sum_r)), dot(w, vec4<f32>(sum_g)), dot(w, vec4<f32>(sum_b))) / nf;
    let weights = w.x + w.y + w.z + w.w;
    textureStore(image_out, id.xy, vec4<f32>(colour / (weights * 255.0), 1.0));
}
