//! Creating and destroying the renderer many times leaks nothing (the validation layer
//! reports live objects when the device is destroyed, and `finish` turns that into an error),
//! with and without frames rendered in between.

use stratus_backend_ash::{Options, Renderer};
use stratus_graph::{FrameInput, FramePlan};
use stratus_test_support::{small, small_noise};

#[test]
fn create_render_destroy_twenty_times() {
    let scene = small("cumulus-noon", 16, 9);
    let plan = FramePlan::for_scene(&scene, true).expect("plan");
    // Small noise: this test is about the life cycle, not the clouds.
    let noise = small_noise(scene.noise.seed);
    let mut reference = None;
    for i in 0..20 {
        let mut renderer = Renderer::new(Options { validation: true })
            .unwrap_or_else(|e| panic!("creation {i}: {e}"));
        if i % 4 == 0 {
            // Twice in a row in the same renderer: everything built for the plan is reused.
            for _ in 0..2 {
                let out = renderer
                    .render(&FrameInput::new(&plan, &scene, &noise))
                    .unwrap_or_else(|e| panic!("render {i}: {e}"));
                assert_eq!(out.stats.as_ref().map(|s| s["pixels"]), Some(16 * 9));
                let reference = reference.get_or_insert_with(|| out.clone());
                assert_eq!(out.radiance, reference.radiance, "renderer {i}");
                assert_eq!(out.image, reference.image, "renderer {i}");
            }
        }
        if i % 5 != 4 {
            renderer
                .finish()
                .unwrap_or_else(|e| panic!("teardown {i}: {e}"));
        } else {
            // Plain drop: the same teardown (it can only print what the layer says).
            drop(renderer);
        }
    }
}

#[test]
fn changing_size_and_variant_rebuilds_and_leaks_nothing() {
    let scene = small("cumulus-noon", 16, 9);
    let noise = small_noise(scene.noise.seed);
    let mut renderer = Renderer::new(Options { validation: true }).expect("renderer");
    let mut outputs = Vec::new();
    for (w, h, stats) in [
        (16, 9, false),
        (24, 12, false),
        (24, 12, true),
        (16, 9, false),
    ] {
        let scene = scene.clone().with_size(w, h);
        let plan = FramePlan::for_scene(&scene, stats).expect("plan");
        let out = renderer
            .render(&FrameInput::new(&plan, &scene, &noise))
            .expect("render");
        assert_eq!(out.radiance.len(), (w * h * 4) as usize);
        assert_eq!(out.stats.is_some(), stats);
        outputs.push(out);
    }
    // Back to the first plan: the same image as the first time.
    assert_eq!(outputs[0].image, outputs[3].image);
    renderer.finish().expect("clean teardown");
}

#[test]
fn switching_temporal_upsampling_on_and_off_rebuilds_and_leaks_nothing() {
    let scene = small("cumulus-noon", 16, 9);
    let noise = small_noise(scene.noise.seed);
    let mut renderer = Renderer::new(Options { validation: true }).expect("renderer");
    for (temporal, stats) in [
        (stratus_scene::Temporal::Off, false),
        (stratus_scene::Temporal::Sixteenth, false),
        (stratus_scene::Temporal::Sixteenth, true),
        (stratus_scene::Temporal::Off, true),
        (stratus_scene::Temporal::Quarter, false),
    ] {
        let mut scene = scene.clone();
        scene.quality.temporal = temporal;
        let plan = FramePlan::for_scene(&scene, stats).expect("plan");
        for _ in 0..2 {
            let out = renderer
                .render(&FrameInput::new(&plan, &scene, &noise))
                .unwrap_or_else(|e| panic!("{temporal:?}: {e}"));
            assert_eq!(out.radiance.len(), 16 * 9 * 4);
        }
    }
    renderer.finish().expect("teardown without leaks");
}
