//! `stratus render`: pick a backend, plan the frame, render one frame or a real-time loop of
//! frames with one persistent renderer, write the last frame and the statistics.

use std::{collections::BTreeMap, io::IsTerminal as _, path::PathBuf, sync::Arc, time::Instant};

use anyhow::{Context, Result, bail};
use clap::{Args, ValueEnum};
use indicatif::{ProgressBar, ProgressStyle};
use serde_json::json;
use stratus_graph::{FrameInput, FrameOutput, FramePlan, Readback, output::median};
use stratus_quality::{DEFAULT_RESULTS, Results, auto_quality};
use stratus_reference::CpuBackend;
use stratus_scene::{Scene, Temporal};

use crate::{
    backends::{Backend, open_realtime},
    output::{check_image_path, write_image},
    scene_io::{check_finite, load_scene, parse_size},
};

/// How the `reference` backend integrates.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum IntegratorArg {
    /// Deterministic quadrature refined until the image stops changing (single scattering of
    /// the real-time model, with its octaves and ambient).
    Quadrature,
    /// Volumetric path tracing (delta/ratio tracking, next-event estimation to the sun).
    Montecarlo,
    /// The path tracer on the chosen backend (GPU or cpu), accumulating --spp paths per pixel,
    /// a workgroup of paths a frame; with `--backend reference`, the same as `montecarlo`.
    Pathtrace,
}

/// Which cloud renderer draws the frame (`--method`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum MethodArg {
    /// The volumetric model: the march (or the path tracer with --integrator pathtrace).
    Volumetric,
    /// Baseline: the basic tutorial ray marcher (Riemann sum, Beer-Powder toward the sun, HG
    /// phase, no ambient or multiple scattering) over the same density field.
    Basic,
    /// Baseline: Wang 2003's sprite clouds, placed from the same weather map and density.
    Sprites,
}

impl MethodArg {
    fn method(self) -> stratus_scene::Method {
        match self {
            Self::Volumetric => stratus_scene::Method::Volumetric,
            Self::Basic => stratus_scene::Method::Basic,
            Self::Sprites => stratus_scene::Method::Sprites,
        }
    }
}

/// Which sky is drawn behind the clouds (`--sky`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum SkyArg {
    /// The simple analytic gradient.
    Analytic,
    /// Hillaire 2020's atmosphere: Rayleigh, Mie and ozone, the clouds lit by the sun through
    /// the air and by the sky, aerial perspective, the ground lit by sun and sky under the
    /// clouds' shadows (every backend, the CPU included).
    Physical,
}

/// Options of `stratus render`.
#[derive(Args, Debug)]
pub struct RenderArgs {
    /// A built-in preset (see `stratus presets`).
    #[arg(long, conflicts_with = "scene")]
    preset: Option<String>,
    /// A scene file (TOML; may be partial and name a `base` preset).
    #[arg(long)]
    scene: Option<PathBuf>,
    /// The renderer.
    #[arg(long, value_enum, default_value_t = Backend::Auto)]
    backend: Backend,
    /// A METAR report (quoted) applied to the scene: its cloud groups become cloud layers,
    /// its weather picks the state (see `stratus weather`).
    #[arg(long, value_name = "METAR")]
    weather: Option<String>,
    /// The sun of a date and place: a UTC date-time (ISO 8601, e.g. 2026-06-21T18:30:00Z),
    /// with --lat and --lon; sets the scene's [sky] (see `stratus astro`).
    #[arg(long, value_name = "UTC", requires_all = ["lat", "lon"])]
    date: Option<String>,
    /// With --date: latitude in degrees, north positive.
    #[arg(long, allow_hyphen_values = true, requires = "date")]
    lat: Option<f64>,
    /// With --date: longitude in degrees, east positive.
    #[arg(long, allow_hyphen_values = true, requires = "date")]
    lon: Option<f64>,
    /// Image size as WIDTHxHEIGHT (overrides the scene's camera.resolution).
    #[arg(long, value_parser = parse_size)]
    size: Option<(u32, u32)>,
    /// Output image: .png (tone-mapped) or .exr (linear radiance, alpha = transmittance). With
    /// --frames, the last frame.
    #[arg(long, default_value = "clouds.png")]
    out: PathBuf,
    /// Also write the work counters, per-pass times, the lightning flashes the frames lit
    /// (`lightning_flashes`) and (one entry per frame) each frame's pass times, CPU time and
    /// flash light (`lightning`, 0 without one) as JSON to this file.
    #[arg(long)]
    stats: Option<PathBuf>,
    /// Render N frames with one persistent renderer, as a real-time loop does, at 60 frames a
    /// second of scene time: the wind advances 1/60 s and the jitter sequence one step per
    /// frame; the camera follows the scene's [animation] (or stays). Only the last frame is
    /// read back, unless --sequence asks for every one.
    #[arg(long, default_value_t = 1, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    frames: u32,
    /// Temporal upsampling: march every pixel every frame (`off`), or one pixel in 4 (`1/4`)
    /// or in 16 (`1/16`) and reproject the rest from the last frame (overrides the scene's
    /// quality.temporal). Pays off over --frames.
    #[arg(long, value_name = "MODE", value_parser = parse_temporal)]
    temporal: Option<Temporal>,
    /// With --frames: also write every frame's display image to DIR/frame_NNNN.png.
    #[arg(long, value_name = "DIR")]
    sequence: Option<PathBuf>,
    /// The integrator: the real-time march (`quadrature`, the default; converged with
    /// `--backend reference`), or the all-orders path tracer (`pathtrace` on any backend,
    /// `montecarlo` on the reference).
    #[arg(long, value_enum, default_value_t = IntegratorArg::Quadrature)]
    integrator: IntegratorArg,
    /// The cloud renderer (overrides the scene's quality.method): the volumetric model, or a
    /// baseline it is measured against (`basic`, `sprites`; GPU backends only).
    #[arg(long, value_enum, value_name = "METHOD")]
    method: Option<MethodArg>,
    /// The sky (overrides the scene's atmosphere.sky): `analytic` or `physical`.
    #[arg(long, value_enum, value_name = "SKY")]
    sky: Option<SkyArg>,
    /// `--integrator montecarlo|pathtrace`: samples (paths) per pixel.
    #[arg(long, default_value_t = 64, value_parser = clap::value_parser!(u32).range(1..))]
    spp: u32,
    /// `--integrator montecarlo|pathtrace`: scattering orders (1 = single scattering, 0 =
    /// all).
    #[arg(long, default_value_t = 0)]
    orders: u32,
    /// Auto quality: render with the cheapest configuration `stratus bench` measured whose
    /// FLIP against the reference is at most E (for this scene; other scenes: on every
    /// measured scene).
    #[arg(long, value_name = "E")]
    max_error: Option<f64>,
    /// The bench results `--max-error` reads.
    #[arg(long, value_name = "FILE", default_value = DEFAULT_RESULTS)]
    bench_results: PathBuf,
}

/// The renderer `backend` names; `auto` falls back from Vulkan to GL to the CPU, saying so.
fn open_backend(backend: Backend, args: &RenderArgs) -> Result<Box<dyn stratus_graph::Backend>> {
    // A CPU frame's own progress bar (rows) for a single frame; a loop shows one bar of
    // frames instead.
    let progress = args.frames == 1;
    Ok(match backend {
        Backend::Reference => Box::new(match args.integrator {
            IntegratorArg::Quadrature => CpuBackend {
                integrator: stratus_reference::Integrator::Quadrature(
                    stratus_reference::QuadratureSettings::converged(),
                ),
                label: "reference (converged quadrature)",
                progress,
                ..CpuBackend::default()
            },
            IntegratorArg::Montecarlo | IntegratorArg::Pathtrace => CpuBackend {
                integrator: stratus_reference::Integrator::MonteCarlo {
                    spp: args.spp,
                    orders: args.orders,
                },
                label: "reference (Monte Carlo)",
                progress,
                ..CpuBackend::default()
            },
        }),
        other => open_realtime(other, progress)?,
    })
}

/// Fault injection for the tests of a device lost mid-sequence (`crates/cli/tests/device_loss.rs`):
/// set to a frame number, `stratus render` loses its renderer's device just before that frame
/// ([`stratus_graph::Backend::lose_device`]).
pub const LOSE_DEVICE_AT_FRAME: &str = "STRATUS_LOSE_DEVICE_AT_FRAME";

/// The frame [`LOSE_DEVICE_AT_FRAME`] names, if set.
fn lose_device_at() -> Result<Option<u32>> {
    match std::env::var(LOSE_DEVICE_AT_FRAME) {
        Ok(v) => v.parse().map(Some).map_err(|e| {
            anyhow::anyhow!("{LOSE_DEVICE_AT_FRAME}={v:?}: expected a frame number ({e})")
        }),
        Err(_) => Ok(None),
    }
}

/// `--temporal`'s values.
pub fn parse_temporal(s: &str) -> Result<Temporal, String> {
    s.parse()
}

/// Frame `i` of a loop starting at `scene` at `fps` frames per second of scene time: the
/// camera on its animation path and the wind `i / fps` seconds on, the jitter sequence `i`
/// steps on.
pub fn frame_scene(scene: &Scene, i: u32, fps: f64) -> Scene {
    let mut s = scene.at_time(f64::from(i) / fps);
    s.quality.frame = s.quality.frame.wrapping_add(i);
    s
}

/// Each pass's median time over the frames it ran in.
fn median_per_pass(frames: &[(f64, Vec<stratus_graph::PassTiming>)]) -> BTreeMap<String, f64> {
    let mut per_pass: BTreeMap<String, Vec<f64>> = BTreeMap::new();
    for (_, timings) in frames {
        for t in timings {
            per_pass.entry(t.pass.clone()).or_default().push(t.ms);
        }
    }
    per_pass.into_iter().map(|(p, v)| (p, median(v))).collect()
}

/// A progress bar for long loops, on a terminal only.
fn progress(frames: u32) -> Option<ProgressBar> {
    if frames < 2 || !std::io::stderr().is_terminal() {
        return None;
    }
    let bar = ProgressBar::new(u64::from(frames));
    if let Ok(style) =
        ProgressStyle::with_template("{msg} [{elapsed_precise}] {wide_bar} {pos}/{len} frames")
    {
        bar.set_style(style);
    }
    bar.set_message("rendering");
    Some(bar)
}

/// Runs `stratus render`.
pub fn run(args: RenderArgs) -> Result<()> {
    check_image_path(&args.out)?;
    let (mut scene, mut name) = load_scene(args.preset.as_deref(), args.scene.as_ref(), args.size)?;
    if let Some(report) = &args.weather {
        let d = crate::weather::derive_metar(report, &scene)?;
        eprintln!(
            "weather: {} ({} cloud layers)",
            d.state.name,
            1 + d.scene.clouds.layers.len()
        );
        scene = d.scene;
        name = format!("{name} with {report:?}");
    }
    if let Some(t) = args.temporal {
        scene.quality.temporal = t;
    }
    if let Some(date) = &args.date {
        scene.sky = stratus_scene::Sky {
            date_utc: Some(date.parse().map_err(|e| anyhow::anyhow!("--date: {e}"))?),
            latitude_deg: args.lat,
            longitude_deg: args.lon,
        };
        // The date and place set the sun: a direction of the scene's own would contradict it.
        scene.sun.direction = None;
        scene.validate().map_err(|e| anyhow::anyhow!("{e}"))?;
        let d = scene.sun_direction();
        eprintln!(
            "sun: elevation {:.2} deg, azimuth {:.2} deg (from the date and place)",
            scene.sun_elevation_deg(),
            d[0].atan2(d[2]).to_degrees().rem_euclid(360.0)
        );
    }
    if let Some(m) = args.method {
        scene.quality.method = m.method();
    }
    if let Some(sky) = args.sky {
        scene.atmosphere.sky = match sky {
            SkyArg::Analytic => stratus_scene::SkyModel::Analytic,
            SkyArg::Physical => stratus_scene::SkyModel::Physical,
        };
    }
    let method = scene.quality.method;
    if method != stratus_scene::Method::Volumetric {
        if args.integrator != IntegratorArg::Quadrature {
            anyhow::bail!(
                "--method {}: a baseline has no path tracer (the path tracer renders the volumetric model); drop --integrator",
                method.name()
            );
        }
        if matches!(args.backend, Backend::Cpu | Backend::Reference) {
            anyhow::bail!(
                "--method {} runs on the GPU backends (wgpu, wgpu-gl, ash, auto); the CPU renders the volumetric model only",
                method.name()
            );
        }
        if scene.quality.temporal != Temporal::Off {
            anyhow::bail!(
                "--method {}: temporal upsampling ({}) reprojects the volumetric march; use --temporal off",
                method.name(),
                scene.quality.temporal.name()
            );
        }
    }
    let path_traced = args.integrator != IntegratorArg::Quadrature;
    if path_traced && scene.quality.temporal != Temporal::Off {
        anyhow::bail!(
            "temporal upsampling ({}) amortises the real-time march; the path tracer accumulates every pixel itself: use --temporal off",
            scene.quality.temporal.name()
        );
    }
    if args.integrator == IntegratorArg::Montecarlo && args.backend != Backend::Reference {
        anyhow::bail!(
            "--integrator montecarlo is the CPU reference's path tracer: add --backend reference, or use --integrator pathtrace to path trace on this backend"
        );
    }
    // The path tracer on a real-time backend: a few paths per pixel a frame, frames enough for
    // --spp.
    let progressive =
        args.integrator == IntegratorArg::Pathtrace && args.backend != Backend::Reference;
    if progressive {
        if args.frames != 1 {
            anyhow::bail!(
                "--frames {}: the path tracer renders as many frames as --spp {} needs",
                args.frames,
                args.spp,
            );
        }
        scene.quality.integrator = stratus_scene::Integrator::Pathtrace;
        scene.quality.path_orders = args.orders;
    }
    if let Some(dir) = &args.sequence {
        std::fs::create_dir_all(dir)
            .with_context(|| format!("--sequence {}: creating the folder", dir.display()))?;
    }
    let scene = match args.max_error {
        Some(e) => {
            let results = Results::load(&args.bench_results)?;
            let (picked, why) = auto_quality(&scene, &name, e, &results)?;
            println!("{why}");
            picked
        }
        None => scene,
    };
    let t0 = Instant::now();
    let noise = Arc::new(stratus::noise_for(&scene));
    let noise_ms = t0.elapsed().as_secs_f64() * 1e3;
    let mut renderer = open_backend(args.backend, &args)?;
    let plan = FramePlan::for_scene(&scene, false)?;
    // The path tracer adds a fixed number of paths per pixel a frame (the WGSL's): --spp
    // rounds up to whole frames, and the report says how many paths were traced.
    let per_frame = if progressive {
        plan.paths_per_frame()
            .context("the path-traced plan has no pathtrace pass")?
    } else {
        1
    };
    let frame_count = if progressive {
        args.spp.max(1).div_ceil(per_frame)
    } else {
        args.frames
    };
    let spp = frame_count * per_frame;
    let render = |r: &mut Box<dyn stratus_graph::Backend>, input: &FrameInput<'_>| {
        r.render(input).map_err(|e| anyhow::anyhow!("{e}"))
    };

    let lose_at = lose_device_at()?;
    let bar = progress(frame_count);
    let t = Instant::now();
    let mut frames: Vec<(f64, Vec<stratus_graph::PassTiming>)> = Vec::new();
    // Each frame's lightning flash (its number and light), if one is lit.
    let mut flashes: Vec<Option<stratus_scene::lightning::Flash>> = Vec::new();
    let mut last: Option<(Scene, FrameOutput)> = None;
    for i in 0..frame_count {
        let s = if progressive {
            // A still scene; each frame draws new paths (their streams follow quality.frame).
            let mut s = scene.clone();
            s.quality.frame = s.quality.frame.wrapping_add(i);
            s
        } else {
            frame_scene(&scene, i, 60.0)
        };
        let is_last = i + 1 == frame_count;
        let readback = if is_last && progressive {
            // The path tracer's per-pixel moments, for the noise estimate.
            Readback {
                output: true,
                resources: vec!["history-meta".into()],
            }
        } else if is_last || args.sequence.is_some() {
            Readback::output()
        } else {
            Readback::none()
        };
        if lose_at == Some(i) && !renderer.lose_device() {
            bail!(
                "{LOSE_DEVICE_AT_FRAME}={i}: {} has no device to lose",
                renderer.describe()
            );
        }
        let out = render(
            &mut renderer,
            &FrameInput::new(&plan, &s, &noise).with_readback(readback),
        )
        .with_context(|| {
            let kept = match &args.sequence {
                Some(dir) if i > 0 => {
                    format!("; frames 0 to {} are complete in {}", i - 1, dir.display())
                }
                _ => String::new(),
            };
            format!(
                "rendering frame {i} of frames 0 to {}{kept}",
                frame_count - 1
            )
        })?;
        frames.push((out.cpu_ms, out.timings.clone()));
        // A flash of brightness 0 shows nothing: not counted.
        flashes.push(stratus_scene::lightning::flash(&s).filter(|_| s.lightning.brightness > 0.0));
        if let Some(dir) = &args.sequence {
            check_finite(&out).with_context(|| format!("frame {i}"))?;
            write_image(&dir.join(format!("frame_{i:04}.png")), &out)?;
        }
        if let Some(bar) = &bar {
            bar.inc(1);
        }
        if is_last {
            last = Some((s, out));
        }
    }
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    let wall_ms = t.elapsed().as_secs_f64() * 1e3;
    let (last_scene, frame) = last.expect("at least one frame");
    check_finite(&frame)?;
    write_image(&args.out, &frame)?;

    println!(
        "wrote {} ({}x{}, scene {name}{})",
        args.out.display(),
        frame.width,
        frame.height,
        if progressive {
            format!(
                ", {spp} paths per pixel in {frame_count} frames of {per_frame}{}",
                if spp == args.spp {
                    String::new()
                } else {
                    format!(" (--spp {} rounded up to whole frames)", args.spp)
                }
            )
        } else if args.frames > 1 {
            format!(", the last of {} frames", args.frames)
        } else {
            String::new()
        }
    );
    println!(
        "backend: {} | variant {}",
        renderer.describe(),
        plan.variant
    );
    // The distinct flashes the frames lit.
    let lightning_flashes = {
        let mut seen: Vec<i64> = flashes.iter().flatten().map(|f| f.index).collect();
        seen.dedup();
        seen.len()
    };
    if scene.lightning.flashes_per_minute > 0.0 {
        let last_flash = match flashes.last().copied().flatten() {
            Some(f) => {
                let cam = last_scene.camera.position;
                let [x, alt, z] = f.position;
                format!(
                    "; the last frame's at x {x:.0} m, altitude {alt:.0} m, z {z:.0} m ({:.1} km from the camera, light {:.2})",
                    ((x - cam[0]).hypot(z - cam[2])).hypot(alt - cam[1]) * 1e-3,
                    f.intensity
                )
            }
            None => "; none in the last frame".into(),
        };
        println!(
            "lightning: {lightning_flashes} flash(es) lit {} of {frame_count} frames ({} a minute){last_flash}",
            flashes.iter().flatten().count(),
            scene.lightning.flashes_per_minute
        );
    }
    let source = frame.timings.first().map_or("untimed", |t| t.source);
    if progressive {
        let pass_ms: f64 = frames
            .iter()
            .flat_map(|f| &f.1)
            .filter(|t| t.pass == "pathtrace")
            .map(|t| t.ms)
            .sum();
        let paths = f64::from(frame.width) * f64::from(frame.height) * f64::from(spp);
        println!(
            "path tracer: {:.3} Mpaths/s ({paths:.0} paths in {pass_ms:.0} ms of pathtrace passes, {source}); {wall_ms:.0} ms wall",
            paths / pass_ms.max(1e-9) / 1e3,
        );
        print_convergence(&frame);
    } else if args.frames == 1 {
        let gpu_ms: f64 = frame.timings.iter().map(|t| t.ms).sum();
        let passes: Vec<String> = frame
            .timings
            .iter()
            .map(|t| format!("{} {:.2} ms", t.pass, t.ms))
            .collect();
        println!(
            "frame: {wall_ms:.1} ms wall, passes {gpu_ms:.2} ms ({}, {source}); noise generated in {noise_ms:.0} ms",
            passes.join(", "),
        );
    } else {
        let passes: Vec<String> = median_per_pass(&frames)
            .iter()
            .map(|(p, v)| format!("{p} {v:.3} ms"))
            .collect();
        println!(
            "{} frames in {wall_ms:.0} ms: median CPU {:.3} ms/frame (record + submit); median GPU per pass: {} ({source}); noise generated in {noise_ms:.0} ms",
            args.frames,
            median(frames.iter().map(|f| f.0).collect()),
            passes.join(", "),
        );
    }

    if let Some(path) = &args.stats {
        // Counters come from the statistics variant; times from the normal one above, which
        // pays nothing for counting.
        let stats_plan = FramePlan::for_scene(&scene, true)?;
        let counted = match frame.stats {
            // The CPU renderers always count; no second render needed.
            Some(_) => frame.clone(),
            None => render(
                &mut renderer,
                &FrameInput::new(&stats_plan, &last_scene, &noise),
            )?,
        };
        let timing =
            |t: &stratus_graph::PassTiming| json!({"pass": t.pass, "ms": t.ms, "source": t.source});
        let doc = json!({
            "scene": name,
            "backend": renderer.describe(),
            "variant": plan.variant,
            "stats_variant": stats_plan.variant,
            "width": frame.width,
            "height": frame.height,
            "counters": counted.stats,
            "passes": frame.timings.iter().map(timing).collect::<Vec<_>>(),
            "frame_ms": wall_ms / f64::from(frame_count),
            "integrator": scene.quality.integrator.name(),
            "method": scene.quality.method.name(),
            "temporal": scene.quality.temporal.name(),
            "median_ms": median_per_pass(&frames),
            "lightning_flashes": lightning_flashes,
            "frames": frames.iter().zip(&flashes).enumerate().map(|(i, ((cpu_ms, timings), flash))| json!({
                "frame": i,
                "cpu_ms": cpu_ms,
                "lightning": flash.map_or(0.0, |f| f.intensity),
                "passes": timings.iter().map(timing).collect::<Vec<_>>(),
            })).collect::<Vec<_>>(),
        });
        let text = serde_json::to_string_pretty(&doc)? + "\n";
        stratus_compare::write_file_atomically(path, text.as_bytes())
            .with_context(|| format!("writing {}", path.display()))?;
        println!("wrote {}", path.display());
    }
    Ok(())
}

/// The path tracer's noise per 8x8 block (where the backend keeps its per-pixel moments: the
/// GPU backends; the CPU's progressive renderer keeps means only).
fn print_convergence(frame: &FrameOutput) {
    let Some(meta) = frame.resources.get("history-meta") else {
        return;
    };
    match crate::convergence::block_noise(frame, meta) {
        Some(c) => println!(
            "noise: relative standard error of the {b}x{b} blocks' mean luminance: worst {:.2}%, median {:.2}% ({} blocks; {} without cloud not judged): {}",
            c.worst * 100.0,
            c.median * 100.0,
            c.blocks,
            c.empty,
            if c.converged() {
                "converged (every block below 1%)".to_string()
            } else {
                format!(
                    "not converged (below 1% in every block needs about {:.0} paths a pixel)",
                    c.paths_for_converged().ceil()
                )
            },
            b = crate::convergence::BLOCK,
        ),
        None => println!("noise: no block holds cloud radiance"),
    }
}
