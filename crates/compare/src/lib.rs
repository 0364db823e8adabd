//! Image comparison for Stratus (`stratus compare` and the conformance tests).
//!
//! * [`Image`]: one in-memory form for what the renderers write: tone-mapped display images
//!   (PNG, 8-bit, gamma-encoded) and linear radiance (EXR, alpha = transmittance), also built
//!   straight from a [`FrameOutput`].
//! * [`compare`]: RMSE and maximum absolute difference on the stored values (linear radiance
//!   for EXR / [`Image::from_frame_radiance`]), the worst pixel, and FLIP (Andersson et al.
//!   2020, LDR-FLIP through NVIDIA's implementation in the `nv-flip` crate) on the tone-mapped
//!   8-bit images: mean, median, p95, p99 and max of the per-pixel error map.
//! * [`heatmap_rgb8`] / [`write_heatmap`]: the FLIP error map as a magma-coloured image.
//!
//! ```
//! use stratus_compare::{CompareOptions, Image, compare};
//!
//! let a = Image::from_linear_rgba(2, 1, vec![0.5, 0.5, 0.5, 1.0, 0.1, 0.2, 0.3, 1.0]);
//! let mut b = a.clone();
//! b.rgba[0] += 0.25;
//! let c = compare(&a, &b, &CompareOptions::default()).unwrap();
//! assert!((c.max_abs - 0.25).abs() < 1e-6);
//! assert_eq!((c.worst.x, c.worst.y), (0, 0));
//! assert!(c.flip.mean > 0.0);
//! ```

#![warn(missing_docs)]

use std::path::Path;

use stratus_graph::FrameOutput;

/// How an [`Image`]'s values are encoded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Encoding {
    /// Linear radiance (any non-negative value), e.g. an EXR or the march output.
    Linear,
    /// Display values in `[0, 1]` after tone mapping and gamma (an 8-bit PNG / the composited
    /// image), read as sRGB by FLIP.
    Display,
}

/// The file formats [`Image::decode`] reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FileKind {
    /// PNG (8 or 16 bits): a display image.
    Png,
    /// OpenEXR (its RGBA layer): a linear image.
    Exr,
}

/// An RGBA image of f32 values, row-major from the top left.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `4 * width * height` values: r, g, b, a per pixel. For linear images from Stratus, alpha
    /// is the clouds' transmittance.
    pub rgba: Vec<f32>,
    /// What the values mean.
    pub encoding: Encoding,
}

/// What can go wrong loading or comparing images.
#[derive(Debug, thiserror::Error)]
pub enum CompareError {
    /// The file could not be read or decoded.
    #[error("reading {path}: {message}")]
    Read {
        /// The file.
        path: String,
        /// What went wrong.
        message: String,
    },
    /// The file type is not PNG or EXR.
    #[error("{0}: unknown image type; use a .png (display) or .exr (linear) file")]
    UnknownType(String),
    /// The images have different sizes.
    #[error("image sizes differ: {0}x{1} vs {2}x{3}")]
    SizeMismatch(u32, u32, u32, u32),
    /// The images have different encodings (a PNG against an EXR).
    #[error("cannot compare a {0:?} image with a {1:?} image: compare PNG with PNG, EXR with EXR")]
    EncodingMismatch(Encoding, Encoding),
    /// Writing the heat map failed.
    #[error("writing {path}: {message}")]
    Write {
        /// The file.
        path: String,
        /// What went wrong.
        message: String,
    },
}

impl Image {
    /// A display image from 8-bit RGBA (value = byte / 255).
    pub fn from_display_rgba8(width: u32, height: u32, data: &[u8]) -> Self {
        Self {
            width,
            height,
            rgba: data.iter().map(|&b| f32::from(b) / 255.0).collect(),
            encoding: Encoding::Display,
        }
    }

    /// A linear image from RGBA floats.
    pub fn from_linear_rgba(width: u32, height: u32, rgba: Vec<f32>) -> Self {
        assert_eq!(rgba.len(), 4 * (width * height) as usize, "rgba length");
        Self {
            width,
            height,
            rgba,
            encoding: Encoding::Linear,
        }
    }

    /// The frame's linear cloud radiance (rgb) and transmittance (a), as an EXR from
    /// `stratus render` holds them.
    pub fn from_frame_radiance(frame: &FrameOutput) -> Self {
        Self::from_linear_rgba(frame.width, frame.height, frame.radiance.clone())
    }

    /// The frame's composited, tone-mapped 8-bit image, as a PNG from `stratus render` holds it.
    pub fn from_frame_display(frame: &FrameOutput) -> Self {
        Self::from_display_rgba8(frame.width, frame.height, &frame.image)
    }

    /// Loads a PNG (any 8/16-bit format; as a display image) or an OpenEXR file (its RGBA
    /// layer; as a linear image, missing alpha = 1).
    pub fn load(path: &Path) -> Result<Self, CompareError> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        let kind = match ext.as_deref() {
            Some("png") => FileKind::Png,
            Some("exr") => FileKind::Exr,
            _ => return Err(CompareError::UnknownType(path.display().to_string())),
        };
        let bytes = std::fs::read(path).map_err(|e| CompareError::Read {
            path: path.display().to_string(),
            message: e.to_string(),
        })?;
        Self::decode(&bytes, kind, &path.display().to_string())
    }

    /// Decodes a PNG (as a display image) or an OpenEXR file (its RGBA layer, as a linear
    /// image) held in memory; `name` names it in errors.
    pub fn decode(bytes: &[u8], kind: FileKind, name: &str) -> Result<Self, CompareError> {
        let err = |message: String| CompareError::Read {
            path: name.to_string(),
            message,
        };
        match kind {
            FileKind::Png => {
                let img = image::load_from_memory_with_format(bytes, image::ImageFormat::Png)
                    .map_err(|e| err(e.to_string()))?;
                let rgba = img.to_rgba32f();
                Ok(Self {
                    width: rgba.width(),
                    height: rgba.height(),
                    rgba: rgba.into_raw(),
                    encoding: Encoding::Display,
                })
            }
            FileKind::Exr => {
                use exr::prelude::*;
                // The header says how large the image is before any pixel is read: a
                // corrupt or hostile one can declare terabytes (found by fuzzing: 686 GB),
                // which would abort the process allocating them.
                let meta =
                    exr::meta::MetaData::read_from_buffered(std::io::Cursor::new(bytes), false)
                        .map_err(|e| err(e.to_string()))?;
                for header in meta.headers.iter() {
                    let size = header.layer_size;
                    let pixels = size.width().checked_mul(size.height());
                    if pixels.is_none_or(|p| p > MAX_EXR_PIXELS) {
                        return Err(err(format!(
                            "its header declares {}x{} pixels, more than the {MAX_EXR_PIXELS} Stratus reads",
                            size.width(),
                            size.height()
                        )));
                    }
                }
                let image = read()
                    .no_deep_data()
                    .largest_resolution_level()
                    .rgba_channels(
                        |resolution, _| {
                            (
                                resolution.width(),
                                vec![0f32; 4 * resolution.width() * resolution.height()],
                            )
                        },
                        |(w, data): &mut (usize, Vec<f32>),
                         pos: Vec2<usize>,
                         (r, g, b, a): (f32, f32, f32, f32)| {
                            let i = 4 * (pos.y() * *w + pos.x());
                            data[i..i + 4].copy_from_slice(&[r, g, b, a]);
                        },
                    )
                    .first_valid_layer()
                    .all_attributes()
                    .from_buffered(std::io::Cursor::new(bytes))
                    .map_err(|e| err(e.to_string()))?;
                let size = image.layer_data.size;
                let (_, data) = image.layer_data.channel_data.pixels;
                Ok(Self::from_linear_rgba(
                    size.width() as u32,
                    size.height() as u32,
                    data,
                ))
            }
        }
    }

    /// Writes the image: `.png` (display images as 8 bits; linear ones tone-mapped with
    /// [`tonemap`] at exposure 1) or `.exr` (the raw values).
    /// The file is complete or absent: it is written under a temporary name beside `path`
    /// and renamed into place ([`write_atomically`]).
    pub fn save(&self, path: &Path) -> Result<(), CompareError> {
        let werr = |message: String| CompareError::Write {
            path: path.display().to_string(),
            message,
        };
        write_atomically(path, |tmp| self.save_to(tmp, path)).map_err(|e| match e {
            AtomicError::Io(e) => werr(e.to_string()),
            AtomicError::Write(e) => e,
        })
    }

    fn save_to(&self, tmp: &Path, path: &Path) -> Result<(), CompareError> {
        let werr = |message: String| CompareError::Write {
            path: path.display().to_string(),
            message,
        };
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("png") => image::save_buffer(
                tmp,
                &self.to_rgb8(1.0),
                self.width,
                self.height,
                image::ExtendedColorType::Rgb8,
            )
            .map_err(|e| werr(e.to_string())),
            Some("exr") => {
                use exr::prelude::*;
                let w = self.width as usize;
                let px = &self.rgba;
                let channels = SpecificChannels::rgba(|Vec2(x, y): Vec2<usize>| {
                    let i = 4 * (y * w + x);
                    (px[i], px[i + 1], px[i + 2], px[i + 3])
                });
                // Written on one thread: exr's parallel writer stores blocks in completion
                // order, which makes the file bytes differ between runs of the same image.
                exr::image::Image::from_channels((w, self.height as usize), channels)
                    .write()
                    .non_parallel()
                    .to_file(tmp)
                    .map_err(|e| werr(e.to_string()))
            }
            _ => Err(CompareError::UnknownType(path.display().to_string())),
        }
    }

    /// The image as 8-bit RGB for FLIP: display images are quantised (`round(v * 255)`),
    /// linear images are tone-mapped by [`tonemap`] with `exposure` first.
    pub fn to_rgb8(&self, exposure: f32) -> Vec<u8> {
        let q = |v: f32| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
        self.rgba
            .chunks_exact(4)
            .flat_map(|p| {
                let rgb = [p[0], p[1], p[2]];
                match self.encoding {
                    Encoding::Display => rgb.map(q),
                    Encoding::Linear => rgb.map(|v| q(tonemap(v * exposure))),
                }
            })
            .collect()
    }
}

/// The display transform of `composite.wgsl` for one linear value (after exposure): Narkowicz's
/// ACES fitted curve, then gamma 2.2. Used to show linear images (cloud radiance without the
/// sky) the way the renderer would.
pub fn tonemap(x: f32) -> f32 {
    let (a, b, c, d, e) = (2.51f32, 0.03f32, 2.43f32, 0.59f32, 0.14f32);
    let x = x.max(0.0);
    let y = ((x * (a * x + b)) / (x * (c * x + d) + e)).clamp(0.0, 1.0);
    y.powf(1.0 / 2.2)
}

/// Options of [`compare`].
#[derive(Clone, Debug, PartialEq)]
pub struct CompareOptions {
    /// Include alpha (transmittance in Stratus's linear images) in RMSE, max abs and the worst
    /// pixel. FLIP always uses rgb only.
    pub include_alpha: bool,
    /// Exposure applied before tone mapping linear images for FLIP.
    pub exposure: f32,
    /// FLIP's observer model: pixels per degree of visual angle (FLIP's default 67: a 0.7 m
    /// wide 4K monitor seen from 0.7 m).
    pub pixels_per_degree: f32,
}

impl Default for CompareOptions {
    fn default() -> Self {
        Self {
            include_alpha: false,
            exposure: 1.0,
            pixels_per_degree: nv_flip::DEFAULT_PIXELS_PER_DEGREE,
        }
    }
}

/// The pixel with the largest absolute difference.
#[derive(Clone, Debug, PartialEq)]
pub struct WorstPixel {
    /// Column.
    pub x: u32,
    /// Row (0 at the top).
    pub y: u32,
    /// Channel of the largest difference (0 r, 1 g, 2 b, 3 a).
    pub channel: usize,
    /// The reference's rgba there.
    pub reference: [f32; 4],
    /// The test image's rgba there.
    pub test: [f32; 4],
}

/// Statistics of a FLIP error map (each pixel's error in `[0, 1]`).
#[derive(Clone, Debug, PartialEq)]
pub struct FlipStats {
    /// Mean error (FLIP's recommended single number).
    pub mean: f64,
    /// Median.
    pub p50: f64,
    /// 95th percentile.
    pub p95: f64,
    /// 99th percentile.
    pub p99: f64,
    /// Maximum.
    pub max: f64,
}

/// The outcome of [`compare`].
#[derive(Clone, Debug, PartialEq)]
pub struct Comparison {
    /// Width of both images.
    pub width: u32,
    /// Height of both images.
    pub height: u32,
    /// Encoding of both images (what RMSE and max abs were computed on).
    pub encoding: Encoding,
    /// Root mean square difference over the compared channels of every pixel.
    pub rmse: f64,
    /// Largest absolute difference of any compared channel.
    pub max_abs: f64,
    /// Where `max_abs` occurs (the first such pixel in row-major order).
    pub worst: WorstPixel,
    /// FLIP of the tone-mapped 8-bit images.
    pub flip: FlipStats,
    /// The FLIP error of every pixel, row-major.
    pub flip_map: Vec<f32>,
}

/// Compares `test` against `reference` (same size and encoding).
pub fn compare(
    reference: &Image,
    test: &Image,
    options: &CompareOptions,
) -> Result<Comparison, CompareError> {
    if (reference.width, reference.height) != (test.width, test.height) {
        return Err(CompareError::SizeMismatch(
            reference.width,
            reference.height,
            test.width,
            test.height,
        ));
    }
    if reference.encoding != test.encoding {
        return Err(CompareError::EncodingMismatch(
            reference.encoding,
            test.encoding,
        ));
    }
    let channels = if options.include_alpha { 4 } else { 3 };
    let (rmse, max_abs, worst_index) = differences(&reference.rgba, &test.rgba, channels);
    let pixel = worst_index / 4;
    let px = |img: &Image| -> [f32; 4] {
        let mut p = [0.0; 4];
        p.copy_from_slice(&img.rgba[4 * pixel..4 * pixel + 4]);
        p
    };
    let (w, h) = (reference.width, reference.height);
    let flip_map = flip_error_map(
        w,
        h,
        &reference.to_rgb8(options.exposure),
        &test.to_rgb8(options.exposure),
        options.pixels_per_degree,
    );
    Ok(Comparison {
        width: w,
        height: h,
        encoding: reference.encoding,
        rmse,
        max_abs,
        worst: WorstPixel {
            x: pixel as u32 % w.max(1),
            y: pixel as u32 / w.max(1),
            channel: worst_index % 4,
            reference: px(reference),
            test: px(test),
        },
        flip: flip_stats(&flip_map),
        flip_map,
    })
}

/// RMSE, max abs and the index of the largest difference over the first `channels` of every
/// 4-value pixel.
fn differences(a: &[f32], b: &[f32], channels: usize) -> (f64, f64, usize) {
    let mut sum = 0.0f64;
    let mut n = 0usize;
    let mut max = 0.0f64;
    let mut worst = 0usize;
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        if i % 4 >= channels {
            continue;
        }
        let d = (f64::from(*x) - f64::from(*y)).abs();
        // A NaN anywhere is the worst difference there is.
        let d = if d.is_nan() { f64::INFINITY } else { d };
        sum += d * d;
        n += 1;
        if d > max {
            max = d;
            worst = i;
        }
    }
    let rmse = if n == 0 { 0.0 } else { (sum / n as f64).sqrt() };
    (rmse, max, worst)
}

/// The FLIP error map of two 8-bit sRGB RGB images (tightly packed, row-major).
pub fn flip_error_map(
    width: u32,
    height: u32,
    reference_rgb8: &[u8],
    test_rgb8: &[u8],
    pixels_per_degree: f32,
) -> Vec<f32> {
    let r = nv_flip::FlipImageRgb8::with_data(width, height, reference_rgb8);
    let t = nv_flip::FlipImageRgb8::with_data(width, height, test_rgb8);
    nv_flip::flip(r, t, pixels_per_degree).to_vec()
}

/// Mean and percentiles of an error map (percentile `p`: the value at index
/// `ceil(p * n) - 1` of the sorted errors).
pub fn flip_stats(map: &[f32]) -> FlipStats {
    if map.is_empty() {
        return FlipStats {
            mean: 0.0,
            p50: 0.0,
            p95: 0.0,
            p99: 0.0,
            max: 0.0,
        };
    }
    let mut sorted: Vec<f32> = map.to_vec();
    sorted.sort_by(f32::total_cmp);
    let n = sorted.len();
    let pct = |p: f64| f64::from(sorted[((p * n as f64).ceil() as usize).clamp(1, n) - 1]);
    FlipStats {
        mean: map.iter().map(|&v| f64::from(v)).sum::<f64>() / n as f64,
        p50: pct(0.5),
        p95: pct(0.95),
        p99: pct(0.99),
        max: f64::from(sorted[n - 1]),
    }
}

/// The error map coloured with FLIP's magma map (black = no error, yellow-white = 1), 8-bit RGB.
pub fn heatmap_rgb8(width: u32, height: u32, map: &[f32]) -> Vec<u8> {
    let img = nv_flip::FlipImageFloat::with_data(width, height, map);
    img.apply_color_lut(&nv_flip::magma_lut()).to_vec()
}

/// The largest EXR, in pixels, that [`Image::decode`] reads: 8192x8192, a gigabyte of RGBA
/// floats (a fuzzer's memory limit is two); a larger one is refused by name, not allocated.
pub const MAX_EXR_PIXELS: usize = 8192 * 8192;

/// Writes the magma heat map of an error map as a PNG.
pub fn write_heatmap(
    path: &Path,
    width: u32,
    height: u32,
    map: &[f32],
) -> Result<(), CompareError> {
    let werr = |message: String| CompareError::Write {
        path: path.display().to_string(),
        message,
    };
    write_atomically(path, |tmp| {
        image::save_buffer(
            tmp,
            &heatmap_rgb8(width, height, map),
            width,
            height,
            image::ExtendedColorType::Rgb8,
        )
        .map_err(|e| werr(e.to_string()))
    })
    .map_err(|e| match e {
        AtomicError::Io(e) => werr(e.to_string()),
        AtomicError::Write(e) => e,
    })
}

/// Why [`write_atomically`] failed: the writer's own error, or moving its file into place.
#[derive(Debug)]
pub enum AtomicError<E> {
    /// The writer failed (its temporary file is removed).
    Write(E),
    /// Renaming the finished file into place failed.
    Io(std::io::Error),
}

impl<E: std::fmt::Display> std::fmt::Display for AtomicError<E> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Write(e) => e.fmt(f),
            Self::Io(e) => write!(f, "moving the finished file into place: {e}"),
        }
    }
}

impl<E: std::fmt::Debug + std::fmt::Display> std::error::Error for AtomicError<E> {}

/// Writes a file so that it is complete or absent, never half-written: `write` writes a
/// temporary file beside `path` (same folder, so the rename stays on one file system; the name
/// keeps the extension, which image writers read the format from), which is then renamed over
/// `path` (atomic on POSIX). A process killed mid-write leaves at most a hidden `.partial` file;
/// a failed write removes it.
pub fn write_atomically<T, E>(
    path: &Path,
    write: impl FnOnce(&Path) -> Result<T, E>,
) -> Result<T, AtomicError<E>> {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let ext = path
        .extension()
        .map(|e| format!(".{}", e.to_string_lossy()))
        .unwrap_or_default();
    let tmp = path.with_file_name(format!(".{name}.{}.partial{ext}", std::process::id()));
    match write(&tmp) {
        Ok(v) => std::fs::rename(&tmp, path).map(|()| v).map_err(|e| {
            let _ = std::fs::remove_file(&tmp);
            AtomicError::Io(e)
        }),
        Err(e) => {
            let _ = std::fs::remove_file(&tmp);
            Err(AtomicError::Write(e))
        }
    }
}

/// [`write_atomically`] for bytes in memory.
pub fn write_file_atomically(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    write_atomically(path, |tmp| std::fs::write(tmp, bytes)).map_err(|e| match e {
        AtomicError::Write(e) | AtomicError::Io(e) => e,
    })
}
