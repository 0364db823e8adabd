//! `stratus astro`: the sun and moon seen from a place at a UTC date-time, the moon's phase,
//! and that day's sunrise and sunset, as JSON.

use anyhow::{Result, anyhow};
use clap::Args;
use stratus_astro::{Place, UtcDateTime};

/// Options of `stratus astro`.
#[derive(Args, Debug)]
pub struct AstroArgs {
    /// The instant, ISO 8601 in UTC, e.g. 2026-06-21T18:30:00Z (years 1800-2200).
    #[arg(long)]
    date: String,
    /// Geodetic latitude in degrees, north positive.
    #[arg(long, allow_hyphen_values = true)]
    lat: f64,
    /// Longitude in degrees, east positive.
    #[arg(long, allow_hyphen_values = true)]
    lon: f64,
}

fn round(v: f64, digits: i32) -> f64 {
    let k = 10f64.powi(digits);
    (v * k).round() / k
}

/// Runs `stratus astro`.
pub fn run(args: AstroArgs) -> Result<()> {
    let t: UtcDateTime = args.date.parse().map_err(|e| anyhow!("--date: {e}"))?;
    let place = Place::new(args.lat, args.lon).map_err(|e| anyhow!("--lat/--lon: {e}"))?;
    let sun = stratus_astro::sun(place, t);
    let moon = stratus_astro::moon(place, t);
    let day = stratus_astro::sun_events(place, t);
    let event = |e: Option<UtcDateTime>| e.map(|t| t.to_string());
    let json = serde_json::json!({
        "date_utc": t.to_string(),
        "latitude_deg": args.lat,
        "longitude_deg": args.lon,
        "sun": {
            "elevation_deg": round(sun.elevation_deg, 4),
            "azimuth_deg": round(sun.azimuth_deg, 4),
        },
        "moon": {
            "elevation_deg": round(moon.elevation_deg, 4),
            "azimuth_deg": round(moon.azimuth_deg, 4),
            "phase": round(stratus_astro::moon_phase(t), 4),
            "distance_km": round(moon.distance_km, 0),
        },
        "sunrise_utc": event(day.sunrise),
        "sunset_utc": event(day.sunset),
        "day": match (day.sunrise, day.sunset) {
            (None, None) if day.always_up => "polar day: the sun does not set",
            (None, None) => "polar night: the sun does not rise",
            _ => "the local solar day (UTC + longitude/15 h) holding the date",
        },
        "readout": stratus_astro::readout(place, t, 0.0),
        "notes": "elevations are geometric (no refraction); azimuths clockwise from north; sunrise and sunset put the sun's upper limb on the horizon (geometric elevation -0.833 degrees)",
    });
    println!("{}", serde_json::to_string_pretty(&json)?);
    Ok(())
}
