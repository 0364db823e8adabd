// Composite: a simple analytic sky and sun disk behind the clouds, the clouds over it,
// exposure, the ACES fitted tone curve and gamma (seed 001), to an 8-bit image.

@group(0) @binding(9) var cloud_in: texture_2d<f32>;                          // march output
@group(0) @binding(10) var image_out: texture_storage_2d<rgba8unorm, write>; // display image
@group(0) @binding(44) var hdr_out: texture_storage_2d<rgba16float, write>;   // HDR output, before the host's target
@group(0) @binding(37) var depth_in: texture_2d<f32>;                         // clouds' depth (m), 0 where none

// Sky radiance along unit `d` for a camera at altitude `alt`: a zenith-to-horizon gradient
// scaled by the sun's illuminance and elevation, a forward glow around the sun, and a dark
// ground below the horizon. Deliberately simple (DESIGN: a simple analytic sky first).
fn sky_radiance(d: vec3<f32>, alt: f32) -> vec3<f32> {
    let sun = frame.sun_direction;
    let e = frame.sun_illuminance;
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
    let cos_r = frame.sun_cos_radius;
    if dot(d, frame.sun_direction) < cos_r {
        return vec3<f32>(0.0);
    }
    return frame.sun_illuminance / (2.0 * PI * max(1.0 - cos_r, 1e-6));
}

// The clouds in the physical sky: the sky-view table (the lit ground included, with the
// clouds' shadows on it) and the sun's disc
// through the air behind them; in front of them the air between the camera and their depth
// (aerial perspective), which dims their light and adds its own. Where a cloud leaves
// transmittance a, the sky behind it shows through as a, and the air in front of the cloud
// stands for the rest: L = a S + (1 - a) S_ap + T_ap C (Hillaire 2020, section 5.4's use of
// the aerial-perspective volume on opaque surfaces, with partly transparent clouds).
// With light shafts the air in front of the clouds and behind them lacks what the clouds'
// shadows take from it (`light_shafts`). The rainbow, in the rain below the clouds, adds in
// front of them (not yet over the host's geometry).
fn physical_composite(pixel: vec2<u32>, view: vec3<f32>, cloud: vec4<f32>) -> vec3<f32> {
    let surface = has_surface(pixel);
    let shafts = composite_shafts(pixel, view, cloud.a, surface);
    var sky = surface_radiance();
    var bow = vec3<f32>(0.0);
    if !surface {
        sky = max(physical_background(pixel, view) - shafts.all * frame.sun_illuminance, vec3<f32>(0.0));
        bow = rainbow_radiance(view) * frame.sun_illuminance;
    }
    if frame.rain_shafts <= 0.0 {
        return sky * cloud.a + physical_over(pixel, cloud, shafts.front) + bow;
    }
    // The rain shafts: in front of everything from below the rain's top, behind the clouds
    // (over the sky and ground only) from above it.
    let veil = rain_veil(pixel, view);
    if rain_in_front() {
        return through_rain(veil, sky * cloud.a + physical_over(pixel, cloud, shafts.front)) + bow;
    }
    return through_rain(veil, sky) * cloud.a + physical_over(pixel, cloud, shafts.front) + bow;
}

// What shows behind the clouds where the host has no geometry: the sky-view table, the lit
// ground below the horizon, and the sun, moon and stars above it.
fn physical_background(pixel: vec2<u32>, view: vec3<f32>) -> vec3<f32> {
    let e = frame.sun_illuminance;
    let r = camera_air_origin().y;
    var sky = sky_view(view) * e;
    if meets_ground(r, view.y) {
        // The table's ground is lit everywhere; where the clouds shade it, less.
        sky = max(sky - ground_shadow_loss(view, r) * e, vec3<f32>(0.0));
    } else {
        var space = night_sky(pixel, view);
        if (frame.flags & FLAG_MOONLIT) == 0u {
            space += sun_disk(view);
        }
        sky += space * transmittance_to_top(r, view.y);
    }
    return sky;
}

// The clouds' light in front of the background, and the air between the camera and them:
// (1 - a) S_ap + T_ap C, the air's light less `shaded` (per unit sun illuminance: what the
// clouds' shadows take from it, `ShaftLoss::front`).
fn physical_over(pixel: vec2<u32>, cloud: vec4<f32>, shaded: vec3<f32>) -> vec3<f32> {
    if cloud.a >= 1.0 {
        return vec3<f32>(0.0);
    }
    let ap = aerial(pixel, textureLoad(depth_in, pixel, 0).r);
    let air = max(ap.rgb - shaded, vec3<f32>(0.0));
    return air * frame.sun_illuminance * (1.0 - cloud.a) + cloud.rgb * ap.a;
}

// Light shafts (crepuscular rays, `atmosphere.light_shafts`). The sky-view and
// aerial-perspective tables hold the air's light as if all of it saw the sun; where a cloud
// shades the air between the camera and what it sees, that air scatters none of the sun's
// light (single scattering: its multiple scattering, lit from the whole sky, stays), and the
// shade shows as dark shafts beside the lit air between them. The loss is the sun's single
// scattering (the tables' own terms, Hillaire 2020 eq. 11's first) times each point's shade,
// integrated along the view ray: what Bruneton and Neyret 2008's light shafts
// remove through a shadow volume's length, here sampled from the cloud-shadow map. A point's
// transmittance toward the sun is the map's at its projection along the sun onto the ground:
// exact below the cloud layers, where shafts are seen; inside them the shade thins linearly to
// none at their top (the clouds' own march lights the air between them there). The map covers
// 40 km around the camera, so a low sun's shafts fade where they project beyond it.
const SHAFT_STEPS: u32 = 48u;
const SHAFT_RANGE_KM: f32 = 32.0;   // as far as the aerial-perspective table reaches
const SHAFT_SALT: u32 = 0x5AF7u;    // the dither's own stream of hash_unit
const SHAFT_MIN_SUN_Y: f32 = 1e-3;  // the sun's least height (its direction's y) with shafts

// The sun's single scattering by the air that the clouds shade, per unit sun illuminance:
// `front` over the ray's first `split_m` m (the clouds' depth), `all` to `end_km`.
struct ShaftLoss {
    front: vec3<f32>,
    all: vec3<f32>,
}

// The shafts of the composite at `pixel` along `view` (none without FLAG_LIGHT_SHAFTS): over
// the host's geometry the air up to the clouds' depth only, which is all of the air the
// composite draws there; elsewhere to where the ray meets the ground or leaves the air.
fn composite_shafts(pixel: vec2<u32>, view: vec3<f32>, alpha: f32, surface: bool) -> ShaftLoss {
    if (frame.flags & FLAG_LIGHT_SHAFTS) == 0u || (surface && alpha >= 1.0) {
        return ShaftLoss(vec3<f32>(0.0), vec3<f32>(0.0));
    }
    let depth = textureLoad(depth_in, pixel, 0).r;
    var end_km = depth * 1e-3;
    if !surface {
        end_km = air_ray_end(camera_air_origin(), view).x;
    }
    return light_shafts(pixel, view, depth, end_km);
}

// The shade (1 - transmittance toward the sun) at camera-relative `rel` (m) between the
// layers' lowest bottom and highest top `span` (m).
fn shaft_shade(rel: vec3<f32>, span: vec2<f32>) -> f32 {
    if rel.y >= span.y {
        return 0.0;
    }
    let sun = frame.sun_direction;
    let shade = 1.0 - ground_shadow(rel - sun * (rel.y / sun.y));
    return shade * (1.0 - saturate((rel.y - span.x) / (span.y - span.x)));
}

// SHAFT_STEPS even segments over the ray's first SHAFT_RANGE_KM (and, looking up, not past the
// layers' top), one sample a segment at a dithered place (the same for every segment of a
// pixel, and every frame), so that the segments' banding turns to fine noise; a segment the
// split cuts counts toward `front` by the part of it in front.
fn light_shafts(pixel: vec2<u32>, view: vec3<f32>, split_m: f32, end_km: f32) -> ShaftLoss {
    var loss = ShaftLoss(vec3<f32>(0.0), vec3<f32>(0.0));
    let sun = frame.sun_direction;
    let span = layers_span();
    let cam_alt = max(frame.camera_position.y, 0.0);
    var end = min(end_km, SHAFT_RANGE_KM);
    if view.y > 0.0 {
        end = min(end, max(span.y - cam_alt, 0.0) * 1e-3 / view.y);
    }
    // A sun within 0.06 degrees of the horizon projects every shaded point off the map (and
    // the projection's division would overflow).
    if sun.y <= SHAFT_MIN_SUN_Y || !(end > 0.0) {
        return loss;
    }
    let origin = camera_air_origin();
    let cos_theta = dot(view, sun);
    let phase_r = phase_rayleigh(cos_theta);
    let phase_m = phase_cornette_shanks_air(cos_theta, frame.mie_g);
    let dt = end / f32(SHAFT_STEPS);
    let offset = hash_unit(pixel, SHAFT_SALT);
    let split_km = split_m * 1e-3;
    var tau = vec3<f32>(0.0);
    for (var k = 0u; k < SHAFT_STEPS; k++) {
        let t = (f32(k) + offset) * dt;
        let p = origin + view * t;
        let r = length(p);
        let air = air_at(r - air_bottom());
        let shade = shaft_shade(view * (t * 1000.0) + vec3<f32>(0.0, cam_alt, 0.0), span);
        if shade > 0.0 {
            let t_view = exp(-(tau + air.extinction * (offset * dt)));
            let single = sun_transmittance(r, dot(p / r, sun)) * (air.rayleigh * phase_r + vec3<f32>(air.mie * phase_m));
            let lost = t_view * single * (shade * dt);
            loss.all += lost;
            // The segment's part in front of the split, so that the front moves smoothly
            // with the clouds' depth (a sample flipping sides would flicker).
            loss.front += lost * saturate((split_km - f32(k) * dt) / dt);
        }
        tau += air.extinction * dt;
    }
    return loss;
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

// The host's geometry as the display image shows it (the CLI and examples; a host composites
// the clouds over its own shading instead): a grey surface (albedo 0.3) facing up, lit as the
// analytic sky's ground is.
fn surface_radiance() -> vec3<f32> {
    let sun = frame.sun_direction;
    let e = frame.sun_illuminance;
    let day = saturate(sun.y * 4.0 + 0.3);
    return vec3<f32>(0.3) * (e * max(sun.y, 0.0) / PI + 0.05 * e * day);
}

// Exposure, tone curve, saturation and gamma of a pixel's radiance, to the display image.
fn store_display(pixel: vec2<u32>, radiance: vec3<f32>) {
    let exposed = radiance * frame.exposure;
    let display = pow(saturated(aces_fitted(exposed)), vec3<f32>(1.0 / 2.2));
    textureStore(image_out, pixel, vec4<f32>(display, 1.0));
}

// The tone-mapped colour `c` with its saturation scaled by `frame.saturation` (`post.saturation`,
// seed 001's "Saturability"): moved away from its luminance (Rec. 709 weights) by that factor,
// within [0, 1]. At 1 it is `c` itself, bit for bit.
fn saturated(c: vec3<f32>) -> vec3<f32> {
    let s = frame.saturation;
    if s == 1.0 {
        return c;
    }
    let y = dot(c, vec3<f32>(0.2126, 0.7152, 0.0722));
    return clamp(vec3<f32>(y) + (c - vec3<f32>(y)) * s, vec3<f32>(0.0), vec3<f32>(1.0));
}

@compute @workgroup_size(8, 8, 1)
fn composite(
    @builtin(global_invocation_id) id: vec3<u32>,
    @builtin(local_invocation_index) local: u32,
) {
    var flare = vec3<f32>(0.0);
    if frame.lens_flare_intensity > 0.0 {
        flare = shared_flare_source(local, analytic_sun());
    }
    if any(id.xy >= frame.size) {
        return;
    }
    let pixel = id.xy;
    let cloud = textureLoad(cloud_in, pixel, 0);
    var background = surface_radiance();
    if !has_surface(pixel) {
        background = analytic_background(view_ray(pixel));
    }
    var radiance = background * cloud.a + cloud.rgb;
    if frame.rain_shafts > 0.0 {
        let veil = rain_veil(pixel, view_ray(pixel));
        if rain_in_front() {
            radiance = through_rain(veil, radiance);
        } else {
            radiance = through_rain(veil, background) * cloud.a + cloud.rgb;
        }
    }
    if frame.lens_flare_intensity > 0.0 {
        radiance += lens_flare(pixel, flare);
    }
    store_display(pixel, radiance);
}

// The sun's illuminance reaching the camera through the analytic sky's air (which does not
// dim it): 0 below the horizon.
fn analytic_sun() -> vec3<f32> {
    let alt = frame.camera_position.y;
    if hits_ground(vec3<f32>(0.0, alt, 0.0), alt, frame.sun_direction) {
        return vec3<f32>(0.0);
    }
    return frame.sun_illuminance;
}

// What shows behind the clouds in the analytic sky where the host has no geometry: the sky's
// gradient, and the sun's disc above the horizon.
fn analytic_background(view: vec3<f32>) -> vec3<f32> {
    let alt = frame.camera_position.y;
    var background = sky_radiance(view, alt);
    if !hits_ground(vec3<f32>(0.0, alt, 0.0), alt, view) {
        background += sun_disk(view);
    }
    return background;
}

// The same in the physical sky (plan option `physical_sky`).
@compute @workgroup_size(8, 8, 1)
fn composite_physical(
    @builtin(global_invocation_id) id: vec3<u32>,
    @builtin(local_invocation_index) local: u32,
) {
    var flare = vec3<f32>(0.0);
    if frame.lens_flare_intensity > 0.0 {
        // The sun's light through the air to the camera: 0 below the horizon.
        let air = sun_transmittance(camera_air_origin().y, frame.sun_direction.y);
        flare = shared_flare_source(local, frame.sun_illuminance * air);
    }
    if any(id.xy >= frame.size) {
        return;
    }
    let pixel = id.xy;
    let cloud = textureLoad(cloud_in, pixel, 0);
    var radiance = physical_composite(pixel, view_ray(pixel), cloud);
    if frame.lens_flare_intensity > 0.0 {
        radiance += lens_flare(pixel, flare);
    }
    store_display(pixel, radiance);
}

// The HDR output (`Clouds::render_hdr`): linear radiance, premultiplied (the host adds it over
// its image times alpha), and transmittance in alpha, before any exposure or tone curve.
// Without FLAG_HDR_SKY it is the march's radiance and transmittance as they are: the host draws
// its own sky. With it (the host asked for the sky, `Clouds::set_hdr_sky`), wherever the host
// has no geometry the sky is drawn behind the clouds and the pixel is opaque (alpha 0): the same
// radiance the display image tone-maps, so a host that draws no sky of its own gets Stratus's.
@compute @workgroup_size(8, 8, 1)
fn hdr_composite(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.size) {
        return;
    }
    let pixel = id.xy;
    let cloud = textureLoad(cloud_in, pixel, 0);
    var out = cloud;
    if (frame.flags & FLAG_HDR_SKY) != 0u && !has_surface(pixel) {
        let view = view_ray(pixel);
        var background = analytic_background(view);
        if frame.rain_shafts > 0.0 && !rain_in_front() {
            // From above the rain's top: the rain veils the sky and ground behind the clouds.
            background = through_rain(rain_veil(pixel, view), background);
        }
        out = vec4<f32>(background * cloud.a + cloud.rgb, 0.0);
    }
    textureStore(hdr_out, pixel, rain_over_hdr(pixel, out));
}

// The same in the physical sky: with FLAG_HDR_SKY the air in front of the clouds dims and
// adds to them over the host's geometry too, as it does over the sky.
@compute @workgroup_size(8, 8, 1)
fn hdr_composite_physical(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.size) {
        return;
    }
    let pixel = id.xy;
    let cloud = textureLoad(cloud_in, pixel, 0);
    var out = cloud;
    if (frame.flags & FLAG_HDR_SKY) != 0u {
        if has_surface(pixel) {
            let shafts = composite_shafts(pixel, view_ray(pixel), cloud.a, true);
            out = vec4<f32>(physical_over(pixel, cloud, shafts.front), cloud.a);
        } else {
            out = vec4<f32>(physical_composite(pixel, view_ray(pixel), cloud), 0.0);
        }
    }
    textureStore(hdr_out, pixel, rain_over_hdr(pixel, out));
}

// The HDR output with the rain shafts in front (premultiplied radiance, transmittance): where
// the camera is below the rain's top the rain veils whatever the host draws behind too, so it
// dims the transmittance; from above it the rain lies behind the clouds, over the background:
// the sky's where the output holds it (`hdr_composite`, `physical_composite`), the host's own
// otherwise, left to the host. A pixel that already holds the physical sky (alpha 0) got it in
// `physical_composite`; the analytic sky's gets it here.
fn rain_over_hdr(pixel: vec2<u32>, out: vec4<f32>) -> vec4<f32> {
    let has_sky = (frame.flags & FLAG_HDR_SKY) != 0u && !has_surface(pixel);
    if frame.rain_shafts <= 0.0 || !rain_in_front() || (physical_sky() && has_sky) {
        return out;
    }
    let veil = rain_veil(pixel, view_ray(pixel));
    return vec4<f32>(through_rain(veil, out.rgb), out.a * veil.transmittance);
}
