//! Tiling noise textures for the Stratus volumetric cloud renderer.
//!
//! Generates, deterministically from a `u64` seed, the textures of the Frostbite cloud model
//! (Högfeldt 2016, sections 4.2-4.4, table 4.1) with the Horizon Zero Dawn channel conventions
//! (Schneider 2015):
//!
//! | texture | default size | R | G | B | A |
//! |---|---|---|---|---|---|
//! | [`shape`](shape_texture) | 128x32x128 ([`ShapeSize::Thesis`]) or 128^3 ([`ShapeSize::Hzd`]) | Perlin-Worley | Worley FBM, 4 cells | Worley FBM, 8 cells | Worley FBM, 16 cells |
//! | [`detail`](detail_texture) | 32^3 | Worley FBM, 2 cells | Worley FBM, 4 cells | Worley FBM, 8 cells | 1 (padding) |
//! | [`curl`](curl_texture) | 128^2 | curl x, `0.5*cx+0.5` | curl y, `0.5*cy+0.5` | 0.5 | 1 |
//! | [`weather`](weather_texture) | 512^2 | coverage | precipitation | cloud type (0 stratus, 0.5 stratocumulus, 1 cumulus) | convective cells: rank of a rough FBM |
//!
//! "Worley FBM, n cells" is the *inverted* Worley FBM ([`worley_fbm3`]) whose first octave has
//! `n` cells across the texture's x axis. Every texture is RGBA8 UNORM, so any GPU backend can
//! sample it with a linear filter and repeat addressing.
//!
//! # Layout
//!
//! * [`Texture3`]: texels stored x fastest, then y, then z; texel `(x, y, z)` starts at byte
//!   `((z * height + y) * width + x) * 4` (the row-major order of a GPU 3D texture upload).
//! * [`Texture2`]: texel `(x, y)` starts at byte `(y * width + x) * 4`.
//!
//! Values are quantised with [`to_unorm8`] (`round(v * 255)`, clamped).
//!
//! # Tiling
//!
//! Every texture tiles in every axis: Perlin noise uses a periodic gradient lattice (thesis
//! 4.2.1) and Worley noise one feature point per cell with a wrap-around search of the 27 (3D)
//! or 9 (2D) neighbouring cells (thesis 4.2.2). All periods are integer numbers of cells; along
//! a shorter axis (the 32-texel y axis of the thesis shape texture) the number of cells is scaled
//! by the axis length, so features are isotropic in texel units.
//!
//! # Determinism
//!
//! Every random quantity is an integer hash of `(seed, cell coordinates, channel, octave)`; no
//! sequential RNG is used. Textures are filled in parallel with rayon, but each texel depends only
//! on the seed and its coordinates (the curl texture is additionally divided by its maximum,
//! which is order-independent). Only correctly rounded operations are used (`+ - * / sqrt floor
//! round`; no `libm` transcendentals, no fused multiply-add), so the bytes are identical across
//! runs, thread counts and platforms.
//!
//! # Building blocks
//!
//! [`perlin3`], [`perlin2`], [`worley3`], [`worley2`] and the FBM helpers [`perlin_fbm3`],
//! [`perlin_fbm2`], [`worley_fbm3`], [`worley_fbm2`] evaluate the same noises at single points
//! (the texture generators use precomputed per-octave tables that give bit-identical results).
#![deny(missing_docs)]

use std::fmt;
use std::str::FromStr;

mod hash;
mod perlin;
mod png;
mod textures;
mod worley;

pub use perlin::{perlin_fbm2, perlin_fbm3, perlin2, perlin3};
pub use png::{NoiseError, weather_from_png};
pub use textures::{curl_texture, detail_texture, shape_texture, weather_texture};
pub use worley::{WORLEY_FBM_WEIGHTS, worley_fbm2, worley_fbm3, worley2, worley3};

/// Quantises `v` in `[0, 1]` to an 8-bit UNORM value: `round(v * 255)`, clamped to `[0, 255]`
/// (NaN gives 0). The single quantisation helper used by every texture.
#[inline]
pub fn to_unorm8(v: f64) -> u8 {
    // `as` saturates (and maps NaN to 0); the clamp documents the intent.
    (v * 255.0).round().clamp(0.0, 255.0) as u8
}

/// A tiling 3D texture, RGBA8, texels stored x fastest, then y, then z (row-major as the GPU
/// expects for a 3D texture upload: index = `((z * height + y) * width + x) * 4`).
#[derive(Clone, PartialEq, Eq)]
pub struct Texture3 {
    /// `[width, height, depth]` in texels.
    pub size: [u32; 3],
    /// `width * height * depth * 4` bytes, RGBA8.
    pub data: Vec<u8>,
}

impl Texture3 {
    /// The RGBA texel at `(x, y, z)`. Panics if out of bounds.
    pub fn texel(&self, x: u32, y: u32, z: u32) -> [u8; 4] {
        let [w, h, d] = self.size;
        assert!(
            x < w && y < h && z < d,
            "texel ({x}, {y}, {z}) out of bounds"
        );
        let i = ((z as usize * h as usize + y as usize) * w as usize + x as usize) * 4;
        [
            self.data[i],
            self.data[i + 1],
            self.data[i + 2],
            self.data[i + 3],
        ]
    }
}

impl fmt::Debug for Texture3 {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Texture3")
            .field("size", &self.size)
            .field("data", &format_args!("[{} bytes]", self.data.len()))
            .finish()
    }
}

/// A tiling 2D texture, RGBA8, index = `(y * width + x) * 4`.
#[derive(Clone, PartialEq, Eq)]
pub struct Texture2 {
    /// `[width, height]` in texels.
    pub size: [u32; 2],
    /// `width * height * 4` bytes, RGBA8.
    pub data: Vec<u8>,
}

impl Texture2 {
    /// The RGBA texel at `(x, y)`. Panics if out of bounds.
    pub fn texel(&self, x: u32, y: u32) -> [u8; 4] {
        let [w, h] = self.size;
        assert!(x < w && y < h, "texel ({x}, {y}) out of bounds");
        let i = (y as usize * w as usize + x as usize) * 4;
        [
            self.data[i],
            self.data[i + 1],
            self.data[i + 2],
            self.data[i + 3],
        ]
    }
}

impl fmt::Debug for Texture2 {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Texture2")
            .field("size", &self.size)
            .field("data", &format_args!("[{} bytes]", self.data.len()))
            .finish()
    }
}

/// Size of the shape texture.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum ShapeSize {
    /// 128x32x128, as in the Frostbite thesis (table 4.1): clouds are flat in y, so the y axis
    /// is shorter to save memory. The default.
    #[default]
    Thesis,
    /// 128x128x128, as in Horizon Zero Dawn (Schneider 2015).
    Hzd,
}

impl ShapeSize {
    /// `[width, height, depth]` in texels.
    pub fn dims(self) -> [u32; 3] {
        match self {
            Self::Thesis => [128, 32, 128],
            Self::Hzd => [128, 128, 128],
        }
    }
}

impl fmt::Display for ShapeSize {
    /// Writes the dimensions, `128x32x128` or `128x128x128` (accepted back by `FromStr`).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let [w, h, d] = self.dims();
        write!(f, "{w}x{h}x{d}")
    }
}

impl FromStr for ShapeSize {
    type Err = ParseShapeSizeError;

    /// Parses `128x32x128` (or `thesis`) and `128x128x128` (or `hzd`), case-insensitively.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim().to_ascii_lowercase().as_str() {
            "128x32x128" | "thesis" => Ok(Self::Thesis),
            "128x128x128" | "hzd" => Ok(Self::Hzd),
            _ => Err(ParseShapeSizeError(s.to_owned())),
        }
    }
}

/// Error from parsing a [`ShapeSize`]; holds the rejected text.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ParseShapeSizeError(pub String);

impl fmt::Display for ParseShapeSizeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "invalid shape texture size {:?}: expected 128x32x128 or 128x128x128",
            self.0
        )
    }
}

impl std::error::Error for ParseShapeSizeError {}

/// Parameters of [`NoiseSet::generate`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct NoiseConfig {
    /// Seed of every texture (each texture and channel derives its own independent stream).
    /// Default 0.
    pub seed: u64,
    /// Shape texture size. Default [`ShapeSize::Thesis`] (128x32x128).
    pub shape: ShapeSize,
    /// Weather texture width and height. Default 512.
    pub weather_size: u32,
    /// Curl texture width and height. Default 128.
    pub curl_size: u32,
    /// Detail texture width, height and depth. Default 32.
    pub detail_size: u32,
}

impl Default for NoiseConfig {
    fn default() -> Self {
        Self {
            seed: 0,
            shape: ShapeSize::Thesis,
            weather_size: 512,
            curl_size: 128,
            detail_size: 32,
        }
    }
}

/// The complete set of textures the cloud renderer samples.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct NoiseSet {
    /// Base shape, see [`shape_texture`].
    pub shape: Texture3,
    /// Erosion detail, see [`detail_texture`].
    pub detail: Texture3,
    /// Curl distortion, see [`curl_texture`].
    pub curl: Texture2,
    /// Procedural weather map, see [`weather_texture`].
    pub weather: Texture2,
}

impl NoiseSet {
    /// Generates all four textures from `cfg`. Deterministic: equal configs give equal bytes.
    pub fn generate(cfg: &NoiseConfig) -> NoiseSet {
        NoiseSet {
            shape: shape_texture(cfg.seed, cfg.shape.dims()),
            detail: detail_texture(cfg.seed, cfg.detail_size),
            curl: curl_texture(cfg.seed, cfg.curl_size),
            weather: weather_texture(cfg.seed, cfg.weather_size),
        }
    }

    /// SHA-256 (hex) over the four textures' sizes and bytes: what a renderer samples, for
    /// keys of results that depend on it (the path tracer's truths).
    pub fn sha256(&self) -> String {
        use sha2::{Digest, Sha256};
        let mut h = Sha256::new();
        for (size, data) in [
            (&self.shape.size[..], &self.shape.data),
            (&self.detail.size[..], &self.detail.data),
            (&self.curl.size[..], &self.curl.data),
            (&self.weather.size[..], &self.weather.data),
        ] {
            for s in size {
                h.update(s.to_le_bytes());
            }
            h.update(data);
        }
        h.finalize().iter().map(|b| format!("{b:02x}")).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unorm8_rounding() {
        assert_eq!(to_unorm8(0.0), 0);
        assert_eq!(to_unorm8(1.0), 255);
        assert_eq!(to_unorm8(-3.0), 0);
        assert_eq!(to_unorm8(7.0), 255);
        assert_eq!(to_unorm8(0.5), 128);
        assert_eq!(to_unorm8(f64::NAN), 0);
    }

    #[test]
    fn shape_size_parse_display() {
        for s in [ShapeSize::Thesis, ShapeSize::Hzd] {
            assert_eq!(s.to_string().parse::<ShapeSize>(), Ok(s));
        }
        assert_eq!("128x32x128".parse(), Ok(ShapeSize::Thesis));
        assert_eq!("128X128X128".parse(), Ok(ShapeSize::Hzd));
        assert_eq!(ShapeSize::default().dims(), [128, 32, 128]);
        let err = "64x64x64".parse::<ShapeSize>().unwrap_err();
        assert!(err.to_string().contains("64x64x64"));
    }
}
