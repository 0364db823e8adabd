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
