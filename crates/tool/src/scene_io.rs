//! Scenes and sizes from the command line, and the checks every renderer's output passes.

use std::path::PathBuf;

use anyhow::{Result, bail};
use stratus_graph::{FrameOutput, MAX_RESOLUTION};
use stratus_scene::Scene;

pub fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("`{s}`: expected WIDTHxHEIGHT, e.g. 256x144"))?;
    let p = |v: &str| {
        v.trim()
            .parse::<u32>()
            .ok()
            .filter(|n| (1..=MAX_RESOLUTION).contains(n))
            .ok_or_else(|| {
                format!(
                    "`{s}`: width and height must be whole numbers within [1, {MAX_RESOLUTION}]"
                )
            })
    };
    Ok((p(w)?, p(h)?))
}

/// Loads the scene the arguments name (default: the default preset) at the requested size.
pub fn load_scene(
    preset: Option<&str>,
    file: Option<&PathBuf>,
    size: Option<(u32, u32)>,
) -> Result<(Scene, String)> {
    let (scene, name) = match (preset, file) {
        (_, Some(f)) => (
            Scene::from_file(f).map_err(|e| anyhow::anyhow!("{e}"))?,
            f.display().to_string(),
        ),
        (Some(p), None) => (
            Scene::preset(p).map_err(|e| anyhow::anyhow!("{e}"))?,
            p.to_string(),
        ),
        (None, None) => (Scene::default(), stratus_scene::DEFAULT_PRESET.to_string()),
    };
    let scene = match size {
        Some((w, h)) => scene.with_size(w, h),
        None => scene,
    };
    scene.validate().map_err(|e| anyhow::anyhow!("{e}"))?;
    Ok((scene, name))
}

/// No NaN or Inf may leave the renderer.
pub fn check_finite(frame: &FrameOutput) -> Result<()> {
    if let Some(i) = frame.radiance.iter().position(|v| !v.is_finite()) {
        let p = i / 4;
        bail!(
            "the renderer produced a non-finite value ({}) at pixel ({}, {}); this is a bug",
            frame.radiance[i],
            p as u32 % frame.width,
            p as u32 / frame.width
        );
    }
    Ok(())
}
