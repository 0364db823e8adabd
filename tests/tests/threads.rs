//! Two renderers on two threads give the same bits as one renderer alone, on each backend
//! (each thread owns its renderer and device; the noise is shared). Validation is on.

use std::sync::Arc;

use stratus_graph::{Backend, FrameInput, FrameOutput, FramePlan};
use stratus_noise::{NoiseConfig, NoiseSet};
use stratus_scene::Scene;

fn scene() -> Scene {
    Scene::preset("cumulus-noon")
        .expect("preset")
        .with_size(64, 36)
}

/// Three frames of a moving sun on `r`; the last one.
fn frames(r: &mut dyn Backend, noise: &Arc<NoiseSet>) -> FrameOutput {
    let base = scene();
    let plan = FramePlan::for_scene(&base, false).expect("plan");
    let mut last = None;
    for i in 0..3 {
        let mut s = base.clone();
        s.sun.elevation_deg += f64::from(i) * 5.0;
        s.quality.frame = i;
        last = Some(
            r.render(&FrameInput::new(&plan, &s, noise))
                .expect("render"),
        );
    }
    last.expect("frames")
}

fn wgpu() -> Box<dyn Backend> {
    Box::new(
        stratus_backend_wgpu::Renderer::new(stratus_backend_wgpu::Options {
            api: stratus_backend_wgpu::Api::Vulkan,
            validation: true,
        })
        .expect("a Vulkan device (lavapipe)"),
    )
}

fn ash() -> Box<dyn Backend> {
    Box::new(
        stratus_backend_ash::Renderer::new(stratus_backend_ash::Options { validation: true })
            .expect("ash on lavapipe"),
    )
}

#[test]
fn two_renderers_on_two_threads_match_one_alone() {
    stratus_test_support::record_wgpu_log();
    let noise = Arc::new(NoiseSet::generate(&NoiseConfig::default()));
    for (name, make) in [("wgpu", wgpu as fn() -> Box<dyn Backend>), ("ash", ash)] {
        let alone = frames(make().as_mut(), &noise);
        let results: Vec<FrameOutput> = std::thread::scope(|s| {
            let handles: Vec<_> = (0..2)
                .map(|_| {
                    let noise = noise.clone();
                    s.spawn(move || frames(make().as_mut(), &noise))
                })
                .collect();
            handles
                .into_iter()
                .map(|h| h.join().expect("thread"))
                .collect()
        });
        for (i, f) in results.iter().enumerate() {
            let d =
                stratus_test_support::frame_differences(&format!("{name} thread {i}"), &alone, f);
            assert!(d.is_empty(), "{d:?}");
        }
    }
    let log = stratus_test_support::take_wgpu_log();
    assert!(log.is_empty(), "wgpu validation: {log:?}");
}
