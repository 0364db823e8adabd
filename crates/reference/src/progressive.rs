//! The path tracer as a real-time renderer runs it (`quality.integrator = "pathtrace"`): every
//! frame adds the plan's paths per frame to each pixel (streams seeded by the pixel, the sample
//! and `quality.frame`) to running means kept between frames, as `wgsl/pathtrace.wgsl` does
//! in its history. A cut, a new size or a moved camera starts over.

use std::time::Instant;

use stratus_graph::{FrameOutput, PassTiming};
use stratus_noise::NoiseSet;
use stratus_scene::{FrameUniforms, Scene};

use crate::medium::Model;
use crate::{Integrator, Medium, composite, render_model};

/// What the CPU renderer keeps between path-traced frames.
#[derive(Clone, Debug, Default)]
pub struct PathState {
    /// Paths per pixel so far, the uniform block they were traced with, and their mean
    /// radiance and transmittance (f32, as the GPU's rgba32float history).
    history: Option<(u32, FrameUniforms, Vec<f32>)>,
}

/// Whether two uniform blocks have the same camera and size (the GPU's `camera_still`).
fn same_view(a: &FrameUniforms, b: &FrameUniforms) -> bool {
    a.camera_position == b.camera_position
        && a.tan_half_fov == b.tan_half_fov
        && a.camera_forward == b.camera_forward
        && a.aspect == b.aspect
        && a.camera_right == b.camera_right
        && a.camera_up == b.camera_up
        && a.size == b.size
}

/// One frame of the progressive path tracer: `paths` more paths per pixel.
pub(crate) fn render(
    scene: &Scene,
    noise: &NoiseSet,
    cut: bool,
    paths: u32,
    state: &mut PathState,
) -> FrameOutput {
    let paths = paths.max(1);
    let q = &scene.quality;
    let u = scene.uniforms();
    // The frame and its physical sky's tables, once for the paths and the composite.
    let model = Model::new(scene, Medium::Clouds(noise));
    let t = Instant::now();
    let mut out = render_model(
        &model,
        &Integrator::MonteCarlo {
            spp: paths,
            orders: q.path_orders,
        },
        false,
    )
    .output;
    // This frame's paths (their mean) join the running mean with their count's weight.
    let (n, mean) = match state.history.take() {
        Some((n, last, mut mean)) if !cut && same_view(&last, &u) => {
            let w = paths as f32 / (n + paths) as f32;
            for (m, x) in mean.iter_mut().zip(&out.radiance) {
                *m += (x - *m) * w;
            }
            (n + paths, mean)
        }
        _ => (paths, out.radiance.clone()),
    };
    out.radiance.clone_from(&mean);
    state.history = Some((n, u, mean));
    let march_ms = t.elapsed().as_secs_f64() * 1e3;

    let t1 = Instant::now();
    out.image = composite::composite_image(
        &model.f,
        model.sky(),
        out.width,
        out.height,
        &out.radiance,
        &out.depth,
        None,
        crate::precipitation::Rain::of(&model).as_ref(),
    );
    out.timings = crate::sky::in_graph_order(
        model.sky(),
        [PassTiming {
            pass: "pathtrace".into(),
            ms: march_ms,
            source: "cpu-wall",
        }],
        PassTiming {
            pass: "composite".into(),
            ms: t1.elapsed().as_secs_f64() * 1e3,
            source: "cpu-wall",
        },
    );
    out.image = crate::post::stylise(
        &model.f,
        out.width,
        out.height,
        std::mem::take(&mut out.image),
        &mut out.timings,
    );
    crate::particles::particles_pass(
        &model.f,
        crate::precipitation::Rain::of(&model).as_ref(),
        &mut out.image,
        &mut out.timings,
    );
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{RenderOptions, render_medium};
    use stratus_graph::{Backend, FrameInput, FramePlan};

    /// One frame's paths, as the reference's Monte Carlo integrator renders them in one go.
    fn single(scene: &Scene, noise: &NoiseSet, paths: u32) -> Vec<f32> {
        render_medium(
            scene,
            Medium::Clouds(noise),
            &Integrator::MonteCarlo {
                spp: paths,
                orders: 0,
            },
            &RenderOptions {
                progress: false,
                threads: None,
            },
        )
        .output
        .radiance
    }

    /// Frames join the running mean of their frames' paths; a moved camera or a cut starts
    /// over.
    #[test]
    fn frames_accumulate_until_the_camera_moves() {
        let noise = crate::small_noise();
        let mut scene = Scene::default().with_size(8, 4);
        scene.camera.pitch_deg = 20.0;
        scene.quality.integrator = stratus_scene::Integrator::Pathtrace;
        let plan = FramePlan::for_scene(&scene, false).unwrap();
        let paths = plan.paths_per_frame().expect("a path-traced plan");
        let mut cpu = crate::CpuBackend::default();
        let frame = |i: u32, s: &Scene| {
            let mut s = s.clone();
            s.quality.frame = i;
            s
        };
        let mut last = Vec::new();
        for i in 0..3 {
            let s = frame(i, &scene);
            last = cpu
                .render(&FrameInput::new(&plan, &s, &noise))
                .unwrap()
                .radiance;
        }
        let singles: Vec<Vec<f32>> = (0..3)
            .map(|i| single(&frame(i, &scene), &noise, paths))
            .collect();
        assert!(singles[0] != singles[1], "frames draw different paths");
        for (k, v) in last.iter().enumerate() {
            let mean = (singles[0][k] + singles[1][k] + singles[2][k]) / 3.0;
            assert!(
                (v - mean).abs() <= 1e-5 * mean.abs().max(1.0),
                "{k}: {v} vs {mean}"
            );
        }

        let mut moved = frame(3, &scene);
        moved.camera.yaw_deg += 1.0;
        let out = cpu.render(&FrameInput::new(&plan, &moved, &noise)).unwrap();
        assert_eq!(out.radiance, single(&moved, &noise, paths));
        let cut = frame(4, &moved);
        let out = cpu
            .render(&FrameInput::new(&plan, &cut, &noise).with_cut())
            .unwrap();
        assert_eq!(out.radiance, single(&cut, &noise, paths));
    }
}
