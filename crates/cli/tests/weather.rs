//! `stratus weather` and `--weather` as a user runs them: the acceptance commands, a
//! scene `stratus scene check` accepts, clear errors, and a weather transition that renders.
//! Validation is on (`STRATUS_VALIDATION=1`).

mod common;

use common::scratch;
use stratus_compare::Image;

fn stratus(args: &[&str]) -> (bool, String) {
    common::stratus_with(args, &[("STRATUS_VALIDATION", "1")])
}

const KJFK: &str = "KJFK 221651Z 31012G20KT 10SM FEW045 SCT120 BKN250 12/M02 A3012";

#[test]
fn a_report_with_three_cloud_groups_prints_three_layers_and_checks() {
    let (ok, text) = stratus(&["weather", KJFK]);
    assert!(ok, "{text}");
    assert!(text.contains("3 cloud layer(s)"), "{text}");
    // The main layer and two extra ones.
    assert_eq!(text.matches("[[clouds.layers]]").count(), 2, "{text}");
    let dir = scratch("weather-check");
    let file = dir.join("kjfk.toml");
    let (ok, out) = stratus(&["weather", KJFK, "--out", file.to_str().unwrap()]);
    assert!(ok, "{out}");
    let (ok, out) = stratus(&["scene", "check", file.to_str().unwrap()]);
    assert!(ok, "{out}");
}

#[test]
fn the_services_json_sets_the_citys_sky_and_prints_the_debug_readout() {
    // The weather service's JSON as the seed gives it: Hangzhou, read at 20:20 local time.
    let json = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../weather/tests/data/hangzhou.json"
    );
    let (ok, text) = stratus(&["weather", "--json", json, "--preset", "night"]);
    assert!(ok, "{text}");
    let sky = &text[text.find("[sky]").expect("a [sky] table")..];
    for line in [
        "date_utc = \"2023-03-24T12:20:00Z\"",
        "latitude_deg = 30.2741",
        "longitude_deg = 120.1551",
    ] {
        assert!(sky.contains(line), "{line}: {text}");
    }
    // The readout: city, place, time, state, sunrise and sunset, moon.
    for part in [
        "place: 杭州 (Hangzhou, 330100)",
        "state: scattered",
        "sunrise 05:59 and sunset 18:12 (UTC+8)",
        "moon 10% lit",
    ] {
        assert!(text.contains(part), "{part}: {text}");
    }
    let dir = scratch("weather-json");
    let file = dir.join("hangzhou.toml");
    let (ok, out) = stratus(&[
        "weather",
        "--json",
        json,
        "--preset",
        "night",
        "--out",
        file.to_str().unwrap(),
    ]);
    assert!(ok, "{out}");
    let (ok, out) = stratus(&[
        "render",
        "--scene",
        file.to_str().unwrap(),
        "--size",
        "32x18",
        "--out",
        dir.join("hz.png").to_str().unwrap(),
    ]);
    assert!(ok, "{out}");
}

#[test]
fn a_malformed_report_names_the_token() {
    let (ok, text) = stratus(&["weather", "KJFK 221651Z 31012KT 10SM XYZ999"]);
    assert!(!ok, "{text}");
    assert!(
        text.contains("XYZ999") && text.contains("character 26"),
        "{text}"
    );
    let (ok, text) = stratus(&["weather", "--state", "sunny"]);
    assert!(
        !ok && text.contains("sunny") && text.contains("overcast"),
        "{text}"
    );
}

#[test]
fn render_with_a_report_draws_its_layers() {
    let dir = scratch("weather-render");
    let with = dir.join("w.png");
    let (ok, text) = stratus(&[
        "render",
        "--weather",
        KJFK,
        "--size",
        "128x72",
        "--out",
        with.to_str().unwrap(),
    ]);
    assert!(ok, "{text}");
    assert!(text.contains("3 cloud layers"), "{text}");
    let without = dir.join("plain.png");
    let (ok, text) = stratus(&[
        "render",
        "--size",
        "128x72",
        "--out",
        without.to_str().unwrap(),
    ]);
    assert!(ok, "{text}");
    let (a, b) = (Image::load(&with).unwrap(), Image::load(&without).unwrap());
    assert_ne!(a.rgba, b.rgba, "the report's layers changed nothing");
}

#[test]
fn a_weather_transition_animates() {
    let dir = scratch("weather-animate");
    let out = dir.join("t.gif");
    let (ok, text) = stratus(&[
        "animate",
        "--from",
        "clear",
        "--to",
        "overcast",
        "--seconds",
        "0.2",
        "--fps",
        "10",
        "--size",
        "32x18",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(ok, "{text}");
    assert!(out.metadata().unwrap().len() > 0);
    let (ok, text) = stratus(&["animate", "--from", "clear", "--seconds", "1"]);
    assert!(!ok && text.contains("--to"), "{text}");
}

#[test]
fn a_hazy_report_washes_out_the_distance_under_the_physical_sky() {
    // The same noon under 10 km or more and under 3000 m of haze: the haze's air takes the
    // contrast out of the scene (Koschmieder's visibility is where it falls to 2%). Measured:
    // a luminance standard deviation of 0.165 without (humid, 77%) and 0.064 with (0.39 of it).
    let dir = scratch("weather-haze");
    let contrast = |visibility: &str| {
        let out = dir.join(format!("haze-{visibility}.png"));
        let report = format!("ZSHC 240000Z 36004MPS {visibility} SCT040 12/08 Q1022");
        let (ok, text) = stratus(&[
            "render",
            "--preset",
            "noon",
            "--size",
            "64x36",
            "--weather",
            &report,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(ok, "{text}");
        let img = Image::load(&out).unwrap();
        let lum: Vec<f64> = img
            .rgba
            .chunks(4)
            .map(|p| 0.2126 * f64::from(p[0]) + 0.7152 * f64::from(p[1]) + 0.0722 * f64::from(p[2]))
            .collect();
        let mean = lum.iter().sum::<f64>() / lum.len() as f64;
        (lum.iter().map(|l| (l - mean).powi(2)).sum::<f64>() / lum.len() as f64).sqrt()
    };
    let clear = contrast("9999");
    let hazy = contrast("3000 HZ");
    eprintln!("luminance standard deviation: clear {clear:.4}, haze {hazy:.4}");
    assert!(
        hazy < 0.5 * clear,
        "luminance standard deviation: {hazy:.4} with haze against {clear:.4} without"
    );
}

/// The acceptance command at a small size: a Miami thunderstorm in heavy rain draws
/// its rain (the particles and shafts its notes name) and its statistics count the flashes
/// of 120 frames (2 s at 40 a minute, one a 1.5 s slot: at least one).
#[test]
fn a_thunderstorm_report_rains_and_its_statistics_count_the_flashes() {
    let dir = scratch("weather-thunderstorm");
    let stats = dir.join("s.json");
    let (ok, text) = stratus(&[
        "render",
        "--weather",
        "METAR KMIA 271853Z 09012KT 2SM +TSRA BKN025CB 26/24 A2992",
        "--size",
        "64x36",
        "--frames",
        "120",
        "--stats",
        stats.to_str().unwrap(),
        "--out",
        dir.join("kmia.png").to_str().unwrap(),
    ]);
    assert!(ok, "{text}");
    assert!(text.contains("lightning: "), "{text}");
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&stats).unwrap()).unwrap();
    let flashes = doc["lightning_flashes"]
        .as_u64()
        .expect("lightning_flashes");
    let lit = doc["frames"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["lightning"].as_f64().unwrap() > 0.0)
        .count();
    println!("{flashes} flash(es) over {lit} of 120 frames");
    assert!(
        flashes >= 1 && lit >= 1,
        "{flashes} flashes, {lit} lit frames"
    );
    assert!(
        doc["median_ms"].get("precipitation").is_some(),
        "no precipitation pass ran: {}",
        doc["median_ms"]
    );
    let (ok, scene) = stratus(&[
        "weather",
        "METAR KMIA 271853Z 09012KT 2SM +TSRA BKN025CB 26/24 A2992",
    ]);
    assert!(ok, "{scene}");
    assert!(
        scene.contains("[precipitation]") && scene.contains("shafts = 1.0"),
        "{scene}"
    );
}
