// Composite: a simple analytic sky and sun disk behind the clouds, the clouds over it,
// exposure, the ACES fitted tone curve and gamma (seed 001), to an 8-bit image.

@group(0) @binding(9) var cloud_in: texture_2d<f32>;                          // march output
@group(0) @binding(10) var image_out: texture_storage_2d<rgba8unorm, write>; // display image
@group(0) @binding(37) var depth_in: texture_2d<f32>;                         // clouds' depth (m), 0 where none

// Sky radiance along unit `d` for a camera at altitude `alt`: a zenith-to-horizon gradient
// scaled by the sun's illuminance and elevation, a forward glow around the sun, and a dark
// ground below the horizon. Deliberately simple (DESIGN: a simple analytic sky first).
fn sky_radiance(d: vec3<f32>, alt: f32) -> vec3<f32> {
    let sun = frame.sun_direction.xyz;
    let e = frame.sun_illuminance.rgb;
    let day = saturate(sun.y * 4.0 + 0.3);
    if hits_ground(vec3<f32>(0.0, alt, 0.0), alt, d) {
        let ground_albedo = vec3<f32>(0.035, 0.035, 0.03);
        return ground_albedo * (e * max(sun.y, 0.0) / PI + 0.05 * e * day);
    }
    let zenith = vec3<f32>(0.018, 0.04, 0.1);
    let horizon = vec3<f32>(0.07, 0.085, 0.11);
    let up = saturate(d.y);
    let gradient = mix(horizon, zenith, sqrt(up));
    // Warm the horizon as the sun sets (longer light paths redden it).
    let sunset = (1.0 - day * 0.8) * pow(1.0 - up, 6.0) * vec3<f32>(0.25, 0.1, 0.0);
    let glow = phase_hg(dot(d, sun), 0.76) * 0.02;
    return e * (gradient * day + sunset * saturate(sun.y * 10.0 + 1.0) + glow * day);
}

// Radiance of the sun's disk: illuminance over its solid angle 2 pi (1 - cos r).
fn sun_disk(d: vec3<f32>) -> vec3<f32> {
    let cos_r = frame.sun_direction.w;
    if dot(d, frame.sun_direction.xyz) < cos_r {
        return vec3<f32>(0.0);
    }
    return frame.sun_illuminance.rgb / (2.0 * PI * max(1.0 - cos_r, 1e-6));
}

// The clouds in the physical sky: the sky-view table (ground included) and the sun's disc
// through the air behind them; in front of them the air between the camera and their depth
// (aerial perspective), which dims their light and adds its own. Where a cloud leaves
// transmittance a, the sky behind it shows through as a, and the air in front of the cloud
// stands for the rest: L = a S + (1 - a) S_ap + T_ap C (Hillaire 2020, section 5.4's use of
// the aerial-perspective volume on opaque surfaces, with partly transparent clouds).
fn physical_composite(pixel: vec2<u32>, view: vec3<f32>, cloud: vec4<f32>) -> vec3<f32> {
    let e = frame.sun_illuminance.rgb;
    let r = camera_air_origin().y;
    var sky = sky_view(view) * e;
    if !meets_ground(r, view.y) {
        sky += sun_disk(view) * transmittance_to_top(r, view.y);
    }
    var radiance = sky * cloud.a;
    if cloud.a < 1.0 {
        let ap = aerial(pixel, textureLoad(depth_in, pixel, 0).r);
        radiance += ap.rgb * e * (1.0 - cloud.a) + cloud.rgb * ap.a;
    }
    return radiance;
}

// ACES filmic curve fitted by Narkowicz (seed 001), input pre-exposed so 1 maps to ~0.8.
fn aces_fitted(x: vec3<f32>) -> vec3<f32> {
    let a = 2.51;
    let b = 0.03;
    let c = 2.43;
    let d = 0.59;
    let e = 0.14;
    return clamp((x * (a * x + b)) / (x * (c * x + d) + e), vec3<f32>(0.0), vec3<f32>(1.0));
}

// Exposure, tone curve and gamma of a pixel's radiance, to the display image.
fn store_display(pixel: vec2<u32>, radiance: vec3<f32>) {
    let exposed = radiance * frame.camera_right.w;
    let display = pow(aces_fitted(exposed), vec3<f32>(1.0 / 2.2));
    textureStore(image_out, pixel, vec4<f32>(display, 1.0));
}

@compute @workgroup_size(8, 8, 1)
fn composite(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.counts.xy) {
        return;
    }
    let pixel = id.xy;
    let view = view_ray(pixel);
    let alt = frame.camera_position.y;
    let cloud = textureLoad(cloud_in, pixel, 0);
    var background = sky_radiance(view, alt);
    if !hits_ground(vec3<f32>(0.0, alt, 0.0), alt, view) {
        background += sun_disk(view);
    }
    store_display(pixel, background * cloud.a + cloud.rgb);
}

// The same in the physical sky (plan option `physical_sky`).
@compute @workgroup_size(8, 8, 1)
fn composite_physical(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.counts.xy) {
        return;
    }
    let pixel = id.xy;
    let cloud = textureLoad(cloud_in, pixel, 0);
    store_display(pixel, physical_composite(pixel, view_ray(pixel), cloud));
}
