//! Creating and destroying the renderer many times leaks nothing (the validation layer
//! reports live objects when the device is destroyed, and `finish` turns that into an error),
//! with and without frames rendered in between.

mod common;

use stratus_backend_ash::{Options, Renderer};
use stratus_shaders::FramePlan;

#[test]
fn create_render_destroy_twenty_times() {
    let scene = common::small("cumulus-noon", 16, 9);
    let plan = FramePlan::for_scene(&scene, true).expect("plan");
    let uniforms = scene.uniforms();
    // Small noise: this test is about the life cycle, not the clouds.
    let noise = stratus_noise::NoiseSet::generate(&stratus_noise::NoiseConfig {
        seed: scene.noise.seed,
        shape: stratus_noise::ShapeSize::Thesis,
        weather_size: 64,
        curl_size: 16,
        detail_size: 8,
    });
    let mut reference = None;
    for i in 0..20 {
        let mut renderer = Renderer::new(Options { validation: true })
            .unwrap_or_else(|e| panic!("creation {i}: {e}"));
        if i % 4 == 0 {
            // Twice in a row in the same renderer: the cached pipelines are reused.
            for _ in 0..2 {
                let out = renderer
                    .render(&plan, &uniforms, &noise)
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
