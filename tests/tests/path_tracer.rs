//! The GPU path tracer (`wgsl/pathtrace.wgsl`) against the CPU path tracer: the same estimator
//! in f32 on the GPU and f64 on the CPU, with independent random streams, so they agree within
//! noise. Per 8x8 block the difference of the mean luminance is measured in combined standard
//! errors (the GPU's from the per-pixel second moment it accumulates in `history-meta`, the
//! CPU's from its per-sample variance), as `cargo xtask mitsuba-check` measures the CPU path
//! tracer against Mitsuba, and over all cloudy blocks pooled, which sees a bias every block
//! shares but none shows beyond its own noise. ash (the committed SPIR-V) must match wgpu bit for bit. Validation
//! is on; any message fails the test.

use std::sync::Arc;

use stratus_graph::{Backend, FrameInput, FrameOutput, FramePlan, Readback};
use stratus_noise::{NoiseConfig, NoiseSet};
use stratus_scene::{Integrator, Scene};

const WIDTH: u32 = 32;
const HEIGHT: u32 = 24;
const BLOCK: u32 = 8;
/// Paths per pixel on each side.
const SPP: u32 = 192;
/// Paths per pixel on each side in the test that also runs the deliberately biased GPU
/// renders: enough that a 2% bias fails the pooled check on either side (see
/// [`DETECTABLE_BIAS`]).
const BIAS_SPP: u32 = 512;
/// The largest |z| allowed over the 12 blocks. With independent normal errors, P(max |z| >
/// 4.0) over 12 blocks is below 0.1%.
const MAX_Z: f64 = 4.0;
/// The bound on the pooled z of all cloudy blocks together (the sum of their differences over
/// its standard error): a bias shared by every block, which no single block shows beyond its
/// noise, adds up there. P(|z| > 2.5) is 1.2% for a normal z; the runs are seeded, so a change
/// to either tracer re-draws it once, not every run.
const MAX_POOLED_Z: f64 = 2.5;
/// The pooled check must be able to see a uniform relative bias this large (at MAX_POOLED_Z):
/// otherwise the test is too noisy to tell 2% of error in the light from noise, and passes by
/// accident. Measured on lavapipe at 192 paths a pixel: the three scenes' pooled checks see
/// 1.84%, 1.56% and 1.58%, and measure GPU - CPU at -0.80%, -0.67% and -0.69% (pooled z -1.08,
/// -1.07 and -1.09). The three draws are one: the scenes share the camera and both tracers'
/// random streams (seeded by pixel and path), so their noise is nearly the same. At 768 paths
/// the first scene measures -0.355% (z -0.96, detectable 0.93%): the lean shrinks with the
/// noise, as noise does. At 192 paths a GPU 2% brighter would read +1.2% and pass, so the
/// first test runs at [`BIAS_SPP`] and renders the GPU with every light 2% weaker and 2%
/// stronger; both must fail the check (the same paths, so each measured shift is the bias
/// plus the lean). Measured at 512 paths: unbiased -0.454% (z -1.00, detectable 1.13%), 2%
/// weaker -2.445% (z -5.44), 2% stronger +1.537% (z +3.36).
const DETECTABLE_BIAS: f64 = 0.02;

/// wgpu on Vulkan (lavapipe) with validation on.
fn wgpu_vulkan() -> stratus_backend_wgpu::Renderer {
    stratus_backend_wgpu::Renderer::new(stratus_backend_wgpu::Options {
        api: stratus_backend_wgpu::Api::Vulkan,
        validation: true,
    })
    .expect("a Vulkan device (lavapipe)")
}

fn noise() -> Arc<NoiseSet> {
    Arc::new(NoiseSet::generate(&NoiseConfig::default()))
}

fn scene() -> Scene {
    let mut s = Scene::preset("cumulus-noon")
        .expect("preset")
        .with_size(WIDTH, HEIGHT);
    // Look up into the clouds, so that most blocks hold cloud.
    s.camera.pitch_deg = 25.0;
    s
}

/// `spp` paths per pixel accumulated over frames on `r`: the output and `history-meta`
/// (depth, paths, mean squared luminance, hits) as floats.
fn gpu(
    r: &mut dyn Backend,
    scene: &Scene,
    noise: &Arc<NoiseSet>,
    spp: u32,
) -> (FrameOutput, Vec<f32>) {
    let mut s = scene.clone();
    s.quality.integrator = Integrator::Pathtrace;
    let plan = FramePlan::for_scene(&s, false).expect("plan");
    let per_frame = plan.paths_per_frame().expect("a path-traced plan");
    assert_eq!(
        spp % per_frame,
        0,
        "{spp} paths are whole frames of {per_frame} paths"
    );
    let frames = spp / per_frame;
    let mut last = None;
    for i in 0..frames {
        let mut f = s.clone();
        f.quality.frame = i;
        let readback = if i + 1 == frames {
            Readback {
                output: true,
                resources: vec!["history-meta".into()],
            }
        } else {
            Readback::none()
        };
        let out = r
            .render(&FrameInput::new(&plan, &f, noise).with_readback(readback))
            .expect("render");
        last = Some(out);
    }
    let out = last.expect("frames");
    let meta: Vec<f32> = out.resources["history-meta"]
        .chunks(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    (out, meta)
}

/// Per block: GPU mean luminance and its standard error (`block_means`, the noise report's),
/// after checking that every pixel accumulated `spp` paths.
fn gpu_blocks(out: &FrameOutput, meta: &[f32], spp: u32) -> Vec<(f64, f64)> {
    for (i, m) in meta.chunks(4).enumerate() {
        let (x, y) = (i as u32 % WIDTH, i as u32 / WIDTH);
        assert_eq!(
            f64::from(m[1]),
            f64::from(spp),
            "pixel ({x}, {y}) accumulated {} paths",
            m[1]
        );
    }
    let bytes = &out.resources["history-meta"];
    stratus_graph::block_means(out, bytes, BLOCK)
        .expect("history-meta of the frame's size")
        .iter()
        .map(|b| (b.mean, b.variance.sqrt()))
        .collect()
}

#[test]
fn gpu_path_tracer_agrees_with_the_cpu_path_tracer() {
    let scene = scene();
    let cpu = agree(&scene, BIAS_SPP);
    // Deliberately biased runs: the sun and the sky (the analytic sky's ambient) both 2%
    // weaker, then both 2% stronger, so the GPU's image is 2% darker or brighter everywhere
    // (light transport is linear in its sources). The pooled check must see both.
    for (factor, words) in [(0.98, "weaker"), (1.02, "stronger")] {
        // A renderer of its own: one renderer accumulates its paths frame after frame.
        let mut wgpu = wgpu_vulkan();
        let mut biased = scene.clone();
        biased.sun.illuminance = biased.sun.illuminance.map(|v| v * factor);
        biased.lighting.ambient_strength *= factor;
        let (out, meta) = gpu(&mut wgpu, &biased, &noise(), BIAS_SPP);
        let p = pooled(&cpu, &gpu_blocks(&out, &meta, BIAS_SPP));
        println!(
            "with every light 2% {words} on the GPU: GPU - CPU {:+.3}%, pooled z {:+.2}",
            100.0 * p.relative,
            p.z
        );
        assert!(
            p.z.abs() >= MAX_POOLED_Z,
            "a GPU with every light 2% {words} passed the pooled check (z {:+.2})",
            p.z
        );
    }
}

/// The same with a high deck over the clouds: paths cross the gap between layers, and the
/// deck shadows the clouds below. The deck is half cirrus, so both densities and their blend
/// are traced.
#[test]
fn gpu_path_tracer_agrees_with_the_cpu_path_tracer_through_two_layers() {
    let mut s = scene();
    s.clouds.layers = vec![stratus_scene::CloudLayer {
        bottom_m: 6000.0,
        top_m: 7000.0,
        coverage: 0.7,
        density: 0.4,
        cloud_type: 0.2,
        precipitation: 0.0,
        cirrus: 0.5,
        cellular: 0.0,
    }];
    agree(&s, SPP);
}

/// The same under the physical sky: the sun through the air at every collision, and paths
/// that leave the clouds see the sky and lit ground in their own direction from their last
/// collision (the sky-view table's integral from there; the CPU's in f64).
#[test]
fn gpu_path_tracer_agrees_with_the_cpu_path_tracer_under_the_physical_sky() {
    let mut s = scene();
    s.atmosphere.sky = stratus_scene::SkyModel::Physical;
    agree(&s, SPP);
}

/// The pooled comparison of all cloudy blocks: the GPU's mean luminance against the CPU's.
struct Pooled {
    /// GPU minus CPU over the CPU's, summed over the blocks.
    relative: f64,
    /// That sum over its standard error.
    z: f64,
    /// The uniform relative bias whose z would reach the bound.
    detectable: f64,
    blocks: usize,
}

/// The CPU's per-block luminance mean and its standard error (an upper bound: the channels of
/// one path are strongly correlated, so the luminance's standard error is at most the weighted
/// sum of the channels').
fn cpu_luminance(c: &stratus_reference::Block) -> (f64, f64) {
    let mean = (0..3)
        .map(|k| stratus_graph::output::LUMA[k] * c.mean[k])
        .sum();
    let se = (0..3)
        .map(|k| stratus_graph::output::LUMA[k] * c.std_error[k])
        .sum();
    (mean, se)
}

fn pooled(cpu: &[stratus_reference::Block], gpu: &[(f64, f64)]) -> Pooled {
    let (mut difference, mut variance, mut total, mut blocks) = (0.0, 0.0, 0.0, 0);
    for (c, &(g, g_se)) in cpu.iter().zip(gpu) {
        let (c_mean, c_se) = cpu_luminance(c);
        if c_mean < 0.02 {
            continue;
        }
        blocks += 1;
        difference += g - c_mean;
        variance += g_se * g_se + c_se * c_se;
        total += c_mean;
    }
    Pooled {
        relative: difference / total,
        z: difference / variance.sqrt(),
        detectable: MAX_POOLED_Z * variance.sqrt() / total,
        blocks,
    }
}

/// Renders `scene` on both tracers at `spp` paths a pixel and holds them to each other;
/// returns the CPU's blocks.
fn agree(scene: &Scene, spp: u32) -> Vec<stratus_reference::Block> {
    stratus_test_support::record_wgpu_log();
    let noise = noise();
    let scene = scene.clone();

    let mut wgpu = wgpu_vulkan();
    let (w_out, w_meta) = gpu(&mut wgpu, &scene, &noise, spp);
    let log = stratus_test_support::take_wgpu_log();
    assert!(log.is_empty(), "wgpu validation: {log:?}");

    let mut ash =
        stratus_backend_ash::Renderer::new(stratus_backend_ash::Options { validation: true })
            .expect("ash on lavapipe");
    let (a_out, a_meta) = gpu(&mut ash, &scene, &noise, spp);
    ash.finish().expect("ash: no validation messages");
    assert!(
        a_out.radiance == w_out.radiance && a_meta == w_meta && a_out.image == w_out.image,
        "ash (committed SPIR-V) and wgpu path traced different bits"
    );

    // No pixel is NaN or infinite, and transmittance is a fraction.
    for (i, v) in w_out.radiance.chunks(4).enumerate() {
        assert!(v.iter().all(|x| x.is_finite()), "pixel {i}: {v:?}");
        assert!(
            (0.0..=1.0).contains(&v[3]),
            "pixel {i}: transmittance {}",
            v[3]
        );
    }

    let cpu = stratus_reference::render_medium(
        &scene,
        stratus_reference::Medium::Clouds(&noise),
        &stratus_reference::Integrator::MonteCarlo { spp, orders: 0 },
        &stratus_reference::RenderOptions {
            progress: false,
            threads: None,
        },
    );
    let cpu_blocks = cpu.blocks(BLOCK);
    let gpu_blocks = gpu_blocks(&w_out, &w_meta, spp);
    assert_eq!(cpu_blocks.len(), gpu_blocks.len());
    let mut worst: (f64, String) = (0.0, String::new());
    let mut cloudy = 0;
    let mut report = Vec::new();
    for (c, &(g, g_se)) in cpu_blocks.iter().zip(&gpu_blocks) {
        let (c_mean, c_se) = cpu_luminance(c);
        if c_mean < 0.02 {
            // Clear sky on the CPU: the GPU must see none either.
            assert!(g < 0.02, "block ({}, {}): gpu {g}, cpu {c_mean}", c.x, c.y);
            continue;
        }
        cloudy += 1;
        let z = (g - c_mean) / (g_se * g_se + c_se * c_se).sqrt();
        let line = format!(
            "block ({:2}, {:2}): gpu {g:.4} +- {g_se:.4}, cpu {c_mean:.4} +- {c_se:.4}, z {z:+.2}",
            c.x, c.y
        );
        if z.abs() > worst.0 {
            worst = (z.abs(), line.clone());
        }
        report.push(line);
    }
    println!("{}", report.join("\n"));
    assert!(cloudy >= 6, "only {cloudy} blocks hold cloud");
    let p = pooled(&cpu_blocks, &gpu_blocks);
    println!(
        "pooled over {} blocks: GPU - CPU {:+.3}% of the CPU's light, z {:+.2}; a uniform bias of {:.2}% would fail it",
        p.blocks,
        100.0 * p.relative,
        p.z,
        100.0 * p.detectable
    );
    assert!(
        p.detectable <= DETECTABLE_BIAS,
        "too noisy to see a {:.0}% bias: the pooled check only catches {:.2}%",
        100.0 * DETECTABLE_BIAS,
        100.0 * p.detectable
    );
    assert!(
        p.z.abs() < MAX_POOLED_Z,
        "GPU and CPU path tracers differ beyond noise over all blocks together: GPU - CPU is {:+.3}% of the CPU's light, z {:+.2}",
        100.0 * p.relative,
        p.z
    );
    assert!(
        worst.0 < MAX_Z,
        "GPU and CPU path tracers differ beyond noise: {}",
        worst.1
    );
    cpu_blocks
}
