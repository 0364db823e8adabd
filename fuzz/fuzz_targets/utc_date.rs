//! UTC date-times (`[sky] date_utc`, `stratus astro --date`) on arbitrary text: errors, never
//! panics; a date that reads prints back to text that reads as the same instant; and the sun,
//! the moon, the phase and the day's sunrise and sunset come out finite for it at a place the
//! input also picks.
#![no_main]

use libfuzzer_sys::fuzz_target;
use stratus_astro::{Place, UtcDateTime};

fuzz_target!(|data: &[u8]| {
    // The first two bytes pick the place; the rest is the date's text.
    let (place, text) = match data {
        [a, b, rest @ ..] => (
            Place::new(
                f64::from(*a) / 255.0 * 180.0 - 90.0,
                f64::from(*b) / 256.0 * 540.0 - 180.0,
            ),
            rest,
        ),
        _ => return,
    };
    let Ok(text) = std::str::from_utf8(text) else {
        return;
    };
    let Ok(t) = text.parse::<UtcDateTime>() else {
        return;
    };
    let printed = t.to_string();
    let again: UtcDateTime = printed
        .parse()
        .unwrap_or_else(|e| panic!("{text:?} printed as {printed:?}, which does not read: {e}"));
    assert_eq!(again.to_string(), printed, "{text:?}");
    let place = place.expect("the place is in range by construction");
    let (sun, moon) = (stratus_astro::sun(place, t), stratus_astro::moon(place, t));
    for v in [
        sun.elevation_deg,
        sun.azimuth_deg,
        moon.elevation_deg,
        moon.azimuth_deg,
        stratus_astro::moon_phase(t),
    ] {
        assert!(v.is_finite(), "{text:?} at {place:?}: {v}");
    }
    let day = stratus_astro::sun_events(place, t);
    for e in [day.sunrise, day.sunset].into_iter().flatten() {
        // Inside the local day, and printable.
        let s = e.seconds_since(day.day_start);
        assert!((0.0..=86_400.0).contains(&s), "{text:?} at {place:?}: {s}");
        let _ = e.to_string();
    }
});
