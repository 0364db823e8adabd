//! `stratus render --integrator pathtrace` as a user runs it: the GPU path tracer's mean
//! radiance agrees with the CPU reference's Monte Carlo path tracer (the acceptance check of
//! the path tracer, at its size), and misuse is refused clearly.

use std::path::Path;

mod common;

use common::{scratch, stratus};

use stratus_compare::Image;

/// Mean of each channel (rgb, transmittance) of a linear EXR.
fn mean(path: &Path) -> [f64; 4] {
    let img = Image::load(path).expect("an EXR");
    let n = f64::from(img.width * img.height);
    let mut m = [0.0; 4];
    for px in img.rgba.chunks(4) {
        for c in 0..4 {
            m[c] += f64::from(px[c]) / n;
        }
    }
    m
}

/// 256 paths per pixel on wgpu and on the CPU reference at 64x36: mean radiance within 2%
/// (measured 0.12% on lavapipe). The random streams are independent, so the two differ by
/// noise: at 32x18 two CPU renders of different seeds already differed by 2.2%.
#[test]
fn gpu_path_tracer_mean_matches_the_reference() {
    let dir = scratch("pathtrace");
    let gpu = dir.join("pt.exr");
    let cpu = dir.join("mc.exr");
    let text = gpu_render(256, &gpu);
    // 256 paths: whole frames of the WGSL's paths per frame (32 today).
    assert!(
        text.contains("256 paths per pixel in ") && text.contains(" frames of "),
        "{text}"
    );
    assert!(text.contains("Mpaths/s"), "{text}");
    let median_256 = median_noise(&text);
    let (ok, text) = stratus(&[
        "render",
        "--preset",
        "cumulus-noon",
        "--size",
        "64x36",
        "--backend",
        "reference",
        "--integrator",
        "montecarlo",
        "--spp",
        "256",
        "--out",
        cpu.to_str().unwrap(),
    ]);
    assert!(ok, "{text}");
    let (g, c) = (mean(&gpu), mean(&cpu));
    let lum = |m: [f64; 4]| 0.2126 * m[0] + 0.7152 * m[1] + 0.0722 * m[2];
    let rel = (lum(g) - lum(c)).abs() / lum(c);
    assert!(
        rel < 0.02,
        "mean radiance: gpu {g:?}, cpu {c:?} ({:.2}% apart)",
        rel * 100.0
    );
    assert!(
        (g[3] - c[3]).abs() < 0.01,
        "transmittance: gpu {}, cpu {}",
        g[3],
        c[3]
    );

    // The noise report follows the paths: an eighth of them, sqrt(8) = 2.8 times the
    // relative standard error (the median block's; heavy-tailed paths make a 32-path
    // estimate of the variance low, hence the loose lower bound).
    let text = gpu_render(32, &dir.join("pt32.exr"));
    assert!(text.contains("not converged"), "{text}");
    let ratio = median_noise(&text) / median_256;
    assert!(
        (1.8..4.0).contains(&ratio),
        "32 paths' noise is {ratio:.2} times 256 paths' (expected about 2.8)"
    );
}

/// `spp` paths per pixel of `cumulus-noon` at 64x36 on wgpu into `out`: what it printed.
fn gpu_render(spp: u32, out: &Path) -> String {
    let spp = spp.to_string();
    let (ok, text) = stratus(&[
        "render",
        "--preset",
        "cumulus-noon",
        "--size",
        "64x36",
        "--integrator",
        "pathtrace",
        "--spp",
        &spp,
        "--backend",
        "wgpu",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(ok, "{text}");
    text
}

/// The median block's relative standard error from `stratus render`'s noise line.
fn median_noise(text: &str) -> f64 {
    let line = text
        .lines()
        .find(|l| l.starts_with("noise: relative standard error"))
        .unwrap_or_else(|| panic!("no noise line in: {text}"));
    let value = line
        .split("median ")
        .nth(1)
        .and_then(|r| r.split('%').next())
        .and_then(|v| v.parse::<f64>().ok())
        .unwrap_or_else(|| panic!("no median in: {line}"));
    assert!(value > 0.0 && value.is_finite(), "{line}");
    value
}

/// The CPU reference's integrator on a GPU backend, temporal upsampling and --frames with the
/// path tracer are refused, each naming what to use instead.
#[test]
fn path_tracer_misuse_is_refused() {
    for (args, expect) in [
        (
            &["--backend", "wgpu", "--integrator", "montecarlo"][..],
            "--integrator pathtrace",
        ),
        (
            &[
                "--backend",
                "wgpu",
                "--integrator",
                "pathtrace",
                "--temporal",
                "1/4",
            ][..],
            "--temporal off",
        ),
        (
            &[
                "--backend",
                "wgpu",
                "--integrator",
                "pathtrace",
                "--frames",
                "3",
            ][..],
            "as many frames as --spp",
        ),
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
