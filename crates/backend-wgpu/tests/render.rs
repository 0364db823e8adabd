//! wgpu backend tests: every preset renders under validation (wgpu's and the Vulkan
//! validation layer's; any error or warning they log fails the test), images look like clouds
//! by simple measures, renders are deterministic, and the statistics are complete.

use std::sync::{Arc, Mutex, OnceLock};

use stratus_backend_wgpu::{Api, Options, Renderer};
use stratus_graph::{FrameInput, FrameOutput, FramePlan, Program};
use stratus_noise::{NoiseConfig, NoiseSet, ShapeSize};
use stratus_scene::{Scene, ShapeTexture};
use stratus_test_support::{assert_no_wgpu_messages, record_wgpu_log};

fn noise(scene: &Scene) -> &'static Arc<NoiseSet> {
    static THESIS: OnceLock<Arc<NoiseSet>> = OnceLock::new();
    assert_eq!(scene.noise.seed, 0, "tests share the seed-0 noise");
    assert_eq!(scene.noise.shape_texture, ShapeTexture::Thesis);
    THESIS.get_or_init(|| {
        Arc::new(NoiseSet::generate(&NoiseConfig {
            seed: 0,
            shape: ShapeSize::Thesis,
            ..NoiseConfig::default()
        }))
    })
}

/// One renderer per test binary and API: creating devices is the slow part on lavapipe.
fn with_renderer<R>(api: Api, f: impl FnOnce(&mut Renderer) -> R) -> R {
    static VK: OnceLock<Mutex<Renderer>> = OnceLock::new();
    static GL: OnceLock<Mutex<Renderer>> = OnceLock::new();
    record_wgpu_log();
    let cell = if api == Api::Vulkan { &VK } else { &GL };
    let m = cell.get_or_init(|| {
        Mutex::new(
            Renderer::new(Options {
                api,
                validation: true,
            })
            .unwrap_or_else(|e| panic!("{e}")),
        )
    });
    let mut r = m.lock().unwrap_or_else(|e| e.into_inner());
    f(&mut r)
}

fn render(api: Api, scene: &Scene, stats: bool) -> FrameOutput {
    let plan = FramePlan::for_scene(scene, stats).unwrap();
    let out = with_renderer(api, |r| {
        r.render(&FrameInput::new(&plan, scene, noise(scene)))
    })
    .unwrap_or_else(|e| panic!("{e}"));
    assert_no_wgpu_messages();
    out
}

fn preset(name: &str, w: u32, h: u32) -> Scene {
    Scene::preset(name).unwrap().with_size(w, h)
}

/// Fraction of pixels (in rows `rows`) whose transmittance is below `t`.
fn cloud_fraction(f: &FrameOutput, rows: std::ops::Range<u32>, t: f32) -> f64 {
    let w = f.width as usize;
    let n = rows.len() * w;
    let covered = rows
        .flat_map(|y| (0..w).map(move |x| (y as usize * w + x) * 4 + 3))
        .filter(|&i| f.radiance[i] < t)
        .count();
    covered as f64 / n as f64
}

fn assert_sane(name: &str, f: &FrameOutput) {
    assert_eq!(f.radiance.len(), (f.width * f.height * 4) as usize);
    for (i, px) in f.radiance.chunks(4).enumerate() {
        assert!(
            px.iter().all(|v| v.is_finite()),
            "{name}: non-finite at pixel {i}: {px:?}"
        );
        assert!(
            (0.0..=1.0).contains(&px[3]),
            "{name}: transmittance {} at pixel {i}",
            px[3]
        );
        assert!(
            px[..3].iter().all(|v| *v >= 0.0),
            "{name}: negative radiance at pixel {i}"
        );
    }
    assert!(
        f.depth.iter().all(|d| d.is_finite() && *d >= 0.0),
        "{name}: bad depth"
    );
    // The march and the composite, and under the physical sky the cloud-shadow map and its
    // six tables unless a frame before computed them for the same air, sun and camera; not the
    // present pass, which runs only into a host's target.
    let passes = if name_is_physical(name) { 3..=9 } else { 2..=2 };
    assert!(
        passes.contains(&f.timings.len()),
        "{name}: a time for every pass that ran: {:?}",
        f.timings
    );
}

fn name_is_physical(name: &str) -> bool {
    Scene::preset(name).is_ok_and(|s| s.atmosphere.sky.is_physical())
}

#[test]
fn every_preset_renders_under_validation() {
    for p in stratus_scene::presets() {
        let f = render(Api::Vulkan, &preset(p.name, 96, 54), false);
        assert_sane(p.name, &f);
    }
}

/// Red over blue of the sunlit clouds: the brightest tenth (by luminance) of the pixels whose
/// transmittance is below 0.5, in the march's radiance (before the air in front of them).
fn sunlit_red_over_blue(f: &FrameOutput) -> f64 {
    let mut lit: Vec<[f32; 3]> = f
        .radiance
        .chunks(4)
        .filter(|p| p[3] < 0.5)
        .map(|p| [p[0], p[1], p[2]])
        .collect();
    assert!(lit.len() > 100, "too few cloud pixels: {}", lit.len());
    let lum = |p: &[f32; 3]| 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
    lit.sort_by(|a, b| lum(b).total_cmp(&lum(a)));
    let top = &lit[..lit.len() / 10];
    let red: f64 = top.iter().map(|p| f64::from(p[0])).sum();
    let blue: f64 = top.iter().map(|p| f64::from(p[2])).sum();
    red / blue
}

/// The sun's white light reddens on its way through the air: at sunset (the sun 4 degrees up)
/// the sunlit clouds are far warmer than at noon, with the same illuminance at the top of the
/// atmosphere. Measured: red over blue 4.21 at sunset, 0.995 at noon.
#[test]
fn sunset_clouds_are_warmer_than_at_noon() {
    let sunset = render(Api::Vulkan, &preset("sunset", 128, 72), false);
    let noon = render(Api::Vulkan, &preset("noon", 128, 72), false);
    let (s, n) = (sunlit_red_over_blue(&sunset), sunlit_red_over_blue(&noon));
    eprintln!("sunlit clouds, red over blue: sunset {s:.3}, noon {n:.3}");
    assert!(s > 2.0 * n, "sunset {s:.3} against noon {n:.3}");
}

/// Night: the moon's disc is the brightest thing in the image, where its direction projects,
/// stars dot the clear sky, and nothing is NaN.
#[test]
fn night_shows_the_moon_and_stars() {
    let scene = preset("night", 256, 144);
    let f = render(Api::Vulkan, &scene, false);
    assert_sane("night", &f);
    let u = scene.uniforms();
    let v3 = |a: [f32; 3]| a.map(f64::from);
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let moon = v3(u.moon_direction);
    let (fwd, right, up) = (v3(u.camera_forward), v3(u.camera_right), v3(u.camera_up));
    let (tan_half, aspect) = (f64::from(u.tan_half_fov), f64::from(u.aspect));
    let z = dot(moon, fwd);
    assert!(z > 0.0, "the moon is behind the camera");
    let ndc = [
        dot(moon, right) / z / (tan_half * aspect),
        -dot(moon, up) / z / tan_half,
    ];
    let at = [
        (ndc[0] + 1.0) / 2.0 * 256.0 - 0.5,
        (ndc[1] + 1.0) / 2.0 * 144.0 - 0.5,
    ];
    // Display luminance of every pixel.
    let lum: Vec<u32> = f
        .image
        .chunks(4)
        .map(|p| u32::from(p[0]) + u32::from(p[1]) + u32::from(p[2]))
        .collect();
    let brightest = (0..lum.len())
        .max_by_key(|&i| (lum[i], usize::MAX - i))
        .unwrap();
    let (bx, by) = ((brightest % 256) as f64, (brightest / 256) as f64);
    eprintln!(
        "moon projects to ({:.1}, {:.1}); the brightest pixel is ({bx}, {by})",
        at[0], at[1]
    );
    assert!(
        (bx - at[0]).abs() <= 2.0 && (by - at[1]).abs() <= 2.0,
        "the brightest pixel ({bx}, {by}) is not the moon's ({:.1}, {:.1})",
        at[0],
        at[1]
    );
    // Stars: peaks of the display image in the clear sky (transmittance above 0.99 over 5x5
    // pixels) away from the moon. Measured: 12 (the preset's clouds ten minutes on, as the
    // moon stands in a gap).
    let clear = |x: usize, y: usize| f.radiance[(y * 256 + x) * 4 + 3] > 0.99;
    let mut stars = 0;
    for y in 2..142 {
        for x in 2..254 {
            if (x as f64 - at[0]).hypot(y as f64 - at[1]) < 8.0 {
                continue;
            }
            let around: Vec<(usize, usize)> = (y - 2..=y + 2)
                .flat_map(|j| (x - 2..=x + 2).map(move |i| (i, j)))
                .filter(|&(i, j)| (i, j) != (x, y))
                .collect();
            if !around.iter().all(|&(i, j)| clear(i, j)) || !clear(x, y) {
                continue;
            }
            let l = lum[y * 256 + x];
            let ring_max = around.iter().map(|&(i, j)| lum[j * 256 + i]).max().unwrap();
            // A smooth sky has no such peak: a star stands 6 levels (of r + g + b) above
            // every pixel around it.
            if l >= ring_max + 6 {
                stars += 1;
            }
        }
    }
    eprintln!("{stars} stars in the clear sky");
    assert!(stars >= 8, "{stars} stars");
}

#[test]
fn cumulus_noon_has_clouds_and_sky() {
    let f = render(Api::Vulkan, &preset("cumulus-noon", 128, 72), false);
    let clouds = cloud_fraction(&f, 0..72, 0.9);
    assert!((0.1..=0.9).contains(&clouds), "cloud fraction {clouds}");
    // Not flat: the display image has both bright cloud and darker sky pixels.
    let lum: Vec<u8> = f.image.chunks(4).map(|p| p[1]).collect();
    let (lo, hi) = (lum.iter().min().unwrap(), lum.iter().max().unwrap());
    assert!(hi - lo > 60, "display image nearly flat: {lo}..{hi}");
}

#[test]
fn above_clouds_looks_down_on_cloud_tops() {
    let f = render(Api::Vulkan, &preset("above-clouds", 128, 72), false);
    let lower = cloud_fraction(&f, 36..72, 0.5);
    assert!(lower > 0.5, "lower half: only {lower} covered by cloud");
    // The camera is above the layer: the clouds it sees lie below it.
    let cam = Scene::preset("above-clouds").unwrap().camera.position[1];
    assert!(
        cam > Scene::preset("above-clouds")
            .unwrap()
            .atmosphere
            .cloud_top_m
    );
}

#[test]
fn renders_are_deterministic() {
    let scene = preset("cumulus-noon", 64, 36);
    let a = render(Api::Vulkan, &scene, false);
    let b = render(Api::Vulkan, &scene, false);
    let bits = |f: &FrameOutput| f.radiance.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&a), bits(&b));
    assert_eq!(a.image, b.image);
}

#[test]
fn statistics_have_every_counter_and_add_up() {
    let scene = preset("cumulus-noon", 64, 36);
    let f = render(Api::Vulkan, &scene, true);
    let s = f.stats.expect("stats plan gathers counters");
    let counters = Program::embedded().unwrap().graph.counter_names();
    assert_eq!(counters.len(), 9);
    for c in &counters {
        assert!(s.contains_key(c), "missing counter {c}");
    }
    assert_eq!(s["pixels"], 64 * 36);
    assert_eq!(
        s["marched_pixels"] + s["exit_missed_layer"] + s["exit_ground"],
        s["pixels"]
    );
    assert!(s["view_steps"] >= s["marched_pixels"]);
    assert!(s["density_evaluations"] > 0 && s["light_samples"] > 0 && s["detail_evaluations"] > 0);
    // The statistics variant draws the same image as the normal one.
    let normal = render(Api::Vulkan, &scene, false);
    assert_eq!(normal.image, f.image);
}

#[test]
fn gl_backend_renders() {
    let scene = preset("cumulus-noon", 64, 36);
    let f = render(Api::Gl, &scene, false);
    assert_sane("cumulus-noon on GL", &f);
    let vk = render(Api::Vulkan, &scene, false);
    // Same clouds, up to rounding of a different compiler: compare the display images loosely
    // here (the conformance suite holds the paths to measured thresholds).
    let diff = f
        .image
        .iter()
        .zip(&vk.image)
        .map(|(a, b)| a.abs_diff(*b) as f64)
        .sum::<f64>()
        / f.image.len() as f64;
    assert!(
        diff < 4.0,
        "GL and Vulkan images differ by {diff} on average"
    );
}
