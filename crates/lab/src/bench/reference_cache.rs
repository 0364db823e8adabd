//! The references the bench measures against, rendered once and cached by a hash of the scene
//! (normalised: fields the reference ignores are reset) and the reference settings, under
//! `$XDG_CACHE_HOME/stratus` or else `target/stratus-cache/` (relative to the working
//! directory). Where the cache lacks one, the committed truths of the multiple-scattering fit
//! (`docs/fit/truths/`, the same files, written by `stratus fit-scattering`) are read: an
//! all-orders truth of 8192 paths a pixel is seconds on a GPU and 10-30 minutes a scene on
//! lavapipe, so the fit's data travels with the repository.

use std::{fmt::Write as _, path::PathBuf, sync::Arc};

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
const COMMITTED_TRUTHS: &str = "docs/fit/truths";

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
    // Cost-only and amortising methods, and the frame (which seeds the path tracer): the
    // reference of every frame of a still camera is the same image.
    s.quality.temporal = d.temporal;
    s.quality.dynamic_step = d.dynamic_step;
    s.quality.checkerboard = d.checkerboard;
    s.quality.empty_space_skip = d.empty_space_skip;
    s.quality.frame = d.frame;
    // The baselines draw the same density: their truth is the volumetric model's.
    s.quality.method = d.method;
    let mc = scene.lighting.multiple_scattering.octaves > 0;
    if mc {
        // Real-time-only terms the path tracer does not model, set to fixed values (not the
        // defaults, which the multiple-scattering fit changes) so that the key stays put.
        s.lighting.multiple_scattering = PREFIT_OCTAVES;
        s.lighting.beer_powder = false;
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

/// The light model's terms added after the cache's v2 (reset to fixed values by
/// `reference_for` like the octaves, and ignored by every reference): left out of the key so
/// that the truths rendered before them stay valid.
const KEYLESS_FIELDS: [&str; 11] = [
    "side_light = ",
    "coverage_exponent = ",
    "far_chord_m = ",
    "limb_darkening = ",
    "forward_lobe = ",
    "forward_lobe_g = ",
    "vertical_anisotropy = ",
    "deck_escape = ",
    "steep_light = ",
    "steep_light_scale = ",
    "downward_dimming = ",
];

/// The scene's TOML as the cache key hashes it: `s.to_toml()` without the `KEYLESS_FIELDS`,
/// and without what the path tracer does not render (the post effects, the exposure's range:
/// the truth is the clouds' radiance; the rainbow, which the composite adds in front of them),
/// so that a stylised preset shares its clouds' truth.
fn key_toml(s: &Scene) -> String {
    let mut s = s.clone();
    s.post = stratus_scene::Post::default();
    s.rainbow = stratus_scene::Rainbow::default();
    s.camera.exposure_range = None;
    s.to_toml()
        .split_inclusive('\n')
        .filter(|line| !KEYLESS_FIELDS.iter().any(|k| line.starts_with(k)))
        .collect()
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
    let mut s = scene.clone();
    s.quality.integrator = stratus_scene::Integrator::Pathtrace;
    s.quality.path_orders = 0;
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

/// Renders (or loads from the cache, or from the committed truths) the reference of `scene`.
/// The all-orders truth comes from the GPU path tracer on `gpu` where one is given, else from
/// the CPU path tracer.
pub(crate) fn reference(
    scene: &Scene,
    noise: &Arc<NoiseSet>,
    mc_spp: u32,
    gpu: Option<&mut dyn Backend>,
) -> Result<Reference> {
    let (mut integrator, s, mc) = reference_for(scene);
    if let Integrator::MonteCarlo { spp, .. } = &mut integrator {
        *spp = mc_spp;
    }
    let on_gpu = mc && gpu.is_some();
    let key = {
        let mut h = Sha256::new();
        h.update(key_toml(&s).as_bytes());
        h.update(format!("{integrator:?}").as_bytes());
        if on_gpu {
            h.update(b"gpu-pathtrace");
        }
        // v2: the GPU path tracer traces a workgroup of paths per pixel a frame (other
        // random streams than v1's one path a frame).
        h.update(b"stratus-reference-cache-v2");
        // Under the physical sky the truths changed (those before are not these scenes'
        // truths; the others' stay valid): a path leaving the clouds sees the sky from its last
        // collision, not from the camera, and the converged quadrature, like the march, looks
        // the ambient up at the sun's angle at each sample.
        if s.atmosphere.sky == stratus_scene::SkyModel::Physical {
            h.update(if mc {
                b"environment-from-the-vertex".as_slice()
            } else {
                b"ambient-by-the-sun-angle-at-the-sample".as_slice()
            });
        }
        h.finalize()
            .iter()
            .take(12)
            .fold(String::new(), |mut acc, b| {
                let _ = write!(acc, "{b:02x}");
                acc
            })
    };
    let label = if on_gpu {
        format!("pathtrace-gpu-{mc_spp}spp")
    } else if mc {
        format!("montecarlo-{mc_spp}spp")
    } else {
        "quadrature".to_string()
    };
    let dir = cache_dir();
    let name = format!("ref-{key}.bin");
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
            // Minutes on lavapipe: a bar of paths (drawn on a terminal only).
            let bar = indicatif::ProgressBar::new(u64::from(mc_spp));
            if let Ok(style) = indicatif::ProgressStyle::with_template(
                "all-orders truth [{elapsed_precise}] {wide_bar} {pos}/{len} paths per pixel",
            ) {
                bar.set_style(style);
            }
            let f = pathtrace_gpu(r, &s, noise, mc_spp, &|i| bar.set_position(u64::from(i)))?;
            bar.finish_and_clear();
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

fn decode(b: &[u8], w: u32, h: u32) -> Option<FrameOutput> {
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

    /// The key leaves out exactly the light model's later terms: a reference's scene hashes as
    /// it did before they existed, and nothing else drops out.
    #[test]
    fn the_key_drops_only_the_later_light_model_terms() {
        let (_, s, _) = reference_for(&Scene::default());
        let full = s.to_toml();
        let key = key_toml(&s);
        let dropped: Vec<&str> = full
            .lines()
            .filter(|l| !key.lines().any(|k| k == *l))
            .collect();
        assert_eq!(
            dropped,
            [
                "side_light = 0.0",
                "coverage_exponent = 0.0",
                "far_chord_m = 0.0",
                "limb_darkening = 0.0",
                "forward_lobe = 0.0",
                "forward_lobe_g = 0.0",
                "vertical_anisotropy = 0.0",
                "deck_escape = 0.0",
                "steep_light = 0.0",
                "steep_light_scale = 1.0",
                "downward_dimming = 0.0"
            ],
            "{full}"
        );
        assert_eq!(full.lines().count(), key.lines().count() + 11);
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
