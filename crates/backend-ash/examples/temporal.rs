//! What temporal upsampling buys and costs, measured on one device in one run (the numbers of
//! the temporal issue's closing note). Every mode has its own persistent renderer (its own
//! history), and the renderers take turns frame by frame, so all see the same machine load.
//!
//! 1. Cost: GPU ms per frame (sum of the passes, median) of full / 1/4 / 1/16 marching, on a
//!    still camera and on a moving one, and the ratio to the full march.
//! 2. Accuracy in motion: each frame's mean FLIP against the full march of the same frame.
//! 3. Ghosting: the worst frame's FLIP in a fast pan (3 degrees a frame).
//! 4. Convergence: after the camera stops, the frames until the image is within FLIP 0.01 of
//!    the same mode's converged still (and that FLIP on the first frame after the stop).
//! 5. Stability (with `--soak N`): N frames of a looping path read back and checked for
//!    non-finite values.
//!
//! `cargo run --release -p stratus-backend-ash --example temporal [WxH] [--soak N]`
//! (default 128x72, no soak).

use std::sync::Arc;

use stratus_backend_ash::{Options, Renderer};
use stratus_compare::{CompareOptions, Image, compare};
use stratus_graph::{FrameInput, FrameOutput, FramePlan, Readback, output::median};
use stratus_noise::{NoiseConfig, NoiseSet};
use stratus_scene::{Animation, Keyframe, Scene, Temporal};

const MODES: [Temporal; 3] = [Temporal::Off, Temporal::Quarter, Temporal::Sixteenth];

type Result<T> = std::result::Result<T, Box<dyn std::error::Error>>;

fn flip(a: &FrameOutput, b: &FrameOutput) -> Result<f64> {
    let o = CompareOptions {
        exposure: 1.0,
        ..CompareOptions::default()
    };
    Ok(compare(
        &Image::from_frame_display(a),
        &Image::from_frame_display(b),
        &o,
    )?
    .flip
    .mean)
}

fn gpu_ms(out: &FrameOutput) -> f64 {
    out.timings.iter().map(|t| t.ms).sum()
}

/// A camera path: from `scene`'s camera, `yaw` degrees and `forward` metres per frame, for
/// `frames` frames at 30 per second; still afterwards.
fn path(scene: &Scene, frames: u32, yaw: f64, forward: f64) -> Scene {
    let mut s = scene.clone();
    let c = &scene.camera;
    let n = f64::from(frames);
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
                    c.position[0] + forward * n * sy,
                    c.position[1],
                    c.position[2] + forward * n * cy,
                ],
                yaw_deg: c.yaw_deg + yaw * n,
                pitch_deg: c.pitch_deg,
            },
        ],
    });
    s
}

struct Mode {
    temporal: Temporal,
    renderer: Renderer,
}

impl Mode {
    /// Renders frame `i` of `scene`'s animation (no wind, so a still camera sees a still
    /// sky); `cut` starts the history over.
    fn frame(
        &mut self,
        scene: &Scene,
        noise: &Arc<NoiseSet>,
        i: u32,
        cut: bool,
    ) -> Result<FrameOutput> {
        let mut s = scene.at_time(f64::from(i) / 30.0);
        s.clouds.time_s = scene.clouds.time_s;
        s.quality.frame = i;
        s.quality.temporal = self.temporal;
        let plan = FramePlan::for_scene(&s, false)?;
        let mut input = FrameInput::new(&plan, &s, noise).with_readback(Readback::output());
        if cut {
            input = input.with_cut();
        }
        Ok(self.renderer.render(&input)?)
    }
}

fn main() -> Result<()> {
    let mut args = std::env::args().skip(1);
    let mut size = (128, 72);
    let mut soak = 0u32;
    while let Some(a) = args.next() {
        if a == "--soak" {
            soak = args.next().ok_or("--soak N")?.parse()?;
        } else {
            let (w, h) = a.split_once('x').ok_or("size must be WxH")?;
            size = (w.parse()?, h.parse()?);
        }
    }
    let base = Scene::preset("cumulus-noon")?.with_size(size.0, size.1);
    let noise = Arc::new(NoiseSet::generate(&NoiseConfig {
        seed: base.noise.seed,
        ..Default::default()
    }));
    let mut modes: Vec<Mode> = MODES
        .iter()
        .map(|&temporal| {
            Ok(Mode {
                temporal,
                renderer: Renderer::new(Options { validation: false })?,
            })
        })
        .collect::<Result<_>>()?;
    println!(
        "cumulus-noon {}x{} on {}",
        size.0,
        size.1,
        modes[0].renderer.adapter()
    );

    // 1-2. Still (64 frames) and moving (64 frames: 0.5 degrees and 4 m a frame), interleaved.
    println!(
        "\n| sequence | mode | GPU ms/frame (median) | vs full | mean FLIP vs full march of the frame | worst |"
    );
    println!("|---|---|---|---|---|---|");
    for (label, scene) in [
        ("still", base.clone()),
        ("moving", path(&base, 64, 0.5, 4.0)),
        ("fast pan (3 deg/frame)", path(&base, 32, 3.0, 0.0)),
    ] {
        let frames = if label.starts_with("fast") { 32 } else { 64 };
        let mut ms: Vec<Vec<f64>> = vec![Vec::new(); MODES.len()];
        let mut per_pass: Vec<std::collections::BTreeMap<String, Vec<f64>>> =
            vec![Default::default(); MODES.len()];
        let mut flips: Vec<Vec<f64>> = vec![Vec::new(); MODES.len()];
        for i in 0..frames {
            let outs: Vec<FrameOutput> = modes
                .iter_mut()
                .map(|m| m.frame(&scene, &noise, i, i == 0))
                .collect::<Result<_>>()?;
            for (k, out) in outs.iter().enumerate() {
                if i > 0 {
                    ms[k].push(gpu_ms(out));
                    for t in &out.timings {
                        per_pass[k].entry(t.pass.clone()).or_default().push(t.ms);
                    }
                }
                flips[k].push(flip(&outs[0], out)?);
            }
        }
        let full = median(ms[0].clone());
        for (k, m) in MODES.iter().enumerate() {
            let t = median(ms[k].clone());
            let f = &flips[k];
            let passes: Vec<String> = per_pass[k]
                .iter()
                .map(|(p, v)| format!("{p} {:.2}", median(v.clone())))
                .collect();
            println!(
                "| {label} | {} | {t:.3} ({}) | {:.3} | {:.4} | {:.4} |",
                m.name(),
                passes.join(", "),
                t / full,
                f.iter().sum::<f64>() / f.len() as f64,
                f.iter().copied().fold(0.0, f64::max)
            );
        }
    }

    // 4. Convergence after a stop: 32 moving frames, then still; against the mode's own
    // converged still (64 still frames from a cut at the stopping point).
    println!(
        "\n| mode | FLIP vs converged still, first frame after the stop | frames until <= 0.01 |"
    );
    println!("|---|---|---|");
    let moving = path(&base, 32, 0.5, 4.0);
    for m in modes.iter_mut().skip(1) {
        let stop = moving.at_time(32.0 / 30.0);
        let mut still_scene = stop.clone();
        still_scene.animation = None;
        still_scene.clouds.time_s = base.clouds.time_s;
        let mut converged = None;
        for i in 0..64 {
            converged = Some(m.frame(&still_scene, &noise, 32 + i, i == 0)?);
        }
        let converged = converged.ok_or("frames")?;
        for i in 0..32 {
            m.frame(&moving, &noise, i, i == 0)?;
        }
        let mut first = None;
        let mut until = None;
        for j in 0..128 {
            let out = m.frame(&moving, &noise, 32 + j, false)?;
            let f = flip(&converged, &out)?;
            first.get_or_insert(f);
            if f <= 0.01 {
                until = Some(j + 1);
                break;
            }
        }
        println!(
            "| {} | {:.4} | {} |",
            m.temporal.name(),
            first.unwrap_or(f64::NAN),
            until.map_or("more than 128".to_string(), |n| n.to_string())
        );
    }

    // 5. Soak: a looping path (out and back) for N frames at 1/16, every frame checked.
    if soak > 0 {
        let there = path(&base, 60, 1.0, 10.0);
        let m = &mut modes[2];
        let mut bad = 0u64;
        for i in 0..soak {
            let k = i % 120;
            let t = if k < 60 { k } else { 120 - k };
            let out = m.frame(&there, &noise, t, i == 0)?;
            bad += out.radiance.iter().filter(|v| !v.is_finite()).count() as u64;
        }
        println!("\nsoak: {soak} frames of a looping path at 1/16: {bad} non-finite values");
    }
    Ok(())
}
