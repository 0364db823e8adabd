//! Measures the convergence of the quadrature: renders a preset with view and light steps
//! doubled at each level (equal light steps to the layer boundary, no jitter, no early exit)
//! and prints how much each doubling changes the image.
//!
//! `cargo run --release -p stratus-reference --example converge -- [preset] [WxH] [levels]
//! [both|view|light] [first view steps] [first light steps]` (defaults: cumulus-noon, 64x36,
//! 5 levels from 128 view x 8 light steps, both doubled).
//!
//! Columns: `mean change` = |mean L(2N) - mean L(N)| / mean L(2N) over the image's linear
//! radiance (r, g, b); `mean abs change` = mean |L(2N) - L(N)| / mean L(2N); `max change` =
//! max |L(2N) - L(N)| / max L(2N) over pixels and channels; `max dT` = largest change of a
//! pixel's transmittance.

use anyhow::{Context, Result};
use stratus_graph::FrameOutput;
use stratus_noise::{NoiseConfig, NoiseSet, ShapeSize};
use stratus_reference::{Integrator, QuadratureSettings, render};
use stratus_scene::{Scene, ShapeTexture};

fn main() -> Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let preset = args.first().map_or("cumulus-noon", String::as_str);
    let size = args.get(1).map_or("64x36", String::as_str);
    let levels: u32 = args.get(2).map_or(Ok(5), |s| s.parse())?;
    // Which steps double: `both` (default), `view` or `light`.
    let which = args.get(3).map_or("both", String::as_str);
    // The first level's view and light steps.
    let view0: u32 = args.get(4).map_or(Ok(128), |s| s.parse())?;
    let light0: u32 = args.get(5).map_or(Ok(8), |s| s.parse())?;
    let (w, h) = size.split_once('x').context("size must be WxH")?;
    let scene = if preset.ends_with(".toml") {
        Scene::from_file(preset)
    } else {
        Scene::preset(preset)
    }
    .map_err(|e| anyhow::anyhow!("{e}"))?
    .with_size(w.parse()?, h.parse()?);
    let noise = NoiseSet::generate(&NoiseConfig {
        seed: scene.noise.seed,
        shape: match scene.noise.shape_texture {
            ShapeTexture::Thesis => ShapeSize::Thesis,
            ShapeTexture::Hzd => ShapeSize::Hzd,
        },
        ..NoiseConfig::default()
    });
    let mut previous: Option<(u32, u32, FrameOutput)> = None;
    println!(
        "{:>6} {:>6} {:>12} {:>12} {:>16} {:>12} {:>10} {:>9}",
        "view", "light", "mean L", "mean change", "mean abs change", "max change", "max dT", "ms"
    );
    for level in 0..levels {
        let (view, light) = match which {
            "view" => (view0 << level, light0),
            "light" => (view0, light0 << level),
            _ => (view0 << level, light0 << level),
        };
        let settings = QuadratureSettings {
            view_steps: Some(view),
            light_steps: Some(light),
            ..QuadratureSettings::converged()
        };
        let frame = render(&scene, &noise, &Integrator::Quadrature(settings), false);
        let ms: f64 = frame.timings.iter().map(|t| t.ms).sum();
        let rgb = |f: &FrameOutput| -> Vec<f64> {
            f.radiance
                .chunks_exact(4)
                .flat_map(|p| [p[0], p[1], p[2]])
                .map(f64::from)
                .collect()
        };
        let cur = rgb(&frame);
        let mean = cur.iter().sum::<f64>() / cur.len() as f64;
        if let Some((pv, pl, prev)) = &previous {
            let old = rgb(prev);
            let old_mean = old.iter().sum::<f64>() / old.len() as f64;
            let max = cur.iter().copied().fold(0.0, f64::max);
            let mean_abs = cur
                .iter()
                .zip(&old)
                .map(|(a, b)| (a - b).abs())
                .sum::<f64>()
                / cur.len() as f64;
            let max_change = cur
                .iter()
                .zip(&old)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            let max_dt = frame
                .radiance
                .chunks_exact(4)
                .zip(prev.radiance.chunks_exact(4))
                .map(|(a, b)| (a[3] - b[3]).abs())
                .fold(0.0, f32::max);
            println!(
                "{view:>6} {light:>6} {mean:>12.6} {:>11.4}% {:>15.4}% {:>11.4}% {max_dt:>10.2e} {ms:>9.0}   (vs {pv}x{pl})",
                (mean - old_mean).abs() / mean * 100.0,
                mean_abs / mean * 100.0,
                max_change / max * 100.0,
            );
        } else {
            println!(
                "{view:>6} {light:>6} {mean:>12.6} {:>12} {:>16} {:>12} {:>10} {ms:>9.0}",
                "", "", "", ""
            );
        }
        previous = Some((view, light, frame));
    }
    Ok(())
}
