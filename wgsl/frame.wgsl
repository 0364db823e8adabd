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
