//! `cargo xtask`: the project's build and check tasks (matklad's cargo-xtask convention).
//!
//! - `build-shaders`: validate `wgsl/` with naga and write `spirv-out/` (or `--check` it);
//! - `validate`: run the external validators over `spirv-out/`;
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
//! - `ephemeris-check` (opt-in, not in CI): stratus-astro's expected values from astropy;
//! - `mitsuba-check` (opt-in, not in CI): the CPU reference against Mitsuba 3 on a gridded
//!   cloud (see [`mitsuba_check`]).

use std::{
    collections::BTreeMap,
    path::{Path, PathBuf},
    process::{Command, ExitCode},
    time::Instant,
};

mod device;
mod ephemeris;

use anyhow::{Context, Result, bail};
use clap::{Parser, Subcommand};
use stratus_shaders::{ShaderTree, build_outputs};

#[derive(Parser)]
#[command(name = "cargo xtask", about = "Stratus build and check tasks", version)]
struct Cli {
    #[command(subcommand)]
    task: Task,
}

#[derive(Subcommand)]
enum Task {
    /// Validate the WGSL with naga and write SPIR-V, GLSL, HLSL, MSL and manifest.json.
    BuildShaders {
        /// Folder holding the WGSL and `modules.toml` [default: <workspace>/wgsl].
        #[arg(long)]
        wgsl: Option<PathBuf>,
        /// Output folder [default: <workspace>/spirv-out].
        #[arg(long)]
        out: Option<PathBuf>,
        /// Change nothing; fail and name every stale, missing or extra file.
        #[arg(long)]
        check: bool,
    },
    /// Run spirv-val and glslangValidator over `spirv-out/` and print a table.
    Validate {
        /// Folder with the generated shaders [default: <workspace>/spirv-out].
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
    /// Replay fuzz/regressions, then fuzz every target (scene TOML, WGSL, PNG, EXR, METAR)
    /// for N seconds each with cargo-fuzz (installed on first use); prints the runs.
    Fuzz {
        /// Seconds per target.
        #[arg(long, default_value_t = 60)]
        seconds: u32,
        /// Instead of a time: stop each target after exactly this many runs (libFuzzer's
        /// `-runs`), however long it takes.
        #[arg(long, value_name = "N")]
        runs: Option<u64>,
        /// Only this target (repeatable); every target by default.
        #[arg(long, value_name = "NAME", value_parser = clap::builder::PossibleValuesParser::new(FUZZ_TARGETS))]
        target: Vec<String>,
    },
    /// Pack what the conformance suite needs on a machine with a GPU and no cargo (the test
    /// binary, `stratus`, glslang, SPIRV-Tools, the validation layer) into
    /// `.device/bundle.tar.gz`; `tests/device/run.sh` runs it there (see its comments).
    DeviceBundle,
    /// Opt-in, not in CI (needs the network once): install astropy in a virtual environment
    /// under target/, write the expected sun and moon positions, phases, sunrises and sunsets
    /// of random dates and places to crates/astro/tests/data/ephemeris.json, and run
    /// stratus-astro's test against them.
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
        Task::BuildShaders { wgsl, out, check } => build_shaders(
            &root,
            &wgsl.unwrap_or_else(|| root.join("wgsl")),
            &out.unwrap_or_else(|| root.join("spirv-out")),
            check,
        ),
        Task::Validate { out } => validate(&out.unwrap_or_else(|| root.join("spirv-out"))),
        Task::Ci => ci(&root),
        Task::Conformance => conformance(&root),
        Task::Export { out } => export(&root, &out),
        Task::WebTest => web_test(&root).map(|_| ()),
        Task::ViewTest => view_test(&root),
        Task::Web { port } => web(&root, port),
        Task::Fuzz {
            seconds,
            runs,
            target,
        } => fuzz(&root, seconds, runs, &target),
        Task::DeviceBundle => device::bundle(&root),
        Task::EphemerisCheck { cases, events } => ephemeris::check(&root, cases, events),
        Task::MitsubaCheck {
            reference_spp,
            mitsuba_spp,
            passes,
            block,
            export_args,
        } => mitsuba_check(
            &root,
            &MitsubaSettings {
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

fn build_shaders(root: &Path, wgsl: &Path, out: &Path, check: bool) -> Result<()> {
    let tree = ShaderTree::from_dir(wgsl, &label(root, wgsl))?;
    let outputs = match build_outputs(&tree) {
        Ok(o) => o,
        Err(diags) => {
            eprintln!("{diags}");
            bail!("{} WGSL error(s) in {}", diags.0.len(), wgsl.display());
        }
    };
    let existing = list_generated(out)?;
    let mut problems = Vec::new();
    for (name, bytes) in &outputs {
        match existing.get(name) {
            None => problems.push(format!("missing: {}", out.join(name).display())),
            Some(old) if old != bytes => {
                problems.push(format!("stale: {}", out.join(name).display()))
            }
            _ => {}
        }
    }
    for name in existing.keys().filter(|n| !outputs.contains_key(*n)) {
        problems.push(format!(
            "extra (no longer generated): {}",
            out.join(name).display()
        ));
    }
    if check {
        if problems.is_empty() {
            println!("{} is fresh ({} files)", out.display(), outputs.len());
            return Ok(());
        }
        for p in &problems {
            eprintln!("{p}");
        }
        bail!(
            "{} is out of date with {} ({} file(s)); run `cargo xtask build-shaders`",
            out.display(),
            wgsl.display(),
            problems.len()
        );
    }
    std::fs::create_dir_all(out).with_context(|| format!("creating {}", out.display()))?;
    for name in existing.keys().filter(|n| !outputs.contains_key(*n)) {
        std::fs::remove_file(out.join(name))?;
    }
    for (name, bytes) in &outputs {
        if existing.get(name) != Some(bytes) {
            std::fs::write(out.join(name), bytes)
                .with_context(|| format!("writing {}", out.join(name).display()))?;
        }
    }
    println!(
        "wrote {} files to {} ({} changed)",
        outputs.len(),
        out.display(),
        problems.len()
    );
    Ok(())
}

/// The files in `out` that build-shaders owns (so stray README files are left alone).
fn list_generated(out: &Path) -> Result<BTreeMap<String, Vec<u8>>> {
    let mut files = BTreeMap::new();
    let Ok(entries) = std::fs::read_dir(out) else {
        return Ok(files);
    };
    for e in entries {
        let path = e?.path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let owned = [".spv", ".glsl", ".hlsl", ".metal", ".wgsl", "manifest.json"]
            .iter()
            .any(|ext| name.ends_with(ext));
        if owned && path.is_file() {
            files.insert(name, std::fs::read(&path)?);
        }
    }
    Ok(files)
}

#[derive(Clone, Copy, PartialEq)]
enum Verdict {
    Pass,
    Fail,
    Skipped,
}

struct Row {
    file: String,
    tool: String,
    verdict: Verdict,
    detail: String,
}

fn run_tool(cmd: &mut Command) -> (Verdict, String) {
    match cmd.output() {
        Ok(o) if o.status.success() => (Verdict::Pass, String::new()),
        Ok(o) => (
            Verdict::Fail,
            format!(
                "{}{}",
                String::from_utf8_lossy(&o.stdout),
                String::from_utf8_lossy(&o.stderr)
            ),
        ),
        Err(e) => (
            Verdict::Fail,
            format!("could not run {:?}: {e}", cmd.get_program()),
        ),
    }
}

fn validate(out: &Path) -> Result<()> {
    let manifest_path = out.join("manifest.json");
    let manifest = stratus_shaders::Manifest::from_json(
        &std::fs::read_to_string(&manifest_path)
            .with_context(|| format!("reading {}", manifest_path.display()))?,
    )
    .with_context(|| format!("parsing {}", manifest_path.display()))?;
    let tmp = std::env::temp_dir().join(format!("stratus-validate-{}", std::process::id()));
    std::fs::create_dir_all(&tmp)?;
    let has_metal = Command::new("xcrun")
        .arg("--find")
        .arg("metal")
        .output()
        .is_ok_and(|o| o.status.success());
    let mut rows = Vec::new();
    for m in &manifest.modules {
        for v in &m.variants {
            let f = &v.files;
            let (verdict, detail) = run_tool(Command::new("spirv-val").arg(out.join(&f.spv)));
            rows.push(Row {
                file: f.spv.clone(),
                tool: "spirv-val".into(),
                verdict,
                detail,
            });
            for (entry, file) in &f.glsl {
                let stage = m
                    .entry_point(entry)
                    .map_or("comp", |e| e.stage.glsl_suffix());
                let (verdict, detail) = run_tool(
                    Command::new("glslangValidator")
                        .args(["-S", stage])
                        .arg(out.join(file)),
                );
                rows.push(Row {
                    file: file.clone(),
                    tool: "glslangValidator".into(),
                    verdict,
                    detail,
                });
            }
            for ep in &m.entry_points {
                let spv = tmp.join(format!("{}.{}.{}.spv", m.name, v.name, ep.name));
                let stage = ep.stage.glsl_suffix();
                let (mut verdict, mut detail) = run_tool(
                    Command::new("glslangValidator")
                        .args(["-D", "-V", "-e", &ep.name, "-S", stage, "-o"])
                        .arg(&spv)
                        .arg(out.join(&f.hlsl)),
                );
                if verdict == Verdict::Pass {
                    (verdict, detail) = run_tool(Command::new("spirv-val").arg(&spv));
                }
                rows.push(Row {
                    file: format!("{} ({})", f.hlsl, ep.name),
                    tool: "glslangValidator -D -V + spirv-val".into(),
                    verdict,
                    detail,
                });
            }
            if has_metal {
                let (verdict, detail) = run_tool(
                    Command::new("xcrun")
                        .args(["-sdk", "macosx", "metal", "-c", "-o"])
                        .arg(tmp.join("out.air"))
                        .arg(out.join(&f.metal)),
                );
                rows.push(Row {
                    file: f.metal.clone(),
                    tool: "xcrun metal".into(),
                    verdict,
                    detail,
                });
            } else {
                rows.push(Row {
                    file: f.metal.clone(),
                    tool: "xcrun metal".into(),
                    verdict: Verdict::Skipped,
                    detail: "not compiled: no Metal toolchain here".into(),
                });
            }
        }
    }
    let _ = std::fs::remove_dir_all(&tmp);

    let wf = rows.iter().map(|r| r.file.len()).max().unwrap_or(4).max(4);
    let wt = rows.iter().map(|r| r.tool.len()).max().unwrap_or(4).max(4);
    println!("{:wf$}  {:wt$}  result", "file", "tool");
    println!("{}  {}  {}", "-".repeat(wf), "-".repeat(wt), "-".repeat(7));
    for r in &rows {
        let v = match r.verdict {
            Verdict::Pass => "PASS".to_string(),
            Verdict::Fail => "FAIL".to_string(),
            Verdict::Skipped => format!("SKIPPED ({})", r.detail),
        };
        println!("{:wf$}  {:wt$}  {v}", r.file, r.tool);
    }
    let failed: Vec<_> = rows.iter().filter(|r| r.verdict == Verdict::Fail).collect();
    for r in &failed {
        eprintln!("\n--- {} ({}) ---\n{}", r.file, r.tool, r.detail.trim_end());
    }
    let pass = rows.iter().filter(|r| r.verdict == Verdict::Pass).count();
    let skipped = rows
        .iter()
        .filter(|r| r.verdict == Verdict::Skipped)
        .count();
    println!(
        "validate: {pass} passed, {} failed, {skipped} skipped",
        failed.len()
    );
    if !failed.is_empty() {
        bail!("{} validation(s) failed", failed.len());
    }
    Ok(())
}

/// System packages the project needs, and why (also listed in the README).
const APT_PACKAGES: &[&str] = &[
    "mesa-vulkan-drivers",
    "libvulkan1",
    "vulkan-tools",
    "vulkan-validationlayers",
    "spirv-tools",
    "glslang-tools",
    "spirv-cross",
    "libegl1",
    "libgl1-mesa-dri",
    "ffmpeg",
    "chromium",
    // The viewer's test: a virtual X server, and the X libraries winit loads.
    "xvfb",
    "libx11-6",
    "libxcursor1",
    "libxrandr2",
    "libxi6",
    "libxkbcommon-x11-0",
];

fn missing_tools() -> Vec<String> {
    let mut missing = Vec::new();
    for tool in [
        "spirv-val",
        "glslangValidator",
        "vulkaninfo",
        "ffmpeg",
        "chromium",
        "Xvfb",
    ] {
        // ffmpeg takes -version, the others --version; both only need to start.
        if Command::new(tool).arg("--version").output().is_err() {
            missing.push(format!("`{tool}`"));
        }
    }
    let icd_dirs = ["/usr/share/vulkan/icd.d", "/etc/vulkan/icd.d"];
    let has_lavapipe = icd_dirs.iter().any(|d| {
        std::fs::read_dir(d).is_ok_and(|rd| {
            rd.flatten()
                .any(|e| e.file_name().to_string_lossy().starts_with("lvp_icd"))
        })
    });
    if !has_lavapipe {
        missing.push("a Vulkan ICD (lavapipe)".into());
    }
    if !Path::new("/usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json").exists() {
        missing.push("the Vulkan validation layer".into());
    }
    if !Path::new("/usr/lib/x86_64-linux-gnu/libEGL.so.1").exists()
        && !Path::new("/usr/lib/aarch64-linux-gnu/libEGL.so.1").exists()
    {
        missing.push("libEGL (for wgpu's GL backend)".into());
    }
    missing
}

fn ensure_tools() -> Result<()> {
    let missing = missing_tools();
    if missing.is_empty() {
        println!("system tools: all present");
        return Ok(());
    }
    let install = format!(
        "apt-get update && apt-get install -y --no-install-recommends {}",
        APT_PACKAGES.join(" ")
    );
    println!("system tools missing: {}", missing.join(", "));
    let is_root = Command::new("id")
        .arg("-u")
        .output()
        .is_ok_and(|o| o.stdout.starts_with(b"0"));
    let sudo = !is_root
        && Command::new("sudo")
            .args(["-n", "true"])
            .output()
            .is_ok_and(|o| o.status.success());
    if !is_root && !sudo {
        bail!("cannot install system packages without root; run:\n    sudo sh -c '{install}'");
    }
    println!("installing: {}", APT_PACKAGES.join(" "));
    let mut cmd = if sudo {
        let mut c = Command::new("sudo");
        c.args(["sh", "-c", &install]);
        c
    } else {
        let mut c = Command::new("sh");
        c.args(["-c", &install]);
        c
    };
    cmd.env("DEBIAN_FRONTEND", "noninteractive");
    let status = cmd.status().context("running apt-get")?;
    if !status.success() {
        bail!("apt-get failed ({status}); run it by hand:\n    {install}");
    }
    let still = missing_tools();
    if !still.is_empty() {
        bail!("still missing after installing: {}", still.join(", "));
    }
    Ok(())
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

fn ci(root: &Path) -> Result<()> {
    let t = Instant::now();
    // A clean clone builds everything once: incremental caches would only double the disk
    // the workspace's own crates take.
    // SAFETY: xtask is single-threaded; the variable is set before any child is spawned.
    unsafe { std::env::set_var("CARGO_INCREMENTAL", "0") };
    step("system tools", ensure_tools)?;
    step("cargo fmt --check", || {
        cargo(root, &["fmt", "--all", "--check"])
    })?;
    step("cargo clippy", || {
        cargo(
            root,
            &[
                "clippy",
                "--workspace",
                "--all-targets",
                "--",
                "-D",
                "warnings",
            ],
        )
    })?;
    step("build-shaders --check", || {
        build_shaders(root, &root.join("wgsl"), &root.join("spirv-out"), true)
    })?;
    step("validate", || validate(&root.join("spirv-out")))?;
    // The browser path first: the conformance suite's `web-tint` column reads its results.
    step("web-test", || web_test(root).map(|_| ()))?;
    step("fuzz (10 s a target)", || {
        let r = fuzz(root, 10, None, &[]);
        // The sanitizer build is of no use to the steps after it; its disk is.
        let _ = std::fs::remove_dir_all(root.join("fuzz/target"));
        r
    })?;
    step("view-test", || view_test(root))?;
    // ... and there a missing browser image fails the column instead of leaving it empty.
    // SAFETY: xtask is single-threaded; the variable is set before any child is spawned.
    unsafe { std::env::set_var("STRATUS_REQUIRE_WEB_TINT", "1") };
    step("cargo test", || cargo(root, &["test", "--workspace"]))?;
    println!("\nci: all steps passed in {:.0?}", t.elapsed());
    Ok(())
}

/// Runs the conformance suite alone. The suite itself prints the table and writes the
/// Markdown (to the target folder it was built in); this says where, pass or fail.
fn conformance(root: &Path) -> Result<()> {
    let t = Instant::now();
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .map(|d| if d.is_absolute() { d } else { root.join(d) })
        .unwrap_or_else(|| root.join("target"));
    let table = target.join("conformance.md");
    // A table from an earlier run must not pass for this one's.
    let _ = std::fs::remove_file(&table);
    let result = cargo(
        root,
        &["test", "-p", "stratus-tests", "--test", "conformance"],
    );
    println!(
        "\nconformance: {} in {:.0?}",
        if result.is_ok() { "passed" } else { "FAILED" },
        t.elapsed()
    );
    if table.exists() {
        println!("Markdown table: {}", table.display());
    } else {
        println!(
            "no Markdown table was written ({} is missing)",
            table.display()
        );
    }
    result
}

/// The target folder (`CARGO_TARGET_DIR` or `<root>/target`).
fn target_dir(root: &Path) -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .map(|d| if d.is_absolute() { d } else { root.join(d) })
        .unwrap_or_else(|| root.join("target"))
}

/// `cargo xtask export --out DIR`: `stratus export-kit` from this checkout.
fn export(root: &Path, out: &Path) -> Result<()> {
    let out = if out.is_absolute() {
        out.to_path_buf()
    } else {
        std::env::current_dir()?.join(out)
    };
    let out = out.to_string_lossy().into_owned();
    cargo(
        root,
        &[
            "run",
            "-q",
            "-p",
            "stratus-cli",
            "--",
            "export-kit",
            "--out",
            &out,
        ],
    )
}

/// Runs `node` with `args` in `web/`, failing with what to install when it cannot start.
fn node(root: &Path, args: &[&str]) -> Result<()> {
    let status = Command::new("node")
        .args(args)
        .current_dir(root.join("web"))
        .status()
        .context("running node (install Node.js 20 or later)")?;
    if !status.success() {
        bail!("`node {}` failed ({status})", args.join(" "));
    }
    Ok(())
}

/// The page's npm dependencies (playwright-core, pinned by web/package-lock.json).
fn npm_ci(root: &Path) -> Result<()> {
    if root.join("web/node_modules/playwright-core").exists() {
        return Ok(());
    }
    let status = Command::new("npm")
        .args(["ci", "--no-audit", "--no-fund"])
        .current_dir(root.join("web"))
        .status()
        .context("running npm (install Node.js 20 or later, with npm)")?;
    if !status.success() {
        bail!("`npm ci` in web/ failed ({status})");
    }
    Ok(())
}

/// FLIP of the browser's image of each golden against the kit's golden image (Tint and
/// SwiftShader against naga and lavapipe). Measured on the six presets: mean 2.10e-3 to
/// 9.61e-3, p99 up to 5.70e-2 (inside-layer): the CPU reference's pattern and size (both
/// filter textures at full precision where lavapipe quantises the weights). The same bounds as
/// the conformance suite's for the CPU and for this path (`web-tint`).
const WEB_TINT_FLIP_MEAN: f64 = 2e-2;
/// See [`WEB_TINT_FLIP_MEAN`].
const WEB_TINT_FLIP_P99: f64 = 8e-2;

/// `cargo xtask web-test`: returns each golden's FLIP mean.
fn web_test(root: &Path) -> Result<Vec<(String, f64)>> {
    let t = Instant::now();
    npm_ci(root)?;
    let target = target_dir(root);
    let kit = target.join("kit");
    let out = target.join("web-test");
    let _ = std::fs::remove_dir_all(&out);
    export(root, &kit)?;
    let (kit_s, out_s) = (
        kit.to_string_lossy().into_owned(),
        out.to_string_lossy().into_owned(),
    );
    node(root, &["test/run.mjs", "--kit", &kit_s, "--out", &out_s])?;
    let index: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(kit.join("kit.json"))?)?;
    let results: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("results.json"))?)?;
    let goldens = index["goldens"]
        .as_array()
        .context("kit.json: no goldens")?;
    let mut flips = Vec::new();
    let mut problems = Vec::new();
    println!("web-tint ({}):", results["adapter"]);
    for g in goldens {
        let name = g["name"].as_str().context("a golden without a name")?;
        let golden = stratus_compare::Image::load(&kit.join(g["image"].as_str().unwrap_or("")))?;
        let web = stratus_compare::Image::load(&out.join(format!("{name}.png")))?;
        let r =
            stratus_compare::compare(&golden, &web, &stratus_compare::CompareOptions::default())?;
        println!(
            "  {name:24} FLIP mean {:.2e}  p99 {:.2e}  max {:.3}",
            r.flip.mean, r.flip.p99, r.flip.max
        );
        if !(r.flip.mean <= WEB_TINT_FLIP_MEAN && r.flip.p99 <= WEB_TINT_FLIP_P99) {
            problems.push(format!(
                "{name}: FLIP mean {:.2e} (bound {WEB_TINT_FLIP_MEAN:.0e}), p99 {:.2e} (bound {WEB_TINT_FLIP_P99:.0e})",
                r.flip.mean, r.flip.p99
            ));
        }
        flips.push((name.to_string(), r.flip.mean));
    }
    let summary = serde_json::json!({
        "adapter": results["adapter"],
        "bound_flip_mean": WEB_TINT_FLIP_MEAN,
        "goldens": flips.iter().map(|(n, f)| serde_json::json!({"name": n, "flip_mean": f})).collect::<Vec<_>>(),
        "problems": problems,
    });
    std::fs::write(
        target.join("web-tint.json"),
        serde_json::to_string_pretty(&summary)? + "\n",
    )?;
    println!(
        "web-test: {} goldens in {:.0?}; results in {}",
        flips.len(),
        t.elapsed(),
        target.join("web-tint.json").display()
    );
    if !problems.is_empty() {
        bail!("web-tint: {}", problems.join("; "));
    }
    Ok(flips)
}

/// `cargo xtask web`: a fresh kit under target/kit, and the page served with it.
fn web(root: &Path, port: u16) -> Result<()> {
    let kit = target_dir(root).join("kit");
    export(root, &kit)?;
    node(
        root,
        &[
            "test/server.mjs",
            "--kit",
            &kit.to_string_lossy(),
            "--port",
            &port.to_string(),
        ],
    )
}

/// The cargo-fuzz targets (fuzz/Cargo.toml).
const FUZZ_TARGETS: [&str; 6] = [
    "scene_toml",
    "wgsl",
    "image_png",
    "image_exr",
    "metar",
    "utc_date",
];

/// `cargo xtask fuzz --seconds N [--runs N] [--target NAME]...`.
fn fuzz(root: &Path, seconds: u32, runs_limit: Option<u64>, only: &[String]) -> Result<()> {
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
                done = text
                    .lines()
                    .find(|l| l.starts_with("Done "))
                    .unwrap_or("Done (no summary)")
                    .to_string();
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

/// The Mitsuba version `mitsuba-check` installs.
const MITSUBA: &str = "mitsuba==3.9.1";

/// The renders and comparison of `mitsuba-check` (written to target/mitsuba-check/check.py).
const MITSUBA_SCRIPT: &str = include_str!("mitsuba_check.py");

/// Settings of `mitsuba-check`.
struct MitsubaSettings {
    reference_spp: u32,
    mitsuba_spp: u32,
    passes: u32,
    block: u32,
    export_args: Vec<String>,
}

/// `cargo xtask mitsuba-check`: the CPU reference's path tracer against Mitsuba 3 (scalar_rgb
/// variant) on the same gridded medium, sun and constant sky. Mitsuba's `volpath` with
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
fn mitsuba_check(root: &Path, s: &MitsubaSettings) -> Result<()> {
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

/// The viewer's screenshots must differ by at least this mean FLIP (the camera moved, turned
/// and the sun went low: measured 0.2).
const VIEW_MIN_DIFFERENCE: f64 = 0.02;
/// Neither screenshot is flat: the standard deviation of its luminance (0-1) outside the
/// overlay is at least this (a sky with clouds and ground: measured about 0.2).
const VIEW_MIN_CONTRAST: f64 = 0.03;
/// The overlay's text shows: glyph edges (a light pixel next to the overlay's dark fill)
/// inside the overlay's rectangle, at least this many (measured over 2000 at 480x270).
const VIEW_MIN_TEXT_EDGES: usize = 300;

fn view_test(root: &Path) -> Result<()> {
    let t = Instant::now();
    let target = target_dir(root);
    let out = target.join("view-test");
    let _ = std::fs::remove_dir_all(&out);
    cargo(root, &["build", "-q", "-p", "stratus-cli"])?;
    let exe = target.join("debug").join("stratus");
    let (xvfb, display) = start_xvfb()?;
    let script = root.join("tests/view/script.toml");
    let result = Command::new(&exe)
        .args(["view", "--script"])
        .arg(&script)
        .args(["--size", "480x270", "--vsync", "off", "--out-dir"])
        .arg(&out)
        .env("DISPLAY", &display)
        .env("STRATUS_VALIDATION", "1")
        .env(
            "XDG_RUNTIME_DIR",
            std::env::var_os("XDG_RUNTIME_DIR").unwrap_or_else(|| std::env::temp_dir().into()),
        )
        .status();
    stop_xvfb(xvfb);
    let status = result.context("running stratus view")?;
    if !status.success() {
        bail!("stratus view --script failed ({status})");
    }
    let shot = |name: &str| -> Result<(stratus_compare::Image, [f64; 4])> {
        let image = stratus_compare::Image::load(&out.join(format!("{name}.png")))?;
        let info: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join(format!("{name}.json")))?)?;
        let r = info["overlay_px"]
            .as_array()
            .with_context(|| format!("{name}.json: no overlay rectangle (overlay hidden?)"))?;
        let r: Vec<f64> = r.iter().filter_map(serde_json::Value::as_f64).collect();
        Ok((image, [r[0], r[1], r[2], r[3]]))
    };
    let path = std::fs::read_to_string(out.join("path-001.toml"))
        .context("the recorded camera path (path-001.toml) was not written")?;
    let keyframes = path.matches("[[animation.keyframes]]").count();
    println!("view-test: the recorded camera path has {keyframes} keyframes");
    let (first, r1) = shot("first")?;
    let (second, r2) = shot("second")?;
    let mut problems = Vec::new();
    let diff =
        stratus_compare::compare(&first, &second, &stratus_compare::CompareOptions::default())?;
    println!(
        "view-test: the screenshots differ by FLIP mean {:.3}",
        diff.flip.mean
    );
    if keyframes < 2 {
        problems.push(format!("the recorded path has {keyframes} keyframes"));
    }
    if diff.flip.mean < VIEW_MIN_DIFFERENCE {
        problems.push(format!(
            "the screenshots barely differ (FLIP mean {:.4} < {VIEW_MIN_DIFFERENCE})",
            diff.flip.mean
        ));
    }
    for (name, image, rect) in [("first", &first, r1), ("second", &second, r2)] {
        let (contrast, edges) = overlay_stats(image, rect);
        println!(
            "view-test: {name}: luminance std-dev {contrast:.3} outside the overlay, {edges} text edges in it"
        );
        if contrast < VIEW_MIN_CONTRAST {
            problems.push(format!("{name} is flat (luminance std-dev {contrast:.4})"));
        }
        if edges < VIEW_MIN_TEXT_EDGES {
            problems.push(format!(
                "{name}: no overlay text ({edges} glyph edges < {VIEW_MIN_TEXT_EDGES})"
            ));
        }
    }
    println!(
        "view-test: {:.0?}; screenshots in {}",
        t.elapsed(),
        out.display()
    );
    if !problems.is_empty() {
        bail!("view-test: {}", problems.join("; "));
    }
    Ok(())
}

/// The luminance standard deviation outside the overlay's rectangle `[x0, y0, x1, y1]`, and
/// the glyph edges inside it: light pixels (luminance > 0.45) next to dark ones (< 0.12).
fn overlay_stats(image: &stratus_compare::Image, rect: [f64; 4]) -> (f64, usize) {
    let (w, h) = (image.width as usize, image.height as usize);
    let lum = |x: usize, y: usize| {
        let p = &image.rgba[4 * (y * w + x)..4 * (y * w + x) + 3];
        0.2126 * f64::from(p[0]) + 0.7152 * f64::from(p[1]) + 0.0722 * f64::from(p[2])
    };
    let inside = |x: usize, y: usize| {
        (x as f64) >= rect[0]
            && (x as f64) < rect[2]
            && (y as f64) >= rect[1]
            && (y as f64) < rect[3]
    };
    let (mut n, mut sum, mut sum2, mut edges) = (0.0f64, 0.0f64, 0.0f64, 0usize);
    for y in 0..h {
        for x in 0..w {
            let l = lum(x, y);
            if !inside(x, y) {
                n += 1.0;
                sum += l;
                sum2 += l * l;
            } else if l > 0.45
                && x + 1 < w
                && y + 1 < h
                && (lum(x + 1, y) < 0.12 || lum(x, y + 1) < 0.12)
            {
                edges += 1;
            }
        }
    }
    let mean = sum / n.max(1.0);
    ((sum2 / n.max(1.0) - mean * mean).max(0.0).sqrt(), edges)
}

/// Whether display `:n` is taken: by a lock file naming a running process, or by a socket
/// without a lock. A lock whose process is gone (a server that was killed, which leaves its
/// lock and socket behind) is stale: both are removed and the display is free again.
fn display_taken(n: u32) -> bool {
    let socket = PathBuf::from(format!("/tmp/.X11-unix/X{n}"));
    let lock = PathBuf::from(format!("/tmp/.X{n}-lock"));
    match std::fs::read_to_string(&lock) {
        Ok(text) => {
            let alive = match text.trim().parse::<u32>() {
                Ok(pid) => Path::new(&format!("/proc/{pid}")).exists(),
                // Not a lock we can read: leave it alone.
                Err(_) => true,
            };
            if alive {
                return true;
            }
            let _ = std::fs::remove_file(&lock);
            let _ = std::fs::remove_file(&socket);
            lock.exists() || socket.exists()
        }
        Err(_) => lock.exists() || socket.exists(),
    }
}

/// Stops Xvfb with SIGTERM, so that it removes its lock file and socket (SIGKILL leaves them,
/// and twenty runs used up every display this test tries), or kills it after 5 s.
fn stop_xvfb(mut xvfb: std::process::Child) {
    let _ = Command::new("kill")
        .args(["-TERM", &xvfb.id().to_string()])
        .status();
    for _ in 0..50 {
        if let Ok(Some(_)) = xvfb.try_wait() {
            return;
        }
        std::thread::sleep(std::time::Duration::from_millis(100));
    }
    let _ = xvfb.kill();
    let _ = xvfb.wait();
}

/// Starts Xvfb on the first free display from :90 and waits for its socket.
fn start_xvfb() -> Result<(std::process::Child, String)> {
    for n in 90..110 {
        let socket = PathBuf::from(format!("/tmp/.X11-unix/X{n}"));
        if display_taken(n) {
            continue;
        }
        let display = format!(":{n}");
        let mut child = Command::new("Xvfb")
            .args([
                display.as_str(),
                "-screen",
                "0",
                "1024x768x24",
                "-nolisten",
                "tcp",
            ])
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .context("starting Xvfb (install it: apt-get install xvfb)")?;
        for _ in 0..100 {
            if socket.exists() {
                return Ok((child, display));
            }
            if let Ok(Some(status)) = child.try_wait() {
                bail!("Xvfb {display} exited at start ({status})");
            }
            std::thread::sleep(std::time::Duration::from_millis(100));
        }
        stop_xvfb(child);
        bail!("Xvfb {display} did not open its socket in 10 s");
    }
    bail!("no free X display between :90 and :109")
}
