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
