// Precipitation and lightning (section `[precipitation]`, `[lightning]`): the rain's shafts in
// the composite, rain or snow particles near the camera drawn over the display image by a
// raster pass, and the light of a lightning flash inside the clouds.

// --- Rain shafts -------------------------------------------------------------------------
// The rain below a raining cell (`rain_at`: a precipitating layer's precipitation where the
// weather map has a cell's core above, `falling_rain`) dims what is behind it and scatters the light under the deck
// (the march's ambient at the layer's bottom, and a lightning flash's) toward the camera; lit from below a dark deck
// while the air about it sees the sky, a distant cell hangs a darker, greyer column. Heavy
// rain's extinction is what Koschmieder's law gives for the visibility a report of heavy rain
// carries, about 3 km (3.912 / 3 km); `rain_shafts` scales it. Steps at a dithered place a
// pixel over the part of the ray below the rain's top within RAIN_SHAFT_RANGE_M m of the camera.
const RAIN_SHAFT_EXTINCTION: f32 = 1.3e-3;
const RAIN_SHAFT_STEPS: u32 = 24u;
const RAIN_SHAFT_RANGE_M: f32 = 30000.0;
const RAIN_SHAFT_SALT: u32 = 0x7A1Bu;

// What the rain between the camera and a pixel's end does: the light it scatters toward the
// camera and the share of what is behind it that it lets through.
struct RainVeil {
    radiance: vec3<f32>,
    transmittance: f32,
}

// Rain falls from the cells' dense cores, not from all of their cloud: a convective cell's
// precipitation covers a fraction of its cloud's area. Where the weather map's coverage (after
// the layer's) passes RAIN_CORE.x rain begins, and is full at RAIN_CORE.y.
const RAIN_CORE: vec2<f32> = vec2<f32>(0.6, 0.9);

// The rain falling at world point `p` (altitude p.y), for the shafts and the particles: under
// each precipitating layer whose bottom is above it, its precipitation where the weather map
// has a core.
fn falling_rain(p: vec3<f32>) -> f32 {
    var rain = 0.0;
    for (var i = 0u; i < layer_count(); i++) {
        let l = cloud_layer(i);
        if l.precipitation > 0.0 && p.y < l.bottom {
            let w = sample_weather(p, l);
            rain += w.precipitation * smoothstep(RAIN_CORE.x, RAIN_CORE.y, w.coverage);
        }
    }
    return rain;
}

// Whether the rain lies in front of the clouds along every ray (the camera is below the
// highest raining layer's bottom), or behind them (the camera is above it).
fn rain_in_front() -> bool {
    return frame.camera_position.y <= rain_top();
}

// The rain shafts along `view` from the camera at `pixel` (none without `rain_shafts`), to the
// host's geometry, the ground, or where the ray leaves the rain.
fn rain_veil(pixel: vec2<u32>, view: vec3<f32>) -> RainVeil {
    var veil = RainVeil(vec3<f32>(0.0), 1.0);
    let top = rain_top();
    if frame.rain_shafts <= 0.0 || top <= 0.0 {
        return veil;
    }
    let cam = frame.camera_position;
    var start = 0.0;
    var end = RAIN_SHAFT_RANGE_M;
    if cam.y > top {
        if view.y >= 0.0 {
            return veil;
        }
        start = (cam.y - top) / -view.y;
    } else if view.y > 0.0 {
        end = min(end, (top - cam.y) / view.y);
    }
    if view.y < 0.0 {
        end = min(end, cam.y / -view.y);
    }
    end = min(end, scene_surface(pixel, view));
    if !(end > start) {
        return veil;
    }
    let dt = (end - start) / f32(RAIN_SHAFT_STEPS);
    let offset = hash_unit(pixel, RAIN_SHAFT_SALT);
    let k = RAIN_SHAFT_EXTINCTION * frame.rain_shafts;
    for (var i = 0u; i < RAIN_SHAFT_STEPS; i++) {
        let t = start + (f32(i) + offset) * dt;
        let rel = view * t + vec3<f32>(0.0, cam.y, 0.0);
        let beta = k * falling_rain(rel + vec3<f32>(cam.x, 0.0, cam.z));
        if beta > 0.0 {
            let step_t = exp(-beta * dt);
            veil.radiance += (ambient(0.0, rel) + lightning_light(rel)) * (veil.transmittance * (1.0 - step_t));
            veil.transmittance *= step_t;
        }
    }
    return veil;
}

// `behind` seen through the rain in front of it.
fn through_rain(veil: RainVeil, behind: vec3<f32>) -> vec3<f32> {
    return veil.radiance + behind * veil.transmittance;
}

// --- Lightning -----------------------------------------------------------------------------
// A flash (`lightning_position`, `lightning_illuminance` 1 km from it; the host draws when
// and where, crates/scene/src/lightning.rs) lights the cloud about it through the cloud: its
// light, scattered many times, leaves the channel diffused, isotropic, and dimmed with
// distance beyond the inverse square over a diffusion length of about a kilometre (light
// diffusing through cloud of extinction ~0.05/m has a transport length of some hundred
// metres; Koshak et al. 1994 model lightning's light leaving a cloud this way). Within
// LIGHTNING_CORE_M of the channel the light stays at its core's.
const LIGHTNING_DIFFUSION_M: f32 = 1500.0;
const LIGHTNING_CORE_M: f32 = 200.0;
// A flash's colour, linear rgb: the channel's light is white to blue-white (its spectrum is
// rich in the nitrogen and hydrogen lines of 500-660 nm and the continuum; Orville 1968).
const LIGHTNING_COLOUR: vec3<f32> = vec3<f32>(0.85, 0.9, 1.0);

// The flash's in-scattered radiance per unit scattering coefficient at camera-relative `rel`
// (isotropic after many scatterings): its illuminance there over 4 pi.
fn lightning_light(rel: vec3<f32>) -> vec3<f32> {
    if frame.lightning_illuminance <= 0.0 {
        return vec3<f32>(0.0);
    }
    let cam = frame.camera_position;
    let to = rel + vec3<f32>(cam.x, 0.0, cam.z) - frame.lightning_position;
    let r = max(length(to), LIGHTNING_CORE_M);
    let q = 1000.0 / r;
    let e = frame.lightning_illuminance * q * q * exp((1000.0 - r) / LIGHTNING_DIFFUSION_M);
    return LIGHTNING_COLOUR * (e / (4.0 * PI));
}

// --- Particles -----------------------------------------------------------------------------
// Rain or snow near the camera: PRECIP_PARTICLES x `precip_density` particles, each at a
// random place in a box of side `precip_box` that moves with the fall and the wind
// (`precip_offset`) and wraps about the camera, drawn where the rain at its place
// (`falling_rain`) is at least its own random share (so the density follows the layer's
// precipitation and the weather map). A raindrop is a streak along its velocity over
// PRECIP_SHUTTER_S (the eye's and a camera's exposure blurs drops into streaks); a snowflake a
// round flake that sways as it falls. Each is lit by the light under the deck (the march's
// ambient at the layer's bottom), and drawn over the display image: its coverage of a pixel
// (its width in pixels, at most one) times its opacity, premultiplied.
const PRECIP_PARTICLES: u32 = 8192u;   // at `precip_density` 1; the pass draws 4x this
const PRECIP_SALT: u32 = 0xD40Bu;
const PRECIP_SHUTTER_S: f32 = 0.033;
const PRECIP_NEAR_M: f32 = 0.25;       // nearer than this a particle is not drawn
const RAIN_WIDTH_M: f32 = 0.004;       // a drop's streak, its glints included
const SNOW_WIDTH_M: f32 = 0.01;        // an aggregate flake
const RAIN_OPACITY: f32 = 0.6;         // a drop is mostly clear: it shows the light above it bent
const SNOW_OPACITY: f32 = 0.9;
const RAIN_GLINT: f32 = 1.6;           // a drop's light over the deck's ambient: it gathers the sky above
const PRECIP_MIN_COVERAGE: f32 = 0.4;  // the least share of a pixel a far particle keeps
const SNOW_SWAY_M: f32 = 0.3;          // the flakes' sway, one turn each 2 m of fall
const PRECIP_MIN_WIDTH_PX: f32 = 1.5;  // thinner particles are drawn this wide, fainter

struct PrecipVertex {
    @builtin(position) position: vec4<f32>,
    // Across the particle (-1 to 1) and along it (0 at its head, 1 at its tail).
    @location(0) uv: vec2<f32>,
    // Premultiplied display colour at full coverage, and its opacity.
    @location(1) @interpolate(flat) colour: vec4<f32>,
    // Its distance from the camera (m).
    @location(2) @interpolate(flat) distance: f32,
}

// Four random numbers in [0, 1) for particle `id`.
fn precip_random(id: u32) -> vec4<f32> {
    let a = pcg(id ^ pcg(PRECIP_SALT));
    let b = pcg(a);
    let c = pcg(b);
    let d = pcg(c);
    return vec4<f32>(vec4<u32>(a, b, c, d) >> vec4<u32>(8u)) * (1.0 / 16777216.0);
}

// A camera-relative point in normalised device coordinates (x right, y up) and its depth.
fn precip_project(rel: vec3<f32>) -> vec3<f32> {
    let z = dot(rel, frame.camera_forward);
    let t = frame.tan_half_fov;
    return vec3<f32>(dot(rel, frame.camera_right) / (z * t * frame.aspect), dot(rel, frame.camera_up) / (z * t), z);
}

@vertex
fn precip_vertex(@builtin(vertex_index) index: u32) -> PrecipVertex {
    var out: PrecipVertex;
    // Not drawn: a degenerate triangle behind the camera (clipped).
    out.position = vec4<f32>(0.0, 0.0, -1.0, 1.0);
    let id = index / 6u;
    if f32(id) >= frame.precip_density * f32(PRECIP_PARTICLES) {
        return out;
    }
    let rnd = precip_random(id);
    let box = frame.precip_box;
    let cam = frame.camera_position;
    let snow = (frame.flags & FLAG_SNOW) != 0u;
    // The particle's place: its random place in the box moved by the fall and drift, wrapped
    // into the box about the camera.
    var rel = (fract((rnd.xyz * box + frame.precip_offset - cam) / box) - 0.5) * box;
    if snow {
        let turn = 2.0 * PI * (frame.precip_offset.y * 0.5 + rnd.w);
        rel += vec3<f32>(cos(turn), 0.0, sin(turn)) * SNOW_SWAY_M;
    }
    let world = rel + cam;
    let share = fract(rnd.w * 7.0);
    if world.y <= 0.0 || falling_rain(world) <= share {
        return out;
    }
    // The head now and the tail where the particle was a shutter ago.
    let tail = rel - frame.precip_velocity * PRECIP_SHUTTER_S;
    let a = precip_project(rel);
    let b = precip_project(tail);
    if min(a.z, b.z) < PRECIP_NEAR_M {
        return out;
    }
    let half = vec2<f32>(frame.size) * 0.5;
    let a_px = a.xy * half;
    var b_px = b.xy * half;
    var width = select(RAIN_WIDTH_M, SNOW_WIDTH_M, snow);
    var opacity = select(RAIN_OPACITY, SNOW_OPACITY, snow);
    if snow {
        b_px = a_px; // a flake: round, its fall in a shutter shorter than it is wide
    }
    let width_px = width / (a.z * frame.tan_half_fov) * half.y;
    let drawn_px = max(width_px, PRECIP_MIN_WIDTH_PX);
    let axis = b_px - a_px;
    let length_px = length(axis);
    var along = vec2<f32>(0.0, -1.0);
    if length_px > 1e-3 {
        along = axis / length_px;
    }
    let across = vec2<f32>(-along.y, along.x);
    let k = index % 6u;
    // Two triangles: (head, -), (head, +), (tail, -); (tail, -), (head, +), (tail, +).
    let at_tail = k == 2u || k == 3u || k == 5u;
    let side = select(-1.0, 1.0, k == 1u || k == 4u || k == 5u);
    let end = select(a_px - along * (0.5 * drawn_px), b_px + along * (0.5 * drawn_px), at_tail);
    let corner = end + across * (side * 0.5 * drawn_px);
    out.position = vec4<f32>(corner / half, 0.5, 1.0);
    out.uv = vec2<f32>(side, select(0.0, 1.0, at_tail));
    // Lit where it is: camera-relative across, its altitude up (as the march's `rel`).
    let at = rel + vec3<f32>(0.0, cam.y, 0.0);
    let light = (ambient(0.0, at) + lightning_light(at)) * select(RAIN_GLINT, 1.0, snow);
    let alpha = opacity * clamp(width_px / drawn_px, PRECIP_MIN_COVERAGE, 1.0);
    let exposed = light * frame.exposure;
    let display = pow(saturated(aces_fitted(exposed)), vec3<f32>(1.0 / 2.2));
    out.colour = vec4<f32>(display, alpha);
    out.distance = length(rel);
    return out;
}

@fragment
fn precip_fragment(in: PrecipVertex) -> @location(0) vec4<f32> {
    let pixel = vec2<u32>(in.position.xy);
    // Behind the host's geometry: hidden.
    if scene_surface(pixel, view_ray(pixel)) < in.distance {
        discard;
    }
    // A drop: soft across (its round section), fading toward the tail. A flake: a soft disc.
    var profile = (1.0 - in.uv.x * in.uv.x) * (1.0 - 0.5 * in.uv.y);
    if (frame.flags & FLAG_SNOW) != 0u {
        let v = 2.0 * in.uv.y - 1.0;
        profile = saturate(1.0 - in.uv.x * in.uv.x - v * v);
    }
    let alpha = in.colour.a * profile;
    return vec4<f32>(in.colour.rgb * alpha, alpha);
}
