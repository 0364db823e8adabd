//! The scene description: plain data, serde-derived, one struct per TOML section.
//!
//! Every field has a default; the defaults are the `cumulus-noon` preset. Angles are in degrees,
//! lengths in metres, times in seconds, colours in linear RGB.

use serde::{Deserialize, Serialize};

/// A complete scene: everything one frame of the cloud renderer needs.
///
/// Coordinate system (seed 001): X points east, Y up, Z north, in metres. The world origin lies
/// on the ground (altitude 0) below the camera's x/z = 0; positions are `[x, altitude, z]`.
/// Load one with [`Scene::from_toml_str`], [`Scene::from_file`] or [`Scene::preset`]; the
/// [`Default`] scene is the `cumulus-noon` preset.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq, Default)]
#[serde(default, deny_unknown_fields)]
pub struct Scene {
    /// Viewpoint, orientation, image size and exposure.
    pub camera: Camera,
    /// The sun: direction, colour and size.
    pub sun: Sun,
    /// Date, time and place: when given, the sun's direction comes from astronomy.
    #[serde(skip_serializing_if = "Sky::is_unset")]
    pub sky: Sky,
    /// Planet and the spherical shell that holds the clouds.
    pub atmosphere: Atmosphere,
    /// The cloud model: coverage, type, wind, noise scales and erosion.
    pub clouds: Clouds,
    /// Procedural noise generation.
    pub noise: Noise,
    /// Scattering, phase function, multiple scattering and ambient light.
    pub lighting: Lighting,
    /// Ray-marching quality and integration method.
    pub quality: Quality,
    /// Post effects on the display image: the stylised Kuwahara filter, saturation and lens
    /// flare.
    #[serde(skip_serializing_if = "Post::is_off")]
    pub post: Post,
    /// The rainbow in sunlit rain (physical sky only).
    #[serde(skip_serializing_if = "Rainbow::is_off")]
    pub rainbow: Rainbow,
    /// The night sky (physical sky with a date and place): the catalogue's stars, the Milky
    /// Way and the moon's disc.
    #[serde(skip_serializing_if = "Night::is_default")]
    pub night: Night,
    /// Falling rain or snow near the camera and the rain's shafts below raining clouds.
    #[serde(skip_serializing_if = "Precipitation::is_off")]
    pub precipitation: Precipitation,
    /// Lightning inside the clouds: flashes at random but seeded times.
    #[serde(skip_serializing_if = "Lightning::is_off")]
    pub lightning: Lightning,
    /// Camera keyframes and a time span for sequences (`stratus render --frames`,
    /// `stratus animate`); absent: the camera stays where `[camera]` puts it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub animation: Option<Animation>,
}

/// A camera path over time (section `[animation]`).
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
#[serde(default, deny_unknown_fields)]
pub struct Animation {
    /// Length of the animation in seconds (> 0). Keyframe times lie within [0, duration_s].
    pub duration_s: f64,
    /// Camera keyframes in time order (at least one). Between keyframes position, yaw and
    /// pitch are interpolated with a smoothstep-eased linear blend; yaw takes the short way
    /// round. Before the first or after the last keyframe the camera holds still.
    pub keyframes: Vec<Keyframe>,
}

impl Default for Animation {
    fn default() -> Self {
        Self {
            duration_s: 10.0,
            keyframes: vec![Keyframe::default()],
        }
    }
}

/// One camera keyframe of an [`Animation`] (`[[animation.keyframes]]`).
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
#[serde(default, deny_unknown_fields)]
pub struct Keyframe {
    /// Time in seconds from the start of the animation (>= 0).
    pub time_s: f64,
    /// Camera position `[x, altitude, z]`, metres (altitude >= 0).
    pub position: [f64; 3],
    /// Heading in degrees (as `camera.yaw_deg`).
    pub yaw_deg: f64,
    /// Elevation of the view in degrees, within [-90, 90] (as `camera.pitch_deg`).
    pub pitch_deg: f64,
}

impl Default for Keyframe {
    fn default() -> Self {
        let c = Camera::default();
        Self {
            time_s: 0.0,
            position: c.position,
            yaw_deg: c.yaw_deg,
            pitch_deg: c.pitch_deg,
        }
    }
}

/// Temporal upsampling (thesis 6.1, Horizon Zero Dawn): how many pixels a frame marches.
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Temporal {
    /// Every pixel every frame; no history. TOML `"off"`.
    #[default]
    #[serde(rename = "off")]
    Off,
    /// One pixel of each 2x2 block per frame, the rest reprojected. TOML `"1/4"`.
    #[serde(rename = "1/4")]
    Quarter,
    /// One pixel of each 4x4 block per frame, the rest reprojected. TOML `"1/16"`.
    #[serde(rename = "1/16")]
    Sixteenth,
}

impl Temporal {
    /// Side of the pixel block one marched pixel stands for (1, 2 or 4): the frame marches
    /// one pixel in `divisor()^2` (`FrameUniforms::block_side`).
    pub const fn divisor(self) -> u32 {
        match self {
            Self::Off => 1,
            Self::Quarter => 2,
            Self::Sixteenth => 4,
        }
    }

    /// The TOML and command-line spelling.
    pub const fn name(self) -> &'static str {
        match self {
            Self::Off => "off",
            Self::Quarter => "1/4",
            Self::Sixteenth => "1/16",
        }
    }

    /// Every mode, cheapest last.
    pub const ALL: [Self; 3] = [Self::Off, Self::Quarter, Self::Sixteenth];
}

impl std::str::FromStr for Temporal {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Self::ALL
            .into_iter()
            .find(|t| t.name() == s)
            .ok_or_else(|| format!("unknown temporal mode `{s}`: expected off, 1/4 or 1/16"))
    }
}

/// The camera (section `[camera]`).
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
#[serde(default, deny_unknown_fields)]
pub struct Camera {
    /// Camera position `[x (east), altitude above ground, z (north)]`, metres. The altitude
    /// must be >= 0; it may be below, inside or above the cloud layer.
    pub position: [f64; 3],
    /// Heading in degrees, clockwise seen from above: 0 looks north (+Z), 90 east (+X).
    pub yaw_deg: f64,
    /// Elevation of the view direction in degrees, within [-90, 90]; positive looks up.
    pub pitch_deg: f64,
    /// Vertical field of view in degrees, within (0, 180).
    pub fov_y_deg: f64,
    /// Image size `[width, height]` in pixels, each within [1, 16384]. The CLI's `--size`
    /// overrides it (see [`Scene::with_size`]).
    pub resolution: [u32; 2],
    /// Linear exposure multiplier applied to radiance before tone mapping (> 0).
    pub exposure: f64,
    /// Adapt the exposure to the light of the hour (seed 001's auto exposure): `exposure`
    /// times the ratio of the daylight of a sun 60 degrees high to the light of this scene's
    /// sun (or moon, at night), to the power 0.75 (see [`Scene::auto_exposure`]).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub auto_exposure: bool,
    /// The least and the greatest exposure, `[min, max]` (seed 001's "exposure adapt min /
    /// max"): the exposure the frame uses (with `auto_exposure`, after adaptation) is clamped
    /// to it. Absent: unbounded.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub exposure_range: Option<[f64; 2]>,
    /// An explicit orientation in world axes, which replaces `yaw_deg` and `pitch_deg` when
    /// given: a host engine's camera, roll included (`stratus::HostCamera` fills it from a
    /// view matrix).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub orientation: Option<Orientation>,
}

/// Post effects on the display image (section `[post]`): the seed's stylised presets, after
/// the tone curve, and the camera's lens flare, added to the radiance before it. They change
/// the display image only (the HDR output, the path tracer's truths and the statistics do not
/// see them): a host's camera makes its own flare.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
#[serde(default, deny_unknown_fields)]
pub struct Post {
    /// The Kuwahara filter (seed 001's "Stylized Kuwahara"): each pixel takes the mean of the
    /// one of its four quadrant windows whose colours vary least, so flat regions turn to
    /// even patches of colour while edges, where the windows on either side differ, stay
    /// sharp: the look of opaque watercolour (Kuwahara et al. 1976).
    pub kuwahara: bool,
    /// The Kuwahara window's radius as a fraction of the image's height, within (0, 0.05]:
    /// the filter's offsets are in UV, not pixels, so the strokes keep their size on
    /// screen at every resolution.
    pub kuwahara_radius: f64,
    /// Saturation of the display image (seed 001's "Saturability"), within [0, 4]: 1 leaves
    /// it, 0 is grey, above 1 the stylised presets' stronger colour. Each pixel's colour
    /// moves away from its luminance (Rec. 709 weights) by this factor.
    pub saturation: f64,
    /// Lens flare (seed 001's "Lens Flare Intensity"), within [0, 10]: 0 draws none. While
    /// the sun's disc is on screen, the lens's ghosts (images of its hexagonal aperture) and
    /// a halo lie along the line from the sun through the image's centre, each carrying a
    /// fixed share of the sun's light that reaches the lens, so the air's reddening and the
    /// clouds in front of the sun dim them; 1 is a multi-coated lens, its ghosts 1e-4 to
    /// 4e-4 of that light each.
    pub lens_flare_intensity: f64,
}

impl Default for Post {
    fn default() -> Self {
        Self {
            kuwahara: false,
            kuwahara_radius: 0.008,
            saturation: 1.0,
            lens_flare_intensity: 0.0,
        }
    }
}

impl Post {
    /// Whether no post effect changes the image (the defaults, which a scene's TOML leaves
    /// out).
    pub fn is_off(&self) -> bool {
        *self == Self::default()
    }
}

/// The rainbow (section `[rainbow]`, seed 001's rainbow effect): the primary and secondary
/// bows of sunlight refracted and reflected in falling raindrops, drawn where rain (below a
/// precipitating cloud layer) is in view and sunlit. Needs the physical sky.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
#[serde(default, deny_unknown_fields)]
pub struct Rainbow {
    /// The air's moisture (seed 001's `moisture`), within [0, 4]: the rain's scattering in
    /// units of moderate rain's (3.912 / 7 km, a 7 km visibility by Koschmieder's law), so the
    /// bow's global strength; 0 (the default) draws none. Over altitude it is weighted by a
    /// profile that peaks at 2 km, (h / 2 km) e^(1 - h / 2 km), as the seed describes.
    pub moisture: f64,
    /// The raindrops' radius in micrometres (seed 001's "Moisture Drop Radius"), within
    /// [5, 2500]: small drops (fog, 10-50) give broad, nearly white fog bows, large ones
    /// (rain, 200-1000) narrow, saturated bows with supernumeraries inside the primary.
    pub drop_radius_um: f64,
    /// The Lee diagram (seed 001's "Use Lee Graph", on by default): the bows from a table
    /// of Airy theory integrated over the visible spectrum and the sun's disc, computed once
    /// for the drop radius. Off: the cheap path, the same theory at three wavelengths per
    /// pixel (no table, no spectrum, no disc).
    pub lee_diagram: bool,
}

impl Default for Rainbow {
    fn default() -> Self {
        Self {
            moisture: 0.0,
            drop_radius_um: 500.0,
            lee_diagram: true,
        }
    }
}

impl Rainbow {
    /// Whether the rainbow is left at its defaults (none drawn; a scene's TOML leaves them out).
    pub fn is_off(&self) -> bool {
        *self == Self::default()
    }

    /// Whether a bow is drawn from the Lee-diagram table (moisture, and `lee_diagram` on): the
    /// frame plan then computes the table and the uniforms' `FLAG_LEE_DIAGRAM` says to read it.
    pub fn uses_table(&self) -> bool {
        self.moisture > 0.0 && self.lee_diagram
    }
}

/// The night sky (section `[night]`, seed 001's night parameters). The stars are a real
/// catalogue's to magnitude 6.5 (XHIP, the Extended Hipparcos Compilation, as the d3-celestial
/// package ships it), placed for the scene's date and place; the Milky
/// Way is a band of unresolved starlight laid out in galactic coordinates. Both show under the
/// physical sky with a date and place, where the sky is dark enough.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
#[serde(default, deny_unknown_fields)]
pub struct Night {
    /// The stars' brightness (seed 001's "Star Intensity"), within [0, 100]: their catalogue
    /// illuminance times this; 1 (default) is the real sky's.
    pub star_intensity: f64,
    /// The stars' least size (seed 001's "Min Radius"): the standard deviation, in pixels, of
    /// the Gaussian a star's light is spread over, within [0.25, 8]; default 0.5.
    pub star_min_radius_px: f64,
    /// How a star's size grows with its brightness (seed 001's "Radius Scale"), within [0, 4]:
    /// the Gaussian's deviation is at least `star_min_radius_px`, and this many pixels times
    /// the fourth root of the star's illuminance over a magnitude-6.5 star's; 0 (default)
    /// keeps every star at the least size. The light is the same whatever the size.
    pub star_radius_scale: f64,
    /// The glare around bright stars (seed 001's "Glare Scale"), within [0, 10]: a wider,
    /// faint halo (four times the star's deviation) holding 2% of its light times this;
    /// default 1, 0 none.
    pub star_glare_scale: f64,
    /// The Milky Way's brightness (seed 001's "MilkyWay Intensity"), within [0, 100]: 1
    /// (default) is the real sky's integrated starlight (Leinert et al. 1998), 0 none.
    pub milky_way_intensity: f64,
    /// The moon's size (seed 001's "Moon Size"), within [0.5, 8]: its disc's angular radius
    /// over the real one (0.259 degrees); its light stays the same, spread over a larger or
    /// smaller disc. Default 1.
    pub moon_size: f64,
    /// How the moon's edge is anti-aliased (seed 001's "Moon MSAA instead of Moon spread"):
    /// false (default) spreads the limb over one pixel; true samples the disc at four points
    /// of each pixel (a rotated grid) and averages them.
    pub moon_msaa: bool,
}

impl Default for Night {
    fn default() -> Self {
        Self {
            star_intensity: 1.0,
            star_min_radius_px: 0.5,
            star_radius_scale: 0.0,
            star_glare_scale: 1.0,
            milky_way_intensity: 1.0,
            moon_size: 1.0,
            moon_msaa: false,
        }
    }
}

impl Night {
    /// Whether every field is at its default (a scene's TOML then leaves the section out).
    pub fn is_default(&self) -> bool {
        *self == Self::default()
    }
}

/// What falls from a precipitating layer (`precipitation.kind`).
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[serde(rename_all = "kebab-case")]
pub enum PrecipitationKind {
    /// Raindrops: streaks falling at about 9 m/s. TOML `"rain"`.
    #[default]
    Rain,
    /// Snowflakes: soft flakes falling at about 1 m/s and swaying. TOML `"snow"`.
    Snow,
}

impl PrecipitationKind {
    /// The name a scene file uses.
    pub fn name(self) -> &'static str {
        match self {
            Self::Rain => "rain",
            Self::Snow => "snow",
        }
    }

    /// Fall speed (m/s): large raindrops' terminal velocity, about 9 m/s (Gunn and Kinzer
    /// 1949), and snowflakes', 0.5-1.5 m/s (Locatelli and Hobbs 1974).
    pub fn fall_speed_m_s(self) -> f64 {
        match self {
            Self::Rain => 9.0,
            Self::Snow => 1.0,
        }
    }
}

/// Precipitation (section `[precipitation]`): what falls below the precipitating cloud layers
/// (a layer's `precipitation` > 0, where the weather map has cloud above). Both effects are
/// off by default; `stratus weather` turns them on for a report's rain or snow.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
#[serde(default, deny_unknown_fields)]
pub struct Precipitation {
    /// Rain or snow.
    pub kind: PrecipitationKind,
    /// The particles near the camera (a raster pass over the display image), within [0, 4]:
    /// 1 draws up to 8192 drops or flakes in a 40 m box about the camera, each where the rain
    /// at its place (the layer's precipitation times the weather map's) is at least its share;
    /// 0 (the default) draws none.
    pub particles: f64,
    /// Rain shafts (the composite), within [0, 4]: the rain's extinction below a raining cell
    /// in units of heavy rain's, so that distant cells hang darker columns over what is behind
    /// them; 0 (the default) draws none.
    pub shafts: f64,
}

impl Default for Precipitation {
    fn default() -> Self {
        Self {
            kind: PrecipitationKind::Rain,
            particles: 0.0,
            shafts: 0.0,
        }
    }
}

impl Precipitation {
    /// Whether nothing is drawn and the kind is the default (a scene's TOML leaves it out).
    pub fn is_off(&self) -> bool {
        *self == Self::default()
    }
}

/// Lightning (section `[lightning]`): flashes inside the main cloud layer (a cumulonimbus),
/// each a light that lights the cloud about it through the cloud itself, at times and places
/// drawn from `noise.seed` (the same scene and seed flash the same way). See
/// [`crate::lightning`].
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
#[serde(default, deny_unknown_fields)]
pub struct Lightning {
    /// Flashes a minute within [0, 120]; 0 (the default) draws none. Ordinary thunderstorms
    /// flash a few times a minute, severe ones tens of times (Williams et al. 1999: peaks
    /// above 60 a minute in severe Florida storms).
    pub flashes_per_minute: f64,
    /// The flashes' brightness within [0, 10] (1: a flash's peak lights the cloud a kilometre
    /// away six times as brightly as the default noon sun does, so that it shows in a daylit
    /// storm; a choice, not a measurement).
    pub brightness: f64,
}

impl Default for Lightning {
    fn default() -> Self {
        Self {
            flashes_per_minute: 0.0,
            brightness: 1.0,
        }
    }
}

impl Lightning {
    /// Whether no flashes are drawn and the brightness is the default.
    pub fn is_off(&self) -> bool {
        *self == Self::default()
    }
}

/// A camera's orientation (`[camera.orientation]`): three unit, mutually orthogonal vectors
/// in world axes (X east, Y up, Z north) with right x up = forward, the handedness of
/// [`Scene::camera_basis`].
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Orientation {
    /// The view direction.
    pub forward: [f64; 3],
    /// The image's right.
    pub right: [f64; 3],
    /// The image's up.
    pub up: [f64; 3],
}

impl Default for Camera {
    fn default() -> Self {
        Self {
            position: [0.0, 200.0, 0.0],
            yaw_deg: 0.0,
            pitch_deg: 12.0,
            fov_y_deg: 60.0,
            resolution: [800, 450],
            exposure: 1.0,
            auto_exposure: false,
            exposure_range: None,
            orientation: None,
        }
    }
}

/// The sun (section `[sun]`).
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
#[serde(default, deny_unknown_fields)]
pub struct Sun {
    /// Angle of the sun above the horizon in degrees, within [-90, 90] (90 = zenith).
    pub elevation_deg: f64,
    /// Compass bearing of the sun in degrees, clockwise from north: 0 north, 90 east,
    /// 180 south, 270 west.
    pub azimuth_deg: f64,
    /// Optional explicit direction `[x, y, z]` pointing from the scene toward the sun (need
    /// not be normalised; must be non-zero). Overrides `elevation_deg`/`azimuth_deg` if given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub direction: Option<[f64; 3]>,
    /// Sun illuminance at the top of the cloud layer, linear RGB in the renderer's relative
    /// units (each >= 0): with `exposure = 1`, a value near 10 gives a well-exposed day.
    pub illuminance: [f64; 3],
    /// Angular radius of the sun disc in degrees, within [0, 45] (the real sun: 0.2665).
    pub angular_radius_deg: f64,
}

impl Default for Sun {
    fn default() -> Self {
        Self {
            elevation_deg: 60.0,
            azimuth_deg: 150.0,
            direction: None,
            illuminance: [10.0, 9.6, 9.0],
            angular_radius_deg: 0.2665,
        }
    }
}

/// When and where the sky is seen (section `[sky]`). With a date-time and a place, the sun's
/// direction is the real sun's there and then (`stratus-astro`: Meeus's series, within 0.011
/// degrees of astropy's), replacing `[sun] elevation_deg`, `azimuth_deg` and `direction`.
/// An animation advances the date with its time.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq, Default)]
#[serde(default, deny_unknown_fields)]
pub struct Sky {
    /// The instant, ISO 8601 in UTC (`2026-06-21T18:30:00Z`); years 1800-2200.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub date_utc: Option<stratus_astro::UtcDateTime>,
    /// Geodetic latitude in degrees, north positive, within [-90, 90].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub latitude_deg: Option<f64>,
    /// Longitude in degrees, east positive, within [-180, 360).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub longitude_deg: Option<f64>,
}

impl Sky {
    /// No field given: the sun comes from `[sun]`.
    pub fn is_unset(&self) -> bool {
        *self == Self::default()
    }

    /// The date and place, when all three are given and valid.
    pub fn when_and_where(&self) -> Option<(stratus_astro::UtcDateTime, stratus_astro::Place)> {
        let place = stratus_astro::Place::new(self.latitude_deg?, self.longitude_deg?).ok()?;
        Some((self.date_utc?, place))
    }
}

/// Planet and cloud layer geometry (section `[atmosphere]`).
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
#[serde(default, deny_unknown_fields)]
pub struct Atmosphere {
    /// Planet radius in metres (> 0); the ground is a sphere of this radius.
    pub planet_radius_m: f64,
    /// Altitude of the bottom of the cloud layer above the ground, metres (>= 0).
    pub cloud_bottom_m: f64,
    /// Altitude of the top of the cloud layer above the ground, metres (> `cloud_bottom_m`).
    pub cloud_top_m: f64,
    /// The sky behind the clouds: the simple analytic gradient (default) or the physical
    /// atmosphere of `air` (Hillaire 2020's lookup tables).
    #[serde(skip_serializing_if = "SkyModel::is_analytic")]
    pub sky: SkyModel,
    /// The air's scattering and absorption (section `[atmosphere.air]`): the Earth's unless
    /// given. Used by the physical sky.
    #[serde(skip_serializing_if = "Air::is_earth")]
    pub air: Air,
    /// Light shafts (crepuscular rays): the clouds' shadows in the air between the camera and
    /// what it sees, the sun's light the air no longer scatters where a cloud shades it. Off
    /// by default (they cost one more march of the air a pixel in the composite); needs the
    /// physical sky.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub light_shafts: bool,
}

impl Default for Atmosphere {
    fn default() -> Self {
        Self {
            planet_radius_m: 6_360_000.0,
            cloud_bottom_m: 1500.0,
            cloud_top_m: 4000.0,
            sky: SkyModel::Analytic,
            air: Air::default(),
            light_shafts: false,
        }
    }
}

/// Which sky is drawn behind the clouds (`atmosphere.sky`).
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[serde(rename_all = "kebab-case")]
pub enum SkyModel {
    /// A zenith-to-horizon gradient scaled by the sun, a glow around it and a dark ground.
    /// TOML `"analytic"`.
    #[default]
    Analytic,
    /// Rayleigh, Mie and ozone over a spherical planet (Hillaire, "A Scalable and Production
    /// Ready Sky and Atmosphere Rendering Technique", EGSR 2020): transmittance and
    /// multiple-scattering tables, the ground's irradiance and the sky ambient computed when
    /// the air (or the cloud layer's altitudes) changes, the sky-view and aerial-perspective
    /// tables when the sun or the camera does too, the clouds' shadow map every frame, the sun's disc seen through the air and the
    /// ground lit by sun and sky. TOML `"physical"`.
    Physical,
}

impl SkyModel {
    /// The default, analytic sky.
    pub fn is_analytic(&self) -> bool {
        *self == Self::Analytic
    }

    /// The physical sky (`FrameUniforms::FLAG_PHYSICAL_SKY` set).
    pub fn is_physical(&self) -> bool {
        *self == Self::Physical
    }
}

/// The air of the physical sky (section `[atmosphere.air]`). Defaults are the Earth's as
/// Hillaire 2020 takes them from Bruneton ("A Qualitative and Quantitative Evaluation of 8
/// Clear Sky Models", IEEE TVCG 2017); channels are the linear RGB primaries' wavelengths
/// (680, 550, 440 nm).
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
#[serde(default, deny_unknown_fields)]
pub struct Air {
    /// Thickness of the atmosphere above the ground, metres (> 0).
    pub thickness_m: f64,
    /// Rayleigh scattering at the ground, per metre (RGB, >= 0).
    pub rayleigh_scattering: [f64; 3],
    /// Rayleigh density scale height, metres (> 0).
    pub rayleigh_scale_height_m: f64,
    /// Mie scattering at the ground, per metre (>= 0).
    pub mie_scattering: f64,
    /// Mie absorption at the ground, per metre (>= 0).
    pub mie_absorption: f64,
    /// Mie density scale height, metres (> 0).
    pub mie_scale_height_m: f64,
    /// Mie phase asymmetry (Cornette-Shanks), in (-1, 1).
    pub mie_g: f64,
    /// Ozone absorption at its peak, per metre (RGB, >= 0).
    pub ozone_absorption: [f64; 3],
    /// Altitude of the ozone peak, metres (>= 0).
    pub ozone_center_m: f64,
    /// Full width of the ozone's tent profile, metres (> 0).
    pub ozone_width_m: f64,
    /// The ground's diffuse albedo (grey, [0, 1]).
    pub ground_albedo: f64,
}

impl Default for Air {
    fn default() -> Self {
        Self {
            thickness_m: 100_000.0,
            rayleigh_scattering: [5.802e-6, 13.558e-6, 33.1e-6],
            rayleigh_scale_height_m: 8000.0,
            mie_scattering: 3.996e-6,
            mie_absorption: 4.40e-6,
            mie_scale_height_m: 1200.0,
            mie_g: 0.8,
            ozone_absorption: [0.650e-6, 1.881e-6, 0.085e-6],
            ozone_center_m: 25_000.0,
            ozone_width_m: 30_000.0,
            ground_albedo: 0.3,
        }
    }
}

impl Air {
    /// The Earth's defaults, unchanged.
    pub fn is_earth(&self) -> bool {
        *self == Self::default()
    }
}

/// How the density falls off toward the bottom and top of a cloud (thesis 5.4 vs HZD).
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[serde(rename_all = "kebab-case")]
pub enum HeightModel {
    /// The thesis' parabola `(x - a)(x - a - h)(-4 / h^2)`, peak 1 (eq. 5.1). TOML `"parabola"`.
    #[default]
    Parabola,
    /// Horizon Zero Dawn's per-type gradients (stratus, stratocumulus, cumulus) blended by
    /// `clouds.cloud_type`. TOML `"cloud-types"`.
    CloudTypes,
}

impl HeightModel {
    /// GPU code of [`HeightModel::Parabola`] (`FrameUniforms::height_model`).
    pub const PARABOLA: u32 = 0;
    /// GPU code of [`HeightModel::CloudTypes`] (`FrameUniforms::height_model`).
    pub const CLOUD_TYPES: u32 = 1;

    /// The code the WGSL uses for this model (`FrameUniforms::height_model`).
    pub const fn code(self) -> u32 {
        match self {
            Self::Parabola => Self::PARABOLA,
            Self::CloudTypes => Self::CLOUD_TYPES,
        }
    }
}

/// Whether a number is zero (fields serialised only when set).
fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

/// Whether a number is one (fields whose default is 1 serialised only when set).
fn is_one(v: &f64) -> bool {
    *v == 1.0
}

/// The default [`Clouds::anvil_shear_m`]: a storm's anvil typically streams tens of
/// kilometres downwind; 6 km puts its leading edge well beyond the tower at the scale of a
/// view a few tens of kilometres across.
pub const DEFAULT_ANVIL_SHEAR_M: f64 = 6000.0;

/// Whether an anvil shear is the default (serialised only when set).
fn is_default_anvil_shear(v: &f64) -> bool {
    *v == DEFAULT_ANVIL_SHEAR_M
}

/// How many times finer than the detail noise the close-range detail reads it, by default
/// (`clouds.close_detail_scale`).
pub const DEFAULT_CLOSE_DETAIL_SCALE: u32 = 4;

/// How far from the camera the close-range detail reaches by default (m,
/// `clouds.close_detail_range_m`): at 1080p and a 60-degree field of view a pixel is a metre
/// across there, a ninth of the finer read's 9.4 m texels.
pub const DEFAULT_CLOSE_DETAIL_RANGE_M: f64 = 1000.0;

/// The march's step within the close-range detail's range by default (m,
/// `quality.close_step_m`): about two of the finer read's 9.4 m texels.
pub const DEFAULT_CLOSE_STEP_M: f64 = 20.0;

/// Most view steps the march takes within the close-range detail's range
/// (`clouds.close_detail_range_m` over `quality.close_step_m`, which validation holds to it):
/// the bound on what close-range detail costs a ray.
pub const MAX_CLOSE_STEPS: u32 = 256;

fn is_default_close_step(v: &f64) -> bool {
    *v == DEFAULT_CLOSE_STEP_M
}

fn is_default_close_detail_scale(v: &u32) -> bool {
    *v == DEFAULT_CLOSE_DETAIL_SCALE
}

fn is_default_close_detail_range(v: &f64) -> bool {
    *v == DEFAULT_CLOSE_DETAIL_RANGE_M
}

/// The cloud model (section `[clouds]`).
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
#[serde(default, deny_unknown_fields)]
pub struct Clouds {
    /// Global cloud coverage, within [0, 1]: 0 clear sky, 1 overcast. Remaps the base shape.
    pub coverage: f64,
    /// Density multiplier applied to the final density (> 0; 1 = as modelled).
    pub density: f64,
    /// Cloud type, within [0, 1]: 0 stratus, 0.5 stratocumulus, 1 cumulus (HZD weather map B).
    pub cloud_type: f64,
    /// Precipitation, within [0, 1]: darkens cloud bottoms (thesis 4.4.1, HZD weather map G).
    pub precipitation: f64,
    /// Height signal: `"parabola"` (thesis eq. 5.1) or `"cloud-types"` (HZD gradients).
    pub height_model: HeightModel,
    /// Compass direction the wind blows *toward*, degrees clockwise from north (0 = north,
    /// 90 = east).
    pub wind_direction_deg: f64,
    /// Wind speed in metres per second (>= 0). Moves the weather map and the noise.
    pub wind_speed_m_s: f64,
    /// Animation time in seconds; wind offsets are `direction * speed * time`, wrapped by each
    /// texture's period (see [`Scene::wind_offsets`]).
    pub time_s: f64,
    /// World size in metres of one tile of the weather map (> 0).
    pub weather_period_m: f64,
    /// World size in metres of the shape texture's x (and z) axis (> 0).
    pub shape_period_m: f64,
    /// World size in metres of one tile of the detail texture (> 0).
    pub detail_period_m: f64,
    /// World size in metres of one tile of the 2D curl-noise texture (> 0).
    pub curl_period_m: f64,
    /// Amount of detail erosion at cloud edges, within [0, 1] (0 = no detail noise).
    pub detail_strength: f64,
    /// Base-density level within [0, 1] below which the detail noise erodes (thesis alg. 4.1,
    /// "edge detail threshold"): denser cores are left intact.
    pub erosion_threshold: f64,
    /// Maximum displacement of the detail-noise lookup by curl noise, metres (>= 0; HZD).
    pub curl_strength_m: f64,
    /// Strength of the linear "denser toward the top" gradient (thesis 4.5.1), within [0, 1]:
    /// 0 = uniform, 1 = zero density at the bottom of a cloud.
    pub height_gradient: f64,
    /// Edge character within [0, 1]: 0 wispy (Worley detail) everywhere, 0.5 HZD's ramp from
    /// wispy bases to billowy (inverted Worley) tops over the lowest tenth of a cloud, 1
    /// billowy almost from the base.
    pub wispy_billowy: f64,
    /// Cumulus from convective cells, within [0, 1] (1, the default: on). In a cumulus layer
    /// (cloud type 0.75 and up, fully at 1) the clouds stand where the weather map's cell
    /// field (its A channel, a rough fractal field) is above `1 - coverage`, the map's
    /// coverage only scaling that share from place to place, each cloud the taller the larger
    /// its cell, instead of filling the map's large coverage regions. Seen from above, such a
    /// field is many separate clouds with fractal outlines and a power law of sizes, as real
    /// cumulus fields are (Lovejoy 1982; Cahalan and Joseph 1989); at 0 it is the weather
    /// map's few large regions (HZD). Values between blend the two (weather transitions);
    /// layers of other types are unchanged. The default is 1 because a straight-down view of
    /// the weather map alone measured D 1.14 and a flat size density (`stratus measure-field`,
    /// docs/cloud-fields.md).
    #[serde(skip_serializing_if = "is_one")]
    pub convective_cells: f64,
    /// Cumulonimbus anvils, within [0, 1] (0, the default: none). In a cumulus layer (cloud
    /// type 0.75 and up, fully at 1) each tower's top spreads sideways over the layer's upper
    /// part into a flat plate kilometres wider than the tower, as a storm's updraft does where
    /// the tropopause stops it, and the plate leans downwind by [`Clouds::anvil_shear_m`].
    /// Values between thin the anvils (weather transitions); layers of other types are
    /// unchanged.
    #[serde(skip_serializing_if = "is_zero")]
    pub anvil: f64,
    /// How far downwind of its tower an anvil's top lies (m, >= 0; along
    /// `wind_direction_deg`): the wind aloft carries the spreading cloud. Read only where
    /// [`Clouds::anvil`] is above 0.
    #[serde(skip_serializing_if = "is_default_anvil_shear")]
    pub anvil_shear_m: f64,
    /// The main layer's cirrus share, within [0, 1] (0, the default: a water cloud of
    /// `cloud_type`). At 1 the layer is cirrus: ice cloud in fibres kilometres long drawn out
    /// along the wind, with fall streaks trailing below their heads, instead of the cumulus
    /// family's heaped shapes; values between blend the two. Meant for thin, high layers
    /// ([`DEFAULT_CIRRUS_DENSITY`] for a cirrus's optical depth).
    #[serde(skip_serializing_if = "is_zero")]
    pub cirrus: f64,
    /// The main layer's cellular share, within [0, 1] (0, the default: the water cloud of
    /// `cloud_type` on the shape noise). At 1 the layer is a field of cloudlets, one on each
    /// cell of the convection that stirs a thin layer (stratocumulus, altocumulus), each
    /// cell about twice as wide as the layer is deep, domed over a flat base, the gaps
    /// between them clear or thin; values between blend the two. Meant for layers up to
    /// about 1.5 km deep.
    #[serde(skip_serializing_if = "is_zero")]
    pub cellular: f64,
    /// How far the cells of cellular layers line up in rolls along the wind, within [0, 1]
    /// (0, the default: round cells; 1: cells [`CELLULAR_ROLL`] times longer along the wind
    /// than across, the cloud streets of a boundary layer's roll convection). Every cellular
    /// layer of the scene takes it.
    #[serde(skip_serializing_if = "is_zero")]
    pub cell_rolls: f64,
    /// Close-range detail, within [0, 1] (0, the default: off). Near the camera the detail
    /// noise (37.5 m texels at the default period) is blur at a metre's pixel, and a cloud's
    /// thin fringe (density 0.05-0.4, hundreds of metres deep) a fog the camera sits in: with
    /// this above 0 the clouds' edges are eroded a second time by the detail noise read
    /// [`Clouds::close_detail_scale`] times finer, its lookup bent by the curl noise read as
    /// much finer, into wisps and billows tens of metres across, with this strength; a level of detail
    /// by distance fades it out between half of [`Clouds::close_detail_range_m`] and all of it,
    /// and the march takes steps of `quality.close_step_m` within that range, so the cost is
    /// bounded by the range whatever the scene. The cores of clouds are left intact, as the
    /// first erosion leaves them.
    #[serde(skip_serializing_if = "is_zero")]
    pub close_detail: f64,
    /// How many times finer than the detail noise the close-range detail reads it, an integer
    /// within [2, 32] (4, the default: 300 m tiles of 9.4 m texels at the default detail
    /// period; 8 was finer than the clouds' fringes show, their mean free path being tens to
    /// hundreds of metres at the default scattering). An integer,
    /// so that the detail's wind offset, wrapped by its period, is whole periods of the finer
    /// read too.
    #[serde(skip_serializing_if = "is_default_close_detail_scale")]
    pub close_detail_scale: u32,
    /// Distance from the camera to which the close-range detail reaches, metres (> 0;
    /// default [`DEFAULT_CLOSE_DETAIL_RANGE_M`]): at full strength up to half of it, fading to
    /// none at it. Read only where [`Clouds::close_detail`] is above 0.
    #[serde(skip_serializing_if = "is_default_close_detail_range")]
    pub close_detail_range_m: f64,
    /// Extra cloud layers (`[[clouds.layers]]`, at most [`MAX_EXTRA_LAYERS`]) besides the main
    /// one that `atmosphere.cloud_bottom_m`/`cloud_top_m` and the fields above describe. Each
    /// has its own altitudes and weather over the same noise, wind and lighting; no two
    /// layers may overlap in altitude. The march marches each layer on its own, nearest first.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub layers: Vec<CloudLayer>,
}

/// Most extra cloud layers a scene may have (four layers in all, as a METAR's four cloud
/// groups).
pub const MAX_EXTRA_LAYERS: usize = 3;

/// An extra cloud layer (`[[clouds.layers]]`): altitudes and weather. Extra layer `k` (from 1)
/// reads the weather map shifted by `k * (0.382, 0.618)` of its period, so that decks do not
/// repeat each other's pattern.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
#[serde(default, deny_unknown_fields)]
pub struct CloudLayer {
    /// Altitude of the layer's bottom above the ground, metres (>= 0).
    pub bottom_m: f64,
    /// Altitude of the layer's top, metres (> `bottom_m`).
    pub top_m: f64,
    /// Coverage within [0, 1] (as `clouds.coverage`).
    pub coverage: f64,
    /// Density multiplier (> 0; as `clouds.density`).
    pub density: f64,
    /// Cloud type within [0, 1]: 0 stratus, 0.5 stratocumulus, 1 cumulus.
    pub cloud_type: f64,
    /// Precipitation within [0, 1].
    pub precipitation: f64,
    /// Cirrus share within [0, 1] (as `clouds.cirrus`).
    #[serde(skip_serializing_if = "is_zero")]
    pub cirrus: f64,
    /// Cellular share within [0, 1] (as `clouds.cellular`).
    #[serde(skip_serializing_if = "is_zero")]
    pub cellular: f64,
}

/// How many times longer than wide a cellular layer's cells are at `clouds.cell_rolls` 1:
/// rolls of boundary-layer convection lie along the mean wind, spaced two to four times the
/// layer's depth and each many times longer (Etling and Brown 1993, Boundary-Layer Meteorol.
/// 65:215); four was chosen by eye.
pub const CELLULAR_ROLL: f64 = 4.0;

/// A cirrus layer's density multiplier: cirrus are optically thin, their optical depth
/// mostly 0.03-3 (thin below 0.3; Sassen and Cho 1992, J. Appl. Meteor. 31:1275). At the
/// default scattering (0.04 per metre) the densest strands of a 1500 m layer at this
/// multiplier are 1-2 optical depths thick straight through.
pub const DEFAULT_CIRRUS_DENSITY: f64 = 0.04;

impl Default for CloudLayer {
    /// A thin, high, stratiform deck (altostratus height).
    fn default() -> Self {
        Self {
            bottom_m: 6000.0,
            top_m: 7000.0,
            coverage: 0.5,
            density: 0.3,
            cloud_type: 0.0,
            precipitation: 0.0,
            cirrus: 0.0,
            cellular: 0.0,
        }
    }
}

impl Default for Clouds {
    fn default() -> Self {
        Self {
            coverage: 0.45,
            density: 1.0,
            cloud_type: 1.0,
            precipitation: 0.0,
            height_model: HeightModel::Parabola,
            wind_direction_deg: 90.0,
            wind_speed_m_s: 10.0,
            time_s: 0.0,
            weather_period_m: 60_000.0,
            shape_period_m: 9_600.0,
            detail_period_m: 1_200.0,
            curl_period_m: 6_000.0,
            detail_strength: 0.35,
            erosion_threshold: 0.4,
            curl_strength_m: 150.0,
            height_gradient: 0.5,
            wispy_billowy: 0.5,
            convective_cells: 1.0,
            anvil: 0.0,
            anvil_shear_m: DEFAULT_ANVIL_SHEAR_M,
            cirrus: 0.0,
            cellular: 0.0,
            cell_rolls: 0.0,
            close_detail: 0.0,
            close_detail_scale: DEFAULT_CLOSE_DETAIL_SCALE,
            close_detail_range_m: DEFAULT_CLOSE_DETAIL_RANGE_M,
            layers: Vec::new(),
        }
    }
}

/// Size of the Perlin-Worley shape texture.
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum ShapeTexture {
    /// 128 x 32 x 128 texels (Högfeldt's thesis, 4.2). TOML `"128x32x128"`.
    #[default]
    #[serde(rename = "128x32x128")]
    Thesis,
    /// 128 x 128 x 128 texels (Horizon Zero Dawn). TOML `"128x128x128"`.
    #[serde(rename = "128x128x128")]
    Hzd,
}

impl ShapeTexture {
    /// Texture size `[x, y, z]` in texels (y is the vertical axis).
    pub const fn dims(self) -> [u32; 3] {
        match self {
            Self::Thesis => [128, 32, 128],
            Self::Hzd => [128, 128, 128],
        }
    }
}

/// Procedural noise generation (section `[noise]`).
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq, Default)]
#[serde(default, deny_unknown_fields)]
pub struct Noise {
    /// Seed of every generated texture (shape, detail, curl, weather). Must be <= 2^63 - 1
    /// because TOML integers are signed 64-bit.
    pub seed: u64,
    /// Shape texture size: `"128x32x128"` (thesis) or `"128x128x128"` (HZD).
    pub shape_texture: ShapeTexture,
}

/// Phase function family.
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[serde(rename_all = "kebab-case")]
pub enum PhaseModel {
    /// Henyey-Greenstein with eccentricity `g` (thesis eq. 5.4). TOML `"hg"`.
    #[default]
    Hg,
    /// Blend of two HG lobes, `(1 - blend) * HG(g) + blend * HG(g2)`: the silver lining
    /// (seed 001). TOML `"two-lobe-hg"`.
    TwoLobeHg,
    /// Cornette-Shanks with eccentricity `g` (thesis eq. 5.5). TOML `"cornette-shanks"`.
    CornetteShanks,
}

impl PhaseModel {
    /// GPU code of [`PhaseModel::Hg`] (`FrameUniforms::phase_model`).
    pub const HG: u32 = 0;
    /// GPU code of [`PhaseModel::TwoLobeHg`] (`FrameUniforms::phase_model`).
    pub const TWO_LOBE_HG: u32 = 1;
    /// GPU code of [`PhaseModel::CornetteShanks`] (`FrameUniforms::phase_model`).
    pub const CORNETTE_SHANKS: u32 = 2;

    /// The code the WGSL uses for this model (`FrameUniforms::phase_model`).
    pub const fn code(self) -> u32 {
        match self {
            Self::Hg => Self::HG,
            Self::TwoLobeHg => Self::TWO_LOBE_HG,
            Self::CornetteShanks => Self::CORNETTE_SHANKS,
        }
    }
}

/// Phase function parameters (section `[lighting.phase]`).
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
#[serde(default, deny_unknown_fields)]
pub struct Phase {
    /// `"hg"`, `"two-lobe-hg"` or `"cornette-shanks"`.
    pub model: PhaseModel,
    /// Eccentricity of the (first) lobe, within (-1, 1); > 0 scatters forward.
    pub g: f64,
    /// Eccentricity of the second lobe of `"two-lobe-hg"`, within (-1, 1).
    pub g2: f64,
    /// Weight of the second lobe of `"two-lobe-hg"`, within [0, 1].
    pub blend: f64,
}

impl Default for Phase {
    fn default() -> Self {
        Self {
            model: PhaseModel::Hg,
            g: 0.6,
            g2: -0.3,
            blend: 0.5,
        }
    }
}

/// Multiple-scattering approximation by octaves (Wrenninge 2013; Hillaire, Frostbite 2016),
/// section `[lighting.multiple_scattering]`.
///
/// Octave `i` (0 = single scattering) adds the single-scattering term computed with the
/// scattering coefficient times `a^i` and the phase eccentricity times `c^i`, attenuated by
/// `1 / (1 + b^i tau)` of the optical depth `tau` toward the sun (the diffuse light's slow
/// fall-off in thick cloud, as two-stream theory gives it, where Wrenninge has
/// `exp(-b^i tau)`), and scaled by the cosine of the sun's zenith angle and by the build-up
/// `1 - exp(-sigma_t density buildup_m)` of the sample's density. Four terms beyond
/// Wrenninge's carry what the octaves' optical depth toward the sun does not know about the
/// cloud around the sample: the octaves are scaled by the weather map's local coverage to the
/// power `coverage_exponent` (light leaks out of a small cloud, not out of a deck), fed
/// through a broken layer's sides as well as its top (`side_light`), and the sun ray beyond
/// the light march's reach is shadowed statistically (`far_chord_m`); and the octaves leaving
/// a deck are limb-darkened toward grazing views (`limb_darkening`). Seen through thin cloud
/// the octaves' light leans toward the sun (`forward_lobe`, `forward_lobe_g`), and in a layer
/// lit from above it is brighter looking up than looking down (`vertical_anisotropy`). A deck
/// lets more of a high sun's diffuse light out of its base than of a low one's
/// (`deck_escape`); in a closed deck the octaves see the column of cloud above the sample
/// (`steep_light`, `steep_light_scale`), and looking down they dim where
/// cloud above the sample shields it (`downward_dimming`). The defaults are fitted to the path
/// tracer's all-orders truth by `stratus fit-scattering` (docs/fit); `a > b` is allowed.
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq)]
#[serde(default, deny_unknown_fields)]
pub struct MultipleScattering {
    /// Number of octaves *beyond* single scattering, within [0, 8] (0 = single scattering
    /// only).
    pub octaves: u32,
    /// Per-octave factor of the scattering contribution, within (0, 2].
    pub a: f64,
    /// Per-octave attenuation of the extinction toward the sun, within (0, 1].
    pub b: f64,
    /// Per-octave attenuation of the phase eccentricity, within (0, 1].
    pub c: f64,
    /// Build-up length, metres within [0, 10000]: the octaves are scaled by `1 - exp(-sigma_t
    /// density buildup_m)` of the sample's density, since light scatters many times only
    /// where there is cloud around to scatter it (thin wisps and edges get little). 0 leaves
    /// them unscaled (Wrenninge's octaves).
    pub buildup_m: f64,
    /// Light fed into the octaves through the sides of broken cloud, within [0, 4]: the
    /// octaves' cosine of the sun's zenith angle mu0 (the flux through a deck's top) becomes
    /// `mu0 + side_light (1 - coverage) sin(zenith) exp(-far)`, `coverage` the weather map's
    /// at the sample and `far` the far shadow's optical depth. 0: mu0 alone.
    pub side_light: f64,
    /// The octaves are scaled by the weather map's coverage at the sample to this power,
    /// within [0, 4]: multiply scattered light leaks out of a small cloud through its sides
    /// but stays in a deck. 0: unscaled.
    pub coverage_exponent: f64,
    /// Far shadow, metres: 0 (off) or within [100, 1000000]. Beyond the light march's reach
    /// the sun ray's optical depth inside the layer is taken as `length f / ((1 - f)
    /// far_chord_m)`, a binary Markov mixture's (clear gaps of mean length `far_chord_m (1 -
    /// f) / f`), over each quarter of that stretch, `f` the weather map's coverage times the
    /// height profile at the quarter's middle.
    /// It shadows single scattering and the side light: toward a sun a few degrees up the
    /// light crosses tens of kilometres of layer that the light march does not sample.
    pub far_chord_m: f64,
    /// Limb darkening of the octaves, within [0, 4]: they are scaled by `mix(1, (1 + k mu) /
    /// (1 + 2k/3), coverage)`, `k` this value, `mu` the absolute cosine of the view ray to the
    /// vertical and `coverage` the weather map's at the sample. The diffuse light leaving a
    /// thick layer is brighter along its normal than at grazing angles (`1 + (3/2) mu` in the
    /// Eddington approximation; Chandrasekhar 1950). 0: isotropic octaves.
    pub limb_darkening: f64,
    /// Forward lobe of the octaves seen through thin cloud, within [0, 1]: a pixel's octave
    /// light is scaled by `1 + w (4 pi HG(cos, forward_lobe_g) - 1)`, `cos` the cosine between
    /// the view ray and the sun, `w = forward_lobe min(T / 0.1, 1)` and `T` the pixel's
    /// transmittance: light that crossed a thin cloud was scattered a few times and still
    /// leans toward the sun; through a thick one (`T` near 0) it is diffuse. Its mean over
    /// the sphere is 1 (it moves light between directions, adding none). 0: off.
    pub forward_lobe: f64,
    /// The forward lobe's Henyey-Greenstein eccentricity, within [0, 0.95].
    pub forward_lobe_g: f64,
    /// Vertical anisotropy of the octaves, within [0, 1]: they are scaled by `1 + s view_y
    /// coverage (1 - h)`, `s` this value, `view_y` the view ray's vertical component (up
    /// positive), `coverage` the weather map's at the sample and `h` its height fraction in
    /// the layer. In a layer lit from above the diffuse light's net flux runs downward, so the
    /// light going down (seen looking up) outshines the light going up (seen looking down),
    /// most toward the layer's base, where the upward stream is only the ground's reflection.
    /// Its mean over the sphere is 1 (it adds no light). 0: off.
    pub vertical_anisotropy: f64,
    /// The octaves' escape from a deck, within [0, 2]: they are scaled by `1 + e w (mu0 -
    /// 1/2)`, `e` this value, `mu0` the cosine of the sun's zenith angle and `w` the layer's
    /// coverage to the 8th power (its weight as a deck). A thick layer lets `(2/3 + mu0) /
    /// (4/3 + (1 - g) tau)` of the flux through its top out of its base in the Eddington
    /// approximation (Meador and Weaver 1980): steep light goes deeper before it turns. 0: off.
    pub deck_escape: f64,
    /// The weight of the column above the sample in a closed deck's octaves, within [0, 1]:
    /// their optical depth is `mix(tau, s tau_col + tau_above, m w)`, `m` this value, `tau` the
    /// sun ray's, `tau_above` its part in the layers above, `tau_col` that of the vertical
    /// column from the sample to the layer's top (three equal steps of the density without
    /// detail erosion), `s` `steep_light_scale` (the diffuse
    /// light's effective path over the vertical: 1.66 for a slab, Elsasser 1942), and `w =
    /// (coverage - 0.8) / 0.1` (clamped) the layer's weight as a closed deck. The truth's multiply scattered light in a thick deck
    /// follows the cloud above the sample, which the slant sun ray passes by. 0: off; 1: the
    /// column (and the layers above) alone in a closed deck. (The name is from its first form, a steeper light
    /// march toward `normalize(sun + up)`.)
    pub steep_light: f64,
    /// The scale of the column's optical depth (`steep_light`), within [0.5, 8].
    pub steep_light_scale: f64,
    /// The octaves' dimming looking down, within [0, 8]: they are scaled by `1 - k |view_y|
    /// coverage (1 - h) tau_v / (tau_v + 1)` for a view ray going down (`k` this value,
    /// `tau_v = tau mu0` the sun ray's optical depth projected on the vertical), clamped at 0:
    /// the light going up through a layer falls with the cloud above it, which the vertical
    /// anisotropy's height fraction does not see. 0: off.
    pub downward_dimming: f64,
}

impl Default for MultipleScattering {
    /// Fitted to the GPU path tracer's all-orders truth (8192 paths a pixel, `docs/fit/truths`;
    /// the march on lavapipe) over fifteen training scenes by `stratus fit-scattering`: 3
    /// octaves with a build-up of 400 m, side light 1, coverage exponent 1, a far-shadow chord
    /// of 8 km, limb darkening 0.25, a forward lobe of 0.3 (g 0.5), a vertical anisotropy of
    /// 0.2, a deck escape of 2 and a downward dimming of 4, with the octaves' own eccentricity
    /// small (c = 0.15), and the deck's column alone (weight 1) at 1.5 times its vertical
    /// optical depth (docs/fit). The thesis's 2 octaves of a = b = c = 0.5 and none of the
    /// other terms before.
    fn default() -> Self {
        Self {
            octaves: 3,
            a: 1.15,
            b: 0.5,
            c: 0.15,
            buildup_m: 400.0,
            side_light: 1.0,
            coverage_exponent: 1.0,
            far_chord_m: 8000.0,
            limb_darkening: 0.25,
            forward_lobe: 0.3,
            forward_lobe_g: 0.5,
            vertical_anisotropy: 0.2,
            deck_escape: 2.0,
            steep_light: 1.0,
            steep_light_scale: 1.5,
            downward_dimming: 4.0,
        }
    }
}

/// Light transport parameters (section `[lighting]`).
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
#[serde(default, deny_unknown_fields)]
pub struct Lighting {
    /// Scattering coefficient sigma_s in 1/m at density 1 (>= 0).
    pub scattering: f64,
    /// Absorption coefficient sigma_a in 1/m at density 1 (>= 0); extinction sigma_t =
    /// sigma_s + sigma_a must be > 0.
    pub absorption: f64,
    /// Apply HZD's Beer-Powder term (darkens thin edges seen with the sun behind the viewer).
    pub beer_powder: bool,
    /// Scale `k` of the powder term `1 - exp(-k * optical depth)` (>= 0; HZD uses 2).
    pub powder_strength: f64,
    /// Ambient radiance at the bottom of the cloud layer, linear RGB (each >= 0), same units
    /// as the sun illuminance.
    pub ambient_bottom: [f64; 3],
    /// Ambient radiance at the top of the cloud layer, linear RGB (each >= 0).
    pub ambient_top: [f64; 3],
    /// Multiplier of the ambient term (>= 0; thesis "ambient multiplier").
    pub ambient_strength: f64,
    /// How strongly precipitation darkens the bottom of clouds (thesis 4.4.1), within [0, 1]:
    /// the sun's light at a sample of height fraction h in a layer whose weather map says
    /// precipitation p is scaled by 1 - k p (1 - h) (1 - exp(-tau / D)): tau is the sun ray's
    /// optical depth as the light march sees it, D is `PRECIPITATION_DEPTH` in lighting.wgsl
    /// (which says how it was chosen). The sky's light is not darkened. With
    /// `quality.light_steps` 0 the layer's own cloud adds nothing to tau, so only layers above
    /// darken it, and a single layer only where the sun ray meets the ground (there the
    /// darkening is full, whatever tau). The path tracer leaves
    /// rain's dark base to the density (precipitation raises it), so the default is chosen
    /// against its truth: 0.6, the lowest mean FLIP of `weather rain`, `weather snow` and
    /// `weather thunderstorm` over 0.3-0.85 (docs/fit-log.md).
    pub precipitation_darkening: f64,
    /// Phase function.
    pub phase: Phase,
    /// Multiple-scattering octaves.
    pub multiple_scattering: MultipleScattering,
}

impl Default for Lighting {
    fn default() -> Self {
        Self {
            scattering: 0.04,
            absorption: 0.0,
            beer_powder: false,
            powder_strength: 2.0,
            ambient_bottom: [0.25, 0.3, 0.4],
            ambient_top: [0.6, 0.75, 1.0],
            ambient_strength: 1.0,
            precipitation_darkening: 0.6,
            phase: Phase::default(),
            multiple_scattering: MultipleScattering::default(),
        }
    }
}

/// What computes the clouds' light.
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Integrator {
    /// The real-time ray march: single scattering with the octave approximation of multiple
    /// scattering and the ambient term. TOML `"march"`.
    #[default]
    March,
    /// The Monte Carlo path tracer (all scattering orders), accumulating paths over frames
    /// while the camera stays. TOML `"pathtrace"`.
    Pathtrace,
}

impl Integrator {
    /// The TOML and command-line name.
    pub const fn name(self) -> &'static str {
        match self {
            Self::March => "march",
            Self::Pathtrace => "pathtrace",
        }
    }
}

/// Which cloud renderer draws the frame: the volumetric model, or one of the baselines it is
/// measured against.
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Method {
    /// The volumetric model (the march, or the path tracer with `integrator = "pathtrace"`).
    /// TOML `"volumetric"`.
    #[default]
    Volumetric,
    /// The basic ray marcher of the volumetric-cloud tutorials: a Riemann sum of sun light
    /// through Beer-Powder toward the sun, Henyey-Greenstein phase and Beer along the view, no
    /// ambient and no multiple scattering, over the same density field. TOML `"basic"`.
    Basic,
    /// Camera-facing textured sprites in boxes placed from the same weather map and density
    /// field (Wang 2003), shaded by artist colour levels instead of light transport. TOML
    /// `"sprites"`.
    Sprites,
}

impl Method {
    /// Every method.
    pub const ALL: [Self; 3] = [Self::Volumetric, Self::Basic, Self::Sprites];

    /// The TOML and command-line name.
    pub const fn name(self) -> &'static str {
        match self {
            Self::Volumetric => "volumetric",
            Self::Basic => "basic",
            Self::Sprites => "sprites",
        }
    }
}

/// How the in-scattered light over one view step is integrated.
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Integration {
    /// Hillaire's energy-conserving analytic step integral `(S - S * Tr) / sigma_t` (thesis
    /// alg. 5.4). TOML `"analytic"`.
    #[default]
    Analytic,
    /// Naive Riemann sum `S * T * dt`, kept to show where it fails. TOML `"riemann"`.
    Riemann,
}

impl Integration {
    /// GPU code of [`Integration::Analytic`] (`FrameUniforms::integration`).
    pub const ANALYTIC: u32 = 0;
    /// GPU code of [`Integration::Riemann`] (`FrameUniforms::integration`).
    pub const RIEMANN: u32 = 1;

    /// The code the WGSL uses for this method (`FrameUniforms::integration`).
    pub const fn code(self) -> u32 {
        match self {
            Self::Analytic => Self::ANALYTIC,
            Self::Riemann => Self::RIEMANN,
        }
    }
}

/// Ray-marching quality (section `[quality]`).
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
#[serde(default, deny_unknown_fields)]
pub struct Quality {
    /// Number of view steps through the layer, within [1, 65536]: step length =
    /// min(layer depth along the ray, cut-off distance) / view_steps (thesis alg. 5.1).
    pub view_steps: u32,
    /// Optional fixed view step length in metres (> 0); if given, used instead of
    /// `view_steps`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub step_length_m: Option<f64>,
    /// Light-march steps toward the sun per view sample, within [0, 16] (0 = no self-shadowing).
    pub light_steps: u32,
    /// Each light step is this many times longer than the previous one, within [1, 16].
    pub light_step_growth: f64,
    /// Length of the first light step in metres (> 0).
    pub first_light_step_m: f64,
    /// Clouds farther than this from the camera are not marched, metres (> 0; thesis alg. 5.1).
    pub cutoff_distance_m: f64,
    /// View step length within `clouds.close_detail_range_m` of the camera where
    /// `clouds.close_detail` is on, metres (> 0; default [`DEFAULT_CLOSE_STEP_M`]): the
    /// close-range detail's wisps are metres across, which the march's steps elsewhere (tens
    /// to hundreds of metres) would alias into noise. Never coarser than the step elsewhere;
    /// at most [`MAX_CLOSE_STEPS`] steps span the range. Read only with close-range detail on.
    #[serde(skip_serializing_if = "is_default_close_step")]
    pub close_step_m: f64,
    /// Stop marching once the view transmittance drops below this, within [0, 1) (0 = never).
    pub early_exit_transmittance: f64,
    /// Jitter each pixel's start offset by a fraction of a step (removes banding).
    pub jitter: bool,
    /// Step integral: `"analytic"` (energy-conserving) or `"riemann"`.
    pub integration: Integration,
    /// Frame number: seeds the per-pixel jitter sequence, and with temporal upsampling picks
    /// which pixel of each block is marched and its van der Corput start offset.
    pub frame: u32,
    /// Temporal upsampling: `"off"`, `"1/4"` or `"1/16"` of the pixels marched per frame.
    pub temporal: Temporal,
    /// Dynamic step length: after 8 empty samples in a row the view step doubles; a sample
    /// in cloud steps back and returns to the fine step.
    pub dynamic_step: bool,
    /// High-transmittance checkerboard skipping (thesis 6.2.2, needs `temporal`): a pixel
    /// whose reprojected history is clear (transmittance 1) is not marched in every other
    /// of its turns, alternating like a checkerboard so no pixel is skipped twice running.
    pub checkerboard: bool,
    /// Empty-space skipping: the ray jumps over cells of a coarse occupancy grid of the
    /// weather map where the coverage leaves no cloud.
    pub empty_space_skip: bool,
    /// `"march"` (real time) or `"pathtrace"` (the all-orders Monte Carlo truth, accumulated
    /// over frames; the march's step settings and methods do not apply).
    pub integrator: Integrator,
    /// Path tracer: the most scattering orders a path contributes (0 = all). Each frame adds
    /// a workgroup of paths per pixel (`wgsl/pathtrace.wgsl`'s `PATHS_PER_FRAME`).
    pub path_orders: u32,
    /// `"volumetric"` (the model), or a baseline it is measured against: `"basic"` (the
    /// tutorial ray marcher) or `"sprites"` (Wang 2003). The baselines run on the GPU backends
    /// only, with the march integrator and temporal upsampling off.
    pub method: Method,
}

impl Default for Quality {
    fn default() -> Self {
        Self {
            view_steps: 64,
            step_length_m: None,
            light_steps: 6,
            light_step_growth: 2.0,
            first_light_step_m: 50.0,
            cutoff_distance_m: 60_000.0,
            close_step_m: DEFAULT_CLOSE_STEP_M,
            early_exit_transmittance: 0.01,
            jitter: true,
            integration: Integration::Analytic,
            frame: 0,
            temporal: Temporal::Off,
            dynamic_step: false,
            checkerboard: false,
            empty_space_skip: false,
            integrator: Integrator::March,
            path_orders: 0,
            method: Method::Volumetric,
        }
    }
}

impl Scene {
    /// This scene with the image size replaced (the CLI's `--size WxH`).
    pub fn with_size(mut self, width: u32, height: u32) -> Self {
        self.camera.resolution = [width, height];
        self
    }

    /// The scene `t` seconds into its animation: the camera from the `[animation]` keyframes
    /// (unchanged without an animation) and the wind `t` seconds on (`clouds.time_s + t`).
    pub fn at_time(&self, t: f64) -> Self {
        let mut s = self.clone();
        s.clouds.time_s += t;
        s.sky.date_utc = s.sky.date_utc.map(|d| d.plus_seconds(t));
        let Some(a) = &self.animation else {
            return s;
        };
        let (Some(first), Some(last)) = (a.keyframes.first(), a.keyframes.last()) else {
            return s;
        };
        let (k0, k1, u) = if t <= first.time_s {
            (first, first, 0.0)
        } else if t >= last.time_s {
            (last, last, 0.0)
        } else {
            let i = a.keyframes.partition_point(|k| k.time_s <= t).max(1);
            let (k0, k1) = (&a.keyframes[i - 1], &a.keyframes[i]);
            let span = k1.time_s - k0.time_s;
            let u = if span > 0.0 {
                (t - k0.time_s) / span
            } else {
                1.0
            };
            (k0, k1, u)
        };
        // Smoothstep easing: the camera starts and stops at each keyframe without a jolt.
        let e = u * u * (3.0 - 2.0 * u);
        let lerp = |a: f64, b: f64| a + (b - a) * e;
        s.camera.position = [0, 1, 2].map(|i| lerp(k0.position[i], k1.position[i]));
        // Yaw the short way round: the difference wrapped into [-180, 180).
        let dyaw = (k1.yaw_deg - k0.yaw_deg + 180.0).rem_euclid(360.0) - 180.0;
        s.camera.yaw_deg = k0.yaw_deg + dyaw * e;
        s.camera.pitch_deg = lerp(k0.pitch_deg, k1.pitch_deg);
        s
    }

    /// The scene with every optional field filled in: its TOML form lists every known key.
    pub(crate) fn schema() -> Self {
        let mut scene = Self::default();
        scene.sun.direction = Some([0.0, 1.0, 0.0]);
        scene.quality.step_length_m = Some(100.0);
        scene.camera.orientation = Some(Orientation {
            forward: [0.0, 0.0, 1.0],
            right: [1.0, 0.0, 0.0],
            up: [0.0, 1.0, 0.0],
        });
        scene.animation = Some(Animation::default());
        scene.clouds.layers = vec![CloudLayer::default()];
        scene.sky = Sky {
            date_utc: "2000-01-01T12:00:00Z".parse().ok(),
            latitude_deg: Some(0.0),
            longitude_deg: Some(0.0),
        };
        // Fields left out when they hold their defaults must still be in the schema.
        scene.atmosphere.sky = SkyModel::Physical;
        scene.atmosphere.light_shafts = true;
        scene.camera.auto_exposure = true;
        scene.atmosphere.air.ground_albedo = 0.5;
        scene.camera.exposure_range = Some([1.0, 1.0]);
        scene.post.kuwahara = true;
        scene.rainbow.moisture = 1.0;
        scene.night.moon_msaa = true;
        scene.precipitation.particles = 1.0;
        scene.lightning.flashes_per_minute = 1.0;
        scene.clouds.convective_cells = 0.5;
        scene.clouds.anvil = 1.0;
        scene.clouds.anvil_shear_m = 1.0;
        scene.clouds.cirrus = 1.0;
        scene.clouds.layers[0].cirrus = 1.0;
        scene.clouds.cellular = 1.0;
        scene.clouds.cell_rolls = 1.0;
        scene.clouds.layers[0].cellular = 1.0;
        scene.clouds.close_detail = 1.0;
        scene.clouds.close_detail_scale = 8;
        scene.clouds.close_detail_range_m = 500.0;
        scene.quality.close_step_m = 10.0;
        scene
    }

    /// Every cloud layer as `(bottom, top)` altitudes in metres: the main one first, then the
    /// extra ones in file order.
    pub fn layer_altitudes(&self) -> Vec<(f64, f64)> {
        let main = (self.atmosphere.cloud_bottom_m, self.atmosphere.cloud_top_m);
        std::iter::once(main)
            .chain(self.clouds.layers.iter().map(|l| (l.bottom_m, l.top_m)))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn animated() -> Scene {
        Scene {
            animation: Some(Animation {
                duration_s: 4.0,
                keyframes: vec![
                    Keyframe {
                        time_s: 0.0,
                        position: [0.0, 100.0, 0.0],
                        yaw_deg: 350.0,
                        pitch_deg: 0.0,
                    },
                    Keyframe {
                        time_s: 2.0,
                        position: [200.0, 300.0, 0.0],
                        yaw_deg: 10.0,
                        pitch_deg: 20.0,
                    },
                ],
            }),
            ..Scene::default()
        }
    }

    #[test]
    fn the_camera_follows_its_keyframes_and_holds_outside_them() {
        let s = animated();
        let at = |t: f64| s.at_time(t).camera;
        assert_eq!(at(0.0).position, [0.0, 100.0, 0.0]);
        assert_eq!(at(-1.0).position, [0.0, 100.0, 0.0]);
        assert_eq!(at(2.0).position, [200.0, 300.0, 0.0]);
        assert_eq!(at(3.5).position, [200.0, 300.0, 0.0]);
        // Halfway (smoothstep(0.5) = 0.5); yaw the short way round, through north.
        let mid = at(1.0);
        assert_eq!(mid.position, [100.0, 200.0, 0.0]);
        assert!((mid.yaw_deg - 360.0).abs() < 1e-9, "{}", mid.yaw_deg);
        assert!((mid.pitch_deg - 10.0).abs() < 1e-9);
        // Eased: a quarter of the time covers less than a quarter of the way.
        assert!(at(0.5).position[0] < 50.0);
        // The wind moves with time.
        assert_eq!(s.at_time(3.0).clouds.time_s, s.clouds.time_s + 3.0);
    }

    #[test]
    fn temporal_modes_parse_and_name_themselves() {
        for t in Temporal::ALL {
            assert_eq!(t.name().parse::<Temporal>(), Ok(t));
        }
        assert_eq!(Temporal::Sixteenth.divisor(), 4);
        assert!(
            "1/8"
                .parse::<Temporal>()
                .unwrap_err()
                .contains("off, 1/4 or 1/16")
        );
    }
}
