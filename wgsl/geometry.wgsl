// Geometry at planet scale in f32: camera rays, ray-sphere intersection in the stable
// quadratic form, altitude without cancellation, and the ray's interval in the cloud layer.
//
// Everything is relative to the point on the planet's surface straight below the camera: the
// planet's centre is at (0, -Rp, 0) in these coordinates and the camera at (0, altitude, 0), so
// no quantity of size Rp is ever subtracted from another of size Rp.

// The view ray through the centre of pixel `pixel` (y down in the image).
fn view_ray(pixel: vec2<u32>) -> vec3<f32> {
    return view_ray_at(vec2<f32>(pixel) + 0.5);
}

// The view ray through the image point `at` (pixels, continuous: pixel p's centre is p + 0.5).
fn view_ray_at(at: vec2<f32>) -> vec3<f32> {
    let size = vec2<f32>(frame.size);
    let ndc = at / size * 2.0 - 1.0;
    let tan_half = frame.tan_half_fov;
    let aspect = frame.aspect;
    let d = frame.camera_forward
        + frame.camera_right * (ndc.x * tan_half * aspect)
        - frame.camera_up * (ndc.y * tan_half);
    return normalize(d);
}

// Roots of |o + t d - centre|^2 = R^2 for a unit `d`, written t^2 + 2 b t + c = 0 with
// b = dot(d, o - centre) and c = |o - centre|^2 - R^2 passed in precomputed (so that the caller
// can form c without cancellation). Returns (t0, t1), t0 <= t1, or (-inf... ) via `hit`.
struct Roots {
    t0: f32,
    t1: f32,
    hit: bool,
}

fn solve_sphere(b: f32, c: f32) -> Roots {
    let disc = b * b - c;
    if disc < 0.0 {
        return Roots(0.0, 0.0, false);
    }
    // Stable form: q = -(b + sign(b) sqrt(disc)); the roots are q and c / q (no subtraction
    // of nearly equal numbers, which would lose the near root at grazing angles).
    let s = sqrt(disc);
    let q = -(b + select(-s, s, b >= 0.0));
    if q == 0.0 {
        return Roots(0.0, 0.0, true);
    }
    let r0 = q;
    let r1 = c / q;
    return Roots(min(r0, r1), max(r0, r1), true);
}

// Intersection of the ray from the camera (altitude `alt`) along unit `d` with the sphere of
// altitude `radius_alt` (radius Rp + radius_alt). c = (alt - r)(alt + r + 2 Rp) exactly.
fn ray_shell(alt: f32, d: vec3<f32>, radius_alt: f32) -> Roots {
    let rp = frame.planet_radius;
    let b = d.y * (alt + rp);
    let c = (alt - radius_alt) * (alt + radius_alt + 2.0 * rp);
    return solve_sphere(b, c);
}

// Altitude of a point given relative to the ground point below the camera:
// |q|^2 - Rp^2 = x^2 + z^2 + y (y + 2 Rp) with q = p + (0, Rp, 0), divided by |q| + Rp.
fn altitude_of(p: vec3<f32>) -> f32 {
    let rp = frame.planet_radius;
    let n = p.x * p.x + p.z * p.z + p.y * (p.y + 2.0 * rp);
    let q = vec3<f32>(p.x, p.y + rp, p.z);
    return n / (length(q) + rp);
}

// Whether the ray from `p` (camera-relative, altitude `alt`) along unit `d` hits the ground.
fn hits_ground(p: vec3<f32>, alt: f32, d: vec3<f32>) -> bool {
    let rp = frame.planet_radius;
    let b = dot(d, vec3<f32>(p.x, p.y + rp, p.z));
    let c = alt * (alt + 2.0 * rp);
    return b < 0.0 && b * b >= c;
}

// Why a ray does or does not march the layer.
const RAY_MARCH: u32 = 0u;
const RAY_MISSES_LAYER: u32 = 1u;
const RAY_HITS_GROUND: u32 = 2u;

struct Interval {
    start: f32,
    length: f32,
    kind: u32,
}

// The part of the view ray inside the shell between altitudes `bottom` and `top`, cut to the
// cut-off distance (thesis alg. 5.1: march min(layer depth, cut-off)). Handles cameras below,
// inside and above the layer (thesis 5.2). Of a ray that passes down through the shell and
// back up, the first part.
fn shell_interval(alt: f32, d: vec3<f32>, bottom: f32, top: f32) -> Interval {
    let cutoff = frame.cutoff_distance;
    let inner = ray_shell(alt, d, bottom);
    let outer = ray_shell(alt, d, top);
    var start = 0.0;
    var end = 0.0;
    if alt < bottom {
        // Below: the ground is inside the inner shell, so a ray that meets it never enters.
        if hits_ground(vec3<f32>(0.0, alt, 0.0), alt, d) {
            return Interval(0.0, 0.0, RAY_HITS_GROUND);
        }
        start = inner.t1;
        end = outer.t1;
    } else if alt <= top {
        end = outer.t1;
        if inner.hit && inner.t0 > 0.0 {
            end = min(end, inner.t0);
        }
    } else {
        if !outer.hit || outer.t1 <= 0.0 {
            return Interval(0.0, 0.0, RAY_MISSES_LAYER);
        }
        start = max(outer.t0, 0.0);
        end = outer.t1;
        if inner.hit && inner.t0 > 0.0 {
            end = min(end, inner.t0);
        }
    }
    let len = min(end - start, cutoff);
    if !(len > 0.0) {
        return Interval(0.0, 0.0, RAY_MISSES_LAYER);
    }
    return Interval(start, len, RAY_MARCH);
}

// The view ray's interval in cloud layer `l`.
fn layer_interval(alt: f32, d: vec3<f32>, l: Layer) -> Interval {
    return shell_interval(alt, d, l.bottom, l.top);
}

// The view ray's interval in the shell that holds every layer (the path tracer's medium,
// and the baselines, which draw one layer).
fn cloud_interval(alt: f32, d: vec3<f32>) -> Interval {
    let span = layers_span();
    return shell_interval(alt, d, span.x, span.y);
}

// The interval of the layer the view ray meets first (the lowest index of equal starts).
fn nearest_layer_interval(alt: f32, d: vec3<f32>) -> Interval {
    var best = layer_interval(alt, d, cloud_layer(0u));
    for (var i = 1u; i < layer_count(); i++) {
        let s = layer_interval(alt, d, cloud_layer(i));
        if s.kind == RAY_MARCH && (best.kind != RAY_MARCH || s.start < best.start) {
            best = s;
        }
    }
    return best;
}

// `ray_shell` from any camera-relative point `p` of altitude `alt`.
fn ray_shell_from(p: vec3<f32>, alt: f32, d: vec3<f32>, radius_alt: f32) -> Roots {
    let rp = frame.planet_radius;
    let b = dot(d, vec3<f32>(p.x, p.y + rp, p.z));
    let c = (alt - radius_alt) * (alt + radius_alt + 2.0 * rp);
    return solve_sphere(b, c);
}
