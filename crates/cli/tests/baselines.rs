//! `stratus render --method sprites | basic` as a user runs it: the sprite clouds agree across
//! wgpu and ash (the acceptance check, at its size), the basic marcher renders, and
//! misuse is refused clearly. Validation is on (`STRATUS_VALIDATION=1`).

use std::{path::Path, process::Command};

use stratus_compare::{CompareOptions, Image, compare};

fn stratus(args: &[&str]) -> (bool, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_stratus"))
        .args(args)
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .env("STRATUS_VALIDATION", "1")
        .output()
        .expect("running stratus");
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    (out.status.success(), text)
}

fn scratch(name: &str) -> std::path::PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir
}

/// 256x144 sprite clouds on wgpu and on ash: FLIP at most 0.01 apart (measured: identical).
#[test]
fn sprites_agree_on_wgpu_and_ash() {
    let dir = scratch("sprites");
    let mut images = Vec::new();
    for backend in ["wgpu", "ash"] {
        let out = dir.join(format!("{backend}.png"));
        let (ok, text) = stratus(&[
            "render",
            "--method",
            "sprites",
            "--preset",
            "cumulus-noon",
            "--size",
            "256x144",
            "--backend",
            backend,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(ok, "{backend}: {text}");
        assert!(text.contains("sprite-draw"), "{backend}: {text}");
        images.push(Image::load(&out).expect("a PNG"));
    }
    let r = compare(&images[0], &images[1], &CompareOptions::default()).expect("comparable");
    assert!(
        r.flip.mean <= 0.01,
        "FLIP {} between wgpu and ash",
        r.flip.mean
    );
}

#[test]
fn basic_marcher_renders() {
    let dir = scratch("basic");
    let out = dir.join("basic.png");
    let (ok, text) = stratus(&[
        "render",
        "--method",
        "basic",
        "--size",
        "64x36",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(ok, "{text}");
    assert!(out.exists());
}

/// The baselines on the CPU, with the path tracer or with temporal upsampling are refused,
/// each saying why.
#[test]
fn baseline_misuse_is_refused() {
    for (args, expect) in [
        (
            &["--method", "sprites", "--backend", "cpu"][..],
            "GPU backends",
        ),
        (
            &["--method", "basic", "--backend", "reference"][..],
            "GPU backends",
        ),
        (
            &["--method", "sprites", "--integrator", "pathtrace"][..],
            "drop --integrator",
        ),
        (
            &["--method", "basic", "--temporal", "1/4"][..],
            "--temporal off",
        ),
        (&["--method", "voxels"][..], "sprites"),
    ] {
        let mut all = vec![
            "render",
            "--preset",
            "cumulus-noon",
            "--size",
            "8x8",
            "--out",
            "/nonexistent-dir/x.png",
        ];
        all.extend_from_slice(args);
        let (ok, text) = stratus(&all);
        assert!(!ok, "{args:?} was accepted: {text}");
        assert!(text.contains(expect), "{args:?}: {text}");
        assert!(!text.contains("panicked"), "{text}");
    }
}
