//! A moving-camera sequence with temporal upsampling on every executing path: each path's
//! renderer carries its history from frame to frame, as an application's does. ash-spv must
//! match wgpu-vulkan bit for bit on every frame; the other paths stay within bounds set from
//! measurement. The sequence also measures what temporal upsampling costs in accuracy: every
//! frame against wgpu-vulkan's full march of the same frame.

use std::sync::Arc;

use stratus_graph::FrameOutput;
use stratus_noise::NoiseSet;
use stratus_scene::{Animation, Keyframe, Scene, Temporal};

use crate::{
    paths::{Path, Renderers},
    report::{self, DeviceClass, Metrics, Thresholds},
    sanity,
    scenes::{HEIGHT, WIDTH},
};

/// Frames of the sequence.
pub const FRAMES: u32 = 32;
/// Frames per second of scene time.
const FPS: f64 = 30.0;

/// `cumulus-noon` with temporal upsampling at 1/16, the camera climbing, moving forward and
/// turning (about 0.4 degrees of yaw and 3 m of travel per frame).
pub fn scene() -> Scene {
    let mut scene = Scene::preset("cumulus-noon")
        .expect("preset")
        .with_size(WIDTH, HEIGHT);
    scene.quality.temporal = Temporal::Sixteenth;
    // The weather map's cumulus, on which the bounds below were measured: on the preset's
    // convective cells wgpu-gl's history drifted up to 8.6e-2 (max abs) from wgpu-vulkan's,
    // over these bounds, and has not been measured on another device (the still scene
    // `stress-convective-cells` holds every path on cells).
    scene.clouds.convective_cells = 0.0;
    let c = &scene.camera;
    scene.animation = Some(Animation {
        duration_s: f64::from(FRAMES) / FPS,
        keyframes: vec![
            Keyframe {
                time_s: 0.0,
                position: c.position,
                yaw_deg: c.yaw_deg,
                pitch_deg: c.pitch_deg,
            },
            Keyframe {
                time_s: f64::from(FRAMES) / FPS,
                position: [40.0, c.position[1] + 60.0, 80.0],
                yaw_deg: c.yaw_deg + 12.0,
                pitch_deg: c.pitch_deg + 2.0,
            },
        ],
    });
    stratus_scene::Scene::from_toml_str(&scene.to_toml(), "sequence").expect("a valid scene")
}

/// Frame `i`: the camera on its path, the wind on, the jitter sequence `i` steps on.
pub fn frame(scene: &Scene, i: u32) -> Scene {
    let mut s = scene.at_time(f64::from(i) / FPS);
    s.quality.frame = i;
    s
}

/// What the sequence measured.
pub struct SequenceResult {
    /// Per path: its frames' metrics against wgpu-vulkan's (frame by frame), or why none.
    pub paths: Vec<(Path, Result<Vec<Metrics>, String>)>,
    /// Per path, every problem.
    pub problems: Vec<(Path, Vec<String>)>,
    /// wgpu-vulkan's temporal frames against its full march of each frame.
    pub temporal_vs_full: Vec<Metrics>,
}

/// The sequence's bounds against wgpu-vulkan per path, measured on this sequence: the history
/// carries each frame's rounding (or, on the CPU, f64) differences on to the next frames, so
/// they exceed the still scenes'.
fn bounds(path: Path, class: DeviceClass) -> Option<Thresholds> {
    match (path, class) {
        (Path::Cpu, _) => Some(CPU_SEQUENCE),
        (Path::WgpuGl, _) | (Path::AshGlsl | Path::AshHlsl, DeviceClass::Other) => {
            Some(GPU_SEQUENCE)
        }
        // ash-glsl and ash-hlsl on the golden device: 0 in every frame (bit-identical to
        // wgpu-vulkan), held to the still scenes' glslang bounds there.
        (Path::AshGlsl | Path::AshHlsl, DeviceClass::Golden) => Some(report::GLSLANG_GOLDEN),
        _ => None,
    }
}

/// A second compiler's rounding, carried by the history: wgpu-gl measured on lavapipe (worst
/// of the 32 frames) FLIP mean 8.29e-5, p99 2.17e-3, max abs 1.23e-2, RMSE 1.16e-4; set at
/// about twice that. glslang's paths on another device class are held to it too (not yet
/// measured on one: no GPU has run the sequence since these bounds).
const GPU_SEQUENCE: Thresholds = Thresholds {
    flip_mean: 2e-4,
    flip_p99: 4e-3,
    max_abs: 2.5e-2,
    rmse: 2.5e-4,
    outliers: f64::INFINITY,
};

/// The CPU renderer's temporal frames against wgpu-vulkan's, set at about twice what was
/// measured on lavapipe (worst of the 32 frames): FLIP mean 4.08e-3, p99 2.55e-2, max abs
/// 1.80 (one cloud-edge pixel whose march differs, carried on by the history; 1.13 before the
/// fitted octaves brightened the clouds), RMSE 1.73e-2.
const CPU_SEQUENCE: Thresholds = Thresholds {
    flip_mean: 1e-2,
    flip_p99: 5e-2,
    max_abs: 3.5,
    rmse: 2.5e-2,
    outliers: f64::INFINITY,
};

/// Temporal (1/16) against the full march of the same frame, worst frame's FLIP mean: 4.62e-2
/// measured on lavapipe (the last frame 3.89e-2; the first, marched in full, 0); set at
/// about 1.5 times that. It holds the algorithm to what it does now: a change that ghosts
/// or smears more fails.
pub const TEMPORAL_VS_FULL_FLIP_MEAN: f64 = 0.07;

fn render_path(
    r: &mut Renderers,
    path: Path,
    scene: &Scene,
    noise: &Arc<NoiseSet>,
) -> Result<Vec<FrameOutput>, String> {
    (0..FRAMES)
        .map(|i| {
            r.render_frame(path, &frame(scene, i), noise, false, i == 0, &[])
                .map(|done| done.frame)
                .map_err(|e| format!("frame {i}: {e}"))
        })
        .collect()
}

/// Runs the sequence on every executing path.
pub fn execute(r: &mut Renderers, noise: &Arc<NoiseSet>) -> SequenceResult {
    let scene = scene();
    let mut problems = Vec::new();
    let mut paths = Vec::new();
    let reference = render_path(r, Path::WgpuVulkan, &scene, noise);
    let mut temporal_vs_full = Vec::new();
    let mut own = Vec::new();
    match &reference {
        Ok(frames) => {
            for (i, f) in frames.iter().enumerate() {
                own.extend(sanity(f).into_iter().map(|p| format!("frame {i}: {p}")));
                let mut full = frame(&scene, i as u32);
                full.quality.temporal = Temporal::Off;
                match r.render(Path::WgpuVulkan, &full, noise, false) {
                    Ok(done) => match Metrics::between(&done.frame, f) {
                        Ok(m) => temporal_vs_full.push(m),
                        Err(e) => own.push(e),
                    },
                    Err(e) => own.push(format!("full march of frame {i}: {e}")),
                }
            }
            if let Some(worst) = temporal_vs_full
                .iter()
                .map(|m| m.flip_mean)
                .reduce(f64::max)
                && !crate::report::within(worst, TEMPORAL_VS_FULL_FLIP_MEAN)
            {
                own.push(format!(
                    "temporal against the full march of the same frame: worst FLIP mean {worst:.4} exceeds {TEMPORAL_VS_FULL_FLIP_MEAN}"
                ));
            }
        }
        Err(e) => own.push(e.clone()),
    }
    problems.push((Path::WgpuVulkan, own));
    for path in [
        Path::AshSpv,
        Path::WgpuGl,
        Path::AshGlsl,
        Path::AshHlsl,
        Path::Cpu,
    ] {
        let mut own = Vec::new();
        if r.unsupported(path).is_some() {
            continue;
        }
        let frames = render_path(r, path, &scene, noise);
        let metrics = match (&frames, &reference) {
            (Ok(frames), Ok(reference)) => {
                let mut list = Vec::new();
                for (i, (f, w)) in frames.iter().zip(reference).enumerate() {
                    own.extend(sanity(f).into_iter().map(|p| format!("frame {i}: {p}")));
                    if path == Path::AshSpv {
                        own.extend(stratus_test_support::frame_differences(
                            &format!("frame {i}: ash-spv against wgpu-vulkan"),
                            f,
                            w,
                        ));
                    }
                    match Metrics::between(w, f) {
                        Ok(m) => {
                            if let Some(t) = bounds(path, r.class) {
                                own.extend(
                                    t.check(&m).into_iter().map(|p| format!("frame {i}: {p}")),
                                );
                            }
                            list.push(m);
                        }
                        Err(e) => own.push(format!("frame {i}: {e}")),
                    }
                }
                Ok(list)
            }
            (Err(e), _) => {
                own.push(e.clone());
                Err(e.clone())
            }
            (_, Err(_)) => Err("no wgpu-vulkan sequence".to_string()),
        };
        paths.push((path, metrics));
        problems.push((path, own));
    }
    SequenceResult {
        paths,
        problems,
        temporal_vs_full,
    }
}

/// The sequence's summary for the console and conformance.md: per path the worst frame.
pub fn summary(s: &SequenceResult) -> String {
    let mut out = format!(
        "\nsequence: {FRAMES} frames of a moving camera with temporal upsampling 1/16 at {WIDTH}x{HEIGHT}, each path against wgpu-vulkan frame by frame (worst frame)\n\n"
    );
    let worst = |list: &[Metrics]| {
        let f = |g: fn(&Metrics) -> f64| list.iter().map(g).fold(0.0, f64::max);
        format!(
            "FLIP mean {:.2e}, p99 {:.2e}, max abs {:.2e}, RMSE {:.2e}",
            f(|m| m.flip_mean),
            f(|m| m.flip_p99),
            f(|m| m.max_abs),
            f(|m| m.rmse)
        )
    };
    for (path, m) in &s.paths {
        let line = match m {
            Ok(list) => worst(list),
            Err(e) => format!("not run: {e}"),
        };
        out.push_str(&format!("- {}: {line}\n", path.label()));
    }
    out.push_str(&format!(
        "- temporal 1/16 against the full march of the same frame (wgpu-vulkan): {}; first frame {:.4}, last {:.4}\n",
        worst(&s.temporal_vs_full),
        s.temporal_vs_full.first().map_or(f64::NAN, |m| m.flip_mean),
        s.temporal_vs_full.last().map_or(f64::NAN, |m| m.flip_mean),
    ));
    out
}
