// The physical sky (`atmosphere.sky = "physical"`): Hillaire's lookup tables ("A Scalable
// and Production Ready Sky and Atmosphere Rendering Technique", EGSR 2020) over the air of
// `frame.air_*` (Rayleigh, Mie and ozone; Bruneton 2017's Earth by default).
//
// - transmittance (256x64): transmittance to the top of the atmosphere by radius and cosine
//   of the zenith angle, Bruneton's parametrisation ("Precomputed Atmospheric Scattering",
//   2008, and its 2017 reimplementation). Computed when the air changes.
// - multi-scattering (32x32): Hillaire's Psi_ms by altitude and the sun's zenith cosine: the
//   second order from isotropic scattering over every direction, over 1 - f_ms for the higher
//   orders. Computed when the air changes.
// - sky-view (192x108): the sky's radiance around the camera, by azimuth from the sun and
//   elevation (denser toward the horizon). Every frame: it follows the sun and the camera.
// - aerial perspective (32x32 froxels x 32 slices of 1 km, as a 1024x32 atlas): light
//   scattered and transmitted between the camera and each depth. Every frame.
// - sky ambient (64x2): the cosine-weighted mean radiance of the lower and upper hemispheres
//   seen from the cloud layer's bottom by the cosine of the sun's zenith angle there, the
//   clouds' ambient light under this sky. Computed when the air or the layer changes.
//
// Every table holds light per unit sun illuminance at the top of the atmosphere; the user of
// a value multiplies by `frame.sun_illuminance`. Lengths here are kilometres (the planet's
// radius is exact enough in f32), coefficients per kilometre. The CPU reference integrates the
// same air in f64 directly (crates/reference/src/atmosphere.rs); tests measure these tables
// against it. Tables are rgba32float read with textureLoad and interpolated here, so no
// backend needs filterable float textures.

@group(0) @binding(27) var transmittance_lut_in: texture_2d<f32>;
@group(0) @binding(28) var multiscatter_lut_in: texture_2d<f32>;
@group(0) @binding(29) var sky_view_in: texture_2d<f32>;
@group(0) @binding(30) var aerial_in: texture_2d<f32>;
@group(0) @binding(31) var sky_ambient_in: texture_2d<f32>;
@group(0) @binding(32) var transmittance_lut_out: texture_storage_2d<rgba32float, write>;
@group(0) @binding(33) var multiscatter_lut_out: texture_storage_2d<rgba32float, write>;
@group(0) @binding(34) var sky_view_out: texture_storage_2d<rgba32float, write>;
@group(0) @binding(35) var aerial_out: texture_storage_2d<rgba32float, write>;
@group(0) @binding(36) var sky_ambient_out: texture_storage_2d<rgba32float, write>;

const TRANSMITTANCE_SIZE: vec2<u32> = vec2<u32>(256u, 64u);
const MULTISCATTER_SIZE: vec2<u32> = vec2<u32>(32u, 32u);
const SKY_VIEW_SIZE: vec2<u32> = vec2<u32>(192u, 108u);
const AERIAL_SLICES: u32 = 32u;
const AERIAL_SIDE: u32 = 32u;
const AERIAL_SLICE_KM: f32 = 1.0;
const TRANSMITTANCE_STEPS: u32 = 128u; // even (Simpson)
const MULTISCATTER_DIRECTIONS: u32 = 64u;
const MULTISCATTER_STEPS: u32 = 32u;
const SKY_VIEW_STEPS: u32 = 48u;
const AMBIENT_DIRECTIONS: u32 = 64u;
const AMBIENT_STEPS: u32 = 24u;
const SKY_AMBIENT_SUNS: u32 = 64u;

fn physical_sky() -> bool {
    return (frame.flags & FLAG_PHYSICAL_SKY) != 0u;
}

// Radii (km) of the ground and of the top of the atmosphere.
fn air_bottom() -> f32 {
    return frame.planet_radius * 1e-3;
}

fn air_top() -> f32 {
    return (frame.planet_radius + frame.air_thickness) * 1e-3;
}

// The air at altitude `h_km`: Rayleigh scattering (rgb), Mie scattering and total extinction
// (rgb), per km.
struct AirSample {
    rayleigh: vec3<f32>,
    mie: f32,
    extinction: vec3<f32>,
}

fn air_at(h_km: f32) -> AirSample {
    let h = max(h_km, 0.0) * 1000.0;
    let rayleigh_density = exp(-h / frame.rayleigh_scale_height);
    let mie_density = exp(-h / frame.mie_scale_height);
    let ozone_density = max(1.0 - abs(h - frame.ozone_center) / (0.5 * frame.ozone_width), 0.0);
    let rayleigh = frame.rayleigh_scattering * (rayleigh_density * 1000.0);
    let mie = frame.mie_scattering * mie_density * 1000.0;
    let mie_extinction = (frame.mie_scattering + frame.mie_absorption) * mie_density * 1000.0;
    let ozone = frame.ozone_absorption * (ozone_density * 1000.0);
    return AirSample(rayleigh, mie, rayleigh + vec3<f32>(mie_extinction) + ozone);
}

// r^2 (mu^2 - 1) + R^2 for the sphere of radius R, with R^2 - r^2 formed as (R - r)(R + r) so
// that it keeps its digits when r is close to R.
fn sphere_discriminant(r: f32, mu: f32, radius: f32) -> f32 {
    return (radius - r) * (radius + r) + r * r * mu * mu;
}

// Distance from radius `r` along a direction of zenith cosine `mu` to the top of the air.
fn distance_to_top(r: f32, mu: f32) -> f32 {
    return max(-r * mu + sqrt(max(sphere_discriminant(r, mu, air_top()), 0.0)), 0.0);
}

// Whether that ray meets the ground, and how far away.
fn meets_ground(r: f32, mu: f32) -> bool {
    return mu < 0.0 && sphere_discriminant(r, mu, air_bottom()) >= 0.0;
}

fn distance_to_ground(r: f32, mu: f32) -> f32 {
    return max(-r * mu - sqrt(max(sphere_discriminant(r, mu, air_bottom()), 0.0)), 0.0);
}

// Radius after `t` km from radius `r` along zenith cosine `mu`.
fn radius_after(r: f32, mu: f32, t: f32) -> f32 {
    return sqrt(max(r * r + t * t + 2.0 * r * mu * t, 0.0));
}

// Bilinear interpolation of table `lut` of `size` texels at `x` in [0, 1]^2, where texel i
// holds the value at x = i / (size - 1) (so both ends are sampled exactly).
fn lut_bilinear(lut: texture_2d<f32>, x: vec2<f32>, size: vec2<u32>) -> vec4<f32> {
    let last = vec2<f32>(size - 1u);
    let f = clamp(x, vec2<f32>(0.0), vec2<f32>(1.0)) * last;
    let i0 = min(vec2<u32>(floor(f)), size - 1u);
    let i1 = min(i0 + 1u, size - 1u);
    let w = f - vec2<f32>(i0);
    let a = mix(textureLoad(lut, vec2<u32>(i0.x, i0.y), 0), textureLoad(lut, vec2<u32>(i1.x, i0.y), 0), w.x);
    let b = mix(textureLoad(lut, vec2<u32>(i0.x, i1.y), 0), textureLoad(lut, vec2<u32>(i1.x, i1.y), 0), w.x);
    return mix(a, b, w.y);
}

// The transmittance table's coordinates of (r, mu): x from the distance to the top between
// its least and greatest at this radius, y from the distance to the horizon (Bruneton).
fn transmittance_coords(r: f32, mu: f32) -> vec2<f32> {
    let bottom = air_bottom();
    let top = air_top();
    let h = sqrt(max((top - bottom) * (top + bottom), 0.0));
    let rho = sqrt(max((r - bottom) * (r + bottom), 0.0));
    let d = distance_to_top(r, mu);
    let d_min = top - r;
    let d_max = rho + h;
    return vec2<f32>((d - d_min) / max(d_max - d_min, 1e-6), rho / h);
}

// The inverse: (r, mu) of table coordinates `x`.
fn transmittance_r_mu(x: vec2<f32>) -> vec2<f32> {
    let bottom = air_bottom();
    let top = air_top();
    let h = sqrt(max((top - bottom) * (top + bottom), 0.0));
    let rho = h * x.y;
    let r = sqrt(rho * rho + bottom * bottom);
    let d_min = top - r;
    let d_max = rho + h;
    let d = d_min + x.x * (d_max - d_min);
    var mu = 1.0;
    if d > 0.0 {
        mu = clamp((h * h - rho * rho - d * d) / (2.0 * r * d), -1.0, 1.0);
    }
    return vec2<f32>(r, mu);
}

// Transmittance from radius r along zenith cosine mu to the top of the air (the ground
// ignored: the caller decides whether the ray meets it).
fn transmittance_to_top(r: f32, mu: f32) -> vec3<f32> {
    return lut_bilinear(transmittance_lut_in, transmittance_coords(r, mu), TRANSMITTANCE_SIZE).rgb;
}

// The sun's light left at radius r for a sun of zenith cosine mu_s: 0 behind the planet.
fn sun_transmittance(r: f32, mu_s: f32) -> vec3<f32> {
    if meets_ground(r, mu_s) {
        return vec3<f32>(0.0);
    }
    return transmittance_to_top(r, mu_s);
}

// Psi_ms at radius r for a sun of zenith cosine mu_s.
fn multiscatter(r: f32, mu_s: f32) -> vec3<f32> {
    let x = vec2<f32>(mu_s * 0.5 + 0.5, (r - air_bottom()) / (air_top() - air_bottom()));
    return lut_bilinear(multiscatter_lut_in, x, MULTISCATTER_SIZE).rgb;
}

fn phase_rayleigh(cos_theta: f32) -> f32 {
    return 3.0 / (16.0 * PI) * (1.0 + cos_theta * cos_theta);
}

// Cornette-Shanks, the Mie phase function of Hillaire 2020 and Bruneton 2017.
fn phase_cornette_shanks_air(cos_theta: f32, g: f32) -> f32 {
    let g2 = g * g;
    return 3.0 / (8.0 * PI) * (1.0 - g2) * (1.0 + cos_theta * cos_theta)
        / ((2.0 + g2) * pow(max(1.0 + g2 - 2.0 * g * cos_theta, 1e-6), 1.5));
}

// Direction k of n spread evenly over the sphere (spherical Fibonacci), as the reference.
fn fibonacci_direction(k: u32, n: u32) -> vec3<f32> {
    let golden = PI * (3.0 - sqrt(5.0));
    let z = 1.0 - (2.0 * f32(k) + 1.0) / f32(n);
    let s = sqrt(max(1.0 - z * z, 0.0));
    let phi = golden * f32(k);
    return vec3<f32>(s * cos(phi), z, s * sin(phi));
}

// The sun's part of the light leaving the lit, diffuse ground where the direction to the sun
// has zenith cosine mu_s: albedo / pi times the sun's cosine and its light left there. The
// multi-scattering table takes the ground as lit by the sun alone (Hillaire 2020, 5.5.2);
// the sky's part is `ground_radiance`'s (wgsl/ground.wgsl).
fn ground_radiance_sun(mu_s: f32) -> vec3<f32> {
    return frame.ground_albedo / PI * max(mu_s, 0.0) * sun_transmittance(air_bottom() + 0.001, mu_s);
}

// In-scattered light and transmittance along a ray from `origin` (km, planet centre at the
// origin) along unit `d` for `distance_km` km in `steps` segments whose ends go as the square of
// their index (short near the camera, where the air is dense), the sun along unit `sun`. A
// caller whose ray ends on the ground adds the ground's light times the transmittance
// (`with_ground`).
struct Scattered {
    radiance: vec3<f32>,
    transmittance: vec3<f32>,
}

fn integrate_air(origin: vec3<f32>, d: vec3<f32>, distance_km: f32, steps: u32, sun: vec3<f32>) -> Scattered {
    let cos_theta = dot(d, sun);
    let phase_r = phase_rayleigh(cos_theta);
    let phase_m = phase_cornette_shanks_air(cos_theta, frame.mie_g);
    var radiance = vec3<f32>(0.0);
    var tau = vec3<f32>(0.0);
    var t0 = 0.0;
    for (var i = 0u; i < steps; i++) {
        let s1 = f32(i + 1u) / f32(steps);
        let t1 = distance_km * s1 * s1;
        let dt = t1 - t0;
        let p = origin + d * (0.5 * (t0 + t1));
        let r = length(p);
        let up = p / r;
        let mu_s = dot(up, sun);
        let air = air_at(r - air_bottom());
        // Transmittance to the segment's middle: the depth so far plus half the segment.
        let t_view = exp(-(tau + 0.5 * air.extinction * dt));
        let t_sun = sun_transmittance(r, mu_s);
        let ms = multiscatter(r, mu_s);
        let inscatter = t_sun * (air.rayleigh * phase_r + vec3<f32>(air.mie * phase_m))
            + ms * (air.rayleigh + vec3<f32>(air.mie));
        radiance += t_view * inscatter * dt;
        tau += air.extinction * dt;
        t0 = t1;
    }
    return Scattered(radiance, exp(-tau));
}

// The light of `integrate_air`'s ray with the lit ground (sun and sky) at its end through the
// air when `ground` (the ray ends there).
fn with_ground(s: Scattered, origin: vec3<f32>, d: vec3<f32>, distance_km: f32, sun: vec3<f32>,
               ground: bool) -> vec3<f32> {
    if !ground {
        return s.radiance;
    }
    let end = origin + d * distance_km;
    return s.radiance + s.transmittance * ground_radiance(dot(normalize(end), sun));
}

// The ray from `origin` along `d`: how far it goes in the air and whether it ends on the
// ground; (0, false) for a ray that misses the air.
fn air_ray_end(origin: vec3<f32>, d: vec3<f32>) -> vec2<f32> {
    let r = length(origin);
    let mu = dot(origin, d) / r;
    if meets_ground(r, mu) {
        return vec2<f32>(distance_to_ground(r, mu), 1.0);
    }
    if r > air_top() {
        // From outside the air (not a case the scenes reach): no light gathered.
        return vec2<f32>(0.0, 0.0);
    }
    return vec2<f32>(distance_to_top(r, mu), 0.0);
}

// The camera's place in the air: the planet's centre straight below it.
fn camera_air_origin() -> vec3<f32> {
    return vec3<f32>(0.0, air_bottom() + max(frame.camera_position.y, 0.0) * 1e-3, 0.0);
}

@compute @workgroup_size(8, 8, 1)
fn transmittance_lut(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= TRANSMITTANCE_SIZE) {
        return;
    }
    let rm = transmittance_r_mu(vec2<f32>(id.xy) / vec2<f32>(TRANSMITTANCE_SIZE - 1u));
    // Composite Simpson rule (as the reference): the densities are smooth, and a horizontal
    // ray's steps of several kilometres are long against the Rayleigh scale height.
    let dt = distance_to_top(rm.x, rm.y) / f32(TRANSMITTANCE_STEPS);
    var sum = vec3<f32>(0.0);
    for (var i = 0u; i <= TRANSMITTANCE_STEPS; i++) {
        var w = select(2.0, 4.0, (i & 1u) == 1u);
        if i == 0u || i == TRANSMITTANCE_STEPS {
            w = 1.0;
        }
        let r = radius_after(rm.x, rm.y, dt * f32(i));
        sum += w * air_at(r - air_bottom()).extinction;
    }
    textureStore(transmittance_lut_out, id.xy, vec4<f32>(exp(-sum * (dt / 3.0)), 1.0));
}

@compute @workgroup_size(8, 8, 1)
fn multiscatter_lut(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= MULTISCATTER_SIZE) {
        return;
    }
    let x = vec2<f32>(id.xy) / vec2<f32>(MULTISCATTER_SIZE - 1u);
    let mu_s = x.x * 2.0 - 1.0;
    let r = air_bottom() + x.y * (air_top() - air_bottom());
    let origin = vec3<f32>(0.0, r, 0.0);
    let sun = vec3<f32>(sqrt(max(1.0 - mu_s * mu_s, 0.0)), mu_s, 0.0);
    let isotropic = 1.0 / (4.0 * PI);
    var l2 = vec3<f32>(0.0);
    var f_ms = vec3<f32>(0.0);
    for (var k = 0u; k < MULTISCATTER_DIRECTIONS; k++) {
        let d = fibonacci_direction(k, MULTISCATTER_DIRECTIONS);
        let end = air_ray_end(origin, d);
        let dt = end.x / f32(MULTISCATTER_STEPS);
        var tau = vec3<f32>(0.0);
        for (var i = 0u; i < MULTISCATTER_STEPS; i++) {
            let p = origin + d * (dt * (f32(i) + 0.5));
            let rp = length(p);
            let air = air_at(rp - air_bottom());
            let t = exp(-(tau + 0.5 * air.extinction * dt));
            let s = air.rayleigh + vec3<f32>(air.mie);
            l2 += t * s * isotropic * sun_transmittance(rp, dot(p / rp, sun)) * dt;
            f_ms += t * s * dt;
            tau += air.extinction * dt;
        }
        if end.y > 0.5 {
            let g = origin + d * end.x;
            l2 += exp(-tau) * ground_radiance_sun(dot(normalize(g), sun));
        }
    }
    let w = 1.0 / f32(MULTISCATTER_DIRECTIONS);
    let psi = (l2 * w) / max(vec3<f32>(1.0) - f_ms * w, vec3<f32>(1e-6));
    textureStore(multiscatter_lut_out, id.xy, vec4<f32>(psi, 1.0));
}

// The sky-view table's elevation of coordinate v for a camera whose horizon lies at
// elevation `horizon` (radians, <= 0): v = 0.5 is the horizon, the texels crowd toward it as
// the square of the distance in v.
fn sky_view_elevation(v: f32, horizon: f32) -> f32 {
    if v >= 0.5 {
        let a = 2.0 * v - 1.0;
        return horizon + (0.5 * PI - horizon) * a * a;
    }
    let a = 1.0 - 2.0 * v;
    return horizon - (horizon + 0.5 * PI) * a * a;
}

fn sky_view_v(elevation: f32, horizon: f32) -> f32 {
    if elevation >= horizon {
        return 0.5 + 0.5 * sqrt(saturate((elevation - horizon) / (0.5 * PI - horizon)));
    }
    return 0.5 - 0.5 * sqrt(saturate((horizon - elevation) / (horizon + 0.5 * PI)));
}

// Elevation of the horizon seen from radius r.
fn horizon_elevation(r: f32) -> f32 {
    return -acos(clamp(air_bottom() / r, -1.0, 1.0));
}

// The sun's azimuth about the zenith (radians, from +x toward +z).
fn sun_azimuth() -> f32 {
    let s = frame.sun_direction;
    return atan2(s.z, s.x);
}

@compute @workgroup_size(8, 8, 1)
fn sky_view_lut(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= SKY_VIEW_SIZE) {
        return;
    }
    let x = vec2<f32>(id.xy) / vec2<f32>(SKY_VIEW_SIZE - 1u);
    let origin = camera_air_origin();
    let elevation = sky_view_elevation(x.y, horizon_elevation(origin.y));
    // Azimuth relative to the sun in [0, pi]: the sky is symmetric about the sun's vertical.
    let phi = sun_azimuth() + x.x * PI;
    let d = vec3<f32>(cos(elevation) * cos(phi), sin(elevation), cos(elevation) * sin(phi));
    textureStore(sky_view_out, id.xy, vec4<f32>(sky_along(origin, d), 1.0));
}

// The sky's radiance (per unit sun illuminance) seen from `origin` (km, planet centre at the
// origin) along unit `d`, the lit ground included where the ray meets it: SKY_VIEW_STEPS of
// `integrate_air` to where the ray leaves the air. The sky-view table's texels from the
// camera, and the path tracer's environment from a path's last collision.
fn sky_along(origin: vec3<f32>, d: vec3<f32>) -> vec3<f32> {
    let end = air_ray_end(origin, d);
    let sun = frame.sun_direction;
    let s = integrate_air(origin, d, end.x, SKY_VIEW_STEPS, sun);
    return with_ground(s, origin, d, end.x, sun, end.y > 0.5);
}

// The sky's radiance (per unit sun illuminance) seen from camera-relative `rel` (m) along
// unit `d` (`sky_along` from that point; `sun_through_air`'s coordinates).
fn sky_from(rel: vec3<f32>, d: vec3<f32>) -> vec3<f32> {
    return sky_along(vec3<f32>(rel.x, rel.y + frame.planet_radius, rel.z) * 1e-3, d);
}

// The sky's radiance (per unit sun illuminance) seen from the camera along unit `d`: the
// sky-view table, ground included.
fn sky_view(d: vec3<f32>) -> vec3<f32> {
    let origin = camera_air_origin();
    let elevation = asin(clamp(d.y, -1.0, 1.0));
    var delta = atan2(d.z, d.x) - sun_azimuth();
    delta = abs(delta - 2.0 * PI * round(delta / (2.0 * PI)));
    let x = vec2<f32>(delta / PI, sky_view_v(elevation, horizon_elevation(origin.y)));
    return lut_bilinear(sky_view_in, x, SKY_VIEW_SIZE).rgb;
}

// The view direction through the centre of aerial froxel column `c` (of AERIAL_SIDE^2).
fn aerial_ray(c: vec2<u32>) -> vec3<f32> {
    let ndc = (vec2<f32>(c) + 0.5) / f32(AERIAL_SIDE) * 2.0 - 1.0;
    let tan_half = frame.tan_half_fov;
    let aspect = frame.aspect;
    return normalize(frame.camera_forward
        + frame.camera_right * (ndc.x * tan_half * aspect)
        - frame.camera_up * (ndc.y * tan_half));
}

// Froxel column (x, y) marches its 32 slices in order; slice z is stored at texel
// (z * 32 + x, y), holding the light scattered toward the camera over the first (z + 1) km
// (rgb) and the mean transmittance over them (a).
@compute @workgroup_size(8, 8, 1)
fn aerial_perspective(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= vec2<u32>(AERIAL_SIDE)) {
        return;
    }
    let d = aerial_ray(id.xy);
    let origin = camera_air_origin();
    let end = air_ray_end(origin, d);
    let sun = frame.sun_direction;
    let cos_theta = dot(d, sun);
    let phase_r = phase_rayleigh(cos_theta);
    let phase_m = phase_cornette_shanks_air(cos_theta, frame.mie_g);
    var radiance = vec3<f32>(0.0);
    var tau = vec3<f32>(0.0);
    // Four midpoint steps a slice, stopping where the ray leaves the air or meets the ground.
    let sub = 4u;
    for (var z = 0u; z < AERIAL_SLICES; z++) {
        for (var k = 0u; k < sub; k++) {
            let t0 = AERIAL_SLICE_KM * (f32(z) + f32(k) / f32(sub));
            let dt = max(min(AERIAL_SLICE_KM / f32(sub), end.x - t0), 0.0);
            let p = origin + d * (t0 + 0.5 * dt);
            let r = length(p);
            let mu_s = dot(p / r, sun);
            let air = air_at(r - air_bottom());
            let t_view = exp(-(tau + 0.5 * air.extinction * dt));
            let inscatter = sun_transmittance(r, mu_s) * (air.rayleigh * phase_r + vec3<f32>(air.mie * phase_m))
                + multiscatter(r, mu_s) * (air.rayleigh + vec3<f32>(air.mie));
            radiance += t_view * inscatter * dt;
            tau += air.extinction * dt;
        }
        let t = exp(-tau);
        textureStore(aerial_out, vec2<u32>(z * AERIAL_SIDE + id.x, id.y),
                     vec4<f32>(radiance, (t.r + t.g + t.b) / 3.0));
    }
}

// Aerial perspective at pixel `pixel` for depth `depth_m`: (in-scattered light per unit sun
// illuminance, mean transmittance), interpolated in the froxel grid and between slices (0 m
// is no air: nothing scattered, transmittance 1).
fn aerial(pixel: vec2<u32>, depth_m: f32) -> vec4<f32> {
    let uv = (vec2<f32>(pixel) + 0.5) / vec2<f32>(frame.size);
    // Froxel centres sit at (c + 0.5) / side.
    let f = clamp(uv * f32(AERIAL_SIDE) - 0.5, vec2<f32>(0.0), vec2<f32>(f32(AERIAL_SIDE - 1u)));
    let c0 = min(vec2<u32>(floor(f)), vec2<u32>(AERIAL_SIDE - 1u));
    let c1 = min(c0 + 1u, vec2<u32>(AERIAL_SIDE - 1u));
    let w = f - vec2<f32>(c0);
    // Slice z holds depth (z + 1) km; depth 0 is the camera.
    let s = clamp(depth_m * 1e-3 / AERIAL_SLICE_KM, 0.0, f32(AERIAL_SLICES));
    let z1 = min(u32(ceil(s)), AERIAL_SLICES);
    let z0 = select(0u, z1 - 1u, z1 > 0u);
    let ws = s - f32(z0);
    var near = vec4<f32>(0.0, 0.0, 0.0, 1.0);
    if z0 > 0u {
        near = aerial_texel(c0, c1, w, z0 - 1u);
    }
    var far = vec4<f32>(0.0, 0.0, 0.0, 1.0);
    if z1 > 0u {
        far = aerial_texel(c0, c1, w, z1 - 1u);
    }
    return mix(near, far, ws);
}

fn aerial_texel(c0: vec2<u32>, c1: vec2<u32>, w: vec2<f32>, z: u32) -> vec4<f32> {
    let o = z * AERIAL_SIDE;
    let a = mix(textureLoad(aerial_in, vec2<u32>(o + c0.x, c0.y), 0), textureLoad(aerial_in, vec2<u32>(o + c1.x, c0.y), 0), w.x);
    let b = mix(textureLoad(aerial_in, vec2<u32>(o + c0.x, c1.y), 0), textureLoad(aerial_in, vec2<u32>(o + c1.x, c1.y), 0), w.x);
    return mix(a, b, w.y);
}

// Texel (i, j) holds the cosine-weighted mean radiance of the lower (j = 0, from below) or
// upper (j = 1, from above) hemisphere seen from the cloud layer's bottom, sky and lit ground,
// per unit sun illuminance, for a sun of zenith cosine t |t| there (t = 2 i / 63 - 1,
// sky_ambient_x): the irradiance through a horizontal surface over pi, the clouds' ambient
// light. The diffuse light inside a layer is fed by the fluxes through its boundaries (as the
// octaves' mu0 says for the sun), so the light near the horizon, which crosses the layer
// lengthwise, counts for little. With the mean over the whole sphere a dawn's deck was lit by
// the glow along the horizon: 2.3 times brighter than the path tracer (docs/fit). A uniform
// environment gives the same ambient either way.
// Both hemispheres from the bottom: the light from above includes the air between the
// layer's clouds, which the sun lights too (the path tracer's paths see the sky from where
// they leave the clouds, inside the layer). Under a low sun that air's light is the reddened
// sun's: against the path tracer (256 paths a pixel, its sky term alone, split by the
// direction the paths left in) the light from above of `dawn`'s dense deck was 0.92 / 0.87 /
// 0.79 (red / green / blue) of the upper hemisphere seen from the layer's top, `sunset`'s
// 1.51 / 1.38 / 1.17. Seen from the bottom, the presets' mean FLIP went from 0.0449 to 0.0437
// (`dawn` 0.058 to 0.052, `noon` 0.043 to 0.040; from half-way up, 0.0441) and the training
// scenes' from 0.0446 to 0.0444. The lower hemisphere stays at the bottom: seen from half-way
// up as well, `dawn`'s deck was 1.10 times the truth's brightness (FLIP 0.080).
// By the sun's angle, not for the camera's place: the sun's zenith angle changes by a degree
// every 111 km, and a twilight sky by much more than that degree's share of its light:
// computed above the camera, the ambient of `dusk`'s clouds toward the afterglow, tens of
// kilometres off, was a third to a half too dark against the path tracer's (whose paths see
// the sky from where they leave the clouds). The table so depends on the air and the layer's
// bottom alone.
@compute @workgroup_size(8, 8, 1)
fn sky_ambient(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= SKY_AMBIENT_SUNS || id.y >= 2u {
        return;
    }
    let top = id.y == 1u;
    let t = f32(id.x) / f32(SKY_AMBIENT_SUNS - 1u) * 2.0 - 1.0;
    let mu_s = sign(t) * t * t;
    let sun = vec3<f32>(sqrt(max(1.0 - mu_s * mu_s, 0.0)), mu_s, 0.0);
    let origin = vec3<f32>(0.0, air_bottom() + frame.cloud_bottom * 1e-3, 0.0);
    var sum = vec3<f32>(0.0);
    var weights = 0.0;
    // Fibonacci directions run from the zenith down: the first half is the upper hemisphere.
    let half = AMBIENT_DIRECTIONS / 2u;
    let first = select(half, 0u, top);
    for (var k = first; k < first + half; k++) {
        let d = fibonacci_direction(k, AMBIENT_DIRECTIONS);
        let end = air_ray_end(origin, d);
        let s = integrate_air(origin, d, end.x, AMBIENT_STEPS, sun);
        let w = abs(d.y);
        sum += w * with_ground(s, origin, d, end.x, sun, end.y > 0.5);
        weights += w;
    }
    textureStore(sky_ambient_out, id.xy, vec4<f32>(sum / weights, 1.0));
}

// The sun's light (per unit illuminance at the top of the air) reaching a cloud sample at
// `rel` (m, relative to the ground below the camera): 1 without the physical sky.
fn sun_through_air(rel: vec3<f32>) -> vec3<f32> {
    if !physical_sky() {
        return vec3<f32>(1.0);
    }
    let q = vec3<f32>(rel.x, rel.y + frame.planet_radius, rel.z) * 1e-3;
    let r = length(q);
    return sun_transmittance(r, dot(q / r, frame.sun_direction));
}

// The sky-ambient table's column coordinate (0 to 1) of a sun of zenith cosine `mu`: the
// square root of |mu|, so that the columns lie densest at the horizon, where the sky's light
// changes fastest with the sun's angle (texel i holds mu = t |t|, t = 2 i / 63 - 1: 0.7
// degrees apart at a sun 2 degrees up, 1.8 with mu spread evenly). Linear in mu, the table
// blended a dawn's sun 2 degrees up with 0.9 and 2.7 degrees: `dawn` measured FLIP 0.052
// against 0.049 now (the presets' mean 0.0437 against 0.0434; the training scenes, none under
// a sun below 3 degrees in the physical sky, unchanged).
fn sky_ambient_x(mu: f32) -> f32 {
    return 0.5 + 0.5 * sign(mu) * sqrt(abs(mu));
}

// The clouds' ambient light at height fraction `h` of the main layer under the physical sky,
// at camera-relative `rel` (m): the sky-ambient table at the sun's zenith cosine there, times
// the sun's illuminance and the ambient strength.
fn sky_ambient_light(h: f32, rel: vec3<f32>) -> vec3<f32> {
    let q = vec3<f32>(rel.x, rel.y + frame.planet_radius, rel.z);
    let x = sky_ambient_x(dot(normalize(q), frame.sun_direction));
    let size = vec2<u32>(SKY_AMBIENT_SUNS, 2u);
    let bottom = lut_bilinear(sky_ambient_in, vec2<f32>(x, 0.0), size).rgb;
    let top = lut_bilinear(sky_ambient_in, vec2<f32>(x, 1.0), size).rgb;
    return mix(bottom, top, h) * frame.sun_illuminance * frame.ambient_strength;
}
