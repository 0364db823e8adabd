//! The ash backend (committed SPIR-V) and the wgpu backend (wgpu's own translation of the
//! WGSL) draw the same frame bit for bit on the same device, for every preset, with and
//! without the statistics variant (so the counters are compared too), plus an unshadowed
//! scene so that every committed `.spv` runs. Both run with validation; any validation
//! message fails the test.

mod common;

use std::{collections::BTreeSet, sync::Mutex};

use stratus_backend_ash as ash_backend;
use stratus_backend_wgpu as wgpu_backend;
use stratus_scene::Scene;
use stratus_shaders::{FrameOutput, FramePlan};

/// Records every warning or error wgpu logs (the Vulkan validation layer's messages about
/// wgpu's calls arrive this way), so the wgpu side is held to the same standard.
struct Recorder(Mutex<Vec<String>>);

impl log::Log for Recorder {
    fn enabled(&self, m: &log::Metadata) -> bool {
        m.level() <= log::Level::Warn && m.target().starts_with("wgpu")
    }
    fn log(&self, r: &log::Record) {
        if self.enabled(r.metadata()) {
            if let Ok(mut v) = self.0.lock() {
                v.push(format!("{} {}: {}", r.level(), r.target(), r.args()));
            }
        }
    }
    fn flush(&self) {}
}

static RECORDER: Recorder = Recorder(Mutex::new(Vec::new()));

fn first_difference(name: &str, what: &str, a: &[f32], b: &[f32]) -> Option<String> {
    let differing = a
        .iter()
        .zip(b)
        .filter(|(x, y)| x.to_bits() != y.to_bits())
        .count();
    if differing == 0 && a.len() == b.len() {
        return None;
    }
    let max = a
        .iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0f32, f32::max);
    Some(format!(
        "{name}: {what}: {differing} of {} floats differ, max abs difference {max:e}",
        a.len()
    ))
}

fn compare(name: &str, a: &FrameOutput, w: &FrameOutput) -> Vec<String> {
    let mut problems = Vec::new();
    problems.extend(first_difference(name, "radiance", &a.radiance, &w.radiance));
    problems.extend(first_difference(name, "depth", &a.depth, &w.depth));
    if a.image != w.image {
        let n = a.image.iter().zip(&w.image).filter(|(x, y)| x != y).count();
        problems.push(format!("{name}: image: {n} bytes differ"));
    }
    if a.stats != w.stats {
        problems.push(format!(
            "{name}: counters differ: ash {:?}, wgpu {:?}",
            a.stats, w.stats
        ));
    }
    problems
}

#[test]
fn ash_and_wgpu_are_bit_identical_on_every_preset() {
    log::set_logger(&RECORDER).expect("the only logger in this test binary");
    log::set_max_level(log::LevelFilter::Warn);
    let mut ash = ash_backend::Renderer::new(ash_backend::Options { validation: true })
        .expect("ash renderer");
    let mut wgpu = wgpu_backend::Renderer::new(wgpu_backend::Options {
        api: wgpu_backend::Api::Vulkan,
        validation: true,
    })
    .expect("wgpu renderer");
    assert_eq!(ash.adapter(), wgpu.adapter(), "both backends on one device");
    let mut noise = common::NoiseCache::default();
    let mut scenes: Vec<(String, Scene)> = stratus_scene::presets()
        .iter()
        .map(|p| (p.name.to_string(), common::small(p.name, 64, 36)))
        .collect();
    // No preset is unshadowed; this one picks the `unshadowed` variants.
    let mut flat = common::small("cumulus-noon", 64, 36);
    flat.quality.light_steps = 0;
    flat.lighting.multiple_scattering.octaves = 0;
    flat.clouds.detail_strength = 0.0;
    scenes.push(("cumulus-noon, unshadowed".into(), flat));

    let mut problems = Vec::new();
    let mut variants = BTreeSet::new();
    for (name, scene) in &scenes {
        let uniforms = scene.uniforms();
        let noise = noise.get(scene);
        for stats in [true, false] {
            let plan = FramePlan::for_scene(scene, stats).expect("plan");
            let a = ash.render(&plan, &uniforms, noise).expect("ash render");
            let w = wgpu.render(&plan, &uniforms, noise).expect("wgpu render");
            assert_eq!(a.radiance.len(), 64 * 36 * 4);
            assert_eq!(a.stats.is_some(), stats);
            if let Some(s) = &a.stats {
                assert_eq!(s["pixels"], 64 * 36, "{name}: {s:?}");
            }
            assert!(
                a.radiance.iter().any(|&v| v > 0.0) && a.image.iter().any(|&v| v > 0),
                "{name}: an empty frame proves nothing"
            );
            assert_eq!(a.timings.len(), plan.passes.len());
            assert_eq!(a.device, w.device);
            problems.extend(compare(&format!("{name} ({})", plan.variant), &a, &w));
            variants.insert(plan.spv_file.clone());
        }
    }
    ash.finish().expect("ash teardown");
    drop(wgpu);
    let logged = std::mem::take(&mut *RECORDER.0.lock().expect("log"));
    assert!(logged.is_empty(), "wgpu logged:\n{}", logged.join("\n"));
    assert_eq!(
        variants.len(),
        6,
        "every committed SPIR-V ran: {variants:?}"
    );
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}
