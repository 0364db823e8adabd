// Lens flare (`post.lens_flare_intensity`, seed 001 section 5.2): light of the sun reflected
// between a lens's surfaces reaches the sensor as ghosts, images of the aperture spread along
// the line from the sun's image through the optical centre, and as a halo around the centre.
// Each ghost here is the hexagonal aperture (six blades) drawn by its signed distance, and
// carries a fixed share of the sun's illuminance that reaches the lens, spread evenly over its
// solid angle: its radiance follows the sun's through the air and through the clouds in front
// of it (the march's transmittance over the sun's disc), and a thick cloud over the sun, the
// host's geometry or the sun's leaving the screen removes it. Shares are per colour channel
// (the coatings tint each ghost); at intensity 1 a ghost carries 1e-4 to 4e-4 of the light,
// the order of a multi-coated lens's double reflections (Hullin et al. 2011, "Physically-based
// real-time lens flare rendering", section 2). Positions are in units of the image's height
// from its centre, y down, so the flare keeps its shape at every resolution.

// A disc is sampled at its centre and four points on its rim.
const FLARE_TAPS: f32 = 5.0;
// The aperture's edge normals: a hexagon turned 15 degrees (its blades' angle in the lens),
// its normals at 45, 105 and 165 degrees (and their opposites).
const FLARE_EDGE_0: vec2<f32> = vec2<f32>(0.70710678, 0.70710678);
const FLARE_EDGE_1: vec2<f32> = vec2<f32>(-0.25881905, 0.96592583);
const FLARE_EDGE_2: vec2<f32> = vec2<f32>(-0.96592583, 0.25881905);
// The halo: its radius and width (image heights), and its share of the sun's light.
const FLARE_HALO_RADIUS: f32 = 0.42;
const FLARE_HALO_WIDTH: f32 = 0.012;
const FLARE_HALO_SHARE: f32 = 0.6e-3;
// The halo's colour fringe: its red ring lies this far outside its blue (image heights).
const FLARE_HALO_FRINGE: f32 = 0.01;

// The sun's image centre on the screen, in pixels (continuous: pixel p spans [p, p + 1)), and
// whether it lies in front of the camera.
struct SunImage {
    at: vec2<f32>,
    ahead: bool,
}

fn sun_image() -> SunImage {
    let sun = frame.sun_direction;
    let z = dot(sun, frame.camera_forward);
    if z <= 0.0 {
        return SunImage(vec2<f32>(0.0), false);
    }
    // view_ray's mapping, inverted: ndc = (pixel + 0.5) / size * 2 - 1, y down.
    let ndc = vec2<f32>(
        dot(sun, frame.camera_right) / (z * frame.tan_half_fov * frame.aspect),
        -dot(sun, frame.camera_up) / (z * frame.tan_half_fov),
    );
    return SunImage((ndc * 0.5 + 0.5) * vec2<f32>(frame.size), true);
}

// The sun's illuminance that reaches the lens, given `direct` (what arrives through the air
// alone): `direct` times the share of the sun's disc that is on screen and unhidden, and the
// clouds' transmittance there. 0 without flare, under the moon as key light, or with the sun
// behind the camera.
fn flare_source(direct: vec3<f32>) -> vec3<f32> {
    if frame.lens_flare_intensity <= 0.0 || (frame.flags & FLAG_MOONLIT) != 0u {
        return vec3<f32>(0.0);
    }
    let image = sun_image();
    if !image.ahead {
        return vec3<f32>(0.0);
    }
    let cos_r = frame.sun_cos_radius;
    let tan_r = sqrt(max(1.0 - cos_r * cos_r, 0.0)) / cos_r;
    let radius_px = max(tan_r / frame.tan_half_fov * 0.5 * f32(frame.size.y), 1.0);
    var seen = 0.0;
    for (var i = 0u; i < 5u; i++) {
        var offset = vec2<f32>(0.0);
        if i > 0u {
            let axis = select(vec2<f32>(0.0, 1.0), vec2<f32>(1.0, 0.0), i < 3u);
            offset = axis * select(-radius_px, radius_px, (i & 1u) == 1u);
        }
        let p = floor(image.at + offset);
        if all(p >= vec2<f32>(0.0)) && all(p < vec2<f32>(frame.size)) {
            let pixel = vec2<u32>(p);
            if !has_surface(pixel) {
                seen += textureLoad(cloud_in, pixel, 0).a;
            }
        }
    }
    return direct * (seen / FLARE_TAPS);
}

// The sun's light reaching the lens, shared by a workgroup: it is the same for every pixel,
// and measuring it reads five texels of the march output (and as many of the scene depth), so
// one invocation in 64 does it.
var<workgroup> flare_light: vec3<f32>;

// `flare_source(direct)`, measured by the workgroup's first invocation. Every invocation of the
// workgroup must call it (it holds a barrier), before any returns.
fn shared_flare_source(local: u32, direct: vec3<f32>) -> vec3<f32> {
    if local == 0u {
        flare_light = flare_source(direct);
    }
    workgroupBarrier();
    return flare_light;
}

// Signed distance (image heights) from `p` to a regular hexagon of circumradius `r` about the
// origin, its edges' normals FLARE_EDGE_*: the largest distance past its three pairs of edges
// (exact inside and beside the edges, a little short beyond corners).
fn aperture_distance(p: vec2<f32>, r: f32) -> f32 {
    let apothem = r * 0.8660254;
    let d0 = abs(dot(p, FLARE_EDGE_0));
    let d1 = abs(dot(p, FLARE_EDGE_1));
    let d2 = abs(dot(p, FLARE_EDGE_2));
    return max(d0, max(d1, d2)) - apothem;
}

// One ghost's radiance per unit sun illuminance at `p`: at `along` times the sun's position
// `s` (1 at the sun, negative across the centre), circumradius `r`, carrying `share` of the
// light over its solid angle (its area in image heights times (2 tan(fov / 2))^2 per unit
// area). Its edge is soft over a fifth of its radius and a little brighter than its middle,
// as a defocused aperture's image is.
fn ghost(p: vec2<f32>, s: vec2<f32>, along: f32, r: f32, share: vec3<f32>) -> vec3<f32> {
    let q = p - s * along;
    // Beyond the soft edge (which ends 0.2 r past the edges, inside 1.25 r): nothing.
    if dot(q, q) > 1.5625 * r * r {
        return vec3<f32>(0.0);
    }
    let d = aperture_distance(q, r);
    let soft = 0.2 * r;
    let inside = 1.0 - smoothstep(-soft, soft, d);
    let rim = 0.75 + 0.5 * smoothstep(-0.5 * r, 0.0, d);
    let apothem = r * 0.8660254;
    let area = 2.0 * sqrt(3.0) * apothem * apothem;
    let height_angle = 2.0 * frame.tan_half_fov;
    return share * (inside * rim / (area * height_angle * height_angle));
}

// The flare's radiance at `pixel` for `source`, the sun's illuminance reaching the lens
// (`flare_source`), times `lens_flare_intensity`.
fn lens_flare(pixel: vec2<u32>, source: vec3<f32>) -> vec3<f32> {
    if all(source <= vec3<f32>(0.0)) {
        return vec3<f32>(0.0);
    }
    let size = vec2<f32>(frame.size);
    let centre = size * 0.5;
    let p = (vec2<f32>(pixel) + 0.5 - centre) / size.y;
    let s = (sun_image().at - centre) / size.y;
    var flare = vec3<f32>(0.0);
    flare += ghost(p, s, 0.55, 0.035, vec3<f32>(1.0e-4, 2.0e-4, 1.2e-4));
    flare += ghost(p, s, 0.25, 0.018, vec3<f32>(2.5e-4, 1.5e-4, 0.6e-4));
    flare += ghost(p, s, -0.2, 0.05, vec3<f32>(1.2e-4, 1.6e-4, 2.4e-4));
    flare += ghost(p, s, -0.45, 0.025, vec3<f32>(2.4e-4, 1.0e-4, 2.2e-4));
    flare += ghost(p, s, -0.8, 0.07, vec3<f32>(1.6e-4, 2.6e-4, 1.4e-4));
    flare += ghost(p, s, -1.25, 0.11, vec3<f32>(4.0e-4, 3.0e-4, 2.0e-4));
    // The halo: a ring about the centre, brightest where the axis crosses it on the sun's
    // side, its red outside its blue (the coatings' dispersion). Its share spreads over the
    // ring's area 2 pi R w sqrt(2 pi) (a Gaussian profile of width w).
    let r = length(p);
    if abs(r - FLARE_HALO_RADIUS) > FLARE_HALO_FRINGE + 6.0 * FLARE_HALO_WIDTH {
        return flare * source * frame.lens_flare_intensity;
    }
    let side = saturate(dot(p, s) / max(r * length(s), 1e-4));
    let ring = vec3<f32>(
        r - (FLARE_HALO_RADIUS + FLARE_HALO_FRINGE),
        r - FLARE_HALO_RADIUS,
        r - (FLARE_HALO_RADIUS - FLARE_HALO_FRINGE),
    ) / FLARE_HALO_WIDTH;
    let profile = exp(-0.5 * ring * ring);
    let ring_area = 2.0 * PI * FLARE_HALO_RADIUS * FLARE_HALO_WIDTH * sqrt(2.0 * PI);
    let height_angle = 2.0 * frame.tan_half_fov;
    // side^2 averages 1/4 around the ring when the sun is off-centre: x4 keeps the share.
    flare += FLARE_HALO_SHARE * profile * (4.0 * side * side)
        / (ring_area * height_angle * height_angle);
    return flare * source * frame.lens_flare_intensity;
}
