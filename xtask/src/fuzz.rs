//! `cargo xtask fuzz`: replay `fuzz/regressions`, then run every cargo-fuzz target.

use std::{
    path::{Path, PathBuf},
    process::Command,
};

use anyhow::{Context, Result, bail};

/// The cargo-fuzz targets (fuzz/Cargo.toml).
pub(crate) const FUZZ_TARGETS: [&str; 6] = [
    "scene_toml",
    "wgsl",
    "image_png",
    "image_exr",
    "metar",
    "utc_date",
];

/// `cargo xtask fuzz --seconds N [--runs N] [--target NAME]...`.
pub(crate) fn fuzz(
    root: &Path,
    seconds: u32,
    runs_limit: Option<u64>,
    only: &[String],
) -> Result<()> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let have = Command::new(&cargo)
        .args(["fuzz", "--version"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !have {
        println!("installing cargo-fuzz (once)");
        let status = Command::new(&cargo)
            .args(["install", "cargo-fuzz", "--locked"])
            .status()
            .context("running cargo install cargo-fuzz")?;
        if !status.success() {
            bail!("`cargo install cargo-fuzz --locked` failed ({status})");
        }
    }
    // Built once, apart from the runs, so that a build failure (a compile error, a full disk)
    // is reported as one and not as a crash of the first target.
    let mut build = Command::new(&cargo);
    build
        .current_dir(root)
        .args(["fuzz", "build", "--fuzz-dir", "fuzz", "-s", "none"]);
    if let [one] = only {
        build.arg(one);
    }
    let status = build.status().context("running cargo fuzz build")?;
    if !status.success() {
        bail!("building the fuzz targets failed ({status}); the fuzzing did not start");
    }
    let mut rows = Vec::new();
    for target in FUZZ_TARGETS
        .into_iter()
        .filter(|t| only.is_empty() || only.iter().any(|o| o == t))
    {
        // Inputs that once crashed, each run once; then N seconds of fuzzing.
        let regressions = root.join("fuzz/regressions").join(target);
        let mut inputs: Vec<PathBuf> = std::fs::read_dir(&regressions)
            .map(|d| d.flatten().map(|e| e.path()).collect())
            .unwrap_or_default();
        inputs.sort();
        let mut runs = vec![Vec::new()];
        if !inputs.is_empty() {
            runs.insert(
                0,
                inputs
                    .iter()
                    .map(|p| p.to_string_lossy().into_owned())
                    .collect(),
            );
        }
        let mut done = String::new();
        for extra in runs {
            let fuzzing = extra.is_empty();
            let mut cmd = Command::new(&cargo);
            cmd.current_dir(root)
                .args(["fuzz", "run", "--fuzz-dir", "fuzz", "-s", "none", target]);
            cmd.args(&extra);
            cmd.arg("--");
            if fuzzing {
                cmd.arg(match runs_limit {
                    Some(n) => format!("-runs={n}"),
                    None => format!("-max_total_time={seconds}"),
                });
            }
            let out = cmd
                .output()
                .with_context(|| format!("running cargo fuzz run {target}"))?;
            let text = format!(
                "{}{}",
                String::from_utf8_lossy(&out.stdout),
                String::from_utf8_lossy(&out.stderr)
            );
            if !out.status.success() {
                eprintln!("{text}");
                bail!(
                    "fuzz target {target} crashed ({}); its input is in fuzz/artifacts/{target}/",
                    if fuzzing {
                        "fuzzing"
                    } else {
                        "replaying fuzz/regressions"
                    }
                );
            }
            if fuzzing {
                // libFuzzer ends a run it finished with "Done N runs in S second(s)"; a run
                // that exits cleanly without it did not fuzz (a harness that returns early, a
                // flag libFuzzer ignored), and is no evidence of anything.
                done = match text.lines().find(|l| l.starts_with("Done ")) {
                    Some(line) => line.to_string(),
                    None => {
                        eprintln!("{text}");
                        bail!(
                            "fuzz target {target} exited without libFuzzer's \"Done N runs\" summary, so it did not fuzz"
                        );
                    }
                };
            }
        }
        println!(
            "fuzz {target:12} {} regression input(s) replayed; {done}; 0 crashes",
            inputs.len()
        );
        rows.push(target);
    }
    println!("fuzz: {} targets, no crash", rows.len());
    Ok(())
}
