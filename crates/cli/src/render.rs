//! `stratus render`: pick a backend, plan the frame, render, write the outputs.

use std::{path::PathBuf, time::Instant};

use anyhow::{Context, Result, bail};
use clap::{Args, ValueEnum};
use serde_json::json;
use stratus_backend_wgpu as backend_wgpu;
use stratus_noise::{NoiseConfig, NoiseSet, ShapeSize};
use stratus_scene::{Scene, ShapeTexture};
use stratus_shaders::{FrameOutput, FramePlan};

use crate::output::{check_image_path, write_image};

/// Which renderer runs the frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Backend {
    /// The best available: wgpu on Vulkan, else wgpu on GL.
    Auto,
    /// wgpu on Vulkan.
    Wgpu,
    /// wgpu on OpenGL through EGL.
    WgpuGl,
    /// Raw Vulkan (ash), running the committed SPIR-V in spirv-out/.
    Ash,
    /// The CPU renderer with the real-time settings (the GPU's steps and jitter, in f64).
    Cpu,
    /// The CPU reference: converged quadrature, or Monte Carlo with --integrator montecarlo.
    Reference,
}

/// How the `reference` backend integrates.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum IntegratorArg {
    /// Deterministic quadrature refined until the image stops changing (single scattering of
    /// the real-time model, with its octaves and ambient).
    Quadrature,
    /// Volumetric path tracing (delta/ratio tracking, next-event estimation to the sun).
    Montecarlo,
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
    /// Image size as WIDTHxHEIGHT (overrides the scene's camera.resolution).
    #[arg(long, value_parser = parse_size)]
    size: Option<(u32, u32)>,
    /// Output image: .png (tone-mapped) or .exr (linear radiance, alpha = transmittance).
    #[arg(long, default_value = "clouds.png")]
    out: PathBuf,
    /// Also write the work counters and per-pass times as JSON to this file.
    #[arg(long)]
    stats: Option<PathBuf>,
    /// `--backend reference`: the integrator.
    #[arg(long, value_enum, default_value_t = IntegratorArg::Quadrature)]
    integrator: IntegratorArg,
    /// `--backend reference --integrator montecarlo`: samples per pixel.
    #[arg(long, default_value_t = 64, value_parser = clap::value_parser!(u32).range(1..))]
    spp: u32,
    /// `--backend reference --integrator montecarlo`: scattering orders (1 = single
    /// scattering, 0 = all).
    #[arg(long, default_value_t = 0)]
    orders: u32,
    /// Auto quality: render with the cheapest configuration `stratus bench` measured whose
    /// FLIP against the reference is at most E (for this scene; other scenes: on every
    /// measured scene).
    #[arg(long, value_name = "E")]
    max_error: Option<f64>,
    /// The bench results `--max-error` reads.
    #[arg(long, value_name = "FILE", default_value = crate::bench::DEFAULT_RESULTS)]
    bench_results: PathBuf,
}

pub(crate) fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("`{s}`: expected WIDTHxHEIGHT, e.g. 256x144"))?;
    let p = |v: &str| {
        v.trim()
            .parse::<u32>()
            .ok()
            .filter(|n| (1..=16384).contains(n))
            .ok_or_else(|| {
                format!("`{s}`: width and height must be whole numbers within [1, 16384]")
            })
    };
    Ok((p(w)?, p(h)?))
}

/// Loads the scene the arguments name (default: the default preset) at the requested size.
pub fn load_scene(
    preset: Option<&str>,
    file: Option<&PathBuf>,
    size: Option<(u32, u32)>,
) -> Result<(Scene, String)> {
    let (scene, name) = match (preset, file) {
        (_, Some(f)) => (
            Scene::from_file(f).map_err(|e| anyhow::anyhow!("{e}"))?,
            f.display().to_string(),
        ),
        (Some(p), None) => (
            Scene::preset(p).map_err(|e| anyhow::anyhow!("{e}"))?,
            p.to_string(),
        ),
        (None, None) => (Scene::default(), stratus_scene::DEFAULT_PRESET.to_string()),
    };
    let scene = match size {
        Some((w, h)) => scene.with_size(w, h),
        None => scene,
    };
    scene.validate().map_err(|e| anyhow::anyhow!("{e}"))?;
    Ok((scene, name))
}

/// The noise textures a scene reads.
pub fn noise_for(scene: &Scene) -> NoiseSet {
    NoiseSet::generate(&NoiseConfig {
        seed: scene.noise.seed,
        shape: match scene.noise.shape_texture {
            ShapeTexture::Thesis => ShapeSize::Thesis,
            ShapeTexture::Hzd => ShapeSize::Hzd,
        },
        ..NoiseConfig::default()
    })
}

/// A renderer the CLI can drive: one frame from a plan.
pub(crate) trait FrameRenderer {
    fn render(&mut self, plan: &FramePlan, scene: &Scene, noise: &NoiseSet) -> Result<FrameOutput>;
    fn describe(&self) -> String;
}

impl FrameRenderer for backend_wgpu::Renderer {
    fn render(&mut self, plan: &FramePlan, scene: &Scene, noise: &NoiseSet) -> Result<FrameOutput> {
        Ok(backend_wgpu::Renderer::render(
            self,
            plan,
            &scene.uniforms(),
            noise,
        )?)
    }
    fn describe(&self) -> String {
        format!("wgpu on {}", self.adapter())
    }
}

impl FrameRenderer for stratus_backend_ash::Renderer {
    fn render(&mut self, plan: &FramePlan, scene: &Scene, noise: &NoiseSet) -> Result<FrameOutput> {
        Ok(stratus_backend_ash::Renderer::render(
            self,
            plan,
            &scene.uniforms(),
            noise,
        )?)
    }
    fn describe(&self) -> String {
        format!("ash (Vulkan) on {}", self.adapter())
    }
}

/// The CPU renderers: the real-time settings (`cpu`) or the reference integrators.
struct Cpu {
    integrator: stratus_reference::Integrator,
    label: &'static str,
}

impl FrameRenderer for Cpu {
    fn render(
        &mut self,
        _plan: &FramePlan,
        scene: &Scene,
        noise: &NoiseSet,
    ) -> Result<FrameOutput> {
        // The CPU runs the model directly; the plan's variant only matters to the GPU.
        Ok(stratus_reference::render(
            scene,
            noise,
            &self.integrator,
            true,
        ))
    }
    fn describe(&self) -> String {
        format!(
            "{} on the CPU ({} threads)",
            self.label,
            rayon::current_num_threads()
        )
    }
}

fn cpu_realtime() -> Cpu {
    Cpu {
        integrator: stratus_reference::Integrator::Quadrature(
            stratus_reference::QuadratureSettings::realtime(),
        ),
        label: "cpu (real-time settings)",
    }
}

/// `STRATUS_VALIDATION=1` turns on the backends' validation (wgpu's and the Vulkan layer).
fn validation() -> bool {
    std::env::var_os("STRATUS_VALIDATION").is_some()
}

fn wgpu(api: backend_wgpu::Api) -> Result<backend_wgpu::Renderer, backend_wgpu::Error> {
    backend_wgpu::Renderer::new(backend_wgpu::Options {
        api,
        validation: validation(),
    })
}

fn open_backend(backend: Backend, args: &RenderArgs) -> Result<Box<dyn FrameRenderer>> {
    Ok(match backend {
        Backend::Wgpu => Box::new(wgpu(backend_wgpu::Api::Vulkan)?),
        Backend::WgpuGl => Box::new(wgpu(backend_wgpu::Api::Gl)?),
        Backend::Ash => Box::new(stratus_backend_ash::Renderer::new(
            stratus_backend_ash::Options {
                validation: validation(),
            },
        )?),
        Backend::Cpu => Box::new(cpu_realtime()),
        Backend::Reference => Box::new(match args.integrator {
            IntegratorArg::Quadrature => Cpu {
                integrator: stratus_reference::Integrator::Quadrature(
                    stratus_reference::QuadratureSettings::converged(),
                ),
                label: "reference (converged quadrature)",
            },
            IntegratorArg::Montecarlo => Cpu {
                integrator: stratus_reference::Integrator::MonteCarlo {
                    spp: args.spp,
                    orders: args.orders,
                },
                label: "reference (Monte Carlo)",
            },
        }),
        Backend::Auto => match wgpu(backend_wgpu::Api::Vulkan) {
            Ok(r) => Box::new(r),
            Err(_) => match wgpu(backend_wgpu::Api::Gl) {
                Ok(r) => {
                    eprintln!(
                        "note: no Vulkan device; using wgpu's GL backend (install mesa-vulkan-drivers for a Vulkan device)"
                    );
                    Box::new(r)
                }
                Err(_) => {
                    eprintln!(
                        "note: no Vulkan or GL device; rendering on the CPU (install mesa-vulkan-drivers for a Vulkan device)"
                    );
                    Box::new(cpu_realtime())
                }
            },
        },
    })
}

/// Runs `stratus render`.
pub fn run(args: RenderArgs) -> Result<()> {
    check_image_path(&args.out)?;
    let (scene, name) = load_scene(args.preset.as_deref(), args.scene.as_ref(), args.size)?;
    let scene = match args.max_error {
        Some(e) => {
            let (picked, why) = crate::bench::auto_quality(&scene, &name, e, &args.bench_results)?;
            println!("{why}");
            picked
        }
        None => scene,
    };
    let t0 = Instant::now();
    let noise = noise_for(&scene);
    let noise_ms = t0.elapsed().as_secs_f64() * 1e3;
    let mut renderer = open_backend(args.backend, &args)?;
    let plan = FramePlan::for_scene(&scene, false)?;
    let t = Instant::now();
    let frame = renderer.render(&plan, &scene, &noise)?;
    let frame_ms = t.elapsed().as_secs_f64() * 1e3;
    check_finite(&frame)?;
    write_image(&args.out, &frame)?;

    let gpu_ms: f64 = frame.timings.iter().map(|t| t.ms).sum();
    println!(
        "wrote {} ({}x{}, scene {name})",
        args.out.display(),
        frame.width,
        frame.height
    );
    println!(
        "backend: {} | variant {}",
        renderer.describe(),
        plan.variant
    );
    let passes: Vec<String> = frame
        .timings
        .iter()
        .map(|t| format!("{} {:.2} ms", t.pass, t.ms))
        .collect();
    println!(
        "frame: {frame_ms:.1} ms wall, passes {gpu_ms:.2} ms ({}, {}); noise generated in {noise_ms:.0} ms",
        passes.join(", "),
        frame.timings.first().map_or("untimed", |t| t.source)
    );

    if let Some(path) = &args.stats {
        // Counters come from the statistics variant; times from the normal one above, which
        // pays nothing for counting.
        let stats_plan = FramePlan::for_scene(&scene, true)?;
        let counted = match frame.stats {
            // The CPU renderers always count; no second render needed.
            Some(_) => frame.clone(),
            None => renderer.render(&stats_plan, &scene, &noise)?,
        };
        let doc = json!({
            "scene": name,
            "backend": renderer.describe(),
            "variant": plan.variant,
            "stats_variant": stats_plan.variant,
            "width": frame.width,
            "height": frame.height,
            "counters": counted.stats,
            "passes": frame.timings.iter().map(|t| json!({"pass": t.pass, "ms": t.ms, "source": t.source})).collect::<Vec<_>>(),
            "frame_ms": frame_ms,
        });
        std::fs::write(path, serde_json::to_string_pretty(&doc)? + "\n")
            .with_context(|| format!("writing {}", path.display()))?;
        println!("wrote {}", path.display());
    }
    Ok(())
}

/// No NaN or Inf may leave the renderer.
pub fn check_finite(frame: &FrameOutput) -> Result<()> {
    if let Some(i) = frame.radiance.iter().position(|v| !v.is_finite()) {
        let p = i / 4;
        bail!(
            "the renderer produced a non-finite value ({}) at pixel ({}, {}); this is a bug",
            frame.radiance[i],
            p as u32 % frame.width,
            p as u32 / frame.width
        );
    }
    Ok(())
}
