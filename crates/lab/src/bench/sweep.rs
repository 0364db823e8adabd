//! The measurement sweep: the configurations a scene is measured with (one axis at a time
//! around its own settings, plus cheap combinations), and measuring each one: its GPU time
//! (median of timed repeats after a warm-up), its work counters (statistics variant) and its
//! error against the cached CPU reference.

use std::{collections::BTreeMap, sync::Arc};

use anyhow::{Context, Result};
use indicatif::ProgressBar;
use stratus_compare::{CompareOptions, Image, compare};
use stratus_graph::{Backend, FrameInput, FrameOutput, FramePlan, output::median};
use stratus_noise::NoiseSet;
use stratus_quality::{Config, Row};
use stratus_reference::Compositor;
use stratus_scene::{
    Animation, Integration, Keyframe, Method, PhaseModel, Scene, ShapeTexture, Temporal,
};

use super::reference_cache::reference;
use stratus_tool::scene_io::check_finite;

/// The sweep for a scene whose own settings are `base`: one axis at a time around `base`,
/// plus cheap combinations.
pub(super) fn sweep(base: &Config, quick: bool) -> Vec<Config> {
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
    // The preset before the multiple-scattering fit.
    if base.octaves > 0 {
        push(Config {
            octaves: stratus_quality::PREFIT_OCTAVES.octaves,
            prefit: true,
            ..base.clone()
        });
    }
    // Methods: temporal upsampling and each cheap-march technique on its own (checkerboard
    // skipping needs temporal upsampling: with 1/16).
    for temporal in [Temporal::Quarter, Temporal::Sixteenth] {
        push(Config {
            temporal,
            ..base.clone()
        });
    }
    push(Config {
        dynamic_step: true,
        ..base.clone()
    });
    push(Config {
        empty_space_skip: true,
        ..base.clone()
    });
    push(Config {
        temporal: Temporal::Sixteenth,
        checkerboard: true,
        ..base.clone()
    });
    // The baselines against the same truth: the basic tutorial marcher at the scene's steps,
    // and Wang 2003's sprites.
    for method in [Method::Basic, Method::Sprites] {
        push(Config {
            method,
            ..base.clone()
        });
    }
    out
}

/// One scene of the bench: its name, the scene at the bench's image size, the configurations
/// it is measured with, and its own (preset) configuration.
pub(super) struct SceneSweep {
    /// The preset name (or `stress-thick`).
    pub name: String,
    /// The scene at the bench's size.
    pub scene: Scene,
    /// The configurations to measure.
    pub configs: Vec<Config>,
    /// The scene's own settings.
    pub base: Config,
}

/// How each configuration is measured.
#[derive(Clone, Copy, Debug)]
pub(super) struct MeasureSettings {
    /// Timed repeats (median reported), after one warm-up frame.
    pub repeats: u32,
    /// Samples per pixel of the Monte Carlo references.
    pub mc_spp: u32,
    /// Only render (or load) the references: measure nothing, return no rows.
    pub references_only: bool,
}

/// Makes a renderer of the bench's backend; `true`: one that times every pass by submitting
/// it alone and waiting for it (`cpu-wall`) instead of by timestamps.
pub(super) type RendererFactory<'a> = &'a dyn Fn(bool) -> Result<Box<dyn Backend>>;

/// Measures every configuration of every scene on `renderer`, in order, advancing `bar` by
/// one per configuration. Each scene's rows get `time_vs_preset`; the Pareto front is left to
/// the caller.
pub(super) fn measure(
    renderer: &mut dyn Backend,
    fresh: RendererFactory<'_>,
    scenes: &[SceneSweep],
    settings: MeasureSettings,
    bar: &ProgressBar,
) -> Result<Vec<Row>> {
    // One noise set per seed and shape texture, shared by every frame that reads it (the
    // renderer uploads noise only when a different one arrives).
    let mut noises: BTreeMap<(u64, bool), Arc<NoiseSet>> = BTreeMap::new();
    let mut rows = Vec::new();
    for SceneSweep {
        name,
        scene,
        configs,
        base,
    } in scenes
    {
        let mut scene_rows: Vec<Row> = Vec::new();
        for config in configs {
            bar.set_message(format!("{name}: {}", config.name()));
            let s = config.apply(scene);
            s.validate().map_err(|e| anyhow::anyhow!("{e}"))?;
            let hzd = s.noise.shape_texture == ShapeTexture::Hzd;
            let noise = noises
                .entry((s.noise.seed, hzd))
                .or_insert_with(|| Arc::new(stratus::noise_for(&s)));
            if settings.references_only {
                reference(&s, noise, settings.mc_spp, Some(&mut *renderer))?;
                bar.inc(1);
                continue;
            }
            // A plan that rasterises every frame (the sprite baseline) on a renderer of its
            // own that times each pass submitted alone, dropped after
            // (`FramePlan::rasterizes_every_frame`): measured on lavapipe, a 64x36 march read
            // 0.012 ms after a sprite frame against 10 ms before, on wgpu and on ash, and the
            // sprite sort read 0.013 ms in one run and 20.9 ms in the next.
            let mut own = if FramePlan::for_scene(&s, false)?.rasterizes_every_frame() {
                Some(fresh(true)?)
            } else {
                None
            };
            let r: &mut dyn Backend = match own.as_mut() {
                Some(b) => b.as_mut(),
                None => &mut *renderer,
            };
            scene_rows.push(measure_config(
                r,
                name,
                &s,
                config,
                config == base,
                noise,
                settings,
            )?);
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
    Ok(rows)
}

/// Measures one configuration: `s` is the scene with `config` applied, `preset` whether
/// `config` is the scene's own.
fn measure_config(
    renderer: &mut dyn Backend,
    name: &str,
    s: &Scene,
    config: &Config,
    preset: bool,
    noise: &Arc<NoiseSet>,
    settings: MeasureSettings,
) -> Result<Row> {
    let super::Reference {
        frame: reference,
        label,
        ..
    } = reference(s, noise, settings.mc_spp, Some(&mut *renderer))?;
    if config.is_method() {
        return measure_method(renderer, name, s, config, preset, noise, reference, label);
    }
    let plan = FramePlan::for_scene(s, false)?;
    let mut frame = None;
    let mut totals = Vec::new();
    let mut passes: BTreeMap<String, Vec<f64>> = BTreeMap::new();
    // One warm-up render (resources, pipeline compilation), then the timed repeats.
    let input = FrameInput::new(&plan, s, noise);
    renderer
        .render(&input)
        .map_err(|e| anyhow::anyhow!("{e}"))?;
    for _ in 0..settings.repeats {
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
    let stats_plan = FramePlan::for_scene(s, true)?;
    let counted = renderer
        .render(&FrameInput::new(&stats_plan, s, noise))
        .map_err(|e| anyhow::anyhow!("{e}"))?;
    let mut row = row(
        name,
        config,
        preset,
        &reference,
        &frame,
        &Compositor::new(s, noise),
        counted.stats,
        label,
    )?;
    row.gpu_ms = median(totals);
    row.passes = passes.into_iter().map(|(k, v)| (k, median(v))).collect();
    row.timing = frame.timings.first().map_or("", |t| t.source).to_string();
    Ok(row)
}

/// The error of a frame against its reference.
pub(crate) struct Errors {
    /// FLIP (mean) of the composited, tone-mapped images.
    pub flip: f64,
    /// Its 95th percentile.
    pub flip_p95: f64,
    /// RMSE of the linear radiance (rgb).
    pub rmse: f64,
}

/// `frame` against `reference`: FLIP on display images, RMSE on the linear radiance. Both
/// display images are composited by `display` (the CPU's composite of the scene) from their
/// radiance, through the air in front of `frame`'s depth: the reference may come from another
/// device (a GPU's truth from the cache, the CPU reference), whose own composite rounds to 8
/// bits differently, and its depth (the path tracer's first collision, not cached) is not the
/// march's (transmittance-weighted); what is measured is the clouds' light and transmittance.
/// Where `frame` saw no cloud but the reference has some, the view ray's entry into the layer
/// stands for the reference's depth ([`Compositor::display`]).
pub(crate) fn errors(
    reference: &FrameOutput,
    frame: &FrameOutput,
    display: &Compositor,
) -> Result<Errors> {
    let linear = compare(
        &Image::from_frame_radiance(reference),
        &Image::from_frame_radiance(frame),
        &compare_options(),
    )?;
    let reference = composite(reference, frame, display)?;
    Ok(Errors {
        rmse: linear.rmse,
        ..display_errors(&reference, frame, display)?
    })
}

/// FLIP of `frame`'s display image (composited by `display` through its own depth, as
/// [`errors`] does) against `reference`, a display image composited the same way (the fit's
/// panels keep its truths' so); RMSE, which needs the reference's radiance, is NaN.
pub(crate) fn display_errors(
    reference: &Image,
    frame: &FrameOutput,
    display: &Compositor,
) -> Result<Errors> {
    let d = compare(
        reference,
        &composite(frame, frame, display)?,
        &compare_options(),
    )?;
    Ok(Errors {
        flip: d.flip.mean,
        flip_p95: d.flip.p95,
        rmse: f64::NAN,
    })
}

/// The errors' comparison: linear values at exposure 1.
fn compare_options() -> CompareOptions {
    CompareOptions {
        exposure: 1.0,
        ..CompareOptions::default()
    }
}

/// The display image of `f`'s radiance, composited by `display` through the air in front of
/// `frame`'s depth.
fn composite(f: &FrameOutput, frame: &FrameOutput, display: &Compositor) -> Result<Image> {
    let image = display
        .display(&f.radiance, &frame.depth)
        .with_context(|| {
            let [w, h] = display.size();
            format!(
                "composite for a {w}x{h} frame: got {} radiance floats and {} depths \
                 (a {}x{} frame); want {} and {}",
                f.radiance.len(),
                frame.depth.len(),
                f.width,
                f.height,
                4 * w * h,
                w * h
            )
        })?;
    Ok(Image::from_display_rgba8(f.width, f.height, &image))
}

/// A row's counters and errors: `frame` against `reference` (times left at 0).
#[allow(clippy::too_many_arguments)]
fn row(
    name: &str,
    config: &Config,
    preset: bool,
    reference: &FrameOutput,
    frame: &FrameOutput,
    display: &Compositor,
    stats: Option<BTreeMap<String, u64>>,
    label: String,
) -> Result<Row> {
    let c = stats.unwrap_or_default();
    // Per output pixel (the `pixels` counter counts marched pixels: with temporal upsampling
    // a fraction of them).
    let pixels = f64::from(frame.width * frame.height).max(1.0);
    let per = |k: &str| c.get(k).copied().unwrap_or(0) as f64 / pixels;

    let e = errors(reference, frame, display)?;
    Ok(Row {
        scene: name.to_string(),
        name: config.name(),
        preset,
        config: config.clone(),
        gpu_ms: 0.0,
        passes: BTreeMap::new(),
        timing: String::new(),
        time_vs_preset: 0.0,
        view_steps_pp: per("view_steps"),
        light_samples_pp: per("light_samples"),
        samples_pp: per("density_evaluations"),
        rmse: e.rmse,
        flip: e.flip,
        flip_p95: e.flip_p95,
        reference: label,
        pareto: false,
        motion_flip: None,
        motion_flip_worst: None,
    })
}

/// Frames a still camera renders before a method's image is compared with the reference:
/// every pixel of a 1/16 block marched four times.
const STILL_FRAMES: u32 = 64;

/// Measures a method (temporal upsampling, a cheap-march technique): the cost is the median
/// frame of a moving-camera sequence ([`moving_camera`]), its motion error
/// the FLIP of every frame against the full march of the same frame; its still error is
/// against the reference after [`STILL_FRAMES`] frames of a still camera, as for the others.
#[allow(clippy::too_many_arguments)]
fn measure_method(
    renderer: &mut dyn Backend,
    name: &str,
    s: &Scene,
    config: &Config,
    preset: bool,
    noise: &Arc<NoiseSet>,
    reference: FrameOutput,
    label: String,
) -> Result<Row> {
    let render = |r: &mut dyn Backend, scene: &Scene, cut: bool| -> Result<FrameOutput> {
        let plan = FramePlan::for_scene(scene, false)?;
        let mut input = FrameInput::new(&plan, scene, noise);
        if cut {
            input = input.with_cut();
        }
        let f = r.render(&input).map_err(|e| anyhow::anyhow!("{e}"))?;
        check_finite(&f)?;
        Ok(f)
    };
    let moving = moving_camera(s);
    let frame_at = |i: u32| {
        let mut f = moving.at_time(f64::from(i) / 30.0);
        f.quality.frame = i;
        f
    };
    // The full march of every frame first (one plan at a time keeps the method's history).
    let mut full = Vec::new();
    for i in 0..MOVING_FRAMES {
        let mut f = frame_at(i);
        f.quality.temporal = Temporal::Off;
        f.quality.dynamic_step = false;
        f.quality.checkerboard = false;
        f.quality.empty_space_skip = false;
        full.push(render(renderer, &f, i == 0)?);
    }
    let options = CompareOptions {
        exposure: 1.0,
        ..CompareOptions::default()
    };
    let mut flips = Vec::new();
    let mut totals = Vec::new();
    let mut passes: BTreeMap<String, Vec<f64>> = BTreeMap::new();
    for (i, want) in full.iter().enumerate() {
        let f = render(renderer, &frame_at(i as u32), i == 0)?;
        if i > 0 {
            // The first frame of a temporal sequence marches everything.
            totals.push(f.timings.iter().map(|t| t.ms).sum());
            for t in &f.timings {
                passes.entry(t.pass.clone()).or_default().push(t.ms);
            }
        }
        let d = compare(
            &Image::from_frame_display(want),
            &Image::from_frame_display(&f),
            &options,
        )?;
        flips.push(d.flip.mean);
    }
    // The still image, converged.
    let mut still = s.clone();
    let mut frame = None;
    for i in 0..STILL_FRAMES {
        still.quality.frame = s.quality.frame.wrapping_add(i);
        frame = Some(render(renderer, &still, i == 0)?);
    }
    let frame = frame.expect("frames");
    let stats_plan = FramePlan::for_scene(&still, true)?;
    let counted = renderer
        .render(&FrameInput::new(&stats_plan, &still, noise))
        .map_err(|e| anyhow::anyhow!("{e}"))?;
    let mut row = row(
        name,
        config,
        preset,
        &reference,
        &frame,
        &Compositor::new(s, noise),
        counted.stats,
        label,
    )?;
    row.gpu_ms = median(totals);
    row.passes = passes.into_iter().map(|(k, v)| (k, median(v))).collect();
    row.timing = frame.timings.first().map_or("", |t| t.source).to_string();
    row.motion_flip = Some(flips.iter().sum::<f64>() / flips.len() as f64);
    row.motion_flip_worst = Some(flips.iter().copied().fold(0.0, f64::max));
    Ok(row)
}

/// Frames of the bench's moving-camera sequence.
pub(super) const MOVING_FRAMES: u32 = 48;

/// `scene` with a camera move for measuring methods in motion: over [`MOVING_FRAMES`] frames
/// at 30 per second, a pan of 0.5 degrees a frame while the camera climbs 2 m and moves 4 m
/// forward a frame. Frame `i` is `at_time(i / 30)`.
pub(super) fn moving_camera(scene: &Scene) -> Scene {
    let mut s = scene.clone();
    let c = &scene.camera;
    let n = f64::from(MOVING_FRAMES);
    let (sy, cy) = c.yaw_deg.to_radians().sin_cos();
    s.animation = Some(Animation {
        duration_s: n / 30.0,
        keyframes: vec![
            Keyframe {
                time_s: 0.0,
                position: c.position,
                yaw_deg: c.yaw_deg,
                pitch_deg: c.pitch_deg,
            },
            Keyframe {
                time_s: n / 30.0,
                position: [
                    c.position[0] + 4.0 * n * sy,
                    c.position[1] + 2.0 * n,
                    c.position[2] + 4.0 * n * cy,
                ],
                yaw_deg: c.yaw_deg + 0.5 * n,
                pitch_deg: c.pitch_deg,
            },
        ],
    });
    s
}
