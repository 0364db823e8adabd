//! Weather for Stratus: METAR reports and weather-service JSON mapped to weather states and
//! cloud layers, and smooth transitions between states.
//!
//! - [`metar::parse`] reads a METAR report; [`scene_from_metar`] turns it into a scene: the
//!   state its weather suggests ([`states`]), a cloud layer per cloud group, its wind, and
//!   ground fog from its visibility.
//! - [`scene_from_service_json`] does the same for seed 001's weather-service JSON
//!   (condition text and Beaufort wind class).
//! - [`haze`] turns a reported visibility, or a haze, smoke, dust or mist group, into the
//!   physical sky's aerosol (Koschmieder).
//! - [`states::WeatherParams::transition`] blends two states with smoothstep easing.

mod derive;
pub mod haze;
pub mod metar;
mod service;
pub mod states;

pub use derive::{Derived, scene_from_metar};
pub use service::scene_from_service_json;

/// Why weather input could not be turned into a scene.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum WeatherError {
    /// The METAR report is malformed (names the token and its position).
    #[error(transparent)]
    Metar(#[from] metar::MetarError),
    /// No weather state has this name.
    #[error("unknown weather state `{name}`: the states are {known}")]
    UnknownState {
        /// The name asked for.
        name: String,
        /// The known names, comma-separated.
        known: String,
    },
    /// The weather-service JSON is malformed or lacks a field.
    #[error("weather JSON: {0}")]
    Json(String),
}

/// Parses METAR `report` and derives its scene on `base`.
pub fn scene_from_metar_text(
    report: &str,
    base: &stratus_scene::Scene,
) -> Result<Derived, WeatherError> {
    let m = metar::parse(report)?;
    Ok(scene_from_metar(&m, base))
}
