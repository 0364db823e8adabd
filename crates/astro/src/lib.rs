//! Astronomy for Stratus: where the sun and moon stand in the sky of a place at a UTC
//! date-time, how much of the moon is lit, and when the sun rises and sets.
//!
//! Positions are geometric (no refraction: the sun at the horizon reads 0 degrees, where the
//! eye sees it about 0.57 degrees higher) and topocentric (seen from the place, not Earth's
//! centre: the moon's parallax reaches a degree). Azimuths run clockwise from north. The
//! series are Meeus's (*Astronomical Algorithms*, 2nd ed., 1998; see [`ephemeris`]). Against
//! astropy over 600 random instants (1950-2100) and places (`cargo xtask ephemeris-check`,
//! values stored in `tests/data/ephemeris.json`): the sun within 0.011 degrees, the moon within
//! 0.026 degrees, its illuminated fraction within 0.0002, and sunrise and sunset within 4 s.

#![deny(missing_docs)]

pub mod celestial;
pub mod ephemeris;
pub mod stars;
mod time;

pub use ephemeris::Horizontal;
pub use time::{UtcDateTime, YEARS, delta_t};

/// Everything that can go wrong, each naming the value.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum AstroError {
    /// A date-time that cannot be read or is out of range.
    #[error("{0}")]
    Date(String),
    /// A latitude or longitude out of range.
    #[error("{0}")]
    Place(String),
}

/// A place on Earth (at sea level on the WGS 84 ellipsoid).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Place {
    /// Geodetic latitude in degrees, north positive, within [-90, 90].
    pub latitude_deg: f64,
    /// Longitude in degrees, east positive, within [-180, 360).
    pub longitude_deg: f64,
}

impl Place {
    /// A checked place.
    pub fn new(latitude_deg: f64, longitude_deg: f64) -> Result<Self, AstroError> {
        if !(-90.0..=90.0).contains(&latitude_deg) {
            return Err(AstroError::Place(format!(
                "latitude {latitude_deg} is outside [-90, 90] degrees"
            )));
        }
        if !(-180.0..360.0).contains(&longitude_deg) {
            return Err(AstroError::Place(format!(
                "longitude {longitude_deg} is outside [-180, 360) degrees (east positive)"
            )));
        }
        Ok(Self {
            latitude_deg,
            longitude_deg,
        })
    }
}

/// The sun seen from `place` at `t`.
pub fn sun(place: Place, t: UtcDateTime) -> Horizontal {
    ephemeris::horizontal(
        t,
        ephemeris::sun(t),
        place.latitude_deg,
        place.longitude_deg,
    )
}

/// The moon seen from `place` at `t`.
pub fn moon(place: Place, t: UtcDateTime) -> Horizontal {
    ephemeris::horizontal(
        t,
        ephemeris::moon(t),
        place.latitude_deg,
        place.longitude_deg,
    )
}

/// The moon's illuminated fraction at `t`: 0 new, 1 full.
pub fn moon_phase(t: UtcDateTime) -> f64 {
    ephemeris::moon_illuminated_fraction(t)
}

/// The debug readout of a place and instant (seed 001's "city, date, place, weather state,
/// sunrise and sunset times and moon phase", less what the caller knows): the sun's elevation
/// and azimuth, that local day's sunrise and sunset as clock times at `utc_offset_h` hours from
/// UTC, and how much of the moon is lit.
pub fn readout(place: Place, t: UtcDateTime, utc_offset_h: f64) -> String {
    let s = sun(place, t);
    let day = sun_events(place, t);
    let clock = |e: Option<UtcDateTime>| {
        e.map_or_else(
            || "none".to_string(),
            |e| {
                let (_, _, _, h, m, _) = e.plus_seconds(utc_offset_h * 3600.0).calendar();
                format!("{h:02}:{m:02}")
            },
        )
    };
    let zone = if utc_offset_h == 0.0 {
        "UTC".to_string()
    } else {
        format!("UTC{utc_offset_h:+}")
    };
    let day_text = match (day.sunrise, day.sunset) {
        (None, None) if day.always_up => "polar day".to_string(),
        (None, None) => "polar night".to_string(),
        (rise, set) => format!("sunrise {} and sunset {} ({zone})", clock(rise), clock(set)),
    };
    format!(
        "sun elevation {:.2} deg, azimuth {:.2} deg; {day_text}; moon {:.0}% lit",
        s.elevation_deg,
        s.azimuth_deg,
        100.0 * moon_phase(t)
    )
}

/// The sun's geometric elevation at sunrise and sunset: its upper limb on the horizon, with
/// the standard 34' of refraction and 16' of semi-diameter (-0.833 degrees, as almanacs use).
pub const SUNRISE_ELEVATION_DEG: f64 = -0.833;

/// Sunrise and sunset of one local day.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DayEvents {
    /// When the day (local mean solar time: UTC + longitude / 15 hours) begins.
    pub day_start: UtcDateTime,
    /// The sun's rise that day, if it rises.
    pub sunrise: Option<UtcDateTime>,
    /// The sun's setting that day, if it sets.
    pub sunset: Option<UtcDateTime>,
    /// Without a rise or a set: whether the sun stays up (polar day) or down (polar night).
    pub always_up: bool,
}

/// Sunrise and sunset of the local solar day at `place` that holds `t` (the day runs from
/// midnight to midnight of local mean solar time, UTC + longitude / 15 hours), to the second.
pub fn sun_events(place: Place, t: UtcDateTime) -> DayEvents {
    let offset_s = place.longitude_deg.rem_euclid(360.0);
    let offset_s = if offset_s > 180.0 {
        offset_s - 360.0
    } else {
        offset_s
    } / 15.0
        * 3600.0;
    let day_start = t.local_midnight(offset_s);
    let height =
        |s: f64| sun(place, day_start.plus_seconds(s)).elevation_deg - SUNRISE_ELEVATION_DEG;
    // Sample every 10 minutes (the sun's elevation has at most two crossings a day), then
    // bisect each crossing to a second.
    const STEP_S: f64 = 600.0;
    let samples: Vec<(f64, f64)> = (0..=144)
        .map(|i| {
            let s = f64::from(i) * STEP_S;
            (s, height(s))
        })
        .collect();
    let (mut sunrise, mut sunset) = (None, None);
    for w in samples.windows(2) {
        let ((s0, h0), (s1, h1)) = (w[0], w[1]);
        if (h0 < 0.0) == (h1 < 0.0) {
            continue;
        }
        let rising = h1 >= 0.0;
        let (mut a, mut b) = (s0, s1);
        while b - a > 0.5 {
            let mid = 0.5 * (a + b);
            if (height(mid) >= 0.0) == rising {
                b = mid;
            } else {
                a = mid;
            }
        }
        let at = day_start.plus_seconds(0.5 * (a + b));
        if rising && sunrise.is_none() {
            sunrise = Some(at);
        } else if !rising && sunset.is_none() {
            sunset = Some(at);
        }
    }
    DayEvents {
        day_start,
        sunrise,
        sunset,
        always_up: samples[72].1 >= 0.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(s: &str) -> UtcDateTime {
        s.parse().unwrap()
    }

    #[test]
    fn the_sun_at_noon_on_the_equinox_stands_at_the_colatitude() {
        // Greenwich, 2026-03-20 12:07 UTC (near local apparent noon on the equinox): elevation
        // about 90 - 51.48 = 38.5 degrees, due south.
        let p = Place::new(51.4769, 0.0).unwrap();
        let s = sun(p, at("2026-03-20T12:07:00Z"));
        assert!((s.elevation_deg - 38.5).abs() < 0.5, "{s:?}");
        assert!((s.azimuth_deg - 180.0).abs() < 1.0, "{s:?}");
    }

    #[test]
    fn midsummer_in_stockholm_has_a_short_night_and_tromso_none() {
        let stockholm = Place::new(59.33, 18.07).unwrap();
        let e = sun_events(stockholm, at("2026-06-21T18:30:00Z"));
        let (rise, set) = (e.sunrise.unwrap(), e.sunset.unwrap());
        // Almanacs: sunrise 01:31 UTC, sunset 20:08 UTC (03:31 and 22:08 CEST).
        assert!(rise.to_string().starts_with("2026-06-21T01:3"), "{rise}");
        assert!(set.to_string().starts_with("2026-06-21T20:0"), "{set}");
        let tromso = Place::new(69.65, 18.96).unwrap();
        let e = sun_events(tromso, at("2026-06-21T12:00:00Z"));
        assert!(e.sunrise.is_none() && e.sunset.is_none() && e.always_up);
        let e = sun_events(tromso, at("2026-12-21T12:00:00Z"));
        assert!(e.sunrise.is_none() && e.sunset.is_none() && !e.always_up);
    }

    #[test]
    fn the_moon_is_full_and_new_when_the_almanac_says() {
        // Full moon 2026-03-03 11:38 UTC (a total lunar eclipse); new moon 2026-03-19 01:23.
        assert!(moon_phase(at("2026-03-03T11:38:00Z")) > 0.995);
        assert!(moon_phase(at("2026-03-19T01:23:00Z")) < 0.005);
        let quarter = moon_phase(at("2026-03-11T09:38:00Z"));
        assert!((quarter - 0.5).abs() < 0.05, "{quarter}");
    }

    #[test]
    fn east_longitudes_past_180_are_the_west_ones() {
        // [-180, 360) is accepted: 200 east is 160 west, for positions and for the local day.
        let t = at("2031-02-03T04:05:06Z");
        let (a, b) = (
            Place::new(-33.9, 200.0).unwrap(),
            Place::new(-33.9, -160.0).unwrap(),
        );
        let (sa, sb) = (sun(a, t), sun(b, t));
        assert!(
            (sa.elevation_deg - sb.elevation_deg).abs() < 1e-9,
            "{sa:?} {sb:?}"
        );
        assert!(
            (sa.azimuth_deg - sb.azimuth_deg).abs() < 1e-9,
            "{sa:?} {sb:?}"
        );
        let (ma, mb) = (moon(a, t), moon(b, t));
        assert!((ma.elevation_deg - mb.elevation_deg).abs() < 1e-9);
        assert_eq!(sun_events(a, t), sun_events(b, t));
    }

    #[test]
    fn places_out_of_range_are_named() {
        assert!(
            Place::new(91.0, 0.0)
                .unwrap_err()
                .to_string()
                .contains("latitude 91")
        );
        assert!(
            Place::new(0.0, 400.0)
                .unwrap_err()
                .to_string()
                .contains("longitude 400")
        );
    }
}
