//! Scene description for Stratus, a real-time volumetric cloud renderer (the cloud model of
//! Högfeldt's Frostbite thesis and Horizon Zero Dawn).
//!
//! A [`Scene`] says everything one frame needs: camera, sun, planet and cloud layer, the cloud
//! model's parameters, noise, lighting and ray-marching quality. Scenes are TOML files:
//!
//! ```toml
//! base = "sunset"          # inherit a preset (default: "cumulus-noon")
//!
//! [clouds]
//! coverage = 0.6
//!
//! [camera]
//! resolution = [1280, 720]
//! ```
//!
//! A file states only what differs from its base; the base's tables are deep-merged with the
//! file's. Loading reports *every* problem at once, each located in the file and naming the
//! field path: syntax errors, unknown fields (with a "did you mean"), wrong types and broken
//! validation rules ([`SceneError`]).
//!
//! Coordinates: X east, Y up, Z north, metres; the world origin is on the ground below the
//! camera's x/z = 0. Angles are degrees, colours linear RGB.
//!
//! [`Scene::uniforms`] packs a scene into [`FrameUniforms`], the uniform block the WGSL reads;
//! [`Scene::sun_direction`], [`Scene::camera_basis`] and [`Scene::wind_offsets`] are the same
//! derived quantities in f64, for the CPU reference.
//!
//! ```
//! use stratus_scene::Scene;
//!
//! let scene = Scene::from_toml_str("base = \"storm\"\n[clouds]\ncoverage = 0.95\n", "my.toml")?;
//! assert_eq!(scene.clouds.coverage, 0.95);
//!
//! let err = Scene::from_toml_str("[clouds]\ncovrage = 1\n", "bad.toml").unwrap_err();
//! assert_eq!(
//!     err.to_string(),
//!     "bad.toml:2:1: unknown field clouds.covrage; did you mean clouds.coverage?"
//! );
//! # Ok::<(), stratus_scene::SceneError>(())
//! ```

#![warn(missing_docs)]

mod error;
pub mod lightning;
mod load;
mod presets;
mod scene;
mod text;
mod uniforms;
mod validate;

pub use error::{Location, Problem, ProblemKind, SceneError};
pub use presets::{DEFAULT_PRESET, PresetInfo, presets};
pub use scene::{
    Air, Animation, Atmosphere, CELLULAR_ROLL, Camera, CloudLayer, Clouds, DEFAULT_CIRRUS_DENSITY,
    DEFAULT_CLOSE_DETAIL_RANGE_M, DEFAULT_CLOSE_DETAIL_SCALE, DEFAULT_CLOSE_STEP_M, HeightModel,
    Integration, Integrator, Keyframe, Lighting, Lightning, MAX_CLOSE_STEPS, MAX_EXTRA_LAYERS,
    Method, MultipleScattering, Night, Noise, Orientation, Phase, PhaseModel, Post, Precipitation,
    PrecipitationKind, Quality, Rainbow, Scene, ShapeTexture, Sky, SkyModel, Sun, Temporal,
};
pub use uniforms::{FrameUniforms, UniformMember};
pub use validate::{MAX_LIGHT_STEPS, MAX_OCTAVE_A, MAX_OCTAVES, MAX_RESOLUTION, MAX_VIEW_STEPS};
