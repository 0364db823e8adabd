//! What a frame costs on each backend, measured in one process with the two persistent
//! renderers interleaved (ash, wgpu, ash, wgpu, ...) so that both see the same machine load:
//! the march pass by GPU timestamps, the CPU time of recording and submitting a frame (not the
//! wait), and the whole `render()` call by wall clock. Nothing is read back (a real-time loop);
//! the wind moves every frame. Prints the median of each and the ash/wgpu ratios.
//!
//! `cargo run --release -p stratus-backend-ash --example ratio [frames] [preset] [WxH]`
//! (defaults: 300, cumulus-noon, 256x144).

use std::{sync::Arc, time::Instant};

use stratus_graph::{FrameInput, FrameOutput, FramePlan, Readback, output::median};
use stratus_noise::{NoiseConfig, NoiseSet};
use stratus_scene::Scene;

fn march_ms(out: &FrameOutput) -> f64 {
    out.timings
        .iter()
        .find(|t| t.pass == "march")
        .map_or(f64::NAN, |t| t.ms)
}

#[derive(Default)]
struct Samples {
    march: Vec<f64>,
    cpu: Vec<f64>,
    wall: Vec<f64>,
}

impl Samples {
    fn push(&mut self, out: &FrameOutput, wall_ms: f64) {
        self.march.push(march_ms(out));
        self.cpu.push(out.cpu_ms);
        self.wall.push(wall_ms);
    }
    fn medians(&self) -> [f64; 3] {
        [
            median(self.march.clone()),
            median(self.cpu.clone()),
            median(self.wall.clone()),
        ]
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let frames: usize = args.next().map_or(Ok(300), |a| a.parse())?;
    let preset = args.next().unwrap_or_else(|| "cumulus-noon".into());
    let (w, h) = match args.next() {
        Some(s) => {
            let (w, h) = s.split_once('x').ok_or("size must be WxH")?;
            (w.parse()?, h.parse()?)
        }
        None => (256, 144),
    };
    let base = Scene::preset(&preset)?.with_size(w, h);
    let plan = FramePlan::for_scene(&base, false)?;
    let noise = Arc::new(NoiseSet::generate(&NoiseConfig {
        seed: base.noise.seed,
        ..Default::default()
    }));
    let mut ash =
        stratus_backend_ash::Renderer::new(stratus_backend_ash::Options { validation: false })?;
    let mut wgpu = stratus_backend_wgpu::Renderer::new(stratus_backend_wgpu::Options {
        api: stratus_backend_wgpu::Api::Vulkan,
        validation: false,
    })?;
    println!(
        "{preset} {w}x{h}, variant {}, {frames} interleaved frames each\nash:  {}\nwgpu: {}",
        plan.variant,
        ash.adapter(),
        wgpu.adapter()
    );
    // Warm up: resources, pipelines and the drivers' shader compilation; both must agree.
    let first = ash.render(&FrameInput::new(&plan, &base, &noise))?;
    let other = wgpu.render(&FrameInput::new(&plan, &base, &noise))?;
    let same = first.radiance.len() == other.radiance.len()
        && first
            .radiance
            .iter()
            .zip(&other.radiance)
            .all(|(a, b)| a.to_bits() == b.to_bits())
        && first.image == other.image;
    println!(
        "first frame: {}",
        if same {
            "bit-identical"
        } else {
            "DIFFERENT images"
        }
    );
    let (created_ash, created_wgpu) = (ash.objects_created(), wgpu.objects_created());
    let (mut a, mut b) = (Samples::default(), Samples::default());
    for i in 0..frames {
        let mut scene = base.clone();
        scene.clouds.time_s += i as f64 / 60.0;
        let frame = FrameInput::new(&plan, &scene, &noise).with_readback(Readback::none());
        let t = Instant::now();
        let out = ash.render(&frame)?;
        a.push(&out, t.elapsed().as_secs_f64() * 1e3);
        let t = Instant::now();
        let out = wgpu.render(&frame)?;
        b.push(&out, t.elapsed().as_secs_f64() * 1e3);
    }
    let [am, ac, aw] = a.medians();
    let [bm, bc, bw] = b.medians();
    println!("median of {frames}:        march GPU ms   CPU ms/frame   render() wall ms");
    println!("ash                    {am:12.3} {ac:14.3} {aw:18.3}");
    println!("wgpu                   {bm:12.3} {bc:14.3} {bw:18.3}");
    println!(
        "ash/wgpu               {:12.2} {:14.2} {:18.2}",
        am / bm,
        ac / bc,
        aw / bw
    );
    println!(
        "GPU objects created after the first frame: ash {}, wgpu {}",
        ash.objects_created() - created_ash,
        wgpu.objects_created() - created_wgpu
    );
    ash.finish()?;
    Ok(())
}
