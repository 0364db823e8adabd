// Light: phase functions, the light march toward the sun, multiple-scattering octaves,
// ambient and precipitation darkening (thesis 5.5, Hillaire 2016, Wrenninge 2013).

// Henyey-Greenstein (thesis eq. 5.4), normalised over the sphere.
fn phase_hg(cos_theta: f32, g: f32) -> f32 {
    let g2 = g * g;
    let denom = max(1.0 + g2 - 2.0 * g * cos_theta, 1e-6);
    return (1.0 - g2) / (4.0 * PI * denom * sqrt(denom));
}

// Cornette-Shanks (thesis eq. 5.5).
fn phase_cornette_shanks(cos_theta: f32, g: f32) -> f32 {
    let g2 = g * g;
    let denom = max(1.0 + g2 - 2.0 * g * cos_theta, 1e-6);
    return 3.0 * (1.0 - g2) * (1.0 + cos_theta * cos_theta)
        / (8.0 * PI * (2.0 + g2) * denom * sqrt(denom));
}

// The scene's phase model with eccentricities scaled by `scale` (c^i for octave i).
fn phase(cos_theta: f32, scale: f32) -> f32 {
    let g = frame.phase.x * scale;
    switch frame.modes.x {
        case PHASE_TWO_LOBE_HG: {
            // Two lobes for the silver lining (seed 001): forward g and backward g2.
            let g2 = frame.phase.y * scale;
            return mix(phase_hg(cos_theta, g), phase_hg(cos_theta, g2), frame.phase.z);
        }
        case PHASE_CORNETTE_SHANKS: {
            return phase_cornette_shanks(cos_theta, g);
        }
        default: {
            return phase_hg(cos_theta, g);
        }
    }
}

// Optical depth toward the sun from `rel` (camera-relative position, world position `p`) in
// layer `l`: `light_steps` segments of exponentially growing length (thesis 5.5.2), density
// sampled at each segment's midpoint; the march ends where it leaves the layer. Each other
// layer above that the sun ray crosses adds one midpoint sample times the length of the
// crossing: the Beer shadow of a high deck on the clouds below, which the few kilometres of
// the light march would not reach.
// Toward a sun a few degrees up the light crosses tens of kilometres of layer, which the
// march does not see. Five more growing segments while the ray is still in the layer (to
// about 100 km) brought `dawn` from FLIP 0.133 to 0.103 against the path tracer, but cost 45%
// more density evaluations there and made the fit's training error worse (0.0570 to 0.0608):
// left out (docs/fit, README).
fn sun_optical_depth(rel: vec3<f32>, p: vec3<f32>, l: Layer, counters: ptr<function, Counters>) -> f32 {
    let sun = frame.sun_direction.xyz;
    let sigma_t = frame.extinction.x + frame.extinction.y;
    let steps = frame.counts.w;
    let growth = frame.march.y;
    var seg = frame.march.z;
    var dist = 0.0;
    var tau = 0.0;
    for (var i = 0u; i < steps; i++) {
        let s = dist + 0.5 * seg;
        let q = rel + sun * s;
        let alt = altitude_of(q);
        if alt > l.top || alt < l.bottom {
            break;
        }
        (*counters).light += 1u;
        tau += layer_density(p + sun * s, alt, l, counters) * sigma_t * seg;
        dist += seg;
        seg *= growth;
    }
    let alt0 = altitude_of(rel);
    for (var j = 0u; j < layer_count(); j++) {
        let above = cloud_layer(j);
        if above.bottom <= l.top {
            continue;
        }
        // From below both spheres, the ray leaves each through its far root.
        let enter = ray_shell_from(rel, alt0, sun, above.bottom);
        let exit = ray_shell_from(rel, alt0, sun, above.top);
        if !enter.hit || !exit.hit || !(exit.t1 > enter.t1) || enter.t1 <= 0.0 {
            continue;
        }
        let s = 0.5 * (enter.t1 + exit.t1);
        (*counters).light += 1u;
        tau += layer_density(p + sun * s, altitude_of(rel + sun * s), above, counters) * sigma_t
            * (exit.t1 - enter.t1);
    }
    return tau;
}

// Sun light scattered toward the viewer per unit illuminance and unit sigma_s: single
// scattering plus the octaves mu0 build sum_{i>=1} a^i phase(cos, c^i) / (1 + b^i tau) (a:
// contribution, b: extinction, c: eccentricity; `build` from octave_buildup; fitted to the
// path tracer, docs/fit).
// Wrenninge's octaves attenuate by exp(-b^i tau). The diffuse light deep in a thick layer falls
// off far more slowly: as 1 / (1 + (3/4)(1 - g) tau) in two-stream theory for conservative
// scattering (Meador and Weaver 1980), and the path tracer agrees (storm's bases were 2.3 times
// too dark). The two forms agree to first order in tau, where clouds are thin.
fn sun_scattering(cos_theta: f32, tau: f32, build: f32) -> f32 {
    let a = frame.multiple_scattering.x;
    let b = frame.multiple_scattering.y;
    let c = frame.multiple_scattering.z;
    let octaves = min(frame.misc.x, MAX_OCTAVES);
    var octave_sum = 0.0;
    var ka = 1.0;
    var kb = 1.0;
    var kc = 1.0;
    for (var i = 0u; i < octaves; i++) {
        ka *= a;
        kb *= b;
        kc *= c;
        octave_sum += ka * phase(cos_theta, kc) / (1.0 + kb * tau);
    }
    // The octaves stand for the multiply scattered, diffuse light of the layer, which the flux
    // through the layer's top feeds: E mu0 for a plane-parallel layer, mu0 the cosine of the
    // sun's zenith angle. The light march sees a few kilometres toward a low sun, not the tens
    // of kilometres of cloud layer its light crosses, so without mu0 the octaves lit a sunset
    // as brightly as noon (measured against the path tracer, docs/fit).
    let mu0 = saturate(frame.sun_direction.y);
    var total = phase(cos_theta, 1.0) * exp(-tau) + mu0 * build * octave_sum;
    if (frame.modes.w & FLAG_BEER_POWDER) != 0u {
        // Beer-Powder (HZD): in-scattering builds up with depth into the cloud, darkening
        // the thin edges. Kept <= 1 so it only removes energy.
        total *= 1.0 - exp(-frame.phase.w * tau);
    }
    return total;
}

// The share of the octaves at a sample of density `density`: 1 - exp(-sigma_t density l), l
// the build-up length (multiple_scattering.w; 0: 1, Wrenninge's octaves everywhere). Light
// scatters many times only where there is cloud around to scatter it: against the path
// tracer the octaves lit thin wisps and edges up to 2.5 times too brightly while the cores
// stayed too dark (docs/fit, brightness by the truth's transmittance). The local density
// stands for the cloud around the sample; it costs no sample.
fn octave_buildup(density: f32) -> f32 {
    let l = frame.multiple_scattering.w;
    if l <= 0.0 {
        return 1.0;
    }
    return 1.0 - exp(-(frame.extinction.x + frame.extinction.y) * density * l);
}

// Ambient light at height fraction `h` (thesis 5.5.3): a gradient from bottom to top colour,
// or under the physical sky the sky's cosine-weighted radiance from below the layer's bottom
// and from above its top (the sky-ambient table).
fn ambient(h: f32) -> vec3<f32> {
    if physical_sky() {
        return sky_ambient_light(h);
    }
    return mix(frame.ambient_bottom.rgb, frame.ambient_top.rgb, h) * frame.ambient_bottom.w;
}

// Height fraction of altitude `alt` in the layer that holds it (ambient and precipitation
// darkening are per layer).
fn height_fraction(alt: f32) -> f32 {
    return saturate(layer_height(cloud_layer(layer_at(alt)), alt));
}

// In-scattered radiance per unit length at a view sample of layer `l`: sigma_s * density *
// (sun + ambient), darkened toward the base of raining clouds (thesis 4.4.1).
fn scattered_light(rel: vec3<f32>, p: vec3<f32>, alt: f32, density: f32, view: vec3<f32>,
                   l: Layer, counters: ptr<function, Counters>) -> vec3<f32> {
    let sun = frame.sun_direction.xyz;
    let h = saturate(layer_height(l, alt));
    var sun_light = vec3<f32>(0.0);
    if !hits_ground(rel, alt, sun) {
        var tau = 0.0;
        if LIGHT_MARCH {
            tau = sun_optical_depth(rel, p, l, counters);
        }
        sun_light = frame.sun_illuminance.rgb * sun_through_air(rel) * sun_scattering(dot(view, sun), tau, octave_buildup(density));
    }
    let weather = sample_weather(p, l);
    let darkening = saturate(1.0 - frame.extinction.z * weather.precipitation * (1.0 - h));
    return frame.extinction.x * density * (sun_light + ambient(h)) * darkening;
}
