//! The debug readout: the sun, the day's sunrise and sunset on a local clock, the moon.

use stratus_astro::{Place, UtcDateTime, readout};

#[test]
fn the_readout_gives_the_sun_the_local_day_and_the_moon() {
    // Hangzhou, 2023-03-24 20:20 local (UTC+8): after dark, two days past new moon.
    let at = Place::new(30.2741, 120.1551).unwrap();
    let t: UtcDateTime = "2023-03-24T12:20:00Z".parse().unwrap();
    let text = readout(at, t, 8.0);
    assert!(text.starts_with("sun elevation -27."), "{text}");
    assert!(
        text.contains("sunrise 05:59 and sunset 18:12 (UTC+8)"),
        "{text}"
    );
    assert!(text.ends_with("moon 10% lit"), "{text}");
    // The same instant on a UTC clock, and the polar night at the North Pole in December.
    assert!(readout(at, t, 0.0).contains("sunrise 21:59 and sunset 10:12 (UTC)"));
    let pole = Place::new(89.9, 0.0).unwrap();
    let winter: UtcDateTime = "2026-12-21T12:00:00Z".parse().unwrap();
    assert!(readout(pole, winter, 0.0).contains("polar night"));
}
