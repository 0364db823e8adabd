//! Geometry derived from a scene (sun direction, camera basis, wind offsets) and the per-frame
//! GPU uniform block.

use crate::scene::{MAX_EXTRA_LAYERS, Scene};

/// Weather-map shift per extra layer, in periods (the golden ratio's fractional parts).
const LAYER_SHIFT: [f64; 2] = [0.381_966, 0.618_034];

/// The one declaration of the per-frame uniform block: every member in order, with its kind
/// (`vec4f`: `vec4<f32>`, `vec4u`: `vec4<u32>`) and what it holds. Member `i` lies at byte
/// offset `16 * i`, the same layout under WGSL, std140 and HLSL cbuffer rules.
///
/// `frame_members!(generator)` calls `generator!` with the list. From it come the Rust block
/// ([`FrameUniforms`], with [`FrameUniforms::MEMBERS`]), the WGSL `struct Frame`
/// ([`FrameUniforms::wgsl`], written to `wgsl/frame.wgsl` by `cargo xtask build-shaders`) and the
/// CPU reference's f64 mirror (`stratus-reference`'s `frame.rs`); a test holds the WGSL's layout
/// to naga's reflection. A new member is added here, filled in [`Scene::uniforms`] and read
/// where it is used.
#[macro_export]
macro_rules! frame_members {
    ($generator:ident) => {
        $generator! {
            /// x, altitude, z (m); w = tan(fov_y / 2).
            camera_position: vec4f,
            /// Unit view direction; w = width / height.
            camera_forward: vec4f,
            /// Unit, image right; w = exposure.
            camera_right: vec4f,
            /// Unit, image up; w = 0.
            camera_up: vec4f,
            /// Unit vector toward the sun; w = cos(sun angular radius).
            sun_direction: vec4f,
            /// Linear rgb; w = 0.
            sun_illuminance: vec4f,
            /// Planet radius, layer bottom, layer top (altitudes, m), cut-off distance (m).
            atmosphere: vec4f,
            /// Coverage, density multiplier, cloud type, precipitation.
            clouds: vec4f,
            /// Detail strength, erosion threshold, curl strength (m), height gradient strength.
            erosion: vec4f,
            /// Weather period, shape period (x axis), detail period, curl period (m).
            periods: vec4f,
            /// Weather offset xz, shape offset xz (m), each within [0, period).
            wind_offsets0: vec4f,
            /// Detail offset xz, curl offset xz (m), each within [0, period).
            wind_offsets1: vec4f,
            /// sigma_s, sigma_a (1/m at density 1), precipitation darkening, wispy_billowy.
            extinction: vec4f,
            /// g, g2, blend, powder strength.
            phase: vec4f,
            /// a (contribution), b (extinction), c (eccentricity) attenuation per octave, octave
            /// build-up length (m).
            multiple_scattering: vec4f,
            /// Linear rgb; w = ambient strength.
            ambient_bottom: vec4f,
            /// Linear rgb; w = 0.
            ambient_top: vec4f,
            /// Step length (m, 0 = derive from view steps), light step growth, first light step (m),
            /// early-exit transmittance.
            march: vec4f,
            /// Width, height, view steps, light steps.
            counts: vec4u,
            /// Phase model ([`PhaseModel::code`](crate::PhaseModel::code)), integration
            /// ([`Integration::code`](crate::Integration::code)), height model
            /// ([`HeightModel::code`](crate::HeightModel::code)), flags
            /// ([`FrameUniforms::FLAG_BEER_POWDER`], [`FrameUniforms::FLAG_JITTER`]).
            modes: vec4u,
            /// Octaves (beyond single scattering), frame (jitter seed, path tracer's random streams),
            /// path tracer's scattering orders (0 = all), extra cloud layers (0-3).
            misc: vec4u,
            /// Last frame's camera position (as `camera_position`, w = its tan(fov_y / 2)): temporal
            /// upsampling reprojects through it. [`Scene::uniforms`] sets the current camera; a
            /// renderer that keeps history replaces it with the one it rendered last.
            previous_position: vec4f,
            /// Last frame's unit view direction; w = its width / height.
            previous_forward: vec4f,
            /// Last frame's unit image right; w = 0.
            previous_right: vec4f,
            /// Last frame's unit image up; w = 0.
            previous_up: vec4f,
            /// Temporal upsampling: block side (1 = off, 2 = 1/4, 4 = 1/16), 0, 0, 0.
            temporal: vec4u,
            /// Extra cloud layer 1 (`clouds.layers[0]`): bottom, top (altitudes, m), coverage,
            /// density multiplier; zero when absent (`misc.w` counts the extra layers).
            layer1: vec4f,
            /// Its cloud type, precipitation, and weather-map offset xz (m, within [0, period)).
            layer1_weather: vec4f,
            /// Extra cloud layer 2, as `layer1`.
            layer2: vec4f,
            /// Its weather, as `layer1_weather`.
            layer2_weather: vec4f,
            /// Extra cloud layer 3, as `layer1`.
            layer3: vec4f,
            /// Its weather, as `layer1_weather`.
            layer3_weather: vec4f,
            /// The physical sky's air: Rayleigh scattering at the ground (rgb, 1/m); w = its scale
            /// height (m).
            air_rayleigh: vec4f,
            /// Mie scattering, Mie absorption (1/m at the ground), Mie scale height (m), Mie g.
            air_mie: vec4f,
            /// Ozone absorption at its peak (rgb, 1/m); w = the peak's altitude (m).
            air_ozone: vec4f,
            /// Thickness of the atmosphere (m), the ozone tent's full width (m), the ground's albedo,
            /// 0.
            air_misc: vec4f,
            /// The moon (physical sky with a date and place): unit direction toward it; w = the full
            /// moon's illuminance (luminance, in the units of `sun_illuminance`; 0 without a moon).
            /// Its phase follows from its direction and the real sun's (`night`).
            moon: vec4f,
            /// The real sun's unit direction (the moon's lit side faces it; `sun_direction` is the
            /// moon's when it is the key light); w = the illuminance of a magnitude-0 star, in the
            /// units of `sun_illuminance` (0: no stars).
            night: vec4f,
            /// The fitted light model's terms beyond the octaves: side light, coverage exponent,
            /// far-shadow chord (m, 0 = off), limb darkening (`MultipleScattering`).
            light_model: vec4f,
            /// The octaves' dependence on the view and sun directions: their forward lobe through
            /// thin cloud (strength, 0 = off; eccentricity), their vertical anisotropy (0 = off), their
            /// deck escape (0 = off) (`MultipleScattering::forward_lobe`, `vertical_anisotropy`,
            /// `deck_escape`).
            octave_direction: vec4f,
            /// The octaves' optical depth in a closed deck and their dimming looking down: the
            /// column's weight (0 = off) and scale, the downward dimming (0 = off), 0
            /// (`MultipleScattering::steep_light`, `steep_light_scale`, `downward_dimming`).
            octave_depth: vec4f,
        }
    };
}

/// The Rust type of a member kind.
macro_rules! member_type {
    (vec4f) => {
        [f32; 4]
    };
    (vec4u) => {
        [u32; 4]
    };
}

/// The WGSL type of a member kind.
macro_rules! member_wgsl {
    (vec4f) => {
        "vec4<f32>"
    };
    (vec4u) => {
        "vec4<u32>"
    };
}

/// Per-frame uniforms, std140/WGSL-uniform compatible, as [`frame_members!`] declares them.
macro_rules! frame_uniforms {
    ($( $(#[doc = $doc:literal])* $name:ident : $kind:ident, )*) => {
        /// Per-frame uniforms, std140/WGSL-uniform compatible: only 16-byte vec4 members, as
        /// [`frame_members!`](crate::frame_members) declares them.
        ///
        /// The WGSL's `struct Frame` is generated from the same declaration
        /// ([`FrameUniforms::wgsl`]); member `i` lies at byte offset `16 * i`. Build it with
        /// [`Scene::uniforms`].
        #[repr(C)]
        #[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
        pub struct FrameUniforms {
            $( $(#[doc = $doc])* pub $name: member_type!($kind), )*
        }

        impl FrameUniforms {
            /// Every member in declaration order with its WGSL type; member `i` is at offset
            /// `16 * i`. The shader-reflection test compares the WGSL struct against this list.
            pub const MEMBERS: &'static [(&'static str, &'static str)] =
                &[$( (stringify!($name), member_wgsl!($kind)) ),*];

            /// What each member holds (its doc comment, one line), in declaration order.
            const DOCS: &'static [&'static [&'static str]] = &[$( &[$($doc),*] ),*];
        }
    };
}

frame_members!(frame_uniforms);

impl FrameUniforms {
    /// Size of the block in bytes (16 bytes a member).
    pub const SIZE: usize = std::mem::size_of::<Self>();

    /// `modes.w` bit: apply the Beer-Powder term.
    pub const FLAG_BEER_POWDER: u32 = 1 << 0;
    /// `modes.w` bit: jitter the view-ray start offset per pixel.
    pub const FLAG_JITTER: u32 = 1 << 1;
    /// `modes.w` bit: dynamic step length (double after 8 empty samples).
    pub const FLAG_DYNAMIC_STEP: u32 = 1 << 2;
    /// `modes.w` bit: high-transmittance checkerboard skipping (temporal only).
    pub const FLAG_CHECKERBOARD: u32 = 1 << 3;
    /// `modes.w` bit: empty-space skipping over the weather map's occupancy grid.
    pub const FLAG_EMPTY_SKIP: u32 = 1 << 4;
    /// `modes.w` bit: the physical sky (`atmosphere.sky = "physical"`).
    pub const FLAG_PHYSICAL_SKY: u32 = 1 << 5;
    /// `modes.w` bit: the moon is the key light (`sun_direction`, `sun_illuminance`).
    pub const FLAG_MOONLIT: u32 = 1 << 6;

    /// The WGSL `struct Frame` of this block, as `wgsl/frame.wgsl` holds it (written by
    /// `cargo xtask build-shaders`, which fails `--check` when the file differs).
    pub fn wgsl() -> String {
        let mut out = String::from(
            "// Generated from crates/scene/src/uniforms.rs (`frame_members!`) by `cargo xtask\n\
             // build-shaders`; edit the declaration there, not this file.\n//\n\
             // The per-frame uniform block: every member a vec4, so the layout is the same under\n\
             // WGSL, std140 and HLSL cbuffer rules.\n\nstruct Frame {\n",
        );
        for ((name, ty), doc) in Self::MEMBERS.iter().zip(Self::DOCS) {
            for line in doc.iter() {
                let line = line.trim();
                if line.is_empty() {
                    out.push_str("    //\n");
                } else {
                    out.push_str(&format!("    // {line}\n"));
                }
            }
            out.push_str(&format!("    {name}: {ty},\n"));
        }
        out.push_str("}\n");
        out
    }

    /// This block with `previous`'s camera as last frame's camera (what a renderer keeping
    /// history does before uploading).
    pub fn with_previous_camera(mut self, previous: &FrameUniforms) -> Self {
        self.previous_position = previous.camera_position;
        self.previous_forward = previous.camera_forward;
        self.previous_right = previous.camera_right;
        self.previous_up = previous.camera_up;
        self
    }

    /// The block's bytes, ready to upload.
    pub fn as_bytes(&self) -> &[u8] {
        bytemuck::bytes_of(self)
    }
}

fn v4(v: [f64; 3], w: f64) -> [f32; 4] {
    [v[0] as f32, v[1] as f32, v[2] as f32, w as f32]
}

fn normalize(v: [f64; 3]) -> Option<[f64; 3]> {
    let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    (len > 0.0 && len.is_finite()).then(|| [v[0] / len, v[1] / len, v[2] / len])
}

/// `x.rem_euclid(period)` guaranteed to lie in `[0, period)` (0 for a non-positive period).
fn wrap(x: f64, period: f64) -> f64 {
    if period.is_nan() || period <= 0.0 {
        return 0.0;
    }
    let r = x.rem_euclid(period);
    // rem_euclid can round up to exactly `period` for tiny negative x.
    if r >= period { 0.0 } else { r }
}

/// [`wrap`] after conversion to f32, where a value just below the period may round up to it.
fn wrap_f32(x: f64, period: f64) -> f32 {
    let r = wrap(x, period) as f32;
    if r >= period as f32 { 0.0 } else { r }
}

/// The full moon's illuminance over the sun's: 0.27 lux against 127,000 lux at the top of the
/// atmosphere (Allen's Astrophysical Quantities).
const FULL_MOON_OVER_SUN: f64 = 2.1e-6;

/// A magnitude-0 star's illuminance over the sun's: 2.54e-6 lux (Vega) against 127,000 lux.
const STAR_MAG0_OVER_SUN: f64 = 2.0e-11;

/// How far auto exposure makes up for less light: the exposure grows as (day / now) to this
/// power (1 would make every hour as bright as noon).
const AUTO_EXPOSURE_ADAPTATION: f64 = 0.75;

/// The unit vector of an elevation and an azimuth clockwise from north, in world axes.
fn direction(elevation_deg: f64, azimuth_deg: f64) -> [f64; 3] {
    let (el, az) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
    [az.sin() * el.cos(), el.sin(), az.cos() * el.cos()]
}

impl Scene {
    /// Unit vector from the scene toward the sun, in world axes (X east, Y up, Z north).
    ///
    /// The real sun's if `[sky]` gives a date and place; else `sun.direction` if it is given
    /// (normalised); else from elevation and azimuth: `(sin az * cos el, sin el, cos az * cos el)`.
    pub fn sun_direction(&self) -> [f64; 3] {
        if let Some((date, place)) = self.sky.when_and_where() {
            let sun = stratus_astro::sun(place, date);
            return direction(sun.elevation_deg, sun.azimuth_deg);
        }
        if let Some(d) = self.sun.direction.and_then(normalize) {
            return d;
        }
        direction(self.sun.elevation_deg, self.sun.azimuth_deg)
    }

    /// The moon when the physical sky has a date and place: its unit direction in world axes
    /// and its illuminated fraction.
    pub fn moon(&self) -> Option<([f64; 3], f64)> {
        if !self.atmosphere.sky.is_physical() {
            return None;
        }
        let (date, place) = self.sky.when_and_where()?;
        let m = stratus_astro::moon(place, date);
        Some((
            direction(m.elevation_deg, m.azimuth_deg),
            stratus_astro::moon_phase(date),
        ))
    }

    /// The light that lights the scene: `(direction, illuminance, is the moon)`. The sun's,
    /// but under the physical sky with a moon, the moon's once the sun is more than 12
    /// degrees below the horizon (nautical twilight's end, when the sky the sun still lights
    /// has faded to about the moonlit sky's brightness). The moon's illuminance is the full
    /// moon's, 2.1e-6 of the sun's (0.27 lux against 127,000 lux), times the phase law of a
    /// Lambertian sphere, (sin a + (pi - a) cos a) / pi at phase angle a.
    pub fn key_light(&self) -> ([f64; 3], [f64; 3], bool) {
        let sun = self.sun_direction();
        if let Some((moon, fraction)) = self.moon()
            && sun[1] < (-12f64).to_radians().sin()
        {
            let a = (2.0 * fraction - 1.0).clamp(-1.0, 1.0).acos();
            let law = (a.sin() + (std::f64::consts::PI - a) * a.cos()) / std::f64::consts::PI;
            let scale = FULL_MOON_OVER_SUN * law.max(0.0);
            return (moon, self.sun.illuminance.map(|e| e * scale), true);
        }
        (sun, self.sun.illuminance, false)
    }

    /// The exposure the uniform block carries: `camera.exposure`, times with
    /// `camera.auto_exposure` the ratio of the light on the ground under a sun 60 degrees
    /// high to this scene's, to the power 0.75 (partial adaptation; at most 10^7). The light on the ground of a key light of zenith
    /// cosine mu is mu T(mu) for the direct beam, T from the air's zenith optical depth and
    /// Kasten and Young's air mass ("Revised optical air mass tables and approximation
    /// formula", Applied Optics 1989), plus a diffuse 0.1 above the horizon falling a decade
    /// every 2.9 degrees below it (twilight: about 400 lux at sunset, 3 lux when the sun is 6
    /// degrees down).
    pub fn auto_exposure(&self) -> f64 {
        let e = self.camera.exposure;
        if !self.camera.auto_exposure {
            return e;
        }
        let (dir, illuminance, _) = self.key_light();
        let luminance = |c: [f64; 3]| 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
        let day = self.ground_light(60f64.to_radians().sin()) * luminance(self.sun.illuminance);
        let now = self.ground_light(dir[1]) * luminance(illuminance);
        // Starlight (about 1e-3 lux, 8e-9 of the sun's) is the floor.
        let floor = 8e-9 * luminance(self.sun.illuminance);
        // Partial adaptation: the eye (and a film) makes up for a dimmer scene only in part,
        // so night stays darker than day (at full adaptation a moonlit scene looks like noon).
        e * (day / now.max(floor))
            .powf(AUTO_EXPOSURE_ADAPTATION)
            .clamp(1e-3, 1e7)
    }

    /// Light on the ground per unit key-light illuminance for a key light of zenith cosine
    /// `mu` (see [`Scene::auto_exposure`]).
    fn ground_light(&self, mu: f64) -> f64 {
        let air = &self.atmosphere.air;
        let tau = [0usize, 1, 2].map(|c| {
            air.rayleigh_scattering[c] * air.rayleigh_scale_height_m
                + (air.mie_scattering + air.mie_absorption) * air.mie_scale_height_m
                + air.ozone_absorption[c] * 0.5 * air.ozone_width_m
        });
        let tau = 0.2126 * tau[0] + 0.7152 * tau[1] + 0.0722 * tau[2];
        let elevation_deg = mu.clamp(-1.0, 1.0).asin().to_degrees();
        let direct = if mu > 0.0 {
            let air_mass = 1.0 / (mu + 0.50572 * (elevation_deg + 6.07995).powf(-1.6364));
            mu * (-tau * air_mass).exp()
        } else {
            0.0
        };
        let diffuse = 0.1 * 10f64.powf(0.35 * elevation_deg.min(0.0));
        direct + diffuse
    }

    /// The sun's elevation above the horizon in degrees, from [`Scene::sun_direction`].
    pub fn sun_elevation_deg(&self) -> f64 {
        self.sun_direction()[1].clamp(-1.0, 1.0).asin().to_degrees()
    }

    /// The camera's unit `(forward, right, up)` vectors in world axes.
    ///
    /// forward = `(sin yaw * cos pitch, sin pitch, cos yaw * cos pitch)`; right =
    /// `(cos yaw, 0, -sin yaw)` (always horizontal, well defined even looking straight up);
    /// up = forward x right. For yaw = pitch = 0 they are +Z, +X and +Y. Algebraically
    /// right x up = forward, like the world's X x Y = Z: the camera frame is the world frame
    /// rotated, and both are left-handed in physical space (X east, Y up, Z north; seed 001),
    /// like Direct3D's view space.
    pub fn camera_basis(&self) -> ([f64; 3], [f64; 3], [f64; 3]) {
        let (yaw, pitch) = (
            self.camera.yaw_deg.to_radians(),
            self.camera.pitch_deg.to_radians(),
        );
        let (sy, cy) = yaw.sin_cos();
        let (sp, cp) = pitch.sin_cos();
        let forward = [sy * cp, sp, cy * cp];
        let right = [cy, 0.0, -sy];
        let up = [-sp * sy, cp, -sp * cy];
        (forward, right, up)
    }

    /// Wind offsets in metres `[x, z]` for the weather map, shape, detail and curl textures.
    ///
    /// Offset = wind direction (unit, toward which the wind blows) * speed * time, computed in
    /// f64 and wrapped into `[0, period)` by each texture's own period, so hours of animation
    /// lose no precision. Cloud features travel with the wind when the shader samples texture
    /// coordinates at `(p.xz - offset) / period`.
    pub fn wind_offsets(&self) -> [[f64; 2]; 4] {
        let c = &self.clouds;
        let (dx, dz) = c.wind_direction_deg.to_radians().sin_cos();
        let distance = c.wind_speed_m_s * c.time_s;
        let (x, z) = (dx * distance, dz * distance);
        [
            c.weather_period_m,
            c.shape_period_m,
            c.detail_period_m,
            c.curl_period_m,
        ]
        .map(|p| [wrap(x, p), wrap(z, p)])
    }

    /// The per-frame uniform block for this scene. Meant for a validated scene; any scene
    /// gives some block without panicking.
    pub fn uniforms(&self) -> FrameUniforms {
        let cam = &self.camera;
        let (forward, right, up) = self.camera_basis();
        let [width, height] = cam.resolution;
        let aspect = f64::from(width) / f64::from(height.max(1));
        let tan_half_fov = (cam.fov_y_deg.to_radians() * 0.5).tan();

        let c = &self.clouds;
        let periods = [
            c.weather_period_m,
            c.shape_period_m,
            c.detail_period_m,
            c.curl_period_m,
        ];
        let (dx, dz) = c.wind_direction_deg.to_radians().sin_cos();
        let distance = c.wind_speed_m_s * c.time_s;
        let offs = periods.map(|p| [wrap_f32(dx * distance, p), wrap_f32(dz * distance, p)]);

        // Extra layer k (from 1) reads the weather map shifted by k (0.382, 0.618) periods
        // (golden-ratio steps, so no two decks line up) on top of the wind.
        let mut extra = [([0.0f32; 4], [0.0f32; 4]); MAX_EXTRA_LAYERS];
        let layers = &c.layers[..c.layers.len().min(MAX_EXTRA_LAYERS)];
        for (k, l) in layers.iter().enumerate() {
            let shift = (k + 1) as f64 * c.weather_period_m;
            let offset = [
                wrap_f32(dx * distance + shift * LAYER_SHIFT[0], c.weather_period_m),
                wrap_f32(dz * distance + shift * LAYER_SHIFT[1], c.weather_period_m),
            ];
            extra[k] = (
                [
                    l.bottom_m as f32,
                    l.top_m as f32,
                    l.coverage as f32,
                    l.density as f32,
                ],
                [
                    l.cloud_type as f32,
                    l.precipitation as f32,
                    offset[0],
                    offset[1],
                ],
            );
        }
        let extra_count = layers.len();

        let atm = &self.atmosphere;
        let li = &self.lighting;
        let ms = &li.multiple_scattering;
        let q = &self.quality;
        let mut flags = 0;
        if li.beer_powder {
            flags |= FrameUniforms::FLAG_BEER_POWDER;
        }
        if q.jitter {
            flags |= FrameUniforms::FLAG_JITTER;
        }
        if q.dynamic_step {
            flags |= FrameUniforms::FLAG_DYNAMIC_STEP;
        }
        if q.checkerboard {
            flags |= FrameUniforms::FLAG_CHECKERBOARD;
        }
        if q.empty_space_skip {
            flags |= FrameUniforms::FLAG_EMPTY_SKIP;
        }
        if atm.sky.is_physical() {
            flags |= FrameUniforms::FLAG_PHYSICAL_SKY;
        }
        let (key_direction, key_illuminance, moonlit) = self.key_light();
        if moonlit {
            flags |= FrameUniforms::FLAG_MOONLIT;
        }
        let sun_luminance = {
            let e = self.sun.illuminance;
            0.2126 * e[0] + 0.7152 * e[1] + 0.0722 * e[2]
        };
        let (moon, star_mag0) = match self.moon() {
            Some((dir, _)) => (
                v4(dir, FULL_MOON_OVER_SUN * sun_luminance),
                STAR_MAG0_OVER_SUN * sun_luminance,
            ),
            None => ([0.0; 4], 0.0),
        };
        let air = &atm.air;

        let block = FrameUniforms {
            camera_position: v4(cam.position, tan_half_fov),
            camera_forward: v4(forward, aspect),
            camera_right: v4(right, self.auto_exposure()),
            camera_up: v4(up, 0.0),
            sun_direction: v4(
                key_direction,
                self.sun.angular_radius_deg.to_radians().cos(),
            ),
            sun_illuminance: v4(key_illuminance, 0.0),
            atmosphere: [
                atm.planet_radius_m as f32,
                atm.cloud_bottom_m as f32,
                atm.cloud_top_m as f32,
                q.cutoff_distance_m as f32,
            ],
            clouds: [
                c.coverage as f32,
                c.density as f32,
                c.cloud_type as f32,
                c.precipitation as f32,
            ],
            erosion: [
                c.detail_strength as f32,
                c.erosion_threshold as f32,
                c.curl_strength_m as f32,
                c.height_gradient as f32,
            ],
            periods: periods.map(|p| p as f32),
            wind_offsets0: [offs[0][0], offs[0][1], offs[1][0], offs[1][1]],
            wind_offsets1: [offs[2][0], offs[2][1], offs[3][0], offs[3][1]],
            extinction: [
                li.scattering as f32,
                li.absorption as f32,
                li.precipitation_darkening as f32,
                c.wispy_billowy as f32,
            ],
            phase: [
                li.phase.g as f32,
                li.phase.g2 as f32,
                li.phase.blend as f32,
                li.powder_strength as f32,
            ],
            multiple_scattering: [ms.a as f32, ms.b as f32, ms.c as f32, ms.buildup_m as f32],
            ambient_bottom: v4(li.ambient_bottom, li.ambient_strength),
            ambient_top: v4(li.ambient_top, 0.0),
            march: [
                q.step_length_m.unwrap_or(0.0) as f32,
                q.light_step_growth as f32,
                q.first_light_step_m as f32,
                q.early_exit_transmittance as f32,
            ],
            counts: [width, height, q.view_steps, q.light_steps],
            modes: [
                li.phase.model.code(),
                q.integration.code(),
                c.height_model.code(),
                flags,
            ],
            misc: [ms.octaves, q.frame, q.path_orders, extra_count as u32],
            previous_position: [0.0; 4],
            previous_forward: [0.0; 4],
            previous_right: [0.0; 4],
            previous_up: [0.0; 4],
            temporal: [q.temporal.divisor(), 0, 0, 0],
            layer1: extra[0].0,
            layer1_weather: extra[0].1,
            layer2: extra[1].0,
            layer2_weather: extra[1].1,
            layer3: extra[2].0,
            layer3_weather: extra[2].1,
            air_rayleigh: v4(air.rayleigh_scattering, air.rayleigh_scale_height_m),
            air_mie: [
                air.mie_scattering as f32,
                air.mie_absorption as f32,
                air.mie_scale_height_m as f32,
                air.mie_g as f32,
            ],
            air_ozone: v4(air.ozone_absorption, air.ozone_center_m),
            air_misc: [
                air.thickness_m as f32,
                air.ozone_width_m as f32,
                air.ground_albedo as f32,
                0.0,
            ],
            moon,
            night: v4(self.sun_direction(), star_mag0),
            light_model: [
                ms.side_light as f32,
                ms.coverage_exponent as f32,
                ms.far_chord_m as f32,
                ms.limb_darkening as f32,
            ],
            octave_direction: [
                ms.forward_lobe as f32,
                ms.forward_lobe_g as f32,
                ms.vertical_anisotropy as f32,
                ms.deck_escape as f32,
            ],
            octave_depth: [
                ms.steep_light as f32,
                ms.steep_light_scale as f32,
                ms.downward_dimming as f32,
                0.0,
            ],
        };
        block.with_previous_camera(&block)
    }
}
