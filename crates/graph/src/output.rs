//! What a frame hands back, the same from every backend (and from the CPU renderers).

use std::collections::BTreeMap;

/// What a backend hands back for one frame. Fields the frame was not asked to read back are
/// empty.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FrameOutput {
    /// Image width.
    pub width: u32,
    /// Image height.
    pub height: u32,
    /// Linear in-scattered radiance (rgb) and transmittance (a), row-major, 4 floats a pixel.
    pub radiance: Vec<f32>,
    /// Transmittance-weighted depth in metres (0 where no cloud), one float a pixel.
    pub depth: Vec<f32>,
    /// The tone-mapped display image, RGBA8, row-major.
    pub image: Vec<u8>,
    /// Other resources read back by name (tightly packed rows of texels).
    pub resources: BTreeMap<String, Vec<u8>>,
    /// Work counters by name, when the plan gathers them.
    pub stats: Option<BTreeMap<String, u64>>,
    /// Time of every pass that ran, in plan order.
    pub timings: Vec<PassTiming>,
    /// CPU time of recording and submitting the frame (not waiting for it), in ms.
    pub cpu_ms: f64,
    /// The device that ran the frame, in words.
    pub device: String,
}

impl FrameOutput {
    /// The luminance ([`LUMA`]) of pixel `i`'s in-scattered radiance.
    pub fn luminance(&self, i: usize) -> f64 {
        (0..3)
            .map(|c| LUMA[c] * f64::from(self.radiance[4 * i + c]))
            .sum()
    }
}

/// The measured time of one pass.
#[derive(Clone, Debug, PartialEq)]
pub struct PassTiming {
    /// Pass name.
    pub pass: String,
    /// Milliseconds.
    pub ms: f64,
    /// `gpu-timestamp` (timestamp queries) or `cpu-wall` (the pass submitted alone and waited
    /// for, where the device has no timestamp queries).
    pub source: &'static str,
}

/// Rec. 709 luminance weights, the path tracer's (`wgsl/pathtrace.wgsl`'s `luminance`).
pub const LUMA: [f64; 3] = [0.2126, 0.7152, 0.0722];

/// One block of a path-traced frame: the mean luminance of its pixels and the variance of that
/// mean.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BlockMean {
    /// Left column of the block.
    pub x: u32,
    /// Top row of the block.
    pub y: u32,
    /// Mean luminance over the block's pixels.
    pub mean: f64,
    /// Variance of `mean`: each pixel's per-path variance over its paths (unbiased), over its
    /// path count, summed and divided by the square of the pixel count.
    pub variance: f64,
}

/// The `block` x `block` blocks (partial at the right and bottom edges) of a path-traced
/// frame's radiance, with the noise of each block's mean from the path tracer's `meta` texels
/// (`history-meta`, rgba32float tightly packed: depth, paths, mean squared luminance, hits).
/// `None` where the sizes disagree.
pub fn block_means(out: &FrameOutput, meta: &[u8], block: u32) -> Option<Vec<BlockMean>> {
    let (w, h) = (out.width as usize, out.height as usize);
    let meta: Vec<f64> = meta
        .chunks_exact(4)
        .map(|c| f64::from(f32::from_le_bytes([c[0], c[1], c[2], c[3]])))
        .collect();
    if meta.len() != 4 * w * h || out.radiance.len() != 4 * w * h || block == 0 {
        return None;
    }
    let b = block as usize;
    let mut blocks = Vec::new();
    for by in (0..h).step_by(b) {
        for bx in (0..w).step_by(b) {
            let (mut sum, mut var, mut n) = (0.0, 0.0, 0.0);
            for y in by..(by + b).min(h) {
                for x in bx..(bx + b).min(w) {
                    let i = y * w + x;
                    let l = out.luminance(i);
                    let (paths, second) = (meta[4 * i + 1], meta[4 * i + 2]);
                    sum += l;
                    n += 1.0;
                    if paths > 1.0 {
                        // The per-path variance (second - l^2) paths / (paths - 1), over paths.
                        var += (second - l * l).max(0.0) / (paths - 1.0);
                    }
                }
            }
            blocks.push(BlockMean {
                x: bx as u32,
                y: by as u32,
                mean: sum / n,
                variance: var / (n * n),
            });
        }
    }
    Some(blocks)
}

/// Names the counters read back from a statistics buffer.
pub fn named_counters(names: &[String], raw: &[u32]) -> BTreeMap<String, u64> {
    names
        .iter()
        .zip(raw)
        .map(|(n, v)| (n.clone(), u64::from(*v)))
        .collect()
}

/// The median of `values` (the mean of the middle two for an even count; NaN when empty):
/// what every benchmark and report here quotes, being robust to the odd slow frame.
pub fn median(mut values: Vec<f64>) -> f64 {
    if values.is_empty() {
        return f64::NAN;
    }
    values.sort_by(f64::total_cmp);
    let n = values.len();
    if n % 2 == 1 {
        values[n / 2]
    } else {
        0.5 * (values[n / 2 - 1] + values[n / 2])
    }
}
