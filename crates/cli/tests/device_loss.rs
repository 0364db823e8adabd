//! A device lost mid-sequence: `stratus render --frames N --sequence DIR` on each GPU backend,
//! its device lost before frame 3 (`STRATUS_LOSE_DEVICE_AT_FRAME`, which calls
//! `Backend::lose_device`: wgpu destroys its device, ash's next submission reports
//! `VK_ERROR_DEVICE_LOST`). The command must end soon with one clear error naming the frame and
//! the loss, keep the frames before it complete, and leave no frame, image or temporary file of
//! its own after it.

mod common;

use std::{
    process::{Command, Stdio},
    time::{Duration, Instant},
};

use common::scratch;

/// Far above the few seconds the six 64x36 frames take in a debug build: a hang, not a slow
/// machine, runs past it.
const LIMIT: Duration = Duration::from_secs(240);

fn lose_mid_sequence(backend: &str) {
    let dir = scratch(&format!("device-loss-{backend}"));
    let frames = dir.join("frames");
    let out = dir.join("last.png");
    let mut child = Command::new(env!("CARGO_BIN_EXE_stratus"))
        .args([
            "render",
            "--backend",
            backend,
            "--size",
            "64x36",
            "--frames",
            "6",
            "--temporal",
            "1/16",
            "--sequence",
        ])
        .arg(&frames)
        .arg("--out")
        .arg(&out)
        .env("STRATUS_LOSE_DEVICE_AT_FRAME", "3")
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("starting stratus");
    let start = Instant::now();
    while child.try_wait().expect("polling stratus").is_none() {
        if start.elapsed() > LIMIT {
            let _ = child.kill();
            panic!("--backend {backend}: stratus still ran {LIMIT:?} after losing its device");
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    let output = child.wait_with_output().expect("stratus's output");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        !output.status.success(),
        "--backend {backend}: a lost device must fail the command"
    );
    assert!(
        stderr.contains("rendering frame 3 of frames 0 to 5")
            && stderr.contains("frames 0 to 2 are complete")
            && stderr.contains("was lost"),
        "--backend {backend}: {stderr}"
    );
    assert!(
        stderr.contains("create a new renderer") && !stderr.contains("panicked"),
        "--backend {backend}: {stderr}"
    );
    let mut names: Vec<String> = std::fs::read_dir(&frames)
        .expect("the sequence folder")
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        ["frame_0000.png", "frame_0001.png", "frame_0002.png"],
        "--backend {backend}: the frames before the loss, complete, and nothing else"
    );
    for n in &names {
        let image = stratus_compare::Image::load(&frames.join(n))
            .unwrap_or_else(|e| panic!("--backend {backend}: {n}: {e}"));
        assert_eq!((image.width, image.height), (64, 36), "{n}");
    }
    let left: Vec<String> = std::fs::read_dir(&dir)
        .expect("scratch")
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n != "frames")
        .collect();
    assert!(
        left.is_empty(),
        "--backend {backend}: no final image or temporary file after the loss: {left:?}"
    );
}

#[test]
fn a_device_lost_mid_sequence_on_wgpu_fails_clearly_and_keeps_the_frames_before() {
    lose_mid_sequence("wgpu");
}

#[test]
fn a_device_lost_mid_sequence_on_ash_fails_clearly_and_keeps_the_frames_before() {
    lose_mid_sequence("ash");
}

/// The CPU has no device: asking to lose one is an error that says so, not a silent pass.
#[test]
fn the_cpu_has_no_device_to_lose() {
    let (ok, text) = common::stratus_with(
        &[
            "render",
            "--backend",
            "reference",
            "--size",
            "16x9",
            "--frames",
            "2",
            "--out",
            scratch("device-loss-cpu")
                .join("x.png")
                .to_str()
                .expect("utf-8"),
        ],
        &[("STRATUS_LOSE_DEVICE_AT_FRAME", "0")],
    );
    assert!(!ok && text.contains("has no device to lose"), "{text}");
}
