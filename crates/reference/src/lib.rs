//! The CPU reference renderer of Stratus: the same scene as the WGSL, in f64, from the same
//! noise texels.
//!
//! Two integrators share the model:
//!
//! * [`Integrator::Quadrature`]: the WGSL's view march line by line (`march.wgsl`,
//!   `lighting.wgsl`, `density.wgsl`, `geometry.wgsl`, `composite.wgsl`, each mirrored by the
//!   module of the same name; every function carries a `// WGSL: <file>::<fn>` comment), and
//!   under the physical sky `atmosphere.wgsl`'s tables and lookups ([`sky`]). With
//!   [`QuadratureSettings::realtime`] it takes the scene's view steps, light steps and jitter, so
//!   a GPU frame and its CPU twin can be compared pixel for pixel, work counters included. With
//!   [`QuadratureSettings::converged`] it is the model's converged answer (see there for the
//!   definition and its measurement).
//! * [`Integrator::MonteCarlo`]: a volumetric path tracer through the same density field (see
//!   the [`montecarlo`] module for the estimators, how the ambient maps to an environment and
//!   which real-time-only terms it ignores).
//!
//! Parameters are read from [`Scene::uniforms`], the f32 values the GPU gets, widened to f64,
//! so both see identical inputs. A [`Medium`] other than the clouds (a homogeneous slab or
//! ball) lets the same integrators run on media with closed-form answers.
//!
//! ```no_run
//! use stratus_reference::{Integrator, QuadratureSettings, render};
//! use stratus_noise::{NoiseConfig, NoiseSet};
//! use stratus_scene::Scene;
//!
//! let scene = Scene::default().with_size(256, 144);
//! let noise = NoiseSet::generate(&NoiseConfig::default());
//! let frame = render(&scene, &noise, &Integrator::Quadrature(QuadratureSettings::realtime()), true);
//! assert_eq!(frame.radiance.len(), 256 * 144 * 4);
//! ```

#![warn(missing_docs)]

pub mod atmosphere;
mod composite;
mod density;
mod environment;
mod flare;
mod frame;
mod geometry;
mod lighting;
mod lightning;
mod march;
mod math;
mod medium;
pub mod montecarlo;
mod night;
mod particles;
mod phase;
mod post;
mod precipitation;
mod progressive;
mod rainbow;
pub mod sky;
mod temporal;
mod texture;

/// Small noise textures (a 32-texel weather map, 8-texel curl and detail), made once, for the
/// unit tests that look at the sky, the far shadow or a few paths rather than the clouds'
/// detail.
#[cfg(test)]
pub(crate) fn small_noise() -> std::sync::Arc<stratus_noise::NoiseSet> {
    static NOISE: std::sync::OnceLock<std::sync::Arc<stratus_noise::NoiseSet>> =
        std::sync::OnceLock::new();
    NOISE
        .get_or_init(|| {
            std::sync::Arc::new(stratus_noise::NoiseSet::generate(
                &stratus_noise::NoiseConfig {
                    weather_size: 32,
                    curl_size: 8,
                    detail_size: 8,
                    ..Default::default()
                },
            ))
        })
        .clone()
}

use std::collections::BTreeMap;
use std::time::Instant;

use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;
use std::sync::Arc;
use stratus_graph::{FrameOutput, PassTiming, SceneDepth};
use stratus_noise::NoiseSet;
use stratus_scene::{Integration, Scene};

use crate::density::Counters;
use crate::frame::{
    FLAG_DYNAMIC_STEP, FLAG_EMPTY_SKIP, FLAG_JITTER, Frame, INTEGRATION_ANALYTIC,
    INTEGRATION_RIEMANN,
};
use crate::geometry::{RayKind, view_ray};
use crate::lighting::LightMarch;
use crate::march::{MarchSettings, march, march_ray};
use crate::math::V3;
use crate::medium::Model;
use crate::montecarlo::{Accumulator, Rng, camera_interval, trace};

pub use crate::composite::Compositor;
pub use crate::environment::Environment;
pub use crate::medium::{DensityGrid, Medium, Shape, sample_density_grid};
pub use crate::{progressive::PathState, temporal::TemporalState};

/// How the radiance of a pixel is computed.
#[derive(Clone, Debug, PartialEq)]
pub enum Integrator {
    /// The WGSL's ray march in f64 (deterministic).
    Quadrature(QuadratureSettings),
    /// Volumetric path tracing with `spp` samples a pixel and `orders` scattering orders
    /// (1 = single scattering; 0 = all), see [`montecarlo`]. The frame's radiance is the mean
    /// in-scattered radiance, its alpha the mean (ratio-tracking) transmittance of the camera
    /// ray, its depth the mean distance of the first collision; [`Rendering::std_error`] holds
    /// the standard errors. Counters: `pixels`, `marched_pixels`, `exit_missed_layer` and
    /// `exit_ground` mean what they mean on the GPU; `view_steps` counts tentative collisions
    /// on camera rays, `light_samples` those of shadow, environment and scattered rays,
    /// `density_evaluations` and `detail_evaluations` every evaluation; `exit_transmittance`
    /// is 0.
    MonteCarlo {
        /// Samples per pixel (at least 1).
        spp: u32,
        /// Scattering orders that contribute (1 = single scattering, 0 = all).
        orders: u32,
    },
}

/// Discretisation of the quadrature. `None` takes the scene's value.
#[derive(Clone, Debug, PartialEq)]
pub struct QuadratureSettings {
    /// Exactly this many view steps per ray (otherwise the scene's `view_steps`, or its step
    /// length when it has one, as the WGSL).
    pub view_steps: Option<u32>,
    /// Light-march steps (otherwise the scene's).
    pub light_steps: Option<u32>,
    /// Growth of successive light steps (otherwise the scene's).
    pub light_step_growth: Option<f64>,
    /// `false`: the light march starts with the scene's first light step, as the WGSL. `true`
    /// (not in the WGSL): the light steps exactly cover the sun ray's path to where it leaves
    /// the layer (with growth 1: equal steps over the whole path to the layer top).
    pub light_to_layer_exit: bool,
    /// Jitter the start offset per pixel (otherwise the scene's flag). Without jitter the
    /// samples are at step midpoints.
    pub jitter: Option<bool>,
    /// Early-exit transmittance (otherwise the scene's; 0 marches the whole interval).
    pub early_exit: Option<f64>,
    /// Step integral (otherwise the scene's).
    pub integration: Option<Integration>,
    /// The cheap-march techniques, dynamic step length and empty-space skipping (otherwise
    /// the scene's flags).
    pub cheap_march: Option<bool>,
}

impl QuadratureSettings {
    /// Exactly what the GPU does for the scene: its view steps (or step length), light steps,
    /// light step growth, jitter, early exit and step integral.
    pub fn realtime() -> Self {
        Self {
            view_steps: None,
            light_steps: None,
            light_step_growth: None,
            light_to_layer_exit: false,
            jitter: None,
            early_exit: None,
            integration: None,
            cheap_march: None,
        }
    }

    /// The converged reference of the real-time model: 1024 view steps, 128 light steps of
    /// equal length covering the whole sun path to where it leaves the layer, no jitter
    /// (midpoint samples), no early exit, the analytic step integral.
    ///
    /// "Converged" means: doubling both the view and the light steps changes the image's mean
    /// linear radiance by less than 0.1%, and no pixel's radiance by more than 1% of the
    /// image's largest radiance. Measured at 64x36 with the `converge` example (`cargo run
    /// --release -p stratus-reference --example converge -- <preset> 64x36 2 both 1024 128`),
    /// 1024x128 against 2048x256 steps:
    ///
    /// | preset | mean change | mean abs change | max change |
    /// |---|---|---|---|
    /// | cumulus-noon | 0.0027% | 0.0084% | 0.19% |
    /// | sunset (sun 4 degrees up: 36 km light paths) | 0.029% | 0.070% | 0.39% |
    /// | above-clouds | 0.0013% | 0.0041% | 0.17% |
    /// | storm | 0.0004% | 0.0009% | 0.05% |
    ///
    /// The light steps matter most at a low sun: for `sunset`, 64 light steps miss the criterion
    /// (doubling them changes the mean by 0.14%), 128 meet it (0.03%); the view steps at 1024
    /// change the mean by 0.003% when doubled. The quadrature's error against closed forms is
    /// second order in the step (`tests/analytic.rs`).
    pub fn converged() -> Self {
        Self {
            view_steps: Some(1024),
            light_steps: Some(128),
            light_step_growth: Some(1.0),
            light_to_layer_exit: true,
            jitter: Some(false),
            early_exit: Some(0.0),
            integration: Some(Integration::Analytic),
            cheap_march: Some(false),
        }
    }

    fn resolve(&self, f: &Frame) -> MarchSettings {
        MarchSettings {
            view_steps: self.view_steps,
            light: LightMarch {
                steps: self.light_steps.unwrap_or(f.light_steps),
                growth: self.light_step_growth.unwrap_or(f.light_step_growth),
                first: f.first_light_step,
                to_layer_exit: self.light_to_layer_exit,
            },
            jitter: self.jitter.unwrap_or(f.flags & FLAG_JITTER != 0),
            early_exit: self.early_exit.unwrap_or(f.early_exit_transmittance),
            integration: match self.integration {
                Some(Integration::Analytic) => INTEGRATION_ANALYTIC,
                Some(Integration::Riemann) => INTEGRATION_RIEMANN,
                None => f.integration,
            },
            dynamic_step: self.cheap_march.unwrap_or(f.flags & FLAG_DYNAMIC_STEP != 0),
            empty_skip: self.cheap_march.unwrap_or(f.flags & FLAG_EMPTY_SKIP != 0),
        }
    }
}

/// Options of a render that do not change the image.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct RenderOptions {
    /// Show a progress bar on stderr.
    pub progress: bool,
    /// Render on a pool of this many threads (default: rayon's global pool). The image does not
    /// depend on it.
    pub threads: Option<usize>,
}

/// A render: the frame, plus the Monte Carlo standard errors.
#[derive(Clone, Debug)]
pub struct Rendering {
    /// Radiance and transmittance, depth, the composited image, counters and timings.
    pub output: FrameOutput,
    /// Monte Carlo only: the standard error of each pixel's mean, 4 floats a pixel (radiance
    /// rgb, transmittance), row-major like `output.radiance`. `None` for the quadrature.
    pub std_error: Option<Vec<f32>>,
}

/// Mean and standard error of a block of pixels of a [`Rendering`].
#[derive(Clone, Debug, PartialEq)]
pub struct Block {
    /// Left column.
    pub x: u32,
    /// Top row.
    pub y: u32,
    /// Width in pixels (smaller at the right edge).
    pub width: u32,
    /// Height in pixels (smaller at the bottom edge).
    pub height: u32,
    /// Mean radiance rgb and transmittance over the block.
    pub mean: [f64; 4],
    /// Standard error of `mean` (pixels are independent: `sqrt(sum se_i^2) / n`); 0 for the
    /// quadrature.
    pub std_error: [f64; 4],
}

impl Rendering {
    /// Means and standard errors over `size` x `size` blocks, row by row (edge blocks are
    /// smaller).
    pub fn blocks(&self, size: u32) -> Vec<Block> {
        let (w, h) = (self.output.width, self.output.height);
        let mut out = Vec::new();
        for by in (0..h).step_by(size as usize) {
            for bx in (0..w).step_by(size as usize) {
                let (bw, bh) = (size.min(w - bx), size.min(h - by));
                let n = f64::from(bw * bh);
                let mut mean = [0.0; 4];
                let mut var = [0.0; 4];
                for y in by..by + bh {
                    for x in bx..bx + bw {
                        let i = 4 * (y * w + x) as usize;
                        for c in 0..4 {
                            mean[c] += f64::from(self.output.radiance[i + c]) / n;
                            if let Some(se) = &self.std_error {
                                var[c] += f64::from(se[i + c]).powi(2);
                            }
                        }
                    }
                }
                out.push(Block {
                    x: bx,
                    y: by,
                    width: bw,
                    height: bh,
                    mean,
                    std_error: var.map(|v| v.sqrt() / n),
                });
            }
        }
        out
    }
}

/// The radiance along one ray, with its standard error (0 for the quadrature).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayEstimate {
    /// In-scattered radiance, linear rgb.
    pub radiance: [f64; 3],
    /// Transmittance of the ray's interval in the medium.
    pub transmittance: f64,
    /// Standard error of radiance rgb and transmittance.
    pub std_error: [f64; 4],
}

/// A scene and a medium ready to trace single rays from the scene's camera (for tests and
/// measurements that need directions other than the camera's pixels).
pub struct Tracer<'a> {
    model: Model<'a>,
}

impl<'a> Tracer<'a> {
    /// The scene's frame (its uniforms widened to f64) with `medium`.
    pub fn new(scene: &Scene, medium: Medium<'a>) -> Self {
        Self {
            model: Model::new(scene, medium),
        }
    }

    /// The quadrature along unit `direction` from the camera (jitter, if on, uses pixel 0, 0).
    pub fn quadrature(&self, direction: [f64; 3], settings: &QuadratureSettings) -> RayEstimate {
        let s = settings.resolve(&self.model.f);
        let jitter = if s.jitter {
            frame::hash_unit([0, 0], self.model.f.frame_index)
        } else {
            0.5
        };
        let r = march_ray(
            &self.model,
            &s,
            V3::from_array(direction).normalize(),
            jitter,
        );
        RayEstimate {
            radiance: r.radiance.to_array(),
            transmittance: r.transmittance,
            std_error: [0.0; 4],
        }
    }

    /// `spp` path-traced samples along unit `direction` from the camera, with `orders`
    /// scattering orders (0 = all); `key` selects the random streams (like a pixel index).
    pub fn monte_carlo(&self, direction: [f64; 3], spp: u32, orders: u32, key: u64) -> RayEstimate {
        let view = V3::from_array(direction).normalize();
        let span = camera_interval(&self.model, view);
        let mut acc = Accumulator::default();
        let mut counters = Counters::default();
        for s in 0..spp.max(1) {
            let mut rng = Rng::new(key, u64::from(s), u64::from(self.model.f.frame_index));
            acc.add(&trace(
                &self.model,
                view,
                &span,
                orders,
                &mut rng,
                &mut counters,
            ));
        }
        let m = acc.mean();
        RayEstimate {
            radiance: [m[0], m[1], m[2]],
            transmittance: m[3],
            std_error: acc.std_error(),
        }
    }
}

/// The work counters the CPU renderers report, named and ordered as the GPU's (the frame
/// graph's `stats` resource).
pub const COUNTER_NAMES: [&str; 9] = [
    "pixels",
    "marched_pixels",
    "view_steps",
    "density_evaluations",
    "detail_evaluations",
    "light_samples",
    "exit_transmittance",
    "exit_missed_layer",
    "exit_ground",
];

/// Renders the scene's clouds with `integrator` (rayon's global pool; a progress bar on stderr
/// if `progress`).
pub fn render(
    scene: &Scene,
    noise: &NoiseSet,
    integrator: &Integrator,
    progress: bool,
) -> FrameOutput {
    render_medium(
        scene,
        Medium::Clouds(noise),
        integrator,
        &RenderOptions {
            progress,
            threads: None,
        },
    )
    .output
}

/// [`render`] of the clouds in front of the host's geometry: every march stops at the surface
/// `depth` holds (`None`: no geometry, the same as [`render`]).
pub fn render_with_scene_depth(
    scene: &Scene,
    noise: &NoiseSet,
    integrator: &Integrator,
    progress: bool,
    depth: Option<&Arc<SceneDepth>>,
) -> FrameOutput {
    let model = Model::with_scene_depth(scene.uniforms(), Medium::Clouds(noise), depth);
    render_model(&model, integrator, progress).output
}

/// The key light's transmittance through every cloud layer toward it from each of `points`
/// (Stratus's world: x east, altitude, z north; m), integrated with `steps` midpoint steps a
/// layer (the GPU's shadow map takes 16; a few hundred converge). What a host's geometry
/// below the clouds receives of the sun.
pub fn sun_transmittance(
    scene: &Scene,
    noise: &NoiseSet,
    points: &[[f64; 3]],
    steps: u32,
) -> Vec<f64> {
    let model = Model::new(scene, Medium::Clouds(noise));
    let f = &model.f;
    let (cx, cz) = (f.camera_position[0], f.camera_position[2]);
    let rp = f.planet_radius;
    let sigma_t = f.scattering + f.absorption;
    points
        .iter()
        .map(|&[x, alt, z]| {
            // Camera-relative, on the planet: the point `alt` above the ground below it.
            let (dx, dz) = (x - cx, z - cz);
            let y = ((rp + alt).powi(2) - dx * dx - dz * dz).sqrt() - rp;
            let tau = model.sun_optical_depth(V3::new(dx, y, dz), alt, steps.max(1));
            (-sigma_t * tau).exp()
        })
        .collect()
}

/// What one pixel contributes.
#[derive(Clone, Copy, Default)]
struct PixelOut {
    value: [f64; 4],
    std_error: [f64; 4],
    depth: f64,
    counters: Counters,
    kind: Option<RayKind>,
    exited_early: bool,
}

/// Renders `medium` in `scene` with `integrator`.
pub fn render_medium(
    scene: &Scene,
    medium: Medium,
    integrator: &Integrator,
    options: &RenderOptions,
) -> Rendering {
    let render = || render_model(&Model::new(scene, medium), integrator, options.progress);
    in_pool(options.threads, render)
}

/// The Monte Carlo integrator's render of `medium` in `scene` (`spp` paths a pixel, `orders`
/// scattering events at most, 0 for all) under `environment` instead of the sky's light:
/// paths that leave the medium see its map, and its sun lights every vertex (the physical sky
/// frozen at one point, as `stratus export-volume` gives it to Mitsuba). Only the Monte Carlo
/// integrator takes it, so it is the only one offered.
pub fn render_medium_lit(
    scene: &Scene,
    medium: Medium,
    environment: &Environment,
    spp: u32,
    orders: u32,
    options: &RenderOptions,
) -> Rendering {
    let render = || {
        let mut model = Model::new(scene, medium);
        model.environment = Some(environment);
        render_model(
            &model,
            &Integrator::MonteCarlo { spp, orders },
            options.progress,
        )
    };
    in_pool(options.threads, render)
}

/// Runs `render` on a pool of `threads` threads, or on rayon's global pool.
fn in_pool(threads: Option<usize>, render: impl FnOnce() -> Rendering + Send) -> Rendering {
    match threads {
        Some(n) => rayon::ThreadPoolBuilder::new()
            .num_threads(n.max(1))
            .build()
            .expect("building a rayon thread pool")
            .install(render),
        None => render(),
    }
}

/// Renders the frame and medium of `model` (its physical sky's tables, if any, computed with
/// it) with `integrator`, on the current pool.
fn render_model(model: &Model, integrator: &Integrator, progress: bool) -> Rendering {
    let f = &model.f;
    let (w, h) = (f.size[0], f.size[1]);
    let bar = if progress {
        let bar = ProgressBar::new(u64::from(h));
        if let Ok(style) = ProgressStyle::with_template(
            "{msg} [{elapsed_precise}] {wide_bar} {pos}/{len} rows (eta {eta})",
        ) {
            bar.set_style(style);
        }
        bar.set_message(match integrator {
            Integrator::Quadrature(_) => "quadrature".to_string(),
            Integrator::MonteCarlo { spp, orders } => {
                format!("path tracing {spp} spp, orders {orders}")
            }
        });
        bar
    } else {
        ProgressBar::hidden()
    };

    let t0 = Instant::now();
    let pixel = |x: u32, y: u32| -> PixelOut {
        match integrator {
            Integrator::Quadrature(settings) => {
                let s = settings.resolve(f);
                let r = march(model, &s, [x, y]);
                PixelOut {
                    value: [r.radiance.x, r.radiance.y, r.radiance.z, r.transmittance],
                    std_error: [0.0; 4],
                    depth: r.depth,
                    counters: r.counters,
                    kind: r.kind,
                    exited_early: r.exited_early,
                }
            }
            Integrator::MonteCarlo { spp, orders } => {
                let view = view_ray(f, [x, y]);
                let span = camera_interval(model, view);
                let mut acc = Accumulator::default();
                let mut counters = Counters::default();
                let key = u64::from(y) * u64::from(w) + u64::from(x);
                for s in 0..(*spp).max(1) {
                    // Must be independent of scheduling: one stream per (pixel, sample, frame).
                    let mut rng = Rng::new(key, u64::from(s), u64::from(f.frame_index));
                    acc.add(&trace(model, view, &span, *orders, &mut rng, &mut counters));
                }
                PixelOut {
                    value: acc.mean(),
                    std_error: acc.std_error(),
                    depth: acc.depth(),
                    counters,
                    kind: Some(span.kind),
                    exited_early: false,
                }
            }
        }
    };
    let rows: Vec<Vec<PixelOut>> = (0..h)
        .into_par_iter()
        .map(|y| {
            let row = (0..w).map(|x| pixel(x, y)).collect();
            bar.inc(1);
            row
        })
        .collect();
    bar.finish_and_clear();
    let march_ms = t0.elapsed().as_secs_f64() * 1e3;

    let n = (w * h) as usize;
    let mut radiance = Vec::with_capacity(4 * n);
    let mut std_error = Vec::with_capacity(4 * n);
    let mut depth = Vec::with_capacity(n);
    // In the order of COUNTER_NAMES (a test holds them to the frame graph's counters, which
    // the build holds to march.wgsl's STAT_* indices).
    let mut raw = [0u64; 9];
    for p in rows.iter().flatten() {
        radiance.extend(p.value.map(|v| v as f32));
        std_error.extend(p.std_error.map(|v| v as f32));
        depth.push(p.depth as f32);
        raw[0] += 1;
        match p.kind {
            Some(RayKind::March) => raw[1] += 1,
            Some(RayKind::MissesLayer) => raw[7] += 1,
            Some(RayKind::HitsGround) => raw[8] += 1,
            None => {}
        }
        raw[2] += p.counters.view_steps;
        raw[3] += p.counters.density;
        raw[4] += p.counters.detail;
        raw[5] += p.counters.light;
        raw[6] += u64::from(p.exited_early);
    }
    let stats: BTreeMap<String, u64> = COUNTER_NAMES
        .iter()
        .zip(raw)
        .map(|(name, v)| (name.to_string(), v))
        .collect();

    let t1 = Instant::now();
    let image = composite::composite_image(
        f,
        model.sky(),
        w,
        h,
        &radiance,
        &depth,
        model.surface.as_deref(),
        crate::precipitation::Rain::of(model).as_ref(),
    );
    let composite_ms = t1.elapsed().as_secs_f64() * 1e3;
    let mut timings = sky::in_graph_order(
        model.sky(),
        [PassTiming {
            pass: "march".to_string(),
            ms: march_ms,
            source: "cpu-wall",
        }],
        PassTiming {
            pass: "composite".to_string(),
            ms: composite_ms,
            source: "cpu-wall",
        },
    );
    let mut image = post::stylise(f, w, h, image, &mut timings);
    crate::particles::particles_pass(
        f,
        crate::precipitation::Rain::of(model).as_ref(),
        &mut image,
        &mut timings,
    );

    let is_mc = matches!(integrator, Integrator::MonteCarlo { .. });
    Rendering {
        output: FrameOutput {
            width: w,
            height: h,
            radiance,
            depth,
            image,
            stats: Some(stats),
            timings,
            device: format!("cpu ({} threads)", rayon::current_num_threads()),
            ..Default::default()
        },
        std_error: is_mc.then_some(std_error),
    }
}

/// The CPU renderers behind the one backend trait, so a caller drives them like the GPU
/// backends: the scene's clouds with `integrator`, ignoring the plan's variant (the CPU runs
/// the whole model). Always counts work; times are CPU wall clock.
pub struct CpuBackend {
    /// How pixels are integrated.
    pub integrator: Integrator,
    /// What to call it, e.g. `reference (converged quadrature)`.
    pub label: &'static str,
    /// A progress bar on stderr.
    pub progress: bool,
    /// Temporal upsampling's history between frames (used when a scene asks for it).
    pub temporal: temporal::TemporalState,
    /// The progressive path tracer's means between frames (`quality.integrator =
    /// "pathtrace"`).
    pub pathtrace: progressive::PathState,
}

impl Default for CpuBackend {
    /// The real-time settings (the GPU's steps and jitter, in f64), no progress bar.
    fn default() -> Self {
        Self {
            integrator: Integrator::Quadrature(QuadratureSettings::realtime()),
            label: "cpu (real-time settings)",
            progress: false,
            temporal: temporal::TemporalState::default(),
            pathtrace: progressive::PathState::default(),
        }
    }
}

impl stratus_graph::Backend for CpuBackend {
    fn describe(&self) -> String {
        format!(
            "{} on the CPU ({} threads)",
            self.label,
            rayon::current_num_threads()
        )
    }
    fn has_timestamps(&self) -> bool {
        false
    }
    fn render(
        &mut self,
        frame: &stratus_graph::FrameInput<'_>,
    ) -> Result<FrameOutput, stratus_graph::BackendError> {
        let t = Instant::now();
        let method = frame.scene.quality.method;
        if method != stratus_scene::Method::Volumetric {
            // The baselines are GPU methods measured against this renderer's truth; there is
            // no CPU copy of them to say what they should draw.
            return Err(format!(
                "quality.method = \"{}\" runs on the GPU backends (wgpu, wgpu-gl, ash); the CPU renders the volumetric model only",
                method.name()
            )
            .into());
        }
        let temporal = frame.scene.quality.temporal != stratus_scene::Temporal::Off;
        let pathtrace = frame.scene.quality.integrator == stratus_scene::Integrator::Pathtrace;
        stratus_graph::backend::check_scene_depth(frame, false)?;
        if !pathtrace {
            self.pathtrace = progressive::PathState::default();
        }
        let mut out = match &self.integrator {
            // The scene asks for the path tracer: the real-time renderer runs it progressively
            // (the reference's own Monte Carlo integrator renders a still in one go).
            Integrator::Quadrature(_) if pathtrace => {
                self.temporal = temporal::TemporalState::default();
                let paths = frame.plan.paths_per_frame().unwrap_or(1);
                progressive::render(
                    frame.scene,
                    frame.noise,
                    frame.cut,
                    paths,
                    &mut self.pathtrace,
                )
            }
            Integrator::Quadrature(settings) if temporal => {
                if frame.cut {
                    self.temporal = temporal::TemporalState::default();
                }
                temporal::render(
                    frame.scene,
                    frame.noise,
                    settings,
                    &mut self.temporal,
                    frame.scene_depth,
                )
            }
            _ => {
                // A frame without temporal upsampling leaves no usable history.
                self.temporal = temporal::TemporalState::default();
                render_with_scene_depth(
                    frame.scene,
                    frame.noise,
                    &self.integrator,
                    self.progress,
                    frame.scene_depth,
                )
            }
        };
        out.cpu_ms = t.elapsed().as_secs_f64() * 1e3;
        Ok(out)
    }
}
