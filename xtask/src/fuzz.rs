//! `cargo xtask fuzz`: replay `fuzz/regressions`, then run every cargo-fuzz target from its
//! committed corpus (`fuzz/seeds/<target>/`) and the seeds the project's files give.

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

/// The committed corpus of `target`: the fewest inputs that reach every edge earlier runs
/// reached, kept by `cargo xtask fuzz --update-seeds`, so that every run starts where earlier
/// runs got to rather than from the project's files alone.
fn committed_seeds(root: &Path, target: &str) -> PathBuf {
    root.join("fuzz/seeds").join(target)
}

/// How many files `dir` holds (0 when it does not exist).
fn count_files(dir: &Path) -> usize {
    std::fs::read_dir(dir).map_or(0, |d| {
        d.flatten()
            .filter(|e| e.file_type().is_ok_and(|t| t.is_file()))
            .count()
    })
}

/// `cargo xtask fuzz --seconds N [--runs N] [--target NAME]... [--update-seeds]`.
pub(crate) fn fuzz(
    root: &Path,
    seconds: u32,
    runs_limit: Option<u64>,
    only: &[String],
    update_seeds: bool,
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
        let seeds = write_seeds(root, target)?;
        let committed = committed_seeds(root, target);
        let committed_before = count_files(&committed);
        if committed_before == 0 && !update_seeds {
            bail!(
                "{}: no committed corpus for fuzz target {target}; make one with `cargo xtask fuzz --target {target} --update-seeds` and commit it",
                committed.display()
            );
        }
        std::fs::create_dir_all(&committed)
            .with_context(|| format!("creating {}", committed.display()))?;
        // What libFuzzer keeps of this target's runs (ignored by git).
        let corpus = root.join("fuzz/corpus").join(target);
        for extra in runs {
            let fuzzing = extra.is_empty();
            let mut cmd = Command::new(&cargo);
            cmd.current_dir(root)
                .args(["fuzz", "run", "--fuzz-dir", "fuzz", "-s", "none", target]);
            cmd.args(&extra);
            if fuzzing {
                // libFuzzer writes what it finds to the first directory and reads the others:
                // the run starts from the project's own inputs instead of from nothing.
                std::fs::create_dir_all(&corpus)
                    .with_context(|| format!("creating {}", corpus.display()))?;
                cmd.arg(&corpus).arg(&committed).arg(&seeds.0);
            }
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
                let doing = if fuzzing {
                    "fuzzing"
                } else {
                    "replaying fuzz/regressions"
                };
                // libFuzzer names the input it saved; without that line the target did not
                // crash on an input (a missing folder, a bad flag) and there is none to keep.
                match text.lines().find(|l| l.contains("Test unit written to")) {
                    Some(line) => bail!("fuzz target {target} crashed ({doing}): {}", line.trim()),
                    None => bail!(
                        "fuzz target {target} failed ({doing}, {}) without saving an input: see libFuzzer's output above",
                        out.status
                    ),
                }
            }
            if fuzzing {
                // libFuzzer ends a run it finished with "Done N runs in S second(s)"; a run
                // that exits cleanly without it did not fuzz (a harness that returns early, a
                // flag libFuzzer ignored), and is no evidence of anything.
                done = match text.lines().find(|l| l.starts_with("Done ")) {
                    // "Done 0 runs": the target returned before libFuzzer ran an input.
                    Some(line) if line.split_whitespace().nth(1) == Some("0") => {
                        eprintln!("{text}");
                        bail!("fuzz target {target} ran no inputs ({line})");
                    }
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
        let updated = if update_seeds {
            merge_into_committed(root, &cargo, target, &committed, &[&corpus, &seeds.0])?;
            format!(
                "; committed corpus {committed_before} -> {} inputs",
                count_files(&committed)
            )
        } else {
            String::new()
        };
        println!(
            "fuzz {target:12} {} regression input(s) replayed, {committed_before} committed and {} generated seed(s); {done}; 0 crashes{updated}",
            inputs.len(),
            seeds.1
        );
        rows.push(target);
    }
    println!("fuzz: {} targets, no crash", rows.len());
    Ok(())
}

/// Replaces the committed corpus with the smallest set of inputs, from it and the folders
/// `others` (this run's corpus, the generated seeds), that reaches every edge they reach:
/// libFuzzer's greedy `-set_cover_merge=1`, over edges alone (`-use_counters=0`; hit counts
/// would keep thousands of near-copies). Written beside it, then swapped in, so an
/// interrupted merge leaves the old corpus.
fn merge_into_committed(
    root: &Path,
    cargo: &str,
    target: &str,
    committed: &Path,
    others: &[&Path],
) -> Result<()> {
    let merged = committed.with_file_name(format!(".{target}.merging"));
    let _ = std::fs::remove_dir_all(&merged);
    std::fs::create_dir_all(&merged).with_context(|| format!("creating {}", merged.display()))?;
    let out = Command::new(cargo)
        .current_dir(root)
        .args(["fuzz", "run", "--fuzz-dir", "fuzz", "-s", "none", target])
        .arg(&merged)
        .arg(committed)
        .args(others)
        .args(["--", "-set_cover_merge=1", "-use_counters=0"])
        .output()
        .with_context(|| format!("running cargo fuzz run {target} -- -set_cover_merge=1"))?;
    if !out.status.success() || count_files(&merged) == 0 {
        eprintln!(
            "{}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
        bail!(
            "merging fuzz target {target}'s corpus into {} failed ({}, {} inputs kept)",
            committed.display(),
            out.status,
            count_files(&merged)
        );
    }
    let _ = std::fs::remove_dir_all(committed);
    std::fs::rename(&merged, committed)
        .with_context(|| format!("renaming {} to {}", merged.display(), committed.display()))
}

/// Writes a target's seed inputs, taken from what the project commits (the scenes, the WGSL,
/// the golden images, the METAR reports, the ephemeris test's dates), to
/// `target/fuzz-seeds/<target>/`; returns the folder and how many seeds it holds. OpenEXR, of
/// which nothing is committed, starts from two small images written here.
fn write_seeds(root: &Path, target: &str) -> Result<(PathBuf, usize)> {
    let files_in = |dir: &str, ext: &str| -> Vec<PathBuf> {
        let mut v: Vec<PathBuf> = std::fs::read_dir(root.join(dir))
            .map(|d| {
                d.flatten()
                    .map(|e| e.path())
                    .filter(|p| p.extension().is_some_and(|x| x == ext))
                    .collect()
            })
            .unwrap_or_default();
        v.sort();
        v
    };
    let read = |p: &Path| std::fs::read(p).with_context(|| format!("reading {}", p.display()));
    let mut seeds: Vec<Vec<u8>> = Vec::new();
    match target {
        "scene_toml" => {
            for p in files_in("scenes", "toml")
                .iter()
                .chain(&files_in("scenes/fit", "toml"))
            {
                seeds.push(read(p)?);
            }
        }
        "wgsl" => {
            for p in files_in("wgsl", "wgsl") {
                seeds.push(read(&p)?);
            }
        }
        "image_png" => {
            for p in files_in("tests/golden", "png") {
                seeds.push(read(&p)?);
            }
        }
        "metar" => {
            let text =
                std::fs::read_to_string(root.join("crates/weather/tests/data/metar_reports.txt"))
                    .context("reading the METAR reports")?;
            seeds.extend(
                text.lines()
                    .filter(|l| !l.trim().is_empty() && !l.starts_with('#'))
                    .map(|l| l.as_bytes().to_vec()),
            );
        }
        "utc_date" => {
            // Two bytes pick the place (see the target), then the date's text.
            let text = std::fs::read_to_string(root.join("crates/astro/tests/data/ephemeris.json"))
                .context("reading the ephemeris cases")?;
            let json: serde_json::Value = serde_json::from_str(&text).context("ephemeris.json")?;
            let cases = json["cases"]
                .as_array()
                .context("ephemeris.json: no cases")?;
            for (i, c) in cases.iter().take(32).enumerate() {
                if let Some(date) = c["date_utc"].as_str() {
                    let mut seed = vec![(i * 37 % 256) as u8, (i * 91 % 256) as u8];
                    seed.extend_from_slice(date.as_bytes());
                    seeds.push(seed);
                }
            }
        }
        "image_exr" => {
            // Nothing committed is an EXR: two small ones as Stratus writes them (linear RGBA,
            // alpha the transmittance).
            let scratch = crate::target_dir(root).join("fuzz-seeds/exr-scratch.exr");
            std::fs::create_dir_all(scratch.parent().unwrap())?;
            for (w, h) in [(1, 1), (8, 4)] {
                let rgba: Vec<f32> = (0..w * h * 4).map(|i| i as f32 / 7.0).collect();
                stratus_compare::Image::from_linear_rgba(w, h, rgba)
                    .save(&scratch)
                    .context("writing an EXR seed")?;
                seeds.push(read(&scratch)?);
            }
        }
        _ => {}
    }
    let dir = crate::target_dir(root).join("fuzz-seeds").join(target);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).with_context(|| format!("creating {}", dir.display()))?;
    for (i, seed) in seeds.iter().enumerate() {
        std::fs::write(dir.join(format!("seed-{i:03}")), seed)
            .with_context(|| format!("writing a seed to {}", dir.display()))?;
    }
    Ok((dir, seeds.len()))
}
