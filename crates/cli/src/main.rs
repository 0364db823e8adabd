//! `stratus`: render, inspect and compare volumetric clouds.

use stratus_lab::{bench, export_volume as export, fit, gpu_bench, measure_field, soak};
use stratus_tool::{animate, astro, compare, inspect, kit, render, weather};
use stratus_viewer as view;

use std::{path::PathBuf, process::ExitCode};

use clap::{Parser, Subcommand};

/// Stratus renders physically grounded volumetric clouds from one WGSL source on wgpu (Vulkan
/// or GL), raw Vulkan and the CPU.
#[derive(Parser)]
#[command(name = "stratus", version, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Render a scene to a PNG (tone-mapped) or EXR (linear radiance, alpha = transmittance).
    Render(render::RenderArgs),
    /// Render a scene's animation (camera keyframes, wind) to a video: .mp4 through ffmpeg,
    /// or .gif.
    Animate(animate::AnimateArgs),
    /// Compare two images (PNG or EXR): FLIP on the tone-mapped images; RMSE, max abs and the
    /// worst pixel on linear values when both are EXR.
    Compare(compare::CompareArgs),
    /// List the built-in scene presets.
    Presets,
    /// Work with scene files.
    #[command(subcommand)]
    Scene(SceneCommand),
    /// Speed against accuracy: sweep quality and method settings over a scene set, measure
    /// error against the CPU reference and GPU cost, write results.csv/json and a chart.
    Bench(bench::BenchArgs),
    /// Fit the march's multiple-scattering octaves to the GPU path tracer's all-orders truth
    /// over training scenes, and measure the fit on the presets (held out).
    FitScattering(fit::FitArgs),
    /// Sample the scene's cloud density on a grid and write it as a Mitsuba 3 `.vol` file
    /// (with the flat, single-lobe setup `cargo xtask mitsuba-check` renders).
    ExportVolume(export::ExportArgs),
    /// Write the engine kit: WGSL and its SPIR-V/GLSL/HLSL/MSL, the manifest and frame graph,
    /// the uniform layout (C header, JSON), the noise textures (DDS, raw) and golden images with
    /// their uniform bytes and resolved frame plans, with a README for integrators.
    ExportKit(kit::KitArgs),
    /// Many frames of one renderer on a looping camera path: counts non-finite values, and
    /// reports memory, GPU objects created after the first frame and drift after a stop.
    Soak(soak::SoakArgs),
    /// What a frame costs on this GPU: every preset on each backend, temporal off, 1/4 and
    /// 1/16, at 1080p and 4K; median GPU ms per pass and per frame, CPU ms per frame, and
    /// density evaluations and light samples per pixel; writes results.json and table.md.
    GpuBench(gpu_bench::GpuBenchArgs),
    /// A cloud field's statistics seen straight down: the number of clouds, the
    /// area-perimeter dimension D and the size density's exponent b, against what real cloud
    /// fields measure.
    MeasureField(measure_field::MeasureFieldArgs),
    /// Validate the embedded WGSL with naga and list its modules, variants and entry points.
    Shaders,
    /// Turn weather into a scene: a METAR report (cloud groups become cloud layers), a
    /// weather-service JSON file, or a named weather state; print or write the scene (TOML).
    Weather(weather::WeatherArgs),
    /// Where the sun and moon stand from a place at a UTC date-time (elevation, azimuth
    /// clockwise from north), the moon's phase, and that day's sunrise and sunset, as JSON.
    Astro(astro::AstroArgs),
    /// An interactive window: fly through the clouds (WASD, mouse), with an overlay of pass
    /// times and controls, screenshots (PNG and EXR) and camera-path recording; `--script`
    /// plays timed input events for headless tests.
    View(view::ViewArgs),
}

#[derive(Subcommand)]
enum SceneCommand {
    /// Validate a scene file and print it in full (defaults filled in), or print every error.
    Check {
        /// The scene file (TOML). It may be partial and name a `base` preset.
        file: PathBuf,
    },
}

fn main() -> ExitCode {
    quiet_headless_wsi();
    exit_quietly_on_closed_pipe();
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Render(args) => render::run(args),
        Command::Animate(args) => animate::run(args),
        Command::Compare(args) => compare::run(args),
        Command::Bench(args) => bench::run(args),
        Command::FitScattering(args) => fit::run(args),
        Command::Presets => inspect::presets(),
        Command::Scene(SceneCommand::Check { file }) => inspect::scene_check(&file),
        Command::Shaders => inspect::shaders(),
        Command::ExportVolume(args) => export::run(args),
        Command::ExportKit(args) => kit::run(args),
        Command::Soak(args) => soak::run(args),
        Command::GpuBench(args) => gpu_bench::run(args),
        Command::MeasureField(args) => measure_field::run(args),
        Command::Weather(args) => weather::run(args),
        Command::Astro(args) => astro::run(args),
        Command::View(args) => view::run(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}

/// `stratus compare a b | head -1` closes the pipe early: end quietly, as other command-line
/// tools do, rather than panic in `println!` (Rust ignores SIGPIPE and makes the write fail).
fn exit_quietly_on_closed_pipe() {
    #[cfg(unix)]
    // SAFETY: restores the default disposition of one signal, first thing in main.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

/// Headless, the Vulkan loader's Wayland WSI prints "error: XDG_RUNTIME_DIR is invalid or not
/// set" when it probes for a compositor. Stratus never opens a window, so give it a private
/// runtime dir to probe instead of alarming the user with an error that is not one.
fn quiet_headless_wsi() {
    if std::env::var_os("XDG_RUNTIME_DIR").is_none() {
        let dir = std::env::temp_dir().join("stratus-runtime");
        if std::fs::create_dir_all(&dir).is_ok() {
            // SAFETY: called first thing in main, before any other thread exists.
            unsafe { std::env::set_var("XDG_RUNTIME_DIR", &dir) };
        }
    }
}
