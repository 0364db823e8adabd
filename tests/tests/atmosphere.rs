//! The physical sky's GPU tables (wgsl/atmosphere.wgsl) against the CPU reference's f64
//! atmosphere integrated directly along each ray (crates/reference/src/atmosphere.rs), and
//! the same bits on ash and wgpu with validation on (cumulus-noon under the physical sky and
//! the presets dawn, noon, dusk and night, two frames each). Each table texel is mapped back to its
//! ray here in f64 by the same parametrisation the WGSL documents; the measured errors are
//! printed (`--nocapture`) and bounded.
//!
//! Measured on lavapipe (wgpu and ash alike), cumulus-noon under the physical sky:
//! transmittance RMSE 2.1e-5, worst texel 2.5e-4 (absolute); multi-scattering RMSE 0.01% and
//! worst 0.07% of the texel's value (the same quadrature; the GPU reads its transmittance
//! table where the reference integrates); sky-view RMSE 0.64%, worst 1.37% (16 directions
//! against 64 steps with multiple scattering integrated at every step). The bounds are about
//! three times those.

use std::f64::consts::PI;
use std::sync::Arc;

use stratus_graph::{Backend, FrameInput, FrameOutput, FramePlan, Readback};
use stratus_noise::NoiseConfig;
use stratus_reference::atmosphere::AtmosphereModel;
use stratus_scene::{Scene, SkyModel};

const TABLES: [&str; 6] = [
    "transmittance-lut",
    "multiscatter-lut",
    "ground-irradiance",
    "sky-view-lut",
    "sky-ambient",
    "aerial-perspective",
];

fn scene() -> Scene {
    let mut s = Scene::preset("cumulus-noon")
        .expect("preset")
        .with_size(64, 36);
    s.atmosphere.sky = SkyModel::Physical;
    s.validate().expect("a valid scene");
    s
}

/// wgpu on Vulkan (lavapipe) with validation on.
fn wgpu_renderer() -> stratus_backend_wgpu::Renderer {
    stratus_backend_wgpu::Renderer::new(stratus_backend_wgpu::Options {
        api: stratus_backend_wgpu::Api::Vulkan,
        validation: true,
    })
    .expect("a Vulkan device (lavapipe)")
}

fn render(r: &mut dyn Backend, scene: &Scene, noise: &Arc<stratus_noise::NoiseSet>) -> FrameOutput {
    let plan = FramePlan::for_scene(scene, false).expect("plan");
    let readback = Readback {
        output: true,
        resources: TABLES
            .iter()
            .chain(&["cloud-shadow"])
            .map(|s| s.to_string())
            .collect(),
    };
    r.render(&FrameInput::new(&plan, scene, noise).with_readback(readback))
        .expect("render")
}

/// The rgb of each rgba32float texel of table `name`.
fn table(out: &FrameOutput, name: &str) -> Vec<[f64; 3]> {
    out.resources[name]
        .chunks_exact(16)
        .map(|t| {
            let f = |k: usize| f64::from(f32::from_le_bytes([t[k], t[k + 1], t[k + 2], t[k + 3]]));
            [f(0), f(4), f(8)]
        })
        .collect()
}

/// Root mean square and largest of `errors`.
fn stats(errors: &[f64]) -> (f64, f64) {
    let rms = (errors.iter().map(|e| e * e).sum::<f64>() / errors.len() as f64).sqrt();
    (rms, errors.iter().cloned().fold(0.0, f64::max))
}

/// Relative error of `gpu` against `truth`, over channels, against the larger of the truth's
/// channel and a floor (where the truth is near 0 the absolute error counts).
fn relative(gpu: [f64; 3], truth: [f64; 3], floor: f64) -> f64 {
    (0..3)
        .map(|c| (gpu[c] - truth[c]).abs() / truth[c].abs().max(floor))
        .fold(0.0, f64::max)
}

/// (r, mu) of transmittance texel coordinates `x` (Bruneton's parametrisation, metres).
fn transmittance_r_mu(m: &AtmosphereModel, x: [f64; 2]) -> (f64, f64) {
    let (bottom, top) = (m.bottom_radius_m, m.top_radius_m);
    let h = (top * top - bottom * bottom).sqrt();
    let rho = h * x[1];
    let r = (rho * rho + bottom * bottom).sqrt();
    let (d_min, d_max) = (top - r, rho + h);
    let d = d_min + x[0] * (d_max - d_min);
    let mu = if d > 0.0 {
        ((h * h - rho * rho - d * d) / (2.0 * r * d)).clamp(-1.0, 1.0)
    } else {
        1.0
    };
    (r, mu)
}

fn distance_to_top(m: &AtmosphereModel, r: f64, mu: f64) -> f64 {
    let disc = r * r * (mu * mu - 1.0) + m.top_radius_m * m.top_radius_m;
    (-r * mu + disc.max(0.0).sqrt()).max(0.0)
}

#[test]
fn physical_sky_tables_match_the_direct_integration_and_both_backends() {
    stratus_test_support::record_wgpu_log();
    let scene = scene();
    let noise = Arc::new(stratus_noise::NoiseSet::generate(&NoiseConfig::default()));
    let mut wgpu = wgpu_renderer();
    let mut ash =
        stratus_backend_ash::Renderer::new(stratus_backend_ash::Options { validation: true })
            .expect("ash on lavapipe");
    let w = render(&mut wgpu, &scene, &noise);
    let a = render(&mut ash, &scene, &noise);
    let differences = stratus_test_support::frame_differences("physical sky", &w, &a);
    assert!(differences.is_empty(), "ash against wgpu: {differences:?}");
    for name in TABLES.iter().chain(&["cloud-shadow"]) {
        assert!(
            w.resources[*name] == a.resources[*name],
            "{name}: ash and wgpu differ"
        );
        if *name == "cloud-shadow" {
            continue; // r32float, checked below
        }
        assert!(
            table(&w, name)
                .iter()
                .flatten()
                .all(|v| v.is_finite() && *v >= 0.0),
            "{name}: a texel is negative or not finite"
        );
    }
    assert!(
        w.radiance.iter().all(|v| v.is_finite()),
        "a pixel is not finite"
    );

    for preset in ["dawn", "noon", "dusk", "night"] {
        let s = Scene::preset(preset).expect("preset").with_size(128, 72);
        let w = render(&mut wgpu, &s, &noise);
        let a = render(&mut ash, &s, &noise);
        // A second frame (the air's tables kept from the first) holds the same bits.
        let w2 = render(&mut wgpu, &s, &noise);
        let a2 = render(&mut ash, &s, &noise);
        for (f, again) in [(&w, &w2), (&a, &a2)] {
            let d = stratus_test_support::frame_differences(preset, f, again);
            assert!(d.is_empty(), "{preset}: a second frame differs: {d:?}");
        }
        for name in TABLES.iter().chain(&["cloud-shadow"]) {
            assert!(
                w.resources[*name] == a.resources[*name],
                "{preset}: {name}: ash and wgpu differ"
            );
        }
        let differences = stratus_test_support::frame_differences(preset, &w, &a);
        assert!(
            differences.is_empty(),
            "{preset}: ash against wgpu: {differences:?}"
        );
    }

    let model = AtmosphereModel::earth(scene.atmosphere.planet_radius_m);

    // Transmittance: every texel, against Simpson on 512 intervals to the top.
    let t = table(&w, "transmittance-lut");
    let (tw, th) = (256usize, 64usize);
    let errors: Vec<f64> = (0..th)
        .flat_map(|j| (0..tw).map(move |i| (i, j)))
        .map(|(i, j)| {
            let x = [i as f64 / (tw - 1) as f64, j as f64 / (th - 1) as f64];
            let (r, mu) = transmittance_r_mu(&model, x);
            let p = [0.0, r, 0.0];
            let d = [(1.0 - mu * mu).max(0.0).sqrt(), mu, 0.0];
            let tau = model.optical_depth(p, d, distance_to_top(&model, r, mu), 512);
            let truth = tau.map(|tau| (-tau).exp());
            (0..3)
                .map(|c| (t[j * tw + i][c] - truth[c]).abs())
                .fold(0.0, f64::max)
        })
        .collect();
    let (rms, worst) = stats(&errors);
    eprintln!("transmittance: RMSE {rms:.2e}, worst texel {worst:.2e} (absolute)");
    assert!(
        rms < 6e-5 && worst < 8e-4,
        "transmittance: RMSE {rms:.2e}, worst {worst:.2e}"
    );

    // Multi-scattering: every fourth texel each way, against the reference's Psi_ms (the
    // same 64 directions and 32 steps, with exact transmittance where the GPU reads its table).
    let ms = table(&w, "multiscatter-lut");
    let n = 32usize;
    let top = model.top_radius_m - model.bottom_radius_m;
    let mut errors = Vec::new();
    for j in (0..n).step_by(4).chain([n - 1]) {
        for i in (0..n).step_by(4).chain([n - 1]) {
            let mu_s = i as f64 / (n - 1) as f64 * 2.0 - 1.0;
            let r = model.bottom_radius_m + j as f64 / (n - 1) as f64 * top;
            let sun = [(1.0 - mu_s * mu_s).max(0.0).sqrt(), mu_s, 0.0];
            let truth = model.multiple_scattering([0.0, r, 0.0], sun, 32, 64);
            let floor = 1e-3 * truth.iter().cloned().fold(0.0, f64::max).max(1e-9);
            errors.push(relative(ms[j * n + i], truth, floor.max(1e-6)));
        }
    }
    let (rms, worst) = stats(&errors);
    eprintln!(
        "multi-scattering: RMSE {:.2}%, worst texel {:.2}%",
        rms * 100.0,
        worst * 100.0
    );
    assert!(
        rms < 5e-4 && worst < 3e-3,
        "multi-scattering: RMSE {rms:.3}, worst {worst:.3}"
    );

    // Sky view: 16 directions spread over the table (above and below the horizon), against
    // the reference's sky radiance with multiple scattering on 64 steps.
    let sky = table(&w, "sky-view-lut");
    let irradiance = table(&w, "ground-irradiance");
    let (sw, sh) = (192usize, 108usize);
    let r = model.bottom_radius_m + scene.camera.position[1].max(0.0);
    let horizon = -(model.bottom_radius_m / r).clamp(-1.0, 1.0).acos();
    let sun = scene.uniforms().sun_direction;
    let sun = [f64::from(sun[0]), f64::from(sun[1]), f64::from(sun[2])];
    let sun_azimuth = sun[2].atan2(sun[0]);
    let mut errors = Vec::new();
    for j in [2usize, 20, 40, 52, 56, 60, 80, 105] {
        for i in [0usize, 95] {
            let v = j as f64 / (sh - 1) as f64;
            let elevation = if v >= 0.5 {
                let a = 2.0 * v - 1.0;
                horizon + (0.5 * PI - horizon) * a * a
            } else {
                let a = 1.0 - 2.0 * v;
                horizon - (horizon + 0.5 * PI) * a * a
            };
            let phi = sun_azimuth + i as f64 / (sw - 1) as f64 * PI;
            let d = [
                elevation.cos() * phi.cos(),
                elevation.sin(),
                elevation.cos() * phi.sin(),
            ];
            // The ground lit by the sky too, through the GPU's irradiance table (held to the
            // CPU twin's below, and that to the direct integral in crates/reference).
            let e = |mu_s: f64| {
                let x = (mu_s * 0.5 + 0.5).clamp(0.0, 1.0) * (irradiance.len() - 1) as f64;
                let i0 = (x.floor() as usize).min(irradiance.len() - 1);
                let i1 = (i0 + 1).min(irradiance.len() - 1);
                let w = x - i0 as f64;
                std::array::from_fn(|c| irradiance[i0][c] * (1.0 - w) + irradiance[i1][c] * w)
            };
            let truth = model.sky_radiance_over_ground([0.0, r, 0.0], d, sun, true, 64, e);
            let floor = 1e-3 * truth.iter().cloned().fold(0.0, f64::max).max(1e-9);
            errors.push(relative(sky[j * sw + i], truth, floor));
        }
    }
    let (rms, worst) = stats(&errors);
    eprintln!(
        "sky view: RMSE {:.2}%, worst texel {:.2}%",
        rms * 100.0,
        worst * 100.0
    );
    assert!(
        rms < 0.02 && worst < 0.045,
        "sky view: RMSE {rms:.3}, worst {worst:.3}"
    );

    // Ground irradiance: the GPU's table against the CPU twin's (f64, the same quadrature),
    // which crates/reference/tests/sky.rs holds to the direct hemisphere integral.
    let cpu = stratus_reference::sky::SkyTables::new(&scene.uniforms());
    let errors: Vec<f64> = irradiance
        .iter()
        .zip(&cpu.ground_irradiance.texels)
        .map(|(g, c)| relative(*g, [c[0], c[1], c[2]], 1e-6))
        .collect();
    let (rms, worst) = stats(&errors);
    eprintln!(
        "ground irradiance against the CPU twin: RMSE {:.3}%, worst {:.3}%",
        rms * 100.0,
        worst * 100.0
    );
    // Measured: worst 0.002% (f32 against f64).
    assert!(
        worst < 1e-4,
        "ground irradiance: RMSE {rms:.2e}, worst {worst:.2e}"
    );

    // Cloud shadow: a transmittance in (0, 1] everywhere, and the scene's clouds shade part of
    // the ground (cumulus at coverage 0.5 over 40 km) while leaving part in the sun.
    let shadow: Vec<f32> = w.resources["cloud-shadow"]
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect();
    assert_eq!(shadow.len(), 128 * 128);
    assert!(
        shadow
            .iter()
            .all(|t| t.is_finite() && *t > 0.0 && *t <= 1.0)
    );
    let shaded = shadow.iter().filter(|t| **t < 0.5).count() as f64 / shadow.len() as f64;
    let lit = shadow.iter().filter(|t| **t > 0.99).count() as f64 / shadow.len() as f64;
    eprintln!(
        "cloud shadow: {:.1}% shaded (T < 0.5), {:.1}% lit (T > 0.99)",
        shaded * 100.0,
        lit * 100.0
    );
    assert!(
        shaded > 0.05 && lit > 0.05,
        "shaded {shaded:.3}, lit {lit:.3}"
    );

    let log = stratus_test_support::take_wgpu_log();
    assert!(log.is_empty(), "wgpu validation: {log:?}");
    ash.finish().expect("ash: no validation messages");
}

/// The transmittance, multi-scattering and sky-ambient tables depend on the air (the last on
/// the cloud layer's bottom too, not its top), not the sun: a frame with another sun does not
/// compute them again, a frame with other air does. The sky view and aerial perspective follow
/// the sun and the camera's altitude (the froxels its orientation too), not the clouds' wind
/// or where over the ground it is.
#[test]
fn air_tables_are_computed_again_only_when_the_air_changes() {
    stratus_test_support::record_wgpu_log();
    let noise = Arc::new(stratus_noise::NoiseSet::generate(&NoiseConfig::default()));
    let mut wgpu = wgpu_renderer();
    let mut s = scene();
    let ran = |r: &mut stratus_backend_wgpu::Renderer, s: &Scene| -> Vec<String> {
        let plan = FramePlan::for_scene(s, false).expect("plan");
        let out = r
            .render(&FrameInput::new(&plan, s, &noise))
            .expect("render");
        out.timings.iter().map(|t| t.pass.clone()).collect()
    };
    let first = ran(&mut wgpu, &s);
    assert!(
        first.contains(&"transmittance-lut".to_string()),
        "{first:?}"
    );
    assert!(first.contains(&"multiscatter-lut".to_string()), "{first:?}");
    s.sun.elevation_deg = 10.0;
    let moved_sun = ran(&mut wgpu, &s);
    assert!(
        !moved_sun.contains(&"transmittance-lut".to_string()),
        "{moved_sun:?}"
    );
    assert!(
        !moved_sun.contains(&"multiscatter-lut".to_string()),
        "{moved_sun:?}"
    );
    assert!(
        !moved_sun.contains(&"sky-ambient".to_string()),
        "{moved_sun:?}"
    );
    for table in ["sky-view-lut", "aerial-perspective"] {
        assert!(moved_sun.contains(&table.to_string()), "{moved_sun:?}");
    }
    // Only the clouds move (ten seconds of wind): no table is computed again, the shadow map
    // is.
    s.clouds.time_s += 10.0;
    let wind = ran(&mut wgpu, &s);
    assert_eq!(wind, ["march", "cloud-shadow", "composite"], "{wind:?}");
    // The camera turns: the aerial perspective's froxels follow it, the sky view does not.
    s.camera.yaw_deg += 30.0;
    let turned = ran(&mut wgpu, &s);
    assert_eq!(
        turned,
        ["aerial-perspective", "march", "cloud-shadow", "composite"],
        "{turned:?}"
    );
    // The camera flies level and straight: the air over every point of the ground is the
    // same, so no table is computed again; climbing, the sky view and the froxels are.
    s.camera.position[0] += 500.0;
    s.camera.position[2] -= 300.0;
    let flown = ran(&mut wgpu, &s);
    assert_eq!(flown, ["march", "cloud-shadow", "composite"], "{flown:?}");
    s.camera.position[1] += 200.0;
    let climbed = ran(&mut wgpu, &s);
    assert_eq!(
        climbed,
        [
            "sky-view-lut",
            "aerial-perspective",
            "march",
            "cloud-shadow",
            "composite"
        ],
        "{climbed:?}"
    );
    // The cloud layer's top moves up: the sky ambient is seen from its bottom, which stays.
    s.atmosphere.cloud_top_m += 300.0;
    let thicker = ran(&mut wgpu, &s);
    assert!(!thicker.contains(&"sky-ambient".to_string()), "{thicker:?}");
    // The cloud layer's bottom moves up: it sees other hemispheres of sky.
    s.atmosphere.cloud_bottom_m += 300.0;
    let higher = ran(&mut wgpu, &s);
    assert!(higher.contains(&"sky-ambient".to_string()), "{higher:?}");
    s.atmosphere.air.mie_scattering *= 4.0;
    let hazier = ran(&mut wgpu, &s);
    assert!(
        hazier.contains(&"transmittance-lut".to_string()),
        "{hazier:?}"
    );
    assert!(
        hazier.contains(&"multiscatter-lut".to_string()),
        "{hazier:?}"
    );
    assert!(hazier.contains(&"sky-ambient".to_string()), "{hazier:?}");
    let log = stratus_test_support::take_wgpu_log();
    assert!(log.is_empty(), "wgpu validation: {log:?}");
}

/// `noon` under an afternoon sun 24 degrees up, the camera turned toward it: cumulus between
/// the camera and the sun, their shadows falling toward it through the air; light shafts on
/// or off, and the clouds' coverage.
fn shafts_scene(shafts: bool, coverage: f64) -> Scene {
    let mut s = Scene::preset("noon").expect("preset").with_size(128, 72);
    s.sky.date_utc = "2026-09-21T15:00:00Z".parse().ok();
    s.camera.yaw_deg = 228.0;
    s.camera.pitch_deg = 6.0;
    s.clouds.coverage = coverage;
    s.atmosphere.light_shafts = shafts;
    s.validate().expect("a valid scene");
    s
}

/// Rec. 709 luma of every pixel of an 8-bit display image.
fn lumas(out: &FrameOutput) -> Vec<f64> {
    out.image
        .chunks_exact(4)
        .map(|p| 0.2126 * f64::from(p[0]) + 0.7152 * f64::from(p[1]) + 0.0722 * f64::from(p[2]))
        .collect()
}

/// Light shafts (composite.wgsl::light_shafts): where the clouds shade the air between the
/// camera and what it sees, the air scatters none of the sun's light. On the GPU and in the
/// CPU twin alike the shafts only ever take light away, take a visible amount where the
/// clouds' shadows lie in the air, take the same amount per pixel on both, and take none from
/// a clear sky. The display image only: the HDR output's shafts over the host's geometry
/// (`hdr_composite_physical`) have no CPU twin to hold them to.
#[test]
fn light_shafts_darken_the_shaded_air_alike_on_the_gpu_and_the_cpu() {
    stratus_test_support::record_wgpu_log();
    let noise = Arc::new(stratus_noise::NoiseSet::generate(&NoiseConfig::default()));
    let mut wgpu = wgpu_renderer();
    let mut cpu = stratus_reference::CpuBackend::default();
    let coverage = Scene::preset("noon").expect("preset").clouds.coverage;
    let darkening = |r: &mut dyn Backend| -> Vec<f64> {
        let on = lumas(&render(r, &shafts_scene(true, coverage), &noise));
        let off = lumas(&render(r, &shafts_scene(false, coverage), &noise));
        off.iter().zip(&on).map(|(off, on)| off - on).collect()
    };
    let gpu = darkening(&mut wgpu);
    let cpu = darkening(&mut cpu);
    let n = gpu.len() as f64;
    let lightest = gpu.iter().cloned().fold(f64::INFINITY, f64::min);
    let mean_gpu = gpu.iter().sum::<f64>() / n;
    let mean_cpu = cpu.iter().sum::<f64>() / n;
    let visible = gpu.iter().filter(|d| **d >= 3.0).count() as f64 / n;
    let apart = gpu
        .iter()
        .zip(&cpu)
        .map(|(g, c)| (g - c).abs())
        .sum::<f64>()
        / n;
    println!(
        "light shafts: mean darkening {mean_gpu:.3} (GPU) and {mean_cpu:.3} (CPU) of 255, \
         {:.1}% of pixels by 3 or more, least {lightest:.2}; GPU and CPU {apart:.3} apart \
         per pixel on average",
        visible * 100.0
    );
    // An 8-bit image rounds each channel by half a step, on and off.
    assert!(
        lightest >= -1.0,
        "a pixel is {lightest:.2} brighter with shafts"
    );
    assert!(
        visible >= 0.05 && mean_gpu >= 0.5,
        "the shafts are not visible: {:.1}% of pixels darker by 3, mean {mean_gpu:.3}",
        visible * 100.0
    );
    // Measured on lavapipe: 0.045 apart against a mean of 1.28 (3.5%; the CPU's f64 and the
    // 8-bit rounding of both).
    assert!(
        apart <= 0.1 * mean_gpu,
        "GPU and CPU shafts differ by {apart:.3} a pixel against a mean darkening of {mean_gpu:.3}"
    );
    // A clear sky: nothing shades the air, not one bit changes.
    let mut clear = |shafts| render(&mut wgpu, &shafts_scene(shafts, 0.0), &noise).image;
    let (on, off) = (clear(true), clear(false));
    assert!(on == off, "shafts darken a clear sky");
}

/// A dated sky's sun moves about 0.004 degrees a second. The sky-view and aerial-perspective
/// tables follow it once it has moved 1.7e-4 in some component of its direction (0.01 degrees,
/// their `tolerance` in wgsl/graph.toml) from where they were computed, not every frame: the
/// frames run them exactly when that says, and a frame on tables that lag by almost that much
/// is within one 8-bit step of one on fresh tables, at sunset, where the sky changes fastest
/// with the sun's angle.
#[test]
fn a_slowly_moving_sun_keeps_its_sky_tables_until_it_has_moved_a_hundredth_of_a_degree() {
    const TOLERANCE: f32 = 1.7e-4;
    stratus_test_support::record_wgpu_log();
    let noise = Arc::new(stratus_noise::NoiseSet::generate(&NoiseConfig::default()));
    let mut wgpu = wgpu_renderer();
    let base = Scene::preset("sunset").expect("preset").with_size(128, 72);
    assert!(base.sky.date_utc.is_some(), "sunset has a dated sky");
    let frame = |r: &mut stratus_backend_wgpu::Renderer, s: &Scene| -> (Vec<String>, Vec<u8>) {
        let plan = FramePlan::for_scene(s, false).expect("plan");
        let out = r
            .render(&FrameInput::new(&plan, s, &noise).with_readback(Readback {
                output: true,
                resources: Vec::new(),
            }))
            .expect("render");
        (
            out.timings.iter().map(|t| t.pass.clone()).collect(),
            out.image,
        )
    };
    let mut computed_at: Option<[f32; 3]> = None;
    let mut refreshed = 0;
    let mut stalest: Option<(f32, Scene, Vec<u8>)> = None;
    for k in 0..10 {
        let s = base.at_time(0.5 * f64::from(k));
        let sun = s.uniforms().sun_direction;
        let moved = computed_at.map_or(f32::INFINITY, |c| {
            (0..3).map(|i| (sun[i] - c[i]).abs()).fold(0.0, f32::max)
        });
        let (ran, image) = frame(&mut wgpu, &s);
        let expected = moved > TOLERANCE;
        for table in ["sky-view-lut", "aerial-perspective"] {
            assert_eq!(
                ran.contains(&table.to_string()),
                expected,
                "frame {k}: the sun moved {moved:.2e} since {table} was computed: {ran:?}"
            );
        }
        if expected {
            computed_at = Some(sun);
            refreshed += 1;
        } else if stalest.as_ref().is_none_or(|(m, _, _)| moved > *m) {
            stalest = Some((moved, s.clone(), image));
        }
    }
    // Five seconds of sun: the tables were computed first and followed it at least once, but
    // not every frame.
    assert!(
        (2..=5).contains(&refreshed),
        "the tables were computed {refreshed} times in 10 frames"
    );
    let (moved, s, lagging) = stalest.expect("a frame on lagging tables");
    let (_, fresh) = frame(&mut wgpu_renderer(), &s);
    let worst = lagging
        .iter()
        .zip(&fresh)
        .map(|(a, b)| a.abs_diff(*b))
        .max()
        .unwrap_or(0);
    println!("tables lagging the sun by {moved:.2e}: at most {worst} of 255 off fresh tables");
    assert!(
        worst <= 1,
        "tables lagging by {moved:.2e} are {worst} of 255 off"
    );
}
