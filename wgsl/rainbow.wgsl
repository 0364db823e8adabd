// The rainbow (`[rainbow]`, seed 001's rainbow effect): the primary and secondary bows of
// sunlight in the falling rain below precipitating cloud layers, under the physical sky.
//
// Light leaving a drop after k internal reflections is deviated by D(i) = 2 (i - r) + k (pi - 2 r)
// (incidence i, refraction r, sin i = n sin r). D has a minimum at cos^2 i = (n^2 - 1) /
// ((k + 1)^2 - 1) (Descartes): the bow, at pi - D from the antisolar point for the primary
// (k = 1, about 42 degrees) and D - pi for the secondary (k = 2, about 51 degrees); the primary
// is bright inside, the secondary outside, and Alexander's dark band lies between. Near the
// bow the outgoing wavefront is cubic, so a drop of radius a scatters, per radian of
// deviation, the share of the light that falls on it
//   dP/dtheta = 2 b T_k 2 pi sqrt(s / c) Ai^2(-s eps),   s = (2 pi a / lambda)^(2/3) / c^(1/3)
// (Airy 1838; van de Hulst 1957, section 13.24): eps the angle into the bright side, b = sin i
// the impact parameter, c half of d^2 D / db^2 at the bow, T_k the Fresnel transmission in,
// k reflections and out (the mean of the two polarisations). Far from the bow Ai^2 averages to
// the two geometric rays' 1 / sqrt(c eps), which fixes the scale. Small drops widen and
// overlap the wavelengths' bows into a whitish fog bow; large ones separate them, with
// supernumerary bows inside the primary. Airy theory is good for drops above about 50 um;
// below it, a guide to the shape only.

@group(0) @binding(46) var rainbow_lut_out: texture_storage_2d<rgba32float, write>;
@group(0) @binding(47) var rainbow_lut_in: texture_2d<f32>;

// The table: the bows' phase function (per steradian, per unit extinction of the rain, rgb for
// a white sun) at angles RAINBOW_MIN_DEG to RAINBOW_MAX_DEG from the antisolar point. The
// primary's light fills the sky inside it and the secondary's outside it; Airy theory is a
// bow's neighbourhood's, so both fade out over the table's last RAINBOW_FADE_DEG at either end
// (where they are a few percent of the bows' peaks) instead of ending at an edge.
const RAINBOW_TEXELS: u32 = 1024u;
const RAINBOW_MIN_DEG: f32 = 8.0;
const RAINBOW_MAX_DEG: f32 = 68.0;
const RAINBOW_FADE_DEG: f32 = 10.0;
// The visible spectrum's samples (400-700 nm) and the sun's disc's (Gauss-Chebyshev nodes of
// the second kind: the disc's chord lengths as weights).
const RAINBOW_WAVELENGTHS: u32 = 30u;
const RAINBOW_SUN_TAPS: u32 = 5u;
// The cheap path's three wavelengths (nm), one a channel.
const RAINBOW_RGB_NM: vec3<f32> = vec3<f32>(610.0, 550.0, 465.0);
// The rain's march along a view ray: steps and reach (m).
const RAIN_STEPS: u32 = 32u;
const RAIN_RANGE_M: f32 = 15000.0;
// Moderate rain's extinction (1/m): 3.912 / 7 km, a 7 km visibility by Koschmieder's law.
// `rainbow_moisture` 1 is this much rain under a layer precipitating at 1.
const RAIN_EXTINCTION: f32 = 5.59e-4;
// The moisture profile's peak altitude (m), as the seed describes.
const MOISTURE_PEAK_M: f32 = 2000.0;

// Water's refractive index at `nm`: Cauchy's form A + B / lambda^2 fitted to Hale and Querry
// 1973's 1.339 at 400 nm and 1.331 at 700 nm (within 0.0003 at 500 and 600 nm).
fn water_index(nm: f32) -> f32 {
    return 1.3271 + 1900.0 / (nm * nm);
}

// The Airy function Ai(x) (DLMF 9.4 and 9.7): the Maclaurin series on [-4, 3], the asymptotic
// expansions beyond to their terms in u1 = 5/72, u2 = 385/10368 (and u3 = 85085/2239488 on the
// bright side), within 0.1% at the joins.
fn airy_ai(x: f32) -> f32 {
    if x > 3.0 {
        let z = 2.0 / 3.0 * x * sqrt(x);
        let series = 1.0 - 0.069444444 / z + 0.037133487 / (z * z);
        return exp(-z) / (2.0 * sqrt(PI) * sqrt(sqrt(x))) * series;
    }
    if x < -4.0 {
        let w = -x;
        let z = 2.0 / 3.0 * w * sqrt(w);
        let phase = z - 0.25 * PI;
        let even = 1.0 - 0.037133487 / (z * z);
        let odd = 0.069444444 / z - 0.037993059 / (z * z * z);
        return (cos(phase) * even + sin(phase) * odd) / (sqrt(PI) * sqrt(sqrt(w)));
    }
    let x3 = x * x * x;
    var f = 1.0;
    var g = x;
    var tf = 1.0;
    var tg = x;
    for (var k = 0u; k < 10u; k++) {
        let k3 = 3.0 * f32(k);
        tf *= x3 / ((k3 + 2.0) * (k3 + 3.0));
        tg *= x3 / ((k3 + 3.0) * (k3 + 4.0));
        f += tf;
        g += tg;
    }
    return 0.355028053887817 * f - 0.258819403792807 * g;
}

// The bow of `k` internal reflections in water of index `n`: its angle from the antisolar
// point (rad), and 2 b T_k 2 pi sqrt(1 / c) and c^(-1/3) (see the top of this file).
struct Bow {
    angle: f32,
    scale: f32,
    c_cbrt_inv: f32,
}

fn rainbow_bow(n: f32, k: u32) -> Bow {
    let kf = f32(k);
    let p2 = (kf + 1.0) * (kf + 1.0);
    let cos_i = sqrt((n * n - 1.0) / (p2 - 1.0));
    let sin_i = sqrt(1.0 - cos_i * cos_i);
    let sin_r = sin_i / n;
    let cos_r = sqrt(1.0 - sin_r * sin_r);
    let i = acos(cos_i);
    let r = asin(sin_r);
    let deviation = 2.0 * (i - r) + kf * (PI - 2.0 * r);
    // d^2 D / db^2 = D''(i) / cos^2 i, D''(i) = -2 (k + 1) r''(i).
    let r1 = cos_i / (n * cos_r);
    let r2 = (-sin_i * cos_r + cos_i * sin_r * r1) / (n * cos_r * cos_r);
    let c = -(kf + 1.0) * r2 / (cos_i * cos_i);
    // Fresnel at the surface (the same angles going in and coming out).
    let rs = (cos_i - n * cos_r) / (cos_i + n * cos_r);
    let rp = (n * cos_i - cos_r) / (n * cos_i + cos_r);
    let big_rs = rs * rs;
    let big_rp = rp * rp;
    let t = 0.5 * ((1.0 - big_rs) * (1.0 - big_rs) * pow(big_rs, kf) + (1.0 - big_rp) * (1.0 - big_rp) * pow(big_rp, kf));
    return Bow(abs(PI - deviation), 2.0 * sin_i * t * 2.0 * PI / sqrt(c), pow(c, -1.0 / 3.0));
}

// The primary and secondary bows' phase function at `phi` (rad) from the antisolar point
// (faded out toward the table's ends) for drops of radius `a` (m) at wavelength `nm`: per steradian, per unit extinction of the rain
// (half of a large drop's extinction is diffraction into the forward peak, Q_ext = 2).
fn rainbow_phase(phi: f32, a: f32, nm: f32) -> f32 {
    let deg = degrees(phi);
    let window = smoothstep(RAINBOW_MIN_DEG, RAINBOW_MIN_DEG + RAINBOW_FADE_DEG, deg)
        * (1.0 - smoothstep(RAINBOW_MAX_DEG - RAINBOW_FADE_DEG, RAINBOW_MAX_DEG, deg));
    let n = water_index(nm);
    let x23 = pow(2.0 * PI * a / (nm * 1e-9), 2.0 / 3.0);
    var sum = 0.0;
    for (var k = 1u; k <= 2u; k++) {
        let bow = rainbow_bow(n, k);
        let s = x23 * bow.c_cbrt_inv;
        // Into the bright side: inside the primary, outside the secondary.
        let eps = select(phi - bow.angle, bow.angle - phi, k == 1u);
        let ai = airy_ai(-s * eps);
        sum += bow.scale * sqrt(s) * ai * ai;
    }
    return window * 0.5 * sum / (2.0 * PI * sin(phi));
}

// CIE 1931 colour matching functions, Wyman, Sloan and Shirley 2013's multi-lobe fit.
fn cie_lobe(nm: f32, mu: f32, below: f32, above: f32) -> f32 {
    let t = (nm - mu) / select(above, below, nm < mu);
    return exp(-0.5 * t * t);
}

// Linear sRGB (D65) of a unit of light at `nm`.
fn spectral_rgb(nm: f32) -> vec3<f32> {
    let x = 1.056 * cie_lobe(nm, 599.8, 37.9, 31.0) + 0.362 * cie_lobe(nm, 442.0, 16.0, 26.7) - 0.065 * cie_lobe(nm, 501.1, 20.4, 26.2);
    let y = 0.821 * cie_lobe(nm, 568.8, 46.9, 40.5) + 0.286 * cie_lobe(nm, 530.9, 16.3, 31.1);
    let z = 1.217 * cie_lobe(nm, 437.0, 11.8, 36.0) + 0.681 * cie_lobe(nm, 459.0, 26.0, 13.8);
    return vec3<f32>(
        3.2406 * x - 1.5372 * y - 0.4986 * z,
        -0.9689 * x + 1.8758 * y + 0.0415 * z,
        0.0557 * x - 0.2040 * y + 1.0570 * z,
    );
}

// The Lee diagram's row for this scene's drops (Lee 1998, "Mie theory, Airy theory, and the
// natural rainbow"): each texel's angle, the bows' phase function summed over the spectrum
// (rgb, normalised so that a flat spectrum is white 1, 1, 1) and averaged over the sun's disc.
@compute @workgroup_size(8, 8, 1)
fn rainbow_lut(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= RAINBOW_TEXELS || id.y >= 1u {
        return;
    }
    let span = radians(RAINBOW_MAX_DEG - RAINBOW_MIN_DEG);
    let phi = radians(RAINBOW_MIN_DEG) + span * f32(id.x) / f32(RAINBOW_TEXELS - 1u);
    let sun_radius = acos(frame.sun_cos_radius);
    let a = frame.rainbow_drop_radius;
    var sum = vec3<f32>(0.0);
    var white = vec3<f32>(0.0);
    for (var j = 0u; j < RAINBOW_WAVELENGTHS; j++) {
        let nm = 400.0 + 300.0 * (f32(j) + 0.5) / f32(RAINBOW_WAVELENGTHS);
        let rgb = spectral_rgb(nm);
        white += rgb;
        var p = 0.0;
        var weights = 0.0;
        for (var m = 1u; m <= RAINBOW_SUN_TAPS; m++) {
            let u = f32(m) * PI / f32(RAINBOW_SUN_TAPS + 1u);
            let w = sin(u) * sin(u);
            p += w * rainbow_phase(phi + cos(u) * sun_radius, a, nm);
            weights += w;
        }
        sum += rgb * (p / weights);
    }
    textureStore(rainbow_lut_out, id.xy, vec4<f32>(max(sum / white, vec3<f32>(0.0)), 1.0));
}

// The bows' phase function (rgb) at `phi` (rad) from the antisolar point: the table's, or the
// cheap path's three wavelengths.
fn rainbow_phase_rgb(phi: f32) -> vec3<f32> {
    if (frame.flags & FLAG_LEE_DIAGRAM) != 0u {
        let x = (degrees(phi) - RAINBOW_MIN_DEG) / (RAINBOW_MAX_DEG - RAINBOW_MIN_DEG);
        return lut_bilinear(rainbow_lut_in, vec2<f32>(x, 0.0), vec2<u32>(RAINBOW_TEXELS, 1u)).rgb;
    }
    let a = frame.rainbow_drop_radius;
    return vec3<f32>(
        rainbow_phase(phi, a, RAINBOW_RGB_NM.r),
        rainbow_phase(phi, a, RAINBOW_RGB_NM.g),
        rainbow_phase(phi, a, RAINBOW_RGB_NM.b),
    );
}

// The moisture's weight at altitude `h` (m): (h / h0) e^(1 - h / h0), 1 at h0 = 2 km.
fn moisture_profile(h: f32) -> f32 {
    let x = max(h, 0.0) / MOISTURE_PEAK_M;
    return x * exp(1.0 - x);
}

// The rain at world point `p` (altitude p.y): under each precipitating layer whose bottom is
// above it, where the weather map has cloud, its precipitation.
fn rain_at(p: vec3<f32>) -> f32 {
    var rain = 0.0;
    for (var i = 0u; i < layer_count(); i++) {
        let l = cloud_layer(i);
        if l.precipitation > 0.0 && p.y < l.bottom {
            let w = sample_weather(p, l);
            rain += w.precipitation * smoothstep(0.35, 0.65, w.coverage);
        }
    }
    return rain;
}

// The highest bottom of a precipitating layer (m; 0 without one): rain falls below it.
fn rain_top() -> f32 {
    var top = 0.0;
    for (var i = 0u; i < layer_count(); i++) {
        let l = cloud_layer(i);
        if l.precipitation > 0.0 {
            top = max(top, l.bottom);
        }
    }
    return top;
}

// The bows' radiance along unit `view` from the camera (per unit key-light illuminance at the
// top of the air, rgb): the rain's single scattering of the key light into the bows, where the
// clouds (the cloud-shadow map, projected along the light) and the air let it through, seen
// through the air and the rain in front. Midpoint steps over the ray's first RAIN_RANGE_M m,
// until it rises above the rain or meets the ground. The rain is in front of the clouds above
// it, so the bows add to whatever the pixel shows behind them.
fn rainbow_radiance(view: vec3<f32>) -> vec3<f32> {
    if frame.rainbow_moisture <= 0.0 {
        return vec3<f32>(0.0);
    }
    let light = frame.sun_direction;
    let phi = acos(clamp(-dot(view, light), -1.0, 1.0));
    if phi < radians(RAINBOW_MIN_DEG) || phi > radians(RAINBOW_MAX_DEG) || light.y <= SHAFT_MIN_SUN_Y {
        return vec3<f32>(0.0);
    }
    let cam = frame.camera_position;
    let top = rain_top();
    var end = RAIN_RANGE_M;
    if view.y > 0.0 {
        end = min(end, max(top - cam.y, 0.0) / view.y);
    } else if view.y < 0.0 {
        end = min(end, cam.y / -view.y);
    }
    if !(end > 0.0) {
        return vec3<f32>(0.0);
    }
    let phase = rainbow_phase_rgb(phi);
    let origin = camera_air_origin();
    let dt = end / f32(RAIN_STEPS);
    var air_tau = vec3<f32>(0.0);
    var rain_tau = 0.0;
    var sum = vec3<f32>(0.0);
    for (var k = 0u; k < RAIN_STEPS; k++) {
        let t = (f32(k) + 0.5) * dt;
        let rel = view * t + vec3<f32>(0.0, cam.y, 0.0);
        let world = rel + vec3<f32>(cam.x, 0.0, cam.z);
        let air = air_at(rel.y * 1e-3);
        let beta = RAIN_EXTINCTION * frame.rainbow_moisture * moisture_profile(rel.y) * rain_at(world);
        if beta > 0.0 {
            let q = origin + view * (t * 1e-3);
            let r = length(q);
            let lit = ground_shadow(rel - light * (rel.y / light.y)) * sun_transmittance(r, dot(q / r, light));
            let seen = exp(-(air_tau + air.extinction * (0.5 * dt * 1e-3))) * exp(-(rain_tau + 0.5 * beta * dt));
            sum += lit * seen * (beta * dt);
        }
        air_tau += air.extinction * (dt * 1e-3);
        rain_tau += beta * dt;
    }
    return sum * phase;
}
