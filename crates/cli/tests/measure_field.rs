//! `stratus measure-field` as a user runs it: the straight-down statistics of a cloud field
//! (count, D, b) in words and JSON, the mask image, and clear refusals.

mod common;

use common::{scratch, stratus};

#[test]
fn a_cumulus_field_is_measured_from_above() {
    let dir = scratch("measure-field");
    let json = dir.join("few.json");
    let mask = dir.join("few.png");
    let (ok, text) = stratus(&[
        "measure-field",
        "--state",
        "few",
        "--size",
        "128",
        "--min-pixels",
        "4",
        "--json",
        json.to_str().unwrap(),
        "--mask",
        mask.to_str().unwrap(),
    ]);
    assert!(ok, "{text}");
    assert!(text.contains("clouds inside the square"), "{text}");
    assert!(text.contains("area-perimeter dimension D"), "{text}");
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    // Fair weather: a few tenths of the sky, and separate clouds to count.
    let fraction = v["cloud_fraction"].as_f64().unwrap();
    assert!((0.05..0.5).contains(&fraction), "{v}");
    assert!(v["clouds"].as_u64().unwrap() >= 3, "{v}");
    // A dimension between a smooth outline's 1 and a plane-filling 2.
    let d = v["d"]["slope"].as_f64().expect("D fitted");
    assert!((1.0..2.0).contains(&d), "{v}");
    let img = image::open(&mask).unwrap().to_luma8();
    assert_eq!(img.dimensions(), (128, 128));
    let white = img.pixels().filter(|p| p.0[0] == 255).count() as f64;
    let cloud = img.pixels().filter(|p| p.0[0] > 0).count() as f64;
    assert!(
        white > 0.0 && cloud / (128.0 * 128.0) - fraction < 1e-9,
        "{v}"
    );
}

#[test]
fn measure_field_refuses_what_it_cannot_measure() {
    for (args, says) in [
        (
            &["measure-field", "--threshold", "1.5"][..],
            "--threshold 1.5",
        ),
        (&["measure-field", "--extent-m", "-3"][..], "--extent-m -3"),
        (&["measure-field", "--state", "drizzly"][..], "--state"),
        (&["measure-field", "--size", "16"][..], "16"),
    ] {
        let (ok, text) = stratus(args);
        assert!(!ok && text.contains(says), "{args:?}: {text}");
    }
}
