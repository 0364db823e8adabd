// The view march (thesis alg. 5.1): one invocation per pixel marches its ray through the
// cloud layer and writes linear in-scattered radiance and transmittance.

@group(0) @binding(6) var cloud_out: texture_storage_2d<rgba32float, write>; // radiance rgb, transmittance
@group(0) @binding(7) var depth_out: texture_storage_2d<r32float, write>;    // transmittance-weighted depth (m), 0 where no cloud
@group(0) @binding(42) var scene_depth_in: texture_2d<f32>;                  // the host's clip-space depth (FLAG_SCENE_DEPTH)

// The distance along a view ray where nothing stops it.
const NO_SURFACE: f32 = 3.0e38;

// Whether the host's geometry covers `pixel` (its depth is not the far plane's).
fn has_surface(pixel: vec2<u32>) -> bool {
    if (frame.flags & FLAG_SCENE_DEPTH) == 0u {
        return false;
    }
    return textureLoad(scene_depth_in, pixel, 0).r != frame.scene_depth_clear;
}

// The distance along the view ray `view` of `pixel` to the host's geometry (m), NO_SURFACE
// where there is none. The depth d lies at B / (d + A) along the view axis (the projection's
// terms); the ray is longer by 1 / cos of its angle to the axis.
fn scene_surface(pixel: vec2<u32>, view: vec3<f32>) -> f32 {
    if !has_surface(pixel) {
        return NO_SURFACE;
    }
    let d = textureLoad(scene_depth_in, pixel, 0).r;
    let axis = frame.scene_depth_b / (d + frame.scene_depth_a);
    return axis / dot(view, frame.camera_forward);
}

// `s` cut at the surface at distance `surface`: shortened where the surface is inside it,
// missed where the surface is in front of it.
fn clip_to_surface(s: Interval, surface: f32) -> Interval {
    if s.kind != RAY_MARCH || s.start + s.length <= surface {
        return s;
    }
    if s.start >= surface {
        return Interval(0.0, 0.0, RAY_MISSES_LAYER);
    }
    return Interval(s.start, surface - s.start, RAY_MARCH);
}

// Work counters (the statistics variant). Indices are named by the `stats` resource in the
// frame graph (wgsl/graph.toml), checked against these values at build time.
const STAT_PIXELS: u32 = 0u;           // pixels processed
const STAT_MARCHED: u32 = 1u;          // pixels whose ray marched the layer
const STAT_VIEW_STEPS: u32 = 2u;       // view-ray steps taken
const STAT_DENSITY: u32 = 3u;          // density evaluations (view and light)
const STAT_DETAIL: u32 = 4u;           // detail-noise evaluations
const STAT_LIGHT: u32 = 5u;            // light-march samples
const STAT_EXIT_TRANSMITTANCE: u32 = 6u; // marches ended early: transmittance below threshold
const STAT_EXIT_MISSED: u32 = 7u;      // rays that miss the layer (nothing to march)
const STAT_EXIT_GROUND: u32 = 8u;      // rays that hit the ground before the layer
const STAT_COUNT: u32 = 9u;

struct Stats {
    counters: array<atomic<u32>, STAT_COUNT>,
}

@group(0) @binding(8) var<storage, read_write> stats: Stats;

fn count(index: u32, value: u32) {
    if STATS && value != 0u {
        atomicAdd(&stats.counters[index], value);
    }
}

// Scattering integrated over one step of length `dt` with extinction `sigma_t`, for a source
// `source` (radiance per unit length) that is constant over the step.
fn step_integral(source: vec3<f32>, sigma_t: f32, dt: f32) -> vec3<f32> {
    if frame.integration == INTEGRATION_RIEMANN {
        // Naive Riemann sum: overshoots when sigma_t * dt is large (kept to show where it fails).
        return source * dt;
    }
    // Hillaire's energy-conserving form (thesis alg. 5.4): (S - S Tr) / sigma_t, written as
    // S dt (1 - e^-x) / x with x = sigma_t dt and a series near 0, so it never divides by 0.
    let x = sigma_t * dt;
    let f = select((1.0 - exp(-x)) / x, 1.0 - 0.5 * x, x < 1e-3);
    return source * (dt * f);
}

// What the march of one view ray produced.
struct MarchResult {
    radiance: vec3<f32>,   // in-scattered radiance
    transmittance: f32,
    depth: f32,            // transmittance-weighted depth (m), 0 where no cloud
}

// The view march's start offset (in steps, [0, 1)) for `pixel`. Without temporal upsampling:
// 0.5, or the per-pixel, per-frame hash with jitter. With it, the thesis's van der Corput
// sequence over the pixel's successive marches (one per `block^2` frames), shifted by a fixed
// per-pixel hash with jitter: each pixel's marches stratify its step interval.
fn start_offset(pixel: vec2<u32>) -> f32 {
    let jitter = (frame.flags & FLAG_JITTER) != 0u;
    let k = frame.block_side;
    if k <= 1u {
        return select(0.5, hash_unit(pixel, frame.frame_index), jitter);
    }
    let base = select(0.5, hash_unit(pixel, 0u), jitter);
    return fract(base + van_der_corput(frame.frame_index / (k * k)));
}

// What a view march has gathered so far (across layers).
struct MarchState {
    radiance: vec3<f32>,
    transmittance: f32,
    depth_sum: f32,  // sum of t * (fraction of the light removed at t)
    octaves: vec3<f32>,  // the octaves' part of `radiance` (forward_lobe)
}

// The view march (thesis alg. 5.1) of the ray through `pixel`, counting its work. Each cloud
// layer is marched on its own interval with the full step count, nearest first: the ray's
// intervals in different layers never overlap because the layers' altitude ranges do not.
// The host's geometry ends the ray: each interval is cut at its surface (a layer behind it is
// not marched), so geometry inside a cloud gets the transmittance and light up to it.
fn march_pixel(pixel: vec2<u32>) -> MarchResult {
    let view = view_ray(pixel);
    let surface = scene_surface(pixel, view);
    let cam_alt = frame.camera_position.y;
    var counters = Counters(0u, 0u, 0u, 0u);
    count(STAT_PIXELS, 1u);

    var state = MarchState(vec3<f32>(0.0), 1.0, 0.0, vec3<f32>(0.0));
    let jitter = start_offset(pixel);
    let n = layer_count();
    var marched = false;
    var ground = false;
    var last_start = -1.0;
    var last_index = NO_LAYER;
    var exited = false;
    for (var k = 0u; k < n; k++) {
        // The nearest layer not marched yet: the smallest (start, index) after the last one.
        var next = NO_LAYER;
        var span = Interval(0.0, 0.0, RAY_MISSES_LAYER);
        for (var i = 0u; i < n; i++) {
            let s = clip_to_surface(layer_interval(cam_alt, view, cloud_layer(i)), surface);
            ground = ground || s.kind == RAY_HITS_GROUND;
            let after = s.start > last_start || (s.start == last_start && i > last_index);
            if s.kind == RAY_MARCH && after && (next == NO_LAYER || s.start < span.start) {
                next = i;
                span = s;
            }
        }
        if next == NO_LAYER {
            break;
        }
        marched = true;
        last_start = span.start;
        last_index = next;
        if march_layer(view, span, cloud_layer(next), jitter, &state, &counters) {
            count(STAT_EXIT_TRANSMITTANCE, 1u);
            exited = true;
            break;
        }
    }
    if marched {
        count(STAT_MARCHED, 1u);
    } else if ground {
        count(STAT_EXIT_GROUND, 1u);
    } else {
        count(STAT_EXIT_MISSED, 1u);
    }

    count(STAT_VIEW_STEPS, counters.view_steps);
    count(STAT_DENSITY, counters.density);
    count(STAT_DETAIL, counters.detail);
    count(STAT_LIGHT, counters.light);
    var depth = 0.0;
    if state.transmittance < 1.0 {
        depth = state.depth_sum / (1.0 - state.transmittance);
    }
    // A march that ends early ends the pixel: nothing behind the cloud may show through the
    // transmittance left (up to the threshold, 1%), least of all the sun's or the moon's disc,
    // whose radiance is 10^5 times the sky's.
    let transmittance = select(state.transmittance, 0.0, exited);
    // The octaves' forward lobe, weighted by the transmittance the march reached.
    let lobe = forward_lobe(dot(view, frame.sun_direction), state.transmittance);
    let radiance = state.radiance + state.octaves * (lobe - 1.0);
    return MarchResult(radiance, transmittance, depth);
}

// The most view steps within close-range detail's range (scene MAX_CLOSE_STEPS, which
// validation holds `clouds.close_detail_range_m / quality.close_step_m` to).
const MAX_CLOSE_STEPS: u32 = 256u;

// The march of the view ray's interval `span` in layer `l`, added to `state`. True when the
// transmittance fell below the early-exit threshold (the pixel is done).
// With close-range detail on (density.wgsl close_detail_weight) the part of the interval
// within `frame.close_detail_range` of the camera is marched first in steps of
// `frame.close_step` (at most MAX_CLOSE_STEPS of them, never coarser than the steps beyond), so
// that its wisps metres across are sampled and not aliased into noise by steps of tens or
// hundreds of metres; the rest of the interval keeps the step it would have had.
fn march_layer(view: vec3<f32>, span: Interval, l: Layer, jitter: f32,
               state: ptr<function, MarchState>, counters: ptr<function, Counters>) -> bool {
    var steps = frame.view_steps;
    if frame.step_length > 0.0 {
        steps = clamp(u32(ceil(span.length / frame.step_length)), 1u, MAX_VIEW_STEPS);
    }
    let near = frame.close_detail_range - span.start;
    if frame.close_detail <= 0.0 || !(near > 0.0) {
        return march_segment(view, span.start, span.length, steps, l, jitter, state, counters);
    }
    let dt = span.length / f32(steps);
    let near_length = min(near, span.length);
    // The bound caps the close steps alone: where the ray's own steps are finer still (a short
    // `quality.step_length_m`, a converged reference) they stay, at most `steps` of them.
    let close = min(ceil(near_length / frame.close_step), f32(MAX_CLOSE_STEPS));
    let near_steps = max(u32(max(close, ceil(near_length / dt))), 1u);
    if march_segment(view, span.start, near_length, near_steps, l, jitter, state, counters) {
        return true;
    }
    let rest = span.length - near_length;
    if !(rest > 0.0) {
        return false;
    }
    let far_steps = clamp(u32(ceil(rest / dt)), 1u, steps);
    return march_segment(view, span.start + near_length, rest, far_steps, l, jitter, state,
                         counters);
}

// The march of `steps` equal steps of the view ray from `start` over `extent` (m) in layer
// `l`, added to `state`; true when the transmittance fell below the early-exit threshold.
fn march_segment(view: vec3<f32>, start: f32, extent: f32, steps: u32, l: Layer, jitter: f32,
                 state: ptr<function, MarchState>, counters: ptr<function, Counters>) -> bool {
    let cam_alt = frame.camera_position.y;
    let cam_xz = frame.camera_position.xz;
    let dt = extent / f32(steps);
    let sigma_e = frame.scattering + frame.absorption;
    let dynamic_step = (frame.flags & FLAG_DYNAMIC_STEP) != 0u;
    let empty_skip = (frame.flags & FLAG_EMPTY_SKIP) != 0u;
    // Samples lie on one grid, t_i = start + (i + jitter) dt; the cheap-march techniques
    // only choose which i to visit, so they never move a sample.
    var i = 0u;
    var stride = 1u;   // 2 after 8 empty samples with the dynamic step
    var empty = 0u;    // empty samples in a row
    loop {
        if i >= steps {
            break;
        }
        (*counters).view_steps += 1u;
        let t = start + (f32(i) + jitter) * dt;
        let rel = view * t + vec3<f32>(0.0, cam_alt, 0.0);
        let p = vec3<f32>(rel.x + cam_xz.x, rel.y, rel.z + cam_xz.y);
        if empty_skip {
            // In a cell where the weather leaves no cloud: jump to the first sample past
            // the cell's edge.
            let exit = empty_cell_exit(p, view);
            if exit > 0.0 {
                let next = u32(clamp(ceil((t + exit - start) / dt - jitter), 0.0, f32(steps)));
                i = max(i + 1u, next);
                continue;
            }
        }
        let alt = altitude_of(rel);
        let density = layer_density(p, alt, l, counters);
        if density <= 0.0 {
            empty += 1u;
            if dynamic_step && empty >= 8u {
                stride = 2u;
            }
            i += stride;
            continue;
        }
        if stride > 1u {
            // Entered cloud on a long step: go back to the sample skipped over and
            // continue at the fine step.
            i -= stride - 1u;
            stride = 1u;
            empty = 0u;
            continue;
        }
        empty = 0u;
        let sigma_t = sigma_e * density;
        let source = scattered_light(rel, p, alt, density, view, l, counters);
        let transmittance = (*state).transmittance;
        (*state).radiance += transmittance * step_integral(source.total, sigma_t, dt);
        (*state).octaves += transmittance * step_integral(source.octaves, sigma_t, dt);
        let step_t = exp(-sigma_t * dt);
        (*state).depth_sum += t * transmittance * (1.0 - step_t);
        (*state).transmittance = transmittance * step_t;
        if (*state).transmittance < frame.early_exit_transmittance {
            return true;
        }
        i += 1u;
    }
    return false;
}

// Every pixel, every frame.
@compute @workgroup_size(8, 8, 1)
fn march(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.size) {
        return;
    }
    let r = march_pixel(id.xy);
    textureStore(cloud_out, id.xy, vec4<f32>(r.radiance, r.transmittance));
    textureStore(depth_out, id.xy, vec4<f32>(r.depth, 0.0, 0.0, 0.0));
}
