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
    fmt::Write as _,
    io::Write as _,
    path::{Path, PathBuf},
};

use anyhow::{Context, Result, bail};
use clap::{Args, ValueEnum};
use indicatif::{ProgressBar, ProgressStyle};
use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};
use stratus_compare::{CompareOptions, Image, compare};
use stratus_noise::NoiseSet;
use stratus_reference::{Integrator, QuadratureSettings};
use stratus_scene::{Integration, PhaseModel, Scene, ShapeTexture};
use stratus_shaders::{FrameOutput, FramePlan};

use crate::render::{FrameRenderer, noise_for};

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
    #[arg(long, value_parser = crate::render::parse_size)]
    size: Option<(u32, u32)>,
    /// Timed repeats per configuration (median reported; default 9 with --quick, else 15).
    #[arg(long)]
    repeats: Option<u32>,
    /// Samples per pixel of the Monte Carlo references (default 24 with --quick, else 128).
    #[arg(long)]
    mc_spp: Option<u32>,
}

/// One point of the sweep: the quality and method settings a configuration overrides.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Config {
    /// View steps per ray.
    pub view_steps: u32,
    /// Light-march steps.
    pub light_steps: u32,
    /// Step integral.
    pub integration: Integration,
    /// Phase function.
    pub phase: PhaseModel,
    /// Beer-Powder term.
    pub beer_powder: bool,
    /// Multiple-scattering octaves beyond single scattering.
    pub octaves: u32,
    /// Per-pixel jitter.
    pub jitter: bool,
    /// Shape texture size.
    pub shape_texture: ShapeTexture,
}

impl Config {
    /// The scene's own settings.
    pub fn of(scene: &Scene) -> Self {
        Self {
            view_steps: scene.quality.view_steps,
            light_steps: scene.quality.light_steps,
            integration: scene.quality.integration,
            phase: scene.lighting.phase.model,
            beer_powder: scene.lighting.beer_powder,
            octaves: scene.lighting.multiple_scattering.octaves,
            jitter: scene.quality.jitter,
            shape_texture: scene.noise.shape_texture,
        }
    }

    /// `scene` with these settings (a fixed step length is dropped: the view steps rule).
    pub fn apply(&self, scene: &Scene) -> Scene {
        let mut s = scene.clone();
        s.quality.view_steps = self.view_steps;
        s.quality.step_length_m = None;
        s.quality.light_steps = self.light_steps;
        s.quality.integration = self.integration;
        s.lighting.phase.model = self.phase;
        s.lighting.beer_powder = self.beer_powder;
        s.lighting.multiple_scattering.octaves = self.octaves;
        s.quality.jitter = self.jitter;
        s.noise.shape_texture = self.shape_texture;
        s
    }

    /// A short name: every setting, e.g. `v64 l6 analytic hg o2 jitter thesis`.
    pub fn name(&self) -> String {
        format!(
            "v{} l{} {} {} o{}{}{} {}",
            self.view_steps,
            self.light_steps,
            match self.integration {
                Integration::Analytic => "analytic",
                Integration::Riemann => "riemann",
            },
            phase_name(self.phase),
            self.octaves,
            if self.beer_powder { " powder" } else { "" },
            if self.jitter { " jitter" } else { "" },
            match self.shape_texture {
                ShapeTexture::Thesis => "128x32x128",
                ShapeTexture::Hzd => "128^3",
            }
        )
    }
}

fn phase_name(p: PhaseModel) -> &'static str {
    match p {
        PhaseModel::Hg => "hg",
        PhaseModel::TwoLobeHg => "2hg",
        PhaseModel::CornetteShanks => "cs",
    }
}

/// The sweep for a scene whose own settings are `base`: one axis at a time around `base`,
/// plus cheap combinations.
fn sweep(base: &Config, quick: bool) -> Vec<Config> {
    let mut out = vec![base.clone()];
    let mut push = |c: Config| {
        if !out.contains(&c) {
            out.push(c);
        }
    };
    let views: &[u32] = if quick {
        &[8, 16, 32, 128]
    } else {
        &[4, 8, 16, 24, 32, 48, 96, 128, 256]
    };
    for &v in views {
        push(Config {
            view_steps: v,
            ..base.clone()
        });
    }
    let lights: &[u32] = if quick {
        &[0, 1, 2, 4]
    } else {
        &[0, 1, 2, 3, 4, 8, 12, 16]
    };
    for &l in lights {
        push(Config {
            light_steps: l,
            ..base.clone()
        });
    }
    for v in [16, base.view_steps] {
        push(Config {
            view_steps: v,
            integration: Integration::Riemann,
            ..base.clone()
        });
    }
    for p in [
        PhaseModel::Hg,
        PhaseModel::TwoLobeHg,
        PhaseModel::CornetteShanks,
    ] {
        push(Config {
            phase: p,
            ..base.clone()
        });
    }
    push(Config {
        beer_powder: !base.beer_powder,
        ..base.clone()
    });
    let octaves: &[u32] = if quick {
        &[0, 1, 4]
    } else {
        &[0, 1, 2, 3, 4, 6, 8]
    };
    for &o in octaves {
        push(Config {
            octaves: o,
            ..base.clone()
        });
    }
    push(Config {
        jitter: !base.jitter,
        ..base.clone()
    });
    push(Config {
        shape_texture: match base.shape_texture {
            ShapeTexture::Thesis => ShapeTexture::Hzd,
            ShapeTexture::Hzd => ShapeTexture::Thesis,
        },
        ..base.clone()
    });
    let combos: &[(u32, u32, Option<u32>)] = if quick {
        &[
            (16, 2, None),
            (32, 4, None),
            (16, 2, Some(0)),
            (32, 2, Some(1)),
        ]
    } else {
        &[
            (16, 2, None),
            (32, 4, None),
            (16, 2, Some(0)),
            (32, 2, Some(1)),
            (24, 3, Some(1)),
            (48, 4, Some(1)),
            (8, 1, Some(0)),
            (128, 8, None),
        ]
    };
    for &(v, l, o) in combos {
        push(Config {
            view_steps: v,
            light_steps: l,
            octaves: o.unwrap_or(base.octaves),
            ..base.clone()
        });
    }
    out
}

/// One measured configuration.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Row {
    /// The scene (preset name).
    pub scene: String,
    /// The configuration's name ([`Config::name`]).
    pub name: String,
    /// Whether this is the scene's own (preset) configuration.
    pub preset: bool,
    /// The settings.
    pub config: Config,
    /// Median GPU time of all passes, ms.
    pub gpu_ms: f64,
    /// Median GPU time of each pass, ms.
    pub passes: BTreeMap<String, f64>,
    /// `gpu_ms` over the preset configuration's.
    pub time_vs_preset: f64,
    /// View steps per pixel.
    pub view_steps_pp: f64,
    /// Light samples per pixel.
    pub light_samples_pp: f64,
    /// Density evaluations (view and light samples) per pixel: "samples per pixel".
    pub samples_pp: f64,
    /// RMSE of linear radiance (rgb) against the reference.
    pub rmse: f64,
    /// Mean FLIP of the composited, tone-mapped image against the reference's.
    pub flip: f64,
    /// 95th percentile of FLIP.
    pub flip_p95: f64,
    /// The reference: `quadrature` or `montecarlo-<spp>spp`.
    pub reference: String,
    /// On the scene's Pareto front of (gpu_ms, flip).
    pub pareto: bool,
}

/// What `results.json` holds.
#[derive(Debug, Serialize, Deserialize)]
pub struct Results {
    /// The device that ran the frames.
    pub device: String,
    /// `wgpu` or `ash`.
    pub backend: String,
    /// Image size.
    pub size: [u32; 2],
    /// Timed repeats per configuration.
    pub repeats: u32,
    /// Monte Carlo samples per pixel of the references.
    pub mc_spp: u32,
    /// Every measurement.
    pub rows: Vec<Row>,
}

/// The default location of the bench's results (where `stratus bench` writes by default).
pub const DEFAULT_RESULTS: &str = "target/stratus-bench/results.json";

fn cache_dir() -> PathBuf {
    match std::env::var_os("XDG_CACHE_HOME") {
        Some(d) if !d.is_empty() => PathBuf::from(d).join("stratus"),
        _ => PathBuf::from("target/stratus-cache"),
    }
}

/// The reference for `scene`: its kind and the scene it renders (fields it ignores reset, so
/// configurations that differ only there share one reference).
fn reference_for(scene: &Scene) -> (Integrator, Scene, bool) {
    let mut s = scene.clone();
    let d = stratus_scene::Quality::default();
    // The converged quadrature and the path tracer override all of these.
    s.quality.view_steps = d.view_steps;
    s.quality.step_length_m = None;
    s.quality.light_steps = d.light_steps;
    s.quality.integration = d.integration;
    s.quality.jitter = d.jitter;
    s.quality.early_exit_transmittance = d.early_exit_transmittance;
    s.quality.light_step_growth = d.light_step_growth;
    s.quality.first_light_step_m = d.first_light_step_m;
    let mc = scene.lighting.multiple_scattering.octaves > 0;
    if mc {
        // Real-time-only terms the path tracer does not model.
        s.lighting.multiple_scattering = Default::default();
        s.lighting.beer_powder = false;
        (Integrator::MonteCarlo { spp: 0, orders: 0 }, s, true)
    } else {
        (
            Integrator::Quadrature(QuadratureSettings::converged()),
            s,
            false,
        )
    }
}

/// Renders (or loads from the cache) the reference of `scene`.
fn reference(scene: &Scene, noise: &NoiseSet, mc_spp: u32) -> Result<(FrameOutput, String)> {
    let (mut integrator, s, mc) = reference_for(scene);
    if let Integrator::MonteCarlo { spp, .. } = &mut integrator {
        *spp = mc_spp;
    }
    let key = {
        let mut h = Sha256::new();
        h.update(s.to_toml().as_bytes());
        h.update(format!("{integrator:?}").as_bytes());
        h.update(b"stratus-reference-cache-v1");
        h.finalize()
            .iter()
            .take(12)
            .fold(String::new(), |mut acc, b| {
                let _ = write!(acc, "{b:02x}");
                acc
            })
    };
    let label = if mc {
        format!("montecarlo-{mc_spp}spp")
    } else {
        "quadrature".to_string()
    };
    let dir = cache_dir();
    let path = dir.join(format!("ref-{key}.bin"));
    let [w, h] = s.camera.resolution;
    if let Ok(bytes) = std::fs::read(&path) {
        if let Some(f) = decode(&bytes, w, h) {
            return Ok((f, label));
        }
    }
    let f = stratus_reference::render(&s, noise, &integrator, false);
    std::fs::create_dir_all(&dir).with_context(|| format!("creating {}", dir.display()))?;
    std::fs::write(&path, encode(&f)).with_context(|| format!("writing {}", path.display()))?;
    Ok((f, label))
}

fn encode(f: &FrameOutput) -> Vec<u8> {
    let mut out = Vec::new();
    out.extend(f.width.to_le_bytes());
    out.extend(f.height.to_le_bytes());
    for v in &f.radiance {
        out.extend(v.to_le_bytes());
    }
    out.extend(&f.image);
    out
}

fn decode(b: &[u8], w: u32, h: u32) -> Option<FrameOutput> {
    let n = (w * h) as usize;
    if b.len() != 8 + 16 * n + 4 * n || b[0..4] != w.to_le_bytes() || b[4..8] != h.to_le_bytes() {
        return None;
    }
    let radiance = b[8..8 + 16 * n]
        .chunks(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    Some(FrameOutput {
        width: w,
        height: h,
        radiance,
        depth: vec![0.0; n],
        image: b[8 + 16 * n..].to_vec(),
        stats: None,
        timings: Vec::new(),
        device: "cache".into(),
    })
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    if v.is_empty() {
        return 0.0;
    }
    let m = v.len() / 2;
    if v.len() % 2 == 1 {
        v[m]
    } else {
        0.5 * (v[m - 1] + v[m])
    }
}

/// Marks the Pareto front of (gpu_ms, flip) per scene: no other row of the scene is at least
/// as fast and at least as accurate and better in one.
fn mark_pareto(rows: &mut [Row]) {
    let keys: Vec<(String, f64, f64)> = rows
        .iter()
        .map(|r| (r.scene.clone(), r.gpu_ms, r.flip))
        .collect();
    for (i, r) in rows.iter_mut().enumerate() {
        let (scene, t, e) = &keys[i];
        r.pareto = !keys.iter().enumerate().any(|(j, (s, t2, e2))| {
            j != i && s == scene && t2 <= t && e2 <= e && (t2 < t || e2 < e)
        });
    }
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
    let mut renderer: Box<dyn FrameRenderer> = match args.backend {
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

    let mut noises: BTreeMap<(u64, bool), NoiseSet> = BTreeMap::new();
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
                .or_insert_with(|| noise_for(&s));
            let (reference, label) = reference(&s, noise, mc_spp)?;
            let plan = FramePlan::for_scene(&s, false)?;
            let mut frame = None;
            let mut totals = Vec::new();
            let mut passes: BTreeMap<String, Vec<f64>> = BTreeMap::new();
            // One warm-up render (pipeline compilation), then the timed repeats.
            renderer.render(&plan, &s, noise)?;
            for _ in 0..repeats {
                let f = renderer.render(&plan, &s, noise)?;
                crate::render::check_finite(&f)?;
                totals.push(f.timings.iter().map(|t| t.ms).sum());
                for t in &f.timings {
                    passes.entry(t.pass.clone()).or_default().push(t.ms);
                }
                frame = Some(f);
            }
            let frame = frame.expect("at least one repeat");
            let stats_plan = FramePlan::for_scene(&s, true)?;
            let counted = renderer.render(&stats_plan, &s, noise)?;
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

/// A drawing surface: the chart is drawn once on each (SVG with text, PNG without).
trait Canvas {
    fn line(&mut self, a: (f64, f64), b: (f64, f64), rgb: (u8, u8, u8), width: u32);
    fn circle(&mut self, c: (f64, f64), r: f64, rgb: (u8, u8, u8), fill: bool);
    fn rect(&mut self, a: (f64, f64), b: (f64, f64), rgb: (u8, u8, u8));
    fn text(&mut self, p: (f64, f64), s: &str, size: u32, rgb: (u8, u8, u8), anchor: &str);
}

struct Svg(String);

fn hex(c: (u8, u8, u8)) -> String {
    format!("#{:02x}{:02x}{:02x}", c.0, c.1, c.2)
}

fn xml(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

impl Canvas for Svg {
    fn line(&mut self, a: (f64, f64), b: (f64, f64), rgb: (u8, u8, u8), width: u32) {
        let _ = writeln!(
            self.0,
            r#"<line x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="{}" stroke-width="{width}"/>"#,
            a.0,
            a.1,
            b.0,
            b.1,
            hex(rgb)
        );
    }
    fn circle(&mut self, c: (f64, f64), r: f64, rgb: (u8, u8, u8), fill: bool) {
        let paint = if fill {
            format!(r#"fill="{}""#, hex(rgb))
        } else {
            format!(r#"fill="none" stroke="{}""#, hex(rgb))
        };
        let _ = writeln!(
            self.0,
            r#"<circle cx="{:.1}" cy="{:.1}" r="{r:.1}" {paint}/>"#,
            c.0, c.1
        );
    }
    fn rect(&mut self, a: (f64, f64), b: (f64, f64), rgb: (u8, u8, u8)) {
        let _ = writeln!(
            self.0,
            r#"<rect x="{:.1}" y="{:.1}" width="{:.1}" height="{:.1}" fill="none" stroke="{}"/>"#,
            a.0,
            a.1,
            b.0 - a.0,
            b.1 - a.1,
            hex(rgb)
        );
    }
    fn text(&mut self, p: (f64, f64), s: &str, size: u32, rgb: (u8, u8, u8), anchor: &str) {
        let _ = writeln!(
            self.0,
            r#"<text x="{:.1}" y="{:.1}" font-family="sans-serif" font-size="{size}" fill="{}" text-anchor="{anchor}">{}</text>"#,
            p.0,
            p.1,
            hex(rgb),
            xml(s)
        );
    }
}

/// The PNG: plotters' bitmap backend, shapes only (no font is needed or looked for).
struct Png<'a>(plotters::prelude::BitMapBackend<'a>);

impl Canvas for Png<'_> {
    fn line(&mut self, a: (f64, f64), b: (f64, f64), rgb: (u8, u8, u8), width: u32) {
        use plotters::prelude::*;
        let style = RGBColor(rgb.0, rgb.1, rgb.2).stroke_width(width);
        let _ = self
            .0
            .draw_line((a.0 as i32, a.1 as i32), (b.0 as i32, b.1 as i32), &style);
    }
    fn circle(&mut self, c: (f64, f64), r: f64, rgb: (u8, u8, u8), fill: bool) {
        use plotters::prelude::*;
        let _ = self.0.draw_circle(
            (c.0 as i32, c.1 as i32),
            r.round() as u32,
            &RGBColor(rgb.0, rgb.1, rgb.2),
            fill,
        );
    }
    fn rect(&mut self, a: (f64, f64), b: (f64, f64), rgb: (u8, u8, u8)) {
        use plotters::prelude::*;
        let _ = self.0.draw_rect(
            (a.0 as i32, a.1 as i32),
            (b.0 as i32, b.1 as i32),
            &RGBColor(rgb.0, rgb.1, rgb.2),
            false,
        );
    }
    fn text(&mut self, _: (f64, f64), _: &str, _: u32, _: (u8, u8, u8), _: &str) {}
}

const PANEL_W: f64 = 460.0;
const PANEL_H: f64 = 380.0;
const MARGIN: (f64, f64, f64, f64) = (56.0, 24.0, 30.0, 44.0); // left, right, top, bottom

/// FLIP (log) against GPU time (log) per scene, one panel each: every configuration a grey
/// dot, the preset a blue ring, the Pareto front red and joined, each front point numbered
/// and named (SVG).
fn draw(canvas: &mut dyn Canvas, results: &Results) {
    let mut scenes: Vec<&str> = results.rows.iter().map(|r| r.scene.as_str()).collect();
    scenes.dedup();
    let grey = (150, 150, 150);
    let black = (0, 0, 0);
    let red = (200, 30, 30);
    let blue = (30, 80, 200);
    for (k, scene) in scenes.iter().enumerate() {
        let ox = k as f64 * PANEL_W;
        let rows: Vec<&Row> = results.rows.iter().filter(|r| r.scene == *scene).collect();
        let lo = |f: fn(&Row) -> f64| {
            rows.iter()
                .map(|r| f(r).max(1e-5))
                .fold(f64::INFINITY, f64::min)
                .log10()
        };
        let hi = |f: fn(&Row) -> f64| {
            rows.iter()
                .map(|r| f(r).max(1e-5))
                .fold(0.0, f64::max)
                .log10()
        };
        let (x0, x1) = (lo(|r| r.gpu_ms) - 0.05, hi(|r| r.gpu_ms) + 0.05);
        let (y0, y1) = (lo(|r| r.flip) - 0.05, hi(|r| r.flip) + 0.05);
        let (l, r_, t, b) = MARGIN;
        let px = |v: f64| ox + l + (v.max(1e-5).log10() - x0) / (x1 - x0) * (PANEL_W - l - r_);
        let py = |v: f64| PANEL_H - b - (v.max(1e-5).log10() - y0) / (y1 - y0) * (PANEL_H - t - b);
        canvas.rect((ox + l, t), (ox + PANEL_W - r_, PANEL_H - b), black);
        canvas.text((ox + PANEL_W / 2.0, 18.0), scene, 14, black, "middle");
        canvas.text(
            (ox + PANEL_W / 2.0, PANEL_H - 8.0),
            "GPU time, ms (log)",
            11,
            black,
            "middle",
        );
        canvas.text((ox + 4.0, t - 8.0), "FLIP (log)", 11, black, "start");
        // Decade and half-decade ticks.
        for e in -5..4 {
            for m in [1.0, 2.0, 5.0] {
                let v = m * 10f64.powi(e);
                let lv = v.log10();
                if lv >= x0 && lv <= x1 {
                    let x = px(v);
                    canvas.line((x, PANEL_H - b), (x, PANEL_H - b + 4.0), black, 1);
                    canvas.text(
                        (x, PANEL_H - b + 15.0),
                        &format!("{v}"),
                        10,
                        black,
                        "middle",
                    );
                }
                if lv >= y0 && lv <= y1 {
                    let y = py(v);
                    canvas.line((ox + l - 4.0, y), (ox + l, y), black, 1);
                    canvas.text((ox + l - 6.0, y + 3.0), &format!("{v}"), 10, black, "end");
                }
            }
        }
        // FLIP 0.05 guide.
        if (0.05f64).log10() >= y0 && (0.05f64).log10() <= y1 {
            let y = py(0.05);
            canvas.line((ox + l, y), (ox + PANEL_W - r_, y), (200, 200, 120), 1);
        }
        for r in &rows {
            canvas.circle((px(r.gpu_ms), py(r.flip)), 2.5, grey, true);
            if r.preset {
                canvas.circle((px(r.gpu_ms), py(r.flip)), 6.0, blue, false);
            }
        }
        let mut front: Vec<&&Row> = rows.iter().filter(|r| r.pareto).collect();
        front.sort_by(|a, b| a.gpu_ms.total_cmp(&b.gpu_ms));
        for w in front.windows(2) {
            canvas.line(
                (px(w[0].gpu_ms), py(w[0].flip)),
                (px(w[1].gpu_ms), py(w[1].flip)),
                red,
                2,
            );
        }
        for (i, r) in front.iter().enumerate() {
            let c = (px(r.gpu_ms), py(r.flip));
            canvas.circle(c, 4.0, red, true);
            canvas.text(
                (c.0 + 6.0, c.1 - 5.0),
                &format!("{}", i + 1),
                10,
                red,
                "start",
            );
            canvas.text(
                (ox + l + 6.0, t + 14.0 + 12.0 * i as f64),
                &format!("{} {}", i + 1, r.name),
                9,
                red,
                "start",
            );
        }
    }
}

fn chart(out: &Path, results: &Results) -> Result<()> {
    let mut n: Vec<&str> = results.rows.iter().map(|r| r.scene.as_str()).collect();
    n.dedup();
    let (w, h) = ((PANEL_W * n.len().max(1) as f64) as u32, PANEL_H as u32);
    let mut svg = Svg(format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}">
<title>Stratus: FLIP against GPU time ({} at {}x{}); red = Pareto front, blue ring = preset settings</title>
<rect width="100%" height="100%" fill="white"/>
"#,
        xml(&results.device),
        results.size[0],
        results.size[1]
    ));
    draw(&mut svg, results);
    svg.0.push_str("</svg>\n");
    let svg_path = out.join("chart.svg");
    std::fs::write(&svg_path, svg.0).with_context(|| format!("writing {}", svg_path.display()))?;

    let png_path = out.join("chart.png");
    {
        use plotters::prelude::*;
        let mut backend = BitMapBackend::new(&png_path, (w, h));
        backend
            .draw_rect((0, 0), (w as i32, h as i32), &WHITE, true)
            .map_err(|e| anyhow::anyhow!("drawing {}: {e:?}", png_path.display()))?;
        let mut png = Png(backend);
        draw(&mut png, results);
        png.0
            .present()
            .map_err(|e| anyhow::anyhow!("writing {}: {e:?}", png_path.display()))?;
    }
    Ok(())
}

/// A coarse scene class: where the camera is against the layer, and whether the sun is low.
fn scene_class(scene: &Scene) -> &'static str {
    let alt = scene.camera.position[1];
    let low_sun = match scene.sun.direction {
        Some(d) => d[1] / (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt() < 0.17,
        None => scene.sun.elevation_deg < 10.0,
    };
    if alt > scene.atmosphere.cloud_top_m {
        "camera above the layer"
    } else if alt >= scene.atmosphere.cloud_bottom_m {
        "camera inside the layer"
    } else if low_sun {
        "camera below, low sun"
    } else {
        "camera below, high sun"
    }
}

/// `stratus render --max-error E`: the cheapest measured configuration whose FLIP is at most
/// `max_error` for this scene. A scene the bench measured uses its own rows; any other scene
/// uses the first measured preset of its class ([`scene_class`]), else needs the configuration
/// to meet `max_error` on every measured scene (the worst case). The error was measured at
/// the bench's image size against its reference; the pick is as good as that measurement.
/// Returns the
/// scene with the configuration applied and a sentence saying what was picked and why.
pub fn auto_quality(
    scene: &Scene,
    name: &str,
    max_error: f64,
    results_path: &Path,
) -> Result<(Scene, String)> {
    let text = std::fs::read_to_string(results_path).with_context(|| {
        format!(
            "reading bench results {} (run `stratus bench` first, or pass --bench-results FILE)",
            results_path.display()
        )
    })?;
    let results: Results = serde_json::from_str(&text)
        .with_context(|| format!("parsing {}", results_path.display()))?;
    let own: Vec<&Row> = results.rows.iter().filter(|r| r.scene == name).collect();
    // Per configuration: worst error and mean time over the scenes that count.
    let mut table: BTreeMap<String, (Config, f64, f64, f64, usize)> = BTreeMap::new();
    let (rows, basis): (Vec<&Row>, String) = if !own.is_empty() {
        (own, format!("scene {name} as measured"))
    } else {
        // Nearest class: a measured preset whose camera is on the same side of the layer
        // and whose sun is as low (or not); failing that, the worst case over all of them.
        let class = scene_class(scene);
        let same: Vec<&Row> = results
            .rows
            .iter()
            .filter(|r| Scene::preset(&r.scene).is_ok_and(|s| scene_class(&s) == class))
            .collect();
        match same.first().map(|r| r.scene.clone()) {
            Some(near) => (
                same.into_iter().filter(|r| r.scene == near).collect(),
                format!(
                    "measured scene {near}, the nearest class ({class}) to {name}, which was not measured"
                ),
            ),
            None => (
                results.rows.iter().collect(),
                format!(
                    "the worst case over every measured scene ({name} was not measured and no measured scene is of its class, {class})"
                ),
            ),
        }
    };
    for r in &rows {
        let e = table
            .entry(r.name.clone())
            .or_insert((r.config.clone(), 0.0, 0.0, 0.0, 0));
        e.1 = e.1.max(r.flip);
        e.2 += r.gpu_ms;
        e.3 += r.samples_pp;
        e.4 += 1;
    }
    let scenes = {
        let mut s: Vec<&str> = rows.iter().map(|r| r.scene.as_str()).collect();
        s.sort();
        s.dedup();
        s.len()
    };
    let candidates: Vec<_> = table
        .iter()
        .filter(|(_, v)| v.4 == scenes)
        .map(|(n, v)| (n, &v.0, v.1, v.2 / v.4 as f64, v.3 / v.4 as f64))
        .collect();
    let best = candidates
        .iter()
        .min_by(|a, b| a.2.total_cmp(&b.2))
        .context("the bench results hold no configuration")?;
    let Some(pick) = candidates
        .iter()
        .filter(|c| c.2 <= max_error)
        .min_by(|a, b| a.3.total_cmp(&b.3))
    else {
        bail!(
            "no measured configuration meets FLIP <= {max_error} on {basis}; the best achievable is {:.4} ({})",
            best.2,
            best.0
        );
    };
    let why = format!(
        "auto quality: picked `{}` for FLIP <= {max_error}: measured FLIP {:.4}, {:.3} ms, {:.1} samples/px on {} ({}, {}x{}); the cheapest of {} measured configurations within the budget",
        pick.0,
        pick.2,
        pick.3,
        pick.4,
        basis,
        results.device,
        results.size[0],
        results.size[1],
        candidates.len()
    );
    Ok((pick.1.apply(scene), why))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(scene: &str, view_steps: u32, gpu_ms: f64, flip: f64) -> Row {
        let base = Config::of(&Scene::default());
        let config = Config {
            view_steps,
            ..base.clone()
        };
        Row {
            scene: scene.into(),
            name: config.name(),
            preset: config == base,
            config,
            gpu_ms,
            passes: BTreeMap::new(),
            time_vs_preset: 1.0,
            view_steps_pp: 0.0,
            light_samples_pp: 0.0,
            samples_pp: f64::from(view_steps),
            rmse: flip,
            flip,
            flip_p95: flip,
            reference: "quadrature".into(),
            pareto: false,
        }
    }

    fn results() -> Results {
        let mut rows = vec![
            row("cumulus-noon", 8, 1.0, 0.2),
            row("cumulus-noon", 16, 2.0, 0.1),
            row("cumulus-noon", 32, 5.0, 0.12),
            row("cumulus-noon", 64, 8.0, 0.01),
            row("sunset", 8, 1.0, 0.3),
            row("sunset", 64, 8.0, 0.05),
        ];
        mark_pareto(&mut rows);
        Results {
            device: "test".into(),
            backend: "wgpu".into(),
            size: [64, 36],
            repeats: 1,
            mc_spp: 1,
            rows,
        }
    }

    #[test]
    fn pareto_front_drops_dominated_rows() {
        let r = results();
        let front: Vec<(u32, bool)> = r.rows[..4]
            .iter()
            .map(|r| (r.config.view_steps, r.pareto))
            .collect();
        assert_eq!(front, [(8, true), (16, true), (32, false), (64, true)]);
    }

    #[test]
    fn auto_quality_picks_the_cheapest_within_budget_and_never_exceeds_it() {
        let dir = std::env::temp_dir().join(format!("stratus-bench-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("results.json");
        std::fs::write(&path, serde_json::to_string(&results()).unwrap()).unwrap();
        let scene = Scene::default();
        let (s, why) = auto_quality(&scene, "cumulus-noon", 0.15, &path).unwrap();
        assert_eq!(s.quality.view_steps, 16, "{why}");
        let (s, _) = auto_quality(&scene, "cumulus-noon", 0.05, &path).unwrap();
        assert_eq!(s.quality.view_steps, 64);
        let e = auto_quality(&scene, "cumulus-noon", 0.001, &path).unwrap_err();
        assert!(e.to_string().contains("best achievable is 0.0100"), "{e}");
        // `storm` was not measured: the nearest class (camera below, high sun) is cumulus-noon.
        let (s, why) = auto_quality(&scene, "storm", 0.15, &path).unwrap();
        assert_eq!(s.quality.view_steps, 16);
        assert!(why.contains("nearest class"), "{why}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn reference_cache_round_trips() {
        let f = FrameOutput {
            width: 2,
            height: 1,
            radiance: vec![0.5, 1.0, 2.0, 0.25, 0.0, 0.1, 0.2, 1.0],
            depth: vec![0.0; 2],
            image: vec![1, 2, 3, 4, 5, 6, 7, 8],
            stats: None,
            timings: Vec::new(),
            device: String::new(),
        };
        let bytes = encode(&f);
        let g = decode(&bytes, 2, 1).unwrap();
        assert_eq!((g.radiance, g.image), (f.radiance, f.image));
        assert!(decode(&bytes, 1, 2).is_none());
    }
}
