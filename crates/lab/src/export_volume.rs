//! `stratus export-volume`: the scene's cloud density sampled on a grid, written as a Mitsuba 3
//! `.vol` file, with the scene set up so that an independent renderer can reproduce it (flat
//! world, one Henyey-Greenstein lobe, no real-time-only terms, a uniform sky or the physical
//! sky frozen at the box's centre as a latitude-longitude map and a sun after the air), and
//! optionally the CPU reference's Monte Carlo renders of the same gridded medium under the same
//! light (`cargo xtask mitsuba-check`).

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use clap::Args;
use serde_json::json;
use stratus_reference::{
    DensityGrid, Environment, Integrator, Medium, RenderOptions, Rendering, render_medium,
    render_medium_lit, sample_density_grid,
};
use stratus_scene::{PhaseModel, Scene, SkyModel};

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
    /// Under the physical sky, the latitude-longitude map of the sky written beside `--out`
    /// (PFM, float RGB), WIDTHxHEIGHT: columns over the full circle, rows from the zenith to
    /// the nadir, both included.
    #[arg(long, default_value = "512x257", value_parser = parse_size)]
    sky_map_size: (u32, u32),
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
/// HG lobe, no octaves, no Beer-Powder, no precipitation, uniform sky (the physical sky is
/// given separately, as an [`Environment`]), the camera at the layer's mid-height looking level
/// at the box.
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

/// Mitsuba's PFM reader's layout: "PF", the size, -1 (little-endian), then float32 RGB rows
/// from the image's bottom row up. The map's first row (the zenith) is the image's top.
fn write_sky_map(path: &Path, env: &Environment) -> Result<()> {
    let mut out = format!("PF\n{} {}\n-1.0\n", env.width, env.height).into_bytes();
    for row in env.radiance.chunks(env.width).rev() {
        for texel in row {
            for c in texel {
                out.extend_from_slice(&(*c as f32).to_le_bytes());
            }
        }
    }
    stratus_compare::write_file_atomically(path, &out)
        .with_context(|| format!("writing {}", path.display()))
}

/// The physical sky of `scene` frozen at the box centre's altitude (`None` under the analytic
/// sky), and the check scene switched to the analytic sky, whose light the environment
/// replaces.
/// Refuses a key light below the horizon: Mitsuba's directional light would light the box
/// from below, where the reference's ground stops it.
fn frozen_sky(
    scene: &Scene,
    check: &mut Scene,
    centre_alt: f64,
    args: &ExportArgs,
) -> Result<Option<Environment>> {
    let sun = check.uniforms().sun_direction;
    if sun[1] <= 0.0 {
        anyhow::bail!(
            "export-volume: the key light is {:.1} deg below the horizon: Mitsuba's directional \
             light would light the box from below, where the reference's ground stops it; \
             choose a scene whose sun (or moon) is up",
            -f64::from(sun[1]).asin().to_degrees()
        );
    }
    let (w, h) = args.sky_map_size;
    if (w < 4 || h < 3) && scene.atmosphere.sky == SkyModel::Physical {
        anyhow::bail!(
            "export-volume: --sky-map-size {w}x{h}: the map needs at least 4x3 texels (columns \
             that wrap around, rows from the zenith to the nadir and one between)"
        );
    }
    let env = Environment::physical_sky(scene, centre_alt, w as usize, h as usize);
    if env.is_some() {
        check.atmosphere.sky = SkyModel::Analytic;
    }
    Ok(env)
}

pub fn run(args: ExportArgs) -> Result<()> {
    let (original, _) = load_scene(args.preset.as_deref(), args.scene.as_ref(), None)?;
    let (mut scene, min, max) = check_scene(original.clone(), &args);
    scene.validate().map_err(|e| anyhow::anyhow!("{e}"))?;
    let env = frozen_sky(&original, &mut scene, 0.5 * (min[1] + max[1]), &args)?;
    let noise = stratus::noise_for(&scene);
    let grid = sample_density_grid(&scene, &noise, min, max, args.dims);
    if grid.max_density() <= 0.0 {
        // An empty box compares the sky with itself: every check would pass, saying nothing.
        anyhow::bail!(
            "export-volume: the box ({:.0?}..{:.0?} m) holds no cloud (max density 0): there \
             would be nothing to compare; move it with --distance-m (now {} m) or widen it \
             with --box-m",
            min,
            max,
            args.distance_m
        );
    }
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
    // Under the physical sky: its map beside the volume, and the sun after the air.
    let (sky_map, sun_illuminance) = match &env {
        Some(env) => {
            let path = args.out.with_extension("sky.pfm");
            write_sky_map(&path, env)?;
            eprintln!(
                "{}: the physical sky at {:.0} m, {}x{}; sun after the air {:?}",
                path.display(),
                0.5 * (min[1] + max[1]),
                env.width,
                env.height,
                env.sun
            );
            (Some(path), env.sun)
        }
        None => (None, v3(u.sun_illuminance)),
    };
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
            "sun_illuminance": sun_illuminance,
            "sky_radiance": ambient,
            "sky_map": sky_map,
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
        // Under the physical sky the reference's pixels also get the sky seen through the
        // medium, sub-pixel by sub-pixel: the sky's gradient at the horizon and the cloud's
        // edges both vary within a pixel, and the product of their pixel means was 0.1-0.3%
        // from the mean of their product (Mitsuba's). The background alone goes with them, for
        // the check to put Mitsuba's own view of the map in its place where the camera sees
        // it (the two filters differ by up to 0.07% a block).
        let behind = env.as_ref().map(|env| env.behind_pixels(&fine));
        if let Some(behind) = &behind {
            renders.insert(
                "background".to_string(),
                json!(pixel_means(behind, args.size, k)),
            );
        }
        for (name, orders) in [("single", 1), ("all", 0)] {
            let options = RenderOptions {
                progress: true,
                threads: None,
            };
            let r = match &env {
                Some(env) => {
                    render_medium_lit(&fine, Medium::Grid(&grid), env, sub_spp, orders, &options)
                }
                None => render_medium(
                    &fine,
                    Medium::Grid(&grid),
                    &Integrator::MonteCarlo {
                        spp: sub_spp,
                        orders,
                    },
                    &options,
                ),
            };
            let (radiance, std_error) = box_filter(&r, behind.as_deref(), args.size, k);
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
        renders.insert("background_included".to_string(), json!(env.is_some()));
        stratus_compare::write_file_atomically(
            &args.reference_out,
            serde_json::to_string(&renders)?.as_bytes(),
        )
        .with_context(|| format!("writing {}", args.reference_out.display()))?;
        eprintln!("{}: reference renders", args.reference_out.display());
    }
    Ok(())
}

/// Every sub-pixel of a `size` image rendered at `k` x `k` sub-pixels a pixel: its index in
/// the fine image and its pixel's index in the image.
fn sub_pixels(size: (u32, u32), k: u32) -> impl Iterator<Item = (usize, usize)> {
    let (w, h, k) = (size.0 as usize, size.1 as usize, k as usize);
    (0..h * k).flat_map(move |y| (0..w * k).map(move |x| (y * w * k + x, (y / k) * w + x / k)))
}

/// Averages `k` x `k` sub-pixels of `values` into each pixel of a `size` image (RGB).
fn pixel_means(values: &[[f64; 3]], size: (u32, u32), k: u32) -> Vec<f64> {
    let n = f64::from(k * k);
    let mut mean = vec![0.0; 3 * size.0 as usize * size.1 as usize];
    for (i, o) in sub_pixels(size, k) {
        for c in 0..3 {
            mean[3 * o + c] += values[i][c] / n;
        }
    }
    mean
}

/// Averages `k` x `k` sub-pixels of `r` into each pixel of a `size` image: radiance and
/// transmittance, and their standard errors (independent sub-pixels). With `behind` (each
/// sub-pixel's background), the radiance also gets the background times the transmittance.
fn box_filter(
    r: &Rendering,
    behind: Option<&[[f64; 3]]>,
    size: (u32, u32),
    k: u32,
) -> (Vec<f64>, Vec<f64>) {
    let n = f64::from(k * k);
    let mut mean = vec![0.0; 4 * size.0 as usize * size.1 as usize];
    let mut var = mean.clone();
    for (fine, pixel) in sub_pixels(size, k) {
        let (i, o) = (4 * fine, 4 * pixel);
        let alpha = f64::from(r.output.radiance[i + 3]);
        let alpha_se = r.std_error.as_ref().map_or(0.0, |se| f64::from(se[i + 3]));
        for c in 0..4 {
            let bg = match behind {
                Some(b) if c < 3 => b[fine][c],
                _ => 0.0,
            };
            mean[o + c] += (f64::from(r.output.radiance[i + c]) + alpha * bg) / n;
            if let Some(se) = &r.std_error {
                var[o + c] += (f64::from(se[i + c]) / n).powi(2) + (alpha_se * bg / n).powi(2);
            }
        }
    }
    (mean, var.into_iter().map(f64::sqrt).collect())
}
