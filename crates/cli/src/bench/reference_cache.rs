//! The references the bench measures against, rendered once and cached by a hash of the scene
//! (normalised: fields the reference ignores are reset) and the reference settings, under
//! `$XDG_CACHE_HOME/stratus` or else `target/stratus-cache/` (relative to the working
//! directory).

use std::{fmt::Write as _, path::PathBuf};

use anyhow::{Context, Result};
use sha2::{Digest, Sha256};
use stratus_graph::FrameOutput;
use stratus_noise::NoiseSet;
use stratus_reference::{Integrator, QuadratureSettings};
use stratus_scene::Scene;

pub(super) fn cache_dir() -> PathBuf {
    match std::env::var_os("XDG_CACHE_HOME") {
        Some(d) if !d.is_empty() => PathBuf::from(d).join("stratus"),
        _ => PathBuf::from("target/stratus-cache"),
    }
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
    // Cost-only and amortising methods, and the frame (which seeds the path tracer): the
    // reference of every frame of a still camera is the same image.
    s.quality.temporal = d.temporal;
    s.quality.dynamic_step = d.dynamic_step;
    s.quality.checkerboard = d.checkerboard;
    s.quality.empty_space_skip = d.empty_space_skip;
    s.quality.frame = d.frame;
    let mc = scene.lighting.multiple_scattering.octaves > 0;
    if mc {
        // Real-time-only terms the path tracer does not model.
        s.lighting.multiple_scattering = Default::default();
        s.lighting.beer_powder = false;
        (Integrator::MonteCarlo { spp: 0, orders: 0 }, s, true)
    } else {
        (
            Integrator::Quadrature(QuadratureSettings::converged()),
            s,
            false,
        )
    }
}

/// Renders (or loads from the cache) the reference of `scene`.
pub(super) fn reference(
    scene: &Scene,
    noise: &NoiseSet,
    mc_spp: u32,
) -> Result<(FrameOutput, String)> {
    let (mut integrator, s, mc) = reference_for(scene);
    if let Integrator::MonteCarlo { spp, .. } = &mut integrator {
        *spp = mc_spp;
    }
    let key = {
        let mut h = Sha256::new();
        h.update(s.to_toml().as_bytes());
        h.update(format!("{integrator:?}").as_bytes());
        h.update(b"stratus-reference-cache-v1");
        h.finalize()
            .iter()
            .take(12)
            .fold(String::new(), |mut acc, b| {
                let _ = write!(acc, "{b:02x}");
                acc
            })
    };
    let label = if mc {
        format!("montecarlo-{mc_spp}spp")
    } else {
        "quadrature".to_string()
    };
    let dir = cache_dir();
    let path = dir.join(format!("ref-{key}.bin"));
    let [w, h] = s.camera.resolution;
    if let Ok(bytes) = std::fs::read(&path) {
        if let Some(f) = decode(&bytes, w, h) {
            return Ok((f, label));
        }
    }
    let f = stratus_reference::render(&s, noise, &integrator, false);
    std::fs::create_dir_all(&dir).with_context(|| format!("creating {}", dir.display()))?;
    std::fs::write(&path, encode(&f)).with_context(|| format!("writing {}", path.display()))?;
    Ok((f, label))
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

#[cfg(test)]
mod tests {
    use super::*;

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
