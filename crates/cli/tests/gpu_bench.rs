//! `stratus gpu-bench` as `tests/device/bench.sh` runs it, small: its table and JSON hold a
//! row per configuration with positive times, both backends count the same work, the sparse
//! march does about a sixteenth of the full march's work per pixel, and bad options are
//! refused with a sentence.

mod common;

use common::{scratch, stratus};

#[test]
fn a_small_gpu_bench_writes_its_table_and_the_work_per_pixel() {
    let dir = scratch("gpu-bench");
    let out = dir.to_str().expect("utf-8 path");
    let (ok, text) = stratus(&[
        "gpu-bench",
        "--presets",
        "cumulus-noon",
        "--backends",
        "wgpu,ash",
        "--temporal",
        "off,1/16",
        "--sizes",
        "64x36",
        "--frames",
        "3",
        "--warmup",
        "1",
        "--out",
        out,
    ]);
    assert!(ok, "{text}");
    let json: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.join("results.json")).expect("results.json"),
    )
    .expect("results.json parses");
    let rows = json["rows"].as_array().expect("rows");
    assert_eq!(rows.len(), 4, "2 backends x 2 temporal modes: {json}");
    let row = |backend: &str, temporal: &str| {
        rows.iter()
            .find(|r| r["backend"] == backend && r["temporal"] == temporal)
            .unwrap_or_else(|| panic!("no {backend} {temporal} row: {json}"))
    };
    for r in rows {
        assert_eq!(r["frames"], 2, "3 frames less 1 of warm-up: {r}");
        assert!(r["gpu_ms"].as_f64().expect("gpu_ms") > 0.0, "{r}");
        assert!(r["passes"]["march"].as_f64().expect("march") > 0.0, "{r}");
        assert!(r["cpu_ms"].as_f64().expect("cpu_ms") > 0.0, "{r}");
    }
    for temporal in ["off", "1/16"] {
        // The backends draw the same bits, so they count the same work.
        for k in ["density_per_pixel", "light_per_pixel"] {
            assert_eq!(
                row("wgpu", temporal)[k],
                row("ash", temporal)[k],
                "{temporal} {k}"
            );
        }
    }
    let full = row("wgpu", "off")["density_per_pixel"]
        .as_f64()
        .expect("density");
    let sparse = row("wgpu", "1/16")["density_per_pixel"]
        .as_f64()
        .expect("density");
    assert!(full > 1.0, "the full march evaluates density: {full}");
    // One pixel in 16 is marched (the rest reprojected): between 1/20 and 1/12 of the work.
    assert!(
        sparse > full / 20.0 && sparse < full / 12.0,
        "1/16: {sparse} density evaluations per pixel against {full}"
    );
    let table = std::fs::read_to_string(dir.join("table.md")).expect("table.md");
    assert_eq!(
        table
            .lines()
            .filter(|l| l.starts_with("| cumulus-noon |"))
            .count(),
        4,
        "{table}"
    );
    assert!(table.contains("- `ash`: ash (Vulkan) on "), "{table}");
}

#[test]
fn gpu_bench_refuses_what_it_cannot_measure() {
    for (args, says) in [
        (
            &["gpu-bench", "--backends", "cpu"][..],
            "--backends: \"cpu\" is not a GPU backend",
        ),
        (
            &["gpu-bench", "--frames", "4", "--warmup", "4"][..],
            "--warmup 4 leaves no frame of --frames 4 to measure",
        ),
        (
            &["gpu-bench", "--presets", "nimbus"][..],
            "--presets nimbus",
        ),
        (&["gpu-bench", "--temporal", "1/3"][..], "--temporal 1/3"),
        (&["gpu-bench", "--sizes", "64by36"][..], "--sizes 64by36"),
    ] {
        let (ok, text) = stratus(args);
        assert!(!ok && text.contains(says), "{args:?}: {text}");
    }
}
