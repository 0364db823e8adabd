//! `stratus astro` as a user runs it: the JSON the sky issue asks for, with values a nautical
//! almanac agrees with, and clear errors for a bad date or place.

mod common;

use common::stratus;

#[test]
fn astro_prints_the_sun_moon_and_day_as_json() {
    let (ok, text) = stratus(&[
        "astro",
        "--date",
        "2026-06-21T18:30:00Z",
        "--lat",
        "59.33",
        "--lon",
        "18.07",
    ]);
    assert!(ok, "{text}");
    let json: serde_json::Value = serde_json::from_str(&text).expect("JSON");
    let num = |p: &str| {
        json.pointer(p)
            .and_then(serde_json::Value::as_f64)
            .unwrap_or_else(|| panic!("{p} in {text}"))
    };
    // Midsummer evening in Stockholm: the sun low in the north-west.
    assert!((num("/sun/elevation_deg") - 8.25).abs() < 0.05, "{text}");
    assert!((num("/sun/azimuth_deg") - 302.9).abs() < 0.1, "{text}");
    // First quarter falls that day: the moon about half lit.
    let phase = num("/moon/phase");
    assert!((0.4..0.6).contains(&phase), "{text}");
    assert!((0.0..360.0).contains(&num("/moon/azimuth_deg")), "{text}");
    assert!(
        (-90.0..=90.0).contains(&num("/moon/elevation_deg")),
        "{text}"
    );
    // Almanac: sunrise 03:31 CEST, sunset 22:08 CEST.
    let s = |p: &str| {
        json.pointer(p)
            .and_then(|v| v.as_str())
            .unwrap_or_default()
            .to_string()
    };
    assert!(s("/sunrise_utc").starts_with("2026-06-21T01:3"), "{text}");
    assert!(s("/sunset_utc").starts_with("2026-06-21T20:0"), "{text}");
    // The debug readout in one line: the same day on a UTC clock, and the moon.
    let readout = s("/readout");
    assert!(
        readout.contains("sunrise 01:3")
            && readout.contains("sunset 20:0")
            && readout.contains("% lit"),
        "{text}"
    );

    // South of the Antarctic circle in June: no sunrise, said so.
    let (ok, text) = stratus(&[
        "astro",
        "--date",
        "2026-06-21T12:00:00Z",
        "--lat",
        "-75",
        "--lon",
        "0",
    ]);
    assert!(ok, "{text}");
    assert!(
        text.contains("\"sunrise_utc\": null") && text.contains("polar night"),
        "{text}"
    );
}

#[test]
fn astro_names_a_bad_date_or_place() {
    let (ok, text) = stratus(&[
        "astro",
        "--date",
        "2026-06-21 18:30",
        "--lat",
        "0",
        "--lon",
        "0",
    ]);
    assert!(
        !ok && text.contains("--date") && text.contains("`Z`"),
        "{text}"
    );
    let (ok, text) = stratus(&[
        "astro",
        "--date",
        "2026-06-21T18:30:00Z",
        "--lat",
        "100",
        "--lon",
        "0",
    ]);
    assert!(!ok && text.contains("latitude 100"), "{text}");
}

#[test]
fn render_takes_the_sun_from_a_date_and_place() {
    let dir = std::env::temp_dir().join(format!("stratus-astro-render-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch dir");
    let out = dir.join("sun.png");
    let out = out.to_str().expect("utf-8 path");
    let (ok, text) = stratus(&[
        "render",
        "--date",
        "2026-06-21T17:30:00Z",
        "--lat",
        "59.33",
        "--lon",
        "18.07",
        "--size",
        "16x9",
        "--backend",
        "cpu",
        "--out",
        out,
    ]);
    assert!(ok, "{text}");
    // The sun `stratus astro` gives for that hour, low in the west-north-west.
    assert!(
        text.contains("sun: elevation 15.07 deg, azimuth 290.70 deg (from the date and place)"),
        "{text}"
    );
    let (ok, text) = stratus(&["render", "--date", "2026-06-21T17:30:00Z", "--lat", "59.33"]);
    assert!(!ok && text.contains("--lon"), "{text}");
    let _ = std::fs::remove_dir_all(&dir);
}
