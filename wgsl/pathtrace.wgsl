// A volumetric path tracer through the same density field as the march: the all-orders truth
// the march's multiple-scattering approximation is measured against, accumulated over frames.
//
// Estimators (Novák et al. 2018, "Monte Carlo methods for volumetric light transport
// simulation"; the CPU path tracer, crates/reference/src/montecarlo.rs, is the same algorithm
// in f64 and explains each choice at length):
// * free flight: delta tracking (Woodcock) with the majorant sigma_t * d_max, d_max bounding
//   the density (multiplier * (1 + precipitation), at most 1);
// * transmittance (toward the sun, toward the environment, and the camera ray's alpha): ratio
//   tracking (Novák et al. 2014), with Russian roulette once below 0.01;
// * at a collision the throughput takes the single-scattering albedo; next-event estimation
//   to the sun; the path goes on along a phase-sampled direction, and where it leaves the
//   layer it sees the environment (`environment`: the sky and lit ground in its direction
//   seen from the collision it left under the physical sky, else a uniform ambient(h), h
//   that collision's height); Russian roulette on the throughput after the third order;
// * directions from Henyey-Greenstein (the two-lobe model samples its mixture; Cornette-Shanks
//   samples HG(g) weighted by CS/HG).
// The octaves, Beer-Powder and precipitation darkening are the march's approximations and are
// not used here; `orders` (path_orders) caps the scattering orders (0 = all, up to MAX_PATH_ORDERS).
//
// Progressive: each frame adds PATHS_PER_FRAME paths per pixel (their random streams seeded by
// the frame, frame_index, and the lane) to the running means in `history` (radiance,
// transmittance) and `history-meta` (depth, paths, mean squared luminance, paths that hit
// cloud). A cut, a new plan or a moved camera starts over; a host that changes anything else
// (sun, wind) cuts the history itself.

// A path of more orders than this ends (a conservative thick cloud needs hundreds; this only
// bounds pathological cases so that an invocation's work is finite).
const MAX_PATH_ORDERS: u32 = 16384u;

// One random stream per path: a 32-bit LCG with PCG's RXS-M-XS output (O'Neill 2014), seeded
// by the pixel and the path's index (frame and lane).
fn rng_seed(pixel: vec2<u32>, path_index: u32) -> u32 {
    return pcg(pixel.x ^ pcg(pixel.y ^ pcg(path_index)));
}

// Uniform in [0, 1), 24 bits.
fn rng_next(rng: ptr<function, u32>) -> f32 {
    *rng = *rng * 747796405u + 2891336453u;
    let s = *rng;
    let word = ((s >> ((s >> 28u) + 4u)) ^ s) * 277803737u;
    return f32(((word >> 22u) ^ word) >> 8u) * (1.0 / 16777216.0);
}

// An exponential distance of rate `sigma` (1 - u > 0 always).
fn rng_exponential(rng: ptr<function, u32>, sigma: f32) -> f32 {
    return -log(1.0 - rng_next(rng)) / sigma;
}

// Up to two parts of a ray inside the cloud layer (a ray from inside that dips below the
// layer without meeting the ground comes back up through it).
struct Segments {
    a: vec2<f32>,   // starts
    b: vec2<f32>,   // ends
    count: u32,
}

// The parts of the ray from `p` along unit `d` inside the shell that holds every layer (no
// cut-off: scattered light sees the whole medium; between layers the density is 0).
fn layer_segments(p: vec3<f32>, alt: f32, d: vec3<f32>) -> Segments {
    var s = Segments(vec2<f32>(0.0), vec2<f32>(0.0), 0u);
    let span = layers_span();
    let bottom = span.x;
    let inner = ray_shell_from(p, alt, d, bottom);
    let outer = ray_shell_from(p, alt, d, span.y);
    let ground = hits_ground(p, alt, d);
    if !outer.hit || outer.t1 <= 0.0 {
        return s;
    }
    let entry = max(outer.t0, 0.0);
    var a = vec2<f32>(0.0);
    var b = vec2<f32>(0.0);
    var n = 0u;
    if inner.hit && inner.t0 > 0.0 && alt >= bottom {
        // Down into the bottom shell; back up unless the ground stops it.
        a[n] = entry;
        b[n] = inner.t0;
        n += u32(inner.t0 > entry);
        if !ground && outer.t1 > inner.t1 {
            a[n] = max(inner.t1, entry);
            b[n] = outer.t1;
            n += 1u;
        }
    } else if alt < bottom {
        if !ground && inner.hit {
            a[0] = max(inner.t1, 0.0);
            b[0] = outer.t1;
            n = 1u;
        }
    } else {
        a[0] = entry;
        b[0] = outer.t1;
        n = 1u;
    }
    s.a = a;
    s.b = b;
    s.count = n;
    return s;
}

// Density at camera-relative `rel`.
fn density_at(rel: vec3<f32>, counters: ptr<function, Counters>) -> f32 {
    let p = vec3<f32>(rel.x + frame.camera_position.x, rel.y, rel.z + frame.camera_position.z);
    return cloud_density(p, altitude_of(rel), counters);
}

// How far the ray from camera-relative `origin` along `dir` may jump from distance `t`: past
// the edge of an empty occupancy cell (no cloud at any altitude), else 0. Both trackers sample
// distances afresh after a jump, which the exponential's lack of memory allows. The jump ends
// 5 cm inside the next cell so that rounding cannot leave the ray on the wall (the density of
// those 5 cm is not sampled: a bias below 0.2% of one mean free path per wall). The grid
// covers the main layer's weather only, so with several layers nothing is skipped.
fn empty_cell_skip(origin: vec3<f32>, dir: vec3<f32>, t: f32) -> f32 {
    if layer_count() > 1u {
        return 0.0;
    }
    let rel = origin + dir * t;
    let p = vec3<f32>(rel.x + frame.camera_position.x, rel.y, rel.z + frame.camera_position.z);
    let exit = empty_cell_exit(p, dir);
    if exit <= 0.0 {
        return 0.0;
    }
    return exit + 0.05;
}

// The bound of the density delta and ratio tracking rely on.
fn density_max() -> f32 {
    var m = 0.0;
    for (var i = 0u; i < layer_count(); i++) {
        let l = cloud_layer(i);
        m = max(m, l.density * (1.0 + l.precipitation));
    }
    return clamp(m, 0.0, 1.0);
}

// Delta tracking: the distance of the first real collision along the ray, or -1.
fn free_flight(origin: vec3<f32>, dir: vec3<f32>, segs: Segments, rng: ptr<function, u32>,
               counters: ptr<function, Counters>) -> f32 {
    let d_max = density_max();
    let majorant = (frame.scattering + frame.absorption) * d_max;
    if majorant <= 0.0 {
        return -1.0;
    }
    for (var k = 0u; k < segs.count; k++) {
        var t = segs.a[k];
        loop {
            let skip = empty_cell_skip(origin, dir, t);
            if skip > 0.0 {
                t += skip;
                if t >= segs.b[k] {
                    break;
                }
                continue;
            }
            t += rng_exponential(rng, majorant);
            if t >= segs.b[k] {
                break;
            }
            (*counters).view_steps += 1u;
            let d = density_at(origin + dir * t, counters);
            if rng_next(rng) * d_max < d {
                return t;
            }
        }
    }
    return -1.0;
}

// Ratio tracking: an unbiased estimate of the transmittance along the ray.
fn transmittance_along(origin: vec3<f32>, dir: vec3<f32>, segs: Segments,
                       rng: ptr<function, u32>, counters: ptr<function, Counters>) -> f32 {
    let sigma_t = frame.scattering + frame.absorption;
    let majorant = sigma_t * density_max();
    if majorant <= 0.0 {
        return 1.0;
    }
    var tr = 1.0;
    for (var k = 0u; k < segs.count; k++) {
        var t = segs.a[k];
        loop {
            let skip = empty_cell_skip(origin, dir, t);
            if skip > 0.0 {
                t += skip;
                if t >= segs.b[k] {
                    break;
                }
                continue;
            }
            t += rng_exponential(rng, majorant);
            if t >= segs.b[k] {
                break;
            }
            (*counters).light += 1u;
            let d = density_at(origin + dir * t, counters);
            tr *= 1.0 - sigma_t * d / majorant;
            if tr <= 0.0 {
                return 0.0;
            }
            if tr < 0.01 {
                // Russian roulette on nearly opaque rays (unbiased).
                if rng_next(rng) < 0.75 {
                    return 0.0;
                }
                tr *= 4.0;
            }
        }
    }
    return tr;
}

// Henyey-Greenstein's cosine for eccentricity `g` from a uniform `u`.
fn sample_hg_cos(g: f32, u: f32) -> f32 {
    if abs(g) < 1e-4 {
        return 1.0 - 2.0 * u;
    }
    let s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
    return clamp((1.0 + g * g - s * s) / (2.0 * g), -1.0, 1.0);
}

// A direction drawn from the scene's phase function around `dir` (the direction the path
// travels) and its weight phase / pdf.
struct PhaseSample {
    dir: vec3<f32>,
    weight: f32,
}

fn sample_phase(dir: vec3<f32>, rng: ptr<function, u32>) -> PhaseSample {
    let u_lobe = rng_next(rng);
    let u = rng_next(rng);
    let phi = 2.0 * PI * rng_next(rng);
    var cos_theta = 0.0;
    var pdf = 0.0;
    if frame.phase_model == PHASE_TWO_LOBE_HG {
        let g = select(frame.phase_g, frame.phase_g2, u_lobe < frame.phase_blend);
        cos_theta = sample_hg_cos(g, u);
        pdf = mix(phase_hg(cos_theta, frame.phase_g), phase_hg(cos_theta, frame.phase_g2),
                  frame.phase_blend);
    } else {
        cos_theta = sample_hg_cos(frame.phase_g, u);
        pdf = phase_hg(cos_theta, frame.phase_g);
    }
    let sin_theta = sqrt(max(1.0 - cos_theta * cos_theta, 0.0));
    // An orthonormal basis around `dir` (Duff et al. 2017).
    let sign = select(-1.0, 1.0, dir.z >= 0.0);
    let a = -1.0 / (sign + dir.z);
    let bb = dir.x * dir.y * a;
    let t = vec3<f32>(1.0 + sign * dir.x * dir.x * a, sign * bb, -sign * dir.x);
    let b = vec3<f32>(bb, sign + dir.y * dir.y * a, -dir.y);
    let w = normalize(t * (sin_theta * cos(phi)) + b * (sin_theta * sin(phi)) + dir * cos_theta);
    return PhaseSample(w, select(0.0, phase(cos_theta, 1.0) / pdf, pdf > 0.0));
}

// The light a path that leaves the clouds from `pos` (camera-relative, m; its last
// collision) along unit `d` sees: under the physical sky the sky and the lit ground in that
// direction seen from there (`sky_from`: the air between the clouds and the ground, or above
// the clouds, lit by the sun), else the ambient's uniform environment ambient(h). Seen from
// the camera instead (the sky-view table, as before), a path leaving a layer's base downward
// saw the ground at once, without the kilometre or two of air below the layer, which a low
// sun lights brightly. The march takes the cosine-weighted hemispheres facing the layer (the
// sky-ambient table). Neither knows the clouds' shadow on that air and ground.
fn environment(pos: vec3<f32>, d: vec3<f32>, h: f32) -> vec3<f32> {
    if physical_sky() {
        return sky_from(pos, d) * frame.sun_illuminance * frame.ambient_strength;
    }
    return ambient(h, pos);
}

// One path through `pixel`'s ray over the march's interval.
struct PathResult {
    radiance: vec3<f32>,
    transmittance: f32,
    depth: f32,          // distance of the first collision, -1 if none
}

fn trace_path(view: vec3<f32>, span: Interval, rng: ptr<function, u32>,
              counters: ptr<function, Counters>) -> PathResult {
    var out = PathResult(vec3<f32>(0.0), 1.0, -1.0);
    if span.kind != RAY_MARCH {
        return out;
    }
    let cam = vec3<f32>(0.0, frame.camera_position.y, 0.0);
    let primary = Segments(vec2<f32>(span.start, 0.0), vec2<f32>(span.start + span.length, 0.0), 1u);
    out.transmittance = transmittance_along(cam, view, primary, rng, counters);
    let first = free_flight(cam, view, primary, rng, counters);
    if first < 0.0 {
        return out;
    }
    out.depth = first;

    let sun = frame.sun_direction;
    let sigma_t = frame.scattering + frame.absorption;
    let albedo = select(0.0, frame.scattering / sigma_t, sigma_t > 0.0);
    let ambient_on = frame.ambient_strength > 0.0
        && (physical_sky() || any(frame.ambient_bottom > vec3<f32>(0.0))
            || any(frame.ambient_top > vec3<f32>(0.0)));
    var max_orders = MAX_PATH_ORDERS;
    if frame.path_orders > 0u {
        max_orders = min(frame.path_orders, MAX_PATH_ORDERS);
    }

    var pos = cam + view * first;
    var dir = view;
    var throughput = 1.0;
    var order = 0u;
    loop {
        throughput *= albedo;
        order += 1u;
        let alt = altitude_of(pos);
        let h = height_fraction(alt);
        // Next event toward the sun (a directional light).
        if !hits_ground(pos, alt, sun) {
            let tr = transmittance_along(pos, sun, layer_segments(pos, alt, sun), rng, counters);
            out.radiance += frame.sun_illuminance * sun_through_air(pos)
                * (throughput * phase(dot(dir, sun), 1.0) * tr);
        }
        // The next direction, from the phase function. Its free flight also estimates the
        // ambient (an environment seen through the medium): a path that leaves the layer along
        // it sees `environment` (ambient(h), or the sky from there). That is the expectation of the CPU path tracer's
        // separate ratio-tracked ray toward the environment, for one tracked ray instead of
        // two per collision.
        let next = sample_phase(dir, rng);
        let t = free_flight(pos, next.dir, layer_segments(pos, alt, next.dir), rng, counters);
        if t < 0.0 {
            if ambient_on {
                out.radiance += environment(pos, next.dir, h) * (throughput * next.weight);
            }
            break;
        }
        if order >= max_orders {
            break;
        }
        throughput *= next.weight;
        dir = next.dir;
        if order >= 3u && throughput < 0.1 {
            if rng_next(rng) >= throughput / 0.1 {
                break;
            }
            throughput = 0.1;
        }
        if throughput <= 0.0 {
            break;
        }
        pos += dir * t;
    }
    return out;
}

fn luminance(c: vec3<f32>) -> f32 {
    return dot(c, vec3<f32>(0.2126, 0.7152, 0.0722));
}

// Paths per pixel per frame: a pixel is one workgroup of this many invocations, one path each,
// summed in workgroup memory. One path per pixel a frame left a GPU nearly idle at the small
// sizes the fit and the bench use (64x36 on an H100: 20 ms a frame for 2304 paths, each frame
// as long as its longest path); the host reads this from the entry point's workgroup size. The
// lanes run along x: llvmpipe vectorises a workgroup along x only (along z this ran 6x slower).
const PATHS_PER_FRAME: u32 = 32u;

// Each lane's path: radiance and transmittance, and (luminance squared, depth, hit, 0). Every
// lane writes its element before the barrier and lane 0 reads them after: nothing reads the
// initial value (the HLSL leaves workgroup memory uninitialised, crates/shaders).
var<workgroup> lane_sums: array<vec4<f32>, PATHS_PER_FRAME>;
var<workgroup> lane_moments: array<vec4<f32>, PATHS_PER_FRAME>;

// PATHS_PER_FRAME more paths for every pixel, joined to the running means.
@compute @workgroup_size(PATHS_PER_FRAME, 1, 1)
fn pathtrace(@builtin(workgroup_id) group: vec3<u32>,
             @builtin(local_invocation_index) lane: u32) {
    // The workgroup is the pixel, so this test is uniform across it (the barriers below).
    if any(group.xy >= frame.size) {
        return;
    }
    let pixel = group.xy;
    let view = view_ray(pixel);
    let span = cloud_interval(frame.camera_position.y, view);
    var counters = Counters(0u, 0u, 0u, 0u);
    if lane == 0u {
        count(STAT_PIXELS, 1u);
        count(STAT_MARCHED, u32(span.kind == RAY_MARCH));
        count(STAT_EXIT_MISSED, u32(span.kind == RAY_MISSES_LAYER));
        count(STAT_EXIT_GROUND, u32(span.kind == RAY_HITS_GROUND));
    }

    // One path per invocation. Tracing several in a loop of one invocation gave wrong images
    // on lavapipe from about 10 paths an invocation on (8x8 blocks too dark, the same bits
    // whichever single path was kept), so a frame's paths are the workgroup's lanes.
    var rng = rng_seed(pixel, frame.frame_index * PATHS_PER_FRAME + lane);
    let r = trace_path(view, span, &rng, &counters);
    let l = luminance(r.radiance);
    let hit = r.depth >= 0.0;
    lane_sums[lane] = vec4<f32>(r.radiance, r.transmittance);
    lane_moments[lane] = vec4<f32>(l * l, select(0.0, r.depth, hit), select(0.0, 1.0, hit), 0.0);
    workgroupBarrier();

    if lane == 0u {
        // Lane 0 sums the lanes' paths. (A tree sum, a barrier in each round of a loop, lost
        // whole frames of some pixels on lavapipe: their history was not written.)
        var sum = vec4<f32>(0.0);
        var sum_moments = vec4<f32>(0.0);
        for (var i = 0u; i < PATHS_PER_FRAME; i++) {
            sum += lane_sums[i];
            sum_moments += lane_moments[i];
        }
        var mean = vec4<f32>(0.0);
        var moments = vec4<f32>(0.0);
        if frame.history_valid == 1u && camera_still() {
            mean = textureLoad(history_in, pixel, 0);
            moments = textureLoad(meta_in, pixel, 0);
        }
        let k = f32(PATHS_PER_FRAME);
        let n = moments.y + k;
        // Running means over every path so far: this frame's k paths weigh k / n.
        mean += (sum - k * mean) / n;
        moments.z += (sum_moments.x - k * moments.z) / n;
        let hits = sum_moments.z;
        if hits > 0.0 {
            moments.w += hits;
            moments.x += (sum_moments.y - hits * moments.x) / moments.w;
        }
        moments.y = n;
        textureStore(history_out, pixel, mean);
        textureStore(meta_out, pixel, moments);
        textureStore(cloud_out, pixel, mean);
        textureStore(depth_out, pixel, vec4<f32>(moments.x, 0.0, 0.0, 0.0));
    }

    count(STAT_VIEW_STEPS, counters.view_steps);
    count(STAT_DENSITY, counters.density);
    count(STAT_DETAIL, counters.detail);
    count(STAT_LIGHT, counters.light);
}
