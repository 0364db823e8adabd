//! stratus-astro against astropy: the expected values in `data/ephemeris.json` come from
//! `cargo xtask ephemeris-check` (600 random instants over 1950-2100 and places over the
//! sphere; see `xtask/src/ephemeris_check.py`). The bounds: the sun within 0.02 degrees and
//! the moon within 0.05 degrees of astropy's (great-circle separation of the two horizontal
//! positions), on every case, about twice what was measured. The measured errors are printed
//! (`--nocapture`) and written to docs/astronomy.md's table.

mod common;

use common::separation;
use serde_json::Value;
use stratus_astro::{Place, UtcDateTime};

/// The bounds, in degrees: about twice the largest error measured over the 600 cases (sun
/// 0.0108, moon 0.0263), far inside the targets the sky was built to (0.05 and 0.5 degrees), so
/// that a change that loses accuracy fails here long before it shows in an image.
const SUN_DEG: f64 = 0.02;
const MOON_DEG: f64 = 0.05;
/// The moon's illuminated fraction: measured largest difference 0.00020; the bound is 5x that.
const PHASE: f64 = 1e-3;
/// Sunrise and sunset, seconds: measured largest 3.9 s over 284 events; the bound is 5x that
/// (the sun's elevation changes slowly near the poles, so a small error in it moves the
/// crossing by more there).
const EVENT_S: f64 = 20.0;

fn cases() -> Vec<Value> {
    let text = include_str!("data/ephemeris.json");
    let doc: Value = serde_json::from_str(text).expect("ephemeris.json");
    doc["cases"].as_array().expect("cases").clone()
}

fn f(v: &Value) -> f64 {
    v.as_f64().expect("a number")
}

struct Stats(Vec<f64>);

impl Stats {
    fn line(&self, what: &str, unit: &str) -> String {
        let mut v = self.0.clone();
        v.sort_by(f64::total_cmp);
        let n = v.len();
        let mean = v.iter().sum::<f64>() / n as f64;
        let p = |q: f64| v[((q * n as f64).ceil() as usize).clamp(1, n) - 1];
        format!(
            "{what}: {n} cases, mean {mean:.5}{unit}, median {:.5}{unit}, p99 {:.5}{unit}, max {:.5}{unit}",
            p(0.5),
            p(0.99),
            p(1.0)
        )
    }
    fn quantiles(&self) -> (f64, f64, f64) {
        let mut v = self.0.clone();
        v.sort_by(f64::total_cmp);
        let n = v.len();
        let p99 = v[((0.99 * n as f64).ceil() as usize).clamp(1, n) - 1];
        (v.iter().sum::<f64>() / n as f64, p99, v[n - 1])
    }
    fn max(&self) -> f64 {
        self.0.iter().copied().fold(0.0, f64::max)
    }
}

/// The great-circle errors of the sun and the moon and the error of the moon's illuminated
/// fraction over every case, with the case of the sun's and the moon's largest.
fn position_errors() -> (Stats, Stats, Stats, (f64, String, f64, String)) {
    let cases = cases();
    assert!(cases.len() >= 500, "{} cases", cases.len());
    let (mut sun, mut moon, mut phase) = (Vec::new(), Vec::new(), Vec::new());
    let mut worst = (0.0, String::new(), 0.0, String::new());
    for c in &cases {
        let date = c["date_utc"].as_str().expect("date");
        let t: UtcDateTime = date.parse().expect("date parses");
        let place = Place::new(f(&c["latitude_deg"]), f(&c["longitude_deg"])).expect("place");
        let s = stratus_astro::sun(place, t);
        let m = stratus_astro::moon(place, t);
        let ds = separation(
            (s.elevation_deg, s.azimuth_deg),
            (f(&c["sun"]["elevation_deg"]), f(&c["sun"]["azimuth_deg"])),
        );
        let dm = separation(
            (m.elevation_deg, m.azimuth_deg),
            (f(&c["moon"]["elevation_deg"]), f(&c["moon"]["azimuth_deg"])),
        );
        if ds > worst.0 {
            worst.0 = ds;
            worst.1 = format!("{date} at {place:?}");
        }
        if dm > worst.2 {
            worst.2 = dm;
            worst.3 = format!("{date} at {place:?}");
        }
        sun.push(ds);
        moon.push(dm);
        phase.push((stratus_astro::moon_phase(t) - f(&c["moon"]["phase"])).abs());
    }
    (Stats(sun), Stats(moon), Stats(phase), worst)
}

#[test]
fn sun_and_moon_agree_with_astropy() {
    let (sun, moon, phase, worst) = position_errors();
    println!("{}", sun.line("sun", " deg"));
    println!("{}", moon.line("moon", " deg"));
    println!("{}", phase.line("moon phase (illuminated fraction)", ""));
    assert!(
        sun.max() <= SUN_DEG,
        "sun off by {:.4} deg ({})",
        worst.0,
        worst.1
    );
    assert!(
        moon.max() <= MOON_DEG,
        "moon off by {:.4} deg ({})",
        worst.2,
        worst.3
    );
    assert!(phase.max() <= PHASE, "phase off by {:.5}", phase.max());
}

/// The errors of sunrise and sunset, seconds, over every case with both events, and the number
/// of events absent from both (polar day or night).
fn event_errors() -> (Stats, usize) {
    let mut diffs = Vec::new();
    let (mut checked, mut polar) = (0, 0);
    for c in cases().iter().filter(|c| c.get("events").is_some()) {
        checked += 1;
        let t: UtcDateTime = c["date_utc"].as_str().expect("date").parse().expect("date");
        let place = Place::new(f(&c["latitude_deg"]), f(&c["longitude_deg"])).expect("place");
        let ours = stratus_astro::sun_events(place, t);
        for (key, mine) in [("sunrise_utc", ours.sunrise), ("sunset_utc", ours.sunset)] {
            let theirs = c["events"][key]
                .as_str()
                .map(|s| s.parse::<UtcDateTime>().expect("event"));
            match (mine, theirs) {
                (Some(a), Some(b)) => diffs.push(a.seconds_since(b).abs()),
                // Polar day or night: neither finds the crossing.
                (None, None) => polar += 1,
                (a, b) => panic!(
                    "{key} on {} at {place:?}: ours {:?}, astropy's {:?}",
                    c["date_utc"],
                    a.map(|t| t.to_string()),
                    b.map(|t| t.to_string())
                ),
            }
        }
    }
    assert!(checked >= 100, "{checked} cases with events");
    (Stats(diffs), polar)
}

#[test]
fn sunrise_and_sunset_agree_with_astropy() {
    let (stats, polar) = event_errors();
    println!(
        "{} ({polar} events absent from both: polar day or night)",
        stats.line("sunrise and sunset", " s")
    );
    assert!(
        stats.max() <= EVENT_S,
        "an event is {:.1} s off",
        stats.max()
    );
}

/// docs/astronomy.md's table of errors against astropy is this file's measurement.
#[test]
fn the_docs_table_is_this_measurement() {
    let (sun, moon, phase, _) = position_errors();
    let (events, _) = event_errors();
    let row = |what: &str, s: &Stats, digits: usize, unit: &str, bound: &str| {
        let (mean, p99, max) = s.quantiles();
        format!(
            "| {what} | {mean:.digits$}{unit} | {p99:.digits$}{unit} | {max:.digits$}{unit} | {bound} |\n"
        )
    };
    let table = [
        "| | mean | p99 | max | bound |\n|---|---|---|---|---|\n".to_string(),
        row("sun", &sun, 4, "°", &format!("{SUN_DEG}°")),
        row("moon", &moon, 4, "°", &format!("{MOON_DEG}°")),
        row("moon's illuminated fraction", &phase, 5, "", ""),
        row(
            &format!("sunrise and sunset ({} events)", events.0.len()),
            &events,
            1,
            " s",
            "",
        ),
    ]
    .concat();
    stratus_test_support::docs_block(
        "docs/astronomy.md",
        "cargo test -p stratus-astro --test ephemeris",
        &table,
    );
}
