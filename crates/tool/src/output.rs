//! Writing what a render produced: PNG (display image), EXR (linear radiance and
//! transmittance), JSON (work counters and pass times).

use std::path::Path;

use anyhow::{Context, Result, bail};
use stratus_graph::FrameOutput;

/// Writes the frame to `path`: `.png` gets the tone-mapped image, `.exr` the linear radiance
/// with transmittance as alpha. The file is complete or absent (written under a temporary name
/// and renamed), so a render killed mid-write leaves no half image.
pub fn write_image(path: &Path, frame: &FrameOutput) -> Result<()> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("png") => stratus_compare::write_atomically(path, |tmp| {
            image::save_buffer(
                tmp,
                &frame.image,
                frame.width,
                frame.height,
                image::ExtendedColorType::Rgba8,
            )
        })
        .with_context(|| format!("writing {}", path.display())),
        // One EXR writer for the project (deterministic bytes): the compare crate's.
        Some("exr") => stratus_compare::Image::from_frame_radiance(frame)
            .save(path)
            .with_context(|| format!("writing {}", path.display())),
        _ => bail!(
            "--out {}: unknown image type; use a .png (tone-mapped) or .exr (linear) file name",
            path.display()
        ),
    }
}

/// Checks that an output file name has a type we can write, before any work is done.
pub fn check_image_path(path: &Path) -> Result<()> {
    let ok = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("png") || e.eq_ignore_ascii_case("exr"));
    if !ok {
        bail!(
            "--out {}: unknown image type; use a .png (tone-mapped) or .exr (linear) file name",
            path.display()
        );
    }
    Ok(())
}
