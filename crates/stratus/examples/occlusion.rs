//! The host's geometry in the clouds: an opaque box in front of them and a plane inside a
//! cloud, given to Stratus as the host's depth buffer (reversed Z, infinite far plane). The
//! clouds are rendered on the GPU (wgpu) and by the CPU reference with the same depth, and
//! their HDR output (linear in-scattered radiance, transmittance in alpha) is measured:
//!
//! - `covered_pixels`: pixels the geometry covers;
//! - `max_cloud_radiance_behind_geometry`: over the box's pixels, the largest in-scattered
//!   radiance or cloud opacity (1 - transmittance) the GPU left; must be 0;
//! - `inside_cloud_transmittance_error`: over the plane's pixels, the largest difference
//!   between the GPU's transmittance to the plane and the CPU reference's; must be ≤ 0.01;
//!   (`..._without_depth`: the same difference of the marches through the whole cloud);
//! - `inside_cloud_transmittance` and `..._without_depth`: the plane's mean transmittance
//!   with the depth and without it (the march through the whole cloud); the first must be
//!   higher.
//!
//! It exits non-zero when a bound fails.
//!
//! `cargo run --release -p stratus --example occlusion -- --out occ.png --json occ.json
//! [--size WxH]` (default 256x144).

use std::path::PathBuf;
use std::sync::Arc;

use stratus::glam::dcamera::rh::proj::directx;
use stratus::{HostCamera, Scene};
use stratus_backend_wgpu::{Api, Options, Renderer};
use stratus_graph::{FrameInput, FrameOutput, FramePlan};
use stratus_reference::{Integrator, QuadratureSettings, render_with_scene_depth};

/// The box's distance along the view axis (m): well in front of the cloud layer.
const BOX_DISTANCE: f64 = 400.0;

fn main() {
    if let Err(e) = run() {
        eprintln!("occlusion: {e}");
        std::process::exit(1);
    }
}

struct Args {
    out: Option<PathBuf>,
    json: Option<PathBuf>,
    size: [u32; 2],
}

fn args() -> Result<Args, String> {
    let mut a = Args {
        out: None,
        json: None,
        size: [256, 144],
    };
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        let mut value = || it.next().ok_or(format!("{flag} needs a value"));
        match flag.as_str() {
            "--out" => a.out = Some(value()?.into()),
            "--json" => a.json = Some(value()?.into()),
            "--size" => {
                let v = value()?;
                let (w, h) = v
                    .split_once('x')
                    .ok_or(format!("--size {v}: expected WxH, e.g. 256x144"))?;
                let parse = |s: &str| s.parse::<u32>().map_err(|e| format!("--size {v}: {e}"));
                a.size = [parse(w)?, parse(h)?];
            }
            "-h" | "--help" => {
                println!(
                    "usage: occlusion [--out IMAGE.png] [--json RESULT.json] [--size WxH]\n\n\
                     Renders cumulus-noon with an opaque box in front of the clouds and a plane\n\
                     inside a cloud as the host's depth buffer, on the GPU and the CPU reference,\n\
                     and measures the HDR output there (see the source's header)."
                );
                std::process::exit(0);
            }
            other => return Err(format!("unknown argument `{other}` (try --help)")),
        }
    }
    Ok(a)
}

/// Transmittance of pixel `i`.
fn alpha(out: &FrameOutput, i: usize) -> f64 {
    f64::from(out.radiance[4 * i + 3])
}

fn run() -> Result<(), String> {
    let args = args()?;
    let [w, h] = args.size;
    let scene = Scene::preset("cumulus-noon")
        .map_err(|e| e.to_string())?
        .with_size(w, h);
    let noise = Arc::new(stratus::noise_for(&scene));
    let plan = FramePlan::for_scene(&scene, false).map_err(|e| e.to_string())?;
    let mut gpu = Renderer::new(Options {
        api: Api::Vulkan,
        validation: false,
    })
    .map_err(|e| e.to_string())?;

    // The clouds without geometry: where they are and how far.
    let open = gpu
        .render(&FrameInput::new(&plan, &scene, &noise))
        .map_err(|e| e.to_string())?;

    // The host's camera: the scene's, with a reversed infinite projection.
    let camera = HostCamera {
        projection: directx::perspective_infinite_reverse(
            scene.camera.fov_y_deg.to_radians(),
            f64::from(w) / f64::from(h),
            0.1,
        ),
        ..HostCamera::of_scene(&scene, 0.1, f64::INFINITY)
    };
    let projection = camera.projection().map_err(|e| e.to_string())?;
    let (forward, _, _) = scene.camera_basis();

    // The box: a face-on rectangle on the left. The plane: the window of the right half with
    // the most cloud, at the median distance of the cloud in it (so part of the cloud is in
    // front of it and part behind).
    let n = (w * h) as usize;
    let in_box = |x: u32, y: u32| {
        (w * 12 / 100..w * 32 / 100).contains(&x) && (h * 35 / 100..h * 75 / 100).contains(&y)
    };
    let (ww, wh) = (w / 5, h / 4);
    let mut best = (f64::INFINITY, 0, 0);
    for y0 in (0..h - wh).step_by(4) {
        for x0 in (w / 2..w - ww).step_by(4) {
            let mean = (y0..y0 + wh)
                .flat_map(|y| (x0..x0 + ww).map(move |x| (y * w + x) as usize))
                .map(|i| alpha(&open, i))
                .sum::<f64>();
            if mean < best.0 {
                best = (mean, x0, y0);
            }
        }
    }
    let (_, px, py) = best;
    let in_plane = |x: u32, y: u32| (px..px + ww).contains(&x) && (py..py + wh).contains(&y);
    let mut distances: Vec<f64> = (py..py + wh)
        .flat_map(|y| (px..px + ww).map(move |x| [x, y]))
        .filter_map(|[x, y]| {
            let i = (y * w + x) as usize;
            let d = f64::from(open.depth[i]);
            // The cloud's depth is along the ray; the plane's along the view axis.
            let view = view_ray(&scene, [x, y]);
            (alpha(&open, i) < 0.9 && d > 0.0).then(|| d * dot(view, forward))
        })
        .collect();
    if distances.is_empty() {
        return Err("no cloud in the right half of cumulus-noon's view to put the plane in".into());
    }
    distances.sort_by(f64::total_cmp);
    let plane_distance = distances[distances.len() / 2];

    let mut depth = vec![projection.clear_depth() as f32; n];
    for y in 0..h {
        for x in 0..w {
            let i = (y * w + x) as usize;
            if in_box(x, y) {
                depth[i] = projection.depth_at(BOX_DISTANCE) as f32;
            } else if in_plane(x, y) {
                depth[i] = projection.depth_at(plane_distance) as f32;
            }
        }
    }
    let scene_depth = Arc::new(
        projection
            .scene_depth([w, h], &depth)
            .map_err(|e| e.to_string())?,
    );

    let frame = FrameInput::new(&plan, &scene, &noise).with_scene_depth(Some(&scene_depth));
    let out = gpu.render(&frame).map_err(|e| e.to_string())?;
    let cpu = render_with_scene_depth(
        &scene,
        &noise,
        &Integrator::Quadrature(QuadratureSettings::realtime()),
        false,
        Some(&scene_depth),
    );

    // The same without the depth: how far the two marches differ anyway.
    let cpu_open = render_with_scene_depth(
        &scene,
        &noise,
        &Integrator::Quadrature(QuadratureSettings::realtime()),
        false,
        None,
    );
    let (mut covered, mut max_behind, mut max_err) = (0u64, 0.0f64, 0.0f64);
    let mut max_err_open = 0.0f64;
    let (mut inside, mut inside_open, mut inside_n) = (0.0, 0.0, 0u64);
    for y in 0..h {
        for x in 0..w {
            let i = (y * w + x) as usize;
            if in_box(x, y) {
                covered += 1;
                let rgb = out.radiance[4 * i..4 * i + 3]
                    .iter()
                    .map(|&v| f64::from(v))
                    .fold(0.0, f64::max);
                max_behind = max_behind.max(rgb).max(1.0 - alpha(&out, i));
            } else if in_plane(x, y) {
                covered += 1;
                max_err = max_err.max((alpha(&out, i) - alpha(&cpu, i)).abs());
                max_err_open = max_err_open.max((alpha(&open, i) - alpha(&cpu_open, i)).abs());
                inside += alpha(&out, i);
                inside_open += alpha(&open, i);
                inside_n += 1;
            }
        }
    }
    let inside = inside / inside_n as f64;
    let inside_open = inside_open / inside_n as f64;
    let result = serde_json::json!({
        "scene": "cumulus-noon",
        "size": [w, h],
        "device": out.device,
        "depth": "reversed Z, infinite far plane",
        "box_distance_m": BOX_DISTANCE,
        "plane_distance_m": plane_distance,
        "covered_pixels": covered,
        "max_cloud_radiance_behind_geometry": max_behind,
        "inside_cloud_transmittance_error": max_err,
        "inside_cloud_transmittance_error_without_depth": max_err_open,
        "inside_cloud_transmittance": inside,
        "inside_cloud_transmittance_without_depth": inside_open,
    });
    let text = serde_json::to_string_pretty(&result).map_err(|e| e.to_string())?;
    println!("{text}");
    if let Some(path) = &args.json {
        stratus_compare::write_file_atomically(path, format!("{text}\n").as_bytes())
            .map_err(|e| format!("writing {}: {e}", path.display()))?;
    }
    if let Some(path) = &args.out {
        let image = image::RgbaImage::from_raw(w, h, out.image.clone())
            .ok_or("the display image is not the frame's size")?;
        stratus_compare::write_atomically(path, |tmp| {
            image.save_with_format(tmp, image::ImageFormat::Png)
        })
        .map_err(|e| format!("writing {}: {e}", path.display()))?;
    }

    let mut failed = Vec::new();
    if max_behind != 0.0 {
        failed.push(format!(
            "clouds show through the box: max radiance or opacity {max_behind:e}, not 0"
        ));
    }
    if max_err > 0.01 {
        failed.push(format!(
            "the GPU's transmittance to the plane is {max_err:.4} off the CPU's (bound 0.01)"
        ));
    }
    if inside <= inside_open {
        failed.push(format!(
            "the plane inside the cloud sees transmittance {inside:.4}, not more than the whole cloud's {inside_open:.4}: the march did not stop at it"
        ));
    }
    if failed.is_empty() {
        Ok(())
    } else {
        Err(failed.join("; "))
    }
}

/// The unit view ray through the centre of `pixel` (as the shaders make it).
fn view_ray(scene: &Scene, pixel: [u32; 2]) -> [f64; 3] {
    let (f, r, u) = scene.camera_basis();
    let [w, h] = scene.camera.resolution.map(f64::from);
    let tan = (scene.camera.fov_y_deg.to_radians() / 2.0).tan();
    let nx = (f64::from(pixel[0]) + 0.5) / w * 2.0 - 1.0;
    let ny = (f64::from(pixel[1]) + 0.5) / h * 2.0 - 1.0;
    let d: Vec<f64> = (0..3)
        .map(|k| f[k] + r[k] * nx * tan * w / h - u[k] * ny * tan)
        .collect();
    let len = dot([d[0], d[1], d[2]], [d[0], d[1], d[2]]).sqrt();
    [d[0] / len, d[1] / len, d[2] / len]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
