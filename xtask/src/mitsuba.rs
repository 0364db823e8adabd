//! `cargo xtask mitsuba-check` (opt-in, not in CI): the CPU reference against Mitsuba 3 on a
//! gridded cloud.

use std::{
    path::{Path, PathBuf},
    process::Command,
    time::Instant,
};

use anyhow::{Context, Result};

use crate::{cargo, python_venv, run, step};

/// The Mitsuba version `mitsuba-check` installs.
pub(crate) const MITSUBA: &str = "mitsuba==3.9.1";

/// The renders and comparison of `mitsuba-check` (written to target/mitsuba-check/check.py).
pub(crate) const MITSUBA_SCRIPT: &str = include_str!("mitsuba_check.py");

/// Settings of `mitsuba-check`.
pub(crate) struct MitsubaSettings {
    pub(crate) reference_spp: u32,
    pub(crate) mitsuba_spp: u32,
    pub(crate) passes: u32,
    pub(crate) block: u32,
    pub(crate) export_args: Vec<String>,
}

/// `cargo xtask mitsuba-check`: the CPU reference's path tracer against Mitsuba 3 (scalar_rgb
/// variant) on the same gridded medium, sun and sky: the analytic sky's constant ambient, or
/// the physical sky frozen at the box's centre (a latitude-longitude map and the sun after the
/// air; docs/path-tracer.md). Mitsuba's `volpath` with
/// `max_depth=2` is single scattering, `volpathmis` with `max_depth=-1` all orders; the reference
/// renders `orders = 1` and `orders = 0` (its radiance plus transmittance times the sky, which
/// the camera sees through the medium in Mitsuba). The reference averages 4x4 pixel-centre
/// sub-pixels per pixel to match Mitsuba's box filter (with one ray per pixel centre, blocks of
/// a back-lit cloud differed by up to 3%).
///
/// Measured (32x32, 8x8 blocks, 64^3 cells over 4 km x layer x 4 km, sigma_s 0.01/m, sigma_a
/// 0.001/m, HG g = 0.6; Mitsuba 8 passes x 1024 spp, reference 4096 spp), largest block
/// difference relative to Mitsuba, and in combined standard errors:
///
/// | scene | single scattering | all orders |
/// |---|---|---|
/// | cumulus-noon (sun behind the camera) | 0.04% (0.8 sigma) | 0.49% (2.0 sigma) |
/// | cumulus-noon, sun `[0.2, 0.35, 0.9]` (back-lit) | 0.28% (1.0 sigma) | 0.63% (1.7 sigma) |
/// | noon (physical sky) | 0.13% (2.4 sigma) | 0.20% (1.9 sigma) |
/// | dawn (physical sky) | 0.50% (2.1 sigma) | 0.75% (3.6 sigma) |
/// | sunset (physical, `--distance-m 16000`, sun 4 deg up ahead) | 0.25% (2.0 sigma) | 0.29% (2.0 sigma) |
pub(crate) fn mitsuba_check(root: &Path, s: &MitsubaSettings) -> Result<()> {
    let t = Instant::now();
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .map(|d| if d.is_absolute() { d } else { root.join(d) })
        .unwrap_or_else(|| root.join("target"));
    let venv = target.join("mitsuba-venv");
    let python = venv.join("bin").join("python");
    let work = target.join("mitsuba-check");
    std::fs::create_dir_all(&work).with_context(|| format!("creating {}", work.display()))?;

    step("mitsuba virtual environment", || {
        python_venv(
            &venv,
            "import mitsuba, numpy; print(mitsuba.__version__)",
            "3.9.1",
            &[MITSUBA, "numpy"],
        )
        .context("pip could not install Mitsuba 3 (it needs the network once)")
    })?;
    step("cargo build --release -p stratus-cli", || {
        cargo(root, &["build", "--release", "-p", "stratus-cli"])
    })?;
    step("stratus export-volume + reference renders", || {
        let spp = s.reference_spp.to_string();
        run(Command::new(target.join("release").join("stratus"))
            .current_dir(&work)
            .args([
                "export-volume",
                "--out",
                "volume.vol",
                "--json",
                "setup.json",
                "--reference-spp",
                &spp,
                "--reference-out",
                "reference.json",
            ])
            .args(&s.export_args))
    })?;
    let result = step("mitsuba renders and comparison", || {
        std::fs::write(work.join("check.py"), MITSUBA_SCRIPT)?;
        run(Command::new(&python).current_dir(&work).args([
            "check.py".to_string(),
            "setup.json".to_string(),
            "reference.json".to_string(),
            s.mitsuba_spp.to_string(),
            s.passes.to_string(),
            s.block.to_string(),
        ]))
    });
    println!(
        "\nmitsuba-check: {} in {:.0?} (files in {})",
        if result.is_ok() { "passed" } else { "FAILED" },
        t.elapsed(),
        work.display()
    );
    result
}
