//! Tiling gradient (Perlin) noise in 2D and 3D, and its fractal sum (FBM).
//!
//! The thesis (Högfeldt 2016, section 4.2.1) generates its tiling Perlin noise with Gustavson's
//! periodic variant of Perlin's improved noise: the gradient lattice is indexed modulo the period,
//! so `f(p + period) == f(p)` exactly. This module does the same, with gradients chosen by an
//! integer hash of `(seed, wrapped lattice point)` instead of a permutation table, so any period
//! (not just powers of two) tiles and the seed space is 64 bits.
//!
//! The public functions hash on every call. The texture generators use the `*Grid` types, which
//! precompute the gradient index of every lattice point of one octave and then evaluate with the
//! *same* floating-point operations, so both paths give bit-identical results.

use crate::hash::{derive_seed, hash_coords};

/// The 12 edge-midpoint gradients of Perlin's improved noise (length sqrt 2).
const GRAD3: [[f64; 3]; 12] = [
    [1.0, 1.0, 0.0],
    [-1.0, 1.0, 0.0],
    [1.0, -1.0, 0.0],
    [-1.0, -1.0, 0.0],
    [1.0, 0.0, 1.0],
    [-1.0, 0.0, 1.0],
    [1.0, 0.0, -1.0],
    [-1.0, 0.0, -1.0],
    [0.0, 1.0, 1.0],
    [0.0, -1.0, 1.0],
    [0.0, 1.0, -1.0],
    [0.0, -1.0, -1.0],
];

/// 8 gradients of length sqrt 2 at multiples of 45 degrees, so 2D noise also spans about [-1, 1].
const GRAD2: [[f64; 2]; 8] = [
    [1.0, 1.0],
    [-1.0, 1.0],
    [1.0, -1.0],
    [-1.0, -1.0],
    [std::f64::consts::SQRT_2, 0.0],
    [-std::f64::consts::SQRT_2, 0.0],
    [0.0, std::f64::consts::SQRT_2],
    [0.0, -std::f64::consts::SQRT_2],
];

/// Perlin's quintic fade curve 6t^5 - 15t^4 + 10t^3 (C2 continuous at lattice planes).
#[inline]
fn fade(t: f64) -> f64 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

#[inline]
fn lerp(a: f64, b: f64, t: f64) -> f64 {
    a + t * (b - a)
}

#[inline]
fn grad3_index(seed: u64, c: [u32; 3]) -> u8 {
    ((hash_coords(seed, &c) >> 40) % 12) as u8
}

#[inline]
fn grad2_index(seed: u64, c: [u32; 2]) -> u8 {
    ((hash_coords(seed, &c) >> 40) % 8) as u8
}

/// Lattice cell containing `v` wrapped into `[0, period)`, and the next lattice index (wrapped).
#[inline]
fn wrap_cell(v: f64, period: u32) -> (u32, u32) {
    assert!(period > 0, "noise period must be at least 1");
    let c = (v.floor() as i64).rem_euclid(i64::from(period)) as u32;
    let c1 = if c + 1 == period { 0 } else { c + 1 };
    (c, c1)
}

#[inline]
fn dot3(g: [f64; 3], x: f64, y: f64, z: f64) -> f64 {
    g[0] * x + g[1] * y + g[2] * z
}

#[inline]
fn dot2(g: [f64; 2], x: f64, y: f64) -> f64 {
    g[0] * x + g[1] * y
}

/// Trilinear blend of the 8 corner contributions; shared by the hashed and the table path.
#[inline]
fn perlin3_blend(f: [f64; 3], g: [[f64; 3]; 8]) -> f64 {
    let [x, y, z] = f;
    let n000 = dot3(g[0], x, y, z);
    let n100 = dot3(g[1], x - 1.0, y, z);
    let n010 = dot3(g[2], x, y - 1.0, z);
    let n110 = dot3(g[3], x - 1.0, y - 1.0, z);
    let n001 = dot3(g[4], x, y, z - 1.0);
    let n101 = dot3(g[5], x - 1.0, y, z - 1.0);
    let n011 = dot3(g[6], x, y - 1.0, z - 1.0);
    let n111 = dot3(g[7], x - 1.0, y - 1.0, z - 1.0);
    let (u, v, w) = (fade(x), fade(y), fade(z));
    let nx00 = lerp(n000, n100, u);
    let nx10 = lerp(n010, n110, u);
    let nx01 = lerp(n001, n101, u);
    let nx11 = lerp(n011, n111, u);
    lerp(lerp(nx00, nx10, v), lerp(nx01, nx11, v), w)
}

#[inline]
fn perlin2_blend(f: [f64; 2], g: [[f64; 2]; 4]) -> f64 {
    let [x, y] = f;
    let n00 = dot2(g[0], x, y);
    let n10 = dot2(g[1], x - 1.0, y);
    let n01 = dot2(g[2], x, y - 1.0);
    let n11 = dot2(g[3], x - 1.0, y - 1.0);
    let (u, v) = (fade(x), fade(y));
    lerp(lerp(n00, n10, u), lerp(n01, n11, u), v)
}

/// Tiling 3D gradient noise.
///
/// `p` is in lattice units (one unit = one gradient cell); the result repeats with `period`
/// cells along each axis, i.e. `perlin3(p + period, period, seed) == perlin3(p, period, seed)`.
/// Values are roughly in `[-1, 1]` (the 12 improved-noise gradients have length sqrt 2); the
/// distribution is concentrated around 0. Every component of `period` must be at least 1.
pub fn perlin3(p: [f64; 3], period: [u32; 3], seed: u64) -> f64 {
    let (x0, x1) = wrap_cell(p[0], period[0]);
    let (y0, y1) = wrap_cell(p[1], period[1]);
    let (z0, z1) = wrap_cell(p[2], period[2]);
    let f = [
        p[0] - p[0].floor(),
        p[1] - p[1].floor(),
        p[2] - p[2].floor(),
    ];
    let g = |x, y, z| GRAD3[grad3_index(seed, [x, y, z]) as usize];
    perlin3_blend(
        f,
        [
            g(x0, y0, z0),
            g(x1, y0, z0),
            g(x0, y1, z0),
            g(x1, y1, z0),
            g(x0, y0, z1),
            g(x1, y0, z1),
            g(x0, y1, z1),
            g(x1, y1, z1),
        ],
    )
}

/// Tiling 2D gradient noise; the 2D equivalent of [`perlin3`] (roughly in `[-1, 1]`).
pub fn perlin2(p: [f64; 2], period: [u32; 2], seed: u64) -> f64 {
    let (x0, x1) = wrap_cell(p[0], period[0]);
    let (y0, y1) = wrap_cell(p[1], period[1]);
    let f = [p[0] - p[0].floor(), p[1] - p[1].floor()];
    let g = |x, y| GRAD2[grad2_index(seed, [x, y]) as usize];
    perlin2_blend(f, [g(x0, y0), g(x1, y0), g(x0, y1), g(x1, y1)])
}

/// Period of FBM octave `octave` (the base period doubled `octave` times).
#[inline]
pub(crate) fn octave_period<const N: usize>(period: [u32; N], octave: u32) -> [u32; N] {
    period.map(|v| {
        v.checked_mul(1u32 << octave)
            .expect("noise period overflows u32 at this octave")
    })
}

/// Seed of FBM octave `octave`, derived from the FBM's seed (octaves are independent).
#[inline]
pub(crate) fn octave_seed(seed: u64, octave: u32) -> u64 {
    derive_seed(seed, u64::from(octave))
}

/// Fractal Brownian motion of [`perlin3`]: `octaves` octaves, each at twice the frequency (and
/// twice the period, so the sum still tiles with `period`) and half the amplitude of the previous,
/// divided by the sum of the amplitudes. Octave `i` uses an independent seed derived from
/// `seed` and `i`. The result is roughly in `[-1, 1]`, in practice mostly within `[-0.6, 0.6]`.
pub fn perlin_fbm3(p: [f64; 3], period: [u32; 3], octaves: u32, seed: u64) -> f64 {
    let mut sum = 0.0;
    let mut amp = 1.0;
    let mut norm = 0.0;
    let mut scale = 1.0;
    for o in 0..octaves {
        let q = p.map(|v| v * scale);
        sum += amp * perlin3(q, octave_period(period, o), octave_seed(seed, o));
        norm += amp;
        amp *= 0.5;
        scale *= 2.0;
    }
    if norm > 0.0 { sum / norm } else { 0.0 }
}

/// Fractal Brownian motion of [`perlin2`]; see [`perlin_fbm3`].
pub fn perlin_fbm2(p: [f64; 2], period: [u32; 2], octaves: u32, seed: u64) -> f64 {
    let mut sum = 0.0;
    let mut amp = 1.0;
    let mut norm = 0.0;
    let mut scale = 1.0;
    for o in 0..octaves {
        let q = p.map(|v| v * scale);
        sum += amp * perlin2(q, octave_period(period, o), octave_seed(seed, o));
        norm += amp;
        amp *= 0.5;
        scale *= 2.0;
    }
    if norm > 0.0 { sum / norm } else { 0.0 }
}

/// One octave of [`perlin3`] with the gradient of every lattice point precomputed.
///
/// The table has `period + 1` entries per axis (the last one repeats the first), so evaluation
/// never wraps. `eval` requires `p` in `[0, period)` on every axis.
pub(crate) struct PerlinGrid3 {
    period: [u32; 3],
    stride: [usize; 2],
    grad: Vec<u8>,
}

impl PerlinGrid3 {
    pub(crate) fn new(period: [u32; 3], seed: u64) -> Self {
        assert!(period.iter().all(|&v| v > 0), "noise period must be >= 1");
        let n = period.map(|v| v as usize + 1);
        let mut grad = Vec::with_capacity(n[0] * n[1] * n[2]);
        for z in 0..n[2] as u32 {
            for y in 0..n[1] as u32 {
                for x in 0..n[0] as u32 {
                    let c = [x % period[0], y % period[1], z % period[2]];
                    grad.push(grad3_index(seed, c));
                }
            }
        }
        Self {
            period,
            stride: [n[0], n[0] * n[1]],
            grad,
        }
    }

    #[inline]
    pub(crate) fn eval(&self, p: [f64; 3]) -> f64 {
        // `p >= 0`, so truncation is floor (and avoids a libm call without SSE4.1).
        let c: [usize; 3] = std::array::from_fn(|i| {
            debug_assert!(p[i] >= 0.0 && p[i] < f64::from(self.period[i]));
            p[i] as usize
        });
        let fl = c.map(|v| v as f64);
        let f = [p[0] - fl[0], p[1] - fl[1], p[2] - fl[2]];
        let [sy, sz] = self.stride;
        let i000 = c[0] + c[1] * sy + c[2] * sz;
        let g = |i: usize| GRAD3[self.grad[i] as usize];
        perlin3_blend(
            f,
            [
                g(i000),
                g(i000 + 1),
                g(i000 + sy),
                g(i000 + sy + 1),
                g(i000 + sz),
                g(i000 + sz + 1),
                g(i000 + sz + sy),
                g(i000 + sz + sy + 1),
            ],
        )
    }
}

/// One octave of [`perlin2`] with precomputed gradients; see [`PerlinGrid3`].
pub(crate) struct PerlinGrid2 {
    period: [u32; 2],
    stride: usize,
    grad: Vec<u8>,
}

impl PerlinGrid2 {
    pub(crate) fn new(period: [u32; 2], seed: u64) -> Self {
        assert!(period.iter().all(|&v| v > 0), "noise period must be >= 1");
        let n = period.map(|v| v as usize + 1);
        let mut grad = Vec::with_capacity(n[0] * n[1]);
        for y in 0..n[1] as u32 {
            for x in 0..n[0] as u32 {
                grad.push(grad2_index(seed, [x % period[0], y % period[1]]));
            }
        }
        Self {
            period,
            stride: n[0],
            grad,
        }
    }

    #[inline]
    pub(crate) fn eval(&self, p: [f64; 2]) -> f64 {
        let c: [usize; 2] = std::array::from_fn(|i| {
            debug_assert!(p[i] >= 0.0 && p[i] < f64::from(self.period[i]));
            p[i] as usize
        });
        let fl = c.map(|v| v as f64);
        let f = [p[0] - fl[0], p[1] - fl[1]];
        let i00 = c[0] + c[1] * self.stride;
        let g = |i: usize| GRAD2[self.grad[i] as usize];
        perlin2_blend(
            f,
            [
                g(i00),
                g(i00 + 1),
                g(i00 + self.stride),
                g(i00 + self.stride + 1),
            ],
        )
    }
}

/// Table-driven equivalent of [`perlin_fbm3`] (bit-identical for `p` in `[0, period)`).
pub(crate) struct PerlinFbm3 {
    /// Base period (octave 0).
    pub(crate) period: [u32; 3],
    octaves: Vec<PerlinGrid3>,
}

impl PerlinFbm3 {
    pub(crate) fn new(period: [u32; 3], octaves: u32, seed: u64) -> Self {
        let octaves = (0..octaves)
            .map(|o| PerlinGrid3::new(octave_period(period, o), octave_seed(seed, o)))
            .collect();
        Self { period, octaves }
    }

    #[inline]
    pub(crate) fn eval(&self, p: [f64; 3]) -> f64 {
        let mut sum = 0.0;
        let mut amp = 1.0;
        let mut norm = 0.0;
        let mut scale = 1.0;
        for grid in &self.octaves {
            let q = p.map(|v| v * scale);
            sum += amp * grid.eval(q);
            norm += amp;
            amp *= 0.5;
            scale *= 2.0;
        }
        if norm > 0.0 { sum / norm } else { 0.0 }
    }
}

/// Table-driven equivalent of [`perlin_fbm2`] (bit-identical for `p` in `[0, period)`).
pub(crate) struct PerlinFbm2 {
    /// Base period (octave 0).
    pub(crate) period: [u32; 2],
    octaves: Vec<PerlinGrid2>,
    /// Amplitude of each octave over the last (0.5 for [`perlin_fbm2`]).
    gain: f64,
}

impl PerlinFbm2 {
    pub(crate) fn new(period: [u32; 2], octaves: u32, seed: u64) -> Self {
        let octaves = (0..octaves)
            .map(|o| PerlinGrid2::new(octave_period(period, o), octave_seed(seed, o)))
            .collect();
        Self {
            period,
            octaves,
            gain: 0.5,
        }
    }

    /// As [`PerlinFbm2::new`], each octave `gain` times the last's amplitude: a gain `g`
    /// gives the field a Hurst exponent `H = -log2(g)` over its octaves (0.5: H = 1, smooth).
    pub(crate) fn with_gain(period: [u32; 2], octaves: u32, seed: u64, gain: f64) -> Self {
        Self {
            gain,
            ..Self::new(period, octaves, seed)
        }
    }

    #[inline]
    pub(crate) fn eval(&self, p: [f64; 2]) -> f64 {
        let mut sum = 0.0;
        let mut amp = 1.0;
        let mut norm = 0.0;
        let mut scale = 1.0;
        for grid in &self.octaves {
            let q = p.map(|v| v * scale);
            sum += amp * grid.eval(q);
            norm += amp;
            amp *= self.gain;
            scale *= 2.0;
        }
        if norm > 0.0 { sum / norm } else { 0.0 }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_matches_hashed_3d() {
        let period = [4, 1, 6];
        let grid = PerlinGrid3::new(period, 7);
        let fbm = PerlinFbm3::new(period, 4, 9);
        for i in 0..500 {
            let t = i as f64 * 0.618_033_988_75;
            let p = [
                (t * 3.1).rem_euclid(4.0),
                (t * 1.7).rem_euclid(1.0),
                (t * 5.3).rem_euclid(6.0),
            ];
            assert_eq!(grid.eval(p), perlin3(p, period, 7));
            assert_eq!(fbm.eval(p), perlin_fbm3(p, period, 4, 9));
        }
    }

    #[test]
    fn grid_matches_hashed_2d() {
        let period = [3, 5];
        let grid = PerlinGrid2::new(period, 7);
        let fbm = PerlinFbm2::new(period, 5, 9);
        for i in 0..500 {
            let t = i as f64 * 0.618_033_988_75;
            let p = [(t * 3.1).rem_euclid(3.0), (t * 1.7).rem_euclid(5.0)];
            assert_eq!(grid.eval(p), perlin2(p, period, 7));
            assert_eq!(fbm.eval(p), perlin_fbm2(p, period, 5, 9));
        }
    }

    #[test]
    fn zero_at_lattice_points() {
        assert_eq!(perlin3([2.0, 3.0, 1.0], [4, 4, 4], 1), 0.0);
        assert_eq!(perlin2([2.0, 3.0], [4, 4], 1), 0.0);
    }
}
