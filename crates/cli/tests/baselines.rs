//! `stratus render --method sprites | basic` as a user runs it: the sprite clouds agree across
//! wgpu and ash (the acceptance check, at its size), the basic marcher renders, and
//! misuse is refused clearly. Validation is on (`STRATUS_VALIDATION=1`).

mod common;

use common::scratch;

use stratus_compare::{CompareOptions, Image, compare};

/// `stratus` with the backends' validation on.
fn stratus(args: &[&str]) -> (bool, String) {
    common::stratus_with(args, &[("STRATUS_VALIDATION", "1")])
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
