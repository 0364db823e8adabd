//! `stratus export-volume`: the scene's cloud density sampled on a grid, written as a Mitsuba 3
//! `.vol` file, with the scene set up so that an independent renderer can reproduce it (flat
//! world, one Henyey-Greenstein lobe, no real-time-only terms, a uniform sky), and optionally the
//! CPU reference's Monte Carlo renders of the same gridded medium (`cargo xtask mitsuba-check`).

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use clap::Args;
use serde_json::json;
use stratus_reference::{
    DensityGrid, Integrator, Medium, RenderOptions, Rendering, render_medium, sample_density_grid,
};
use stratus_scene::{PhaseModel, Scene};

use stratus_tool::scene_io::load_scene;

#[derive(Args)]
pub struct ExportArgs {
    /// A built-in preset (see `stratus presets`).
    #[arg(long, conflicts_with = "scene")]
    preset: Option<String>,
    /// A scene file (TOML; may be partial and name a `base` preset).
    #[arg(long)]
    scene: Option<PathBuf>,
    /// Grid cells as XxYxZ (Y is the altitude).
    #[arg(long, default_value = "64x64x64", value_parser = parse_dims)]
    dims: [usize; 3],
    /// Horizontal size of the box, metres (its height is the cloud layer's).
    #[arg(long, default_value_t = 4000.0)]
    box_m: f64,
    /// Horizontal distance from the camera to the box's centre, metres (the camera is at the
    /// layer's mid-height, looking level along the scene's yaw).
    #[arg(long, default_value_t = 8000.0)]
    distance_m: f64,
    /// Scattering coefficient at density 1 (1/m), replacing the scene's (keeps the box
    /// optically moderate so that all orders converge quickly).
    #[arg(long, default_value_t = 0.01)]
    scattering: f64,
    /// Absorption coefficient at density 1 (1/m), replacing the scene's.
    #[arg(long, default_value_t = 0.001)]
    absorption: f64,
    /// Image size WIDTHxHEIGHT of the renders described in `--json`.
    #[arg(long, default_value = "32x32", value_parser = parse_size)]
    size: (u32, u32),
    /// The Mitsuba volume file to write.
    #[arg(long, default_value = "volume.vol")]
    out: PathBuf,
    /// Also write the setup (camera, sun, sky, medium, box) as JSON here.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Also render the gridded medium with the reference's path tracer at this many samples
    /// per pixel, single scattering and all orders, into `--reference-out` (JSON).
    #[arg(long, default_value_t = 0)]
    reference_spp: u32,
    /// The reference renders k x k sub-pixels per pixel (pixel-centre rays) and averages them,
    /// approximating Mitsuba's box pixel filter; each sub-pixel gets `reference_spp / k^2`
    /// samples (at least 1).
    #[arg(long, default_value_t = 4)]
    supersample: u32,
    /// Where the reference renders go.
    #[arg(long, default_value = "reference.json")]
    reference_out: PathBuf,
}

fn parse_dims(s: &str) -> std::result::Result<[usize; 3], String> {
    let v: Vec<usize> = s
        .split('x')
        .map(|p| p.parse::<usize>().map_err(|e| format!("{s}: {e}")))
        .collect::<std::result::Result<_, _>>()?;
    match v.as_slice() {
        [x, y, z] if *x > 0 && *y > 0 && *z > 0 => Ok([*x, *y, *z]),
        _ => Err(format!("{s}: expected XxYxZ, each at least 1")),
    }
}

fn parse_size(s: &str) -> std::result::Result<(u32, u32), String> {
    let (w, h) = s
        .split_once('x')
        .ok_or_else(|| format!("{s}: expected WIDTHxHEIGHT"))?;
    let w = w.parse().map_err(|e| format!("{s}: {e}"))?;
    let h = h.parse().map_err(|e| format!("{s}: {e}"))?;
    Ok((w, h))
}

/// The scene made reproducible by a general-purpose volumetric path tracer: flat world, single
/// HG lobe, no octaves, no Beer-Powder, no precipitation, uniform sky, the camera at the
/// layer's mid-height looking level at the box.
fn check_scene(mut s: Scene, args: &ExportArgs) -> (Scene, [f64; 3], [f64; 3]) {
    s = s.with_size(args.size.0, args.size.1);
    s.atmosphere.planet_radius_m = 1e14;
    s.lighting.multiple_scattering.octaves = 0;
    s.lighting.beer_powder = false;
    s.lighting.phase.model = PhaseModel::Hg;
    s.lighting.scattering = args.scattering;
    s.lighting.absorption = args.absorption;
    s.lighting.ambient_top = s.lighting.ambient_bottom;
    s.clouds.precipitation = 0.0;
    s.quality.cutoff_distance_m = 1e6;
    let (bottom, top) = (s.atmosphere.cloud_bottom_m, s.atmosphere.cloud_top_m);
    let mid = 0.5 * (bottom + top);
    s.camera.pitch_deg = 0.0;
    // The level forward direction of the scene's yaw, read back from the uniforms.
    let fwd = s.uniforms().camera_forward;
    let (fx, fz) = (f64::from(fwd[0]), f64::from(fwd[2]));
    let n = (fx * fx + fz * fz).sqrt().max(1e-12);
    let (fx, fz) = (fx / n, fz / n);
    let cam = s.camera.position;
    let centre = [
        cam[0] + fx * args.distance_m,
        mid,
        cam[2] + fz * args.distance_m,
    ];
    s.camera.position = [cam[0], mid, cam[2]];
    let h = 0.5 * args.box_m;
    // A hair inside the layer so that the whole box is in it.
    let eps = 1e-3 * (top - bottom);
    let min = [centre[0] - h, bottom + eps, centre[2] - h];
    let max = [centre[0] + h, top - eps, centre[2] + h];
    (s, min, max)
}

/// Mitsuba 3's binary grid volume: "VOL", version 3, encoding 1 (float32), the resolution, the
/// channel count (1), the bounding box (min xyz, max xyz) and the data, x fastest, then y, then
/// z; all little-endian.
pub fn write_vol(path: &Path, grid: &DensityGrid) -> Result<()> {
    let mut out = Vec::with_capacity(48 + 4 * grid.data.len());
    out.extend_from_slice(b"VOL");
    out.push(3);
    out.extend_from_slice(&1i32.to_le_bytes());
    for d in grid.dims {
        out.extend_from_slice(&i32::try_from(d)?.to_le_bytes());
    }
    out.extend_from_slice(&1i32.to_le_bytes());
    for v in grid.min.iter().chain(grid.max.iter()) {
        out.extend_from_slice(&(*v as f32).to_le_bytes());
    }
    for v in &grid.data {
        out.extend_from_slice(&v.to_le_bytes());
    }
    stratus_compare::write_file_atomically(path, &out)
        .with_context(|| format!("writing {}", path.display()))
}

pub fn run(args: ExportArgs) -> Result<()> {
    let (scene, _) = load_scene(args.preset.as_deref(), args.scene.as_ref(), None)?;
    let (scene, min, max) = check_scene(scene, &args);
    scene.validate().map_err(|e| anyhow::anyhow!("{e}"))?;
    let noise = stratus::noise_for(&scene);
    let grid = sample_density_grid(&scene, &noise, min, max, args.dims);
    write_vol(&args.out, &grid)?;
    eprintln!(
        "{}: {}x{}x{} cells, box {:?}..{:?} m, max density {:.4}",
        args.out.display(),
        grid.dims[0],
        grid.dims[1],
        grid.dims[2],
        min,
        max,
        grid.max_density()
    );

    let u = scene.uniforms();
    let v3 = |a: [f32; 3]| a.map(f64::from);
    let ambient = v3(u.ambient_bottom).map(|c| c * f64::from(u.ambient_strength));
    if let Some(path) = &args.json {
        let setup = json!({
            "width": args.size.0,
            "height": args.size.1,
            "camera_position": v3(u.camera_position),
            "camera_forward": v3(u.camera_forward),
            "camera_right": v3(u.camera_right),
            "camera_up": v3(u.camera_up),
            "fov_y_deg": 2.0 * f64::from(u.tan_half_fov).atan().to_degrees(),
            "sun_direction": v3(u.sun_direction),
            "sun_illuminance": v3(u.sun_illuminance),
            "sky_radiance": ambient,
            "sigma_s": f64::from(u.scattering),
            "sigma_a": f64::from(u.absorption),
            "phase_g": scene.lighting.phase.g,
            "box_min": min,
            "box_max": max,
            "dims": grid.dims,
            "max_density": grid.max_density(),
            "volume": args.out,
        });
        stratus_compare::write_file_atomically(
            path,
            serde_json::to_string_pretty(&setup)?.as_bytes(),
        )
        .with_context(|| format!("writing {}", path.display()))?;
    }

    if args.reference_spp > 0 {
        let mut renders = serde_json::Map::new();
        let k = args.supersample.max(1);
        let fine = scene.clone().with_size(args.size.0 * k, args.size.1 * k);
        let sub_spp = args.reference_spp.div_ceil(k * k).max(1);
        for (name, orders) in [("single", 1), ("all", 0)] {
            let r = render_medium(
                &fine,
                Medium::Grid(&grid),
                &Integrator::MonteCarlo {
                    spp: sub_spp,
                    orders,
                },
                &RenderOptions {
                    progress: true,
                    threads: None,
                },
            );
            let (radiance, std_error) = box_filter(&r, args.size, k);
            renders.insert(
                name.to_string(),
                json!({
                    "radiance": radiance,
                    "std_error": std_error,
                    "ms": r.output.timings.first().map(|t| t.ms),
                }),
            );
        }
        renders.insert("spp".to_string(), json!(sub_spp * k * k));
        renders.insert("sky_radiance".to_string(), json!(ambient));
        stratus_compare::write_file_atomically(
            &args.reference_out,
            serde_json::to_string(&renders)?.as_bytes(),
        )
        .with_context(|| format!("writing {}", args.reference_out.display()))?;
        eprintln!("{}: reference renders", args.reference_out.display());
    }
    Ok(())
}

/// Averages `k` x `k` sub-pixels of `r` into each pixel of a `size` image: radiance and
/// transmittance, and their standard errors (independent sub-pixels).
fn box_filter(r: &Rendering, size: (u32, u32), k: u32) -> (Vec<f64>, Vec<f64>) {
    let (w, h) = (size.0 as usize, size.1 as usize);
    let (k, fw) = (k as usize, r.output.width as usize);
    let n = (k * k) as f64;
    let mut mean = vec![0.0; 4 * w * h];
    let mut var = vec![0.0; 4 * w * h];
    for y in 0..h * k {
        for x in 0..w * k {
            let i = 4 * (y * fw + x);
            let o = 4 * ((y / k) * w + x / k);
            for c in 0..4 {
                mean[o + c] += f64::from(r.output.radiance[i + c]) / n;
                if let Some(se) = &r.std_error {
                    var[o + c] += (f64::from(se[i + c]) / n).powi(2);
                }
            }
        }
    }
    (mean, var.into_iter().map(f64::sqrt).collect())
}
