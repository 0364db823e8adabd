//! Properties of the point-evaluated noise functions: tiling, ranges, continuity, seeds.

use stratus_noise::{
    perlin_fbm2, perlin_fbm3, perlin2, perlin3, worley_fbm2, worley_fbm3, worley2, worley3,
};

/// Deterministic quasi-random sample points in `[-span, span)^N` (golden-ratio sequence).
fn points<const N: usize>(count: usize, span: f64) -> Vec<[f64; N]> {
    const STEPS: [f64; 3] = [0.754_877_666_2, 0.569_840_290_9, 0.438_579_006_9];
    (1..=count)
        .map(|i| std::array::from_fn(|k| ((i as f64 * STEPS[k]).fract() * 2.0 - 1.0) * span))
        .collect()
}

const PERIODS3: [[u32; 3]; 4] = [[4, 1, 4], [3, 5, 7], [1, 1, 1], [16, 4, 16]];
const PERIODS2: [[u32; 2]; 4] = [[4, 4], [3, 7], [1, 1], [16, 2]];

fn shifted<const N: usize>(p: [f64; N], period: [u32; N], k: [i32; N]) -> [f64; N] {
    std::array::from_fn(|i| p[i] + f64::from(k[i]) * f64::from(period[i]))
}

#[test]
fn noise_3d_tiles_in_every_axis() {
    for period in PERIODS3 {
        for p in points::<3>(400, 20.0) {
            for k in [[1, 0, 0], [0, 1, 0], [0, 0, 1], [-2, 3, -1]] {
                let q = shifted(p, period, k);
                let checks = [
                    (perlin3(p, period, 11), perlin3(q, period, 11)),
                    (worley3(p, period, 11), worley3(q, period, 11)),
                    (perlin_fbm3(p, period, 4, 11), perlin_fbm3(q, period, 4, 11)),
                    (worley_fbm3(p, period, 11), worley_fbm3(q, period, 11)),
                ];
                for (a, b) in checks {
                    assert!((a - b).abs() <= 1e-9, "{p:?} period {period:?}: {a} vs {b}");
                }
            }
        }
    }
}

#[test]
fn noise_2d_tiles_in_every_axis() {
    for period in PERIODS2 {
        for p in points::<2>(400, 20.0) {
            for k in [[1, 0], [0, 1], [-3, 2]] {
                let q = shifted(p, period, k);
                let checks = [
                    (perlin2(p, period, 5), perlin2(q, period, 5)),
                    (worley2(p, period, 5), worley2(q, period, 5)),
                    (perlin_fbm2(p, period, 5, 5), perlin_fbm2(q, period, 5, 5)),
                    (worley_fbm2(p, period, 5), worley_fbm2(q, period, 5)),
                ];
                for (a, b) in checks {
                    assert!((a - b).abs() <= 1e-9, "{p:?} period {period:?}: {a} vs {b}");
                }
            }
        }
    }
}

#[test]
fn value_ranges() {
    let (mut pmin, mut pmax) = (f64::MAX, f64::MIN);
    for p in points::<3>(20_000, 8.0) {
        let v = perlin3(p, [8, 8, 8], 3);
        pmin = pmin.min(v);
        pmax = pmax.max(v);
        assert!((0.0..=1.0).contains(&worley3(p, [8, 8, 8], 3)));
        assert!((0.0..=1.0).contains(&worley_fbm3(p, [8, 8, 8], 3)));
        assert!(perlin_fbm3(p, [8, 8, 8], 5, 3).abs() <= 1.0);
    }
    // "Roughly [-1, 1]", and actually using a good part of it.
    assert!(pmin > -1.1 && pmin < -0.6, "perlin3 min {pmin}");
    assert!(pmax < 1.1 && pmax > 0.6, "perlin3 max {pmax}");

    let (mut pmin, mut pmax) = (f64::MAX, f64::MIN);
    for p in points::<2>(20_000, 8.0) {
        let v = perlin2(p, [8, 8], 3);
        pmin = pmin.min(v);
        pmax = pmax.max(v);
        assert!((0.0..=1.0).contains(&worley2(p, [8, 8], 3)));
        assert!((0.0..=1.0).contains(&worley_fbm2(p, [8, 8], 3)));
        assert!(perlin_fbm2(p, [8, 8], 5, 3).abs() <= 1.0);
    }
    assert!(pmin > -1.1 && pmin < -0.6, "perlin2 min {pmin}");
    assert!(pmax < 1.1 && pmax > 0.6, "perlin2 max {pmax}");
}

#[test]
fn noise_is_continuous() {
    // Lipschitz-style check: a step of 1e-4 cells never changes the value by more than 1e-3
    // (Perlin's gradients have length sqrt 2; Worley's distance is 1-Lipschitz).
    let h = 1e-4;
    for p in points::<3>(2_000, 6.0) {
        for axis in 0..3 {
            let mut q = p;
            q[axis] += h;
            assert!((perlin3(p, [3, 2, 5], 1) - perlin3(q, [3, 2, 5], 1)).abs() < 1e-3);
            assert!((worley3(p, [3, 2, 5], 1) - worley3(q, [3, 2, 5], 1)).abs() < 1e-3);
        }
    }
}

#[test]
fn seeds_change_the_noise() {
    let ps = points::<3>(64, 4.0);
    let differs = |f: &dyn Fn([f64; 3], u64) -> f64| ps.iter().any(|&p| f(p, 1) != f(p, 2));
    assert!(differs(&|p, s| perlin3(p, [4, 4, 4], s)));
    assert!(differs(&|p, s| worley3(p, [4, 4, 4], s)));
    assert!(differs(&|p, s| perlin_fbm3(p, [4, 4, 4], 3, s)));
    assert!(differs(&|p, s| worley_fbm3(p, [4, 4, 4], s)));
    assert!(differs(&|p, s| perlin2([p[0], p[1]], [4, 4], s)));
    assert!(differs(&|p, s| worley2([p[0], p[1]], [4, 4], s)));
}
