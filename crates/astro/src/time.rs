//! UTC date-times: parsing ISO 8601, Julian days, and the difference between Terrestrial Time
//! (what the ephemerides are written in) and UTC.

use std::{fmt, str::FromStr};

use crate::AstroError;

/// Seconds in a day.
const DAY_S: f64 = 86_400.0;

/// The years the ephemerides are used for: their series are fitted to observations of a few
/// centuries around 2000 (Meeus, *Astronomical Algorithms*, 2nd ed., 1998, ch. 25 and 47).
pub const YEARS: std::ops::RangeInclusive<i32> = 1800..=2200;

/// A UTC date-time of the proleptic Gregorian calendar, to the millisecond or finer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UtcDateTime {
    /// Julian day of the instant (UTC).
    jd: f64,
}

impl UtcDateTime {
    /// The instant `year-month-day hour:minute:second` UTC, checked.
    pub fn new(
        year: i32,
        month: u32,
        day: u32,
        hour: u32,
        minute: u32,
        second: f64,
    ) -> Result<Self, AstroError> {
        let bad = |what: &str| AstroError::Date(format!("{what} is out of range"));
        if !YEARS.contains(&year) {
            return Err(AstroError::Date(format!(
                "year {year} is outside {}-{}, the years the ephemerides hold for",
                YEARS.start(),
                YEARS.end()
            )));
        }
        if !(1..=12).contains(&month) {
            return Err(bad(&format!("month {month}")));
        }
        if day < 1 || day > days_in_month(year, month) {
            return Err(bad(&format!("day {day} of {year}-{month:02}")));
        }
        if hour > 23 {
            return Err(bad(&format!("hour {hour}")));
        }
        if minute > 59 {
            return Err(bad(&format!("minute {minute}")));
        }
        // A leap second's label (60) is refused: this time scale has no room for it, and
        // counting it as the next minute could step past the last year.
        if !(0.0..60.0).contains(&second) {
            return Err(bad(&format!("second {second}")));
        }
        let fraction = (f64::from(hour) * 3600.0 + f64::from(minute) * 60.0 + second) / DAY_S;
        Ok(Self {
            jd: julian_day(year, month, f64::from(day) + fraction),
        })
    }

    /// The instant at Julian day `jd` (UTC).
    pub fn from_julian_day(jd: f64) -> Self {
        Self { jd }
    }

    /// The Julian day (UTC).
    pub fn julian_day(self) -> f64 {
        self.jd
    }

    /// The Julian Ephemeris Day (Terrestrial Time): UTC plus [`delta_t`].
    pub fn julian_ephemeris_day(self) -> f64 {
        self.jd + delta_t(self.decimal_year()) / DAY_S
    }

    /// `seconds` later (earlier if negative).
    pub fn plus_seconds(self, seconds: f64) -> Self {
        Self {
            jd: self.jd + seconds / DAY_S,
        }
    }

    /// Seconds from `other` to `self`.
    pub fn seconds_since(self, other: Self) -> f64 {
        (self.jd - other.jd) * DAY_S
    }

    /// The calendar date and time: `(year, month, day, hour, minute, second)`.
    pub fn calendar(self) -> (i32, u32, u32, u32, u32, f64) {
        // Meeus, ch. 7: Julian day to calendar date.
        let z = (self.jd + 0.5).floor();
        let f = self.jd + 0.5 - z;
        let alpha = ((z - 1_867_216.25) / 36_524.25).floor();
        let a = z + 1.0 + alpha - (alpha / 4.0).floor();
        let b = a + 1524.0;
        let c = ((b - 122.1) / 365.25).floor();
        let d = (365.25 * c).floor();
        let e = ((b - d) / 30.6001).floor();
        let day = (b - d - (30.6001 * e).floor()) as u32;
        let month = if e < 14.0 { e - 1.0 } else { e - 13.0 } as u32;
        let year = if month > 2 { c - 4716.0 } else { c - 4715.0 } as i32;
        let seconds = f * DAY_S;
        let hour = (seconds / 3600.0).floor().min(23.0);
        let minute = ((seconds - hour * 3600.0) / 60.0).floor().min(59.0);
        let second = seconds - hour * 3600.0 - minute * 60.0;
        (year, month, day, hour as u32, minute as u32, second)
    }

    /// The year with its fraction (for [`delta_t`]).
    fn decimal_year(self) -> f64 {
        2000.0 + (self.jd - 2_451_544.5) / 365.2425
    }

    /// Midnight UTC starting the calendar day that holds `self + offset_s`, minus `offset_s`:
    /// the start of a local day whose clock runs `offset_s` ahead of UTC.
    pub fn local_midnight(self, offset_s: f64) -> Self {
        let shifted = self.jd + offset_s / DAY_S;
        Self {
            jd: (shifted - 0.5).floor() + 0.5 - offset_s / DAY_S,
        }
    }
}

impl fmt::Display for UtcDateTime {
    /// ISO 8601 to the millisecond: `2026-06-21T18:30:00Z`, `2026-06-21T18:30:00.250Z`. Read
    /// back, it gives the same instant (dates are read to the millisecond).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // Whole milliseconds since the Julian day count's noon-to-midnight shift: exact in f64
        // (2e14 < 2^53), and the 40 us the Julian day's own precision allows round away.
        const DAY_MS: i64 = 86_400_000;
        let total = ((self.jd + 0.5) * DAY_MS as f64).round() as i64;
        let (day, ms) = (total.div_euclid(DAY_MS), total.rem_euclid(DAY_MS));
        let (y, mo, d, ..) = Self {
            jd: day as f64 - 0.5,
        }
        .calendar();
        let (h, mi, sec, frac) = (ms / 3_600_000, ms / 60_000 % 60, ms / 1000 % 60, ms % 1000);
        write!(f, "{y:04}-{mo:02}-{d:02}T{h:02}:{mi:02}:{sec:02}")?;
        if frac != 0 {
            write!(f, ".{frac:03}")?;
        }
        f.write_str("Z")
    }
}

impl FromStr for UtcDateTime {
    type Err = AstroError;

    /// ISO 8601 in UTC: `YYYY-MM-DDTHH:MM[:SS[.fff]]` ending in `Z` or `+00:00` (a space may
    /// stand for the `T`). Fractions of a second are read to the millisecond (further digits
    /// are dropped).
    fn from_str(text: &str) -> Result<Self, AstroError> {
        let expected = || {
            AstroError::Date(format!(
                "{text:?} is not a UTC date-time; expected ISO 8601 like 2026-06-21T18:30:00Z"
            ))
        };
        let body = text
            .strip_suffix('Z')
            .or_else(|| text.strip_suffix("+00:00"))
            .ok_or_else(|| {
                AstroError::Date(format!(
                    "{text:?} does not end in `Z` (UTC); expected ISO 8601 like 2026-06-21T18:30:00Z"
                ))
            })?;
        let (date, time) = body.split_once(['T', ' ']).ok_or_else(expected)?;
        let mut d = date.splitn(3, '-');
        let number = |s: Option<&str>, digits: usize| -> Result<u32, AstroError> {
            let s = s.ok_or_else(expected)?;
            if s.len() != digits || !s.bytes().all(|b| b.is_ascii_digit()) {
                return Err(expected());
            }
            s.parse().map_err(|_| expected())
        };
        let year = number(d.next(), 4)? as i32;
        let month = number(d.next(), 2)?;
        let day = number(d.next(), 2)?;
        let mut t = time.splitn(3, ':');
        let hour = number(t.next(), 2)?;
        let minute = number(t.next(), 2)?;
        let second = match t.next() {
            None => 0.0,
            Some(s) => {
                let (whole, frac) = s.split_once('.').unwrap_or((s, ""));
                let whole = number(Some(whole), 2)?;
                // A dot needs digits after it.
                if !frac.bytes().all(|b| b.is_ascii_digit()) || (frac.is_empty() && s.contains('.'))
                {
                    return Err(expected());
                }
                let frac: f64 = if frac.is_empty() {
                    0.0
                } else {
                    let ms = &frac[..frac.len().min(3)];
                    format!("0.{ms}").parse().map_err(|_| expected())?
                };
                f64::from(whole) + frac
            }
        };
        Self::new(year, month, day, hour, minute, second)
    }
}

impl serde::Serialize for UtcDateTime {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.to_string())
    }
}

impl<'de> serde::Deserialize<'de> for UtcDateTime {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let text = String::deserialize(d)?;
        text.parse().map_err(serde::de::Error::custom)
    }
}

fn leap(year: i32) -> bool {
    (year % 4 == 0 && year % 100 != 0) || year % 400 == 0
}

fn days_in_month(year: i32, month: u32) -> u32 {
    match month {
        1 | 3 | 5 | 7 | 8 | 10 | 12 => 31,
        4 | 6 | 9 | 11 => 30,
        _ if leap(year) => 29,
        _ => 28,
    }
}

/// Julian day of a Gregorian calendar date, `day` with its fraction (Meeus, ch. 7).
fn julian_day(year: i32, month: u32, day: f64) -> f64 {
    let (y, m) = if month <= 2 {
        (f64::from(year - 1), f64::from(month + 12))
    } else {
        (f64::from(year), f64::from(month))
    };
    let a = (y / 100.0).floor();
    let b = 2.0 - a + (a / 4.0).floor();
    (365.25 * (y + 4716.0)).floor() + (30.6001 * (m + 1.0)).floor() + day + b - 1524.5
}

/// TT - UTC in seconds: the polynomials of Espenak and Meeus ("Five Millennium Canon of Solar
/// Eclipses", NASA/TP-2006-214141), good to a second over 1900-2050 and to about a minute at
/// the ends of [`YEARS`]. A minute moves the moon 0.01 degrees.
pub fn delta_t(year: f64) -> f64 {
    let u = (year - 1820.0) / 100.0;
    match year {
        y if y < 1860.0 => {
            let t = y - 1800.0;
            13.72 - 0.332447 * t + 0.0068612 * t.powi(2) + 0.0041116 * t.powi(3)
                - 0.00037436 * t.powi(4)
                + 0.0000121272 * t.powi(5)
                - 0.0000001699 * t.powi(6)
                + 0.000000000875 * t.powi(7)
        }
        y if y < 1900.0 => {
            let t = y - 1860.0;
            7.62 + 0.5737 * t - 0.251754 * t.powi(2) + 0.01680668 * t.powi(3)
                - 0.0004473624 * t.powi(4)
                + t.powi(5) / 233174.0
        }
        y if y < 1920.0 => {
            let t = y - 1900.0;
            -2.79 + 1.494119 * t - 0.0598939 * t.powi(2) + 0.0061966 * t.powi(3)
                - 0.000197 * t.powi(4)
        }
        y if y < 1941.0 => {
            let t = y - 1920.0;
            21.20 + 0.84493 * t - 0.076100 * t.powi(2) + 0.0020936 * t.powi(3)
        }
        y if y < 1961.0 => {
            let t = y - 1950.0;
            29.07 + 0.407 * t - t.powi(2) / 233.0 + t.powi(3) / 2547.0
        }
        y if y < 1986.0 => {
            let t = y - 1975.0;
            45.45 + 1.067 * t - t.powi(2) / 260.0 - t.powi(3) / 718.0
        }
        y if y < 2005.0 => {
            let t = y - 2000.0;
            63.86 + 0.3345 * t - 0.060374 * t.powi(2)
                + 0.0017275 * t.powi(3)
                + 0.000651814 * t.powi(4)
                + 0.00002373599 * t.powi(5)
        }
        y if y < 2050.0 => {
            let t = y - 2000.0;
            62.92 + 0.32217 * t + 0.005589 * t.powi(2)
        }
        y if y < 2150.0 => -20.0 + 32.0 * u * u - 0.5628 * (2150.0 - y),
        _ => -20.0 + 32.0 * u * u,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn julian_days_of_known_dates() {
        // Meeus, ch. 7: 2000 January 1.5 is JD 2451545.0; 1957 October 4.81 is 2436116.31.
        let j2000 = UtcDateTime::new(2000, 1, 1, 12, 0, 0.0).unwrap();
        assert_eq!(j2000.julian_day(), 2_451_545.0);
        let sputnik = julian_day(1957, 10, 4.81);
        assert!((sputnik - 2_436_116.31).abs() < 1e-9);
    }

    #[test]
    fn parse_print_and_calendar_round_trip() {
        let t: UtcDateTime = "2026-06-21T18:30:00Z".parse().unwrap();
        assert_eq!(t.to_string(), "2026-06-21T18:30:00Z");
        assert_eq!(t.calendar().0, 2026);
        let t: UtcDateTime = "2024-02-29 23:59:59.7+00:00".parse().unwrap();
        assert_eq!(t.to_string(), "2024-02-29T23:59:59.700Z");
        // Read to the millisecond, printed back the same, at the very end of the range too.
        let t: UtcDateTime = "2200-12-31T23:59:59.99987Z".parse().unwrap();
        assert_eq!(t.to_string(), "2200-12-31T23:59:59.999Z");
        assert_eq!(t.to_string().parse::<UtcDateTime>().unwrap(), t);
        assert_eq!(t.plus_seconds(0.001).to_string(), "2201-01-01T00:00:00Z");
        assert_eq!(
            "2026-06-21T18:30Z".parse::<UtcDateTime>().unwrap(),
            "2026-06-21T18:30:00Z".parse().unwrap()
        );
    }

    #[test]
    fn bad_dates_are_named() {
        for (text, says) in [
            ("2026-06-21T18:30:00", "does not end in `Z`"),
            ("2026-06-21T18:30:00+02:00", "does not end in `Z`"),
            ("2026-13-01T00:00:00Z", "month 13"),
            ("2025-02-29T00:00:00Z", "day 29 of 2025-02"),
            ("2026-06-21T24:00:00Z", "hour 24"),
            ("2200-12-31T23:59:60Z", "second 60"),
            ("1500-01-01T00:00:00Z", "year 1500"),
            ("21/06/2026 18:30Z", "expected ISO 8601"),
            ("2026-6-21T18:30:00Z", "expected ISO 8601"),
            ("2026-06-21T18:30:00.Z", "expected ISO 8601"),
            ("", "does not end in `Z`"),
        ] {
            let e = text.parse::<UtcDateTime>().unwrap_err().to_string();
            assert!(e.contains(says), "{text:?}: {e}");
        }
    }

    #[test]
    fn local_midnight_starts_the_local_day() {
        let t: UtcDateTime = "2026-06-21T23:30:00Z".parse().unwrap();
        // Three hours ahead of UTC it is already the 22nd: that day began at 21:00 UTC.
        assert_eq!(
            t.local_midnight(3.0 * 3600.0).to_string(),
            "2026-06-21T21:00:00Z"
        );
        assert_eq!(t.local_midnight(0.0).to_string(), "2026-06-21T00:00:00Z");
    }

    #[test]
    fn delta_t_is_continuous_enough_and_near_the_measured() {
        // Measured TT - UTC: 63.8 s in 2000, 69.4 s in 2020 (IERS); the 2005-2050 polynomial
        // gives 71.6 s for 2020 (it was fitted before the Earth's rotation sped up).
        assert!((delta_t(2000.0) - 63.8).abs() < 1.0);
        assert!((delta_t(2020.0) - 69.4).abs() < 2.5);
        for y in (1801..2199).map(f64::from) {
            let jump = (delta_t(y + 1e-6) - delta_t(y - 1e-6)).abs();
            assert!(jump < 5.0, "{y}: {jump}");
        }
    }
}
