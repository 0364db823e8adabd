//! `cargo xtask`: the project's build and check tasks (matklad's cargo-xtask convention).
//!
//! - `build-shaders`: validate `wgsl/` with naga and write `spirv-out/` and the pinned
//!   translations in `tests/out/` (or `--check` them);
//! - `validate`: run the external validators over `spirv-out/` and every variant's GLSL and
//!   HLSL, made afresh;
//! - `ci`: install missing system tools, then fmt, clippy, `build-shaders --check`,
//!   `validate`, `web-test`, `fuzz` (10 s a target) and every test;
//! - `conformance`: the cross-backend conformance suite alone (`tests/tests/conformance`),
//!   which prints its results table and writes it as Markdown;
//! - `export`: the engine kit (`stratus export-kit`) for other engines;
//! - `web-test`: the kit's browser consumer (`web/`) in headless Chromium, against the goldens;
//! - `web`: serve the interactive page with a fresh kit;
//! - `fuzz`: replay the fuzz regressions, then fuzz every cargo-fuzz target for N seconds;
//! - `device-bundle`: pack the conformance suite, the CLI, glslang and the validation layer
//!   for a machine with a real GPU and no cargo (`tests/device/run.sh` runs it there);
//! - `device-bench`: pack the CLI (and, given the peer's WGSL, the peer harness) for the
//!   same machine (`tests/device/bench.sh` runs `stratus gpu-bench` there);
//! - `ephemeris-check` (opt-in, not in CI): stratus-astro's expected values from astropy;
//! - `mitsuba-check` (opt-in, not in CI): the CPU reference against Mitsuba 3 on a gridded
//!   cloud (see [`mitsuba`]).
//!
//! One module per task (or pair of tasks); this file holds the command line and the helpers
//! every task uses (the workspace's folders, running cargo and other programs, CI steps).

use std::{
    path::{Path, PathBuf},
    process::{Command, ExitCode},
    time::Instant,
};

mod ci;
mod device;
mod ephemeris;
mod fuzz;
mod mitsuba;
mod shaders;
mod view;
mod web;

use anyhow::{Context, Result, bail};
use clap::{Parser, Subcommand};

#[derive(Parser)]
#[command(name = "cargo xtask", about = "Stratus build and check tasks", version)]
struct Cli {
    #[command(subcommand)]
    task: Task,
}

#[derive(Subcommand)]
enum Task {
    /// Validate the WGSL with naga; write spirv-out/ (SPIR-V per variant, composed WGSL,
    /// manifest.json) and the pinned translations in tests/out/; with `--languages all`, also
    /// every variant's GLSL, HLSL and MSL (to target/shaders/ by default).
    BuildShaders {
        /// Folder holding the WGSL and `modules.toml` [default: <workspace>/wgsl].
        #[arg(long)]
        wgsl: Option<PathBuf>,
        /// Output folder [default: <workspace>/spirv-out].
        #[arg(long)]
        out: Option<PathBuf>,
        /// Change nothing; fail and name every stale, missing or extra file in spirv-out/
        /// and tests/out/.
        #[arg(long)]
        check: bool,
        /// `spirv`: what is committed (spirv-out/, tests/out/). `all`: GLSL, HLSL and MSL of
        /// every variant as well, written to the translations folder.
        #[arg(long, value_enum, default_value_t = shaders::LanguageChoice::Spirv)]
        languages: shaders::LanguageChoice,
        /// Where `--languages all` writes GLSL, HLSL and MSL [default: <target>/shaders].
        #[arg(long)]
        translations: Option<PathBuf>,
    },
    /// Run spirv-val over `spirv-out/`, and glslangValidator (GLSL, and HLSL through glslang's
    /// HLSL front end) over every variant's translations, made afresh in <target>/shaders;
    /// print a table.
    Validate {
        /// Folder with the committed shaders [default: <workspace>/spirv-out].
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Everything CI runs: tools, fmt, clippy, build-shaders --check, validate, web-test,
    /// fuzz (10 s a target), tests.
    Ci,
    /// Run only the conformance suite (scenes x execution paths); print its table and write
    /// it to <target>/conformance.md. `STRATUS_UPDATE_GOLDENS=1` rewrites tests/golden/.
    Conformance,
    /// Write the engine kit (shaders, manifest and frame graph, uniform layout, noise textures,
    /// golden images with their uniform bytes and frame plans, README) to a folder.
    Export {
        /// The kit's folder.
        #[arg(long)]
        out: PathBuf,
    },
    /// The browser path: export a kit, render its goldens in headless Chromium through
    /// web/stratus-kit.js (Tint, SwiftShader), and compare each with its golden by FLIP.
    WebTest,
    /// The viewer under Xvfb: `stratus view --script tests/view/script.toml` flies, moves the
    /// sun and takes two screenshots; they must differ, have contrast, and show the overlay's
    /// text.
    ViewTest,
    /// Serve the interactive page (web/index.html) with a fresh kit on http://127.0.0.1:PORT.
    Web {
        /// The port.
        #[arg(long, default_value_t = 8080)]
        port: u16,
    },
    /// Replay fuzz/regressions, then fuzz every target (scene TOML, WGSL, PNG, EXR, METAR,
    /// UTC dates) for N seconds each with cargo-fuzz (installed on first use), starting from
    /// its committed corpus (fuzz/seeds/<target>/) and the project's files; prints the runs.
    Fuzz {
        /// Seconds per target.
        #[arg(long, default_value_t = 60)]
        seconds: u32,
        /// Instead of a time: stop each target after exactly this many runs (libFuzzer's
        /// `-runs`), however long it takes.
        #[arg(long, value_name = "N")]
        runs: Option<u64>,
        /// Only this target (repeatable); every target by default.
        #[arg(long, value_name = "NAME", value_parser = clap::builder::PossibleValuesParser::new(fuzz::FUZZ_TARGETS))]
        target: Vec<String>,
        /// After fuzzing, replace the committed corpus (fuzz/seeds/<target>/) with the fewest
        /// inputs, from it, this run's corpus and the project's files, that reach every edge
        /// they reach (libFuzzer's -set_cover_merge=1); commit the result.
        #[arg(long)]
        update_seeds: bool,
    },
    /// Pack what the conformance suite needs on a machine with a GPU and no cargo (the test
    /// binary, `stratus`, glslang, SPIRV-Tools, the validation layer) into
    /// `.device/bundle.tar.gz`; `tests/device/run.sh` runs it there (see its comments).
    DeviceBundle,
    /// Pack what the GPU benchmark needs on a machine with a GPU and no cargo (`stratus`, and
    /// with --peer-wgsl the peer harness of ../shared/peer-bench with the peer's WGSL) into
    /// `.device/bench.tar.gz`; `tests/device/bench.sh` runs `stratus gpu-bench` there and
    /// writes its table.
    DeviceBench {
        /// The peer's extracted WGSL folder (see ../shared/peer-bench/README.md; kept outside
        /// the repository, packed into the ignored .device/ only).
        #[arg(long)]
        peer_wgsl: Option<PathBuf>,
    },
    /// Opt-in, not in CI (needs the network once): install astropy in a virtual environment
    /// under target/, write the expected sun and moon positions, phases, sunrises and sunsets
    /// of random dates and places to crates/astro/tests/data/ephemeris.json, the brightest
    /// catalogue stars' and the galactic centre's to crates/astro/tests/data/stars.json, and
    /// run stratus-astro's tests against them.
    EphemerisCheck {
        /// Random dates and places.
        #[arg(long, default_value_t = 600)]
        cases: u32,
        /// How many of them also get sunrise and sunset.
        #[arg(long, default_value_t = 150)]
        events: u32,
    },
    /// Opt-in, not in CI (needs the network once): install Mitsuba 3 in a virtual environment
    /// under target/, export a gridded cloud with `stratus export-volume`, render it with
    /// Mitsuba and with the reference's path tracer, and compare block averages (single
    /// scattering within 1%, all orders within the Monte Carlo noise).
    MitsubaCheck {
        /// Reference samples per pixel.
        #[arg(long, default_value_t = 4096)]
        reference_spp: u32,
        /// Mitsuba samples per pixel of each independent pass.
        #[arg(long, default_value_t = 1024)]
        mitsuba_spp: u32,
        /// Independent Mitsuba passes (their spread gives Mitsuba's standard error).
        #[arg(long, default_value_t = 8)]
        passes: u32,
        /// Block size in pixels.
        #[arg(long, default_value_t = 8)]
        block: u32,
        /// Extra arguments for `stratus export-volume` (e.g. `--preset storm`).
        #[arg(last = true)]
        export_args: Vec<String>,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let root = workspace_root();
    let result = match cli.task {
        Task::BuildShaders {
            wgsl,
            out,
            check,
            languages,
            translations,
        } => shaders::build_shaders(
            &root,
            &wgsl.unwrap_or_else(|| root.join("wgsl")),
            &out.unwrap_or_else(|| root.join("spirv-out")),
            check,
            (languages == shaders::LanguageChoice::All)
                .then(|| translations.unwrap_or_else(|| target_dir(&root).join("shaders")))
                .as_deref(),
        ),
        Task::Validate { out } => {
            shaders::validate(&root, &out.unwrap_or_else(|| root.join("spirv-out")))
        }
        Task::Ci => ci::ci(&root),
        Task::Conformance => ci::conformance(&root),
        Task::Export { out } => web::export(&root, &out),
        Task::WebTest => web::web_test(&root).map(|_| ()),
        Task::ViewTest => view::view_test(&root),
        Task::Web { port } => web::web(&root, port),
        Task::Fuzz {
            seconds,
            runs,
            target,
            update_seeds,
        } => fuzz::fuzz(&root, seconds, runs, &target, update_seeds),
        Task::DeviceBundle => device::bundle(&root),
        Task::DeviceBench { peer_wgsl } => device::bench(&root, peer_wgsl.as_deref()),
        Task::EphemerisCheck { cases, events } => ephemeris::check(&root, cases, events),
        Task::MitsubaCheck {
            reference_spp,
            mitsuba_spp,
            passes,
            block,
            export_args,
        } => mitsuba::mitsuba_check(
            &root,
            &mitsuba::MitsubaSettings {
                reference_spp,
                mitsuba_spp,
                passes,
                block,
                export_args,
            },
        ),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}

fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask lives in the workspace")
        .to_path_buf()
}

/// How a folder is named in diagnostics: relative to the workspace root when inside it.
fn label(root: &Path, dir: &Path) -> String {
    let abs = dir.canonicalize().unwrap_or_else(|_| dir.to_path_buf());
    let root = root.canonicalize().unwrap_or_else(|_| root.to_path_buf());
    abs.strip_prefix(&root)
        .map(|p| p.display().to_string())
        .unwrap_or_else(|_| dir.display().to_string())
}

fn cargo(root: &Path, args: &[&str]) -> Result<()> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let mut cmd = Command::new(&cargo);
    cmd.args(args).current_dir(root);
    // Headless, the Vulkan loader's Wayland WSI prints "error: XDG_RUNTIME_DIR is invalid or
    // not set" whenever a test creates an instance; give it a private dir so that real errors
    // stand out in the log (the `stratus` CLI does the same).
    if std::env::var_os("XDG_RUNTIME_DIR").is_none() {
        let dir = std::env::temp_dir().join("stratus-runtime");
        if std::fs::create_dir_all(&dir).is_ok() {
            cmd.env("XDG_RUNTIME_DIR", dir);
        }
    }
    let status = cmd
        .status()
        .with_context(|| format!("running cargo {}", args.join(" ")))?;
    if !status.success() {
        bail!("`cargo {}` failed ({status})", args.join(" "));
    }
    Ok(())
}

fn step(name: &str, f: impl FnOnce() -> Result<()>) -> Result<()> {
    println!("\n==> {name}");
    let t = Instant::now();
    let r = f();
    println!(
        "<== {name}: {} in {:.0?}{}",
        if r.is_ok() { "ok" } else { "FAILED" },
        t.elapsed(),
        disk_free(Path::new("."))
            .map(|f| format!(" ({f} free on this disk)"))
            .unwrap_or_default()
    );
    r
}

/// The space left on the disk that holds `path`, as `df` prints it (e.g. "41G"), when `df`
/// can say. CI prints it after every step: one run ran out of disk in its fuzz build, and the
/// log could not say which step had used the space.
fn disk_free(path: &Path) -> Option<String> {
    let out = Command::new("df")
        .args(["-h", "--output=avail"])
        .arg(path)
        .output()
        .ok()?;
    let text = String::from_utf8(out.stdout).ok()?;
    Some(text.lines().nth(1)?.trim().to_string())
}

/// The target folder (`CARGO_TARGET_DIR` or `<root>/target`).
fn target_dir(root: &Path) -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .map(|d| if d.is_absolute() { d } else { root.join(d) })
        .unwrap_or_else(|| root.join("target"))
}

/// A Python virtual environment at `venv` where `check` (Python code) prints `version`,
/// installing `packages` with pip if it does not (the network is needed once).
fn python_venv(venv: &Path, check: &str, version: &str, packages: &[&str]) -> Result<()> {
    let python = venv.join("bin").join("python");
    if !python.exists() {
        run(Command::new("python3").args(["-m", "venv"]).arg(venv))?;
    }
    let have = Command::new(&python).args(["-c", check]).output();
    match have {
        Ok(o) if o.status.success() && String::from_utf8_lossy(&o.stdout).trim() == version => {
            Ok(())
        }
        _ => run(Command::new(&python)
            .args(["-m", "pip", "install", "--disable-pip-version-check"])
            .args(packages)),
    }
}

/// Runs a command, failing if it does.
fn run(cmd: &mut Command) -> Result<()> {
    let status = cmd
        .status()
        .with_context(|| format!("running {:?}", cmd.get_program()))?;
    if !status.success() {
        bail!("{:?} failed ({status})", cmd.get_program());
    }
    Ok(())
}
