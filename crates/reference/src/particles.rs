//! The CPU twin of `precipitation.wgsl`'s particles: rain or snow near the camera drawn over
//! the display image (the raster pass's triangles, rasterised here at pixel centres).

use crate::frame::{Frame, PI, pcg, xyz};
use crate::geometry::view_ray;
use crate::lightning::lightning_light;
use crate::math::{V3, saturate};
use crate::precipitation::{Rain, falling_rain, scene_surface};

// WGSL: precipitation.wgsl (constants).
const PRECIP_PARTICLES: u32 = 8192;
const PRECIP_SALT: u32 = 0xD40B;
const PRECIP_SHUTTER_S: f64 = 0.033;
const PRECIP_NEAR_M: f64 = 0.25;
const RAIN_WIDTH_M: f64 = 0.004;
const SNOW_WIDTH_M: f64 = 0.01;
const RAIN_OPACITY: f64 = 0.6;
const SNOW_OPACITY: f64 = 0.9;
const RAIN_GLINT: f64 = 1.6;
const PRECIP_MIN_COVERAGE: f64 = 0.4;
const SNOW_SWAY_M: f64 = 0.3;
const PRECIP_MIN_WIDTH_PX: f64 = 1.5;
// WGSL: common.wgsl::FLAG_SNOW
const FLAG_SNOW: u32 = 4096;
// The graph's `precipitation` pass draws this many particles at most (its vertices / 6).
const PASS_PARTICLES: u32 = 4 * PRECIP_PARTICLES;

// WGSL: precipitation.wgsl::precip_random
/// Four random numbers in [0, 1) for particle `id`.
fn precip_random(id: u32) -> [f64; 4] {
    let a = pcg(id ^ pcg(PRECIP_SALT));
    let b = pcg(a);
    let c = pcg(b);
    let d = pcg(c);
    [a, b, c, d].map(|v| f64::from(v >> 8) * (1.0 / 16_777_216.0))
}

/// `x - floor(x)`, the WGSL's `fract`.
fn fract(x: f64) -> f64 {
    x - x.floor()
}

/// One particle as the vertex shader leaves it: its quad in pixels (head and tail ends, the
/// unit axis and half its drawn width), its premultiplied colour's parts and distance.
struct Particle {
    head: [f64; 2],
    tail: [f64; 2],
    along: [f64; 2],
    half_width: f64,
    colour: V3,
    alpha: f64,
    distance: f64,
}

// WGSL: precipitation.wgsl::precip_vertex
/// Particle `id`, or `None` where the vertex shader leaves it undrawn.
fn particle(f: &Frame, rain: &Rain, id: u32) -> Option<Particle> {
    if f64::from(id) >= f.precip_density * f64::from(PRECIP_PARTICLES) {
        return None;
    }
    let rnd = precip_random(id);
    let b = f.precip_box;
    let cam = xyz(f.camera_position);
    let snow = f.flags & FLAG_SNOW != 0;
    let off = xyz(f.precip_offset);
    let place = |r: f64, o: f64, c: f64| (fract((r * b + o - c) / b) - 0.5) * b;
    let mut rel = V3::new(
        place(rnd[0], off.x, cam.x),
        place(rnd[1], off.y, cam.y),
        place(rnd[2], off.z, cam.z),
    );
    if snow {
        let turn = 2.0 * PI * (off.y * 0.5 + rnd[3]);
        rel += V3::new(turn.cos(), 0.0, turn.sin()) * SNOW_SWAY_M;
    }
    let world = rel + cam;
    let share = fract(rnd[3] * 7.0);
    if world.y <= 0.0 || falling_rain(f, rain.noise, world) <= share {
        return None;
    }
    let tail = rel - xyz(f.precip_velocity) * PRECIP_SHUTTER_S;
    let (forward, right, up) = f.camera_axes();
    let t = f.tan_half_fov;
    let project = |p: V3| {
        let z = p.dot(forward);
        [p.dot(right) / (z * t * f.aspect), p.dot(up) / (z * t), z]
    };
    let a = project(rel);
    let bb = project(tail);
    if a[2].min(bb[2]) < PRECIP_NEAR_M {
        return None;
    }
    let half = [f64::from(f.size[0]) * 0.5, f64::from(f.size[1]) * 0.5];
    let a_px = [a[0] * half[0], a[1] * half[1]];
    let b_px = if snow {
        a_px
    } else {
        [bb[0] * half[0], bb[1] * half[1]]
    };
    let (width, opacity) = if snow {
        (SNOW_WIDTH_M, SNOW_OPACITY)
    } else {
        (RAIN_WIDTH_M, RAIN_OPACITY)
    };
    let width_px = width / (a[2] * f.tan_half_fov) * half[1];
    let drawn = width_px.max(PRECIP_MIN_WIDTH_PX);
    let axis = [b_px[0] - a_px[0], b_px[1] - a_px[1]];
    let len = axis[0].hypot(axis[1]);
    let along = if len > 1e-3 {
        [axis[0] / len, axis[1] / len]
    } else {
        [0.0, -1.0]
    };
    let glint = if snow { 1.0 } else { RAIN_GLINT };
    // Lit where it is: camera-relative across, its altitude up (as the march's `rel`).
    let at = rel + V3::new(0.0, cam.y, 0.0);
    let light = (crate::lighting::ambient(f, rain.sky, 0.0, at) + lightning_light(f, at)) * glint;
    let exposed = light * f.exposure;
    let display = crate::composite::saturated(f, crate::composite::aces_fitted(exposed));
    let g = 1.0 / 2.2;
    Some(Particle {
        head: [
            a_px[0] - along[0] * 0.5 * drawn,
            a_px[1] - along[1] * 0.5 * drawn,
        ],
        tail: [
            b_px[0] + along[0] * 0.5 * drawn,
            b_px[1] + along[1] * 0.5 * drawn,
        ],
        along,
        half_width: 0.5 * drawn,
        colour: V3::new(display.x.powf(g), display.y.powf(g), display.z.powf(g)),
        alpha: opacity * (width_px / drawn).clamp(PRECIP_MIN_COVERAGE, 1.0),
        distance: rel.length(),
    })
}

/// The particles drawn over `image` (rgba8, the display image) in their order, as the
/// `precipitation` raster pass does: each pixel whose centre lies in a particle's quad, not
/// behind the host's geometry, blended "over" with the fragment's premultiplied colour.
pub(crate) fn draw_particles(f: &Frame, rain: &Rain, image: &mut [u8]) {
    if f.precip_density <= 0.0 {
        return;
    }
    let [w, h] = f.size;
    let half = [f64::from(w) * 0.5, f64::from(h) * 0.5];
    let snow = f.flags & FLAG_SNOW != 0;
    for id in 0..PASS_PARTICLES {
        let Some(p) = particle(f, rain, id) else {
            continue;
        };
        let across = [-p.along[1], p.along[0]];
        let len = (p.tail[0] - p.head[0]) * p.along[0] + (p.tail[1] - p.head[1]) * p.along[1];
        // The quad's corners in pixel coordinates (y down), for its bounding box.
        let corners = [p.head, p.tail].map(|e| {
            [-1.0, 1.0].map(|s| {
                let x = e[0] + across[0] * s * p.half_width;
                let y = e[1] + across[1] * s * p.half_width;
                [(x + half[0]), (half[1] - y)]
            })
        });
        let flat = corners.iter().flatten();
        let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for c in flat {
            x0 = x0.min(c[0]);
            x1 = x1.max(c[0]);
            y0 = y0.min(c[1]);
            y1 = y1.max(c[1]);
        }
        let xs = (x0 - 0.5).ceil().max(0.0) as u32
            ..=((x1 - 0.5).floor().min(f64::from(w) - 1.0)).max(-1.0) as u32;
        let ys = (y0 - 0.5).ceil().max(0.0) as u32
            ..=((y1 - 0.5).floor().min(f64::from(h) - 1.0)).max(-1.0) as u32;
        if x1 < 0.5 || y1 < 0.5 {
            continue;
        }
        for py in ys.clone() {
            for px in xs.clone() {
                // The pixel centre in the quad's frame: along from the head's end, across from
                // the axis.
                let cx = f64::from(px) + 0.5 - half[0];
                let cy = half[1] - (f64::from(py) + 0.5);
                let dx = cx - p.head[0];
                let dy = cy - p.head[1];
                let s = dx * p.along[0] + dy * p.along[1];
                let u = (dx * across[0] + dy * across[1]) / p.half_width;
                if !(0.0..=len).contains(&s) || !(-1.0..=1.0).contains(&u) {
                    continue;
                }
                let v = if len > 0.0 { s / len } else { 0.0 };
                let pixel = [px, py];
                if scene_surface(f, rain.surface, pixel, view_ray(f, pixel)) < p.distance {
                    continue;
                }
                let profile = if snow {
                    let vv = 2.0 * v - 1.0;
                    saturate(1.0 - u * u - vv * vv)
                } else {
                    (1.0 - u * u) * (1.0 - 0.5 * v)
                };
                let a = p.alpha * profile;
                let i = 4 * (py * w + px) as usize;
                for (c, src) in [p.colour.x, p.colour.y, p.colour.z].into_iter().enumerate() {
                    let dst = f64::from(image[i + c]) / 255.0;
                    image[i + c] = (saturate(src * a + dst * (1.0 - a)) * 255.0).round() as u8;
                }
                let dst = f64::from(image[i + 3]) / 255.0;
                image[i + 3] = (saturate(a + dst * (1.0 - a)) * 255.0).round() as u8;
            }
        }
    }
}

/// The `precipitation` pass: the particles over the display image when the frame draws them
/// (`precip_density` > 0 and the clouds' weather map at hand), its time appended to `timings`.
pub(crate) fn particles_pass(
    f: &Frame,
    rain: Option<&Rain>,
    image: &mut [u8],
    timings: &mut Vec<stratus_graph::PassTiming>,
) {
    let Some(rain) = rain.filter(|_| f.precip_density > 0.0) else {
        return;
    };
    let t = std::time::Instant::now();
    draw_particles(f, rain, image);
    timings.push(stratus_graph::PassTiming {
        pass: "precipitation".to_string(),
        ms: t.elapsed().as_secs_f64() * 1e3,
        source: "cpu-wall",
    });
}
