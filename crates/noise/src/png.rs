//! Loading an artist-authored weather texture from a PNG file.

use std::fmt;
use std::io::BufReader;
use std::path::{Path, PathBuf};

use image::{DynamicImage, ImageFormat, ImageReader};

use crate::Texture2;

/// Error returned by [`weather_from_png`]. Every variant names the offending file.
#[derive(Debug)]
#[non_exhaustive]
pub enum NoiseError {
    /// The file could not be opened or read.
    Io {
        /// The file that was being read.
        path: PathBuf,
        /// The underlying I/O error.
        source: std::io::Error,
    },
    /// The file is not a valid PNG image.
    Decode {
        /// The file that was being decoded.
        path: PathBuf,
        /// The decoder's message.
        message: String,
    },
    /// The PNG is valid but its pixel format is not 8-bit RGB or RGBA.
    UnsupportedFormat {
        /// The file that was decoded.
        path: PathBuf,
        /// The pixel format that was found, e.g. `L8` or `Rgba16`.
        format: String,
    },
    /// The image has zero width or height.
    Empty {
        /// The file that was decoded.
        path: PathBuf,
    },
}

impl fmt::Display for NoiseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Io { path, source } => {
                write!(
                    f,
                    "cannot read weather texture {}: {source}",
                    path.display()
                )
            }
            Self::Decode { path, message } => write!(
                f,
                "weather texture {} is not a valid PNG image: {message}",
                path.display()
            ),
            Self::UnsupportedFormat { path, format } => write!(
                f,
                "weather texture {} has pixel format {format}; expected 8-bit RGB or RGBA",
                path.display()
            ),
            Self::Empty { path } => {
                write!(f, "weather texture {} is empty (0 pixels)", path.display())
            }
        }
    }
}

impl std::error::Error for NoiseError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Io { source, .. } => Some(source),
            _ => None,
        }
    }
}

/// Loads a weather texture from an 8-bit RGB or RGBA PNG file (HZD layout: R = coverage,
/// G = precipitation, B = cloud type; A = the convective cells' rank; see
/// [`crate::weather_texture`]).
///
/// RGB images get A = 255 (with `clouds.convective_cells`, every cumulus point inside a
/// cell). Any non-empty size is accepted (the texture need not be square or a power of two);
/// it is the caller's job to sample it with repeat addressing. Other pixel formats
/// (grey, 16-bit, ...) are rejected with [`NoiseError::UnsupportedFormat`] rather than silently
/// converted, because a weather map's channels carry data, not colour.
pub fn weather_from_png(path: &Path) -> Result<Texture2, NoiseError> {
    let file = std::fs::File::open(path).map_err(|source| NoiseError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let image = ImageReader::with_format(BufReader::new(file), ImageFormat::Png)
        .decode()
        .map_err(|e| NoiseError::Decode {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
    let (width, height) = (image.width(), image.height());
    if width == 0 || height == 0 {
        return Err(NoiseError::Empty {
            path: path.to_path_buf(),
        });
    }
    let data = match image {
        DynamicImage::ImageRgba8(rgba) => rgba.into_raw(),
        DynamicImage::ImageRgb8(rgb) => rgb
            .into_raw()
            .chunks_exact(3)
            .flat_map(|p| [p[0], p[1], p[2], 255])
            .collect(),
        other => {
            return Err(NoiseError::UnsupportedFormat {
                path: path.to_path_buf(),
                format: format!("{:?}", other.color()),
            });
        }
    };
    Ok(Texture2 {
        size: [width, height],
        data,
    })
}
