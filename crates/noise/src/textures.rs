//! The four cloud textures: shape, detail, curl and weather.

use rayon::prelude::*;

use crate::hash::derive_seed;
use crate::perlin::{PerlinFbm2, PerlinFbm3};
use crate::worley::{WorleyFbm2, WorleyFbm3};
use crate::{Texture2, Texture3, to_unorm8};

// ---------------------------------------------------------------------------------------------
// Parameters. Frequencies are numbers of noise cells across the texture's x axis (the thesis,
// section 4.2.2, describes Worley octaves by cell size: a 128^3 cube with cell size 16 has exactly
// 8 feature points per axis, and octaves double the frequency, e.g. 2, 4, 8, 16).
// ---------------------------------------------------------------------------------------------

/// Shape R: base frequency of the Perlin FBM (cells across x).
const SHAPE_PERLIN_FREQ: u32 = 4;
/// Shape R: octaves of the Perlin FBM (4, 8, 16, 32, 64 cells across 128 texels).
const SHAPE_PERLIN_OCTAVES: u32 = 5;
/// Shape G, B, A: base frequencies of the three inverted Worley FBMs ("Worley at increasing
/// frequencies", thesis table 4.1 / HZD). Each FBM itself sums 3 octaves (f, 2f, 4f).
/// G (frequency 4) is also the Worley FBM that shapes the Perlin-Worley R channel.
const SHAPE_WORLEY_FREQS: [u32; 3] = [4, 8, 16];
/// Shape R: gain applied to the Perlin FBM before it is mapped to [0, 1] and dilated by Worley.
/// The normalised 5-octave FBM has a standard deviation of about 0.16, so with gain 2 the mapped
/// Perlin value mostly lies within [0.2, 0.8] and is rarely clipped.
const SHAPE_PERLIN_GAIN: f64 = 2.0;
/// Shape R: final linear stretch of the Perlin-Worley value, `[LO, HI] -> [0, 1]` (clamped).
/// The Perlin-Worley remap lifts values (it maps onto `[(1 - w) / (2 - w), 1]`), so before the
/// stretch it lies in about [0.35, 1] with mean 0.67; after it, measured over seeds 0-3: mean
/// 0.49, standard deviation 0.15-0.17, under 1% of texels clipped at either end.
const SHAPE_R_RANGE: [f64; 2] = [0.35, 1.0];

/// Detail R, G, B: base frequencies of the three inverted Worley FBMs (cells across 32 texels).
const DETAIL_WORLEY_FREQS: [u32; 3] = [2, 4, 8];

/// Curl: base frequency and octaves of the Perlin FBM potential (seed document 001, 3.1.2:
/// "the curl of 2D Perlin noise"). The curl differentiates, which weights every octave equally,
/// so only 3 octaves (4, 8, 16 cells: at least 8 texels per cell at 128^2) are used.
const CURL_FREQ: u32 = 4;
const CURL_OCTAVES: u32 = 3;

/// Weather R (coverage): Perlin FBM base frequency/octaves and Worley FBM base frequency.
const COVERAGE_PERLIN_FREQ: u32 = 4;
const COVERAGE_PERLIN_OCTAVES: u32 = 5;
const COVERAGE_WORLEY_FREQ: u32 = 4;
const COVERAGE_PERLIN_GAIN: f64 = 2.5;
/// Weather R: contrast remap of the Perlin-Worley value, `[LO, HI] -> [0, 1]` (clamped). Chosen
/// so that there is clear sky and overcast sky: measured over seeds 0-3, mean coverage 0.50-0.51,
/// 11-15% of texels below 0.1 and 10-17% above 0.9 (HZD's typical sky is "50% coverage").
const COVERAGE_RANGE: [f64; 2] = [0.42, 0.87];
/// Weather G (precipitation): the rain field's Perlin FBM base frequency and octaves, and the
/// coverage range over which precipitation fades in (smoothstep). HZD: precipitation is tied to
/// dense cloud (rain clouds are overcast regions); measured mean 0.12-0.14, about two thirds of
/// texels exactly 0.
const RAIN_FREQ: u32 = 8;
const RAIN_OCTAVES: u32 = 3;
const RAIN_COVERAGE_RAMP: [f64; 2] = [0.5, 1.0];
/// Weather B (cloud type): low-frequency Perlin FBM, `0.5 + 0.5 * gain * fbm`, clamped. With
/// gain 2.5 the field spans the three types (measured standard deviation 0.22-0.27) and only
/// 2-10% of texels saturate at pure stratus (0) or pure cumulus (1).
const TYPE_FREQ: u32 = 2;
const TYPE_OCTAVES: u32 = 3;
const TYPE_GAIN: f64 = 2.5;
/// Weather A (convective cells): a Perlin FBM whose octaves fall off by `CELL_GAIN` rather
/// than by half, so that the field is rough on every scale it spans: its Hurst exponent is
/// `H = -log2(CELL_GAIN)`, 0.36, and the level sets of a fractional Brownian surface are
/// fractal, of dimension `2 - H` (Mandelbrot 1982, The Fractal Geometry of Nature, ch. 28).
/// Its octaves span 20 to 160 cells across the map: 3 km down to 375 m over the default
/// 60 km map; the shape noise carves finer detail. Chosen by measuring the fields it draws
/// (`stratus measure-field` of the `few` and `scattered` states, 35 km at 512 px, seeds 0-2;
/// docs/cloud-fields.md) against real ones: outlines of area-perimeter dimension about 1.35
/// (Lovejoy 1982) and sizes n(L) ∝ L^-b, b 1.7-2.0 (Benner and Curry 1998). Base
/// frequencies of 8, 12 and 16 cells drew clouds of up to 17 km and D 1.24-1.28; gains of
/// 0.62-0.75 smoother outlines (D 1.27 for `few`); three octaves at gain 0.8 D 1.26-1.30.
/// This one measures D 1.29-1.39 and b 1.89-2.12. The channel holds the field's rank
/// (histogram equalised), so that the share of the map above `1 - f` is `f`.
const CELL_FREQ: u32 = 20;
const CELL_OCTAVES: u32 = 4;
const CELL_GAIN: f64 = 0.78;

// Seed tags: every channel draws from an independent derived seed.
const TAG_SHAPE_PERLIN: u64 = 0x5348_0000;
const TAG_SHAPE_WORLEY: u64 = 0x5348_0100;
const TAG_DETAIL_WORLEY: u64 = 0x4454_0100;
const TAG_CURL: u64 = 0x4355_0000;
const TAG_COVERAGE_PERLIN: u64 = 0x5745_0000;
const TAG_COVERAGE_WORLEY: u64 = 0x5745_0100;
const TAG_RAIN: u64 = 0x5745_0200;
const TAG_TYPE: u64 = 0x5745_0300;
const TAG_CELLS: u64 = 0x5745_0400;

/// Number of noise cells along an axis of `size_axis` texels, for a noise with `freq` cells
/// across the reference axis of `size_ref` texels: `round(freq * size_axis / size_ref)`, at
/// least 1. Keeps features isotropic in texel units (the shape texture is sampled with the same
/// texel size in world space on all axes) while every axis still tiles with an integer period.
pub(crate) fn axis_cells(freq: u32, size_axis: u32, size_ref: u32) -> u32 {
    let (f, a, r) = (
        u64::from(freq),
        u64::from(size_axis),
        u64::from(size_ref.max(1)),
    );
    ((f * a + r / 2) / r).clamp(1, u64::from(u32::MAX)) as u32
}

/// `v` mapped linearly from `[lo, hi]` to `[new_lo, new_hi]` (not clamped).
#[inline]
pub(crate) fn remap(v: f64, lo: f64, hi: f64, new_lo: f64, new_hi: f64) -> f64 {
    new_lo + (v - lo) / (hi - lo) * (new_hi - new_lo)
}

/// Hermite smoothstep (polynomial only, so results are identical on every platform).
#[inline]
fn smoothstep(e0: f64, e1: f64, x: f64) -> f64 {
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// HZD-style Perlin-Worley (Schneider 2015): the Perlin FBM, mapped to [0, 1], is remapped from
/// `[worley - 1, 1]` to `[0, 1]`. Where the inverted Worley FBM is high (near feature points) the
/// Perlin value is kept; where it is low the value is lifted towards 1, which adds billowy
/// bumps to Perlin's connected shapes. Finally the result is stretched by `range`.
#[inline]
fn perlin_worley(perlin: f64, worley_fbm: f64, gain: f64, range: [f64; 2]) -> f64 {
    let p01 = (0.5 + 0.5 * gain * perlin).clamp(0.0, 1.0);
    let pw = remap(p01, worley_fbm - 1.0, 1.0, 0.0, 1.0);
    remap(pw, range[0], range[1], 0.0, 1.0).clamp(0.0, 1.0)
}

/// Point of a noise with base `period` at normalised texture coordinate `u` (texel centres).
#[inline]
fn at<const N: usize>(u: [f64; N], period: [u32; N]) -> [f64; N] {
    std::array::from_fn(|i| u[i] * f64::from(period[i]))
}

/// Fills an RGBA8 3D texture; `f` receives the texel centre in normalised `[0, 1)^3`
/// coordinates. Z-slices are filled in parallel; each texel depends only on its coordinates.
fn fill3(size: [u32; 3], f: impl Fn([f64; 3]) -> [f64; 4] + Sync) -> Texture3 {
    let [w, h, d] = size.map(|v| v as usize);
    let mut data = vec![0u8; w * h * d * 4];
    if !data.is_empty() {
        data.par_chunks_mut(w * h * 4)
            .enumerate()
            .for_each(|(z, slice)| {
                let uz = (z as f64 + 0.5) / d as f64;
                for (y, row) in slice.chunks_exact_mut(w * 4).enumerate() {
                    let uy = (y as f64 + 0.5) / h as f64;
                    for (x, texel) in row.chunks_exact_mut(4).enumerate() {
                        let ux = (x as f64 + 0.5) / w as f64;
                        let v = f([ux, uy, uz]);
                        for (t, c) in texel.iter_mut().zip(v) {
                            *t = to_unorm8(c);
                        }
                    }
                }
            });
    }
    Texture3 { size, data }
}

/// Fills an RGBA8 2D texture; rows in parallel, `f` receives normalised texel-centre coordinates.
fn fill2(size: [u32; 2], f: impl Fn([f64; 2]) -> [f64; 4] + Sync) -> Texture2 {
    let [w, h] = size.map(|v| v as usize);
    let mut data = vec![0u8; w * h * 4];
    if !data.is_empty() {
        data.par_chunks_mut(w * 4).enumerate().for_each(|(y, row)| {
            let uy = (y as f64 + 0.5) / h as f64;
            for (x, texel) in row.chunks_exact_mut(4).enumerate() {
                let ux = (x as f64 + 0.5) / w as f64;
                let v = f([ux, uy]);
                for (t, c) in texel.iter_mut().zip(v) {
                    *t = to_unorm8(c);
                }
            }
        });
    }
    Texture2 { size, data }
}

/// Generates the base-shape texture (thesis table 4.1: 128x32x128 RGBA8; HZD: 128^3 RGBA8).
///
/// * R: Perlin-Worley: a 5-octave Perlin FBM (4 cells across x) remapped by the G channel's
///   inverted Worley FBM, HZD style (see the crate docs).
/// * G, B, A: inverted Worley FBM (3 octaves, weights [`crate::WORLEY_FBM_WEIGHTS`]) with base
///   frequencies 4, 8 and 16 cells across x.
///
/// Cell counts along y and z are scaled by `size[axis] / size[0]` (rounded, at least 1), so
/// features are isotropic in texel units and every axis tiles. A zero size gives an empty texture.
pub fn shape_texture(seed: u64, size: [u32; 3]) -> Texture3 {
    if size.contains(&0) {
        return Texture3 {
            size,
            data: Vec::new(),
        };
    }
    let cells = |f: u32| size.map(|s| axis_cells(f, s, size[0]));
    let perlin = PerlinFbm3::new(
        cells(SHAPE_PERLIN_FREQ),
        SHAPE_PERLIN_OCTAVES,
        derive_seed(seed, TAG_SHAPE_PERLIN),
    );
    let worley: [WorleyFbm3; 3] = std::array::from_fn(|i| {
        WorleyFbm3::new(
            cells(SHAPE_WORLEY_FREQS[i]),
            derive_seed(seed, TAG_SHAPE_WORLEY + i as u64),
        )
    });
    fill3(size, |u| {
        let g = worley[0].eval(at(u, worley[0].period));
        let b = worley[1].eval(at(u, worley[1].period));
        let a = worley[2].eval(at(u, worley[2].period));
        let p = perlin.eval(at(u, perlin.period));
        let r = perlin_worley(p, g, SHAPE_PERLIN_GAIN, SHAPE_R_RANGE);
        [r, g, b, a]
    })
}

/// Generates the detail texture (thesis table 4.1 / HZD: 32^3): R, G, B = inverted Worley FBM
/// with base frequencies 2, 4 and 8 cells across the cube; A = 1 (padding, so the texture can be
/// uploaded as RGBA8). A zero size gives an empty texture.
pub fn detail_texture(seed: u64, size: u32) -> Texture3 {
    let size3 = [size; 3];
    if size == 0 {
        return Texture3 {
            size: size3,
            data: Vec::new(),
        };
    }
    let worley: [WorleyFbm3; 3] = std::array::from_fn(|i| {
        WorleyFbm3::new(
            [axis_cells(DETAIL_WORLEY_FREQS[i], size, size); 3],
            derive_seed(seed, TAG_DETAIL_WORLEY + i as u64),
        )
    });
    fill3(size3, |u| {
        let [r, g, b] = std::array::from_fn(|i| worley[i].eval(at(u, worley[i].period)));
        [r, g, b, 1.0]
    })
}

/// Generates the 2D curl-noise texture (HZD: 128^2; seed document 001 section 3.1.2: the curl of
/// 2D Perlin noise).
///
/// The potential ψ is a 3-octave tiling Perlin FBM (4 cells across). The curl
/// `(∂ψ/∂y, −∂ψ/∂x)` is taken by central differences between neighbouring texels (indices wrap,
/// so the result tiles), with x along increasing column index and y along increasing row index.
/// The field is divergence-free. It is divided by its maximum magnitude over the texture, so
/// `|curl| <= 1`, and encoded R = 0.5 * cx + 0.5, G = 0.5 * cy + 0.5 (decode with `2 * v - 1`),
/// B = 0.5 (neutral), A = 1.
pub fn curl_texture(seed: u64, size: u32) -> Texture2 {
    let n = size as usize;
    if n == 0 {
        return Texture2 {
            size: [size; 2],
            data: Vec::new(),
        };
    }
    let potential = PerlinFbm2::new(
        [axis_cells(CURL_FREQ, size, size); 2],
        CURL_OCTAVES,
        derive_seed(seed, TAG_CURL),
    );
    let mut psi = vec![0.0f64; n * n];
    psi.par_chunks_mut(n).enumerate().for_each(|(y, row)| {
        let uy = (y as f64 + 0.5) / n as f64;
        for (x, v) in row.iter_mut().enumerate() {
            let ux = (x as f64 + 0.5) / n as f64;
            *v = potential.eval(at([ux, uy], potential.period));
        }
    });
    let curl: Vec<[f64; 2]> = (0..n * n)
        .into_par_iter()
        .map(|i| {
            let (x, y) = (i % n, i / n);
            let (xm, xp) = ((x + n - 1) % n, (x + 1) % n);
            let (ym, yp) = ((y + n - 1) % n, (y + 1) % n);
            let dpsi_dx = 0.5 * (psi[y * n + xp] - psi[y * n + xm]);
            let dpsi_dy = 0.5 * (psi[yp * n + x] - psi[ym * n + x]);
            [dpsi_dy, -dpsi_dx]
        })
        .collect();
    // The maximum is exact and independent of reduction order.
    let max_len = curl
        .par_iter()
        .map(|c| (c[0] * c[0] + c[1] * c[1]).sqrt())
        .reduce(|| 0.0, f64::max);
    let inv = if max_len > 0.0 { 1.0 / max_len } else { 0.0 };
    let mut data = vec![0u8; n * n * 4];
    data.par_chunks_mut(4).zip(&curl).for_each(|(t, c)| {
        t[0] = to_unorm8(0.5 * c[0] * inv + 0.5);
        t[1] = to_unorm8(0.5 * c[1] * inv + 0.5);
        t[2] = to_unorm8(0.5);
        t[3] = to_unorm8(1.0);
    });
    Texture2 {
        size: [size; 2],
        data,
    }
}

/// Generates a procedural weather texture (HZD channel layout, Schneider 2015; tiles in x and y).
///
/// * R, coverage: Perlin-Worley of a 5-octave Perlin FBM (4 cells across) and an inverted Worley
///   FBM (4 cells), stretched so that there are clear-sky regions (0) and overcast regions (1).
/// * G, precipitation: zero below a coverage of 0.5, fading in up to full coverage, modulated by
///   an independent rain field; mostly low.
/// * B, cloud type: smooth 3-octave Perlin FBM at 2 cells across; 0 = stratus, 0.5 =
///   stratocumulus, 1 = cumulus.
/// * A, convective cells: the rank, in [0, 1], of a rough Perlin FBM (Hurst exponent 0.36)
///   among the texture's texels: uniform over the map, so that thresholding it at `1 - f`
///   covers `f` of it with islands of fractal outline and power-law sizes. The renderer's
///   `clouds.convective_cells` draws cumulus from it.
///
/// The thesis' weather texture (section 4.4, table 4.2) is laid out differently (R = coverage,
/// G = cloud height, B = start height); this crate follows HZD's layout. The thesis also scales
/// the texture over the whole scene to hide repetition (4.4), which is up to the renderer.
pub fn weather_texture(seed: u64, size: u32) -> Texture2 {
    let size2 = [size; 2];
    if size == 0 {
        return Texture2 {
            size: size2,
            data: Vec::new(),
        };
    }
    let cells = |f: u32| [axis_cells(f, size, size); 2];
    let cov_perlin = PerlinFbm2::new(
        cells(COVERAGE_PERLIN_FREQ),
        COVERAGE_PERLIN_OCTAVES,
        derive_seed(seed, TAG_COVERAGE_PERLIN),
    );
    let cov_worley = WorleyFbm2::new(
        cells(COVERAGE_WORLEY_FREQ),
        derive_seed(seed, TAG_COVERAGE_WORLEY),
    );
    let rain = PerlinFbm2::new(cells(RAIN_FREQ), RAIN_OCTAVES, derive_seed(seed, TAG_RAIN));
    let kind = PerlinFbm2::new(cells(TYPE_FREQ), TYPE_OCTAVES, derive_seed(seed, TAG_TYPE));
    let cell_rank = cell_ranks(seed, size);
    let mut tex = fill2(size2, |u| {
        let p = cov_perlin.eval(at(u, cov_perlin.period));
        let w = cov_worley.eval(at(u, cov_worley.period));
        let coverage = perlin_worley(p, w, COVERAGE_PERLIN_GAIN, COVERAGE_RANGE);
        let rain_field = (0.5 + rain.eval(at(u, rain.period))).clamp(0.0, 1.0);
        let precipitation =
            smoothstep(RAIN_COVERAGE_RAMP[0], RAIN_COVERAGE_RAMP[1], coverage) * rain_field;
        let cloud_type = (0.5 + 0.5 * TYPE_GAIN * kind.eval(at(u, kind.period))).clamp(0.0, 1.0);
        [coverage, precipitation, cloud_type, 1.0]
    });
    for (texel, rank) in tex.data.chunks_exact_mut(4).zip(cell_rank) {
        texel[3] = to_unorm8(rank);
    }
    tex
}

/// The weather map's A channel: each texel's rank among the rough cell FBM's values, scaled
/// to [0, 1] (ties broken by texel index, so that the result is deterministic).
fn cell_ranks(seed: u64, size: u32) -> Vec<f64> {
    let n = size as usize;
    let fbm = PerlinFbm2::with_gain(
        [axis_cells(CELL_FREQ, size, size); 2],
        CELL_OCTAVES,
        derive_seed(seed, TAG_CELLS),
        CELL_GAIN,
    );
    let values: Vec<f64> = (0..n * n)
        .into_par_iter()
        .map(|i| {
            let u = [
                ((i % n) as f64 + 0.5) / n as f64,
                ((i / n) as f64 + 0.5) / n as f64,
            ];
            fbm.eval(at(u, fbm.period))
        })
        .collect();
    let mut order: Vec<usize> = (0..n * n).collect();
    order.par_sort_unstable_by(|&a, &b| values[a].total_cmp(&values[b]).then(a.cmp(&b)));
    let mut rank = vec![0.0; n * n];
    let last = (n * n).saturating_sub(1).max(1) as f64;
    for (r, &i) in order.iter().enumerate() {
        rank[i] = r as f64 / last;
    }
    rank
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{perlin_fbm2, perlin_fbm3, worley_fbm2, worley_fbm3};

    fn centre(i: u32, n: u32) -> f64 {
        (f64::from(i) + 0.5) / f64::from(n)
    }

    /// The table-driven textures equal the documented formulas evaluated with the public,
    /// hash-per-call building blocks, byte for byte.
    #[test]
    fn shape_texels_match_point_functions() {
        let (seed, size) = (5, [16, 8, 12]);
        let tex = shape_texture(seed, size);
        let cells = |f: u32| size.map(|s| axis_cells(f, s, size[0]));
        for (x, y, z) in [(0, 0, 0), (15, 7, 11), (3, 5, 8), (9, 2, 0)] {
            let u = [centre(x, size[0]), centre(y, size[1]), centre(z, size[2])];
            let w: [f64; 3] = std::array::from_fn(|i| {
                let c = cells(SHAPE_WORLEY_FREQS[i]);
                worley_fbm3(at(u, c), c, derive_seed(seed, TAG_SHAPE_WORLEY + i as u64))
            });
            let c = cells(SHAPE_PERLIN_FREQ);
            let p = perlin_fbm3(
                at(u, c),
                c,
                SHAPE_PERLIN_OCTAVES,
                derive_seed(seed, TAG_SHAPE_PERLIN),
            );
            let r = perlin_worley(p, w[0], SHAPE_PERLIN_GAIN, SHAPE_R_RANGE);
            let expected = [r, w[0], w[1], w[2]].map(to_unorm8);
            assert_eq!(tex.texel(x, y, z), expected, "texel ({x}, {y}, {z})");
        }
    }

    #[test]
    fn detail_and_weather_texels_match_point_functions() {
        let seed = 9;
        let detail = detail_texture(seed, 10);
        let weather = weather_texture(seed, 24);
        for (x, y, z) in [(0, 0, 0), (9, 9, 9), (4, 1, 7)] {
            let u = [centre(x, 10), centre(y, 10), centre(z, 10)];
            let expected: [u8; 3] = std::array::from_fn(|i| {
                let c = [axis_cells(DETAIL_WORLEY_FREQS[i], 10, 10); 3];
                let seed = derive_seed(seed, TAG_DETAIL_WORLEY + i as u64);
                to_unorm8(worley_fbm3(at(u, c), c, seed))
            });
            let t = detail.texel(x, y, z);
            assert_eq!([t[0], t[1], t[2]], expected);
            assert_eq!(t[3], 255);
        }
        let c = |f: u32| [axis_cells(f, 24, 24); 2];
        for (x, y) in [(0, 0), (23, 23), (5, 17)] {
            let u = [centre(x, 24), centre(y, 24)];
            let p = perlin_fbm2(
                at(u, c(COVERAGE_PERLIN_FREQ)),
                c(COVERAGE_PERLIN_FREQ),
                COVERAGE_PERLIN_OCTAVES,
                derive_seed(seed, TAG_COVERAGE_PERLIN),
            );
            let w = worley_fbm2(
                at(u, c(COVERAGE_WORLEY_FREQ)),
                c(COVERAGE_WORLEY_FREQ),
                derive_seed(seed, TAG_COVERAGE_WORLEY),
            );
            let coverage = perlin_worley(p, w, COVERAGE_PERLIN_GAIN, COVERAGE_RANGE);
            assert_eq!(weather.texel(x, y)[0], to_unorm8(coverage));
        }
    }

    /// The curl texture encodes `(dψ/dy, -dψ/dx) / max|curl|` of the potential, by central
    /// differences with wrapped neighbours.
    #[test]
    fn curl_matches_definition() {
        let (seed, n) = (4u64, 16u32);
        let tex = curl_texture(seed, n);
        let c = [axis_cells(CURL_FREQ, n, n); 2];
        let psi = |x: u32, y: u32| {
            let u = [centre(x % n, n), centre(y % n, n)];
            perlin_fbm2(at(u, c), c, CURL_OCTAVES, derive_seed(seed, TAG_CURL))
        };
        let curl = |x: u32, y: u32| {
            let ddx = 0.5 * (psi(x + 1, y) - psi(x + n - 1, y));
            let ddy = 0.5 * (psi(x, y + 1) - psi(x, y + n - 1));
            [ddy, -ddx]
        };
        let max = (0..n * n)
            .map(|i| {
                let v = curl(i % n, i / n);
                (v[0] * v[0] + v[1] * v[1]).sqrt()
            })
            .fold(0.0, f64::max);
        for (x, y) in [(0, 0), (15, 15), (3, 9), (12, 1)] {
            let v = curl(x, y);
            let t = tex.texel(x, y);
            assert_eq!(t[0], to_unorm8(0.5 * v[0] / max + 0.5), "({x}, {y})");
            assert_eq!(t[1], to_unorm8(0.5 * v[1] / max + 0.5), "({x}, {y})");
            assert_eq!([t[2], t[3]], [128, 255]);
        }
    }

    /// The cell channel is the rough FBM's rank: uniform over the map (each tenth of the
    /// range holds a tenth of the texels), ordered as the FBM is, and the same every time.
    #[test]
    fn the_cell_channel_ranks_a_rough_fbm_uniformly() {
        let (seed, n) = (3u64, 64u32);
        let tex = weather_texture(seed, n);
        let a: Vec<u8> = tex.data.chunks_exact(4).map(|t| t[3]).collect();
        let total = a.len() as f64;
        for decile in 0..10u32 {
            let lo = (decile * 256 / 10) as u8;
            let hi = ((decile + 1) * 256 / 10).min(256);
            let share = a.iter().filter(|&&v| v >= lo && u32::from(v) < hi).count() as f64 / total;
            assert!((share - 0.1).abs() < 0.01, "decile {decile}: {share}");
        }
        let c = [axis_cells(CELL_FREQ, n, n); 2];
        let fbm = PerlinFbm2::with_gain(c, CELL_OCTAVES, derive_seed(seed, TAG_CELLS), CELL_GAIN);
        let value = |x: u32, y: u32| fbm.eval(at([centre(x, n), centre(y, n)], c));
        for ((x0, y0), (x1, y1)) in [((0, 0), (9, 33)), ((40, 2), (7, 61)), ((5, 5), (6, 5))] {
            let (v0, v1) = (value(x0, y0), value(x1, y1));
            let (a0, a1) = (tex.texel(x0, y0)[3], tex.texel(x1, y1)[3]);
            // 8-bit ranks may tie; they never invert.
            let ordered = if v0 < v1 { a0 <= a1 } else { a0 >= a1 };
            assert!(
                ordered,
                "({x0},{y0}) {v0} -> {a0}, ({x1},{y1}) {v1} -> {a1}"
            );
        }
        assert_eq!(weather_texture(seed, n).data, tex.data);
    }

    #[test]
    fn axis_cells_rounding() {
        assert_eq!(axis_cells(4, 128, 128), 4);
        assert_eq!(axis_cells(4, 32, 128), 1);
        assert_eq!(axis_cells(8, 32, 128), 2);
        assert_eq!(axis_cells(16, 32, 128), 4);
        assert_eq!(axis_cells(2, 32, 128), 1); // 0.5 rounds up, and never below 1
        assert_eq!(axis_cells(1, 1, 128), 1);
        assert_eq!(axis_cells(4, 100, 128), 3);
    }
}
