//! `stratus export-volume`: what `cargo xtask mitsuba-check` gives Mitsuba. Under the physical
//! sky, the sky as a latitude-longitude map and the sun after the air; a scene Mitsuba's
//! emitters cannot express is refused.

mod common;

use std::path::Path;

use common::{scratch, stratus_in};

/// `stratus export-volume ARGS --dims 8x8x8` in `dir`: whether it succeeded, and its output.
fn export(dir: &Path, args: &[&str]) -> (bool, String) {
    let all: Vec<&str> = ["export-volume", "--dims", "8x8x8"]
        .into_iter()
        .chain(args.iter().copied())
        .collect();
    stratus_in(dir, &all, &[])
}

/// The JSON file `name` in `dir`.
fn json(dir: &Path, name: &str) -> serde_json::Value {
    serde_json::from_slice(&std::fs::read(dir.join(name)).unwrap()).unwrap()
}

/// The map's texels, row by row from the zenith (PFM stores the bottom row first).
fn read_pfm(bytes: &[u8]) -> (usize, usize, Vec<[f32; 3]>) {
    let mut lines = bytes.splitn(4, |&b| b == b'\n');
    assert_eq!(lines.next(), Some(&b"PF"[..]), "not a colour PFM");
    let size = String::from_utf8(lines.next().unwrap().to_vec()).unwrap();
    let (w, h) = size.split_once(' ').unwrap();
    let (w, h): (usize, usize) = (w.parse().unwrap(), h.parse().unwrap());
    assert_eq!(lines.next(), Some(&b"-1.0"[..]), "not little-endian");
    let data = lines.next().unwrap();
    assert_eq!(data.len(), w * h * 12, "{w}x{h} RGB float32");
    let floats: Vec<f32> = data
        .chunks(4)
        .map(|c| f32::from_le_bytes(c.try_into().unwrap()))
        .collect();
    let rows: Vec<&[f32]> = floats.chunks(3 * w).collect();
    let texels = rows
        .iter()
        .rev()
        .flat_map(|row| row.chunks(3).map(|t| [t[0], t[1], t[2]]))
        .collect();
    (w, h, texels)
}

#[test]
fn the_physical_sky_goes_to_mitsuba_as_a_map_and_a_reddened_sun() {
    let dir = scratch("export-volume-sky");
    let (ok, text) = export(
        &dir,
        &[
            "--preset",
            "noon",
            "--json",
            "setup.json",
            "--sky-map-size",
            "64x33",
        ],
    );
    assert!(ok, "{text}");
    let setup = json(&dir, "setup.json");
    assert_eq!(setup["sky_map"], "volume.sky.pfm", "{setup}");
    let (w, h, sky) = read_pfm(&std::fs::read(dir.as_path().join("volume.sky.pfm")).unwrap());
    assert_eq!((w, h), (64, 33));
    assert!(sky.iter().flatten().all(|v| v.is_finite() && *v >= 0.0));
    // A clear noon sky is blue at the zenith; the sun after the air is redder than the sky.
    let zenith = sky[0];
    assert!(zenith[2] > 1.5 * zenith[0], "zenith {zenith:?}");
    let sun: Vec<f64> = setup["sun_illuminance"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert!(sun[0] > sun[2] && sun[2] > 0.0, "sun after the air {sun:?}");
    // One row is one latitude: the zenith row is the same light in every column.
    let spread = sky[..w]
        .iter()
        .map(|t| t[2])
        .fold((f32::MAX, f32::MIN), |(lo, hi), v| (lo.min(v), hi.max(v)));
    assert!(
        spread.1 - spread.0 < 1e-4 * spread.1,
        "zenith row {spread:?}"
    );

    // The analytic sky stays the uniform ambient: no map.
    let (ok, text) = export(
        &dir,
        &[
            "--preset",
            "cumulus-noon",
            "--out",
            "analytic.vol",
            "--json",
            "analytic.json",
        ],
    );
    assert!(ok, "{text}");
    let setup = json(&dir, "analytic.json");
    assert!(setup["sky_map"].is_null(), "{setup}");
    assert!(!dir.as_path().join("analytic.sky.pfm").exists());
}

#[test]
fn a_scene_the_check_cannot_express_is_refused_by_name() {
    let dir = scratch("export-volume-low-sun");
    std::fs::write(
        dir.as_path().join("low.toml"),
        "base = \"cumulus-noon\"\n[sun]\nelevation_deg = -5.0\n",
    )
    .unwrap();
    let (ok, text) = export(&dir, &["--scene", "low.toml"]);
    assert!(!ok, "{text}");
    assert!(
        text.contains("5.0 deg below the horizon") && !text.contains("panicked"),
        "{text}"
    );
    assert!(!dir.as_path().join("volume.vol").exists(), "wrote a volume");

    // `sunset`'s clouds are sparse: 8 km ahead the box is clear, and a clear box would compare
    // the sky with itself.
    let (ok, text) = export(&dir, &["--preset", "sunset"]);
    assert!(!ok, "{text}");
    assert!(
        text.contains("holds no cloud") && text.contains("--distance-m"),
        "{text}"
    );
    assert!(!dir.as_path().join("volume.vol").exists(), "wrote a volume");
}
