//! The CPU reference's quadrature with the real-time settings against the GPU (wgpu on Vulkan)
//! for the same scene: max abs and RMSE of linear radiance, FLIP of the displayed images, the
//! work counters side by side.
//!
//! `cargo run --release -p stratus-reference --example vs_gpu -- [preset|scene.toml] [WxH] [out-dir]`
//! (defaults: cumulus-noon, 256x144, no files). With an output directory it writes the two
//! images and the FLIP heat map there.

use std::path::PathBuf;

use anyhow::{Context, Result};
use stratus_backend_wgpu::{Api, Options, Renderer};
use stratus_compare::{CompareOptions, Image, compare, write_heatmap};
use stratus_graph::{FrameInput, FramePlan};
use stratus_noise::{NoiseConfig, NoiseSet, ShapeSize};
use stratus_reference::{Integrator, QuadratureSettings, render};
use stratus_scene::{Scene, ShapeTexture};

fn main() -> Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let preset = args.first().map_or("cumulus-noon", String::as_str);
    let size = args.get(1).map_or("256x144", String::as_str);
    let out_dir = args.get(2).map(PathBuf::from);
    let (w, h) = size.split_once('x').context("size must be WxH")?;
    let scene = if preset.ends_with(".toml") {
        Scene::from_file(preset)
    } else {
        Scene::preset(preset)
    }
    .map_err(|e| anyhow::anyhow!("{e}"))?
    .with_size(w.parse()?, h.parse()?);
    let noise = std::sync::Arc::new(NoiseSet::generate(&NoiseConfig {
        seed: scene.noise.seed,
        shape: match scene.noise.shape_texture {
            ShapeTexture::Thesis => ShapeSize::Thesis,
            ShapeTexture::Hzd => ShapeSize::Hzd,
        },
        ..NoiseConfig::default()
    }));

    let mut gpu = Renderer::new(Options {
        api: Api::Vulkan,
        validation: false,
    })?;
    let plan = FramePlan::for_scene(&scene, false)?;
    let gpu_frame = gpu.render(&FrameInput::new(&plan, &scene, &noise))?;
    let counting = FramePlan::for_scene(&scene, true)?;
    let gpu_stats = gpu
        .render(&FrameInput::new(&counting, &scene, &noise))?
        .stats
        .unwrap_or_default();
    let cpu_frame = render(
        &scene,
        &noise,
        &Integrator::Quadrature(QuadratureSettings::realtime()),
        false,
    );

    println!(
        "scene {preset} {size}: GPU = {}, CPU = {}",
        gpu_frame.device, cpu_frame.device
    );
    let linear = compare(
        &Image::from_frame_radiance(&cpu_frame),
        &Image::from_frame_radiance(&gpu_frame),
        &CompareOptions::default(),
    )?;
    let with_t = compare(
        &Image::from_frame_radiance(&cpu_frame),
        &Image::from_frame_radiance(&gpu_frame),
        &CompareOptions {
            include_alpha: true,
            ..CompareOptions::default()
        },
    )?;
    let display = compare(
        &Image::from_frame_display(&cpu_frame),
        &Image::from_frame_display(&gpu_frame),
        &CompareOptions::default(),
    )?;
    let max_radiance = cpu_frame
        .radiance
        .chunks_exact(4)
        .flat_map(|p| [p[0], p[1], p[2]])
        .fold(0f32, f32::max);
    println!(
        "linear radiance: max abs {:.3e} (largest radiance {max_radiance:.3}), RMSE {:.3e}, worst pixel ({}, {}) channel {}: cpu {:?} gpu {:?}",
        linear.max_abs,
        linear.rmse,
        linear.worst.x,
        linear.worst.y,
        linear.worst.channel,
        linear.worst.reference,
        linear.worst.test
    );
    println!(
        "transmittance included: max abs {:.3e}, RMSE {:.3e}",
        with_t.max_abs, with_t.rmse
    );
    println!(
        "display image: max abs {:.4} ({} / 255), RMSE {:.3e}, FLIP mean {:.5}, p50 {:.5}, p95 {:.5}, p99 {:.5}, max {:.5}",
        display.max_abs,
        (display.max_abs * 255.0).round(),
        display.rmse,
        display.flip.mean,
        display.flip.p50,
        display.flip.p95,
        display.flip.p99,
        display.flip.max
    );
    let differing = cpu_frame
        .image
        .iter()
        .zip(&gpu_frame.image)
        .filter(|(a, b)| a != b)
        .count();
    println!(
        "display bytes differing: {differing} of {}",
        cpu_frame.image.len()
    );
    let depth_max = cpu_frame
        .depth
        .iter()
        .zip(&gpu_frame.depth)
        .map(|(a, b)| (a - b).abs())
        .fold(0f32, f32::max);
    println!("depth: max abs difference {depth_max:.3} m");
    println!(
        "{:<22} {:>12} {:>12} {:>10}",
        "counter", "cpu", "gpu", "diff %"
    );
    if let Some(cpu_stats) = &cpu_frame.stats {
        for (name, cpu) in cpu_stats {
            let gpu = gpu_stats.get(name).copied().unwrap_or(0);
            let rel = if gpu > 0 {
                (*cpu as f64 - gpu as f64) / gpu as f64 * 100.0
            } else {
                0.0
            };
            println!("{name:<22} {cpu:>12} {gpu:>12} {rel:>10.4}");
        }
    }
    for t in cpu_frame.timings.iter().chain(&gpu_frame.timings) {
        println!("time {}: {:.2} ms ({})", t.pass, t.ms, t.source);
    }

    if let Some(dir) = out_dir {
        std::fs::create_dir_all(&dir)?;
        let save = |name: &str, frame: &stratus_graph::FrameOutput| -> Result<()> {
            Image::from_frame_display(frame).save(&dir.join(name))?;
            Ok(())
        };
        save("cpu.png", &cpu_frame)?;
        save("gpu.png", &gpu_frame)?;
        write_heatmap(
            &dir.join("flip.png"),
            display.width,
            display.height,
            &display.flip_map,
        )?;
        println!("wrote cpu.png, gpu.png, flip.png to {}", dir.display());
    }
    Ok(())
}
