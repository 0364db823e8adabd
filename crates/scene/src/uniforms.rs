//! Geometry derived from a scene (sun direction, camera basis, wind offsets) and the per-frame
//! GPU uniform block.

use crate::scene::{MAX_EXTRA_LAYERS, Scene};

/// Weather-map shift per extra layer, in periods (the golden ratio's fractional parts).
const LAYER_SHIFT: [f64; 2] = [0.381_966, 0.618_034];

/// A lightning flash's illuminance 1 km from it at its peak and `lightning.brightness` 1, in
/// the units of `sun.illuminance`: six times the default noon sun's (10), so that a flash in a
/// daylit storm shows through its rain (chosen by eye, not measured).
const LIGHTNING_ILLUMINANCE: f64 = 60.0;
/// The side of the box of rain or snow particles about the camera (m).
const PRECIP_BOX_M: f64 = 40.0;
/// The share of the clouds' wind that drifts the particles.
const PRECIP_DRIFT: f64 = 0.3;

/// The one declaration of the per-frame uniform block: every member in order, with its kind
/// (`vec4f`: `vec4<f32>`, `vec4u`: `vec4<u32>`) and what it holds. UniformMember `i` lies at byte
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
            /// Camera position: x, altitude, z (m).
            camera_position: vec3f,
            /// tan(fov_y / 2).
            tan_half_fov: f32,
            /// Unit view direction.
            camera_forward: vec3f,
            /// Image width / height.
            aspect: f32,
            /// Unit, image right.
            camera_right: vec3f,
            /// Exposure (`camera.exposure`, times auto exposure's factor).
            exposure: f32,
            /// Unit, image up.
            camera_up: vec3f,
            /// Padding (0).
            _pad0: f32,
            /// Unit vector toward the key light (the sun; the moon under `FLAG_MOONLIT`).
            sun_direction: vec3f,
            /// cos(the sun's angular radius).
            sun_cos_radius: f32,
            /// The key light's illuminance, linear rgb.
            sun_illuminance: vec3f,
            /// Padding (0).
            _pad1: f32,
            /// Planet radius (m).
            planet_radius: f32,
            /// The main cloud layer's bottom (altitude, m).
            cloud_bottom: f32,
            /// The main cloud layer's top (altitude, m).
            cloud_top: f32,
            /// The march's cut-off distance (m).
            cutoff_distance: f32,
            /// The main layer's coverage.
            coverage: f32,
            /// The main layer's density multiplier.
            density: f32,
            /// The main layer's cloud type (`clouds.cloud_type`).
            cloud_type: f32,
            /// The main layer's precipitation.
            precipitation: f32,
            /// Detail-noise strength.
            detail_strength: f32,
            /// Erosion threshold.
            erosion_threshold: f32,
            /// Curl-noise displacement (m).
            curl_strength: f32,
            /// Height-gradient strength.
            height_gradient: f32,
            /// Weather-map period (m).
            weather_period: f32,
            /// Shape-noise period along x (m).
            shape_period: f32,
            /// Detail-noise period (m).
            detail_period: f32,
            /// Curl-noise period (m).
            curl_period: f32,
            /// Weather-map wind offset xz (m, within [0, period)).
            weather_offset: vec2f,
            /// Shape-noise wind offset xz (m, within [0, period)).
            shape_offset: vec2f,
            /// Detail-noise wind offset xz (m, within [0, period)).
            detail_offset: vec2f,
            /// Curl-noise wind offset xz (m, within [0, period)).
            curl_offset: vec2f,
            /// sigma_s (1/m at density 1).
            scattering: f32,
            /// sigma_a (1/m at density 1).
            absorption: f32,
            /// Darkening by precipitation.
            precipitation_darkening: f32,
            /// Wispy (0) to billowy (1) erosion.
            wispy_billowy: f32,
            /// Phase function: the first lobe's g.
            phase_g: f32,
            /// Phase function: the second lobe's g.
            phase_g2: f32,
            /// Phase function: the blend of the two lobes.
            phase_blend: f32,
            /// The powder term's strength.
            powder_strength: f32,
            /// Multiple-scattering octaves: contribution attenuation a per octave.
            ms_contribution: f32,
            /// Multiple-scattering octaves: extinction attenuation b per octave.
            ms_extinction: f32,
            /// Multiple-scattering octaves: eccentricity attenuation c per octave.
            ms_eccentricity: f32,
            /// Multiple-scattering octaves: build-up length (m).
            ms_buildup: f32,
            /// Ambient light at the layer's bottom, linear rgb.
            ambient_bottom: vec3f,
            /// Ambient strength.
            ambient_strength: f32,
            /// Ambient light at the layer's top, linear rgb.
            ambient_top: vec3f,
            /// The share of cumulus standing on the weather map's convective cells.
            convective_cells: f32,
            /// View step length (m; 0 = derive it from `view_steps`).
            step_length: f32,
            /// Growth factor of each light step over the last.
            light_step_growth: f32,
            /// First light step (m).
            first_light_step: f32,
            /// Transmittance below which the view march stops.
            early_exit_transmittance: f32,
            /// Image width and height (pixels).
            size: vec2u,
            /// View steps.
            view_steps: u32,
            /// Light steps.
            light_steps: u32,
            /// [`PhaseModel::code`](crate::PhaseModel::code).
            phase_model: u32,
            /// [`Integration::code`](crate::Integration::code).
            integration: u32,
            /// [`HeightModel::code`](crate::HeightModel::code).
            height_model: u32,
            /// `FLAG_*` bits ([`FrameUniforms::FLAG_BEER_POWDER`], ...).
            flags: u32,
            /// Multiple-scattering octaves beyond single scattering.
            octaves: u32,
            /// Frame index: the jitter seed and the path tracer's random streams.
            frame_index: u32,
            /// The path tracer's scattering orders (0 = all).
            path_orders: u32,
            /// Extra cloud layers (0-3).
            extra_layers: u32,
            /// Last frame's camera position: temporal upsampling reprojects through last frame's
            /// camera. [`Scene::uniforms`] sets the current camera; a renderer that keeps history
            /// replaces it with the one it rendered last.
            previous_position: vec3f,
            /// Last frame's tan(fov_y / 2).
            previous_tan_half_fov: f32,
            /// Last frame's unit view direction.
            previous_forward: vec3f,
            /// Last frame's width / height.
            previous_aspect: f32,
            /// Last frame's unit image right.
            previous_right: vec3f,
            /// Last frame's exposure (a change of exposure, like a move, ends the history's exact
            /// reuse).
            previous_exposure: f32,
            /// Last frame's unit image up.
            previous_up: vec3f,
            /// Padding (0).
            _pad4: f32,
            /// Temporal upsampling's block side (1 = off, 2 = 1/4, 4 = 1/16).
            block_side: u32,
            /// 1 when the history holds a frame to reproject (the renderer sets it), else 0.
            history_valid: u32,
            /// Padding (0).
            _pad5: u32,
            /// Padding (0).
            _pad6: u32,
            /// Extra cloud layer 1 (`clouds.layers[0]`; zero when absent): bottom (altitude, m).
            layer1_bottom: f32,
            /// Extra cloud layer 1: top (altitude, m).
            layer1_top: f32,
            /// Extra cloud layer 1: coverage.
            layer1_coverage: f32,
            /// Extra cloud layer 1: density multiplier.
            layer1_density: f32,
            /// Extra cloud layer 1: cloud type.
            layer1_cloud_type: f32,
            /// Extra cloud layer 1: precipitation.
            layer1_precipitation: f32,
            /// Extra cloud layer 1: weather-map offset xz (m, within [0, period)).
            layer1_weather_offset: vec2f,
            /// Extra cloud layer 2 (`clouds.layers[1]`; zero when absent): bottom (altitude, m).
            layer2_bottom: f32,
            /// Extra cloud layer 2: top (altitude, m).
            layer2_top: f32,
            /// Extra cloud layer 2: coverage.
            layer2_coverage: f32,
            /// Extra cloud layer 2: density multiplier.
            layer2_density: f32,
            /// Extra cloud layer 2: cloud type.
            layer2_cloud_type: f32,
            /// Extra cloud layer 2: precipitation.
            layer2_precipitation: f32,
            /// Extra cloud layer 2: weather-map offset xz (m, within [0, period)).
            layer2_weather_offset: vec2f,
            /// Extra cloud layer 3 (`clouds.layers[2]`; zero when absent): bottom (altitude, m).
            layer3_bottom: f32,
            /// Extra cloud layer 3: top (altitude, m).
            layer3_top: f32,
            /// Extra cloud layer 3: coverage.
            layer3_coverage: f32,
            /// Extra cloud layer 3: density multiplier.
            layer3_density: f32,
            /// Extra cloud layer 3: cloud type.
            layer3_cloud_type: f32,
            /// Extra cloud layer 3: precipitation.
            layer3_precipitation: f32,
            /// Extra cloud layer 3: weather-map offset xz (m, within [0, period)).
            layer3_weather_offset: vec2f,
            /// The physical sky's air: Rayleigh scattering at the ground (rgb, 1/m).
            rayleigh_scattering: vec3f,
            /// Rayleigh scale height (m).
            rayleigh_scale_height: f32,
            /// Mie scattering at the ground (1/m).
            mie_scattering: f32,
            /// Mie absorption at the ground (1/m).
            mie_absorption: f32,
            /// Mie scale height (m).
            mie_scale_height: f32,
            /// Mie phase asymmetry g.
            mie_g: f32,
            /// Ozone absorption at its peak (rgb, 1/m).
            ozone_absorption: vec3f,
            /// The ozone peak's altitude (m).
            ozone_center: f32,
            /// Thickness of the atmosphere (m).
            air_thickness: f32,
            /// The ozone tent's full width (m).
            ozone_width: f32,
            /// The ground's albedo.
            ground_albedo: f32,
            /// Padding (0).
            _pad7: f32,
            /// Unit vector toward the moon (physical sky with a date and place). Its phase follows
            /// from its direction and the real sun's.
            moon_direction: vec3f,
            /// The full moon's illuminance (luminance, in the units of `sun_illuminance`; 0 without
            /// a moon).
            moon_illuminance: f32,
            /// The real sun's unit direction (the moon's lit side faces it; `sun_direction` is the
            /// moon's when it is the key light).
            real_sun_direction: vec3f,
            /// The illuminance of a magnitude-0 star, in the units of `sun_illuminance` (0: no
            /// stars).
            star_illuminance: f32,
            /// Fitted light model (`MultipleScattering`): side light.
            side_light: f32,
            /// Fitted light model: coverage exponent.
            coverage_exponent: f32,
            /// Fitted light model: far-shadow chord (m, 0 = off).
            far_chord: f32,
            /// Fitted light model: limb darkening.
            limb_darkening: f32,
            /// The octaves' forward lobe through thin cloud: strength (0 = off).
            forward_lobe: f32,
            /// The octaves' forward lobe: eccentricity.
            forward_lobe_g: f32,
            /// The octaves' vertical anisotropy (0 = off).
            vertical_anisotropy: f32,
            /// The octaves' escape from a deck (0 = off).
            deck_escape: f32,
            /// The octaves' optical depth in a closed deck: the column's weight (0 = off).
            steep_light: f32,
            /// The octaves' optical depth in a closed deck: its scale.
            steep_light_scale: f32,
            /// The octaves' dimming looking down (0 = off).
            downward_dimming: f32,
            /// Padding (0).
            _pad8: f32,
            /// The host's scene depth (`FLAG_SCENE_DEPTH`): its projection's term A. A
            /// depth d lies at distance B / (d + A) along the view axis (m).
            scene_depth_a: f32,
            /// The scene depth's projection term B.
            scene_depth_b: f32,
            /// The scene depth of a pixel without geometry (the far plane's: 1 standard, 0
            /// reversed Z).
            scene_depth_clear: f32,
            /// Saturation of the display image (`post.saturation`; 1 leaves it).
            saturation: f32,
            /// The Kuwahara filter's window radius, a fraction of the image's height
            /// (`post.kuwahara_radius`; 0 without the filter).
            kuwahara_radius: f32,
            /// The rainbow's moisture (`rainbow.moisture`; 0: no rainbow).
            rainbow_moisture: f32,
            /// The raindrops' radius (m).
            rainbow_drop_radius: f32,
            /// The lens flare's strength (`post.lens_flare_intensity`; 0: none).
            lens_flare_intensity: f32,
            /// The world direction of the J2000 equinox (the star catalogue's x axis) at the
            /// scene's date and place (0 without them).
            celestial_x: vec3f,
            /// The stars' least Gaussian deviation (`night.star_min_radius_px`, pixels).
            star_min_radius: f32,
            /// The world direction of the J2000 catalogue's y axis (right ascension 6 h on
            /// the equator).
            celestial_y: vec3f,
            /// The stars' growth with brightness (`night.star_radius_scale`, pixels).
            star_radius_scale: f32,
            /// The world direction of the J2000 north celestial pole.
            celestial_z: vec3f,
            /// The bright stars' glare (`night.star_glare_scale`).
            star_glare_scale: f32,
            /// The Milky Way's brightness (`night.milky_way_intensity`).
            milky_way_intensity: f32,
            /// cos(the moon's angular radius), `night.moon_size` applied.
            moon_cos_radius: f32,
            /// The stars' brightness over the real sky's (`night.star_intensity`).
            star_intensity: f32,
            /// The rain shafts' extinction in units of heavy rain's (`precipitation.shafts`; 0:
            /// none).
            rain_shafts: f32,
            /// The lit flash's place (world metres: x, altitude, z; [`crate::lightning`]).
            lightning_position: vec3f,
            /// The lit flash's illuminance 1 km from it, in the units of `sun_illuminance` (0:
            /// no flash this frame).
            lightning_illuminance: f32,
            /// How far the particles have fallen and drifted (m, each within [0,
            /// `precip_box`)): they move with it through the box about the camera.
            precip_offset: vec3f,
            /// The particles' share drawn (`precipitation.particles`; 0: none).
            precip_density: f32,
            /// The particles' velocity (m/s): their fall and the wind's drift.
            precip_velocity: vec3f,
            /// The side of the box of particles about the camera (m).
            precip_box: f32,
            /// Where a cumulonimbus anvil's top lies downwind of its tower (xz, m at the
            /// layer's top; `clouds.anvil_shear_m` along the wind's direction).
            anvil_shear: vec2f,
            /// Cumulonimbus anvils on cumulus layers, within [0, 1] (`clouds.anvil`; 0: none).
            anvil: f32,
            /// Padding (0).
            _pad9: f32,
            /// The main layer's cirrus share, within [0, 1] (`clouds.cirrus`).
            cirrus: f32,
            /// Extra layer 1's cirrus share (`[[clouds.layers]] cirrus`; 0 where there is
            /// no such layer).
            layer1_cirrus: f32,
            /// Extra layer 2's cirrus share.
            layer2_cirrus: f32,
            /// Extra layer 3's cirrus share.
            layer3_cirrus: f32,
            /// The wind's direction (unit xz, toward which it blows): cirrus fibres lie along
            /// it.
            wind_direction: vec2f,
            /// How far the wind has carried the cirrus strands along itself (m), wrapped by
            /// their period along it (CIRRUS_STRETCH * CIRRUS_SCALE shape periods): the shape
            /// offset wraps per axis, which in the wind's stretched frame is no period.
            cirrus_strand_offset: f32,
            /// How far the wind has carried the cirrus fibres along itself (m), wrapped by
            /// CIRRUS_FIBRE_STRETCH detail periods.
            cirrus_fibre_offset: f32,
            /// The wind's offset of the curl noise bending cirrus strands (xz, m), wrapped per
            /// axis by CIRRUS_BEND_SCALE curl periods, the period it is read at.
            cirrus_bend_offset: vec2f,
            /// How many times longer along the wind than across cellular layers' cells are
            /// (1 to CELLULAR_ROLL, from `clouds.cell_rolls`).
            cellular_stretch: f32,
            /// How far the wind has carried the cellular layers' cells along itself (m),
            /// wrapped by `cellular_stretch` shape periods: whole periods of every layer's
            /// read, whose period is the shape's over a power of two.
            cellular_offset: f32,
            /// The main layer's cellular share, within [0, 1] (`clouds.cellular`).
            cellular: f32,
            /// Extra layer 1's cellular share (`[[clouds.layers]] cellular`; 0 where there
            /// is no such layer).
            layer1_cellular: f32,
            /// Extra layer 2's cellular share.
            layer2_cellular: f32,
            /// Extra layer 3's cellular share.
            layer3_cellular: f32,
            /// Close-range detail's strength, within [0, 1] (`clouds.close_detail`; 0: off).
            close_detail: f32,
            /// How many times finer than the detail noise close-range detail reads it (an
            /// integer, `clouds.close_detail_scale`).
            close_detail_scale: f32,
            /// How far from the camera close-range detail reaches (m,
            /// `clouds.close_detail_range_m`).
            close_detail_range: f32,
            /// The march's step within that range (m, `quality.close_step_m`).
            close_step: f32,
        }
    };
}

/// The Rust type of a member kind.
macro_rules! member_type {
    (f32) => {
        f32
    };
    (u32) => {
        u32
    };
    (vec2f) => {
        [f32; 2]
    };
    (vec2u) => {
        [u32; 2]
    };
    (vec3f) => {
        [f32; 3]
    };
}

/// The WGSL type of a member kind, and its alignment under WGSL's uniform rules (std140's
/// and HLSL's packing agree for these members: none crosses a 16-byte row).
macro_rules! member_wgsl {
    (f32) => {
        ("f32", 4)
    };
    (u32) => {
        ("u32", 4)
    };
    (vec2f) => {
        ("vec2<f32>", 8)
    };
    (vec2u) => {
        ("vec2<u32>", 8)
    };
    (vec3f) => {
        ("vec3<f32>", 16)
    };
}

/// One member of the uniform block: its name, WGSL type, byte offset and size.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct UniformMember {
    /// The member's name, the same in Rust, WGSL and the engine kit's `uniforms.h`.
    pub name: &'static str,
    /// Its WGSL type (`f32`, `u32`, `vec2<f32>`, `vec2<u32>`, `vec3<f32>`).
    pub wgsl: &'static str,
    /// Its byte offset in the block.
    pub offset: usize,
    /// Its size in bytes.
    pub size: usize,
}

impl UniformMember {
    /// Whether the member holds u32s (else f32s).
    pub fn is_unsigned(&self) -> bool {
        self.wgsl.contains("u32")
    }

    /// How many scalars it holds (1 to 3).
    pub fn components(&self) -> usize {
        self.size / 4
    }
}

/// Per-frame uniforms, std140/WGSL-uniform compatible, as [`frame_members!`] declares them.
macro_rules! frame_uniforms {
    ($( $(#[doc = $doc:literal])* $name:ident : $kind:ident, )*) => {
        /// Per-frame uniforms, std140/WGSL-uniform compatible, as
        /// [`frame_members!`](crate::frame_members) declares them: scalars, vec2s and vec3s
        /// laid out so that Rust's `repr(C)` puts each where WGSL's uniform rules do (a const
        /// check below holds every member to its WGSL alignment).
        ///
        /// The WGSL's `struct Frame` is generated from the same declaration
        /// ([`FrameUniforms::wgsl`]). Build it with [`Scene::uniforms`].
        #[repr(C)]
        #[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
        pub struct FrameUniforms {
            $( $(#[doc = $doc])* pub $name: member_type!($kind), )*
        }

        impl FrameUniforms {
            /// Every member in declaration order: name, WGSL type, offset and size. The
            /// shader-reflection test compares the WGSL struct against this list.
            pub const MEMBERS: &'static [UniformMember] = &[$( UniformMember {
                name: stringify!($name),
                wgsl: member_wgsl!($kind).0,
                offset: std::mem::offset_of!(FrameUniforms, $name),
                size: std::mem::size_of::<member_type!($kind)>(),
            } ),*];

            /// What each member holds (its doc comment), in declaration order.
            const DOCS: &'static [&'static [&'static str]] = &[$( &[$($doc),*] ),*];

            /// Each member's WGSL alignment, in declaration order.
            const ALIGN: &'static [usize] = &[$( member_wgsl!($kind).1 ),*];
        }
    };
}

frame_members!(frame_uniforms);

// Rust's repr(C) packs the members back to back (4-byte alignment); WGSL aligns a vec3 to 16
// bytes and a vec2 to 8. They agree when every member starts on its WGSL alignment and the
// block is whole rows, which the declaration must keep (padding members fill the gaps).
const _: () = {
    let mut i = 0;
    while i < FrameUniforms::MEMBERS.len() {
        assert!(
            FrameUniforms::MEMBERS[i]
                .offset
                .is_multiple_of(FrameUniforms::ALIGN[i]),
            "a uniform member starts off its WGSL alignment: add padding before it"
        );
        i += 1;
    }
    assert!(std::mem::size_of::<FrameUniforms>().is_multiple_of(16));
};

impl FrameUniforms {
    /// Size of the block in bytes.
    pub const SIZE: usize = std::mem::size_of::<Self>();

    /// `flags` bit: apply the Beer-Powder term.
    pub const FLAG_BEER_POWDER: u32 = 1 << 0;
    /// `flags` bit: jitter the view-ray start offset per pixel.
    pub const FLAG_JITTER: u32 = 1 << 1;
    /// `flags` bit: dynamic step length (double after 8 empty samples).
    pub const FLAG_DYNAMIC_STEP: u32 = 1 << 2;
    /// `flags` bit: high-transmittance checkerboard skipping (temporal only).
    pub const FLAG_CHECKERBOARD: u32 = 1 << 3;
    /// `flags` bit: empty-space skipping over the weather map's occupancy grid.
    pub const FLAG_EMPTY_SKIP: u32 = 1 << 4;
    /// `flags` bit: the physical sky (`atmosphere.sky = "physical"`).
    pub const FLAG_PHYSICAL_SKY: u32 = 1 << 5;
    /// `flags` bit: the moon is the key light (`sun_direction`, `sun_illuminance`).
    pub const FLAG_MOONLIT: u32 = 1 << 6;
    /// `flags` bit: the host's scene depth is bound; the march stops at its surfaces.
    pub const FLAG_SCENE_DEPTH: u32 = 1 << 7;
    /// `flags` bit: the HDR output carries the sky behind the clouds where the host has no
    /// geometry (the host flag `sky`).
    pub const FLAG_HDR_SKY: u32 = 1 << 8;
    /// `flags` bit: light shafts, the clouds' shadows in the air
    /// (`atmosphere.light_shafts`).
    pub const FLAG_LIGHT_SHAFTS: u32 = 1 << 9;
    /// `flags` bit: the rainbow from the Lee-diagram table (`rainbow.lee_diagram`), else the
    /// cheap three-wavelength path.
    pub const FLAG_LEE_DIAGRAM: u32 = 1 << 10;
    /// `flags` bit: the moon's disc sampled at four points a pixel (`night.moon_msaa`), else
    /// its limb spread over a pixel.
    pub const FLAG_MOON_MSAA: u32 = 1 << 11;
    /// `flags` bit: the particles are snowflakes (`precipitation.kind = "snow"`), else rain.
    pub const FLAG_SNOW: u32 = 1 << 12;

    /// The WGSL `struct Frame` of this block, as `wgsl/frame.wgsl` holds it (written by
    /// `cargo xtask build-shaders`, which fails `--check` when the file differs).
    pub fn wgsl() -> String {
        let mut out = String::from(
            "// Generated from crates/scene/src/uniforms.rs (`frame_members!`) by `cargo xtask\n\
             // build-shaders`; edit the declaration there, not this file.\n//\n\
             // The per-frame uniform block. No member crosses a 16-byte row, so the layout is the\n\
             // same under WGSL, std140 and HLSL cbuffer rules.\n\nstruct Frame {\n",
        );
        for (member, doc) in Self::MEMBERS.iter().zip(Self::DOCS) {
            for line in doc.iter() {
                let line = line.trim();
                if line.is_empty() {
                    out.push_str("    //\n");
                } else {
                    out.push_str(&format!("    // {line}\n"));
                }
            }
            out.push_str(&format!("    {}: {},\n", member.name, member.wgsl));
        }
        out.push_str("}\n");
        out
    }

    /// This block with `previous`'s camera as last frame's camera (what a renderer keeping
    /// history does before uploading).
    pub fn with_previous_camera(mut self, previous: &FrameUniforms) -> Self {
        self.previous_position = previous.camera_position;
        self.previous_tan_half_fov = previous.tan_half_fov;
        self.previous_forward = previous.camera_forward;
        self.previous_aspect = previous.aspect;
        self.previous_right = previous.camera_right;
        self.previous_exposure = previous.exposure;
        self.previous_up = previous.camera_up;
        self
    }

    /// The block's bytes, ready to upload.
    pub fn as_bytes(&self) -> &[u8] {
        bytemuck::bytes_of(self)
    }
}

fn v3(v: [f64; 3]) -> [f32; 3] {
    v.map(|x| x as f32)
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

// WGSL: density.wgsl::CIRRUS_STRETCH, CIRRUS_SCALE, CIRRUS_FIBRE_STRETCH, CIRRUS_BEND_SCALE
/// How cirrus reads its noise (see `cirrus_density` in wgsl/density.wgsl): the strands' shape
/// noise CIRRUS_STRETCH times longer along the wind at CIRRUS_SCALE of its period, the fibres'
/// detail noise CIRRUS_FIBRE_STRETCH times longer, the bends' curl noise at CIRRUS_BEND_SCALE
/// times its period. The wind offsets of those reads wrap by those periods.
const CIRRUS_STRETCH: f64 = 16.0;
/// See [`CIRRUS_STRETCH`].
const CIRRUS_SCALE: f64 = 0.5;
/// See [`CIRRUS_STRETCH`].
const CIRRUS_FIBRE_STRETCH: f64 = 30.0;
/// See [`CIRRUS_STRETCH`].
const CIRRUS_BEND_SCALE: f64 = 4.0;

/// The full moon's illuminance over the sun's: 0.27 lux against 127,000 lux at the top of the
/// atmosphere (Allen's Astrophysical Quantities).
const FULL_MOON_OVER_SUN: f64 = 2.1e-6;

/// A magnitude-0 star's illuminance over the sun's: 2.54e-6 lux (Vega) against 127,000 lux.
const STAR_MAG0_OVER_SUN: f64 = 2.0e-11;
/// cos(the moon's mean angular radius, 0.259 degrees).
const MOON_COS_RADIUS: f64 = 0.999_989_78;

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

    /// The exposure the uniform block carries, within `camera.exposure_range` when given:
    /// `camera.exposure`, times with
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
            return self.bound_exposure(e);
        }
        let (dir, illuminance, _) = self.key_light();
        let luminance = |c: [f64; 3]| 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
        let day = self.ground_light(60f64.to_radians().sin()) * luminance(self.sun.illuminance);
        let now = self.ground_light(dir[1]) * luminance(illuminance);
        // Starlight (about 1e-3 lux, 8e-9 of the sun's) is the floor.
        let floor = 8e-9 * luminance(self.sun.illuminance);
        // Partial adaptation: the eye (and a film) makes up for a dimmer scene only in part,
        // so night stays darker than day (at full adaptation a moonlit scene looks like noon).
        self.bound_exposure(
            e * (day / now.max(floor))
                .powf(AUTO_EXPOSURE_ADAPTATION)
                .clamp(1e-3, 1e7),
        )
    }

    /// `exposure` within `camera.exposure_range` when one is given (max then min, not
    /// `clamp`, which panics on a range validation would refuse: a host may ask an
    /// unvalidated scene).
    fn bound_exposure(&self, exposure: f64) -> f64 {
        match self.camera.exposure_range {
            Some([lo, hi]) => exposure.max(lo).min(hi),
            None => exposure,
        }
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

    /// The camera's unit `(forward, right, up)` vectors in world axes: `camera.orientation`'s
    /// when given, else from yaw and pitch:
    ///
    /// forward = `(sin yaw * cos pitch, sin pitch, cos yaw * cos pitch)`; right =
    /// `(cos yaw, 0, -sin yaw)` (always horizontal, well defined even looking straight up);
    /// up = forward x right. For yaw = pitch = 0 they are +Z, +X and +Y. Algebraically
    /// right x up = forward, like the world's X x Y = Z: the camera frame is the world frame
    /// rotated, and both are left-handed in physical space (X east, Y up, Z north; seed 001),
    /// like Direct3D's view space.
    pub fn camera_basis(&self) -> ([f64; 3], [f64; 3], [f64; 3]) {
        if let Some(o) = &self.camera.orientation {
            return (o.forward, o.right, o.up);
        }
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
        let cellular_stretch = 1.0 + (crate::CELLULAR_ROLL - 1.0) * c.cell_rolls.clamp(0.0, 1.0);

        // Extra layer k (from 1) reads the weather map shifted by k (0.382, 0.618) periods
        // (golden-ratio steps, so no two decks line up) on top of the wind.
        let mut extra = [([0.0f32; 6], [0.0f32; 2]); MAX_EXTRA_LAYERS];
        let layers = &c.layers[..c.layers.len().min(MAX_EXTRA_LAYERS)];
        for (k, l) in layers.iter().enumerate() {
            let shift = (k + 1) as f64 * c.weather_period_m;
            let offset = [
                wrap_f32(dx * distance + shift * LAYER_SHIFT[0], c.weather_period_m),
                wrap_f32(dz * distance + shift * LAYER_SHIFT[1], c.weather_period_m),
            ];
            extra[k] = (
                [
                    l.bottom_m,
                    l.top_m,
                    l.coverage,
                    l.density,
                    l.cloud_type,
                    l.precipitation,
                ]
                .map(|v| v as f32),
                offset,
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
        if atm.light_shafts {
            flags |= FrameUniforms::FLAG_LIGHT_SHAFTS;
        }
        if self.rainbow.uses_table() {
            flags |= FrameUniforms::FLAG_LEE_DIAGRAM;
        }
        if self.night.moon_msaa {
            flags |= FrameUniforms::FLAG_MOON_MSAA;
        }
        if self.precipitation.kind == crate::PrecipitationKind::Snow {
            flags |= FrameUniforms::FLAG_SNOW;
        }
        let flash = crate::lightning::flash(self);
        // The particles fall at their kind's speed and drift with a share of the wind (the
        // wind near the ground is weaker than the clouds'); their offsets wrap in f64, so
        // hours of rain lose no precision.
        let precip_velocity = [
            dx * c.wind_speed_m_s * PRECIP_DRIFT,
            -self.precipitation.kind.fall_speed_m_s(),
            dz * c.wind_speed_m_s * PRECIP_DRIFT,
        ];
        let precip_offset = precip_velocity.map(|v| (v * c.time_s).rem_euclid(PRECIP_BOX_M));
        // The catalogue's axes in the world: from the date and place (none without them).
        let celestial = match self.sky.when_and_where() {
            Some((date, place)) => stratus_astro::celestial::transpose(
                &stratus_astro::celestial::equatorial_to_world(place, date),
            ),
            None => [[0.0; 3]; 3],
        };
        let (key_direction, key_illuminance, moonlit) = self.key_light();
        if moonlit {
            flags |= FrameUniforms::FLAG_MOONLIT;
        }
        let sun_luminance = {
            let e = self.sun.illuminance;
            0.2126 * e[0] + 0.7152 * e[1] + 0.0722 * e[2]
        };
        let (moon_direction, moon_illuminance, star_mag0) = match self.moon() {
            Some((dir, _)) => (
                dir,
                FULL_MOON_OVER_SUN * sun_luminance,
                STAR_MAG0_OVER_SUN * sun_luminance,
            ),
            None => ([0.0; 3], 0.0, 0.0),
        };
        let air = &atm.air;
        let [
            [
                layer1_bottom,
                layer1_top,
                layer1_coverage,
                layer1_density,
                layer1_cloud_type,
                layer1_precipitation,
            ],
            [
                layer2_bottom,
                layer2_top,
                layer2_coverage,
                layer2_density,
                layer2_cloud_type,
                layer2_precipitation,
            ],
            [
                layer3_bottom,
                layer3_top,
                layer3_coverage,
                layer3_density,
                layer3_cloud_type,
                layer3_precipitation,
            ],
        ] = extra.map(|(l, _)| l);
        let f = |v: f64| v as f32;

        let block = FrameUniforms {
            camera_position: v3(cam.position),
            tan_half_fov: f(tan_half_fov),
            camera_forward: v3(forward),
            aspect: f(aspect),
            camera_right: v3(right),
            exposure: f(self.auto_exposure()),
            camera_up: v3(up),
            _pad0: 0.0,
            sun_direction: v3(key_direction),
            sun_cos_radius: f(self.sun.angular_radius_deg.to_radians().cos()),
            sun_illuminance: v3(key_illuminance),
            _pad1: 0.0,
            planet_radius: f(atm.planet_radius_m),
            cloud_bottom: f(atm.cloud_bottom_m),
            cloud_top: f(atm.cloud_top_m),
            cutoff_distance: f(q.cutoff_distance_m),
            coverage: f(c.coverage),
            density: f(c.density),
            cloud_type: f(c.cloud_type),
            precipitation: f(c.precipitation),
            detail_strength: f(c.detail_strength),
            erosion_threshold: f(c.erosion_threshold),
            curl_strength: f(c.curl_strength_m),
            height_gradient: f(c.height_gradient),
            weather_period: f(periods[0]),
            shape_period: f(periods[1]),
            detail_period: f(periods[2]),
            curl_period: f(periods[3]),
            weather_offset: offs[0],
            shape_offset: offs[1],
            detail_offset: offs[2],
            curl_offset: offs[3],
            scattering: f(li.scattering),
            absorption: f(li.absorption),
            precipitation_darkening: f(li.precipitation_darkening),
            wispy_billowy: f(c.wispy_billowy),
            phase_g: f(li.phase.g),
            phase_g2: f(li.phase.g2),
            phase_blend: f(li.phase.blend),
            powder_strength: f(li.powder_strength),
            ms_contribution: f(ms.a),
            ms_extinction: f(ms.b),
            ms_eccentricity: f(ms.c),
            ms_buildup: f(ms.buildup_m),
            ambient_bottom: v3(li.ambient_bottom),
            ambient_strength: f(li.ambient_strength),
            ambient_top: v3(li.ambient_top),
            convective_cells: f(c.convective_cells),
            step_length: f(q.step_length_m.unwrap_or(0.0)),
            light_step_growth: f(q.light_step_growth),
            first_light_step: f(q.first_light_step_m),
            early_exit_transmittance: f(q.early_exit_transmittance),
            size: [width, height],
            view_steps: q.view_steps,
            light_steps: q.light_steps,
            phase_model: li.phase.model.code(),
            integration: q.integration.code(),
            height_model: c.height_model.code(),
            flags,
            octaves: ms.octaves,
            frame_index: q.frame,
            path_orders: q.path_orders,
            extra_layers: extra_count as u32,
            previous_position: [0.0; 3],
            previous_tan_half_fov: 0.0,
            previous_forward: [0.0; 3],
            previous_aspect: 0.0,
            previous_right: [0.0; 3],
            previous_exposure: 0.0,
            previous_up: [0.0; 3],
            _pad4: 0.0,
            block_side: q.temporal.divisor(),
            history_valid: 0,
            _pad5: 0,
            _pad6: 0,
            layer1_bottom,
            layer1_top,
            layer1_coverage,
            layer1_density,
            layer1_cloud_type,
            layer1_precipitation,
            layer1_weather_offset: extra[0].1,
            layer2_bottom,
            layer2_top,
            layer2_coverage,
            layer2_density,
            layer2_cloud_type,
            layer2_precipitation,
            layer2_weather_offset: extra[1].1,
            layer3_bottom,
            layer3_top,
            layer3_coverage,
            layer3_density,
            layer3_cloud_type,
            layer3_precipitation,
            layer3_weather_offset: extra[2].1,
            rayleigh_scattering: v3(air.rayleigh_scattering),
            rayleigh_scale_height: f(air.rayleigh_scale_height_m),
            mie_scattering: f(air.mie_scattering),
            mie_absorption: f(air.mie_absorption),
            mie_scale_height: f(air.mie_scale_height_m),
            mie_g: f(air.mie_g),
            ozone_absorption: v3(air.ozone_absorption),
            ozone_center: f(air.ozone_center_m),
            air_thickness: f(air.thickness_m),
            ozone_width: f(air.ozone_width_m),
            ground_albedo: f(air.ground_albedo),
            _pad7: 0.0,
            moon_direction: v3(moon_direction),
            moon_illuminance: f(moon_illuminance),
            real_sun_direction: v3(self.sun_direction()),
            star_illuminance: f(star_mag0),
            side_light: f(ms.side_light),
            coverage_exponent: f(ms.coverage_exponent),
            far_chord: f(ms.far_chord_m),
            limb_darkening: f(ms.limb_darkening),
            forward_lobe: f(ms.forward_lobe),
            forward_lobe_g: f(ms.forward_lobe_g),
            vertical_anisotropy: f(ms.vertical_anisotropy),
            deck_escape: f(ms.deck_escape),
            steep_light: f(ms.steep_light),
            steep_light_scale: f(ms.steep_light_scale),
            downward_dimming: f(ms.downward_dimming),
            _pad8: 0.0,
            scene_depth_a: 0.0,
            scene_depth_b: 0.0,
            scene_depth_clear: 0.0,
            saturation: f(self.post.saturation),
            kuwahara_radius: if self.post.kuwahara {
                f(self.post.kuwahara_radius)
            } else {
                0.0
            },
            rainbow_moisture: f(self.rainbow.moisture),
            rainbow_drop_radius: f(self.rainbow.drop_radius_um * 1e-6),
            lens_flare_intensity: f(self.post.lens_flare_intensity),
            celestial_x: v3(celestial[0]),
            star_min_radius: f(self.night.star_min_radius_px),
            celestial_y: v3(celestial[1]),
            star_radius_scale: f(self.night.star_radius_scale),
            celestial_z: v3(celestial[2]),
            star_glare_scale: f(self.night.star_glare_scale),
            milky_way_intensity: f(self.night.milky_way_intensity),
            moon_cos_radius: f((MOON_COS_RADIUS.acos() * self.night.moon_size).cos()),
            star_intensity: f(self.night.star_intensity),
            rain_shafts: f(self.precipitation.shafts),
            lightning_position: v3(flash.map_or([0.0; 3], |f| f.position)),
            lightning_illuminance: f(flash.map_or(0.0, |f| {
                f.intensity * self.lightning.brightness * LIGHTNING_ILLUMINANCE
            })),
            precip_offset: v3(precip_offset),
            precip_density: f(self.precipitation.particles),
            precip_velocity: v3(precip_velocity),
            precip_box: f(PRECIP_BOX_M),
            anvil_shear: [f(dx * c.anvil_shear_m), f(dz * c.anvil_shear_m)],
            anvil: f(c.anvil),
            _pad9: 0.0,
            cirrus: f(c.cirrus),
            layer1_cirrus: f(layers.first().map_or(0.0, |l| l.cirrus)),
            layer2_cirrus: f(layers.get(1).map_or(0.0, |l| l.cirrus)),
            layer3_cirrus: f(layers.get(2).map_or(0.0, |l| l.cirrus)),
            wind_direction: [f(dx), f(dz)],
            cirrus_strand_offset: wrap_f32(
                distance,
                CIRRUS_STRETCH * CIRRUS_SCALE * c.shape_period_m,
            ),
            cirrus_fibre_offset: wrap_f32(distance, CIRRUS_FIBRE_STRETCH * c.detail_period_m),
            cirrus_bend_offset: [
                wrap_f32(dx * distance, CIRRUS_BEND_SCALE * c.curl_period_m),
                wrap_f32(dz * distance, CIRRUS_BEND_SCALE * c.curl_period_m),
            ],
            cellular_stretch: f(cellular_stretch),
            cellular_offset: wrap_f32(distance, cellular_stretch * c.shape_period_m),
            cellular: f(c.cellular),
            layer1_cellular: f(layers.first().map_or(0.0, |l| l.cellular)),
            layer2_cellular: f(layers.get(1).map_or(0.0, |l| l.cellular)),
            layer3_cellular: f(layers.get(2).map_or(0.0, |l| l.cellular)),
            close_detail: f(c.close_detail),
            close_detail_scale: c.close_detail_scale as f32,
            close_detail_range: f(c.close_detail_range_m),
            close_step: f(q.close_step_m),
        };
        block.with_previous_camera(&block)
    }
}
