//! `stratus measure-field`: the statistics of a cloud field seen straight down, to hold the
//! model against what real cloud fields measure.
//!
//! The scene's clouds are rendered from high above, looking straight down over a square of
//! `--extent-m` on a side (a narrow field of view from far away, so the view is nearly
//! orthographic). A pixel is cloud where the clouds' transmittance is below `--threshold`.
//! Clouds are the 4-connected components of the cloud pixels; those touching the border are
//! left out (their size and outline are cut). Per cloud: its area A and perimeter P (the pixel
//! edges between it and the rest). Reported:
//! - the number of clouds;
//! - the area-perimeter dimension D, from the least-squares slope of log P against log A
//!   (P ∝ A^(D/2)) over clouds of at least `--min-pixels`. Real fields measure D ≈ 1.35 over
//!   six decades of area (Lovejoy 1982, Science 216:185), 1.2-1.55 for cumulus (Cahalan and
//!   Joseph 1989, Mon. Wea. Rev. 117:261);
//! - the exponent b of the size density n(L) ∝ L^-b, L = sqrt(A) the cloud's equivalent size,
//!   from the least-squares slope of log n against log L over logarithmic bins holding at least
//!   three clouds. Fair-weather cumulus measure b ≈ 1.7-2.0 (Benner and Curry 1998, J. Geophys.
//!   Res. 103:28753; Neggers, Jonker and Siebesma 2003, J. Atmos. Sci. 60:1060).

use std::{io::IsTerminal as _, path::PathBuf, sync::Arc};

use anyhow::{Context as _, Result, bail};
use clap::Args;
use serde::Serialize;
use stratus_graph::{FrameInput, FramePlan, Readback};
use stratus_scene::{Scene, SkyModel};
use stratus_tool::{
    backends::{Backend, Open, open},
    scene_io::load_scene,
};

/// Options of `stratus measure-field`.
#[derive(Args, Debug)]
pub struct MeasureFieldArgs {
    /// A built-in preset (see `stratus presets`).
    #[arg(long)]
    preset: Option<String>,
    /// A scene file (TOML).
    #[arg(long)]
    scene: Option<PathBuf>,
    /// A weather state applied to the scene (see `stratus weather --list`).
    #[arg(long)]
    state: Option<String>,
    /// The side of the square seen, metres.
    #[arg(long, default_value_t = 35_000.0, allow_hyphen_values = true)]
    extent_m: f64,
    /// Pixels on a side.
    #[arg(long, default_value_t = 512, value_parser = clap::value_parser!(u32).range(64..=2048))]
    size: u32,
    /// A pixel is cloud where the transmittance straight down is below this.
    #[arg(long, default_value_t = 0.5)]
    threshold: f64,
    /// The smallest cloud the fits use, pixels (smaller ones are outlined mostly by the grid).
    #[arg(long, default_value_t = 16)]
    min_pixels: usize,
    /// The renderer.
    #[arg(long, value_enum, default_value_t = Backend::Auto)]
    backend: Backend,
    /// Also write the results as JSON here.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Also write the cloud mask (white cloud, grey cut by the border, black clear) as a PNG.
    #[arg(long)]
    mask: Option<PathBuf>,
}

/// One cloud: its area and perimeter in pixels, and whether the border cuts it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Cloud {
    /// Pixels.
    pub area: usize,
    /// Pixel edges between the cloud and the rest.
    pub perimeter: usize,
    /// Whether it touches the image's border.
    pub cut: bool,
}

/// A least-squares line's slope and its standard error.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Slope {
    /// The slope.
    pub slope: f64,
    /// Its standard error.
    pub stderr: f64,
    /// The points fitted.
    pub points: usize,
}

/// What the command reports.
#[derive(Debug, Serialize)]
pub struct FieldStats {
    /// The scene, in words.
    pub scene: String,
    /// The side of the square seen, metres, and its pixels.
    pub extent_m: f64,
    /// Pixels on a side.
    pub size: u32,
    /// The transmittance below which a pixel is cloud.
    pub threshold: f64,
    /// The share of pixels that are cloud.
    pub cloud_fraction: f64,
    /// Clouds not cut by the border.
    pub clouds: usize,
    /// Clouds cut by the border.
    pub cut: usize,
    /// The area-perimeter dimension, with its standard error and the clouds it was fitted on.
    pub d: Option<Slope>,
    /// The size density's exponent b (n(L) ∝ L^-b), with its standard error and bins.
    pub b: Option<Slope>,
    /// The sizes L the exponent was fitted over, metres (the bins' centres, smallest and
    /// largest).
    pub b_range_m: Option<[f64; 2]>,
    /// The largest cloud's equivalent size sqrt(A), metres.
    pub largest_m: f64,
}

/// The 4-connected components of `mask` (`width` by `height`, row-major).
pub fn clouds(mask: &[bool], width: usize, height: usize) -> Vec<Cloud> {
    components(mask, width, height).0
}

/// The 4-connected components of `mask`, and each pixel's component (`usize::MAX` where clear).
fn components(mask: &[bool], width: usize, height: usize) -> (Vec<Cloud>, Vec<usize>) {
    let mut label = vec![usize::MAX; mask.len()];
    let mut out = Vec::new();
    let mut stack = Vec::new();
    for start in 0..mask.len() {
        if !mask[start] || label[start] != usize::MAX {
            continue;
        }
        let id = out.len();
        let mut cloud = Cloud {
            area: 0,
            perimeter: 0,
            cut: false,
        };
        label[start] = id;
        stack.push(start);
        while let Some(i) = stack.pop() {
            cloud.area += 1;
            let (x, y) = (i % width, i / width);
            if x == 0 || y == 0 || x + 1 == width || y + 1 == height {
                cloud.cut = true;
            }
            let neighbours = [
                (x > 0).then(|| i - 1),
                (x + 1 < width).then(|| i + 1),
                (y > 0).then(|| i - width),
                (y + 1 < height).then(|| i + width),
            ];
            for n in neighbours {
                match n {
                    Some(n) if mask[n] => {
                        if label[n] == usize::MAX {
                            label[n] = id;
                            stack.push(n);
                        }
                    }
                    // An edge to clear sky, or to the image's edge.
                    _ => cloud.perimeter += 1,
                }
            }
        }
        out.push(cloud);
    }
    (out, label)
}

/// The least-squares slope of `y` against `x`, with its standard error (`None` with fewer than
/// three points or no spread in `x`).
pub fn fit(points: &[(f64, f64)]) -> Option<Slope> {
    let n = points.len();
    if n < 3 {
        return None;
    }
    let nf = n as f64;
    let mx = points.iter().map(|p| p.0).sum::<f64>() / nf;
    let my = points.iter().map(|p| p.1).sum::<f64>() / nf;
    let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
    if sxx <= 0.0 {
        return None;
    }
    let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let slope = sxy / sxx;
    let resid: f64 = points
        .iter()
        .map(|p| (p.1 - my - slope * (p.0 - mx)).powi(2))
        .sum();
    Some(Slope {
        slope,
        stderr: (resid / (nf - 2.0) / sxx).sqrt(),
        points: n,
    })
}

/// The area-perimeter dimension D of `clouds` (uncut, at least `min_pixels`): twice the slope
/// of log P against log A.
pub fn dimension(clouds: &[Cloud], min_pixels: usize) -> Option<Slope> {
    let points: Vec<(f64, f64)> = clouds
        .iter()
        .filter(|c| !c.cut && c.area >= min_pixels)
        .map(|c| ((c.area as f64).ln(), (c.perimeter as f64).ln()))
        .collect();
    fit(&points).map(|s| Slope {
        slope: 2.0 * s.slope,
        stderr: 2.0 * s.stderr,
        points: s.points,
    })
}

/// Bins per factor of 10 in size.
const BINS_PER_DECADE: f64 = 5.0;

/// The size density's exponent b of `clouds` (uncut, at least `min_pixels`), sizes in metres
/// of `pixel_m` a pixel, and the sizes (bin centres) it was fitted over.
pub fn size_exponent(
    clouds: &[Cloud],
    min_pixels: usize,
    pixel_m: f64,
) -> Option<(Slope, [f64; 2])> {
    let sizes: Vec<f64> = clouds
        .iter()
        .filter(|c| !c.cut && c.area >= min_pixels)
        .map(|c| (c.area as f64).sqrt() * pixel_m)
        .collect();
    let smallest = sizes.iter().copied().fold(f64::INFINITY, f64::min);
    if !smallest.is_finite() {
        return None;
    }
    let mut counts: Vec<usize> = Vec::new();
    for l in &sizes {
        let k = ((l / smallest).log10() * BINS_PER_DECADE).floor() as usize;
        if counts.len() <= k {
            counts.resize(k + 1, 0);
        }
        counts[k] += 1;
    }
    let step = 10f64.powf(1.0 / BINS_PER_DECADE);
    let points: Vec<(f64, f64, f64)> = counts
        .iter()
        .enumerate()
        .filter(|(_, n)| **n >= 3)
        .map(|(k, &n)| {
            let lo = smallest * step.powi(k as i32);
            let centre = lo * step.sqrt();
            // The density per metre of size: the count over the bin's width.
            (centre.ln(), (n as f64 / (lo * (step - 1.0))).ln(), centre)
        })
        .collect();
    let s = fit(&points.iter().map(|p| (p.0, p.1)).collect::<Vec<_>>())?;
    let range = [
        points.first().map_or(0.0, |p| p.2),
        points.last().map_or(0.0, |p| p.2),
    ];
    Some((
        Slope {
            slope: -s.slope,
            ..s
        },
        range,
    ))
}

/// The scene looked at straight down from far above: a square of `extent_m` on a side at the
/// cloud layer's middle, `size` pixels, the analytic sky (the transmittance does not depend on
/// the light).
fn top_down(scene: &Scene, extent_m: f64, size: u32) -> Scene {
    let mut s = scene.clone().with_size(size, size);
    let mid = 0.5 * (s.atmosphere.cloud_bottom_m + s.atmosphere.cloud_top_m);
    let half_fov = 5f64.to_radians();
    s.camera.fov_y_deg = 2.0 * half_fov.to_degrees();
    s.camera.position = [0.0, mid + 0.5 * extent_m / half_fov.tan(), 0.0];
    s.camera.pitch_deg = -90.0;
    s.camera.yaw_deg = 0.0;
    s.animation = None;
    s.atmosphere.sky = SkyModel::Analytic;
    s.atmosphere.light_shafts = false;
    s.sky = Default::default();
    s.quality.temporal = stratus_scene::Temporal::Off;
    s
}

/// How a field is measured: the square seen, its pixels, the cloud threshold and the smallest
/// cloud the fits use.
#[derive(Clone, Copy, Debug)]
pub struct Measure {
    /// The side of the square seen, metres.
    pub extent_m: f64,
    /// Pixels on a side.
    pub size: u32,
    /// A pixel is cloud where the transmittance straight down is below this.
    pub threshold: f64,
    /// The smallest cloud the fits use, pixels.
    pub min_pixels: usize,
}

impl Default for Measure {
    /// The command's defaults: 35 km at 512 px, threshold 0.5, clouds of 16 px or more.
    fn default() -> Self {
        Self {
            extent_m: 35_000.0,
            size: 512,
            threshold: 0.5,
            min_pixels: 16,
        }
    }
}

/// The field statistics of `scene`'s clouds seen straight down on `renderer`, with every
/// cloud and each pixel's cloud (an index into them, or past their end where clear).
pub fn measure(
    renderer: &mut dyn stratus_graph::Backend,
    scene: &Scene,
    name: String,
    how: &Measure,
) -> Result<(FieldStats, Vec<Cloud>, Vec<usize>)> {
    let view = top_down(scene, how.extent_m, how.size);
    view.validate()
        .map_err(|e| anyhow::anyhow!("the straight-down view of {name}: {e}"))?;
    let noise = Arc::new(stratus::noise_for(&view));
    let plan = FramePlan::for_scene(&view, false)?;
    let frame = renderer
        .render(&FrameInput::new(&plan, &view, &noise).with_readback(Readback::output()))
        .map_err(|e| anyhow::anyhow!("{e}"))?;
    let (w, h) = (frame.width as usize, frame.height as usize);
    let mask: Vec<bool> = frame
        .radiance
        .chunks(4)
        .map(|p| f64::from(p[3]) < how.threshold)
        .collect();
    if mask.len() != w * h {
        bail!("the renderer read back {} pixels for {w}x{h}", mask.len());
    }
    let (all, labels) = components(&mask, w, h);
    let pixel_m = how.extent_m / f64::from(how.size);
    let b = size_exponent(&all, how.min_pixels, pixel_m);
    let stats = FieldStats {
        scene: name,
        extent_m: how.extent_m,
        size: how.size,
        threshold: how.threshold,
        cloud_fraction: mask.iter().filter(|m| **m).count() as f64 / mask.len() as f64,
        clouds: all.iter().filter(|c| !c.cut).count(),
        cut: all.iter().filter(|c| c.cut).count(),
        d: dimension(&all, how.min_pixels),
        b: b.map(|b| b.0),
        b_range_m: b.map(|b| b.1),
        largest_m: all
            .iter()
            .map(|c| (c.area as f64).sqrt() * pixel_m)
            .fold(0.0, f64::max),
    };
    Ok((stats, all, labels))
}

/// Runs `stratus measure-field`.
pub fn run(args: MeasureFieldArgs) -> Result<()> {
    if !(args.extent_m > 0.0 && args.extent_m.is_finite()) {
        bail!(
            "--extent-m {}: must be a positive number of metres",
            args.extent_m
        );
    }
    if !(args.threshold > 0.0 && args.threshold < 1.0) {
        bail!(
            "--threshold {}: a transmittance strictly between 0 and 1",
            args.threshold
        );
    }
    let (mut scene, mut name) = load_scene(args.preset.as_deref(), args.scene.as_ref(), None)?;
    if let Some(state) = &args.state {
        let s =
            stratus_weather::states::find(state).map_err(|e| anyhow::anyhow!("--state: {e}"))?;
        s.params.apply(&mut scene);
        name = format!("{name} in the {state} state");
    }
    let mut renderer = open(args.backend, &Open::default()).context("opening the renderer")?;
    if std::io::stderr().is_terminal() {
        eprintln!(
            "rendering {name} straight down, {:.0} m across at {} px ({})",
            args.extent_m,
            args.size,
            renderer.describe()
        );
    }
    let how = Measure {
        extent_m: args.extent_m,
        size: args.size,
        threshold: args.threshold,
        min_pixels: args.min_pixels,
    };
    let (stats, all, labels) = measure(renderer.as_mut(), &scene, name, &how)?;
    let (w, h) = (args.size as usize, args.size as usize);
    print_stats(&stats, args.min_pixels);
    if let Some(path) = &args.json {
        stratus_compare::write_file_atomically(
            path,
            (serde_json::to_string_pretty(&stats)? + "\n").as_bytes(),
        )
        .with_context(|| format!("writing {}", path.display()))?;
        println!("wrote {}", path.display());
    }
    if let Some(path) = &args.mask {
        // White for clouds inside the square, grey for those the border cuts, black clear.
        let grey: Vec<u8> = labels
            .iter()
            .map(|&l| match all.get(l) {
                None => 0,
                Some(c) if c.cut => 128,
                Some(_) => 255,
            })
            .collect();
        let mask = image::GrayImage::from_raw(w as u32, h as u32, grey).context("mask size")?;
        stratus_compare::write_atomically(path, |tmp| {
            mask.save_with_format(tmp, image::ImageFormat::Png)
        })
        .map_err(|e| anyhow::anyhow!("writing {}: {e}", path.display()))?;
        println!("wrote {}", path.display());
    }
    Ok(())
}

fn print_stats(s: &FieldStats, min_pixels: usize) {
    println!(
        "{}: {:.0} m across at {} px ({:.1} m a pixel), cloud where the transmittance is below {}",
        s.scene,
        s.extent_m,
        s.size,
        s.extent_m / f64::from(s.size),
        s.threshold
    );
    println!(
        "cloud fraction {:.3}; {} clouds inside the square (and {} cut by its border); the largest {:.0} m across (sqrt of its area)",
        s.cloud_fraction, s.clouds, s.cut, s.largest_m
    );
    match s.d {
        Some(d) => println!(
            "area-perimeter dimension D = {:.3} ± {:.3} over {} clouds of at least {min_pixels} px (real fields: 1.35, Lovejoy 1982; cumulus 1.2-1.55, Cahalan and Joseph 1989)",
            d.slope, d.stderr, d.points
        ),
        None => println!(
            "area-perimeter dimension D: fewer than 3 clouds of at least {min_pixels} px inside the square"
        ),
    }
    match (s.b, s.b_range_m) {
        (Some(b), Some([lo, hi])) => println!(
            "size density n(L) ∝ L^-b: b = {:.2} ± {:.2} over {} bins, L {:.0}-{:.0} m ({:.2} decades) (fair-weather cumulus: 1.7-2.0, Benner and Curry 1998, Neggers et al. 2003)",
            b.slope,
            b.stderr,
            b.points,
            lo,
            hi,
            (hi / lo).log10()
        ),
        _ => println!("size density exponent b: fewer than 3 size bins of 3 or more clouds"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn components_count_their_area_and_edges() {
        // A 2x2 square inside, and an L touching the border.
        let rows = ["......", ".##...", ".##..#", "....##"];
        let mask: Vec<bool> = rows
            .iter()
            .flat_map(|r| r.chars().map(|c| c == '#'))
            .collect();
        let c = clouds(&mask, 6, 4);
        assert_eq!(c.len(), 2);
        assert_eq!(
            c[0],
            Cloud {
                area: 4,
                perimeter: 8,
                cut: false
            }
        );
        assert_eq!(c[1].area, 3);
        assert!(c[1].cut);
        // The cut cloud's edges include those on the image's border.
        assert_eq!(c[1].perimeter, 8);
    }

    #[test]
    fn squares_have_dimension_one_and_a_known_size_law_is_recovered() {
        // Squares: P = 4 sqrt(A), so D = 1 exactly.
        let squares: Vec<Cloud> = (4..40)
            .map(|s| Cloud {
                area: s * s,
                perimeter: 4 * s,
                cut: false,
            })
            .collect();
        let d = dimension(&squares, 1).unwrap();
        assert!((d.slope - 1.0).abs() < 1e-9, "{d:?}");
        // Sizes drawn so that n(L) ∝ L^-2: counts per log bin fall as L^-1.
        let mut field = Vec::new();
        for l in 2..200usize {
            let n = (4000.0 / (l * l) as f64).round() as usize;
            for _ in 0..n {
                field.push(Cloud {
                    area: l * l,
                    perimeter: 4 * l,
                    cut: false,
                });
            }
        }
        let (b, range) = size_exponent(&field, 1, 10.0).unwrap();
        assert!((b.slope - 2.0).abs() < 0.15, "{b:?} over {range:?}");
        // Cut clouds are left out.
        let cut = vec![
            Cloud {
                area: 100,
                perimeter: 40,
                cut: true
            };
            10
        ];
        assert!(dimension(&cut, 1).is_none());
    }
}
