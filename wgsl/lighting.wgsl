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
    let g = frame.phase_g * scale;
    switch frame.phase_model {
        case PHASE_TWO_LOBE_HG: {
            // Two lobes for the silver lining (seed 001): forward g and backward g2.
            let g2 = frame.phase_g2 * scale;
            return mix(phase_hg(cos_theta, g), phase_hg(cos_theta, g2), frame.phase_blend);
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
// sampled at each segment's midpoint; the march ends where it leaves the layer. The layers
// above add `optical_depth_above`.
// Toward a sun a few degrees up the light crosses tens of kilometres of layer, which the
// march does not see: far_optical_depth stands in for that stretch.
fn sun_optical_depth(rel: vec3<f32>, p: vec3<f32>, l: Layer, counters: ptr<function, Counters>) -> f32 {
    return segment_optical_depth(rel, p, l, frame.sun_direction, frame.first_light_step,
                                 frame.light_step_growth, frame.light_steps, true, counters);
}

// The sun ray's optical depth through the layers above layer `l`: each one it crosses adds
// ABOVE_SAMPLES midpoint samples of equal stretches of the crossing, the Beer shadow of a high
// deck on the clouds below, which the few kilometres of the light march would not reach. One
// sample at the crossing's middle missed a stratus deck, whose cloud fills the lowest quarter
// of its layer: under `weather fog`'s deck the fog measured FLIP 0.230 (2.78 times the truth's
// brightness where dense), with four samples 0.149 (1.34), `weather mist` 0.095 and 0.074;
// with eight 0.161 and 0.068 (these two states chose the count: docs/fit-log.md).
const ABOVE_SAMPLES: u32 = 4u;

fn optical_depth_above(rel: vec3<f32>, p: vec3<f32>, l: Layer, counters: ptr<function, Counters>) -> f32 {
    let sun = frame.sun_direction;
    let sigma_t = frame.scattering + frame.absorption;
    var tau = 0.0;
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
        let step = (exit.t1 - enter.t1) / f32(ABOVE_SAMPLES);
        for (var k = 0u; k < ABOVE_SAMPLES; k++) {
            let s = enter.t1 + (f32(k) + 0.5) * step;
            (*counters).light += 1u;
            tau += layer_density(p + sun * s, altitude_of(rel + sun * s), above, counters)
                * sigma_t * step;
        }
    }
    return tau;
}

// Optical depth from `rel` (world position `p`) along unit `d` in layer `l`: `steps` segments,
// the first `first` metres long, each `growth` times the one before, density sampled at each
// segment's midpoint (its detail erosion only if `with_detail`), one light sample each; the
// march ends where it leaves the layer. The sun's light march and the octaves' column.
fn segment_optical_depth(rel: vec3<f32>, p: vec3<f32>, l: Layer, d: vec3<f32>, first: f32,
                         growth: f32, steps: u32, with_detail: bool,
                         counters: ptr<function, Counters>) -> f32 {
    let sigma_t = frame.scattering + frame.absorption;
    var seg = first;
    var dist = 0.0;
    var tau = 0.0;
    for (var i = 0u; i < steps; i++) {
        let s = dist + 0.5 * seg;
        let alt = altitude_of(rel + d * s);
        if alt > l.top || alt < l.bottom {
            break;
        }
        (*counters).light += 1u;
        tau += layer_density_with(p + d * s, alt, l, with_detail, counters) * sigma_t * seg;
        dist += seg;
        seg *= growth;
    }
    return tau;
}

// The octaves' column in a closed deck (octave_optical_depth): three equal steps straight up
// from the sample to the layer's top, of the density without its detail erosion, which shapes
// edges metres across while multiply scattered light gathers over kilometres. Four steps
// fitted a training mean of 0.0446 against three's 0.0448 (`storm` 0.042 against 0.044) for
// 10.5% more march time on `storm` against 7.5% (lavapipe, 256x144).
const COLUMN_STEPS: u32 = 3u;

// The octaves' optical depth at a sample of layer `l` whose sun ray has optical depth `tau`.
// In a closed deck the truth's multiply scattered sun light follows the cloud above the
// sample (its height in the layer, correlation 0.92 over `storm`'s upper third against the
// path tracer; the vertical optical depth above it, -0.89), which the slant sun ray, kilometres
// long through a thick deck, passes by: over that part of `storm` the sun ray's optical depth
// was 100-112 at every pixel while the truth's light varied three times as much as the
// march's. Deep in a thick plane-parallel layer the diffuse light falls with the optical depth
// from the top (two-stream theory, Meador and Weaver 1980), whatever the sun's angle once the
// direct beam is spent: diffuse light crosses a slab along an effective path about 1.66 times
// the vertical (the diffusivity factor, Elsasser 1942). So in a deck the octaves see the
// vertical column above the sample, to the layer's top, times s (steep_light_scale, fitted: 1.5),
// mixed in with weight m w (m: steep_light, fitted: 1, the column and the layers above alone;
// 0 = off), w = (coverage - 0.8) / 0.1 clamped, the layer's weight as a closed deck (set by
// hand: `storm`'s 0.9 gets 1, `stratocumulus-overcast`'s 0.8 none). The layers above the deck keep their part
// of `tau` (`above`): the column stands in for the deck's own cloud alone (without them the
// mist under `weather mist`'s cumulus took no shade from them in its octaves: FLIP 0.098, with
// them 0.095, at one sample per layer above). Decks only: broken cloud's light comes in
// through the sides as well (side light). Against the 8192-path truths (docs/fit) the column
// took the training mean from 0.0525 to 0.0448 and `storm` from 0.055 to 0.044; over mu0 (the
// direct beam's slant) it fitted 0.0522 (the storm deck under a 25-degree sun 0.047 to 0.102),
// over mu0^(1/2) 0.0477 (both with four steps). A steeper march of two steps toward
// normalize(sun + up), scaled by a fitted 3.6 for the column it did not reach, had fitted
// 0.0525 (`storm` 0.055).
fn octave_optical_depth(rel: vec3<f32>, p: vec3<f32>, l: Layer, tau: f32, above: f32,
                        counters: ptr<function, Counters>) -> f32 {
    let w = saturate((l.coverage - 0.8) / 0.1);
    let m = frame.steep_light * w;
    // Not below a weight of 1e-3: a layer of coverage 0.8 (`stratocumulus-overcast`'s) got a
    // weight of about 1e-7 from f32 rounding on lavapipe, and the march's work for nothing.
    if w < 1e-3 || m <= 0.0 || frame.light_steps == 0u {
        return tau;
    }
    let up = normalize(vec3<f32>(rel.x, rel.y + frame.planet_radius, rel.z));
    // From inside the layer's top sphere the ray leaves it through the far root.
    let top = ray_shell_from(rel, altitude_of(rel), up, l.top);
    let len = select(0.0, top.t1, top.hit && top.t1 > 0.0);
    let column = segment_optical_depth(rel, p, l, up, len / f32(COLUMN_STEPS), 1.0,
                                       COLUMN_STEPS, false, counters);
    return mix(tau, frame.steep_light_scale * column + above, m);
}

// The far shadow: optical depth of the sun ray's stretch inside layer `l` beyond the light
// march's reach (its segments' total length), taken statistically instead of sampled. Broken
// cloud along a line is a binary Markov mixture (Levermore and Pomraning 1986): with cloud
// fraction f and opaque clouds of mean chord lambda, the clear gaps have mean length
// lambda (1 - f) / f and a ray of length L gets through with probability exp(-L f / ((1 - f)
// lambda)). The stretch is cut into four quarters, each its own mixture: f is the weather
// map's coverage times the height profile at the quarter's middle (a cumulus layer's thin top
// lets a low sun's light through; the map says where the cloud fields and the gaps between
// them lie), lambda the fitted chord (far_chord; 0 = off). Toward a sun a few degrees up,
// the light crosses tens of kilometres of layer; sampling them with five more growing light
// steps (to about 100 km) cost 45% more density evaluations on `dawn` and made the fit's
// training error worse (0.0570 to 0.0608, README). The weather map is a 2D texture read, not
// a density evaluation: against the converged quadrature of the same model (single
// scattering) it took `dawn` from FLIP 0.038 to 0.026 and `sunset` from 0.070 to 0.050 over
// the layer's mean coverage.
// The stretch ends where the sun ray enters an anvil's band, at `band` (anvil_band_entry;
// anvil_optical_depth samples the band). A cirrus layer's share (l.cirrus) takes none: the
// mixture's clouds are opaque, and cirrus an optical depth or so through.
fn far_optical_depth(rel: vec3<f32>, p: vec3<f32>, l: Layer, band: f32) -> f32 {
    let chord = frame.far_chord;
    if chord <= 0.0 || frame.light_steps == 0u {
        // Off, or no light march: 0 light steps leave the clouds unshadowed.
        return 0.0;
    }
    let reach = light_march_reach();
    let sun = frame.sun_direction;
    let exit = ray_shell_from(rel, altitude_of(rel), sun, l.top);
    var end = exit.t1;
    if band >= 0.0 {
        end = min(end, max(band, reach));
    }
    let len = end - reach;
    if !exit.hit || !(len > 0.0) {
        return 0.0;
    }
    var tau = 0.0;
    for (var i = 0u; i < 4u; i++) {
        let t = reach + (f32(i) + 0.5) * 0.25 * len;
        let h = saturate(layer_height(l, altitude_of(rel + sun * t)));
        let w = sample_weather(p + sun * t, l);
        let f = min(w.coverage * height_signal(h / w.top, l.cloud_type), 0.95);
        tau += 0.25 * len * f / ((1.0 - f) * chord);
    }
    return tau * (1.0 - l.cirrus);
}

// The light march's reach: its segments' total length (m).
fn light_march_reach() -> f32 {
    let growth = frame.light_step_growth;
    let steps = f32(frame.light_steps);
    if growth == 1.0 {
        return frame.first_light_step * steps;
    }
    return frame.first_light_step * (pow(growth, steps) - 1.0) / (growth - 1.0);
}

// Where the sun ray from camera-relative `rel` enters layer `l`'s anvil band (height
// fraction ANVIL_BASE and up): 0 from inside it, -1 where the layer has no anvil or the ray
// does not reach the band.
fn anvil_band_entry(rel: vec3<f32>, l: Layer) -> f32 {
    if anvil_weight(l) <= 0.0 {
        return -1.0;
    }
    let alt = altitude_of(rel);
    let base = mix(l.bottom, l.top, ANVIL_BASE);
    if alt >= base {
        return 0.0;
    }
    // From below the band's sphere the ray leaves it through the far root.
    let enter = ray_shell_from(rel, alt, frame.sun_direction, base);
    if !enter.hit || !(enter.t1 > 0.0) {
        return -1.0;
    }
    return enter.t1;
}

// An anvil's shade: the sun ray's optical depth through layer `l`'s anvil band beyond the
// light march's reach, ABOVE_SAMPLES midpoint samples of the density (the layers above's
// sampling). Under a storm's anvil the light march (3.2 km at the defaults) ends kilometres
// below the plate and the far shadow took it for broken cloud of the fitted chord, so the
// octaves, which do not read the far shadow, saw none of it and single scattering little:
// `weather thunderstorm` measured FLIP 0.186 against its truth, the dense cloud under the
// anvil 1.15 times the truth's brightness (docs/fit-log.md). A plate is a slab, not broken
// cloud: sampled, its tens of optical depths reach both (FLIP 0.186 still, but the dense
// cloud 0.85 of the truth's brightness, RMSE 0.159 to 0.114). The octaves see all of it. A
// share of it alone, for light that would come around the plate's edges and through its gaps,
// had been chosen while the precipitation darkening also dimmed the sky's light (0.75: FLIP
// 0.136 against 0.139 for all); since the darkening takes the sun's light alone, shares of
// 0.5, 0.75, 1 and 1.25 measure 0.142, 0.126, 0.118 and 0.118 (docs/fit-log.md), so the
// octaves take the plate's shade as single scattering does. Only layers with an anvil pay:
// four density evaluations per lit sample.
fn anvil_optical_depth(rel: vec3<f32>, p: vec3<f32>, l: Layer, band: f32,
                       counters: ptr<function, Counters>) -> f32 {
    if band < 0.0 || frame.light_steps == 0u {
        return 0.0;
    }
    let sun = frame.sun_direction;
    let exit = ray_shell_from(rel, altitude_of(rel), sun, l.top);
    let start = max(band, light_march_reach());
    if !exit.hit || !(exit.t1 > start) {
        return 0.0;
    }
    let sigma_t = frame.scattering + frame.absorption;
    let step = (exit.t1 - start) / f32(ABOVE_SAMPLES);
    var tau = 0.0;
    for (var k = 0u; k < ABOVE_SAMPLES; k++) {
        let s = start + (f32(k) + 0.5) * step;
        (*counters).light += 1u;
        tau += layer_density(p + sun * s, altitude_of(rel + sun * s), l, counters) * sigma_t * step;
    }
    return tau;
}

// Sun light scattered toward the viewer per unit illuminance and unit sigma_s: single
// scattering plus the octaves F build sum_{i>=1} a^i phase(cos, c^i) / (1 + b^i tau_oct) (a:
// contribution, b: extinction, c: eccentricity; F their feeding, below; `build` from
// octave_buildup; `tau_oct` from octave_optical_depth, `tau` the sun ray's; fitted to the path
// tracer, docs/fit). `far` (far_optical_depth) shadows
// single scattering beyond the light march and the side light; `coverage` is the region's
// cover about the sample (density.wgsl regional_coverage: the weather map's, or on convective
// cells the cells' share), `view_y` the view ray's vertical component (diffuse_limb), `h` the
// sample's height fraction in its cloud (vertical_anisotropy, downward_dimming: in its layer
// over the profile's top, density.wgsl cloud_top_fraction; a stratus fills the lowest third of
// its layer, and in the layer's fraction the top of `weather fog`'s ground fog was taken for
// its base, its light looking down dimmed away: FLIP 0.114, with the cloud's 0.094),
// `layer_coverage` its layer's coverage and `above` the sun ray's optical depth through the
// layers above it (deck_escape).
// Wrenninge's octaves attenuate by exp(-b^i tau). The diffuse light deep in a thick layer falls
// off far more slowly: as 1 / (1 + (3/4)(1 - g) tau) in two-stream theory for conservative
// scattering (Meador and Weaver 1980), and the path tracer agrees (storm's bases were 2.3 times
// too dark). The two forms agree to first order in tau, where clouds are thin.
// Returns the whole and, apart, the octaves' part of it (the march gives that part a forward
// lobe once it knows the pixel's transmittance: forward_lobe).
struct SunScattering {
    total: f32,
    octaves: f32,
}

fn sun_scattering(cos_theta: f32, view_y: f32, tau: f32, tau_oct: f32, far: f32, build: f32,
                  coverage: f32, h: f32, layer_coverage: f32, above: f32) -> SunScattering {
    let a = frame.ms_contribution;
    let b = frame.ms_extinction;
    let c = frame.ms_eccentricity;
    let octaves = min(frame.octaves, MAX_OCTAVES);
    var octave_sum = 0.0;
    var ka = 1.0;
    var kb = 1.0;
    var kc = 1.0;
    for (var i = 0u; i < octaves; i++) {
        ka *= a;
        kb *= b;
        kc *= c;
        octave_sum += ka * phase(cos_theta, kc) / (1.0 + kb * tau_oct);
    }
    // The octaves stand for the multiply scattered, diffuse light of the cloud, which the sun's
    // flux into it feeds: through a deck's top, E mu0 per unit area (mu0 the cosine of the
    // sun's zenith angle; without it the octaves lit a sunset as brightly as noon). A broken
    // layer's clouds also take light through their sides, in proportion to sin(zenith) and to
    // the clear share (1 - coverage) around them, unless far cloud shadows them (`far`).
    let mu0 = saturate(frame.sun_direction.y);
    let side = sqrt(max(1.0 - mu0 * mu0, 0.0)) * (1.0 - saturate(coverage)) * exp(-far);
    var feed = mu0 + frame.side_light * side;
    // Multiply scattered light leaks out of a small cloud through its sides but stays in a
    // deck: the octaves scale with the region's coverage (to a fitted power) as well as
    // with the local density (`build`). Against the path tracer the octaves alone lit high-sun
    // cumulus up to 1.4 times too brightly while decks stayed 7% too dark (docs/fit).
    if frame.coverage_exponent > 0.0 {
        feed *= pow(max(coverage, 1e-6), frame.coverage_exponent);
    }
    feed *= diffuse_limb(view_y, coverage) * vertical_anisotropy(view_y, coverage, h)
        * deck_escape(mu0, layer_coverage, above);
    feed *= downward_dimming(view_y, coverage, h, tau * mu0);
    var octaves_part = feed * build * octave_sum;
    var total = phase(cos_theta, 1.0) * exp(-tau - far) + octaves_part;
    if (frame.flags & FLAG_BEER_POWDER) != 0u {
        // Beer-Powder (HZD): in-scattering builds up with depth into the cloud, darkening
        // the thin edges. Kept <= 1 so it only removes energy.
        let powder = 1.0 - exp(-frame.powder_strength * tau);
        total *= powder;
        octaves_part *= powder;
    }
    return SunScattering(total, octaves_part);
}

// The pixel transmittance at and above which the forward lobe has its full strength.
const FORWARD_LOBE_THIN: f32 = 0.1;

// The octaves' forward lobe through thin cloud: the factor on a pixel's octave light, given
// the cosine between its view ray and the sun and its transmittance. The octaves' own
// eccentricities (c^i g, c = 0.15 before this term) make their light nearly isotropic, right
// for the diffuse light of a thick cloud but not for light that crossed a thin one: scattered
// a few times, it still leans toward the sun (the eccentricity of n scatterings of HG(g) is
// g^n). Against the path tracer's truth (8192 paths a pixel, 20 scenes) the octave light of
// pixels of transmittance 0.05-0.5 was 1.70 times the truth's looking away from the sun
// (cosine below -0.6) and 0.59 times looking toward it (above 0.6), and 1.52 and 0.49 at
// 0.5-0.95, while in pixels below 0.05 it was 0.90-0.97 at every angle (docs/fit). A view
// sample does not know how thin the cloud is; the pixel's transmittance, once the march
// ends, does. So 1 + w (4 pi HG(cos, g_f) - 1): its mean over the sphere is 1 (light moved
// between directions, none added), w = k min(T / 0.1, 1) (k: frame.forward_lobe, 0 = off;
// g_f: .y). Thresholds of 0.05, 0.2 and 0.5 and g_f of 0.3-0.6 fitted within 0.0006 of
// each other. Per pixel, not per sample: a phase function and a second accumulator.
fn forward_lobe(cos_theta: f32, transmittance: f32) -> f32 {
    let k = frame.forward_lobe;
    if k <= 0.0 {
        return 1.0;
    }
    let w = k * saturate(transmittance / FORWARD_LOBE_THIN);
    return 1.0 + w * (4.0 * PI * phase_hg(cos_theta, frame.forward_lobe_g) - 1.0);
}

// The diffuse light leaving a thick plane-parallel layer is limb-darkened: brighter along the
// layer's normal than at grazing angles, I(mu) proportional to 1 + (3/2) mu in the Eddington
// approximation (Chandrasekhar 1950, Radiative Transfer, ch. 1), mu the cosine of the angle to
// the normal. The octaves know no normal, and against the path tracer (8192 paths a pixel)
// decks seen 20-40 degrees up were darker, relative to the truth, than near the horizon
// (`stratocumulus-overcast` 0.86-0.91 of its brightness against 0.94-1.04, `storm` 0.76-0.95
// against 0.96-1.10). Here with a fitted strength k (limb_darkening; 0 = off) in place of 3/2,
// normalised to keep the flux through the layer ((1 + k mu) / (1 + 2k/3)), mu = |view_y| the
// view ray's cosine to the vertical, and weighted by the region's coverage: a deck is a
// layer, a small cumulus has no one normal. The factor is 1 at mu = 2/3: it darkens grazing
// views and brightens steep ones, and the refit raised the octaves' a with it (1.15 to 1.2).
// Fitted k = 0.5 took the training scenes' mean FLIP from 0.0505 to 0.0486 and the presets'
// from 0.0583 to 0.0572 (that fit's docs/fit; since vertical_anisotropy, which takes the
// up-down part, k = 0.25 and a = 1.15); one abs, a division and a mix per lit sample.
fn diffuse_limb(view_y: f32, coverage: f32) -> f32 {
    let k = frame.limb_darkening;
    let layer = (1.0 + k * abs(view_y)) / (1.0 + 2.0 * k / 3.0);
    return mix(1.0, layer, saturate(coverage));
}

// The octaves' vertical anisotropy: the factor on their light at a sample of height fraction
// `h` in its layer, seen along a view ray of vertical component `view_y` (up positive). In a
// layer lit from above the diffuse light's net flux runs down: in two-stream theory for
// conservative scattering the downward flux exceeds the upward one by the same net flux at
// every depth, the upward stream falling to the ground's reflection at the base while near a
// thick layer's top the two are nearly equal (Meador and Weaver 1980). So light seen looking
// up (going down) outshines light seen looking down (going up), most toward the base. The
// octaves know neither stream: diffuse_limb's |view_y| treats up and down alike. Against the
// path tracer (8192 paths a pixel) decks seen from below were 0.86-0.95 of the truth's
// brightness looking 20-40 degrees up (`stratocumulus-overcast`, `storm`), and the layer below
// a camera inside it 1.2-1.3 times it looking down (`inside-layer`). Hence 1 + s view_y
// coverage (1 - h): its mean over the sphere is 1 (no light added), a deck's (coverage) and
// strongest at its base (1 - h, the simplest stand-in for the optical depth below the sample,
// which the march does not know; with s held at 0.5 and the rest refit, no weight by height
// fitted 0.0005 worse). s: frame.vertical_anisotropy (0 = off); one multiply-add per lit
// sample.
fn vertical_anisotropy(view_y: f32, coverage: f32, h: f32) -> f32 {
    return 1.0 + frame.vertical_anisotropy * view_y * saturate(coverage) * (1.0 - saturate(h));
}

// The octaves' dimming looking down: the factor on their light at a sample of height fraction
// `h` whose sun ray's optical depth projected on the vertical is `tau_v` (tau mu0), seen along
// a view ray of vertical component `view_y`. The light going up through a layer falls with the
// cloud above the sample that shields it from the light coming down, which the vertical
// anisotropy's height fraction does not see. Against the path tracer (8192 paths a pixel) a
// camera inside a layer saw the cloud 5-20 degrees below it at 1.15-1.25 times the truth's
// brightness, the octaves 0.61 of the truth's luminance against its 0.46 of multiply
// scattered light, where the vertical anisotropy is 0.97-0.99 (`inside-layer`). Hence 1 - k
// |view_y| coverage (1 - h) tau_v / (tau_v + 1) looking down (k: downward_dimming, fitted, 0 =
// off), clamped at 0: the weights of the vertical anisotropy times the cloud above (0 at a
// cloud's lit top under any sun). Looking up it is 1. One division per lit sample.
fn downward_dimming(view_y: f32, coverage: f32, h: f32, tau_v: f32) -> f32 {
    let k = frame.downward_dimming * max(-view_y, 0.0) * saturate(coverage) * (1.0 - saturate(h));
    return max(1.0 - k * tau_v / (tau_v + 1.0), 0.0);
}

// The octaves' escape from a deck: the factor on their feed for a sun of zenith cosine `mu0`
// over a layer of coverage `layer_coverage`. The diffuse light a thick conservative layer
// lets through its base is (2/3 + mu0) / (4/3 + (1 - g) tau) of the flux mu0 through its top
// in the Eddington approximation (Meador and Weaver 1980): light that enters steeply goes
// deeper before it turns and is likelier to come out of the base than light that enters at a
// grazing angle. The octaves attenuate along the sun ray and do not know that. Against the
// path tracer's truth (8192 paths a pixel) decks were darker under a high sun than under a
// low one: dense cloud 0.95 of the truth's brightness at 45-60 degrees (`stratocumulus,
// high sun`, `stratocumulus-overcast`), 0.97 at 40 (`storm`), 1.02 at 25 (`storm deck`),
// while cumulus stayed at 0.95-0.96 at every elevation. Hence 1 + e w (mu0 - 1/2): the ratio
// (2/3 + mu0) / (2/3 + 1/2) is 1 + (6/7)(mu0 - 1/2), here with a fitted strength e
// (frame.deck_escape, 0 = off) in place of 6/7, 1 at 60 degrees from the zenith, and
// w = layer_coverage^8 (DECK_POWER) the layer's weight as a deck: a closed layer's clouds are
// far wider than they are thick, a broken one's are not. The weather map's coverage at the
// sample does not tell them apart (it is high inside a cumulus as well: weighted by it,
// `denser cumulus` went from FLIP 0.063 to 0.071), nor did the layer's coverage to the 4th
// power (training mean 0.0474 against 0.0453 for the 8th; e = 1.5, before a refit). One power
// and a multiply-add per lit sample.
// e w is held to the Eddington ratio's own 6/7 (DECK_ESCAPE_MAX), which it stands for: the fit
// took e to 2, the top of its range, where `storm`'s coverage of 0.9 (w 0.43) gives 0.86, but a
// full layer (w 1) got 2, 2.3 times the ratio's. No training scene or preset is that full; the
// ground fog of `weather fog` (coverage 1) was lit 1.34 times the truth's brightness where
// dense, FLIP 0.149, and is 1.13 and 0.114 with the bound (`weather mist`'s 0.074 to 0.071; the
// training scene closed to 0.92, w 0.51, 0.040 to 0.042; nothing else moved: docs/fit-log.md).
// Under a layer above, of optical depth `above` along the sun ray, the light that reaches the
// deck's top is only exp(-above) the direct beam; the rest comes diffuse, from every direction
// of the sky above it, and enters as light of zenith cosine DIFFUSE_MU does (the Eddington
// ratio averaged over that light: (2/3 + 2/3) / (4/3 + (1 - g) tau)). So the escape takes
// mix(DIFFUSE_MU, mu0, exp(-above)) for mu0. The ground fog under `weather fog`'s deck (a
// sun 60 degrees up, zenith cosine 0.87, its escape 1.32) was lit 1.15 times the truth's
// brightness where dense, FLIP 0.094; with the diffuse light's 1.14, 1.06 and 0.077
// (`weather mist`, under broken cumulus, 0.070 to 0.072; a single layer does not move:
// docs/fit-log.md).
fn deck_escape(mu0: f32, layer_coverage: f32, above: f32) -> f32 {
    let e = frame.deck_escape;
    let mu = mix(DIFFUSE_MU, mu0, exp(-above));
    return 1.0 + min(e * pow(saturate(layer_coverage), DECK_POWER), DECK_ESCAPE_MAX) * (mu - 0.5);
}

// The power of the layer's coverage that weights the octaves' deck escape (deck_escape).
const DECK_POWER: f32 = 8.0;

// The mean cosine, weighted by the flux, of light arriving alike from every direction of a
// hemisphere (the integral of mu 2 mu over [0, 1]): the zenith cosine the deck escape takes for
// the diffuse light that a layer above has made of the sun's.
const DIFFUSE_MU: f32 = 2.0 / 3.0;

// The most the deck escape's strength may be (deck_escape): the Eddington approximation's 6/7.
const DECK_ESCAPE_MAX: f32 = 0.857142857;

// The share of the octaves at a sample of density `density`: 1 - exp(-sigma_t density l), l
// the build-up length (ms_buildup; 0: 1, Wrenninge's octaves everywhere). Light
// scatters many times only where there is cloud around to scatter it: against the path
// tracer the octaves lit thin wisps and edges up to 2.5 times too brightly while the cores
// stayed too dark (docs/fit, brightness by the truth's transmittance). The local density
// stands for the cloud around the sample; it costs no sample.
fn octave_buildup(density: f32) -> f32 {
    let l = frame.ms_buildup;
    if l <= 0.0 {
        return 1.0;
    }
    return 1.0 - exp(-(frame.scattering + frame.absorption) * density * l);
}

// The share of the octaves a cellular layer's cloudlets keep (`clouds.cellular`, per layer):
// mix(1, CELLULAR_OCTAVES, cellular). A cloudlet a few hundred metres deep and about twice
// that across (density.wgsl: cellular_base) loses its multiply scattered light through its
// top, base and sides sooner than the cumulus and decks the octaves were fitted on. Fed by the
// cloudlets' share of the region (regional_coverage), `type altocumulus` was still lit 1.16 /
// 1.29 / 1.28 times the truth's brightness (dense / mid / thin), FLIP 0.062. The share was
// chosen on that scene alone (0.6, 0.68, 0.75, 0.82, 1: FLIP 0.054, 0.045, 0.044, 0.047,
// 0.062) and checked on `type stratocumulus`, held out: 0.112 to 0.081 (docs/fit-log.md).
// The path tracer knows no octaves: no truth moved.
const CELLULAR_OCTAVES: f32 = 0.75;

fn cellular_octaves(l: Layer) -> f32 {
    return mix(1.0, CELLULAR_OCTAVES, l.cellular);
}

// Ambient light at height fraction `h` (thesis 5.5.3): a gradient from bottom to top colour,
// or under the physical sky the sky's cosine-weighted radiance from below and from above,
// seen from the layer's bottom (the sky-ambient table, for the sun's angle at camera-relative
// `rel`, m).
fn ambient(h: f32, rel: vec3<f32>) -> vec3<f32> {
    if physical_sky() {
        return sky_ambient_light(h, rel);
    }
    return mix(frame.ambient_bottom, frame.ambient_top, h) * frame.ambient_strength;
}

// Height fraction of altitude `alt` in the layer that holds it (ambient and precipitation
// darkening are per layer).
fn height_fraction(alt: f32) -> f32 {
    return saturate(layer_height(cloud_layer(layer_at(alt)), alt));
}

// In-scattered radiance per unit length at a view sample of layer `l`: sigma_s * density *
// (sun + ambient + a lightning flash's light), the sun's and the flash's light darkened toward
// the base of raining clouds (thesis 4.4.1); and, apart, the octaves' part of it. The darkening
// stands for the light a raining cloud's heavier water load takes on its way down to the base;
// the sky's light is not darkened, for the reason the ambient takes no occlusion: in a nearly
// uniform environment a conservative medium's diffuse radiance stays the environment's however
// thick the cloud (docs/fit-log.md). Darkening it as well left the rain states' shaded bases
// darker than the truth's (`weather rain` FLIP 0.0722, `rainbow` 0.0789; with the sun's light
// alone darkened, and the strength chosen again, 0.0606 and 0.0646). The water load is met
// along the light's way through the cloud: a sample the sun ray reaches through little cloud
// (a thin edge, a shaft's side) takes little of it, so the darkening grows with the sun ray's
// optical depth tau as 1 - exp(-tau / PRECIPITATION_DEPTH), in full where the ray meets the
// ground. Chosen by the mean FLIP of `weather rain`, `weather snow` and `weather thunderstorm`
// (the scenes that chose the strength, which stayed 0.6): depths of 4, 6, 8, 10 and 20 measured
// 0.0729, 0.0716, 0.0704, 0.0699 and 0.0723, without the depth 0.0738 (`rain` 0.0606 to
// 0.0577, `snow` 0.0429 to 0.0342, `thunderstorm` 0.1179 to 0.1177; `rainbow`, held out, 0.0646
// to 0.0665: docs/fit-log.md).
const PRECIPITATION_DEPTH: f32 = 10.0;

struct ScatteredLight {
    total: vec3<f32>,
    octaves: vec3<f32>,
}

fn scattered_light(rel: vec3<f32>, p: vec3<f32>, alt: f32, density: f32, view: vec3<f32>,
                   l: Layer, counters: ptr<function, Counters>) -> ScatteredLight {
    let sun = frame.sun_direction;
    let h = saturate(layer_height(l, alt));
    var sun_light = vec3<f32>(0.0);
    var octave_light = vec3<f32>(0.0);
    let weather = sample_weather(p, l);
    // The share of the darkening the sun ray's cloud gives (PRECIPITATION_DEPTH).
    var load = 1.0;
    if !hits_ground(rel, alt, sun) {
        var tau = 0.0;
        var above = 0.0;
        var far = 0.0;
        var tau_oct = 0.0;
        if LIGHT_MARCH {
            above = optical_depth_above(rel, p, l, counters);
            let band = anvil_band_entry(rel, l);
            tau = sun_optical_depth(rel, p, l, counters) + above
                + anvil_optical_depth(rel, p, l, band, counters);
            far = far_optical_depth(rel, p, l, band);
            tau_oct = octave_optical_depth(rel, p, l, tau, above, counters);
        }
        let s = sun_scattering(dot(view, sun), view.y, tau, tau_oct, far,
                               octave_buildup(density) * cellular_octaves(l),
                               regional_coverage(p, l, weather),
                               saturate(h / cloud_top_fraction(l, weather)), l.coverage, above);
        let lit = frame.sun_illuminance * sun_through_air(rel);
        sun_light = lit * s.total;
        octave_light = lit * s.octaves;
        load = 1.0 - exp(-tau / PRECIPITATION_DEPTH);
    }
    let darkening = saturate(1.0 - frame.precipitation_darkening * weather.precipitation * (1.0 - h)
                                   * load);
    let k = frame.scattering * density;
    let dark = darkening * k;
    return ScatteredLight((sun_light + lightning_light(rel)) * dark + ambient(h, rel) * k,
                          octave_light * dark);
}
