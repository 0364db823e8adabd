//! Aerial perspective for the host's geometry: the table `Clouds::aerial_perspective` hands
//! out, read by the host's helper (`wgsl/host/aerial_perspective.wgsl`, run here in a shader of
//! the host's own) at pixels and distances, against the CPU reference's table read the same
//! way.

use stratus::{AERIAL_SIDE, AERIAL_SLICES, Clouds, Scene};
use stratus_reference::sky::SkyTables;
use stratus_test_support::{assert_no_wgpu_messages, record_wgpu_log};

mod common;

const W: u32 = 64;
const H: u32 = 36;

/// The helper, as a host copies it.
const HELPER: &str = include_str!("../../../wgsl/host/aerial_perspective.wgsl");

/// The host's probe: the helper at each (uv, distance) of a storage buffer.
const PROBE: &str = "
@group(0) @binding(0) var map: texture_2d<f32>;
@group(0) @binding(1) var<uniform> aerial: StratusAerial;
@group(0) @binding(2) var<storage, read> probes: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read_write> out: array<vec4<f32>>;

@compute @workgroup_size(64)
fn probe(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < arrayLength(&probes) {
        let p = probes[id.x];
        out[id.x] = stratus_aerial_perspective(map, aerial, p.xy, p.z);
    }
}
";

/// The helper at `probes` (uv, distance) from `clouds`' last table.
fn probe(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    clouds: &Clouds,
    probes: &[[f32; 4]],
) -> Vec<[f32; 4]> {
    let aerial = clouds
        .aerial_perspective()
        .expect("a table under the physical sky");
    common::run_probe(
        device,
        queue,
        &format!("{HELPER}\n{PROBE}"),
        aerial.view,
        &aerial.uniform,
        probes,
        16,
    )
    .chunks_exact(16)
    .map(|c| std::array::from_fn(|k| f32::from_le_bytes(c[4 * k..4 * k + 4].try_into().unwrap())))
    .collect()
}

/// The helper's haze at pixel centres and distances from 0 to beyond the table (35 km), on
/// the GPU's table, against the CPU's table read the same way: within 1% of the in-scattered
/// light (relative, of the largest channel) and 0.002 of the transmittance, under a high sun
/// and a low one. Without the physical sky there is no table.
#[test]
fn the_hosts_aerial_perspective_matches_the_cpus() {
    record_wgpu_log();
    let (device, queue) = common::device();
    let target = common::target(&device, wgpu::TextureFormat::Rgba8Unorm, W, H);
    let view = target.create_view(&Default::default());
    for preset in ["cumulus-noon", "sunset"] {
        let mut scene = Scene::preset(preset).unwrap().with_size(W, H);
        scene.atmosphere.sky = stratus_scene::SkyModel::Physical;
        let mut clouds = Clouds::new(&device, &queue, scene.clone()).expect("clouds");
        assert!(
            clouds.aerial_perspective().is_none(),
            "no table before a frame"
        );
        let mut encoder = device.create_command_encoder(&Default::default());
        clouds.render(&mut encoder, &view).expect("a frame");
        queue.submit([encoder.finish()]);
        let aerial = clouds.aerial_perspective().expect("a table");
        let texture = aerial.view.texture();
        assert_eq!(
            [texture.width(), texture.height()],
            [AERIAL_SIDE * AERIAL_SLICES, AERIAL_SIDE]
        );
        let mut probes = Vec::new();
        let mut pixels = Vec::new();
        for y in (0..H).step_by(5) {
            for x in (0..W).step_by(7) {
                for distance in [0.0, 300.0, 1500.0, 7250.0, 20_000.0, 35_000.0] {
                    let uv = [(x as f32 + 0.5) / W as f32, (y as f32 + 0.5) / H as f32];
                    probes.push([uv[0], uv[1], distance as f32, 0.0]);
                    pixels.push(([x, y], distance));
                }
            }
        }
        let gpu = probe(&device, &queue, &clouds, &probes);
        let u = clouds.scene().uniforms();
        let cpu = SkyTables::new(&u);
        let e = u.sun_illuminance.map(f64::from);
        let (mut worst_light, mut worst_t) = (0.0f64, 0.0f64);
        for (g, (pixel, distance)) in gpu.iter().zip(&pixels) {
            let c = cpu.aerial_at(&u, *pixel, *distance);
            let light: [f64; 3] = std::array::from_fn(|k| c[k] * e[k]);
            let scale = light.iter().cloned().fold(1e-6, f64::max);
            for k in 0..3 {
                worst_light = worst_light.max((f64::from(g[k]) - light[k]).abs() / scale);
            }
            worst_t = worst_t.max((f64::from(g[3]) - c[3]).abs());
            if *distance == 0.0 {
                assert_eq!(*g, [0.0, 0.0, 0.0, 1.0], "no air at the camera");
            }
        }
        println!(
            "{preset}: worst in-scattered light {worst_light:.2e} (relative), transmittance {worst_t:.2e}"
        );
        assert!(
            worst_light <= 0.01,
            "{preset}: in-scattered light {worst_light:.4} off the CPU's"
        );
        assert!(
            worst_t <= 0.002,
            "{preset}: transmittance {worst_t:.4} off the CPU's"
        );
    }
    let analytic = Scene::preset("cumulus-noon").unwrap().with_size(W, H);
    let mut clouds = Clouds::new(&device, &queue, analytic).expect("clouds");
    let mut encoder = device.create_command_encoder(&Default::default());
    clouds.render(&mut encoder, &view).expect("a frame");
    queue.submit([encoder.finish()]);
    assert!(
        clouds.aerial_perspective().is_none(),
        "a table without the physical sky"
    );
    assert_no_wgpu_messages();
}
