//! The CPU twin of `temporal.wgsl`: temporal upsampling with the same block order, start
//! offsets, reprojection, neighbourhood clamp, disocclusion test and blend, over history
//! stored in f32 as the GPU stores it. The CPU renderer keeps the history between frames.

use std::{collections::BTreeMap, time::Instant};

use rayon::prelude::*;
use stratus_graph::{FrameOutput, PassTiming};
use stratus_noise::NoiseSet;
use stratus_scene::{FrameUniforms, Scene};

use crate::{
    COUNTER_NAMES, QuadratureSettings, composite,
    frame::{FLAG_CHECKERBOARD, FLAG_SCENE_DEPTH, Frame, xyz},
    geometry::{RayKind, nearest_layer_interval, view_ray},
    march::{MarchSettings, PixelResult, has_surface, march},
    medium::{Medium, Model},
};

// WGSL: temporal.wgsl (constants).
const HISTORY_SAMPLES: f64 = 16.0;
const HISTORY_SAMPLES_MOVING: f64 = 2.0;
const DISOCCLUSION_DEPTH: f64 = 0.5;

/// What the CPU renderer keeps between temporal frames.
#[derive(Clone, Debug, Default)]
pub struct TemporalState {
    history: Option<History>,
    last: Option<FrameUniforms>,
}

#[derive(Clone, Debug)]
struct History {
    size: [u32; 2],
    block: u32,
    /// Radiance rgb and transmittance, f32 as the GPU's rgba32float.
    color: Vec<[f32; 4]>,
    /// Depth, sample count, and 1 where the host's geometry cut the march.
    meta: Vec<[f32; 3]>,
}

// WGSL: temporal.wgsl::bayer2
fn bayer2(v: u32) -> [u32; 2] {
    [(v ^ (v >> 1)) & 1, v & 1]
}

// WGSL: temporal.wgsl::block_offset
fn block_offset(f: u32, k: u32) -> [u32; 2] {
    match k {
        2 => bayer2(f % 4),
        4 => {
            let b = f % 16;
            let (fine, coarse) = (bayer2(b >> 2), bayer2(b & 3));
            [fine[0] + 2 * coarse[0], fine[1] + 2 * coarse[1]]
        }
        _ => [0, 0],
    }
}

// WGSL: temporal.wgsl::reproject
fn reproject(f: &Frame, pixel: [u32; 2], depth: f64) -> [f64; 2] {
    if f.camera_still() {
        return pixel.map(f64::from);
    }
    let view = view_ray(f, pixel);
    let dir = if depth > 0.0 {
        view * depth + (xyz(f.camera_position) - xyz(f.previous_position))
    } else {
        view
    };
    let z = dir.dot(xyz(f.previous_forward));
    if z <= 0.0 {
        return [-1e9; 2];
    }
    let tan_half = f.previous_tan_half_fov;
    let aspect = f.previous_aspect;
    let ndc = [
        dir.dot(xyz(f.previous_right)) / (z * tan_half * aspect),
        -dir.dot(xyz(f.previous_up)) / (z * tan_half),
    ];
    [
        (ndc[0] * 0.5 + 0.5) * f64::from(f.size[0]) - 0.5,
        (ndc[1] * 0.5 + 0.5) * f64::from(f.size[1]) - 0.5,
    ]
}

fn on_screen(f: &Frame, q: [f64; 2]) -> bool {
    q[0] >= -0.5
        && q[1] >= -0.5
        && q[0] <= f64::from(f.size[0]) - 0.5
        && q[1] <= f64::from(f.size[1]) - 0.5
}

impl History {
    // WGSL: temporal.wgsl::history_at
    fn color_at(&self, q: [f64; 2]) -> [f64; 4] {
        let [w, h] = self.size.map(|v| v as i64);
        let c = [
            q[0].clamp(0.0, (w - 1) as f64),
            q[1].clamp(0.0, (h - 1) as f64),
        ];
        let base = c.map(|v| v.floor() as i64);
        let wx = catmull_rom(c[0] - base[0] as f64);
        let wy = catmull_rom(c[1] - base[1] as f64);
        let mut sum = [0.0; 4];
        for (j, wyj) in wy.iter().enumerate() {
            let mut row = [0.0; 4];
            for (i, wxi) in wx.iter().enumerate() {
                let x = (base[0] + i as i64 - 1).clamp(0, w - 1);
                let y = (base[1] + j as i64 - 1).clamp(0, h - 1);
                let t = self.color[(y * w + x) as usize];
                for k in 0..4 {
                    row[k] += f64::from(t[k]) * wxi;
                }
            }
            for k in 0..4 {
                sum[k] += row[k] * wyj;
            }
        }
        [
            sum[0].max(0.0),
            sum[1].max(0.0),
            sum[2].max(0.0),
            sum[3].clamp(0.0, 1.0),
        ]
    }

    // WGSL: temporal.wgsl::history_nearest
    fn nearest(&self, q: [f64; 2]) -> [f64; 4] {
        let [w, h] = self.size.map(|v| v as i64);
        let x = (q[0].round_ties_even() as i64).clamp(0, w - 1);
        let y = (q[1].round_ties_even() as i64).clamp(0, h - 1);
        self.color[(y * w + x) as usize].map(f64::from)
    }

    // WGSL: temporal.wgsl::meta_at
    fn meta_at(&self, q: [f64; 2]) -> [f64; 3] {
        let [w, h] = self.size.map(|v| v as i64);
        // WGSL's round() rounds half to even.
        let x = (q[0].round_ties_even() as i64).clamp(0, w - 1);
        let y = (q[1].round_ties_even() as i64).clamp(0, h - 1);
        self.meta[(y * w + x) as usize].map(f64::from)
    }

    // WGSL: temporal.wgsl::footprint_cut
    /// Whether any texel of `color_at`'s 4 x 4 footprint at `q` was cut by the host's
    /// geometry.
    fn footprint_cut(&self, q: [f64; 2]) -> bool {
        let [w, h] = self.size.map(|v| v as i64);
        let base = [
            q[0].clamp(0.0, (w - 1) as f64).floor() as i64,
            q[1].clamp(0.0, (h - 1) as f64).floor() as i64,
        ];
        (-1..=2).any(|dy| {
            (-1..=2).any(|dx| {
                let x = (base[0] + dx).clamp(0, w - 1);
                let y = (base[1] + dy).clamp(0, h - 1);
                self.meta[(y * w + x) as usize][2] > 0.0
            })
        })
    }
}

// WGSL: temporal.wgsl::catmull_rom
fn catmull_rom(t: f64) -> [f64; 4] {
    [
        t * (-0.5 + t * (1.0 - 0.5 * t)),
        1.0 + t * t * (-2.5 + 1.5 * t),
        t * (0.5 + t * (2.0 - 1.5 * t)),
        t * t * (-0.5 + 0.5 * t),
    ]
}

fn f32x4(v: [f64; 4]) -> [f32; 4] {
    v.map(|x| x as f32)
}

/// One temporal frame of `scene` on the CPU with `settings`, updating `state`.
pub(crate) fn render(
    scene: &Scene,
    noise: &NoiseSet,
    settings: &QuadratureSettings,
    state: &mut TemporalState,
    depth: Option<&std::sync::Arc<stratus_graph::SceneDepth>>,
) -> FrameOutput {
    let mut u = scene.uniforms();
    let (w, h) = (u.size[0], u.size[1]);
    let k = u.block_side.max(1);
    let history = state
        .history
        .take()
        .filter(|hist| hist.size == [w, h] && hist.block == k);
    if let (Some(last), Some(_)) = (&state.last, &history) {
        u = u.with_previous_camera(last);
        u.history_valid = 1;
    }
    let model = Model::with_scene_depth(u, Medium::Clouds(noise), depth);
    let f = &model.f;
    let s: MarchSettings = settings.resolve(f);
    let valid_history = f.history_valid != 0;

    // The sparse march: one pixel per block.
    let t0 = Instant::now();
    let (bw, bh) = (w.div_ceil(k), h.div_ceil(k));
    let sparse: Vec<(PixelResult, bool)> = (0..bh)
        .into_par_iter()
        .flat_map_iter(|by| {
            let (model, s, history) = (&model, &s, &history);
            (0..bw).map(move |bx| {
                let f = &model.f;
                let o = block_offset(f.frame_index, k);
                let pixel = [bx * k + o[0], by * k + o[1]];
                let mut skip = pixel[0] >= w || pixel[1] >= h;
                if !skip
                    && f.flags & FLAG_CHECKERBOARD != 0
                    && valid_history
                    && !has_surface(model, pixel)
                {
                    let turn = f.frame_index / (k * k);
                    let q = reproject(f, pixel, 0.0);
                    if (bx + by + turn) & 1 == 0
                        && on_screen(f, q)
                        && history
                            .as_ref()
                            .is_some_and(|hist| hist.nearest(q)[3] >= 1.0)
                    {
                        skip = true;
                    }
                }
                if skip {
                    let clear = PixelResult {
                        transmittance: 1.0,
                        ..PixelResult::default()
                    };
                    (clear, false)
                } else {
                    (march(model, s, pixel), true)
                }
            })
        })
        .collect();
    let march_ms = t0.elapsed().as_secs_f64() * 1e3;
    // Stored as the GPU stores them (rgba32float, r32float).
    let sparse_color: Vec<[f32; 4]> = sparse
        .iter()
        .map(|(r, _)| f32x4([r.radiance.x, r.radiance.y, r.radiance.z, r.transmittance]))
        .collect();
    let sparse_depth: Vec<f32> = sparse.iter().map(|(r, _)| r.depth as f32).collect();

    // The resolve: every pixel.
    let t1 = Instant::now();
    let resolved: Vec<([f32; 4], [f32; 3], Option<PixelResult>)> = (0..h)
        .into_par_iter()
        .flat_map_iter(|y| {
            let (model, s, history, sparse_color, sparse_depth) =
                (&model, &s, &history, &sparse_color, &sparse_depth);
            (0..w).map(move |x| {
                let f = &model.f;
                let pixel = [x, y];
                let block = [x / k, y / k];
                let o = block_offset(f.frame_index, k);
                let marched = x == block[0] * k + o[0] && y == block[1] * k + o[1];
                let bi = (block[1] * bw + block[0]) as usize;
                let current = sparse_color[bi].map(f64::from);
                let current_depth = f64::from(sparse_depth[bi]);

                let mut depth = current_depth;
                if depth <= 0.0 {
                    let span = nearest_layer_interval(f, f.camera_position[1], view_ray(f, pixel));
                    if span.kind == RayKind::March {
                        depth = span.start + 0.5 * span.length;
                    }
                }
                let q = reproject(f, pixel, depth);
                // The host's geometry: its pixels are marched every frame, and history its
                // march cut is not resampled.
                let surface = has_surface(model, pixel);
                let moving = q[0] != f64::from(x) || q[1] != f64::from(y);
                let mut valid = valid_history && on_screen(f, q) && !surface;
                if valid
                    && f.flags & FLAG_SCENE_DEPTH != 0
                    && let Some(hist) = history
                {
                    valid = !if moving {
                        hist.footprint_cut(q)
                    } else {
                        hist.meta_at(q)[2] > 0.0
                    };
                }
                let mut hist_color = [0.0, 0.0, 0.0, 1.0];
                let mut past = [0.0; 3];
                if valid && let Some(hist) = history {
                    hist_color = hist.color_at(q);
                    past = hist.meta_at(q);
                    if moving && current_depth > 0.0 && past[0] > 0.0 {
                        let point = xyz(f.camera_position) + view_ray(f, pixel) * current_depth;
                        let expected = (point - xyz(f.previous_position)).length();
                        valid = (past[0] - expected).abs() <= DISOCCLUSION_DEPTH * expected;
                    }
                }
                if valid && moving {
                    let mut lo = [1e30f64; 4];
                    let mut hi = [-1e30f64; 4];
                    for dy in -1i64..=1 {
                        for dx in -1i64..=1 {
                            let bx = (i64::from(block[0]) + dx).clamp(0, i64::from(bw) - 1);
                            let by = (i64::from(block[1]) + dy).clamp(0, i64::from(bh) - 1);
                            let sc = sparse_color[(by * i64::from(bw) + bx) as usize];
                            for c in 0..4 {
                                lo[c] = lo[c].min(f64::from(sc[c]));
                                hi[c] = hi[c].max(f64::from(sc[c]));
                            }
                        }
                    }
                    for c in 0..4 {
                        hist_color[c] = hist_color[c].clamp(lo[c], hi[c]);
                    }
                }
                let mut remarch = None;
                let (result, samples, out_depth) = if marched {
                    if valid {
                        let cap = if moving {
                            HISTORY_SAMPLES_MOVING
                        } else {
                            HISTORY_SAMPLES
                        };
                        let n = (past[1] + 1.0).min(cap);
                        let a = 1.0 / n;
                        let blended =
                            [0, 1, 2, 3].map(|c| hist_color[c] + (current[c] - hist_color[c]) * a);
                        let d = if current_depth > 0.0 {
                            current_depth
                        } else {
                            past[0]
                        };
                        (blended, n, d)
                    } else {
                        (current, 1.0, current_depth)
                    }
                } else if valid {
                    (hist_color, if moving { 0.0 } else { past[1] }, past[0])
                } else {
                    let r = march(model, s, pixel);
                    let out = [r.radiance.x, r.radiance.y, r.radiance.z, r.transmittance];
                    let d = r.depth;
                    remarch = Some(r);
                    (out, 1.0, d)
                };
                let cut = if surface { 1.0 } else { 0.0 };
                (
                    f32x4(result),
                    [out_depth as f32, samples as f32, cut],
                    remarch,
                )
            })
        })
        .collect();
    let resolve_ms = t1.elapsed().as_secs_f64() * 1e3;

    // Work counters over every march of the frame, in COUNTER_NAMES order.
    let mut raw = [0u64; 9];
    let marches = sparse
        .iter()
        .filter(|(_, m)| *m)
        .map(|(r, _)| r)
        .chain(resolved.iter().filter_map(|(_, _, r)| r.as_ref()));
    for r in marches {
        raw[0] += 1;
        match r.kind {
            Some(RayKind::March) => raw[1] += 1,
            Some(RayKind::MissesLayer) => raw[7] += 1,
            Some(RayKind::HitsGround) => raw[8] += 1,
            None => {}
        }
        raw[2] += r.counters.view_steps;
        raw[3] += r.counters.density;
        raw[4] += r.counters.detail;
        raw[5] += r.counters.light;
        raw[6] += u64::from(r.exited_early);
    }
    let stats: BTreeMap<String, u64> = COUNTER_NAMES
        .iter()
        .zip(raw)
        .map(|(name, v)| (name.to_string(), v))
        .collect();

    let color: Vec<[f32; 4]> = resolved.iter().map(|(c, _, _)| *c).collect();
    let meta: Vec<[f32; 3]> = resolved.iter().map(|(_, m, _)| *m).collect();
    let radiance: Vec<f32> = color.iter().flatten().copied().collect();
    let depth: Vec<f32> = meta.iter().map(|m| m[0]).collect();

    let t2 = Instant::now();
    let image = composite::composite_image(
        &model.f,
        model.sky(),
        w,
        h,
        &radiance,
        &depth,
        model.surface.as_deref(),
        crate::precipitation::Rain::of(&model).as_ref(),
    );
    let composite_ms = t2.elapsed().as_secs_f64() * 1e3;

    state.history = Some(History {
        size: [w, h],
        block: k,
        color,
        meta,
    });
    state.last = Some(u);
    let timing = |pass: &str, ms: f64| PassTiming {
        pass: pass.to_string(),
        ms,
        source: "cpu-wall",
    };
    // The sky's tables (under the physical sky) come first, as in the frame graph.
    let mut timings = crate::sky::in_graph_order(
        model.sky(),
        [timing("march", march_ms), timing("resolve", resolve_ms)],
        timing("composite", composite_ms),
    );
    let mut image = crate::post::stylise(&model.f, w, h, image, &mut timings);
    crate::particles::particles_pass(
        &model.f,
        crate::precipitation::Rain::of(&model).as_ref(),
        &mut image,
        &mut timings,
    );
    FrameOutput {
        width: w,
        height: h,
        radiance,
        depth,
        image,
        stats: Some(stats),
        timings,
        device: format!("cpu ({} threads)", rayon::current_num_threads()),
        ..Default::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The 4x4 and 2x2 ordered-dither (Bayer) matrices, written out: rank at (x, y).
    #[test]
    fn block_offsets_follow_the_bayer_matrices() {
        let m4 = [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];
        for b in 0..16 {
            let [x, y] = block_offset(b, 4);
            assert_eq!(m4[y as usize][x as usize], b, "rank {b}");
        }
        let m2 = [[0, 2], [3, 1]];
        for b in 0..4 {
            let [x, y] = block_offset(b, 2);
            assert_eq!(m2[y as usize][x as usize], b, "rank {b}");
        }
    }
}
