//! `stratus soak`: many frames of one persistent renderer on a looping camera path, watching for
//! what long runs break: non-finite values, memory growth, GPU objects created after the first
//! frame, and drift (the frame after the camera stops against a fresh renderer's still).

use std::{io::IsTerminal as _, sync::Arc};

use anyhow::{Result, bail};
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use stratus_compare::{CompareOptions, Image, compare};
use stratus_graph::{FrameInput, FrameOutput, FramePlan, Readback};
use stratus_scene::{Scene, Temporal};

use stratus_tool::{
    backends::{Backend, Open, open},
    render::{frame_scene, parse_temporal},
    scene_io::{load_scene, parse_size},
};

/// Options of `stratus soak`.
#[derive(Args, Debug)]
pub struct SoakArgs {
    /// Frames in the loop.
    #[arg(long, default_value_t = 2000, value_parser = clap::value_parser!(u32).range(1..))]
    frames: u32,
    /// Image size.
    #[arg(long, default_value = "64x36", value_parser = parse_size)]
    size: (u32, u32),
    /// The renderer (not `reference`).
    #[arg(long, value_enum, default_value_t = Backend::Auto)]
    backend: Backend,
    /// A built-in preset.
    #[arg(long, default_value = "cumulus-noon")]
    preset: String,
    /// Temporal upsampling during the loop (the history is what long runs stress).
    #[arg(long, default_value = "1/4", value_parser = parse_temporal)]
    temporal: Temporal,
    /// Frames rendered at the final camera after the loop stops, and by a fresh renderer for
    /// the still it is compared with.
    #[arg(long, default_value_t = 32)]
    settle: u32,
    /// Instead of the loop: create a renderer, render one 16x9 frame and drop it, N times, and
    /// report the RSS growth (leaks of device, resources or pipelines show there).
    #[arg(long, value_name = "N")]
    cycles: Option<u32>,
    /// Validation on (wgpu's, and the Vulkan validation layer, whose object tracking reports
    /// every object still alive when a device is destroyed): any message fails the soak.
    /// `STRATUS_VALIDATION=1` does the same.
    #[arg(long)]
    validate: bool,
}

impl SoakArgs {
    fn validation(&self) -> bool {
        self.validate || stratus_tool::backends::validation()
    }

    /// A renderer of the soak's backend, with validation as `--validate` or the environment
    /// asks.
    fn renderer(&self) -> Result<Box<dyn stratus_graph::Backend>> {
        open(
            self.backend,
            &Open {
                validation: self.validation(),
                ..Open::default()
            },
        )
    }
}

/// Fails with what wgpu logged since the last check (the ash backend returns its layer's
/// messages as errors itself).
fn check_validation(what: &str) -> Result<()> {
    let messages = stratus_tool::validation::take();
    if messages.is_empty() {
        Ok(())
    } else {
        bail!("{what}: validation reported:\n{}", messages.join("\n"))
    }
}

/// One cycle: a renderer created, used for one frame and torn down with `finish`, which
/// returns what validation reported while destroying the device (objects left alive among
/// it). The frame's non-finite values, and whether the renderer was validated.
fn one_cycle(
    args: &SoakArgs,
    scene: &Scene,
    plan: &FramePlan,
    noise: &Arc<stratus_noise::NoiseSet>,
) -> Result<(usize, bool)> {
    let input = FrameInput::new(plan, scene, noise).with_readback(Readback::output());
    let mut r = args.renderer()?;
    let f = r.render(&input).map_err(|e| anyhow::anyhow!("{e}"))?;
    let validated = r.validated();
    r.finish()
        .map_err(|e| anyhow::anyhow!("tearing down: {e}"))?;
    Ok((non_finite(&f), validated))
}

/// `--cycles N`: renderers created and dropped, RSS after the first few and at the end.
fn cycles(args: &SoakArgs, n: u32) -> Result<()> {
    let (scene, name) = load_scene(Some(&args.preset), None, Some((16, 9)))?;
    let noise = Arc::new(stratus::noise_for(&scene));
    let plan = FramePlan::for_scene(&scene, false)?;
    // The allocator and the driver settle over the first cycles; measure from the tenth.
    let warm = n.min(10);
    let mut rss_warm = None;
    let mut nan = 0;
    let bar = (n > 1 && std::io::stderr().is_terminal()).then(|| {
        let bar = ProgressBar::new(u64::from(n));
        if let Ok(style) = ProgressStyle::with_template(
            "cycles [{elapsed_precise}] {wide_bar} {pos}/{len} ({per_sec})",
        ) {
            bar.set_style(style);
        }
        bar
    });
    let mut validated = true;
    for i in 0..n {
        let (bad, checked) = one_cycle(args, &scene, &plan, &noise)
            .map_err(|e| anyhow::anyhow!("cycle {i}: {e}"))?;
        nan += bad;
        validated &= checked;
        if args.validation() {
            check_validation(&format!("cycle {i}"))?;
        }
        if let Some(bar) = &bar {
            bar.inc(1);
        }
        if i + 1 == warm {
            rss_warm = rss();
        }
    }
    let rss_end = rss();
    let per = match (rss_warm, rss_end) {
        (Some(a), Some(b)) if n > warm => format!(
            " ({:+.1} KiB a cycle over the last {})",
            (b as f64 - a as f64) / 1024.0 / f64::from(n - warm),
            n - warm
        ),
        _ => String::new(),
    };
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    println!("cycles: {n} renderers created, used for one frame of {name} and dropped");
    println!("non-finite values: {nan}");
    println!(
        "{}",
        validation_line(args, validated, &format!("{n} device teardowns"))
    );
    println!(
        "RSS: {} after {warm} cycles, {} after {n}{per}",
        mib(rss_warm),
        mib(rss_end)
    );
    if nan > 0 {
        bail!("{nan} non-finite values");
    }
    Ok(())
}

/// The loop's camera: a circle of 2 km radius around the preset's position, once around every
/// 600 frames (10 s at 60 fps), looking along the path and slowly up and down.
fn looping(base: &Scene, i: u32) -> Scene {
    let mut s = frame_scene(base, i, 60.0);
    let turn = f64::from(i % 600) / 600.0 * std::f64::consts::TAU;
    let [x, y, z] = base.camera.position;
    s.camera.position = [x + 2000.0 * turn.sin(), y, z + 2000.0 * turn.cos()];
    s.camera.yaw_deg = base.camera.yaw_deg + turn.to_degrees() + 90.0;
    s.camera.pitch_deg = base.camera.pitch_deg + 4.0 * (3.0 * turn).sin();
    s
}

/// Resident set size of this process, bytes (Linux).
fn rss() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmRSS:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

fn mib(b: Option<u64>) -> String {
    b.map_or("unknown".into(), |b| {
        format!("{:.1} MiB", b as f64 / 1048576.0)
    })
}

/// Non-finite values in a frame's read-back radiance and depth.
fn non_finite(f: &FrameOutput) -> usize {
    f.radiance
        .iter()
        .chain(&f.depth)
        .filter(|v| !v.is_finite())
        .count()
}

/// Renders `frames` frames of a still camera at `scene` on `r` (starting over), returning the last.
fn settle(
    r: &mut dyn stratus_graph::Backend,
    plan: &FramePlan,
    scene: &Scene,
    noise: &Arc<stratus_noise::NoiseSet>,
    first: u32,
    frames: u32,
) -> Result<FrameOutput> {
    let mut last = None;
    for k in 0..frames.max(1) {
        let mut s = scene.clone();
        s.quality.frame = first.wrapping_add(k);
        let input = FrameInput::new(plan, &s, noise).with_readback(Readback::output());
        last = Some(r.render(&input).map_err(|e| anyhow::anyhow!("{e}"))?);
    }
    Ok(last.expect("at least one frame"))
}

/// What validation found, in a line: by here any message has failed the soak. `validated`:
/// whether the renderers had validation on (the CPU renderer has none).
fn validation_line(args: &SoakArgs, validated: bool, over: &str) -> String {
    if args.validation() && !validated {
        "validation: asked for, but the CPU renderer has no validation layer".into()
    } else if args.validation() {
        format!(
            "validation: on, no messages over {over} (the layer's object tracking reports any object alive at device destruction)"
        )
    } else {
        "validation: off (--validate turns on the Vulkan layer and its object tracking)".into()
    }
}

/// Runs `stratus soak`.
pub fn run(args: SoakArgs) -> Result<()> {
    if args.validation() {
        stratus_tool::validation::record();
    }
    if args.backend == Backend::Reference {
        bail!(
            "--backend reference renders stills only; soak a real-time renderer (cpu, wgpu, wgpu-gl, ash or auto)"
        );
    }
    if let Some(n) = args.cycles {
        return cycles(&args, n);
    }
    let (mut base, name) = load_scene(Some(&args.preset), None, Some(args.size))?;
    base.quality.temporal = args.temporal;
    base.validate().map_err(|e| anyhow::anyhow!("{e}"))?;
    let noise = Arc::new(stratus::noise_for(&base));
    let plan = FramePlan::for_scene(&base, false)?;
    let mut renderer = args.renderer()?;
    println!(
        "soak: {} frames of {name} at {}x{} (temporal {}) on {}",
        args.frames,
        args.size.0,
        args.size.1,
        args.temporal.name(),
        renderer.describe()
    );

    let bar = (std::io::stderr().is_terminal()).then(|| {
        let bar = ProgressBar::new(u64::from(args.frames));
        if let Ok(style) = ProgressStyle::with_template(
            "soak [{elapsed_precise}] {wide_bar} {pos}/{len} frames ({per_sec})",
        ) {
            bar.set_style(style);
        }
        bar
    });
    let mut nan = 0usize;
    let mut nan_frames = 0u32;
    let (mut rss_start, mut objects_start) = (None, 0);
    for i in 0..args.frames {
        let s = looping(&base, i);
        // The loop moves the camera only; a change to it that touched the plan's key would
        // render with a stale plan.
        anyhow::ensure!(
            plan.serves(&s),
            "frame {i}: the looping camera changed the scene's plan key"
        );
        let input = FrameInput::new(&plan, &s, &noise).with_readback(Readback::output());
        let f = renderer
            .render(&input)
            .map_err(|e| anyhow::anyhow!("frame {i}: {e}"))?;
        let bad = non_finite(&f);
        if bad > 0 {
            nan += bad;
            nan_frames += 1;
        }
        if i == 0 {
            // After the first frame: resources, pipelines and noise are in place.
            rss_start = rss();
            objects_start = renderer.objects_created();
        }
        if let Some(bar) = &bar {
            bar.inc(1);
        }
    }
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    let rss_end = rss();
    let objects_end = renderer.objects_created();

    // Drift: the camera stops where the loop ended; after `settle` frames there, against a
    // fresh renderer's `settle` frames of the same still camera.
    let stop = looping(&base, args.frames - 1);
    let stopped = settle(
        renderer.as_mut(),
        &plan,
        &stop,
        &noise,
        args.frames,
        args.settle,
    )?;
    let mut fresh = args.renderer()?;
    let still = settle(
        fresh.as_mut(),
        &plan,
        &stop,
        &noise,
        args.frames,
        args.settle,
    )?;
    let display = compare(
        &Image::from_frame_display(&still),
        &Image::from_frame_display(&stopped),
        &CompareOptions::default(),
    )?;
    let linear = compare(
        &Image::from_frame_radiance(&still),
        &Image::from_frame_radiance(&stopped),
        &CompareOptions {
            include_alpha: true,
            ..Default::default()
        },
    )?;

    println!(
        "non-finite values: {nan} (in {nan_frames} of {} frames)",
        args.frames
    );
    let growth = match (rss_start, rss_end) {
        (Some(a), Some(b)) => format!(" ({:+.1} MiB)", (b as f64 - a as f64) / 1048576.0),
        _ => String::new(),
    };
    println!(
        "RSS: {} after the first frame, {} at the end{growth}",
        mib(rss_start),
        mib(rss_end)
    );
    println!(
        "GPU objects created by the renderer: {objects_start} after the first frame, {objects_end} at the end (a steady loop creates none)"
    );
    println!(
        "drift: {} frames after the stop against a fresh renderer's still: FLIP mean {:.2e}, max abs {:.2e}",
        args.settle, display.flip.mean, linear.max_abs
    );
    // Both renderers torn down before the verdict: what outlives a device is reported then
    // (ash returns it from `finish`, wgpu logs it).
    let validated = renderer.validated() && fresh.validated();
    fresh
        .finish()
        .map_err(|e| anyhow::anyhow!("tearing down: {e}"))?;
    renderer
        .finish()
        .map_err(|e| anyhow::anyhow!("tearing down: {e}"))?;
    if args.validation() {
        check_validation("the loop")?;
    }
    println!(
        "{}",
        validation_line(&args, validated, &format!("{} frames", args.frames))
    );
    if nan > 0 {
        bail!("{nan} non-finite values in {nan_frames} frames");
    }
    if objects_end != objects_start {
        bail!(
            "the renderer created {} GPU objects during the loop",
            objects_end - objects_start
        );
    }
    Ok(())
}
