//! `stratus gpu-bench`: what a frame costs on this machine's GPU, preset by preset. Every
//! preset on each backend, with temporal upsampling off, 1/4 and 1/16, at each size: the median
//! GPU time of every pass and of the whole frame, the CPU time to record and submit a frame,
//! and the work per output pixel (density evaluations and light samples, from the statistics
//! variant), which does not depend on the device and so is the measure that means something
//! where there is no GPU. Writes `results.json` and `table.md` (the table `docs/gpu-bench.md`
//! holds). `tests/device/bench.sh` runs it on a machine with a GPU and no cargo
//! (`cargo xtask device-bench` packs it).

use std::{collections::BTreeMap, io::IsTerminal as _, path::PathBuf, sync::Arc};

use anyhow::{Context as _, Result, bail};
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use serde::Serialize;
use stratus_graph::{FrameInput, FramePlan, Readback, output::median};
use stratus_scene::{Scene, Temporal};
use stratus_tool::{
    backends::{Backend, Open, open},
    render::frame_scene,
    scene_io::parse_size,
};

/// Options of `stratus gpu-bench`.
#[derive(Args, Debug)]
pub struct GpuBenchArgs {
    /// Comma-separated presets (default: every preset; see `stratus presets`).
    #[arg(long, value_delimiter = ',')]
    presets: Vec<String>,
    /// Comma-separated backends: `wgpu` (Vulkan), `ash`, `wgpu-gl`.
    #[arg(long, value_delimiter = ',', default_value = "wgpu,ash")]
    backends: Vec<String>,
    /// Comma-separated temporal modes: `off`, `1/4`, `1/16`.
    #[arg(long, value_delimiter = ',', default_value = "off,1/4,1/16")]
    temporal: Vec<String>,
    /// Comma-separated image sizes, WIDTHxHEIGHT.
    #[arg(long, value_delimiter = ',', default_value = "1920x1080,3840x2160")]
    sizes: Vec<String>,
    /// Frames per configuration, at 60 frames a second of scene time (the wind moves, the
    /// jitter sequence steps, a dated sun drifts).
    #[arg(long, default_value_t = 120, value_parser = clap::value_parser!(u32).range(2..))]
    frames: u32,
    /// Leading frames left out of the medians (pipelines warming, the temporal history filling).
    #[arg(long, default_value_t = 30)]
    warmup: u32,
    /// Output folder: results.json and table.md.
    #[arg(long, default_value = "target/gpu-bench")]
    out: PathBuf,
}

/// One configuration's measurements.
#[derive(Debug, Serialize)]
pub struct Row {
    /// The preset.
    pub preset: String,
    /// The backend, as asked (`wgpu`, `ash`, `wgpu-gl`).
    pub backend: String,
    /// The temporal mode.
    pub temporal: String,
    /// Width and height.
    pub size: [u32; 2],
    /// Median over the measured frames of the sum of every pass's GPU time, ms.
    pub gpu_ms: f64,
    /// Each pass's median GPU time over the measured frames it ran in, ms (a pass that runs
    /// on some frames only, such as the sky tables on a threshold, has its median over those).
    pub passes: BTreeMap<String, f64>,
    /// Each pass's mean over every measured frame (0 on frames it did not run): what it adds
    /// to a frame on average.
    pub pass_mean_ms: BTreeMap<String, f64>,
    /// Median CPU time to record and submit a frame, ms.
    pub cpu_ms: f64,
    /// Where the times come from (`gpu-timestamp`, or a wall-clock fallback).
    pub source: String,
    /// Density evaluations per output pixel, one frame of the statistics variant.
    pub density_per_pixel: f64,
    /// Light samples per output pixel, one frame of the statistics variant.
    pub light_per_pixel: f64,
    /// Frames measured (after the warm-up).
    pub frames: u32,
}

/// The whole run.
#[derive(Debug, Serialize)]
pub struct Report {
    /// Each backend's device, in words.
    pub devices: BTreeMap<String, String>,
    /// The command's options, in words.
    pub command: String,
    /// Every configuration.
    pub rows: Vec<Row>,
}

fn backend(name: &str) -> Result<Backend> {
    Ok(match name {
        "wgpu" => Backend::Wgpu,
        "ash" => Backend::Ash,
        "wgpu-gl" => Backend::WgpuGl,
        other => bail!("--backends: {other:?} is not a GPU backend (wgpu, ash, wgpu-gl)"),
    })
}

/// Runs `stratus gpu-bench`.
pub fn run(args: GpuBenchArgs) -> Result<()> {
    if args.warmup >= args.frames {
        bail!(
            "--warmup {} leaves no frame of --frames {} to measure",
            args.warmup,
            args.frames
        );
    }
    let presets: Vec<String> = if args.presets.is_empty() {
        stratus_scene::presets()
            .iter()
            .map(|p| p.name.to_string())
            .collect()
    } else {
        args.presets.clone()
    };
    let mut scenes = Vec::new();
    for p in &presets {
        scenes.push((
            p.clone(),
            Scene::preset(p).map_err(|e| anyhow::anyhow!("--presets {p}: {e}"))?,
        ));
    }
    let backends: Vec<(String, Backend)> = args
        .backends
        .iter()
        .map(|b| Ok((b.clone(), backend(b)?)))
        .collect::<Result<_>>()?;
    let temporal: Vec<(String, Temporal)> = args
        .temporal
        .iter()
        .map(|t| {
            t.parse::<Temporal>()
                .map(|m| (t.clone(), m))
                .map_err(|e| anyhow::anyhow!("--temporal {t}: {e}"))
        })
        .collect::<Result<_>>()?;
    let sizes: Vec<(u32, u32)> = args
        .sizes
        .iter()
        .map(|s| parse_size(s).map_err(|e| anyhow::anyhow!("--sizes {s}: {e}")))
        .collect::<Result<_>>()?;
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("creating {}", args.out.display()))?;

    let total = (scenes.len() * backends.len() * temporal.len() * sizes.len()) as u64;
    let bar = std::io::stderr().is_terminal().then(|| {
        let bar = ProgressBar::new(total * u64::from(args.frames));
        if let Ok(style) = ProgressStyle::with_template(
            "{msg} [{elapsed_precise}] {wide_bar} {pos}/{len} frames (eta {eta})",
        ) {
            bar.set_style(style);
        }
        bar
    });

    let mut report = Report {
        devices: BTreeMap::new(),
        command: format!(
            "stratus gpu-bench --presets {} --backends {} --temporal {} --sizes {} --frames {} --warmup {}",
            presets.join(","),
            args.backends.join(","),
            args.temporal.join(","),
            args.sizes.join(","),
            args.frames,
            args.warmup
        ),
        rows: Vec::new(),
    };
    for (bname, b) in &backends {
        let mut renderer =
            open(*b, &Open::default()).with_context(|| format!("opening the {bname} backend"))?;
        report.devices.insert(bname.clone(), renderer.describe());
        for (preset, base) in &scenes {
            let noise = Arc::new(stratus::noise_for(base));
            for &(w, h) in &sizes {
                for (tname, t) in &temporal {
                    let mut scene = base.clone().with_size(w, h);
                    scene.quality.temporal = *t;
                    let what = format!("{preset} {bname} {tname} {w}x{h}");
                    if let Some(bar) = &bar {
                        bar.set_message(what.clone());
                    }
                    let plan = FramePlan::for_scene(&scene, false).with_context(|| what.clone())?;
                    let mut frames = Vec::new();
                    let mut last = scene.clone();
                    for i in 0..args.frames {
                        last = frame_scene(&scene, i, 60.0);
                        let input =
                            FrameInput::new(&plan, &last, &noise).with_readback(Readback::none());
                        let out = renderer
                            .render(&input)
                            .map_err(|e| anyhow::anyhow!("{what}, frame {i}: {e}"))?;
                        if i >= args.warmup {
                            frames.push((out.cpu_ms, out.timings));
                        }
                        if let Some(bar) = &bar {
                            bar.inc(1);
                        }
                    }
                    let stats_plan =
                        FramePlan::for_scene(&scene, true).with_context(|| what.clone())?;
                    let counted = renderer
                        .render(&FrameInput::new(&stats_plan, &last, &noise))
                        .map_err(|e| anyhow::anyhow!("{what}, statistics variant: {e}"))?;
                    let counters = counted.stats.with_context(|| {
                        format!("{what}: the statistics variant counted nothing")
                    })?;
                    let pixels = f64::from(w) * f64::from(h);
                    let per_pixel = |k: &str| -> Result<f64> {
                        Ok(*counters
                            .get(k)
                            .with_context(|| format!("{what}: no counter {k}"))?
                            as f64
                            / pixels)
                    };
                    let mut per_pass: BTreeMap<String, Vec<f64>> = BTreeMap::new();
                    let mut sums = Vec::new();
                    for (_, timings) in &frames {
                        sums.push(timings.iter().map(|t| t.ms).sum::<f64>());
                        for t in timings {
                            per_pass.entry(t.pass.clone()).or_default().push(t.ms);
                        }
                    }
                    let n = frames.len() as f64;
                    report.rows.push(Row {
                        preset: preset.clone(),
                        backend: bname.clone(),
                        temporal: tname.clone(),
                        size: [w, h],
                        gpu_ms: median(sums),
                        pass_mean_ms: per_pass
                            .iter()
                            .map(|(p, v)| (p.clone(), v.iter().sum::<f64>() / n))
                            .collect(),
                        passes: per_pass.into_iter().map(|(p, v)| (p, median(v))).collect(),
                        cpu_ms: median(frames.iter().map(|f| f.0).collect()),
                        source: frames
                            .iter()
                            .find_map(|f| f.1.first())
                            .map_or("untimed", |t| t.source)
                            .to_string(),
                        density_per_pixel: per_pixel("density_evaluations")?,
                        light_per_pixel: per_pixel("light_samples")?,
                        frames: frames.len() as u32,
                    });
                }
            }
        }
        renderer
            .finish()
            .map_err(|e| anyhow::anyhow!("tearing down {bname}: {e}"))?;
    }
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    let json = args.out.join("results.json");
    stratus_compare::write_file_atomically(
        &json,
        (serde_json::to_string_pretty(&report)? + "\n").as_bytes(),
    )
    .with_context(|| format!("writing {}", json.display()))?;
    let md = args.out.join("table.md");
    stratus_compare::write_file_atomically(&md, table(&report).as_bytes())
        .with_context(|| format!("writing {}", md.display()))?;
    println!("{}", table(&report));
    println!("wrote {} and {}", json.display(), md.display());
    Ok(())
}

/// The report as Markdown: the devices, the command, and one row per configuration.
pub fn table(report: &Report) -> String {
    let mut s = String::new();
    for (b, d) in &report.devices {
        s.push_str(&format!("- `{b}`: {d}\n"));
    }
    s.push_str(&format!("- command: `{}`\n\n", report.command));
    s.push_str("| preset | backend | temporal | size | GPU ms/frame (median, all passes) | per pass (median ms; mean per frame where it differs) | CPU ms/frame | density evaluations / pixel | light samples / pixel |\n");
    s.push_str("|---|---|---|---|---|---|---|---|---|\n");
    for r in &report.rows {
        let passes: Vec<String> = r
            .passes
            .iter()
            .map(|(p, m)| {
                let mean = r.pass_mean_ms.get(p).copied().unwrap_or(0.0);
                if (mean - m).abs() > 0.05 * m.abs().max(1e-6) {
                    format!("{p} {m:.3} (mean {mean:.3})")
                } else {
                    format!("{p} {m:.3}")
                }
            })
            .collect();
        s.push_str(&format!(
            "| {} | {} | {} | {}x{} | {:.3} | {} | {:.3} | {:.2} | {:.2} |\n",
            r.preset,
            r.backend,
            r.temporal,
            r.size[0],
            r.size[1],
            r.gpu_ms,
            passes.join(", "),
            r.cpu_ms,
            r.density_per_pixel,
            r.light_per_pixel
        ));
    }
    s
}
