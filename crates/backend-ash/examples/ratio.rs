//! The ash/wgpu time ratio on one device, measured in one process with the two backends
//! interleaved (ash, wgpu, ash, wgpu, ...) so that both see the same machine load: the march
//! pass by GPU timestamps, and the whole `render()` call by wall clock. Prints the median of
//! each and the ratios.
//!
//! `cargo run --release -p stratus-backend-ash --example ratio [repeats] [preset] [WxH]`
//! (defaults: 9, cumulus-noon, 256x144).

use std::time::Instant;

use stratus_noise::{NoiseConfig, NoiseSet};
use stratus_scene::Scene;
use stratus_shaders::{FrameOutput, FramePlan};

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn march_ms(out: &FrameOutput) -> f64 {
    out.timings
        .iter()
        .find(|t| t.pass == "march")
        .map_or(f64::NAN, |t| t.ms)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let repeats: usize = args.next().map_or(Ok(9), |a| a.parse())?;
    let preset = args.next().unwrap_or_else(|| "cumulus-noon".into());
    let (w, h) = match args.next() {
        Some(s) => {
            let (w, h) = s.split_once('x').ok_or("size must be WxH")?;
            (w.parse()?, h.parse()?)
        }
        None => (256, 144),
    };
    let scene = Scene::preset(&preset)?.with_size(w, h);
    let plan = FramePlan::for_scene(&scene, false)?;
    let uniforms = scene.uniforms();
    let noise = NoiseSet::generate(&NoiseConfig {
        seed: scene.noise.seed,
        ..Default::default()
    });
    let mut ash =
        stratus_backend_ash::Renderer::new(stratus_backend_ash::Options { validation: false })?;
    let mut wgpu = stratus_backend_wgpu::Renderer::new(stratus_backend_wgpu::Options {
        api: stratus_backend_wgpu::Api::Vulkan,
        validation: false,
    })?;
    println!(
        "{preset} {w}x{h}, variant {}, {repeats} interleaved repeats each\nash:  {}\nwgpu: {}",
        plan.variant,
        ash.adapter(),
        wgpu.adapter()
    );
    // Warm up: pipeline creation and the drivers' shader compilation.
    let first = ash.render(&plan, &uniforms, &noise)?;
    let other = wgpu.render(&plan, &uniforms, &noise)?;
    let same = first.radiance.len() == other.radiance.len()
        && first
            .radiance
            .iter()
            .zip(&other.radiance)
            .all(|(a, b)| a.to_bits() == b.to_bits())
        && first.image == other.image;
    println!("outputs bit-identical: {same}");

    let (mut ash_march, mut wgpu_march, mut ash_wall, mut wgpu_wall) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut sources = (first.timings[0].source, other.timings[0].source);
    for _ in 0..repeats {
        let t = Instant::now();
        let a = ash.render(&plan, &uniforms, &noise)?;
        ash_wall.push(t.elapsed().as_secs_f64() * 1e3);
        let t = Instant::now();
        let b = wgpu.render(&plan, &uniforms, &noise)?;
        wgpu_wall.push(t.elapsed().as_secs_f64() * 1e3);
        ash_march.push(march_ms(&a));
        wgpu_march.push(march_ms(&b));
        sources = (a.timings[0].source, b.timings[0].source);
    }
    let (am, wm) = (median(ash_march.clone()), median(wgpu_march.clone()));
    let (aw, ww) = (median(ash_wall), median(wgpu_wall));
    println!(
        "march ({} / {}): ash {am:.3} ms, wgpu {wm:.3} ms, ash/wgpu {:.3}",
        sources.0,
        sources.1,
        am / wm
    );
    println!("  ash  runs: {ash_march:.3?}\n  wgpu runs: {wgpu_march:.3?}");
    println!(
        "whole render() call (wall): ash {aw:.1} ms, wgpu {ww:.1} ms, ash/wgpu {:.3}",
        aw / ww
    );
    if wm < 0.1 * am {
        println!(
            "note: wgpu's march timestamps cannot be right (the frame took {ww:.0} ms); on lavapipe \
             they are taken late when a render pass has bound a framebuffer (see the ash backend's \
             TIMESTAMP_STAGE notes), so only the wall-clock ratio means something here"
        );
    }
    ash.finish()?;
    Ok(())
}
