// The lit ground under the physical sky: the sky's irradiance on it and the clouds' shadows
// on it.
//
// - ground irradiance (64x1): the irradiance the sky (not the sun's disc) gives a horizontal
//   ground per unit sun illuminance, by the sun's zenith cosine: the cosine-weighted integral
//   of the sky's radiance over the upper hemisphere (Bruneton and Neyret 2008's irradiance
//   table, for one altitude). The ground's light is albedo / pi times sun plus sky. It depends
//   on the air only, so it is computed when the air changes.
// - cloud shadow (128x128): the transmittance of the key light's way through every cloud layer
//   from the ground, on a square 40 km wide centred below the camera, every frame (it follows
//   the wind, the sun and the camera). A transmittance map and not a Beer shadow map
//   (Hillaire 2016: front depth, mean extinction and maximum optical depth, to be evaluated
//   at any depth): the only receiver is the ground, at one height, so the transmittance there
//   is the whole answer, with no reconstruction error. Its texels are 313 m, finer than a
//   cumulus; the shadow fades out over the outer quarter of the square, where the map ends.

@group(0) @binding(38) var ground_irradiance_in: texture_2d<f32>;
@group(0) @binding(39) var ground_irradiance_out: texture_storage_2d<rgba32float, write>;
@group(0) @binding(40) var cloud_shadow_in: texture_2d<f32>;
@group(0) @binding(41) var cloud_shadow_out: texture_storage_2d<r32float, write>;
@group(0) @binding(43) var host_shadow_out: texture_storage_2d<r32float, write>;

const GROUND_IRRADIANCE_SIZE: u32 = 64u;
const GROUND_IRRADIANCE_DIRECTIONS: u32 = 128u; // over the sphere; the upper half counts
const SHADOW_SIZE: u32 = 128u;
const SHADOW_HALF_EXTENT: f32 = 20000.0;        // m
const SHADOW_FADE_START: f32 = 0.75;            // of the half extent
const SHADOW_STEPS: u32 = 16u;                  // per layer crossed
// The host's map (its geometry's shadows, `Clouds::cloud_shadow`): 64 steps a layer are
// within 0.004 of the converged column where 16 are 0.09 off (cumulus under a noon sun).
const HOST_SHADOW_STEPS: u32 = 64u;

// Texel i of the irradiance table holds the sun's zenith cosine 2 i / (size - 1) - 1.
@compute @workgroup_size(8, 8, 1)
fn ground_irradiance(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= GROUND_IRRADIANCE_SIZE || id.y >= 1u {
        return;
    }
    let mu_s = f32(id.x) / f32(GROUND_IRRADIANCE_SIZE - 1u) * 2.0 - 1.0;
    let sun = vec3<f32>(sqrt(max(1.0 - mu_s * mu_s, 0.0)), mu_s, 0.0);
    // A metre above the ground, so that no upward ray starts below it.
    let origin = vec3<f32>(0.0, air_bottom() + 0.001, 0.0);
    var sum = vec3<f32>(0.0);
    for (var k = 0u; k < GROUND_IRRADIANCE_DIRECTIONS; k++) {
        let d = fibonacci_direction(k, GROUND_IRRADIANCE_DIRECTIONS);
        if d.y <= 0.0 {
            continue;
        }
        let end = air_ray_end(origin, d);
        sum += integrate_air(origin, d, end.x, AMBIENT_STEPS, sun).radiance * d.y;
    }
    let e = sum * (4.0 * PI / f32(GROUND_IRRADIANCE_DIRECTIONS));
    textureStore(ground_irradiance_out, id.xy, vec4<f32>(e, 1.0));
}

// The sky's irradiance on the ground for a sun of zenith cosine mu_s.
fn sky_irradiance(mu_s: f32) -> vec3<f32> {
    let x = vec2<f32>(mu_s * 0.5 + 0.5, 0.0);
    return lut_bilinear(ground_irradiance_in, x, vec2<u32>(GROUND_IRRADIANCE_SIZE, 1u)).rgb;
}

// Light leaving the lit, diffuse ground where the sun's zenith cosine is mu_s, sun and sky.
fn ground_radiance(mu_s: f32) -> vec3<f32> {
    return ground_radiance_sun(mu_s) + frame.ground_albedo / PI * sky_irradiance(mu_s);
}

// The ground point of shadow-map texel `c`, relative to the ground below the camera (m): on
// the planet's surface, texel i at (2 i / (size - 1) - 1) times the half extent.
fn shadow_ground_point(c: vec2<u32>) -> vec3<f32> {
    let xz = (vec2<f32>(c) / f32(SHADOW_SIZE - 1u) * 2.0 - 1.0) * SHADOW_HALF_EXTENT;
    let rp = frame.planet_radius;
    let s2 = dot(xz, xz);
    // sqrt(Rp^2 - s^2) - Rp without cancellation.
    let y = -s2 / (sqrt(max(rp * rp - s2, 0.0)) + rp);
    return vec3<f32>(xz.x, y, xz.y);
}

@compute @workgroup_size(8, 8, 1)
fn cloud_shadow(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= vec2<u32>(SHADOW_SIZE)) {
        return;
    }
    textureStore(cloud_shadow_out, id.xy, vec4<f32>(shadow_transmittance(id.xy, SHADOW_STEPS), 0.0, 0.0, 1.0));
}

// The same map for the host's geometry, with more steps (`host-shadow`, the `shadow` flag).
@compute @workgroup_size(8, 8, 1)
fn host_cloud_shadow(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= vec2<u32>(SHADOW_SIZE)) {
        return;
    }
    textureStore(host_shadow_out, id.xy, vec4<f32>(shadow_transmittance(id.xy, HOST_SHADOW_STEPS), 0.0, 0.0, 1.0));
}

// The key light's transmittance from the ground at shadow-map texel `c` up through every
// cloud layer, `steps` midpoint steps a layer.
fn shadow_transmittance(c: vec2<u32>, steps: u32) -> f32 {
    let rel = shadow_ground_point(c);
    let sun = frame.sun_direction;
    let rp = frame.planet_radius;
    let up = normalize(vec3<f32>(rel.x, rel.y + rp, rel.z));
    var tau = 0.0;
    // Where the key light is below the ground's horizon the ground is unlit anyway.
    if dot(up, sun) > 0.0 {
        let cam_xz = frame.camera_position.xz;
        // Not counted: the counters measure the march's work, the same with and without the
        // physical sky.
        var counters = Counters(0u, 0u, 0u, 0u);
        for (var i = 0u; i < layer_count(); i++) {
            let l = cloud_layer(i);
            // From below a shell, the far root is where the ray leaves it upward.
            let start = max(ray_shell_from(rel, 0.0, sun, l.bottom).t1, 0.0);
            let end = ray_shell_from(rel, 0.0, sun, l.top).t1;
            let dt = (end - start) / f32(steps);
            if !(dt > 0.0) {
                continue;
            }
            for (var k = 0u; k < steps; k++) {
                let q = rel + sun * (start + (f32(k) + 0.5) * dt);
                let p = vec3<f32>(q.x + cam_xz.x, q.y, q.z + cam_xz.y);
                tau += layer_density(p, altitude_of(q), l, &counters) * dt;
            }
        }
    }
    let sigma_t = frame.scattering + frame.absorption;
    return exp(-sigma_t * tau);
}

// The clouds' transmittance of the key light at ground point `rel` (m, relative to the ground
// below the camera): the map, fading to 1 toward its edge and 1 beyond it.
fn ground_shadow(rel: vec3<f32>) -> f32 {
    let edge = max(abs(rel.x), abs(rel.z)) / SHADOW_HALF_EXTENT;
    if edge >= 1.0 {
        return 1.0;
    }
    let x = rel.xz / (2.0 * SHADOW_HALF_EXTENT) + 0.5;
    let t = lut_bilinear(cloud_shadow_in, x, vec2<u32>(SHADOW_SIZE)).r;
    return mix(t, 1.0, smoothstep(SHADOW_FADE_START, 1.0, edge));
}

// The part of the sky-view table's ground light (per unit key-light illuminance) along `view`
// from the camera at radius `r` (km) that the clouds' shadow takes away: the ground's sun
// term at the point the ray meets, times the air's transmittance back to the camera
// (Bruneton 2017: the ratio of two transmittances to the top), times the shadow's share.
fn ground_shadow_loss(view: vec3<f32>, r: f32) -> vec3<f32> {
    let t = distance_to_ground(r, view.y);
    let cam_alt = max(frame.camera_position.y, 0.0);
    let shadow = ground_shadow(view * (t * 1000.0) + vec3<f32>(0.0, cam_alt, 0.0));
    if shadow >= 1.0 {
        return vec3<f32>(0.0);
    }
    let r_g = air_bottom();
    // Zenith cosines at the ground point of the view ray and of the sun (Bruneton 2008).
    let mu_g = clamp((r * view.y + t) / r_g, -1.0, 1.0);
    let mu_s = clamp((r * frame.sun_direction.y + t * dot(view, frame.sun_direction)) / r_g, -1.0, 1.0);
    let t_view = min(transmittance_to_top(r_g, -mu_g) / max(transmittance_to_top(r, -view.y), vec3<f32>(1e-20)),
                     vec3<f32>(1.0));
    return (1.0 - shadow) * t_view * ground_radiance_sun(mu_s);
}
