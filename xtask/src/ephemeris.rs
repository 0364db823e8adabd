//! `cargo xtask ephemeris-check` (opt-in, not in CI: it needs the network once): installs
//! astropy in a virtual environment under target/, writes the expected sun and moon positions,
//! moon phases, sunrises and sunsets of random dates and places to
//! `crates/astro/tests/data/ephemeris.json` (committed), and the 40 brightest catalogue stars'
//! and the galactic centre's positions at 61 dates and places to
//! `crates/astro/tests/data/stars.json` (committed), and runs stratus-astro's tests against
//! them, printing the errors.

use std::{path::Path, process::Command};

use anyhow::{Context, Result};

/// The astropy the expected values were made with.
const ASTROPY: &str = "8.0.2";
/// The script (written to target/ephemeris-check/ and run there).
const SCRIPT: &str = include_str!("ephemeris_check.py");
/// The stars' script: the catalogue's brightest stars and the galactic centre.
const STARS_SCRIPT: &str = include_str!("stars_check.py");

/// `cargo xtask ephemeris-check --cases N --events M`.
pub fn check(root: &Path, cases: u32, events: u32) -> Result<()> {
    let target = crate::target_dir(root);
    let venv = target.join("ephemeris-venv");
    crate::step("astropy virtual environment", || {
        crate::python_venv(
            &venv,
            "import astropy; print(astropy.__version__)",
            ASTROPY,
            &[&format!("astropy=={ASTROPY}")],
        )
        .context("pip could not install astropy (it needs the network once)")
    })?;
    let work = target.join("ephemeris-check");
    std::fs::create_dir_all(&work)?;
    let script = work.join("ephemeris_check.py");
    std::fs::write(&script, SCRIPT)?;
    let out = root.join("crates/astro/tests/data/ephemeris.json");
    crate::step("expected values from astropy", || {
        crate::run(
            Command::new(venv.join("bin").join("python"))
                .arg(&script)
                .arg(&out)
                .arg(cases.to_string())
                .arg(events.to_string()),
        )
    })?;
    let stars_script = work.join("stars_check.py");
    std::fs::write(&stars_script, STARS_SCRIPT)?;
    crate::step(
        "the brightest stars and the galactic centre from astropy",
        || {
            crate::run(
                Command::new(venv.join("bin").join("python"))
                    .arg(&stars_script)
                    .arg(root.join("crates/astro/data/stars.csv"))
                    .arg(root.join("crates/astro/tests/data/stars.json"))
                    .arg("40")
                    .arg("60"),
            )
        },
    )?;
    crate::step("stratus-astro against them", || {
        crate::cargo(
            root,
            &[
                "test",
                "-p",
                "stratus-astro",
                "--test",
                "ephemeris",
                "--test",
                "stars",
                "--",
                "--nocapture",
            ],
        )
    })
}
