//! The CPU twin of `post.wgsl`: the stylised Kuwahara filter on the display image.

use rayon::prelude::*;

use std::time::Instant;

use stratus_graph::PassTiming;

use crate::frame::Frame;

/// The display image after the frame's post passes (the Kuwahara filter when
/// `kuwahara_radius` > 0), each pass's time appended to `timings` under its graph name.
pub(crate) fn stylise(
    f: &Frame,
    width: u32,
    height: u32,
    image: Vec<u8>,
    timings: &mut Vec<PassTiming>,
) -> Vec<u8> {
    if f.kuwahara_radius <= 0.0 {
        return image;
    }
    let t = Instant::now();
    let out = kuwahara(f, width, height, &image);
    timings.push(PassTiming {
        pass: "kuwahara".to_string(),
        ms: t.elapsed().as_secs_f64() * 1e3,
        source: "cpu-wall",
    });
    out
}

// WGSL: post.wgsl::KUWAHARA_TAPS
/// Taps from the centre to the window's edge along each axis.
const KUWAHARA_TAPS: i32 = 4;
// WGSL: post.wgsl::KUWAHARA_FLAT
/// The summed variance (levels^2) at which a window's weight has halved.
const KUWAHARA_FLAT: f64 = 12.0;

// WGSL: post.wgsl::kuwahara
/// The Kuwahara filter of an RGBA8 `width` x `height` image (see `post.wgsl`): each pixel takes
/// the means of its four corner windows, weighted toward those whose 8-bit levels vary least.
/// The tap offsets are rounded in f32 as the shader does (`kuwahara_radius` times the height,
/// one f32 product), and the sums are integers, so only the weighting's rounding (f64 here,
/// f32 there) can differ from the GPU's, by a level where a mean lies half-way.
pub(crate) fn kuwahara(f: &Frame, width: u32, height: u32, image: &[u8]) -> Vec<u8> {
    kuwahara_with(f.kuwahara_radius as f32, width, height, image)
}

/// [`kuwahara`] with the radius (a fraction of the height) given.
fn kuwahara_with(radius: f32, width: u32, height: u32, image: &[u8]) -> Vec<u8> {
    let radius_px = radius * height as f32;
    let offset = |i: i32| (i as f32 * radius_px * 0.25 + 0.5).floor() as i32;
    let (w, h) = (width as i32, height as i32);
    let n = ((KUWAHARA_TAPS + 1) * (KUWAHARA_TAPS + 1)) as u32;
    (0..h)
        .into_par_iter()
        .flat_map_iter(|y| {
            (0..w).flat_map(move |x| {
                let mut sum = [[0u32; 3]; 4];
                let mut squares = [[0u32; 3]; 4];
                for j in -KUWAHARA_TAPS..=KUWAHARA_TAPS {
                    let ty = (y + offset(j)).clamp(0, h - 1);
                    for i in -KUWAHARA_TAPS..=KUWAHARA_TAPS {
                        let tx = (x + offset(i)).clamp(0, w - 1);
                        let at = 4 * (ty * w + tx) as usize;
                        for q in 0..4 {
                            let (right, lower) = (q & 1 != 0, q & 2 != 0);
                            let in_x = if right { i >= 0 } else { i <= 0 };
                            let in_y = if lower { j >= 0 } else { j <= 0 };
                            if in_x && in_y {
                                for c in 0..3 {
                                    let v = u32::from(image[at + c]);
                                    sum[q][c] += v;
                                    squares[q][c] += v * v;
                                }
                            }
                        }
                    }
                }
                let nf = f64::from(n);
                let mut colour = [0.0f64; 3];
                let mut weights = 0.0;
                for q in 0..4 {
                    let total: u32 = (0..3)
                        .map(|c| n * squares[q][c] - sum[q][c] * sum[q][c])
                        .sum();
                    let v = f64::from(total) / (nf * nf) / KUWAHARA_FLAT;
                    let w = 1.0 / (1.0 + v.powi(4));
                    for c in 0..3 {
                        colour[c] += f64::from(sum[q][c]) * (w / nf);
                    }
                    weights += w;
                }
                // The store's rgba8unorm conversion: to the nearest level.
                let level = |c: usize| (colour[c] / weights).round().clamp(0.0, 255.0) as u8;
                [level(0), level(1), level(2), 255]
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A step between two noisy flat halves: the filter takes the noise out of the halves and
    /// keeps the step (the windows beside it lie on one side).
    #[test]
    fn kuwahara_flattens_noise_and_keeps_a_step() {
        let (w, h) = (64u32, 64u32);
        let mut image = Vec::new();
        let mut state = 1u32;
        for _y in 0..h {
            for x in 0..w {
                state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
                let noise = (state >> 24) as i32 % 21 - 10;
                let level = if x < w / 2 { 60 } else { 190 } + noise;
                image.extend_from_slice(&[level as u8, level as u8, level as u8, 255]);
            }
        }
        let out = kuwahara_with(4.0 / 64.0, w, h, &image);
        let at = |img: &[u8], x: u32, y: u32| f64::from(img[(4 * (y * w + x)) as usize]);
        let spread = |img: &[u8]| {
            let v: Vec<f64> = (8..24)
                .flat_map(|y| (8..24).map(move |x| (x, y)))
                .map(|(x, y)| at(img, x, y))
                .collect();
            let m = v.iter().sum::<f64>() / v.len() as f64;
            v.iter().map(|a| (a - m) * (a - m)).sum::<f64>() / v.len() as f64
        };
        let (before, after) = (spread(&image), spread(&out));
        assert!(after < 0.3 * before, "flat variance {before} -> {after}");
        for y in 4..60 {
            let step = at(&out, 32, y) - at(&out, 31, y);
            assert!(step > 100.0, "row {y}: the step is {step} levels");
        }
    }
}
