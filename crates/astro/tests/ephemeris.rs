//! stratus-astro against astropy: the expected values in `data/ephemeris.json` come from
//! `cargo xtask ephemeris-check` (600 random instants over 1950-2100 and places over the
//! sphere; see `xtask/src/ephemeris_check.py`). The targets: the sun within 0.05 degrees and
//! the moon within 0.5 degrees of astropy's (great-circle separation of the two horizontal
//! positions), on every case. The measured errors are printed (`--nocapture`).

use serde_json::Value;
use stratus_astro::{Place, UtcDateTime};

/// The targets of the issue, in degrees.
const SUN_DEG: f64 = 0.05;
const MOON_DEG: f64 = 0.5;
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

/// Great-circle angle between two (elevation, azimuth) directions, degrees.
fn separation(a: (f64, f64), b: (f64, f64)) -> f64 {
    let v = |(el, az): (f64, f64)| {
        let (el, az) = (el.to_radians(), az.to_radians());
        [el.cos() * az.sin(), el.cos() * az.cos(), el.sin()]
    };
    let (p, q) = (v(a), v(b));
    let dot = p[0] * q[0] + p[1] * q[1] + p[2] * q[2];
    let cross = [
        p[1] * q[2] - p[2] * q[1],
        p[2] * q[0] - p[0] * q[2],
        p[0] * q[1] - p[1] * q[0],
    ];
    let sin = (cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]).sqrt();
    sin.atan2(dot).to_degrees()
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
    fn max(&self) -> f64 {
        self.0.iter().copied().fold(0.0, f64::max)
    }
}

#[test]
fn sun_and_moon_agree_with_astropy() {
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
    let (sun, moon, phase) = (Stats(sun), Stats(moon), Stats(phase));
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

#[test]
fn sunrise_and_sunset_agree_with_astropy() {
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
    let stats = Stats(diffs);
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
