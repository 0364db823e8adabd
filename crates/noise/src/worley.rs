//! Tiling cellular (Worley) noise in 2D and 3D, and its inverted fractal sum.
//!
//! Follows the thesis (Högfeldt 2016, section 4.2.2): the domain is divided into equal cells,
//! each cell holds exactly one feature point at a random position inside it, and a point's value
//! is the Euclidean distance to the nearest feature point, found by looking at its own cell and
//! the 26 (3D) / 8 (2D) neighbouring cells. Neighbour cell indices wrap around at the period, so
//! the noise tiles in every dimension. One point per cell guarantees there are no large empty
//! (dark, once inverted) regions.
//!
//! Feature points are a pure hash of `(seed, wrapped cell)`. The public functions hash on every
//! call; the texture generators use the `*Grid` types, which precompute the feature points of one
//! octave (with a one-cell wrapped border) and evaluate with the same floating-point operations,
//! so both paths are bit-identical.

use crate::hash::{hash_coords, unit21};
use crate::perlin::{octave_period, octave_seed};

/// Weights of the three octaves of [`worley_fbm3`] / [`worley_fbm2`] (base, 2x and 4x
/// frequency). They sum to 1, so the FBM stays in `[0, 1]`. From the baseline blog post (seed
/// document 003, section "FBM": `WorleyFBM = 0.625 * Worley(freq=4) + 0.25 * Worley(freq=8) +
/// 0.125 * Worley(freq=16)`), the usual weights of the HZD-style Worley FBM.
pub const WORLEY_FBM_WEIGHTS: [f64; 3] = [0.625, 0.25, 0.125];

#[inline]
fn feature3(seed: u64, c: [u32; 3]) -> [f64; 3] {
    let h = hash_coords(seed, &c);
    [unit21(h, 0), unit21(h, 21), unit21(h, 42)]
}

#[inline]
fn feature2(seed: u64, c: [u32; 2]) -> [f64; 2] {
    let h = hash_coords(seed, &c);
    [unit21(h, 0), unit21(h, 21)]
}

#[inline]
fn dist2_3(q: [f64; 3], p: [f64; 3]) -> f64 {
    let d = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
    d[0] * d[0] + d[1] * d[1] + d[2] * d[2]
}

#[inline]
fn dist2_2(q: [f64; 2], p: [f64; 2]) -> f64 {
    let d = [q[0] - p[0], q[1] - p[1]];
    d[0] * d[0] + d[1] * d[1]
}

/// Tiling 3D Worley noise: distance from `p` to the nearest feature point, in cell units,
/// clamped to `[0, 1]`.
///
/// `p` is in cell units; the pattern repeats every `period` cells on each axis
/// (`worley3(p + period, ..) == worley3(p, ..)`). Every component of `period` must be at least 1
/// (a period of 1 or 2 simply makes the wrapped neighbours repeat the same feature points).
/// Not inverted: 0 at a feature point, growing towards cell borders.
pub fn worley3(p: [f64; 3], period: [u32; 3], seed: u64) -> f64 {
    assert!(period.iter().all(|&v| v > 0), "noise period must be >= 1");
    let c = p.map(|v| v.floor() as i64);
    let mut best = f64::INFINITY;
    for dz in -1..=1 {
        for dy in -1..=1 {
            for dx in -1..=1 {
                let n = [c[0] + dx, c[1] + dy, c[2] + dz];
                let w: [u32; 3] =
                    std::array::from_fn(|i| n[i].rem_euclid(i64::from(period[i])) as u32);
                let off = feature3(seed, w);
                let q = [
                    n[0] as f64 + off[0],
                    n[1] as f64 + off[1],
                    n[2] as f64 + off[2],
                ];
                best = min_fast(best, dist2_3(q, p));
            }
        }
    }
    best.sqrt().min(1.0)
}

/// Tiling 2D Worley noise (9-cell search); the 2D equivalent of [`worley3`].
pub fn worley2(p: [f64; 2], period: [u32; 2], seed: u64) -> f64 {
    assert!(period.iter().all(|&v| v > 0), "noise period must be >= 1");
    let c = p.map(|v| v.floor() as i64);
    let mut best = f64::INFINITY;
    for dy in -1..=1 {
        for dx in -1..=1 {
            let n = [c[0] + dx, c[1] + dy];
            let w: [u32; 2] = std::array::from_fn(|i| n[i].rem_euclid(i64::from(period[i])) as u32);
            let off = feature2(seed, w);
            let q = [n[0] as f64 + off[0], n[1] as f64 + off[1]];
            best = min_fast(best, dist2_2(q, p));
        }
    }
    best.sqrt().min(1.0)
}

/// Inverted Worley FBM in 3D: `sum_i WORLEY_FBM_WEIGHTS[i] * (1 - worley3(p * 2^i, period * 2^i))`
/// for `i = 0, 1, 2`, each octave with an independent seed derived from `seed`.
///
/// Inverting makes the feature points bright "billows" (HZD, Schneider 2015; thesis 4.2.2 notes
/// that inverting switches between wispy and billowy shapes). In `[0, 1]`, tiles with `period`.
pub fn worley_fbm3(p: [f64; 3], period: [u32; 3], seed: u64) -> f64 {
    let mut sum = 0.0;
    let mut scale = 1.0;
    for (o, w) in WORLEY_FBM_WEIGHTS.iter().enumerate() {
        let o = o as u32;
        let q = p.map(|v| v * scale);
        sum += w * (1.0 - worley3(q, octave_period(period, o), octave_seed(seed, o)));
        scale *= 2.0;
    }
    sum
}

/// Inverted Worley FBM in 2D; see [`worley_fbm3`].
pub fn worley_fbm2(p: [f64; 2], period: [u32; 2], seed: u64) -> f64 {
    let mut sum = 0.0;
    let mut scale = 1.0;
    for (o, w) in WORLEY_FBM_WEIGHTS.iter().enumerate() {
        let o = o as u32;
        let q = p.map(|v| v * scale);
        sum += w * (1.0 - worley2(q, octave_period(period, o), octave_seed(seed, o)));
        scale *= 2.0;
    }
    sum
}

/// `min` for non-NaN values without `f64::min`'s NaN handling (which dominated the inner loop).
#[inline(always)]
fn min_fast(a: f64, b: f64) -> f64 {
    if b < a { b } else { a }
}

/// One octave of [`worley3`] with all feature points precomputed.
///
/// The table covers cells `-1..=period` on each axis (the border cells hold the wrapped feature
/// points shifted by one period), stored as absolute positions, so the 27-cell search needs no
/// hashing and no modulo. `eval` requires `p` in `[0, period)` on every axis.
pub(crate) struct WorleyGrid3 {
    period: [u32; 3],
    stride: [usize; 2],
    points: Vec<[f64; 3]>,
}

impl WorleyGrid3 {
    pub(crate) fn new(period: [u32; 3], seed: u64) -> Self {
        assert!(period.iter().all(|&v| v > 0), "noise period must be >= 1");
        let n = period.map(|v| v as usize + 2);
        let mut points = Vec::with_capacity(n[0] * n[1] * n[2]);
        for z in 0..n[2] {
            for y in 0..n[1] {
                for x in 0..n[0] {
                    let cell = [x as i64 - 1, y as i64 - 1, z as i64 - 1];
                    let w: [u32; 3] =
                        std::array::from_fn(|i| cell[i].rem_euclid(i64::from(period[i])) as u32);
                    let off = feature3(seed, w);
                    points.push([
                        cell[0] as f64 + off[0],
                        cell[1] as f64 + off[1],
                        cell[2] as f64 + off[2],
                    ]);
                }
            }
        }
        Self {
            period,
            stride: [n[0], n[0] * n[1]],
            points,
        }
    }

    #[inline]
    pub(crate) fn eval(&self, p: [f64; 3]) -> f64 {
        let c: [usize; 3] = std::array::from_fn(|i| {
            debug_assert!(p[i] >= 0.0 && p[i] < f64::from(self.period[i]));
            p[i] as usize // p >= 0: truncation is floor
        });
        let [sy, sz] = self.stride;
        // Padded index of cell (c - 1), i.e. the first of the 27 neighbours.
        let base = c[0] + c[1] * sy + c[2] * sz;
        let mut best = f64::INFINITY;
        for dz in 0..3 {
            for dy in 0..3 {
                for &q in &self.points[base + dy * sy + dz * sz..][..3] {
                    best = min_fast(best, dist2_3(q, p));
                }
            }
        }
        best.sqrt().min(1.0)
    }
}

/// One octave of [`worley2`] with precomputed feature points; see [`WorleyGrid3`].
pub(crate) struct WorleyGrid2 {
    period: [u32; 2],
    stride: usize,
    points: Vec<[f64; 2]>,
}

impl WorleyGrid2 {
    pub(crate) fn new(period: [u32; 2], seed: u64) -> Self {
        assert!(period.iter().all(|&v| v > 0), "noise period must be >= 1");
        let n = period.map(|v| v as usize + 2);
        let mut points = Vec::with_capacity(n[0] * n[1]);
        for y in 0..n[1] {
            for x in 0..n[0] {
                let cell = [x as i64 - 1, y as i64 - 1];
                let w: [u32; 2] =
                    std::array::from_fn(|i| cell[i].rem_euclid(i64::from(period[i])) as u32);
                let off = feature2(seed, w);
                points.push([cell[0] as f64 + off[0], cell[1] as f64 + off[1]]);
            }
        }
        Self {
            period,
            stride: n[0],
            points,
        }
    }

    #[inline]
    pub(crate) fn eval(&self, p: [f64; 2]) -> f64 {
        let c: [usize; 2] = std::array::from_fn(|i| {
            debug_assert!(p[i] >= 0.0 && p[i] < f64::from(self.period[i]));
            p[i] as usize // p >= 0: truncation is floor
        });
        let base = c[0] + c[1] * self.stride;
        let mut best = f64::INFINITY;
        for dy in 0..3 {
            for &q in &self.points[base + dy * self.stride..][..3] {
                best = min_fast(best, dist2_2(q, p));
            }
        }
        best.sqrt().min(1.0)
    }
}

/// Table-driven equivalent of [`worley_fbm3`] (bit-identical for `p` in `[0, period)`).
pub(crate) struct WorleyFbm3 {
    /// Base period (octave 0).
    pub(crate) period: [u32; 3],
    octaves: [WorleyGrid3; 3],
}

impl WorleyFbm3 {
    pub(crate) fn new(period: [u32; 3], seed: u64) -> Self {
        let octaves = std::array::from_fn(|o| {
            let o = o as u32;
            WorleyGrid3::new(octave_period(period, o), octave_seed(seed, o))
        });
        Self { period, octaves }
    }

    #[inline]
    pub(crate) fn eval(&self, p: [f64; 3]) -> f64 {
        let mut sum = 0.0;
        let mut scale = 1.0;
        for (grid, w) in self.octaves.iter().zip(WORLEY_FBM_WEIGHTS) {
            let q = p.map(|v| v * scale);
            sum += w * (1.0 - grid.eval(q));
            scale *= 2.0;
        }
        sum
    }
}

/// Table-driven equivalent of [`worley_fbm2`] (bit-identical for `p` in `[0, period)`).
pub(crate) struct WorleyFbm2 {
    /// Base period (octave 0).
    pub(crate) period: [u32; 2],
    octaves: [WorleyGrid2; 3],
}

impl WorleyFbm2 {
    pub(crate) fn new(period: [u32; 2], seed: u64) -> Self {
        let octaves = std::array::from_fn(|o| {
            let o = o as u32;
            WorleyGrid2::new(octave_period(period, o), octave_seed(seed, o))
        });
        Self { period, octaves }
    }

    #[inline]
    pub(crate) fn eval(&self, p: [f64; 2]) -> f64 {
        let mut sum = 0.0;
        let mut scale = 1.0;
        for (grid, w) in self.octaves.iter().zip(WORLEY_FBM_WEIGHTS) {
            let q = p.map(|v| v * scale);
            sum += w * (1.0 - grid.eval(q));
            scale *= 2.0;
        }
        sum
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_matches_hashed_3d() {
        for period in [[4, 1, 6], [1, 1, 1], [2, 3, 2]] {
            let grid = WorleyGrid3::new(period, 7);
            let fbm = WorleyFbm3::new(period, 9);
            for i in 0..300 {
                let t = i as f64 * 0.618_033_988_75;
                let p: [f64; 3] = std::array::from_fn(|k| {
                    (t * [3.1, 1.7, 5.3][k]).rem_euclid(f64::from(period[k]))
                });
                assert_eq!(grid.eval(p), worley3(p, period, 7));
                assert_eq!(fbm.eval(p), worley_fbm3(p, period, 9));
            }
        }
    }

    #[test]
    fn grid_matches_hashed_2d() {
        for period in [[3, 5], [1, 1], [1, 2]] {
            let grid = WorleyGrid2::new(period, 7);
            let fbm = WorleyFbm2::new(period, 9);
            for i in 0..300 {
                let t = i as f64 * 0.618_033_988_75;
                let p = [
                    (t * 3.1).rem_euclid(f64::from(period[0])),
                    (t * 1.7).rem_euclid(f64::from(period[1])),
                ];
                assert_eq!(grid.eval(p), worley2(p, period, 7));
                assert_eq!(fbm.eval(p), worley_fbm2(p, period, 9));
            }
        }
    }

    #[test]
    fn zero_at_feature_points() {
        let off = feature3(5, [1, 2, 3]);
        let p = [1.0 + off[0], 2.0 + off[1], 3.0 + off[2]];
        assert_eq!(worley3(p, [4, 4, 4], 5), 0.0);
        let off = feature2(5, [1, 2]);
        assert_eq!(worley2([1.0 + off[0], 2.0 + off[1]], [4, 4], 5), 0.0);
    }
}
