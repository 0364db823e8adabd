//! Checks that the GPU timestamps give each pass its own cost: renders cumulus-noon at
//! 256x144 with timestamps, then with every pass submitted alone and timed on the CPU (the
//! reference), and the same frame with backend-wgpu, and prints the median of each pass.
//!
//! `cargo run --release -p stratus-backend-ash --example timestamps [repeats]`

use std::sync::Arc;

use stratus_backend_ash::{Options, Renderer};
use stratus_graph::{FrameInput, FrameOutput, FramePlan, Readback, output::median};
use stratus_noise::{NoiseConfig, NoiseSet};
use stratus_scene::Scene;

fn summary(label: &str, runs: &[FrameOutput]) {
    let passes: Vec<String> = runs[0]
        .timings
        .iter()
        .enumerate()
        .map(|(i, t)| {
            let ms = median(runs.iter().map(|r| r.timings[i].ms).collect());
            format!("{} {ms:8.3} ms", t.pass)
        })
        .collect();
    println!(
        "{label:<32} {}  ({})",
        passes.join("  "),
        runs[0].timings[0].source
    );
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let repeats: usize = std::env::args().nth(1).map_or(Ok(7), |a| a.parse())?;
    let scene = Scene::preset("cumulus-noon")?.with_size(256, 144);
    let plan = FramePlan::for_scene(&scene, false)?;
    let noise = Arc::new(NoiseSet::generate(&NoiseConfig {
        seed: scene.noise.seed,
        ..Default::default()
    }));
    let frame = FrameInput::new(&plan, &scene, &noise).with_readback(Readback::none());
    let mut ash = Renderer::new(Options { validation: false })?;
    let mut wgpu = stratus_backend_wgpu::Renderer::new(stratus_backend_wgpu::Options {
        api: stratus_backend_wgpu::Api::Vulkan,
        validation: false,
    })?;
    println!(
        "{}, {}x{}, variant {}, median of {repeats}",
        ash.adapter(),
        plan.width,
        plan.height,
        plan.variant
    );
    // Warm up (pipeline compilation).
    ash.render(&frame)?;
    wgpu.render(&frame)?;
    let run = |ash: &mut Renderer| {
        (0..repeats)
            .map(|_| ash.render(&frame))
            .collect::<Result<Vec<_>, _>>()
    };
    summary("ash, timestamps", &run(&mut ash)?);
    ash.set_cpu_wall_timing(true);
    summary("ash, each pass submitted alone", &run(&mut ash)?);
    let runs = (0..repeats)
        .map(|_| wgpu.render(&frame))
        .collect::<Result<Vec<_>, _>>()?;
    summary("wgpu, timestamps", &runs);
    ash.finish()?;
    Ok(())
}
