//! wgpu backend tests: every preset renders under validation (wgpu's and the Vulkan
//! validation layer's; any error or warning they log fails the test), images look like clouds
//! by simple measures, renders are deterministic, and the statistics are complete.

use std::sync::{Arc, Mutex, OnceLock};

use stratus_backend_wgpu::{Api, Options, Renderer};
use stratus_graph::output::LUMA;
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

/// The display image's brightest pixel (the sum of its channels; the first in row order on a
/// tie), as (x, y).
fn brightest_pixel(f: &FrameOutput) -> (f64, f64) {
    let lum: Vec<u32> = f
        .image
        .chunks(4)
        .map(|p| u32::from(p[0]) + u32::from(p[1]) + u32::from(p[2]))
        .collect();
    let i = (0..lum.len())
        .max_by_key(|&i| (lum[i], usize::MAX - i))
        .unwrap();
    let w = f.width as usize;
    ((i % w) as f64, (i / w) as f64)
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
    // present pass, which runs only into a host's target. The stylised presets add their
    // Kuwahara filter; a rainbow from its table adds the table, unless a frame before computed
    // it for the same drops and sun (tests share one renderer, in no fixed order).
    let styled = usize::from(Scene::preset(name).is_ok_and(|s| s.post.kuwahara));
    let bow_table = usize::from(Scene::preset(name).is_ok_and(|s| s.rainbow.uses_table()));
    let passes = if name_is_physical(name) {
        3 + styled..=9 + styled + bow_table
    } else {
        2 + styled..=2 + styled
    };
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
    let (bx, by) = brightest_pixel(&f);
    // Display luminance of every pixel, for the stars below.
    let lum: Vec<u32> = f
        .image
        .chunks(4)
        .map(|p| u32::from(p[0]) + u32::from(p[1]) + u32::from(p[2]))
        .collect();
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
    // pixels) away from the moon. Measured: 8 with the catalogue's stars (12 with the
    // procedural ones before them), the bound about two thirds of it as before (the preset's
    // clouds ten minutes on, as the moon stands in a gap).
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
    assert!(stars >= 5, "{stars} stars");
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

/// The display image's luminance (Rec. 709 weights of its 8-bit levels, 0-1), row-major.
fn display_luminance(f: &FrameOutput) -> Vec<f64> {
    f.image
        .chunks(4)
        .map(|p| (0..3).map(|c| LUMA[c] * f64::from(p[c])).sum::<f64>() / 255.0)
        .collect()
}

/// The gradient's magnitude (central differences) of a `w` x `h` image at every inner pixel
/// (0 on the border).
fn gradient(l: &[f64], w: usize, h: usize) -> Vec<f64> {
    let mut g = vec![0.0; w * h];
    for y in 1..h - 1 {
        for x in 1..w - 1 {
            let gx = l[y * w + x + 1] - l[y * w + x - 1];
            let gy = l[(y + 1) * w + x] - l[(y - 1) * w + x];
            g[y * w + x] = 0.5 * (gx * gx + gy * gy).sqrt();
        }
    }
    g
}

/// The stylised presets' Kuwahara filter does what it is for (seed 001's watercolour look):
/// inside the unfiltered image's flat regions (the half of its pixels whose 5x5
/// neighbourhood's largest gradient is least), the fine texture's variance (the mean square of
/// the Laplacian, which a smooth gradient does not have) falls; at the strongest edges (the
/// top 1% of gradients) the filtered image keeps at least 80% of the gradient (the largest
/// within a pixel, as the filter may move an edge by one). Rendered at 256x144 with the
/// preset's radius (1.2 texels there), and at three times it for the flattening alone: a
/// window that wide also erases features narrower than itself, the distant clouds' thin bands
/// at the horizon among them, whose edges are the image's strongest.
#[test]
fn the_kuwahara_filter_flattens_regions_and_keeps_edges() {
    let (w, h) = (256usize, 144usize);
    let styled = preset("kuwahara-day", w as u32, h as u32);
    assert!(styled.post.kuwahara);
    let mut plain = styled.clone();
    plain.post.kuwahara = false;
    let before = display_luminance(&render(Api::Vulkan, &plain, false));
    let g0 = gradient(&before, w, h);
    let inner = |i: usize| {
        let (x, y) = (i % w, i / w);
        x >= 3 && y >= 3 && x < w - 3 && y < h - 3
    };
    let around = |g: &[f64], i: usize, r: i64| {
        let (x, y) = ((i % w) as i64, (i / w) as i64);
        let mut out = Vec::new();
        for dy in -r..=r {
            for dx in -r..=r {
                out.push(g[((y + dy) as usize) * w + (x + dx) as usize]);
            }
        }
        out
    };
    let mut flatness: Vec<(f64, usize)> = (0..w * h)
        .filter(|&i| inner(i))
        .map(|i| (around(&g0, i, 2).into_iter().fold(0.0, f64::max), i))
        .collect();
    flatness.sort_by(|a, b| a.0.total_cmp(&b.0));
    let flat: Vec<usize> = flatness[..flatness.len() / 2].iter().map(|p| p.1).collect();
    let mut strength: Vec<(f64, usize)> = (0..w * h)
        .filter(|&i| inner(i))
        .map(|i| (g0[i], i))
        .collect();
    strength.sort_by(|a, b| b.0.total_cmp(&a.0));
    let edges: Vec<usize> = strength[..strength.len() / 100]
        .iter()
        .map(|p| p.1)
        .collect();
    let flat_variance = |l: &[f64]| {
        flat.iter()
            .map(|&i| {
                let lap = 4.0 * l[i] - l[i - 1] - l[i + 1] - l[i - w] - l[i + w];
                lap * lap
            })
            .sum::<f64>()
            / flat.len() as f64
    };
    let v0 = flat_variance(&before);
    let e0 = edges.iter().map(|&i| g0[i]).sum::<f64>() / edges.len() as f64;
    for scale in [1.0, 3.0] {
        let mut s = styled.clone();
        s.post.kuwahara_radius *= scale;
        let after = display_luminance(&render(Api::Vulkan, &s, false));
        let g1 = gradient(&after, w, h);
        let v1 = flat_variance(&after);
        let e1 = edges
            .iter()
            .map(|&i| around(&g1, i, 1).into_iter().fold(0.0, f64::max))
            .sum::<f64>()
            / edges.len() as f64;
        eprintln!(
            "kuwahara radius x{scale}: flat regions' texture variance {v0:.3e} -> {v1:.3e} ({:.2}), strongest edges' gradient {e0:.4} -> {e1:.4} ({:.2})",
            v1 / v0,
            e1 / e0
        );
        assert!(
            v1 < 0.8 * v0,
            "x{scale}: the flat regions' texture variance went from {v0:.3e} to {v1:.3e}"
        );
        if scale == 1.0 {
            assert!(
                e1 >= 0.8 * e0,
                "x{scale}: the strongest edges' gradient went from {e0:.4} to {e1:.4}"
            );
        }
    }
}

/// Each display pixel's angle from the antisolar point (degrees) and whether its view ray is
/// above the horizon, as the shaders' `view_ray` casts it.
fn antisolar_angles(scene: &Scene) -> Vec<(f64, bool)> {
    let [w, h] = scene.camera.resolution;
    let (fw, r, u) = scene.camera_basis();
    let tan_half = (scene.camera.fov_y_deg.to_radians() / 2.0).tan();
    let aspect = f64::from(w) / f64::from(h);
    let light = scene.key_light().0;
    let mut out = Vec::new();
    for y in 0..h {
        for x in 0..w {
            let nx = (f64::from(x) + 0.5) / f64::from(w) * 2.0 - 1.0;
            let ny = (f64::from(y) + 0.5) / f64::from(h) * 2.0 - 1.0;
            let d: [f64; 3] = std::array::from_fn(|c| {
                fw[c] + r[c] * nx * tan_half * aspect - u[c] * ny * tan_half
            });
            let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            let cos = -(d[0] * light[0] + d[1] * light[1] + d[2] * light[2]) / n;
            out.push((cos.clamp(-1.0, 1.0).acos().to_degrees(), d[1] > 0.0));
        }
    }
    out
}

/// The rainbow's display-image difference (the scene with its rain's bows less the same with
/// moisture 0), red and blue, averaged in 0.25-degree rings around the antisolar point over
/// the pixels above the horizon: `(ring's inner angle, red, blue)`.
fn bow_rings(scene: &Scene) -> Vec<(f64, f64, f64)> {
    let mut dry = scene.clone();
    dry.rainbow.moisture = 0.0;
    let wet = render(Api::Vulkan, scene, false);
    let dry = render(Api::Vulkan, &dry, false);
    let mut rings = vec![(0.0, 0.0, 0usize); 360];
    for (i, (phi, sky)) in antisolar_angles(scene).into_iter().enumerate() {
        let ring = (phi * 4.0) as usize;
        if !sky || ring >= rings.len() {
            continue;
        }
        let d = |c: usize| f64::from(wet.image[4 * i + c]) - f64::from(dry.image[4 * i + c]);
        rings[ring].0 += d(0);
        rings[ring].1 += d(2);
        rings[ring].2 += 1;
    }
    rings
        .into_iter()
        .enumerate()
        .filter(|r| r.1.2 > 0)
        .map(|(k, (red, blue, n))| (k as f64 / 4.0, red / n as f64, blue / n as f64))
        .collect()
}

/// The ring in `range` (degrees) where `channel` of the bows peaks.
fn peak(
    rings: &[(f64, f64, f64)],
    range: std::ops::Range<f64>,
    channel: fn(&(f64, f64, f64)) -> f64,
) -> f64 {
    rings
        .iter()
        .filter(|r| range.contains(&r.0))
        .max_by(|a, b| channel(a).total_cmp(&channel(b)))
        .map(|r| r.0 + 0.125)
        .expect("rings in range")
}

/// The rainbow preset's bows where the optics puts them (Descartes's angles, Airy's widths):
/// the primary's red ring outside its blue one, both 40-43 degrees from the antisolar point,
/// and the secondary's order reversed at 50-54 degrees, from the Lee-diagram table and from
/// the cheap three-wavelength path alike.
#[test]
fn the_rainbow_bows_lie_at_their_angles_in_their_colour_order() {
    let mut scene = preset("rainbow", 256, 144);
    assert!(scene.rainbow.moisture > 0.0 && scene.rainbow.lee_diagram);
    for lee in [true, false] {
        scene.rainbow.lee_diagram = lee;
        let rings = bow_rings(&scene);
        let red = |r: &(f64, f64, f64)| r.1;
        let blue = |r: &(f64, f64, f64)| r.2;
        let (r1, b1) = (
            peak(&rings, 38.0..46.0, red),
            peak(&rings, 38.0..46.0, blue),
        );
        let (r2, b2) = (
            peak(&rings, 48.0..56.0, red),
            peak(&rings, 48.0..56.0, blue),
        );
        let top = rings.iter().map(|r| r.1.max(r.2)).fold(0.0, f64::max);
        eprintln!(
            "lee_diagram {lee}: primary red {r1:.2} blue {b1:.2}, secondary red {r2:.2} blue {b2:.2} degrees; strongest ring +{top:.1} levels"
        );
        assert!(top >= 4.0, "the bows add only {top:.1} levels");
        assert!(
            r1 > b1 && (40.0..=43.0).contains(&r1) && (40.0..=43.0).contains(&b1),
            "primary: red {r1}, blue {b1}"
        );
        assert!(
            r2 < b2 && (50.0..=54.0).contains(&r2) && (50.0..=54.0).contains(&b2),
            "secondary: red {r2}, blue {b2}"
        );
    }
}

/// No bow in the sky without its light: with the sun above 42 degrees no primary (it lies
/// below the horizon; the secondary, at 51 degrees, still shows, as in nature, until the sun
/// passes 51 and its outer light fades), with a sun at 75 degrees none at all, and none with
/// moisture 0 or without rain (no precipitating layer). A bow shows as a pixel above the
/// horizon that differs from the same scene's with moisture 0.
#[test]
fn the_rainbow_is_absent_under_a_high_sun_dry_air_or_no_rain() {
    let base = preset("rainbow", 128, 72);
    let mut high_sun = base.clone();
    high_sun.sky.date_utc = "2026-09-21T11:30:00Z".parse().ok();
    assert!(high_sun.sun_elevation_deg() > 42.0);
    let mut tropical_noon = high_sun.clone();
    tropical_noon.sky.latitude_deg = Some(15.0);
    assert!(tropical_noon.sun_elevation_deg() > 74.0);
    let mut no_rain = base.clone();
    no_rain.clouds.precipitation = 0.0;
    let mut bone_dry = base.clone();
    bone_dry.rainbow.moisture = 0.0;
    for (what, scene, within_deg) in [
        ("a sun above 42 degrees (the primary)", high_sun, 46.0),
        ("a sun at 75 degrees", tropical_noon, 180.0),
        ("no rain", no_rain, 180.0),
        ("moisture 0", bone_dry, 180.0),
    ] {
        let mut dry = scene.clone();
        dry.rainbow.moisture = 0.0;
        let a = render(Api::Vulkan, &scene, false);
        let b = render(Api::Vulkan, &dry, false);
        let angles = antisolar_angles(&scene);
        let differ = (0..angles.len())
            .filter(|&i| angles[i].1 && angles[i].0 < within_deg)
            .filter(|&i| a.image[4 * i..4 * i + 4] != b.image[4 * i..4 * i + 4])
            .count();
        assert_eq!(differ, 0, "{what}: {differ} sky pixels show a bow");
    }
    // And the base scene does show one (the comparison can fail).
    let mut dry = base.clone();
    dry.rainbow.moisture = 0.0;
    assert_ne!(
        render(Api::Vulkan, &base, false).image,
        render(Api::Vulkan, &dry, false).image
    );
}

/// Where the sun's centre falls on `scene`'s image, in pixels (continuous, y down), from the
/// scene's camera alone; `None` with the sun behind the camera.
fn sun_on_image(scene: &Scene) -> Option<[f64; 2]> {
    sun_on_image_of(scene, scene.key_light().0)
}

/// Where world direction `sun` falls on `scene`'s image (as [`sun_on_image`]).
fn sun_on_image_of(scene: &Scene, sun: [f64; 3]) -> Option<[f64; 2]> {
    let [w, h] = scene.camera.resolution;
    let (fw, r, u) = scene.camera_basis();
    let tan_half = (scene.camera.fov_y_deg.to_radians() / 2.0).tan();
    let aspect = f64::from(w) / f64::from(h);
    let dot = |a: [f64; 3]| a[0] * sun[0] + a[1] * sun[1] + a[2] * sun[2];
    let z = dot(fw);
    (z > 0.0).then(|| {
        [
            (dot(r) / (z * tan_half * aspect) * 0.5 + 0.5) * f64::from(w),
            (-dot(u) / (z * tan_half) * 0.5 + 0.5) * f64::from(h),
        ]
    })
}

/// The lens flare's display-image difference (the scene less the same without flare), summed
/// over the channels, per pixel.
fn flare_difference(scene: &Scene) -> Vec<f64> {
    let mut plain = scene.clone();
    plain.post.lens_flare_intensity = 0.0;
    let a = render(Api::Vulkan, scene, false).image;
    let b = render(Api::Vulkan, &plain, false).image;
    (0..a.len() / 4)
        .map(|i| {
            (0..3)
                .map(|c| f64::from(a[4 * i + c]) - f64::from(b[4 * i + c]))
                .sum()
        })
        .collect()
}

/// The `lens-flare` preset's flare brightens the image (a flare adds light); its ghosts lie
/// along the line from the sun's image through the image's centre, on both sides of the centre,
/// and its halo on a ring about the centre, on the sun's side; turned away from the sun, or with a closed deck between the camera and the sun, the image is
/// the flareless one bit for bit.
#[test]
fn the_lens_flare_lies_on_the_sun_axis_and_only_while_the_sun_is_seen() {
    let scene = preset("lens-flare", 192, 108);
    let [w, h] = scene.camera.resolution;
    let sun = sun_on_image(&scene).expect("the preset faces the sun");
    assert!(
        sun[0] > 0.0 && sun[0] < f64::from(w) && sun[1] > 0.0 && sun[1] < f64::from(h),
        "the preset's sun {sun:?} is on screen"
    );
    let diff = flare_difference(&scene);
    let (cx, cy) = (f64::from(w) / 2.0, f64::from(h) / 2.0);
    let axis = [sun[0] - cx, sun[1] - cy];
    let axis_len = (axis[0] * axis[0] + axis[1] * axis[1]).sqrt();
    // Per pixel: distance from the axis and from the centre (image heights), position along
    // the axis (1 at the sun) and the cosine between the pixel's and the sun's directions
    // from the centre.
    let place = |i: usize| {
        let (x, y) = (
            (i as u32 % w) as f64 + 0.5 - cx,
            (i as u32 / w) as f64 + 0.5 - cy,
        );
        let hf = f64::from(h);
        let off = (x * axis[1] - y * axis[0]).abs() / axis_len / hf;
        let along = (x * axis[0] + y * axis[1]) / (axis_len * axis_len);
        let radius = (x * x + y * y).sqrt() / hf;
        let cos = (x * axis[0] + y * axis[1]) / (axis_len * (x * x + y * y).sqrt().max(1e-9));
        (off, along, radius, cos)
    };
    let darker = diff.iter().filter(|&&d| d < 0.0).count();
    assert_eq!(darker, 0, "the flare darkened {darker} pixels");
    let sum = |keep: &dyn Fn((f64, f64, f64, f64)) -> bool| -> f64 {
        (0..diff.len())
            .filter(|&i| keep(place(i)))
            .map(|i| diff[i].max(0.0))
            .sum()
    };
    // The halo's band: its ring (0.42 image heights), red and blue fringes 0.01 either side,
    // and six widths (0.012) of its profile beyond them.
    let in_band = |p: (f64, f64, f64, f64)| (p.2 - 0.42).abs() < 0.01 + 6.0 * 0.012;
    let ghosts = sum(&|p| !in_band(p));
    // The largest ghost's reach (1.25 x its circumradius 0.11) bounds a ghost's distance from
    // the axis.
    let by_axis = sum(&|p| !in_band(p) && p.0 < 0.14);
    let across = sum(&|p| !in_band(p) && p.0 < 0.14 && p.1 < -0.5);
    // The halo away from the ghosts: on the ring's half toward the sun, none on the other.
    let sun_side = sum(&|p| in_band(p) && p.0 >= 0.14 && p.3 > 0.0);
    let far_side = sum(&|p| in_band(p) && p.0 >= 0.14 && p.3 <= 0.0);
    println!(
        "flare: ghosts {ghosts:.0} levels ({:.3} within 0.14 image heights of the axis, {:.3} \
         of them past the centre); halo off the axis: {sun_side:.0} levels on the sun's \
         side, {far_side:.0} on the other",
        by_axis / ghosts,
        across / ghosts,
    );
    assert!(ghosts > 200.0, "the ghosts add {ghosts} levels in all");
    assert!(
        by_axis / ghosts > 0.9,
        "{:.3} of the ghosts lie by the axis",
        by_axis / ghosts
    );
    assert!(
        across / ghosts > 0.2,
        "{:.3} of the ghosts lie past the centre",
        across / ghosts
    );
    assert!(sun_side > 100.0, "the halo adds {sun_side} levels");
    assert_eq!(far_side, 0.0, "the halo shows away from the sun");

    // Turned away: the sun's disc off screen (to the left of the image).
    let mut away = scene.clone();
    away.camera.yaw_deg += 100.0;
    let off = sun_on_image(&away).is_none_or(|s| s[0] < 0.0 || s[0] > f64::from(w));
    assert!(off, "turned 100 degrees, the sun leaves the image");
    assert!(
        flare_difference(&away).iter().all(|&d| d == 0.0),
        "flare with the sun off screen"
    );

    // A closed deck in front of the sun.
    let mut overcast = scene.clone();
    overcast.clouds.coverage = 1.0;
    let diff = flare_difference(&overcast);
    let flared = diff.iter().filter(|&&d| d != 0.0).count();
    assert_eq!(flared, 0, "{flared} pixels flare through a closed deck");
}

/// The world direction of the J2000 unit vector `v` in `scene`'s sky: its uniforms' celestial
/// axes (the renderer's own rotation, from the date and place).
fn celestial_world(scene: &Scene, v: [f64; 3]) -> [f64; 3] {
    let u = scene.uniforms();
    let axes = [u.celestial_x, u.celestial_y, u.celestial_z].map(|a| a.map(f64::from));
    std::array::from_fn(|i| axes[0][i] * v[0] + axes[1][i] * v[1] + axes[2][i] * v[2])
}

/// The unit view ray through the centre of `scene`'s pixel (x, y).
fn pixel_ray(scene: &Scene, x: f64, y: f64) -> [f64; 3] {
    let [w, h] = scene.camera.resolution;
    let (fw, r, u) = scene.camera_basis();
    let tan_half = (scene.camera.fov_y_deg.to_radians() / 2.0).tan();
    let aspect = f64::from(w) / f64::from(h);
    let nx = (x + 0.5) / f64::from(w) * 2.0 - 1.0;
    let ny = (y + 0.5) / f64::from(h) * 2.0 - 1.0;
    let d: [f64; 3] =
        std::array::from_fn(|c| fw[c] + r[c] * nx * tan_half * aspect - u[c] * ny * tan_half);
    let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    d.map(|x| x / n)
}

/// `scene` looking at world direction `d` (yaw clockwise from north, pitch up), clear.
fn looking_at(mut scene: Scene, d: [f64; 3]) -> Scene {
    scene.camera.yaw_deg = d[0].atan2(d[2]).to_degrees();
    scene.camera.pitch_deg = d[1].asin().to_degrees();
    scene.clouds.coverage = 0.0;
    scene
}

fn angle_deg(a: [f64; 3], b: [f64; 3]) -> f64 {
    (a[0] * b[0] + a[1] * b[1] + a[2] * b[2])
        .clamp(-1.0, 1.0)
        .acos()
        .to_degrees()
}

/// The Milky Way's brightest direction on screen is the galactic centre's, within 5 degrees:
/// a clear moonless night (15 July 2026, 25 S 25 E, the centre 69 degrees up in the east), the
/// camera toward where the renderer's sky puts the centre, the display image with the Milky
/// Way less the same without it (no stars in either), smoothed over 15x15 pixels.
#[test]
fn the_milky_way_is_brightest_toward_the_galactic_centre() {
    let mut base = preset("night", 160, 90);
    base.sky.date_utc = "2026-07-15T19:00:00Z".parse().ok();
    base.sky.latitude_deg = Some(-25.0);
    base.sky.longitude_deg = Some(25.0);
    base.camera.fov_y_deg = 60.0;
    base.night.star_intensity = 0.0;
    let g = stratus_astro::celestial::equatorial_to_galactic();
    let centre = celestial_world(&base, g[0]);
    assert!(
        centre[1] > 0.5,
        "the centre stands {} up",
        centre[1].asin().to_degrees()
    );
    let scene = looking_at(base, centre);
    let mut dark = scene.clone();
    dark.night.milky_way_intensity = 0.0;
    let (a, b) = (
        render(Api::Vulkan, &scene, false),
        render(Api::Vulkan, &dark, false),
    );
    let (w, h) = (160usize, 90usize);
    let diff: Vec<f64> = (0..w * h)
        .map(|i| {
            (0..3)
                .map(|c| f64::from(a.image[4 * i + c]) - f64::from(b.image[4 * i + c]))
                .sum()
        })
        .collect();
    let mut best = (f64::MIN, 0, 0);
    for y in 7..h - 7 {
        for x in 7..w - 7 {
            let mut s = 0.0;
            for j in y - 7..=y + 7 {
                for i in x - 7..=x + 7 {
                    s += diff[j * w + i];
                }
            }
            if s > best.0 {
                best = (s, x, y);
            }
        }
    }
    let (total, x, y) = best;
    let off = angle_deg(pixel_ray(&scene, x as f64, y as f64), centre);
    println!("the Milky Way is brightest at ({x}, {y}), {off:.2} degrees from the galactic centre");
    assert!(
        total > 15.0 * 15.0 * 3.0,
        "the Milky Way adds only {total} levels there"
    );
    assert!(
        off < 5.0,
        "brightest {off} degrees from the galactic centre"
    );
}

/// The catalogue's stars shine where the sky puts them: on the README's Milky Way night
/// (12 August 2026, 22:00 UTC, 46 N 8 E), looking at Vega, the brightest pixel is within a
/// pixel and a half of where Vega's J2000 position projects through the renderer's rotation
/// (itself within 0.02 degrees of astropy's, crates/astro/tests/stars.rs).
#[test]
fn catalogue_stars_shine_where_the_sky_puts_them() {
    let mut base = preset("night", 256, 144);
    base.sky.date_utc = "2026-08-12T22:00:00Z".parse().ok();
    base.camera.fov_y_deg = 20.0;
    base.night.milky_way_intensity = 0.0;
    let vega = stratus_astro::stars::catalogue()
        .iter()
        .find(|s| (s.ra_deg - 279.2347).abs() < 1e-3)
        .copied()
        .expect("Vega");
    let direction = celestial_world(
        &base,
        stratus_astro::celestial::equatorial_vector(vega.ra_deg, vega.dec_deg),
    );
    // Off the centre, so that the projection is tested, not only the camera's aim.
    let mut scene = looking_at(base, direction);
    scene.camera.yaw_deg += 3.0;
    scene.camera.pitch_deg -= 2.0;
    let f = render(Api::Vulkan, &scene, false);
    let (bx, by) = brightest_pixel(&f);
    let at = sun_on_image_of(&scene, direction).expect("Vega in front");
    println!(
        "Vega projects to ({:.2}, {:.2}); the brightest pixel is ({bx}, {by})",
        at[0], at[1]
    );
    assert!(
        (bx + 0.5 - at[0]).abs() <= 1.5 && (by + 0.5 - at[1]).abs() <= 1.5,
        "the brightest pixel ({bx}, {by}) is not Vega's ({:.1}, {:.1})",
        at[0],
        at[1]
    );
}

/// The moon's limb is anti-aliased either way `night.moon_msaa` chooses: with the disc four
/// times its size (about 5 pixels in radius) and exposed below white, both the spread edge and the four rotated-grid
/// samples leave a ring of part-covered pixels between the sky and the lit disc, and the two
/// images differ only on and around the disc.
#[test]
fn the_moons_limb_is_anti_aliased_by_spread_or_msaa() {
    let mut spread = preset("night", 256, 144);
    spread.night.moon_size = 4.0;
    spread.clouds.coverage = 0.0;
    // An exposure that keeps the disc below white (auto exposure clips it, and a clipped pixel
    // shows no coverage): its radiance, the moon's illuminance over its solid angle, to 0.4.
    let u = spread.uniforms();
    let disc = f64::from(u.moon_illuminance)
        / (2.0 * std::f64::consts::PI * (1.0 - f64::from(u.moon_cos_radius)));
    spread.camera.auto_exposure = false;
    spread.camera.exposure = 0.4 / disc;
    let mut msaa = spread.clone();
    msaa.night.moon_msaa = true;
    let at = sun_on_image_of(&spread, spread.moon().expect("a moon").0).expect("in front");
    let radius_px = (0.259f64 * 4.0).to_radians().tan()
        / (spread.camera.fov_y_deg.to_radians() / 2.0).tan()
        * 72.0;
    let lum = |f: &FrameOutput| -> Vec<f64> {
        f.image
            .chunks(4)
            .map(|p| f64::from(p[0]) + f64::from(p[1]) + f64::from(p[2]))
            .collect()
    };
    let (a, b) = (
        lum(&render(Api::Vulkan, &spread, false)),
        lum(&render(Api::Vulkan, &msaa, false)),
    );
    let dist = |i: usize| {
        let (x, y) = ((i % 256) as f64 + 0.5, (i / 256) as f64 + 0.5);
        ((x - at[0]).powi(2) + (y - at[1]).powi(2)).sqrt()
    };
    let far_differ = (0..a.len())
        .filter(|&i| dist(i) > radius_px + 3.0 && a[i] != b[i])
        .count();
    assert_eq!(far_differ, 0, "the modes differ away from the moon");
    assert!(
        (0..a.len()).any(|i| a[i] != b[i]),
        "the two modes draw the same limb"
    );
    for (name, img) in [("spread", &a), ("msaa", &b)] {
        let peak = (0..img.len())
            .filter(|&i| dist(i) < radius_px)
            .map(|i| img[i])
            .fold(0.0, f64::max);
        let sky = (0..img.len())
            .filter(|&i| dist(i) > radius_px + 4.0 && dist(i) < radius_px + 8.0)
            .map(|i| img[i])
            .fold(0.0, f64::max);
        let part = (0..img.len())
            .filter(|&i| (dist(i) - radius_px).abs() < 1.5)
            .filter(|&i| img[i] > sky + 0.1 * (peak - sky) && img[i] < sky + 0.9 * (peak - sky))
            .count();
        println!(
            "{name}: {part} part-covered limb pixels (disc {radius_px:.1} px, peak {peak}, sky {sky})"
        );
        assert!(part >= 6, "{name}: {part} part-covered pixels on the limb");
    }
}

/// A raining deck (cumulus-noon, coverage 0.6, precipitating at 1) at the first frame that shows
/// a lightning flash within 20 degrees of the view, and nothing drawn of the rain or the flash
/// yet (each test turns on its own).
fn raining(w: u32, h: u32) -> Scene {
    let mut s = preset("cumulus-noon", w, h);
    // A deck of the weather map's cumulus, as scenes/thunderstorm.toml's: on the default's
    // convective cells the rain-shaft test found 3 columns between the shafts, not its 59.
    s.clouds.convective_cells = 0.0;
    s.clouds.coverage = 0.6;
    s.clouds.precipitation = 1.0;
    s.lightning.flashes_per_minute = 40.0;
    s.clouds.time_s = stratus_scene::lightning::first_flash_in_view(&s, 20.0, 0.8)
        .expect("a flash within the hour");
    s.lightning.brightness = 0.0;
    s
}

/// `a` less `b` in display luminance (levels, 0-255), per pixel.
fn luminance_difference(a: &FrameOutput, b: &FrameOutput) -> Vec<f64> {
    display_luminance(a)
        .iter()
        .zip(display_luminance(b))
        .map(|(x, y)| (x - y) * 255.0)
        .collect()
}

/// With no layer precipitating, `wet` (an effect of the rain on) renders `dry` (off) bit for
/// bit: `what` needs falling rain.
fn assert_dry_without_precipitation(dry: &Scene, wet: &Scene, what: &str) {
    let (mut dry, mut wet) = (dry.clone(), wet.clone());
    dry.clouds.precipitation = 0.0;
    wet.clouds.precipitation = 0.0;
    assert!(
        render(Api::Vulkan, &wet, false).image == render(Api::Vulkan, &dry, false).image,
        "{what} without a precipitating layer"
    );
}

/// Rain's particles change the image where they fall (streaks over it), fewer where the layer
/// precipitates less, snow's differently; a layer that does not precipitate drops none (the
/// image is the dry one bit for bit).
#[test]
fn rain_and_snow_particles_fall_only_from_precipitating_layers() {
    let dry = raining(192, 108);
    let mut wet = dry.clone();
    wet.precipitation.particles = 4.0;
    let base = render(Api::Vulkan, &dry, false);
    let rain = render(Api::Vulkan, &wet, false);
    let streaks = |img: &FrameOutput, base: &FrameOutput| {
        luminance_difference(img, base)
            .iter()
            .filter(|d| d.abs() >= 1.0)
            .count()
    };
    let streaked = streaks(&rain, &base);
    let mut lighter = wet.clone();
    lighter.clouds.precipitation = 0.5;
    let mut lighter_dry = dry.clone();
    lighter_dry.clouds.precipitation = 0.5;
    let light = streaks(
        &render(Api::Vulkan, &lighter, false),
        &render(Api::Vulkan, &lighter_dry, false),
    );
    println!(
        "particles: precipitation 1 streaks {streaked} pixels by a level or more, 0.5 {light}"
    );
    assert!(
        light < streaked,
        "half the precipitation streaks {light} pixels, all of it {streaked}"
    );
    let mut snowy = wet.clone();
    snowy.precipitation.kind = stratus_scene::PrecipitationKind::Snow;
    let snow = render(Api::Vulkan, &snowy, false);
    let flaked = luminance_difference(&snow, &base)
        .iter()
        .filter(|d| d.abs() >= 1.0)
        .count();
    println!("particles: snow changes {flaked} pixels");
    assert!(
        streaked >= 125,
        "rain streaks {streaked} pixels (measured 250)"
    );
    assert!(flaked >= 45, "snow flakes {flaked} pixels (measured 93)");
    assert_ne!(rain.image, snow.image);
    assert_dry_without_precipitation(&dry, &wet, "particles");
}

/// Rain shafts: over the band of sky just above the horizon the rain dims the columns below the
/// raining cells more than those between them; no precipitation, no shafts.
///
/// The measure is a column's change in display levels, which is the veil's own light (the
/// ambient under the deck) less what it takes of the clouds behind it: it depends on how bright
/// those clouds' rain-darkened bases are. It is measured with the precipitation darkening at
/// 0.5, which the scene keeps. When the darkening dimmed the sky's light as well as the sun's,
/// 59 of 192 columns dimmed by under a quarter of the darkest (-44.9 levels), and the test
/// counted them as the gaps between the shafts; at a darkening of 0.3 only 13 did, so those
/// gaps were where the veil's light balanced what it takes, not clear air. Since the darkening
/// leaves the sky's light alone the bases behind the veil are brighter and the columns change
/// by -47.3 to -17.7 levels, none by under a quarter of the darkest; with the veil's light off
/// (no ambient) by -173.1 to -70.6: the veil spans the band, thinner between the raining cells.
/// So the test holds the shafts' structure: the least dimmed column dims by at most half as
/// much as the darkest (measured 0.37 of it), where a uniform veil would dim them alike.
#[test]
fn rain_shafts_hang_darker_columns_below_raining_cells() {
    let mut dry = raining(192, 108);
    dry.lighting.precipitation_darkening = 0.5;
    let mut wet = dry.clone();
    wet.precipitation.shafts = 1.0;
    let base = render(Api::Vulkan, &dry, false);
    let shafts = render(Api::Vulkan, &wet, false);
    let diff = luminance_difference(&shafts, &base);
    let (w, h) = (192usize, 108usize);
    // The horizon's row: the camera's pitch below the image's centre.
    let tan_half = (dry.camera.fov_y_deg.to_radians() / 2.0).tan();
    let horizon =
        (h as f64 / 2.0 * (1.0 + dry.camera.pitch_deg.to_radians().tan() / tan_half)) as usize;
    let band = horizon - 10..horizon - 2;
    let column: Vec<f64> = (0..w)
        .map(|x| band.clone().map(|y| diff[y * w + x]).sum::<f64>() / band.len() as f64)
        .collect();
    let darkest = column.iter().copied().fold(f64::INFINITY, f64::min);
    let brightest = column.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    println!(
        "rain shafts above the horizon (rows {band:?}): columns change by {darkest:.1} to {brightest:.1} levels"
    );
    assert!(
        darkest <= -20.0,
        "the darkest column dims by {darkest:.1} levels (measured -47.3)"
    );
    assert!(
        brightest >= 0.5 * darkest,
        "the least dimmed column dims by {brightest:.1} levels, over half the darkest's {darkest:.1}: \
         no darker columns below the raining cells (measured -17.7 against -47.3)"
    );
    assert_dry_without_precipitation(&dry, &wet, "shafts");
}

/// A lightning flash brightens the image and nowhere darkens it, most about where the flash is
/// (its light's centroid near the flash's place on the image); without it the frame is the
/// dark one bit for bit.
#[test]
fn a_lightning_flash_lights_the_cloud_about_it() {
    let dark = raining(192, 108);
    let mut lit = dark.clone();
    lit.lightning.brightness = 1.0;
    let flash = stratus_scene::lightning::flash(&lit).expect("the frame has a flash");
    let cam = lit.camera.position;
    let to = [0, 1, 2].map(|k| flash.position[k] - cam[k]);
    let len = (to[0] * to[0] + to[1] * to[1] + to[2] * to[2]).sqrt();
    let at = sun_on_image_of(&lit, to.map(|v| v / len)).expect("the flash is ahead");
    let diff = luminance_difference(
        &render(Api::Vulkan, &lit, false),
        &render(Api::Vulkan, &dark, false),
    );
    let darker = diff.iter().filter(|&&d| d < 0.0).count();
    let total: f64 = diff.iter().map(|d| d.max(0.0)).sum();
    let w = 192usize;
    let centroid = (0..diff.len()).fold([0.0; 2], |c, i| {
        let d = diff[i].max(0.0) / total;
        [
            c[0] + d * ((i % w) as f64 + 0.5),
            c[1] + d * ((i / w) as f64 + 0.5),
        ]
    });
    let off = (centroid[0] - at[0]).hypot(centroid[1] - at[1]) / 108.0;
    println!(
        "lightning: {total:.0} levels brighter in all, centroid ({:.1}, {:.1}) vs the flash at ({:.1}, {:.1}): {off:.3} image heights; {darker} pixels darker",
        centroid[0], centroid[1], at[0], at[1]
    );
    assert_eq!(darker, 0, "the flash darkened {darker} pixels");
    assert!(
        total > 5000.0,
        "the flash adds {total} levels (measured 24793)"
    );
    assert!(
        off < 0.1,
        "the flash light is {off:.3} image heights from it (measured 0.022)"
    );
}
