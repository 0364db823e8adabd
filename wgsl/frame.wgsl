// Generated from crates/scene/src/uniforms.rs (`frame_members!`) by `cargo xtask
// build-shaders`; edit the declaration there, not this file.
//
// The per-frame uniform block: every member a vec4, so the layout is the same under
// WGSL, std140 and HLSL cbuffer rules.

struct Frame {
    // x, altitude, z (m); w = tan(fov_y / 2).
    camera_position: vec4<f32>,
    // Unit view direction; w = width / height.
    camera_forward: vec4<f32>,
    // Unit, image right; w = exposure.
    camera_right: vec4<f32>,
    // Unit, image up; w = 0.
    camera_up: vec4<f32>,
    // Unit vector toward the sun; w = cos(sun angular radius).
    sun_direction: vec4<f32>,
    // Linear rgb; w = 0.
    sun_illuminance: vec4<f32>,
    // Planet radius, layer bottom, layer top (altitudes, m), cut-off distance (m).
    atmosphere: vec4<f32>,
    // Coverage, density multiplier, cloud type, precipitation.
    clouds: vec4<f32>,
    // Detail strength, erosion threshold, curl strength (m), height gradient strength.
    erosion: vec4<f32>,
    // Weather period, shape period (x axis), detail period, curl period (m).
    periods: vec4<f32>,
    // Weather offset xz, shape offset xz (m), each within [0, period).
    wind_offsets0: vec4<f32>,
    // Detail offset xz, curl offset xz (m), each within [0, period).
    wind_offsets1: vec4<f32>,
    // sigma_s, sigma_a (1/m at density 1), precipitation darkening, wispy_billowy.
    extinction: vec4<f32>,
    // g, g2, blend, powder strength.
    phase: vec4<f32>,
    // a (contribution), b (extinction), c (eccentricity) attenuation per octave, octave
    // build-up length (m).
    multiple_scattering: vec4<f32>,
    // Linear rgb; w = ambient strength.
    ambient_bottom: vec4<f32>,
    // Linear rgb; w = 0.
    ambient_top: vec4<f32>,
    // Step length (m, 0 = derive from view steps), light step growth, first light step (m),
    // early-exit transmittance.
    march: vec4<f32>,
    // Width, height, view steps, light steps.
    counts: vec4<u32>,
    // Phase model ([`PhaseModel::code`](crate::PhaseModel::code)), integration
    // ([`Integration::code`](crate::Integration::code)), height model
    // ([`HeightModel::code`](crate::HeightModel::code)), flags
    // ([`FrameUniforms::FLAG_BEER_POWDER`], [`FrameUniforms::FLAG_JITTER`]).
    modes: vec4<u32>,
    // Octaves (beyond single scattering), frame (jitter seed, path tracer's random streams),
    // path tracer's scattering orders (0 = all), extra cloud layers (0-3).
    misc: vec4<u32>,
    // Last frame's camera position (as `camera_position`, w = its tan(fov_y / 2)): temporal
    // upsampling reprojects through it. [`Scene::uniforms`] sets the current camera; a
    // renderer that keeps history replaces it with the one it rendered last.
    previous_position: vec4<f32>,
    // Last frame's unit view direction; w = its width / height.
    previous_forward: vec4<f32>,
    // Last frame's unit image right; w = 0.
    previous_right: vec4<f32>,
    // Last frame's unit image up; w = 0.
    previous_up: vec4<f32>,
    // Temporal upsampling: block side (1 = off, 2 = 1/4, 4 = 1/16), 0, 0, 0.
    temporal: vec4<u32>,
    // Extra cloud layer 1 (`clouds.layers[0]`): bottom, top (altitudes, m), coverage,
    // density multiplier; zero when absent (`misc.w` counts the extra layers).
    layer1: vec4<f32>,
    // Its cloud type, precipitation, and weather-map offset xz (m, within [0, period)).
    layer1_weather: vec4<f32>,
    // Extra cloud layer 2, as `layer1`.
    layer2: vec4<f32>,
    // Its weather, as `layer1_weather`.
    layer2_weather: vec4<f32>,
    // Extra cloud layer 3, as `layer1`.
    layer3: vec4<f32>,
    // Its weather, as `layer1_weather`.
    layer3_weather: vec4<f32>,
    // The physical sky's air: Rayleigh scattering at the ground (rgb, 1/m); w = its scale
    // height (m).
    air_rayleigh: vec4<f32>,
    // Mie scattering, Mie absorption (1/m at the ground), Mie scale height (m), Mie g.
    air_mie: vec4<f32>,
    // Ozone absorption at its peak (rgb, 1/m); w = the peak's altitude (m).
    air_ozone: vec4<f32>,
    // Thickness of the atmosphere (m), the ozone tent's full width (m), the ground's albedo,
    // 0.
    air_misc: vec4<f32>,
    // The moon (physical sky with a date and place): unit direction toward it; w = the full
    // moon's illuminance (luminance, in the units of `sun_illuminance`; 0 without a moon).
    // Its phase follows from its direction and the real sun's (`night`).
    moon: vec4<f32>,
    // The real sun's unit direction (the moon's lit side faces it; `sun_direction` is the
    // moon's when it is the key light); w = the illuminance of a magnitude-0 star, in the
    // units of `sun_illuminance` (0: no stars).
    night: vec4<f32>,
    // The fitted light model's terms beyond the octaves: side light, coverage exponent,
    // far-shadow chord (m, 0 = off), limb darkening (`MultipleScattering`).
    light_model: vec4<f32>,
    // The octaves' dependence on the view and sun directions: their forward lobe through
    // thin cloud (strength, 0 = off; eccentricity), their vertical anisotropy (0 = off), their
    // deck escape (0 = off) (`MultipleScattering::forward_lobe`, `vertical_anisotropy`,
    // `deck_escape`).
    octave_direction: vec4<f32>,
    // The octaves' optical depth in a closed deck and their dimming looking down: the
    // column's weight (0 = off) and scale, the downward dimming (0 = off), 0
    // (`MultipleScattering::steep_light`, `steep_light_scale`, `downward_dimming`).
    octave_depth: vec4<f32>,
}
