//! How converged a path-traced image is: per 8x8 block, the standard error of the block's mean
//! luminance relative to that mean, from the per-pixel second moments the GPU path tracer keeps
//! in `history-meta` (depth, paths, mean squared luminance, hits). A reference counts as
//! converged when every block with cloud in it is below 1%.

use stratus_graph::FrameOutput;

/// Block size in pixels (the path tracer tests' and the Mitsuba check's blocks).
pub const BLOCK: u32 = 8;
/// Relative standard error below which a block counts as converged.
pub const CONVERGED: f64 = 0.01;
/// Blocks whose mean luminance is below this share of the brightest block's hold (almost) no
/// cloud radiance, so a relative error says nothing there; they are counted, not judged.
const EMPTY: f64 = 1e-3;

/// The per-block noise of a path-traced frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Convergence {
    /// The largest relative standard error over the judged blocks.
    pub worst: f64,
    /// Its median.
    pub median: f64,
    /// Blocks judged.
    pub blocks: usize,
    /// Blocks without cloud radiance, not judged.
    pub empty: usize,
    /// Paths per pixel so far (the first pixel's; every pixel has the same).
    pub paths: f64,
}

impl Convergence {
    /// Whether every judged block is below [`CONVERGED`].
    pub fn converged(&self) -> bool {
        self.worst < CONVERGED
    }

    /// Paths per pixel that would bring the worst block to [`CONVERGED`] (the error falls
    /// as one over the square root of the paths).
    pub fn paths_for_converged(&self) -> f64 {
        self.paths * (self.worst / CONVERGED).powi(2)
    }
}

/// The noise of `out`'s radiance given its `history-meta` texels (rgba32float, tightly
/// packed); `None` where the sizes disagree or no block holds cloud.
pub fn block_noise(out: &FrameOutput, meta: &[u8]) -> Option<Convergence> {
    let blocks = stratus_graph::block_means(out, meta, BLOCK)?;
    let brightest = blocks.iter().map(|b| b.mean).fold(0.0, f64::max);
    if brightest <= 0.0 {
        return None;
    }
    let mut rel: Vec<f64> = blocks
        .iter()
        .filter(|b| b.mean > EMPTY * brightest)
        .map(|b| b.variance.sqrt() / b.mean)
        .collect();
    rel.sort_by(f64::total_cmp);
    let judged = rel.len();
    // Every pixel has the same path count: the first's (history-meta's second float).
    let paths = meta
        .get(4..8)
        .map(|c| f64::from(f32::from_le_bytes([c[0], c[1], c[2], c[3]])))?;
    Some(Convergence {
        worst: *rel.last()?,
        median: rel[judged / 2],
        blocks: judged,
        empty: blocks.len() - judged,
        paths,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame(w: u32, h: u32, lum: f32) -> FrameOutput {
        FrameOutput {
            width: w,
            height: h,
            radiance: (0..w * h).flat_map(|_| [lum, lum, lum, 1.0]).collect(),
            ..FrameOutput::default()
        }
    }

    fn meta(w: u32, h: u32, paths: f32, second: f32) -> Vec<u8> {
        (0..w * h)
            .flat_map(|_| [0.0f32, paths, second, 0.0])
            .flat_map(f32::to_le_bytes)
            .collect()
    }

    /// One 8x8 block of pixels of mean 1 and per-path variance 1 after 100 paths: each pixel's
    /// mean has variance 1/99 (the unbiased per-path variance over 100 paths is 100/99), the
    /// block's 1/(64 * 99), so its relative standard error is 1/(8 sqrt(99)).
    #[test]
    fn a_block_of_known_variance() {
        let c = block_noise(&frame(8, 8, 1.0), &meta(8, 8, 100.0, 2.0)).unwrap();
        let expected = 1.0 / (8.0 * 99f64.sqrt());
        assert!((c.worst - expected).abs() < 1e-9, "{c:?}");
        assert_eq!((c.blocks, c.empty), (1, 0));
        assert!(!c.converged());
        // Four times the paths halve the error: 4 * 100 paths (the ratio of 99s aside).
        assert!((c.paths_for_converged() - 100.0 * (expected / 0.01).powi(2)).abs() < 1e-6);
    }

    /// Blocks without radiance are counted, not judged; a size mismatch is no answer.
    #[test]
    fn empty_blocks_and_bad_sizes() {
        let mut f = frame(16, 8, 1.0);
        for y in 0..8 {
            for x in 8..16 {
                let i = (y * 16 + x) * 4;
                f.radiance[i..i + 3].fill(0.0);
            }
        }
        let c = block_noise(&f, &meta(16, 8, 100.0, 2.0)).unwrap();
        assert_eq!((c.blocks, c.empty), (1, 1));
        assert!(block_noise(&f, &meta(8, 8, 100.0, 2.0)).is_none());
        assert!(block_noise(&frame(8, 8, 0.0), &meta(8, 8, 100.0, 0.0)).is_none());
    }
}
