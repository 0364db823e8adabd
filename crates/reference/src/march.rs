//! The CPU twin of `march.wgsl`: the view march (thesis alg. 5.1) of one pixel, with the
//! analytic or Riemann step integral, jitter, early exit and the work counters.

use crate::density::{Counters, Layer, cloud_layer, layer_count};
use crate::frame::{
    FLAG_SCENE_DEPTH, Frame, INTEGRATION_RIEMANN, MAX_VIEW_STEPS, hash_unit, van_der_corput, xyz,
};
use crate::geometry::{Interval, RayKind, altitude_of, cloud_interval, layer_interval, view_ray};
use crate::lighting::{LightMarch, forward_lobe, scattered_light};
use crate::math::V3;
use crate::medium::Model;
use stratus_graph::SceneDepth;
use stratus_scene::MAX_CLOSE_STEPS;

/// The discretisation of one quadrature render, resolved from the scene and the settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct MarchSettings {
    /// `Some(n)`: exactly `n` view steps; `None`: as the WGSL (`frame.view_steps`, or the step
    /// length `frame.step_length` when it is > 0).
    pub view_steps: Option<u32>,
    /// The light march.
    pub light: LightMarch,
    /// Jittered start offset (`FLAG_JITTER`).
    pub jitter: bool,
    /// Early-exit transmittance (`frame.early_exit_transmittance`; 0 = never).
    pub early_exit: f64,
    /// `INTEGRATION_ANALYTIC` or `INTEGRATION_RIEMANN` (`frame.integration`).
    pub integration: u32,
    /// Dynamic step length (`FLAG_DYNAMIC_STEP`).
    pub dynamic_step: bool,
    /// Empty-space skipping (`FLAG_EMPTY_SKIP`).
    pub empty_skip: bool,
}

/// What the march of one pixel produced.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct PixelResult {
    pub radiance: V3,
    pub transmittance: f64,
    pub depth: f64,
    pub counters: Counters,
    /// Which `STAT_EXIT_*` / `STAT_MARCHED` counter the pixel adds to.
    pub kind: Option<RayKind>,
    pub exited_early: bool,
}

// WGSL: march.wgsl::step_integral
/// Scattering integrated over one step of length `dt` with extinction `sigma_t`, for a source
/// constant over the step.
pub(crate) fn step_integral(integration: u32, source: V3, sigma_t: f64, dt: f64) -> V3 {
    if integration == INTEGRATION_RIEMANN {
        return source * dt;
    }
    // Must agree: the same series below x = 1e-3 (in f64 the exact form would do, but the
    // switch point is kept so that the two compute the same function).
    let x = sigma_t * dt;
    let f = if x < 1e-3 {
        1.0 - 0.5 * x
    } else {
        (1.0 - (-x).exp()) / x
    };
    source * (dt * f)
}

/// The view ray's interval in the medium: in layer `l` (`layer_interval`), or with `None` in
/// the shell of every layer (`cloud_interval`), clipped to the medium's support.
pub(crate) fn medium_interval(m: &Model, cam_alt: f64, view: V3, l: Option<&Layer>) -> Interval {
    let span = match l {
        Some(l) => layer_interval(&m.f, cam_alt, view, l),
        None => cloud_interval(&m.f, cam_alt, view),
    };
    if span.kind != RayKind::March {
        return span;
    }
    match m.clip(
        V3::new(0.0, cam_alt, 0.0),
        view,
        span.start,
        span.start + span.length,
    ) {
        Some((t0, t1)) => Interval {
            start: t0,
            length: t1 - t0,
            kind: RayKind::March,
        },
        None => Interval {
            start: 0.0,
            length: 0.0,
            kind: RayKind::MissesLayer,
        },
    }
}

// WGSL: march.wgsl::start_offset
/// The view march's start offset in steps: without temporal upsampling 0.5 or the PCG hash of
/// the pixel and frame; with it, the van der Corput sequence over the pixel's marches,
/// shifted by a per-pixel hash with jitter.
pub(crate) fn start_offset(f: &Frame, pixel: [u32; 2], jitter: bool) -> f64 {
    let k = f.block_side;
    if k <= 1 {
        // Must agree: the same PCG hash of the pixel and the frame index (`frame.frame_index`).
        return if jitter {
            hash_unit(pixel, f.frame_index)
        } else {
            0.5
        };
    }
    let base = if jitter { hash_unit(pixel, 0) } else { 0.5 };
    // Differs in the last bit: the f32 sum may round where the f64 one is exact.
    (base + van_der_corput(f.frame_index / (k * k))).fract()
}

// WGSL: march.wgsl::has_surface
/// Whether the host's geometry covers `pixel` (its depth is not the far plane's).
pub(crate) fn has_surface(m: &Model, pixel: [u32; 2]) -> bool {
    surface_at(&m.f, m.surface.as_deref(), pixel)
}

/// [`has_surface`] of frame `f` with scene depth `depth`.
pub(crate) fn surface_at(f: &Frame, depth: Option<&SceneDepth>, pixel: [u32; 2]) -> bool {
    if f.flags & FLAG_SCENE_DEPTH == 0 {
        return false;
    }
    depth.is_some_and(|d| f64::from(d.depth(pixel[0], pixel[1])) != f.scene_depth_clear)
}

// WGSL: march.wgsl::scene_surface
/// The distance along the view ray `view` of `pixel` to the host's geometry (m), infinite
/// where there is none: the depth d lies at B / (d + A) along the view axis.
pub(crate) fn scene_surface(m: &Model, pixel: [u32; 2], view: V3) -> f64 {
    let Some(d) = m.surface.as_ref().filter(|_| has_surface(m, pixel)) else {
        return f64::INFINITY;
    };
    let f = &m.f;
    let axis = f.scene_depth_b / (f64::from(d.depth(pixel[0], pixel[1])) + f.scene_depth_a);
    axis / view.dot(xyz(f.camera_forward))
}

// WGSL: march.wgsl::clip_to_surface
/// `s` cut at the surface at distance `surface`.
fn clip_to_surface(s: Interval, surface: f64) -> Interval {
    if s.kind != RayKind::March || s.start + s.length <= surface {
        return s;
    }
    if s.start >= surface {
        return Interval {
            start: 0.0,
            length: 0.0,
            kind: RayKind::MissesLayer,
        };
    }
    Interval {
        start: s.start,
        length: surface - s.start,
        kind: RayKind::March,
    }
}

// WGSL: march.wgsl::march_pixel
/// The march of one pixel, cut at the host's geometry.
pub(crate) fn march(m: &Model, s: &MarchSettings, pixel: [u32; 2]) -> PixelResult {
    let view = view_ray(&m.f, pixel);
    let surface = scene_surface(m, pixel, view);
    march_ray_to(m, s, view, start_offset(&m.f, pixel, s.jitter), surface)
}

/// What a view march has gathered so far, across layers (the WGSL's `MarchState`).
#[derive(Clone, Copy, Debug)]
struct MarchState {
    radiance: V3,
    transmittance: f64,
    depth_sum: f64,
    /// The octaves' part of `radiance` (the forward lobe's).
    octaves: V3,
}

/// The march of one view ray from the camera with start offset `jitter` (in steps).
// Must agree: each layer on its own interval, nearest first by (start, index); the pixel's
// kind is "marched" if any layer was, else "hits ground" if any layer's ray did.
pub(crate) fn march_ray(m: &Model, s: &MarchSettings, view: V3, jitter: f64) -> PixelResult {
    march_ray_to(m, s, view, jitter, f64::INFINITY)
}

/// [`march_ray`] ending at distance `surface` (the host's geometry).
fn march_ray_to(m: &Model, s: &MarchSettings, view: V3, jitter: f64, surface: f64) -> PixelResult {
    let f = &m.f;
    let cam_alt = f.camera_position[1];
    let mut counters = Counters::default();
    let mut state = MarchState {
        radiance: V3::ZERO,
        transmittance: 1.0,
        depth_sum: 0.0,
        octaves: V3::ZERO,
    };
    let mut exited_early = false;
    let spans: Vec<(u32, Interval)> = (0..layer_count(f))
        .map(|i| {
            let l = cloud_layer(f, i);
            let span = medium_interval(m, cam_alt, view, Some(&l));
            (i, clip_to_surface(span, surface))
        })
        .collect();
    let ground = spans.iter().any(|(_, s)| s.kind == RayKind::HitsGround);
    let mut order: Vec<&(u32, Interval)> = spans
        .iter()
        .filter(|(_, s)| s.kind == RayKind::March)
        .collect();
    order.sort_by(|a, b| a.1.start.total_cmp(&b.1.start).then(a.0.cmp(&b.0)));
    let marched = !order.is_empty();
    for &&(i, span) in &order {
        if march_layer(
            m,
            s,
            view,
            span,
            &cloud_layer(f, i),
            jitter,
            &mut state,
            &mut counters,
        ) {
            exited_early = true;
            break;
        }
    }
    let kind = if marched {
        RayKind::March
    } else if ground {
        RayKind::HitsGround
    } else {
        RayKind::MissesLayer
    };
    let depth = if state.transmittance < 1.0 {
        state.depth_sum / (1.0 - state.transmittance)
    } else {
        0.0
    };
    // The octaves' forward lobe, weighted by the transmittance the march reached.
    let lobe = forward_lobe(f, view.dot(f.sun()), state.transmittance);
    PixelResult {
        radiance: state.radiance + state.octaves * (lobe - 1.0),
        // An early exit ends the pixel: nothing behind it shows through (as the WGSL).
        transmittance: if exited_early {
            0.0
        } else {
            state.transmittance
        },
        depth,
        counters,
        kind: Some(kind),
        exited_early,
    }
}

// WGSL: march.wgsl::march_layer
/// The march of the view ray's interval `span` in layer `l`, added to `state`; true when the
/// transmittance fell below the early-exit threshold. With close-range detail on, the part
/// within its range of the camera first, in steps of `close_step` (never coarser than the
/// rest's, at most `MAX_CLOSE_STEPS`), then the rest at the step it would have had.
#[allow(clippy::too_many_arguments)]
fn march_layer(
    m: &Model,
    s: &MarchSettings,
    view: V3,
    span: Interval,
    l: &Layer,
    jitter: f64,
    state: &mut MarchState,
    counters: &mut Counters,
) -> bool {
    let f = &m.f;
    // Must agree: in step-length mode ceil(length / step), clamped to [1, MAX_VIEW_STEPS].
    let steps = match s.view_steps {
        Some(n) => n.max(1),
        None if f.step_length > 0.0 => {
            ((span.length / f.step_length).ceil() as u32).clamp(1, MAX_VIEW_STEPS)
        }
        None => f.view_steps,
    };
    let near = f.close_detail_range - span.start;
    // Must agree: a NaN start marches the whole interval, as the WGSL's !(near > 0).
    if f.close_detail <= 0.0 || near.is_nan() || near <= 0.0 {
        let whole = (span.start, span.length, steps);
        return march_segment(m, s, view, whole, l, jitter, state, counters);
    }
    let dt = span.length / f64::from(steps);
    let near_length = near.min(span.length);
    // The bound caps the close steps alone: the ray's own finer steps stay (WGSL: march_layer).
    let close = (near_length / f.close_step)
        .ceil()
        .min(f64::from(MAX_CLOSE_STEPS));
    let near_steps = (close.max((near_length / dt).ceil()) as u32).max(1);
    let first = (span.start, near_length, near_steps);
    if march_segment(m, s, view, first, l, jitter, state, counters) {
        return true;
    }
    let rest = span.length - near_length;
    if rest.is_nan() || rest <= 0.0 {
        return false;
    }
    let far_steps = ((rest / dt).ceil() as u32).clamp(1, steps);
    let second = (span.start + near_length, rest, far_steps);
    march_segment(m, s, view, second, l, jitter, state, counters)
}

// WGSL: march.wgsl::march_segment
/// The march of `steps` equal steps of the view ray from `start` over `extent` (m) in layer
/// `l`, added to `state`; true when the transmittance fell below the early-exit threshold.
#[allow(clippy::too_many_arguments)]
fn march_segment(
    m: &Model,
    s: &MarchSettings,
    view: V3,
    (start, extent, steps): (f64, f64, u32),
    l: &Layer,
    jitter: f64,
    state: &mut MarchState,
    counters: &mut Counters,
) -> bool {
    let f = &m.f;
    let cam_alt = f.camera_position[1];
    let cam_xz = [f.camera_position[0], f.camera_position[2]];
    let dt = extent / f64::from(steps);
    let sigma_e = f.scattering + f.absorption;
    // Must agree: samples on one grid t_i = start + (i + jitter) dt; the cheap-march
    // techniques choose which i to visit (stride 2 after 8 empty samples, back one on
    // entering cloud; jumps over empty occupancy cells).
    let mut i = 0u32;
    let mut stride = 1u32;
    let mut empty = 0u32;
    while i < steps {
        // Must agree: one view step counted per loop iteration, also for empty samples.
        counters.view_steps += 1;
        let t = start + (f64::from(i) + jitter) * dt;
        let rel = view * t + V3::new(0.0, cam_alt, 0.0);
        let p = V3::new(rel.x + cam_xz[0], rel.y, rel.z + cam_xz[1]);
        if s.empty_skip {
            let exit = m.empty_cell_exit(p, view);
            if exit > 0.0 {
                let next = ((t + exit - start) / dt - jitter)
                    .ceil()
                    .clamp(0.0, f64::from(steps)) as u32;
                i = (i + 1).max(next);
                continue;
            }
        }
        let alt = altitude_of(f, rel);
        let density = m.layer_density(p, alt, l, counters);
        if density <= 0.0 {
            empty += 1;
            if s.dynamic_step && empty >= 8 {
                stride = 2;
            }
            i += stride;
            continue;
        }
        if stride > 1 {
            i -= stride - 1;
            stride = 1;
            empty = 0;
            continue;
        }
        empty = 0;
        let sigma_t = sigma_e * density;
        let (source, octaves) =
            scattered_light(m, &s.light, rel, p, alt, density, view, l, counters);
        state.radiance += step_integral(s.integration, source, sigma_t, dt) * state.transmittance;
        state.octaves += step_integral(s.integration, octaves, sigma_t, dt) * state.transmittance;
        let step_t = (-sigma_t * dt).exp();
        state.depth_sum += t * state.transmittance * (1.0 - step_t);
        state.transmittance *= step_t;
        // Must agree: the early exit is tested after the step that crossed the threshold
        // (STAT_EXIT_TRANSMITTANCE).
        if state.transmittance < s.early_exit {
            return true;
        }
        i += 1;
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::QuadratureSettings;
    use crate::medium::Medium;

    /// The view steps of one horizontal ray from `inside-layer`'s camera (in the layer, its
    /// 30 km cut-off 96 steps of 312.5 m), with close-range detail `close` and the step
    /// `close_step_m` within its range: every sample counted (no early exit).
    fn steps(close: f64, close_step_m: f64) -> u64 {
        steps_of(close, close_step_m, None)
    }

    /// As [`steps`], with `view_steps` across the interval where given (as the converged
    /// quadrature sets them).
    fn steps_of(close: f64, close_step_m: f64, view_steps: Option<u32>) -> u64 {
        let noise = stratus_noise::NoiseSet::generate(&Default::default());
        let mut scene = stratus_scene::Scene::preset("inside-layer").unwrap();
        scene.quality.early_exit_transmittance = 0.0;
        scene.clouds.close_detail = close;
        scene.quality.close_step_m = close_step_m;
        let m = Model::new(&scene, Medium::Clouds(&noise));
        let mut s = QuadratureSettings::realtime().resolve(&m.f);
        if view_steps.is_some() {
            s.view_steps = view_steps;
        }
        march_ray(&m, &s, V3::new(0.0, 0.0, -1.0), 0.5)
            .counters
            .view_steps
    }

    /// Close-range detail marches its range (1000 m) in its own steps before the rest of the
    /// interval at the step it had: 50 steps of 20 m, then 93 of at most 312.5 m for the 29 km
    /// left, where the march without it takes 96; a finer step is held to MAX_CLOSE_STEPS.
    #[test]
    fn close_detail_marches_its_range_in_bounded_fine_steps() {
        assert_eq!(steps(0.0, 20.0), 96);
        assert_eq!(steps(1.0, 20.0), 50 + 93);
        assert_eq!(steps(1.0, 1.0), u64::from(MAX_CLOSE_STEPS) + 93);
    }

    /// The bound holds the close steps alone, never the ray's own: with 16384 steps of 1.83 m
    /// across the 30 km (finer than the 20 m close step) the range keeps its 547 of them, not
    /// MAX_CLOSE_STEPS, and the 29 km beyond take the 15838 they had.
    #[test]
    fn close_detail_never_coarsens_finer_steps() {
        assert_eq!(steps_of(0.0, 20.0, Some(16384)), 16384);
        assert_eq!(steps_of(1.0, 20.0, Some(16384)), 547 + 15838);
    }
}
