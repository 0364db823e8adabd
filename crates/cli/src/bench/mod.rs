//! `stratus bench`: speed against accuracy.
//!
//! For every scene of a fixed set and every configuration of a sweep (view steps, light steps,
//! step integral, phase model, Beer-Powder, octaves, jitter, shape texture) it renders the frame
//! on the GPU and measures
//!
//! * **error** against the CPU reference: the converged quadrature of the configuration's own
//!   model when it is single scattering (0 octaves), else the Monte Carlo path tracer with all
//!   scattering orders (the truth the octaves approximate); RMSE on linear radiance (rgb) and
//!   FLIP (mean) on the tone-mapped, composited images;
//! * **cost**: the GPU time of every pass (timestamp queries, median of repeats) and the work
//!   counters of the statistics variant per pixel (view steps, density evaluations, light
//!   samples; "samples per pixel" = density evaluations per pixel, view and light samples both).
//!
//! References are rendered once and cached by a hash of the scene (normalised: fields the
//! reference ignores are reset) and the reference settings, under `$XDG_CACHE_HOME/stratus`
//! or else `target/stratus-cache/` (relative to the working directory).
//!
//! Outputs in `--out`: `results.csv` (one row per scene and configuration, `pareto` = on the
//! scene's front of GPU time against FLIP), `results.json` (the same plus the run's settings;
//! `stratus render --max-error` reads it) and `chart.png` / `chart.svg` (FLIP against GPU time
//! per scene, front joined and named; the PNG has no text, the SVG names everything).

use std::{
    collections::BTreeMap,
    io::Write as _,
    path::{Path, PathBuf},
    sync::Arc,
};

use anyhow::{Context, Result};
use clap::{Args, ValueEnum};
use indicatif::{ProgressBar, ProgressStyle};
use stratus::quality::{Config, Results, Row, mark_pareto, phase_name};
use stratus_compare::{CompareOptions, Image, compare};
use stratus_graph::{Backend, FrameInput, FramePlan, output::median};
use stratus_noise::NoiseSet;
use stratus_scene::{Scene, ShapeTexture};

use crate::scene_io::{check_finite, parse_size};

mod chart;
mod reference_cache;
mod sweep;

use self::{
    chart::chart,
    reference_cache::{cache_dir, reference},
    sweep::sweep,
};

/// The GPU backend the bench times.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum BenchBackend {
    /// wgpu on Vulkan.
    Wgpu,
    /// Raw Vulkan (ash) with the committed SPIR-V.
    Ash,
}

/// Options of `stratus bench`.
#[derive(Args, Debug)]
pub struct BenchArgs {
    /// The GPU backend to time.
    #[arg(long, value_enum, default_value_t = BenchBackend::Wgpu)]
    backend: BenchBackend,
    /// Comma-separated presets or `stress-thick` (default: cumulus-noon, sunset,
    /// above-clouds, storm without --quick, and the stability case stress-thick).
    #[arg(long, value_delimiter = ',')]
    scenes: Option<Vec<String>>,
    /// A few minutes on lavapipe: 64x36 images, 9 repeats, ~23 configurations a scene,
    /// 24-spp Monte Carlo references.
    #[arg(long)]
    quick: bool,
    /// Output directory.
    #[arg(long, default_value = "target/stratus-bench")]
    out: PathBuf,
    /// Image size (default 64x36 with --quick, else 128x72).
    #[arg(long, value_parser = parse_size)]
    size: Option<(u32, u32)>,
    /// Timed repeats per configuration (median reported; default 9 with --quick, else 15).
    #[arg(long)]
    repeats: Option<u32>,
    /// Samples per pixel of the Monte Carlo references (default 24 with --quick, else 128).
    #[arg(long)]
    mc_spp: Option<u32>,
}

/// A stability case charted next to the presets: `cumulus-noon` with ten times the
/// scattering coefficient and single scattering, so that a view step's optical depth is far
/// above 1 at the low step counts of the sweep. The Riemann sum overshoots there while the
/// analytic step integral stays bounded; the chart shows both.
pub const STRESS_THICK: &str = "stress-thick";

/// A preset, or the stability case [`STRESS_THICK`].
fn bench_scene(name: &str) -> Result<Scene> {
    if name == STRESS_THICK {
        let mut s = Scene::preset("cumulus-noon").map_err(|e| anyhow::anyhow!("{e}"))?;
        s.lighting.scattering *= 10.0;
        s.lighting.multiple_scattering.octaves = 0;
        return Ok(s);
    }
    Scene::preset(name).map_err(|e| anyhow::anyhow!("{e}"))
}

/// Runs `stratus bench`.
pub fn run(args: BenchArgs) -> Result<()> {
    let scenes = args.scenes.clone().unwrap_or_else(|| {
        let mut v = vec!["cumulus-noon", "sunset", "above-clouds"];
        if !args.quick {
            v.push("storm");
        }
        v.push(STRESS_THICK);
        v.into_iter().map(String::from).collect()
    });
    let (w, h) = args
        .size
        .unwrap_or(if args.quick { (64, 36) } else { (128, 72) });
    let repeats = args
        .repeats
        .unwrap_or(if args.quick { 9 } else { 15 })
        .max(1);
    let mc_spp = args
        .mc_spp
        .unwrap_or(if args.quick { 24 } else { 128 })
        .max(1);
    let validation = std::env::var_os("STRATUS_VALIDATION").is_some();
    let mut renderer: Box<dyn Backend> = match args.backend {
        BenchBackend::Wgpu => Box::new(stratus_backend_wgpu::Renderer::new(
            stratus_backend_wgpu::Options {
                api: stratus_backend_wgpu::Api::Vulkan,
                validation,
            },
        )?),
        BenchBackend::Ash => Box::new(stratus_backend_ash::Renderer::new(
            stratus_backend_ash::Options { validation },
        )?),
    };
    let device = renderer.describe();
    eprintln!(
        "bench on {device}: {w}x{h}, {repeats} repeats, references cached in {}",
        cache_dir().display()
    );

    let mut plan_scenes = Vec::new();
    for name in &scenes {
        let scene = bench_scene(name)?.with_size(w, h);
        let base = Config::of(&scene);
        let mut configs = sweep(&base, args.quick);
        if name == STRESS_THICK {
            // Single scattering only: its reference is the converged quadrature. An all-orders
            // path tracer in a medium this dense would take far too long for a sweep.
            configs.retain(|c| c.octaves == 0);
        }
        plan_scenes.push((name.clone(), scene, configs, base));
    }
    let total: usize = plan_scenes.iter().map(|p| p.2.len()).sum();
    let bar = ProgressBar::new(total as u64);
    if let Ok(style) = ProgressStyle::with_template(
        "{msg:40} [{elapsed_precise}] {wide_bar} {pos}/{len} configurations",
    ) {
        bar.set_style(style);
    }

    let mut noises: BTreeMap<(u64, bool), Arc<NoiseSet>> = BTreeMap::new();
    let mut rows = Vec::new();
    for (name, scene, configs, base) in &plan_scenes {
        let mut scene_rows: Vec<Row> = Vec::new();
        for config in configs {
            bar.set_message(format!("{name}: {}", config.name()));
            let s = config.apply(scene);
            s.validate().map_err(|e| anyhow::anyhow!("{e}"))?;
            let hzd = s.noise.shape_texture == ShapeTexture::Hzd;
            let noise = noises
                .entry((s.noise.seed, hzd))
                .or_insert_with(|| Arc::new(stratus::noise_for(&s)));
            let (reference, label) = reference(&s, noise, mc_spp)?;
            let plan = FramePlan::for_scene(&s, false)?;
            let mut frame = None;
            let mut totals = Vec::new();
            let mut passes: BTreeMap<String, Vec<f64>> = BTreeMap::new();
            // One warm-up render (resources, pipeline compilation), then the timed repeats.
            let input = FrameInput::new(&plan, &s, noise);
            renderer
                .render(&input)
                .map_err(|e| anyhow::anyhow!("{e}"))?;
            for _ in 0..repeats {
                let f = renderer
                    .render(&input)
                    .map_err(|e| anyhow::anyhow!("{e}"))?;
                check_finite(&f)?;
                totals.push(f.timings.iter().map(|t| t.ms).sum());
                for t in &f.timings {
                    passes.entry(t.pass.clone()).or_default().push(t.ms);
                }
                frame = Some(f);
            }
            let frame = frame.expect("at least one repeat");
            let stats_plan = FramePlan::for_scene(&s, true)?;
            let counted = renderer
                .render(&FrameInput::new(&stats_plan, &s, noise))
                .map_err(|e| anyhow::anyhow!("{e}"))?;
            let c = counted.stats.unwrap_or_default();
            let pixels = c.get("pixels").copied().unwrap_or(1).max(1) as f64;
            let per = |k: &str| c.get(k).copied().unwrap_or(0) as f64 / pixels;

            let options = CompareOptions {
                exposure: 1.0,
                ..CompareOptions::default()
            };
            let linear = compare(
                &Image::from_frame_radiance(&reference),
                &Image::from_frame_radiance(&frame),
                &options,
            )?;
            let display = compare(
                &Image::from_frame_display(&reference),
                &Image::from_frame_display(&frame),
                &options,
            )?;
            scene_rows.push(Row {
                scene: name.clone(),
                name: config.name(),
                preset: config == base,
                config: config.clone(),
                gpu_ms: median(totals),
                passes: passes.into_iter().map(|(k, v)| (k, median(v))).collect(),
                time_vs_preset: 0.0,
                view_steps_pp: per("view_steps"),
                light_samples_pp: per("light_samples"),
                samples_pp: per("density_evaluations"),
                rmse: linear.rmse,
                flip: display.flip.mean,
                flip_p95: display.flip.p95,
                reference: label,
                pareto: false,
            });
            bar.inc(1);
        }
        let preset_ms = scene_rows
            .iter()
            .find(|r| r.preset)
            .map_or(1.0, |r| r.gpu_ms.max(1e-9));
        for r in &mut scene_rows {
            r.time_vs_preset = r.gpu_ms / preset_ms;
        }
        rows.extend(scene_rows);
    }
    bar.finish_and_clear();
    mark_pareto(&mut rows);

    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("creating {}", args.out.display()))?;
    let results = Results {
        device,
        backend: format!("{:?}", args.backend).to_lowercase(),
        size: [w, h],
        repeats,
        mc_spp,
        rows,
    };
    write_csv(&args.out.join("results.csv"), &results.rows)?;
    let json = args.out.join("results.json");
    std::fs::write(&json, serde_json::to_string_pretty(&results)? + "\n")
        .with_context(|| format!("writing {}", json.display()))?;
    chart(&args.out, &results)?;
    summary(&results);
    println!(
        "wrote {0}/results.csv, {0}/results.json, {0}/chart.png, {0}/chart.svg",
        args.out.display()
    );
    Ok(())
}

fn write_csv(path: &Path, rows: &[Row]) -> Result<()> {
    let mut f = std::io::BufWriter::new(
        std::fs::File::create(path).with_context(|| format!("writing {}", path.display()))?,
    );
    writeln!(
        f,
        "scene,config,preset,view_steps,light_steps,integration,phase,beer_powder,octaves,jitter,shape_texture,gpu_ms,march_ms,composite_ms,time_vs_preset,view_steps_pp,light_samples_pp,samples_pp,rmse,flip,flip_p95,reference,pareto"
    )?;
    for r in rows {
        let c = &r.config;
        writeln!(
            f,
            "{},{},{},{},{},{:?},{},{},{},{},{:?},{:.4},{:.4},{:.4},{:.3},{:.2},{:.2},{:.2},{:.6},{:.5},{:.5},{},{}",
            r.scene,
            r.name,
            r.preset,
            c.view_steps,
            c.light_steps,
            c.integration,
            phase_name(c.phase),
            c.beer_powder,
            c.octaves,
            c.jitter,
            c.shape_texture,
            r.gpu_ms,
            r.passes.get("march").copied().unwrap_or(0.0),
            r.passes.get("composite").copied().unwrap_or(0.0),
            r.time_vs_preset,
            r.view_steps_pp,
            r.light_samples_pp,
            r.samples_pp,
            r.rmse,
            r.flip,
            r.flip_p95,
            r.reference,
            r.pareto
        )?;
    }
    Ok(())
}

/// Prints, per scene, the front and the cheapest configuration within FLIP 0.05.
fn summary(results: &Results) {
    let mut scenes: Vec<&str> = results.rows.iter().map(|r| r.scene.as_str()).collect();
    scenes.dedup();
    for scene in scenes {
        let rows: Vec<&Row> = results.rows.iter().filter(|r| r.scene == scene).collect();
        println!("{scene}:");
        let mut front: Vec<&&Row> = rows.iter().filter(|r| r.pareto).collect();
        front.sort_by(|a, b| a.gpu_ms.total_cmp(&b.gpu_ms));
        for r in front {
            println!(
                "  front  {:42} {:7.3} ms ({:4.2}x preset) {:7.1} samples/px  FLIP {:.4}  RMSE {:.4} ({})",
                r.name, r.gpu_ms, r.time_vs_preset, r.samples_pp, r.flip, r.rmse, r.reference
            );
        }
        match rows
            .iter()
            .filter(|r| r.flip <= 0.05)
            .min_by(|a, b| a.gpu_ms.total_cmp(&b.gpu_ms))
        {
            Some(r) => println!(
                "  cheapest within FLIP 0.05: {} ({:.3} ms, {:.2}x preset, {:.1} samples/px, FLIP {:.4})",
                r.name, r.gpu_ms, r.time_vs_preset, r.samples_pp, r.flip
            ),
            None => println!("  no configuration within FLIP 0.05"),
        }
    }
}
