//! The `stratus` command's sequences, run as a user runs them: temporal upsampling converging
//! on a still camera, every frame of a sequence written, and `stratus animate` writing a
//! video that ffmpeg's own probe reads back.

use std::{path::Path, process::Command};

use stratus_compare::{CompareOptions, Image, compare};

fn stratus(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_stratus"))
        .args(args)
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .expect("running stratus");
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(out.status.success(), "stratus {args:?} failed:\n{text}");
    text
}

fn scratch(name: &str) -> std::path::PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir
}

/// The acceptance: after 64 frames of a still camera, 1/16 temporal upsampling is
/// within FLIP 0.02 of the full march of the same frame (measured 0.015 on lavapipe), on
/// `cumulus-noon` with the weather map's cumulus, where it was measured. On the default's
/// convective cells, finer than the map's regions, it measured 0.038: not yet within it
/// (docs/temporal.md).
#[test]
fn temporal_upsampling_converges_to_the_full_march_on_a_still_camera() {
    let dir = scratch("temporal-still");
    let scene = dir.join("map-cumulus.toml");
    std::fs::write(
        &scene,
        "base = \"cumulus-noon\"\n[clouds]\nconvective_cells = 0.0\n",
    )
    .unwrap();
    let mut images = Vec::new();
    for mode in ["1/16", "off"] {
        let out = dir.join(format!("{}.exr", mode.replace('/', "-")));
        let stats = dir.join(format!("{}.json", mode.replace('/', "-")));
        stratus(&[
            "render",
            "--scene",
            scene.to_str().unwrap(),
            "--size",
            "128x72",
            "--frames",
            "64",
            "--temporal",
            mode,
            "--backend",
            "wgpu",
            "--stats",
            stats.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        let doc: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&stats).unwrap()).unwrap();
        assert_eq!(doc["temporal"], mode);
        assert_eq!(doc["frames"].as_array().map(Vec::len), Some(64));
        assert!(doc["median_ms"]["march"].as_f64().is_some_and(|v| v > 0.0));
        if mode != "off" {
            assert!(doc["median_ms"]["resolve"].as_f64().is_some());
        }
        images.push(Image::load(&out).unwrap());
    }
    let c = compare(&images[1], &images[0], &CompareOptions::default()).unwrap();
    assert!(c.flip.mean <= 0.02, "FLIP mean {}", c.flip.mean);
}

#[test]
fn a_sequence_writes_every_frame() {
    let dir = scratch("sequence");
    let frames = dir.join("frames");
    stratus(&[
        "render",
        "--scene",
        concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/flythrough.toml"),
        "--size",
        "48x27",
        "--frames",
        "3",
        "--temporal",
        "1/4",
        "--backend",
        "wgpu",
        "--sequence",
        frames.to_str().unwrap(),
        "--out",
        dir.join("last.png").to_str().unwrap(),
    ]);
    for i in 0..3 {
        let f = frames.join(format!("frame_{i:04}.png"));
        let img = Image::load(&f).unwrap_or_else(|e| panic!("{}: {e}", f.display()));
        assert_eq!((img.width, img.height), (48, 27));
    }
    assert!(!frames.join("frame_0003.png").exists());
}

#[test]
fn animate_writes_a_video_ffprobe_can_read() {
    let dir = scratch("animate");
    let video = dir.join("fly.mp4");
    let text = stratus(&[
        "animate",
        "--scene",
        concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/flythrough.toml"),
        "--size",
        "64x35",
        "--seconds",
        "0.5",
        "--fps",
        "10",
        "--backend",
        "wgpu",
        "--out",
        video.to_str().unwrap(),
    ]);
    assert!(text.contains("5 frames"), "{text}");
    let probe = Command::new("ffprobe")
        .args([
            "-v",
            "error",
            "-count_frames",
            "-select_streams",
            "v:0",
            "-show_entries",
            "stream=codec_name,width,height,nb_read_frames",
            "-of",
            "csv=p=0",
        ])
        .arg(&video)
        .output()
        .expect("ffprobe (Debian's ffmpeg package; `cargo xtask ci` installs it)");
    let fields = String::from_utf8_lossy(&probe.stdout).trim().to_string();
    // The odd height is padded to an even one for yuv420p.
    assert_eq!(fields, "h264,64,36,5", "ffprobe: {fields}");
}

#[test]
fn animate_refuses_an_unknown_video_type() {
    let out = Command::new(env!("CARGO_BIN_EXE_stratus"))
        .args(["animate", "--preset", "cumulus-noon", "--out", "x.avi"])
        .output()
        .expect("running stratus");
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("x.avi") && err.contains(".mp4"), "{err}");
}
