//! The CPU twin of `composite.wgsl`: the analytic sky and sun disk behind the clouds, or the
//! physical sky (its tables, the sun's and the moon's discs and the stars through the air, and
//! aerial perspective on the clouds), exposure, the ACES fitted curve and gamma 2.2, to 8 bits.

use rayon::prelude::*;

use crate::frame::{FLAG_LIGHT_SHAFTS, FLAG_MOONLIT, Frame, PI};
use crate::geometry::{hits_ground, view_ray};
use crate::math::{V3, mix_v, saturate};
use crate::phase::phase_hg;
use crate::precipitation::{Rain, rain_in_front, rain_veil, through_rain};
use crate::sky::{SkyTables, physical};

// WGSL: composite.wgsl::sky_radiance
/// Sky radiance along unit `d` for a camera at altitude `alt`.
pub(crate) fn sky_radiance(f: &Frame, d: V3, alt: f64) -> V3 {
    let sun = f.sun();
    let e = f.sun_illuminance();
    let day = saturate(sun.y * 4.0 + 0.3);
    if hits_ground(f, V3::new(0.0, alt, 0.0), alt, d) {
        let ground_albedo = V3::new(0.035, 0.035, 0.03);
        return ground_albedo.mul_v(e * (sun.y.max(0.0) / PI) + e * (0.05 * day));
    }
    let zenith = V3::new(0.018, 0.04, 0.1);
    let horizon = V3::new(0.07, 0.085, 0.11);
    let up = saturate(d.y);
    let gradient = mix_v(horizon, zenith, up.sqrt());
    let sunset = V3::new(0.25, 0.1, 0.0) * ((1.0 - day * 0.8) * (1.0 - up).powf(6.0));
    let glow = phase_hg(d.dot(sun), 0.76) * 0.02;
    e.mul_v(gradient * day + sunset * saturate(sun.y * 10.0 + 1.0) + V3::splat(glow * day))
}

// WGSL: composite.wgsl::sun_disk
/// Radiance of the sun's disk: illuminance over its solid angle.
pub(crate) fn sun_disk(f: &Frame, d: V3) -> V3 {
    let cos_r = f.sun_cos_radius;
    if d.dot(f.sun()) < cos_r {
        return V3::ZERO;
    }
    f.sun_illuminance() / (2.0 * PI * (1.0 - cos_r).max(1e-6))
}

// WGSL: composite.wgsl::aces_fitted
/// Narkowicz's ACES fit, clamped to `[0, 1]`.
pub(crate) fn aces_fitted(x: V3) -> V3 {
    let curve = |x: f64| {
        let (a, b, c, d, e) = (2.51, 0.03, 2.43, 0.59, 0.14);
        ((x * (a * x + b)) / (x * (c * x + d) + e)).clamp(0.0, 1.0)
    };
    V3::new(curve(x.x), curve(x.y), curve(x.z))
}

// WGSL: composite.wgsl::saturated
/// The tone-mapped colour `c` with its saturation scaled by `saturation` (1: `c` itself).
pub(crate) fn saturated(f: &Frame, c: V3) -> V3 {
    let s = f.saturation;
    if s == 1.0 {
        return c;
    }
    let y = c.dot(V3::new(0.2126, 0.7152, 0.0722));
    let out = V3::splat(y) + (c - V3::splat(y)) * s;
    V3::new(saturate(out.x), saturate(out.y), saturate(out.z))
}

/// `f32 -> rgba8unorm` store conversion: clamp, scale by 255, round to nearest.
fn unorm8(x: f64) -> u8 {
    (saturate(x) * 255.0).round() as u8
}

// WGSL: composite.wgsl::physical_composite
/// The clouds in the physical sky: the sky-view table (ground included) and, above the
/// horizon, the moon's disc, the stars and (unless the moon is the key light) the sun's disc
/// through the air behind them; in front of them the air between the camera and their depth
/// (aerial perspective), which dims their light and adds its own. Where a cloud leaves
/// transmittance a, the sky behind shows through as a and the air in front of the cloud
/// stands for the rest: `L = a S + (1 - a) S_ap + T_ap C` (Hillaire 2020, section 5.4's
/// aerial-perspective volume on opaque surfaces, with partly transparent clouds). `depth` is
/// the clouds' depth (m) at `pixel`.
// The WGSL pass's inputs, each a binding or a per-pixel value there.
#[allow(clippy::too_many_arguments)]
pub(crate) fn physical_composite(
    f: &Frame,
    sky: &SkyTables,
    pixel: [u32; 2],
    view: V3,
    cloud: [f64; 4],
    depth: f64,
    surface: bool,
    rain: Option<&Rain>,
) -> V3 {
    let e = f.sun_illuminance();
    let r = sky.camera_air_origin(f).y;
    let alpha = cloud[3];
    // With light shafts the air in front of the clouds and behind them lacks what the clouds'
    // shadows take from it.
    let (shaded_front, shaded_all) = composite_shafts(f, sky, pixel, view, alpha, depth, surface);
    // The ground below the horizon is in the table; only the sky above it shows space.
    let mut background = sky.sky_view(f, view).mul_v(e);
    if surface {
        background = surface_radiance(f);
    } else if sky.meets_ground(r, view.y) {
        // The table's ground is lit everywhere; where the clouds shade it, less.
        let lost = sky.ground_shadow_loss(f, view, r).mul_v(e);
        background = non_negative(background - lost);
    } else {
        let mut space = crate::night::night_sky(f, pixel, view);
        if f.flags & FLAG_MOONLIT == 0 {
            space += sun_disk(f, view);
        }
        background += space.mul_v(sky.transmittance_to_top(r, view.y));
    }
    let mut bow = V3::ZERO;
    if !surface {
        background = non_negative(background - shaded_all.mul_v(e));
        bow = sky.rainbow_radiance(f, view).mul_v(e);
    }
    // The rain shafts: in front of everything from below the rain's top, behind the clouds
    // (over the sky and ground only) from above it.
    let veil = rain
        .filter(|_| f.rain_shafts > 0.0)
        .map(|rain| (rain_veil(f, rain, pixel, view), rain_in_front(f)));
    if let Some((veil, false)) = veil {
        background = through_rain(veil, background);
    }
    let mut radiance = background * alpha;
    if alpha < 1.0 {
        let ap = sky.aerial(f, pixel, depth);
        let air = non_negative(V3::new(ap[0], ap[1], ap[2]) - shaded_front);
        radiance += air.mul_v(e) * (1.0 - alpha) + V3::new(cloud[0], cloud[1], cloud[2]) * ap[3];
    }
    if let Some((veil, true)) = veil {
        radiance = through_rain(veil, radiance);
    }
    radiance + bow
}

/// `max(v, 0)` in each channel (the WGSL's `max(v, vec3(0.0))`).
fn non_negative(v: V3) -> V3 {
    V3::new(v.x.max(0.0), v.y.max(0.0), v.z.max(0.0))
}

// WGSL: composite.wgsl::composite_shafts
/// The light shafts of the composite at `pixel` along `view` (`(front, all)`, per unit key
/// light; none without `FLAG_LIGHT_SHAFTS`): over the host's geometry the air up to the clouds'
/// depth `depth` (m) only, elsewhere to where the ray meets the ground or leaves the air.
fn composite_shafts(
    f: &Frame,
    sky: &SkyTables,
    pixel: [u32; 2],
    view: V3,
    alpha: f64,
    depth: f64,
    surface: bool,
) -> (V3, V3) {
    if f.flags & FLAG_LIGHT_SHAFTS == 0 || (surface && alpha >= 1.0) {
        return (V3::ZERO, V3::ZERO);
    }
    let end = if surface {
        depth
    } else {
        sky.air_ray_end(sky.camera_air_origin(f), view).0
    };
    sky.light_shafts(f, pixel, view, depth, end)
}

// WGSL: composite.wgsl::surface_radiance
/// The host's geometry in the display image: a grey surface (albedo 0.3) facing up, lit as
/// the analytic sky's ground is.
pub(crate) fn surface_radiance(f: &Frame) -> V3 {
    let sun = f.sun();
    let e = f.sun_illuminance();
    let day = (sun.y * 4.0 + 0.3).clamp(0.0, 1.0);
    e * (0.3 * (sun.y.max(0.0) / PI + 0.05 * day))
}

// WGSL: composite.wgsl::store_display
/// Exposure, tone curve, saturation and gamma of a pixel's radiance, to the display's 8 bits.
fn store_display(f: &Frame, radiance: V3) -> [u8; 4] {
    let exposed = radiance * f.exposure;
    let display = saturated(f, aces_fitted(exposed));
    let g = 1.0 / 2.2;
    [
        unorm8(display.x.powf(g)),
        unorm8(display.y.powf(g)),
        unorm8(display.z.powf(g)),
        255,
    ]
}

// WGSL: composite.wgsl::composite
/// The display pixel for march output `cloud` (radiance rgb, transmittance), with the lens
/// flare of `flare` (the sun's light reaching the lens, [`crate::flare::flare_source`]).
pub(crate) fn composite(
    f: &Frame,
    pixel: [u32; 2],
    cloud: [f64; 4],
    surface: bool,
    flare: V3,
    rain: Option<&Rain>,
) -> [u8; 4] {
    let background = if surface {
        surface_radiance(f)
    } else {
        analytic_background(f, view_ray(f, pixel))
    };
    let light = V3::new(cloud[0], cloud[1], cloud[2]);
    let mut radiance = background * cloud[3] + light;
    if let Some(rain) = rain.filter(|_| f.rain_shafts > 0.0) {
        let veil = rain_veil(f, rain, pixel, view_ray(f, pixel));
        radiance = if rain_in_front(f) {
            through_rain(veil, radiance)
        } else {
            through_rain(veil, background) * cloud[3] + light
        };
    }
    if f.lens_flare_intensity > 0.0 {
        radiance += crate::flare::lens_flare(f, pixel, flare);
    }
    store_display(f, radiance)
}

// WGSL: composite.wgsl::analytic_sun
/// The sun's illuminance reaching the camera through the analytic sky's air: 0 below the
/// horizon.
fn analytic_sun(f: &Frame) -> V3 {
    let alt = f.camera_position[1];
    if hits_ground(f, V3::new(0.0, alt, 0.0), alt, f.sun()) {
        return V3::ZERO;
    }
    f.sun_illuminance()
}

// WGSL: composite.wgsl::analytic_background
/// What shows behind the clouds in the analytic sky where the host has no geometry: the sky's
/// gradient, and the sun's disc above the horizon.
fn analytic_background(f: &Frame, view: V3) -> V3 {
    let alt = f.camera_position[1];
    let mut background = sky_radiance(f, view, alt);
    if !hits_ground(f, V3::new(0.0, alt, 0.0), alt, view) {
        background += sun_disk(f, view);
    }
    background
}

// WGSL: composite.wgsl::composite_physical
/// The display pixel in the physical sky, for march output `cloud` at depth `depth` (m), with
/// the lens flare of `flare` (the sun's light reaching the lens).
// The WGSL pass's inputs, each a binding or a per-pixel value there.
#[allow(clippy::too_many_arguments)]
pub(crate) fn composite_physical(
    f: &Frame,
    sky: &SkyTables,
    pixel: [u32; 2],
    cloud: [f64; 4],
    depth: f64,
    surface: bool,
    flare: V3,
    rain: Option<&Rain>,
) -> [u8; 4] {
    let view = view_ray(f, pixel);
    let mut radiance = physical_composite(f, sky, pixel, view, cloud, depth, surface, rain);
    if f.lens_flare_intensity > 0.0 {
        radiance += crate::flare::lens_flare(f, pixel, flare);
    }
    store_display(f, radiance)
}

/// The display image of a `width` x `height` frame from its stored (f32) radiance and
/// transmittance, 4 floats a pixel, and depth (m), one float a pixel, as the GPU's composite
/// pass reads the march output: in the physical sky when the frame is under it (`sky`, the
/// frame's tables, then given), else the analytic one; the host's geometry where `surface`
/// (the frame's scene depth) covers a pixel.
// The WGSL pass's inputs, each a binding or a per-pixel value there.
#[allow(clippy::too_many_arguments)]
pub(crate) fn composite_image(
    f: &Frame,
    sky: Option<&SkyTables>,
    width: u32,
    height: u32,
    radiance: &[f32],
    depth: &[f32],
    surface: Option<&stratus_graph::SceneDepth>,
    rain: Option<&Rain>,
) -> Vec<u8> {
    let sky = physical(f, sky);
    // The sun's light reaching the lens: through the air, then through the clouds (the march's
    // transmittance) over its disc, where no geometry hides it.
    let flare = if f.lens_flare_intensity > 0.0 {
        let direct = match sky {
            Some(sky) => f
                .sun_illuminance()
                .mul_v(sky.sun_transmittance(sky.camera_air_origin(f).y, f.sun().y)),
            None => analytic_sun(f),
        };
        crate::flare::flare_source(f, direct, |[x, y]| {
            if crate::march::surface_at(f, surface, [x, y]) {
                0.0
            } else {
                f64::from(radiance[4 * (y * width + x) as usize + 3])
            }
        })
    } else {
        V3::ZERO
    };
    let image: Vec<u8> = (0..height)
        .into_par_iter()
        .flat_map_iter(|y| {
            (0..width).flat_map(move |x| {
                let i = (y * width + x) as usize;
                let cloud = [0, 1, 2, 3].map(|c| f64::from(radiance[4 * i + c]));
                let surface = crate::march::surface_at(f, surface, [x, y]);
                match sky {
                    Some(sky) => {
                        let depth = f64::from(depth[i]);
                        composite_physical(f, sky, [x, y], cloud, depth, surface, flare, rain)
                    }
                    None => composite(f, [x, y], cloud, surface, flare, rain),
                }
            })
        })
        .collect();
    image
}

/// The composite pass of one scene on the CPU, for any renderer's linear output: display
/// images made from radiance alone, by one code path in f64, whichever device rendered it.
///
/// Measurements of error need this. Two devices' composite passes round the same radiance to
/// the display's 8 bits differently: an H200's all-orders truth and lavapipe's march of the
/// same empty, uniformly lit ground differ by one level everywhere, which FLIP scores about
/// 0.025 (its small differences are magnified) over a third of the image. Compositing both
/// images here leaves the difference of their clouds.
pub struct Compositor {
    f: Frame,
    sky: Option<SkyTables>,
    /// Per pixel, where the view ray enters the cloud layers (m; 0 where it meets none).
    entry: Vec<f32>,
}

impl Compositor {
    /// The composite of `scene` (its sky's tables computed, and under the physical sky the
    /// clouds' shadow on the ground from `noise`, as the frame's passes do).
    pub fn new(scene: &stratus_scene::Scene, noise: &stratus_noise::NoiseSet) -> Self {
        let model = crate::medium::Model::new(scene, crate::medium::Medium::Clouds(noise));
        let (w, h) = (model.f.size[0], model.f.size[1]);
        let entry = (0..h)
            .flat_map(|y| (0..w).map(move |x| [x, y]))
            .map(|pixel| {
                let span = crate::montecarlo::camera_interval(&model, view_ray(&model.f, pixel));
                match span.kind {
                    crate::geometry::RayKind::March => span.start as f32,
                    _ => 0.0,
                }
            })
            .collect();
        Self {
            sky: model.sky().cloned(),
            f: model.f,
            entry,
        }
    }

    /// The frame size this composite is for (width, height).
    pub fn size(&self) -> [u32; 2] {
        [self.f.size[0], self.f.size[1]]
    }

    /// The display image (RGBA8, row-major) of a frame of this scene's size from its linear
    /// radiance and transmittance (4 floats a pixel) and the clouds' depth (m, one float a
    /// pixel: where the aerial perspective in front of them ends). Where the depth is 0 but
    /// the pixel holds cloud (transmittance below 1: an image composited through another
    /// image's depth, which saw no cloud there), the view ray's entry into the cloud layers
    /// stands in for it, so that the cloud still lies behind air. `None` if the slices do not
    /// hold the frame's pixels.
    pub fn display(&self, radiance: &[f32], depth: &[f32]) -> Option<Vec<u8>> {
        let [w, h] = self.size();
        let n = (w * h) as usize;
        if radiance.len() != 4 * n || depth.len() != n {
            return None;
        }
        let depth: Vec<f32> = (0..n)
            .map(|i| {
                if depth[i] <= 0.0 && radiance[4 * i + 3] < 1.0 {
                    self.entry[i]
                } else {
                    depth[i]
                }
            })
            .collect();
        // The clouds' difference is what it measures: no rain.
        let image = composite_image(
            &self.f,
            self.sky.as_ref(),
            w,
            h,
            radiance,
            &depth,
            None,
            None,
        );
        Some(crate::post::stylise(&self.f, w, h, image, &mut Vec::new()))
    }
}
