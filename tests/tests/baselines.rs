//! The baselines (`quality.method = "basic" | "sprites"`) on both GPU backends with validation
//! on: ash (the committed SPIR-V) draws the same bits as wgpu, with the same work counters; the
//! sprites' order is a permutation drawn back to front; the images hold cloud and sky; and the
//! basic marcher, without ambient or multiple scattering, is darker than the model's march of
//! the same density. Any validation message fails the test.

use std::sync::Arc;

use stratus_graph::{Backend, FrameInput, FrameOutput, FramePlan, Readback};
use stratus_noise::{NoiseConfig, NoiseSet};
use stratus_scene::{Method, Scene};

const WIDTH: u32 = 128;
const HEIGHT: u32 = 72;

fn scene(method: Method) -> Scene {
    let mut s = Scene::preset("cumulus-noon")
        .expect("preset")
        .with_size(WIDTH, HEIGHT);
    s.quality.method = method;
    s.validate().expect("a valid scene");
    s
}

/// One frame (and its statistics-variant counters), reading back `resources` too.
fn render(
    r: &mut dyn Backend,
    scene: &Scene,
    noise: &Arc<NoiseSet>,
    resources: &[&str],
) -> FrameOutput {
    let plan = FramePlan::for_scene(scene, false).expect("plan");
    let readback = Readback {
        output: true,
        resources: resources.iter().map(|s| s.to_string()).collect(),
    };
    let mut out = r
        .render(&FrameInput::new(&plan, scene, noise).with_readback(readback))
        .expect("render");
    let stats_plan = FramePlan::for_scene(scene, true).expect("stats plan");
    out.stats = r
        .render(&FrameInput::new(&stats_plan, scene, noise))
        .expect("stats render")
        .stats;
    out
}

fn floats(bytes: &[u8]) -> Vec<f32> {
    bytes
        .chunks(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect()
}

/// Transmittance (alpha) of every pixel.
fn transmittance(f: &FrameOutput) -> Vec<f32> {
    f.radiance.chunks(4).map(|p| p[3]).collect()
}

fn mean_luma(f: &FrameOutput) -> f64 {
    let n = f.radiance.len() / 4;
    f.radiance
        .chunks(4)
        .map(|p| 0.2126 * f64::from(p[0]) + 0.7152 * f64::from(p[1]) + 0.0722 * f64::from(p[2]))
        .sum::<f64>()
        / n as f64
}

/// Holds cloud and clear sky, every value finite, transmittance a fraction.
fn assert_cloud_and_sky(name: &str, f: &FrameOutput) {
    assert!(
        f.radiance.iter().all(|v| v.is_finite()),
        "{name}: a value is not finite"
    );
    let t = transmittance(f);
    assert!(
        t.iter().all(|t| (0.0..=1.0).contains(t)),
        "{name}: transmittance outside [0, 1]"
    );
    let cloud = t.iter().filter(|t| **t < 0.5).count();
    let clear = t.iter().filter(|t| **t > 0.99).count();
    assert!(
        cloud > t.len() / 20 && clear > t.len() / 20,
        "{name}: {cloud} cloudy and {clear} clear pixels of {}",
        t.len()
    );
}

#[test]
fn baselines_draw_the_same_bits_on_ash_and_wgpu() {
    stratus_test_support::record_wgpu_log();
    let noise = Arc::new(NoiseSet::generate(&NoiseConfig::default()));
    let mut wgpu = stratus_backend_wgpu::Renderer::new(stratus_backend_wgpu::Options {
        api: stratus_backend_wgpu::Api::Vulkan,
        validation: true,
    })
    .expect("a Vulkan device (lavapipe)");
    let mut ash =
        stratus_backend_ash::Renderer::new(stratus_backend_ash::Options { validation: true })
            .expect("ash on lavapipe");

    let sprites = scene(Method::Sprites);
    let extra = ["sprites", "sprite-order"];
    let w = render(&mut wgpu, &sprites, &noise, &extra);
    let a = render(&mut ash, &sprites, &noise, &extra);
    let again = render(&mut wgpu, &sprites, &noise, &extra);
    let differences = stratus_test_support::frame_differences("sprites", &w, &a);
    assert!(differences.is_empty(), "ash against wgpu: {differences:?}");
    let repeat = stratus_test_support::frame_differences("sprites again", &w, &again);
    assert!(repeat.is_empty(), "not deterministic: {repeat:?}");
    assert_cloud_and_sky("sprites", &w);

    // The order is a permutation of the slots, and the drawn sprites (alpha > 0) come back to
    // front: their distances from the camera never increase.
    let data = floats(&w.resources["sprites"]);
    let order: Vec<usize> = floats(&w.resources["sprite-order"])
        .iter()
        .map(|v| *v as usize)
        .collect();
    let count = order.len();
    let mut seen = vec![false; count];
    for &slot in &order {
        assert!(
            slot < count && !seen[slot],
            "slot {slot} twice or out of range"
        );
        seen[slot] = true;
    }
    let texel =
        |row: usize, slot: usize| &data[4 * (row * count + slot)..4 * (row * count + slot) + 4];
    let rp = sprites.atmosphere.planet_radius_m;
    let [cx, cy, cz] = sprites.camera.position;
    let distance = |slot: usize| {
        // As the WGSL: the sprite's camera-relative position on the curved planet.
        let p = texel(0, slot);
        let (dx, dz, alt) = (f64::from(p[0]) - cx, f64::from(p[2]) - cz, f64::from(p[1]));
        let k = alt * (alt + 2.0 * rp) - dx * dx - dz * dz;
        let y = k / (rp + (rp * rp + k).sqrt());
        (dx * dx + (y - cy).powi(2) + dz * dz).sqrt()
    };
    let drawn: Vec<usize> = order
        .iter()
        .copied()
        .filter(|&s| texel(1, s)[3] > 0.0)
        .collect();
    assert!(
        drawn.len() > 100,
        "only {} of {count} sprites drawn",
        drawn.len()
    );
    for pair in drawn.windows(2) {
        let (d0, d1) = (distance(pair[0]), distance(pair[1]));
        // The keys quantise distance to 2^-20 of 131 km (0.125 m), computed in f32.
        assert!(
            d1 <= d0 + 1.0,
            "sprite {} ({d1:.1} m) drawn after the nearer {} ({d0:.1} m)",
            pair[1],
            pair[0]
        );
    }

    let basic = scene(Method::Basic);
    let w = render(&mut wgpu, &basic, &noise, &[]);
    let a = render(&mut ash, &basic, &noise, &[]);
    let differences = stratus_test_support::frame_differences("basic", &w, &a);
    assert!(differences.is_empty(), "ash against wgpu: {differences:?}");
    assert_cloud_and_sky("basic", &w);
    let stats = w.stats.as_ref().expect("counters");
    assert!(
        stats["light_samples"] > 0 && stats["view_steps"] > 0,
        "{stats:?}"
    );
    // No ambient and no multiple scattering: darker than the model's march.
    let model = render(&mut wgpu, &scene(Method::Volumetric), &noise, &[]);
    assert!(
        mean_luma(&w) < mean_luma(&model),
        "basic {} against the model's {}",
        mean_luma(&w),
        mean_luma(&model)
    );

    let log = stratus_test_support::take_wgpu_log();
    assert!(log.is_empty(), "wgpu validation: {log:?}");
    ash.finish().expect("ash: no validation messages");
}
