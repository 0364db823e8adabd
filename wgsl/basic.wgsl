// The basic ray marcher of the volumetric-cloud tutorials (GPU Pro 7's "Real-Time Volumetric
// Cloudscapes" as popularised in Real-Time Rendering, 4th ed., ch. 14): a measured baseline for
// the model in march.wgsl, drawing the same density field (`cloud_density`, whose base shape
// is the Worley FBM with weights 0.625 / 0.25 / 0.125).
//
// Per view sample at the start of each of `view_steps` equal steps (no jitter), a Riemann sum
//   L += E_sun * BeerPowder(tau_sun) * HG(cos theta, g) * Beer(tau_view) * sigma_s * rho * dt
// where tau_sun is a Riemann sum of the density along the sun ray through the layer
// (`light_steps` equal steps) and Beer-Powder is Schneider's 2 e^-tau (1 - e^-2 tau). What it
// leaves out, the chart measures: no ambient, no multiple scattering, no energy-conserving step
// integral, no early exit.

// The optical depth toward the sun from `rel` (camera-relative, altitude `alt`) to the top of
// the layer, at most three layer thicknesses, in `frame.light_steps` equal Riemann steps.
fn basic_sun_depth(rel: vec3<f32>, alt: f32, counters: ptr<function, Counters>) -> f32 {
    let steps = frame.light_steps;
    if steps == 0u {
        return 0.0;
    }
    let sun = frame.sun_direction;
    let rp = frame.planet_radius;
    let top = frame.cloud_top;
    let thickness = top - frame.cloud_bottom;
    // The sun ray's exit through the top shell, from a point at altitude `alt` (c < 0 inside).
    let exit = solve_sphere(dot(sun, vec3<f32>(rel.x, rel.y + rp, rel.z)), (alt - top) * (alt + top + 2.0 * rp));
    let length = min(max(exit.t1, 0.0), 3.0 * thickness);
    let dt = length / f32(steps);
    let sigma_t = frame.scattering + frame.absorption;
    let cam_xz = frame.camera_position.xz;
    var tau = 0.0;
    for (var i = 1u; i <= steps; i += 1u) {
        (*counters).light += 1u;
        let q = rel + sun * (f32(i) * dt);
        let p = vec3<f32>(q.x + cam_xz.x, q.y, q.z + cam_xz.y);
        tau += sigma_t * cloud_density(p, altitude_of(q), counters) * dt;
    }
    return tau;
}

fn basic_pixel(pixel: vec2<u32>) -> MarchResult {
    let view = view_ray(pixel);
    let cam_alt = frame.camera_position.y;
    let cam_xz = frame.camera_position.xz;
    var counters = Counters(0u, 0u, 0u, 0u);
    count(STAT_PIXELS, 1u);

    var radiance = vec3<f32>(0.0);
    var transmittance = 1.0;
    var depth_sum = 0.0;
    let span = cloud_interval(cam_alt, view);
    if span.kind == RAY_MISSES_LAYER {
        count(STAT_EXIT_MISSED, 1u);
    } else if span.kind == RAY_HITS_GROUND {
        count(STAT_EXIT_GROUND, 1u);
    } else {
        count(STAT_MARCHED, 1u);
        let steps = frame.view_steps;
        let dt = span.length / f32(steps);
        let sigma_s = frame.scattering;
        let sigma_t = sigma_s + frame.absorption;
        let sun_phase = frame.sun_illuminance * phase_hg(dot(view, frame.sun_direction), frame.phase_g);
        for (var i = 0u; i < steps; i += 1u) {
            counters.view_steps += 1u;
            let t = span.start + f32(i) * dt;
            let rel = view * t + vec3<f32>(0.0, cam_alt, 0.0);
            let p = vec3<f32>(rel.x + cam_xz.x, rel.y, rel.z + cam_xz.y);
            let alt = altitude_of(rel);
            let density = cloud_density(p, alt, &counters);
            if density <= 0.0 {
                continue;
            }
            let tau = basic_sun_depth(rel, alt, &counters);
            let beer_powder = 2.0 * exp(-tau) * (1.0 - exp(-2.0 * tau));
            radiance += sun_phase * (beer_powder * transmittance * sigma_s * density * dt);
            let step_t = exp(-sigma_t * density * dt);
            depth_sum += t * transmittance * (1.0 - step_t);
            transmittance *= step_t;
        }
    }

    count(STAT_VIEW_STEPS, counters.view_steps);
    count(STAT_DENSITY, counters.density);
    count(STAT_DETAIL, counters.detail);
    count(STAT_LIGHT, counters.light);
    var depth = 0.0;
    if transmittance < 1.0 {
        depth = depth_sum / (1.0 - transmittance);
    }
    return MarchResult(radiance, transmittance, depth);
}

// Every pixel, every frame (quality.method = "basic").
@compute @workgroup_size(8, 8, 1)
fn march_basic(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.size) {
        return;
    }
    let r = basic_pixel(id.xy);
    textureStore(cloud_out, id.xy, vec4<f32>(r.radiance, r.transmittance));
    textureStore(depth_out, id.xy, vec4<f32>(r.depth, 0.0, 0.0, 0.0));
}
