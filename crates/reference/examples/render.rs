//! Renders a preset with the CPU reference and writes a PNG (and prints counters and timings).
//!
//! `cargo run --release -p stratus-reference --example render -- [preset] [WxH] [integrator] [out.png]`
//! where integrator is `realtime`, `converged` or `mc:SPP:ORDERS`.

use anyhow::{Context, Result, bail};
use stratus_noise::{NoiseConfig, NoiseSet, ShapeSize};
use stratus_reference::{Integrator, QuadratureSettings, render};
use stratus_scene::{Scene, ShapeTexture};

fn main() -> Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let preset = args.first().map_or("cumulus-noon", String::as_str);
    let size = args.get(1).map_or("256x144", String::as_str);
    let integrator = args.get(2).map_or("realtime", String::as_str);
    let out = args.get(3).map_or("reference.png", String::as_str);
    let (w, h) = size.split_once('x').context("size must be WxH")?;
    let scene = Scene::preset(preset)
        .map_err(|e| anyhow::anyhow!("{e}"))?
        .with_size(w.parse()?, h.parse()?);
    let integrator = match integrator {
        "realtime" => Integrator::Quadrature(QuadratureSettings::realtime()),
        "converged" => Integrator::Quadrature(QuadratureSettings::converged()),
        mc if mc.starts_with("mc:") => {
            let v: Vec<u32> = mc[3..]
                .split(':')
                .map(str::parse)
                .collect::<Result<_, _>>()?;
            Integrator::MonteCarlo {
                spp: v[0],
                orders: *v.get(1).unwrap_or(&0),
            }
        }
        other => bail!("unknown integrator {other}"),
    };
    let noise = NoiseSet::generate(&NoiseConfig {
        seed: scene.noise.seed,
        shape: match scene.noise.shape_texture {
            ShapeTexture::Thesis => ShapeSize::Thesis,
            ShapeTexture::Hzd => ShapeSize::Hzd,
        },
        ..NoiseConfig::default()
    });
    let frame = render(&scene, &noise, &integrator, true);
    image::save_buffer(
        out,
        &frame.image,
        frame.width,
        frame.height,
        image::ExtendedColorType::Rgba8,
    )?;
    println!("wrote {out} on {}", frame.device);
    for t in &frame.timings {
        println!("{}: {:.1} ms ({})", t.pass, t.ms, t.source);
    }
    println!("{:#?}", frame.stats);
    let n = (frame.width * frame.height) as usize;
    let mean: f64 = (0..n)
        .map(|i| f64::from(frame.radiance[4 * i]))
        .sum::<f64>()
        / n as f64;
    println!("mean radiance r {mean:.5}");
    Ok(())
}
