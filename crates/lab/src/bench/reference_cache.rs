//! The references the bench measures against, rendered once and cached by a hash of the scene
//! (normalised: fields the reference ignores are reset) and the reference settings, under
//! `$XDG_CACHE_HOME/stratus` or else `target/stratus-cache/` (relative to the working
//! directory). Where the cache lacks one, the committed truths of the multiple-scattering fit
//! (`docs/fit/truths/`, the same files, written by `stratus fit-scattering`) are read: an
//! all-orders truth of 8192 paths a pixel is seconds on a GPU and 10-30 minutes a scene on
//! lavapipe, so the fit's data travels with the repository.

use std::{
    fmt::Write as _,
    path::{Path, PathBuf},
    sync::Arc,
};

use anyhow::{Context, Result};
use sha2::{Digest, Sha256};
use stratus_graph::{Backend, FrameInput, FrameOutput, FramePlan, Readback};
use stratus_noise::NoiseSet;
use stratus_quality::PREFIT_OCTAVES;
use stratus_reference::{Integrator, QuadratureSettings};
use stratus_scene::Scene;

use stratus_tool::scene_io::check_finite;

pub(super) fn cache_dir() -> PathBuf {
    match std::env::var_os("XDG_CACHE_HOME") {
        Some(d) if !d.is_empty() => PathBuf::from(d).join("stratus"),
        _ => PathBuf::from("target/stratus-cache"),
    }
}

/// The committed truths (`<fit dir>/truths` of the published fit), relative to the working
/// directory like the cache: read where the cache has no file of the key.
pub(crate) const COMMITTED_TRUTHS: &str = "docs/fit/truths";

/// The precipitation darkening every all-orders truth's key is made with (the march's default
/// when the committed truths were traced; the path tracer does not read it).
const KEYED_PRECIPITATION_DARKENING: f64 = 0.5;

/// The scene's TOML as the key hashes it: as the scene serialised when the committed truths
/// were traced, so that a new default moves no key (the tracer's uniforms, hashed too, still
/// hold every value the tracer reads). `clouds.convective_cells` was written then where it
/// was not 0, its default until the presets moved to convective cells; it is written now
/// where it is not 1 (its `skip_serializing_if`), so a 0 is dropped and a 1 put back.
fn key_text(s: &Scene) -> String {
    let text = s.to_toml();
    let cells = s.clouds.convective_cells;
    let mut out = String::with_capacity(text.len() + 32);
    let mut section = "";
    for line in text.lines() {
        if line.starts_with('[') {
            section = line;
        }
        let clouds = section == "[clouds]";
        if clouds && cells == 0.0 && line.starts_with("convective_cells = ") {
            continue;
        }
        out.push_str(line);
        out.push('\n');
        // The field followed `wispy_billowy`, which is always written.
        if clouds && cells == 1.0 && line.starts_with("wispy_billowy = ") {
            out.push_str("convective_cells = 1.0\n");
        }
    }
    out
}

/// The reference for `scene`: its kind and the scene it renders (fields it ignores reset, so
/// configurations that differ only there share one reference).
fn reference_for(scene: &Scene) -> (Integrator, Scene, bool) {
    let mut s = scene.clone();
    let d = stratus_scene::Quality::default();
    // The converged quadrature and the path tracer override all of these.
    s.quality.view_steps = d.view_steps;
    s.quality.step_length_m = None;
    s.quality.light_steps = d.light_steps;
    s.quality.integration = d.integration;
    s.quality.jitter = d.jitter;
    s.quality.early_exit_transmittance = d.early_exit_transmittance;
    s.quality.light_step_growth = d.light_step_growth;
    s.quality.first_light_step_m = d.first_light_step_m;
    s.quality.close_step_m = d.close_step_m;
    // Cost-only and amortising methods, and the frame (which seeds the path tracer): the
    // reference of every frame of a still camera is the same image.
    s.quality.temporal = d.temporal;
    s.quality.dynamic_step = d.dynamic_step;
    s.quality.checkerboard = d.checkerboard;
    s.quality.empty_space_skip = d.empty_space_skip;
    s.quality.frame = d.frame;
    // The baselines draw the same density: their truth is the volumetric model's.
    s.quality.method = d.method;
    // What the composite adds in front of the clouds' radiance (the post effects, the
    // rainbow) and the display's exposure: a stylised preset shares its clouds' truth.
    s.post = stratus_scene::Post::default();
    s.rainbow = stratus_scene::Rainbow::default();
    s.camera.exposure_range = None;
    let mc = scene.lighting.multiple_scattering.octaves > 0;
    if mc {
        // Real-time-only terms the path tracer does not model, set to fixed values (not the
        // defaults, which the multiple-scattering fit changes) so that the key stays put.
        s.lighting.multiple_scattering = PREFIT_OCTAVES;
        s.lighting.beer_powder = false;
        let d = stratus_scene::Lighting::default();
        s.lighting.powder_strength = d.powder_strength;
        // The march's stand-in for rain's dark base, which the path tracer leaves to the
        // density (precipitation raises it): a fixed value, like the octaves', so that choosing
        // the march's default again moves no key.
        s.lighting.precipitation_darkening = KEYED_PRECIPITATION_DARKENING;
        (Integrator::MonteCarlo { spp: 0, orders: 0 }, s, true)
    } else {
        // Single scattering: the octave constants do nothing (fixed, as above).
        s.lighting.multiple_scattering = stratus_scene::MultipleScattering {
            octaves: 0,
            ..PREFIT_OCTAVES
        };
        (
            Integrator::Quadrature(QuadratureSettings::converged()),
            s,
            false,
        )
    }
}

/// The scene the GPU path tracer renders for `scene`'s all-orders truth: the path-traced
/// integrator, every order.
fn traced(scene: &Scene) -> Scene {
    let mut s = scene.clone();
    s.quality.integrator = stratus_scene::Integrator::Pathtrace;
    s.quality.path_orders = 0;
    s
}

/// What the GPU path tracer's truth of `s` (a scene of [`traced`]) depends on besides the
/// scene's settings, hashed: what its frame plan executes (the WGSL its passes reach, compacted
/// and compiled: [`stratus_shaders::plan_digest`]), the noise textures it samples and the
/// uniform bytes the scene becomes. A change to any of them is another truth; a change to
/// code the tracer does not reach is not.
pub(crate) fn tracer_digest(s: &Scene, noise: &NoiseSet) -> Result<String> {
    let plan = FramePlan::for_scene(s, false)?;
    let tree = stratus_shaders::ShaderTree::embedded()
        .map_err(|e| anyhow::anyhow!("the embedded WGSL: {e}"))?;
    let code = stratus_shaders::plan_digest(&tree, &plan)
        .map_err(|e| anyhow::anyhow!("hashing the path tracer's plan: {e}"))?;
    let mut h = Sha256::new();
    h.update(code.as_bytes());
    h.update(noise.sha256().as_bytes());
    h.update(s.uniforms().as_bytes());
    Ok(hex12(&h.finalize()))
}

fn hex12(bytes: &[u8]) -> String {
    bytes.iter().take(12).fold(String::new(), |mut acc, b| {
        let _ = write!(acc, "{b:02x}");
        acc
    })
}

/// `spp` paths per pixel (rounded up to whole frames) of the GPU path tracer
/// (`wgsl/pathtrace.wgsl`) on `renderer`, accumulated in its history over frames: the
/// all-orders truth of `scene` (whose octaves and Beer-Powder the path tracer ignores).
/// `progress` is told the paths per pixel so far after each frame.
pub(crate) fn pathtrace_gpu(
    renderer: &mut dyn Backend,
    scene: &Scene,
    noise: &Arc<NoiseSet>,
    spp: u32,
    progress: &dyn Fn(u32),
) -> Result<FrameOutput> {
    // The plan of a path-traced scene leaves out the march's methods.
    let s = traced(scene);
    let plan = FramePlan::for_scene(&s, false)?;
    let per_frame = plan
        .paths_per_frame()
        .context("the path-traced plan has no pathtrace pass")?;
    let frames = spp.max(1).div_ceil(per_frame);
    let mut last = None;
    for i in 0..frames {
        let mut f = s.clone();
        f.quality.frame = i;
        // The first frame starts over: the renderer may hold another scene's paths.
        let mut input = FrameInput::new(&plan, &f, noise).with_readback(if i + 1 == frames {
            // With the per-pixel moments, for the noise estimate.
            Readback {
                output: true,
                resources: vec!["history-meta".into()],
            }
        } else {
            Readback::none()
        });
        if i == 0 {
            input = input.with_cut();
        }
        last = Some(
            renderer
                .render(&input)
                .map_err(|e| anyhow::anyhow!("{e}"))?,
        );
        progress((i + 1) * per_frame);
    }
    let out = last.expect("at least one path");
    check_finite(&out)?;
    Ok(out)
}

/// A reference and where it came from.
pub(crate) struct Reference {
    /// The rendered (or loaded) reference.
    pub frame: FrameOutput,
    /// Its kind, for reports (`pathtrace-gpu-8192spp`, `quadrature`).
    pub label: String,
    /// Its file in the cache (present once this returns), named by the key.
    pub file: PathBuf,
}

/// What names a scene's reference: the scene it renders, how, and the key of its file.
pub(crate) struct ReferenceKey {
    integrator: Integrator,
    /// The scene the reference renders (fields it ignores reset).
    scene: Scene,
    /// An all-orders truth (else single scattering by the converged quadrature).
    mc: bool,
    /// The hash that names its file, `ref-<key>.bin`.
    pub key: String,
    /// Its kind, for reports.
    pub label: String,
}

impl ReferenceKey {
    /// The reference's file name in the cache and among the committed truths.
    pub fn file_name(&self) -> String {
        format!("ref-{}.bin", self.key)
    }
}

/// The key of `scene`'s reference: `mc_spp` paths a pixel for an all-orders truth, on the GPU
/// path tracer where `on_gpu`. The key hashes the normalised scene, the integrator and, for the
/// GPU path tracer, [`tracer_digest`]: a truth rendered by another tracer, or from other noise,
/// is another key, never silently reused. The CPU references hash the noise and the cache's
/// version alone (their Rust is not hashed: they are cached, never committed).
pub(crate) fn reference_key(
    scene: &Scene,
    noise: &NoiseSet,
    mc_spp: u32,
    on_gpu: bool,
) -> Result<ReferenceKey> {
    let (mut integrator, s, mc) = reference_for(scene);
    if let Integrator::MonteCarlo { spp, .. } = &mut integrator {
        *spp = mc_spp;
    }
    let on_gpu = mc && on_gpu;
    let mut h = Sha256::new();
    h.update(key_text(&s).as_bytes());
    h.update(format!("{integrator:?}").as_bytes());
    if on_gpu {
        h.update(b"gpu-pathtrace");
        h.update(tracer_digest(&traced(&s), noise)?.as_bytes());
    } else {
        h.update(b"cpu-reference");
        h.update(noise.sha256().as_bytes());
    }
    // v3: the tracer's code, noise and uniforms are in the key (v2 named the scene alone).
    h.update(b"stratus-reference-cache-v3");
    let label = if on_gpu {
        format!("pathtrace-gpu-{mc_spp}spp")
    } else if mc {
        format!("montecarlo-{mc_spp}spp")
    } else {
        "quadrature".to_string()
    };
    Ok(ReferenceKey {
        integrator,
        scene: s,
        mc,
        key: hex12(&h.finalize()),
        label,
    })
}

/// Renders (or loads from the cache, or from the committed truths) the reference of `scene`.
/// The all-orders truth comes from the GPU path tracer on `gpu` where one is given, else from
/// the CPU path tracer.
pub(crate) fn reference(
    scene: &Scene,
    noise: &Arc<NoiseSet>,
    mc_spp: u32,
    gpu: Option<&mut dyn Backend>,
) -> Result<Reference> {
    let rk = reference_key(scene, noise, mc_spp, gpu.is_some())?;
    let name = rk.file_name();
    let ReferenceKey {
        integrator,
        scene: s,
        mc,
        label,
        ..
    } = rk;
    let dir = cache_dir();
    let path = dir.join(&name);
    let [w, h] = s.camera.resolution;
    let done = |frame: FrameOutput| Reference {
        frame,
        label: label.clone(),
        file: path.clone(),
    };
    // The cache, else the committed truths (copied into the cache: the fit copies its truths
    // from there).
    let committed = PathBuf::from(COMMITTED_TRUTHS).join(&name);
    for file in [&path, &committed] {
        let Ok(bytes) = std::fs::read(file) else {
            continue;
        };
        let Some(f) = decode(&bytes, w, h) else {
            continue;
        };
        if *file != path {
            std::fs::create_dir_all(&dir).with_context(|| format!("creating {}", dir.display()))?;
            stratus_compare::write_file_atomically(&path, &bytes)
                .with_context(|| format!("writing {}", path.display()))?;
        }
        return Ok(done(f));
    }
    let f = match gpu {
        Some(r) if mc => {
            let f = traced_with_bar(r, &s, noise, mc_spp, "all-orders truth")?;
            report_noise(&f);
            f
        }
        _ => stratus_reference::render(&s, noise, &integrator, false),
    };
    std::fs::create_dir_all(&dir).with_context(|| format!("creating {}", dir.display()))?;
    stratus_compare::write_file_atomically(&path, &encode(&f))
        .with_context(|| format!("writing {}", path.display()))?;
    Ok(done(f))
}

/// One row of the committed truths' `index.csv`: a truth's file and the scene it is of.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct CommittedTruth {
    /// Its file in `docs/fit/truths`, `ref-<key>.bin`.
    pub file: String,
    /// The scene's name: a training scene's description or a preset's name.
    pub scene: String,
    /// `train` or `held-out`.
    pub set: String,
    /// Paths per pixel it was traced with.
    pub paths: u32,
    /// Its size.
    pub width: u32,
    /// Its size.
    pub height: u32,
}

/// The first line of `index.csv`.
pub(crate) const INDEX_HEADER: &str = "file,scene,set,paths_per_pixel,width,height";

/// Reads `dir/index.csv` (the committed truths' index); a malformed row is an error naming it.
pub(crate) fn read_index(dir: &Path) -> Result<Vec<CommittedTruth>> {
    let path = dir.join("index.csv");
    let text =
        std::fs::read_to_string(&path).with_context(|| format!("reading {}", path.display()))?;
    let mut rows = Vec::new();
    for (n, line) in text.lines().enumerate().skip(1) {
        let bad = || {
            format!(
                "{}:{}: expected {INDEX_HEADER}, got `{line}`",
                path.display(),
                n + 1
            )
        };
        // The scene is quoted (names hold commas); the rest are plain.
        let (file, rest) = line.split_once(",\"").with_context(bad)?;
        let (scene, rest) = rest.split_once("\",").with_context(bad)?;
        let f: Vec<&str> = rest.split(',').collect();
        let [set, paths, width, height] = f[..] else {
            anyhow::bail!(bad());
        };
        rows.push(CommittedTruth {
            file: file.to_string(),
            scene: scene.to_string(),
            set: set.to_string(),
            paths: paths.parse().with_context(bad)?,
            width: width.parse().with_context(bad)?,
            height: height.parse().with_context(bad)?,
        });
    }
    Ok(rows)
}

/// Writes `rows` as `dir/index.csv`.
pub(crate) fn write_index(dir: &Path, rows: &[CommittedTruth]) -> Result<()> {
    let mut text = format!("{INDEX_HEADER}\n");
    for r in rows {
        let _ = writeln!(
            text,
            "{},\"{}\",{},{},{},{}",
            r.file, r.scene, r.set, r.paths, r.width, r.height
        );
    }
    let path = dir.join("index.csv");
    stratus_compare::write_file_atomically(&path, text.as_bytes())
        .with_context(|| format!("writing {}", path.display()))
}

/// The committed truth of `scene` (named `name` in the index) for the tracer this build
/// holds, at the paths per pixel the index records for it: an error, saying what to run,
/// where the index has none or has one under another key (the tracer, its noise or the
/// scene's settings changed since it was traced).
pub(crate) fn committed_truth(
    dir: &Path,
    name: &str,
    scene: &Scene,
    noise: &NoiseSet,
) -> Result<FrameOutput> {
    let rows = read_index(dir)?;
    let Some(row) = rows
        .iter()
        .filter(|r| r.scene == name)
        .max_by_key(|r| r.paths)
    else {
        anyhow::bail!(
            "{}: no committed truth of `{name}`: render one (stratus fit-scattering --evaluate --scenes <its name> --spp 2048 --out docs/fit; minutes on a GPU)",
            dir.display()
        );
    };
    let key = reference_key(scene, noise, row.paths, true)?;
    if key.file_name() != row.file {
        anyhow::bail!(
            "{}: the truth of `{name}` ({}, {} paths a pixel) was traced under another key than this build's ({}): the path tracer, its noise or the scene changed since. `stratus fit-scattering --recheck-truths` carries it over where a fresh trace agrees with it, else render it again",
            dir.display(),
            row.file,
            row.paths,
            key.file_name()
        );
    }
    let [w, h] = key.scene.camera.resolution;
    let path = dir.join(&row.file);
    let bytes = std::fs::read(&path).with_context(|| format!("reading {}", path.display()))?;
    decode(&bytes, w, h).with_context(|| {
        format!(
            "{}: not a {w}x{h} truth of `{name}` (index.csv names it)",
            path.display()
        )
    })
}

/// The bounds of a recheck: a block's z, as the path-tracer agreement test holds the GPU and
/// CPU tracers to (`tests/tests/path_tracer.rs`), and the pooled z of all cloudy blocks.
const RECHECK_BLOCK_Z: f64 = 4.0;
const RECHECK_POOLED_Z: f64 = 3.0;
/// Blocks darker than this share of the brightest are not judged (sky at night, ground).
const RECHECK_EMPTY: f64 = 0.02;

/// How a fresh trace compares with a committed truth.
#[derive(Clone, Debug)]
pub(crate) struct Recheck {
    /// The largest |z| of an 8x8 block's mean luminance.
    pub worst_block_z: f64,
    /// The z of all judged blocks' summed difference.
    pub pooled_z: f64,
    /// The summed difference over the truth's summed luminance (fresh - truth).
    pub relative: f64,
    /// The uniform relative bias the pooled check would just see.
    pub detectable: f64,
    /// Blocks judged.
    pub blocks: usize,
}

impl Recheck {
    /// Within noise: every block and the pool within their bounds.
    pub fn agrees(&self) -> bool {
        self.worst_block_z < RECHECK_BLOCK_Z && self.pooled_z.abs() < RECHECK_POOLED_Z
    }
}

/// Compares a fresh trace (`fresh` with its `history-meta`, `fresh_paths` a pixel) with a
/// truth of `truth_paths` a pixel, per 8x8 block of mean luminance: the truth's variance is
/// the fresh one's scaled by the ratio of paths (it has no moments of its own).
pub(crate) fn recheck(
    truth: &FrameOutput,
    truth_paths: u32,
    fresh: &FrameOutput,
) -> Result<Recheck> {
    let meta = fresh
        .resources
        .get("history-meta")
        .context("the fresh trace has no history-meta to estimate its noise")?;
    let f = stratus_graph::block_means(fresh, meta, 8).context("the fresh trace's blocks")?;
    let t = stratus_graph::block_means(truth, meta, 8).context("the truth's blocks")?;
    let paths = meta
        .get(4..8)
        .map(|c| f64::from(f32::from_le_bytes([c[0], c[1], c[2], c[3]])))
        .unwrap_or(0.0);
    anyhow::ensure!(paths > 1.0, "the fresh trace has {paths} paths a pixel");
    let scale = 1.0 + paths / f64::from(truth_paths.max(1));
    let brightest = t.iter().map(|b| b.mean).fold(0.0, f64::max);
    if brightest <= 0.0 {
        // A truth without clouds (`weather clear`) holds no light to weigh: it agrees exactly
        // with a fresh trace that holds none either, and differs from one that holds any.
        let fresh_light = f.iter().map(|b| b.mean).fold(0.0, f64::max);
        let z = if fresh_light > 0.0 {
            f64::INFINITY
        } else {
            0.0
        };
        return Ok(Recheck {
            worst_block_z: z,
            pooled_z: z,
            relative: 0.0,
            detectable: 0.0,
            blocks: 0,
        });
    }
    let (mut diff, mut var, mut total, mut blocks, mut worst) = (0.0, 0.0, 0.0, 0, 0.0f64);
    for (a, b) in f.iter().zip(&t) {
        if b.mean <= RECHECK_EMPTY * brightest || a.variance <= 0.0 {
            continue;
        }
        let v = a.variance * scale;
        worst = worst.max(((a.mean - b.mean) / v.sqrt()).abs());
        diff += a.mean - b.mean;
        var += v;
        total += b.mean;
        blocks += 1;
    }
    anyhow::ensure!(blocks > 0, "no block of the truth holds light to compare");
    Ok(Recheck {
        worst_block_z: worst,
        pooled_z: diff / var.sqrt(),
        relative: diff / total,
        detectable: RECHECK_POOLED_Z * var.sqrt() / total,
        blocks,
    })
}

/// Traces `scene` afresh with `paths` a pixel on `gpu` (with the moments of its noise).
pub(crate) fn fresh_trace(
    gpu: &mut dyn Backend,
    scene: &Scene,
    noise: &Arc<NoiseSet>,
    paths: u32,
) -> Result<FrameOutput> {
    let (_, s, _) = reference_for(scene);
    traced_with_bar(gpu, &s, noise, paths, "recheck")
}

/// [`pathtrace_gpu`] with a bar of paths named `what` (minutes on lavapipe; drawn on a
/// terminal only).
fn traced_with_bar(
    gpu: &mut dyn Backend,
    s: &Scene,
    noise: &Arc<NoiseSet>,
    paths: u32,
    what: &str,
) -> Result<FrameOutput> {
    let bar = indicatif::ProgressBar::new(u64::from(paths));
    if let Ok(style) = indicatif::ProgressStyle::with_template(&format!(
        "{what} [{{elapsed_precise}}] {{wide_bar}} {{pos}}/{{len}} paths per pixel"
    )) {
        bar.set_style(style);
    }
    let f = pathtrace_gpu(gpu, s, noise, paths, &|i| bar.set_position(u64::from(i)))?;
    bar.finish_and_clear();
    Ok(f)
}

fn encode(f: &FrameOutput) -> Vec<u8> {
    let mut out = Vec::new();
    out.extend(f.width.to_le_bytes());
    out.extend(f.height.to_le_bytes());
    for v in &f.radiance {
        out.extend(v.to_le_bytes());
    }
    out.extend(&f.image);
    out
}

/// A truth's file (`encode`'s bytes) of a `w` x `h` image; `None` where it is not one.
pub(crate) fn decode(b: &[u8], w: u32, h: u32) -> Option<FrameOutput> {
    let n = (w * h) as usize;
    if b.len() != 8 + 16 * n + 4 * n || b[0..4] != w.to_le_bytes() || b[4..8] != h.to_le_bytes() {
        return None;
    }
    let radiance = b[8..8 + 16 * n]
        .chunks(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    Some(FrameOutput {
        width: w,
        height: h,
        radiance,
        depth: vec![0.0; n],
        image: b[8 + 16 * n..].to_vec(),
        device: "cache".into(),
        ..Default::default()
    })
}

/// Prints how converged a freshly rendered truth is (its 8x8 blocks' noise).
fn report_noise(out: &FrameOutput) {
    if let Some(c) = out
        .resources
        .get("history-meta")
        .and_then(|meta| stratus_tool::convergence::block_noise(out, meta))
    {
        eprintln!(
            "  truth: {} paths a pixel, 8x8 blocks' relative standard error worst {:.2}%, median {:.2}%{}",
            c.paths,
            c.worst * 100.0,
            c.median * 100.0,
            if c.converged() {
                " (converged)"
            } else {
                " (not converged: above 1%)"
            }
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A `w` x `h` trace of luminance `lum` everywhere with `paths` paths a pixel of per-path
    /// variance `var` (its `history-meta`).
    fn trace(w: u32, h: u32, lum: f32, paths: f32, var: f32) -> FrameOutput {
        let n = (w * h) as usize;
        let mut f = FrameOutput {
            width: w,
            height: h,
            radiance: (0..n).flat_map(|_| [lum, lum, lum, 0.0]).collect(),
            ..Default::default()
        };
        // second moment = var (paths - 1) / paths + lum^2 gives back `var` per path.
        let second = var * (paths - 1.0) / paths + lum * lum;
        let meta = (0..n)
            .flat_map(|_| [0.0f32, paths, second, 0.0])
            .flat_map(f32::to_le_bytes)
            .collect();
        f.resources.insert("history-meta".into(), meta);
        f
    }

    /// Noise alone agrees; a uniform bias the pooled check can see does not, although every
    /// block alone is within its bound.
    #[test]
    fn recheck_sees_a_uniform_bias_that_no_block_shows() {
        let truth = trace(64, 32, 1.0, 8192.0, 1.0);
        // 128 paths of per-path variance 1: a block's mean has a standard error of
        // 1 / sqrt(64 * 128) = 1.1%.
        let same = recheck(&truth, 8192, &trace(64, 32, 1.0, 128.0, 1.0)).unwrap();
        assert!(same.agrees() && same.pooled_z.abs() < 1e-9, "{same:?}");
        // 2% brighter: each block's z is about 1.8, the 32 blocks' pooled z about 10.
        let bright = recheck(&truth, 8192, &trace(64, 32, 1.02, 128.0, 1.0)).unwrap();
        assert!(bright.worst_block_z < RECHECK_BLOCK_Z, "{bright:?}");
        assert!(!bright.agrees() && bright.pooled_z > 5.0, "{bright:?}");
        assert!((bright.relative - 0.02).abs() < 1e-6, "{bright:?}");
        assert_eq!(bright.blocks, 32);
    }

    /// A truth without clouds (`weather clear`) agrees with a fresh trace without them and
    /// differs from one with any light, rather than failing the whole recheck.
    #[test]
    fn recheck_of_a_cloudless_truth() {
        let empty = trace(64, 32, 0.0, 8192.0, 0.0);
        let r = recheck(&empty, 8192, &trace(64, 32, 0.0, 128.0, 0.0)).unwrap();
        assert!(r.agrees() && r.blocks == 0, "{r:?}");
        let lit = recheck(&empty, 8192, &trace(64, 32, 0.01, 128.0, 1.0)).unwrap();
        assert!(!lit.agrees(), "{lit:?}");
    }

    #[test]
    fn reference_cache_round_trips() {
        let f = FrameOutput {
            width: 2,
            height: 1,
            radiance: vec![0.5, 1.0, 2.0, 0.25, 0.0, 0.1, 0.2, 1.0],
            depth: vec![0.0; 2],
            image: vec![1, 2, 3, 4, 5, 6, 7, 8],
            ..Default::default()
        };
        let bytes = encode(&f);
        let g = decode(&bytes, 2, 1).unwrap();
        assert_eq!((g.radiance, g.image), (f.radiance, f.image));
        assert!(decode(&bytes, 1, 2).is_none());
    }
}
