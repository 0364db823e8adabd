//! The CPU twin of `night.wgsl`: the moon's disc, the catalogue's stars and the Milky Way.

use stratus_astro::stars::{GpuTable, RECORDS_AT, gpu_table, unpack};

use crate::frame::{FLAG_MOON_MSAA, Frame, PI, pcg, xyz};
use crate::geometry::view_ray_at;
use crate::math::{V3, saturate, smoothstep};

// WGSL: night.wgsl (constants)
const STAR_MARGIN: f64 = 0.017_453_293;
const STAR_GLARE_SHARE: f64 = 0.02;
const STAR_GLARE_WIDTH: f64 = 4.0;
const S10: f64 = 0.328_280_63;
const MILKY_WAY_CELLS: f64 = 28.0;
const GALACTIC: [[f64; 3]; 3] = [
    [-0.054_875_56, -0.873_437_09, -0.483_835_02],
    [0.494_109_43, -0.444_829_63, 0.746_982_24],
    [-0.867_666_15, -0.198_076_37, 0.455_983_78],
];

// WGSL: night.wgsl::to_celestial
/// `d` (world) in J2000 equatorial axes.
fn to_celestial(f: &Frame, d: V3) -> V3 {
    V3::new(
        d.dot(xyz(f.celestial_x)),
        d.dot(xyz(f.celestial_y)),
        d.dot(xyz(f.celestial_z)),
    )
}

// WGSL: night.wgsl::star_colour
/// The linear sRGB colour, of luminance 1, of a star of colour index `bv` (Ballesteros 2012's
/// temperature, Kim et al. 2002's Planckian locus).
pub(crate) fn star_colour(bv: f64) -> V3 {
    let t = (4600.0 * (1.0 / (0.92 * bv + 1.7) + 1.0 / (0.92 * bv + 0.62))).clamp(1667.0, 25000.0);
    let k = 1000.0 / t;
    let x = if t <= 4000.0 {
        -0.266_123_9 * k * k * k - 0.234_358_9 * k * k + 0.877_695_6 * k + 0.179_910
    } else {
        -3.025_846_9 * k * k * k + 2.107_037_9 * k * k + 0.222_634_7 * k + 0.240_390
    };
    let y = if t <= 2222.0 {
        -1.106_381_4 * x * x * x - 1.348_110_20 * x * x + 2.185_558_32 * x - 0.202_196_83
    } else if t <= 4000.0 {
        -0.954_947_6 * x * x * x - 1.374_185_93 * x * x + 2.091_370_15 * x - 0.167_488_67
    } else {
        3.081_758_0 * x * x * x - 5.873_386_70 * x * x + 3.751_129_97 * x - 0.370_014_83
    };
    let (cx, cy, cz) = (x / y, 1.0, (1.0 - x - y) / y);
    let rgb = V3::new(
        (3.2406 * cx - 1.5372 * cy - 0.4986 * cz).max(0.0),
        (-0.9689 * cx + 1.8758 * cy + 0.0415 * cz).max(0.0),
        (0.0557 * cx - 0.2040 * cy + 1.0570 * cz).max(0.0),
    );
    rgb / rgb.dot(V3::new(0.2126, 0.7152, 0.0722))
}

// WGSL: night.wgsl::splat
fn splat(r: f64, sigma: f64) -> f64 {
    (-r * r / (2.0 * sigma * sigma)).exp() / (2.0 * PI * sigma * sigma)
}

/// The angle between unit vectors from their chord (as the WGSL computes it).
fn chord_angle(a: V3, b: V3) -> f64 {
    2.0 * (0.5 * (a - b).length()).min(1.0).asin()
}

// WGSL: night.wgsl::stars
/// The stars' radiance along unit world direction `d`: the stars of its cell of the
/// catalogue's table, each a Gaussian splat of its light (see `night.wgsl`).
pub(crate) fn stars(f: &Frame, d: V3) -> V3 {
    let e0 = f.star_illuminance * f.star_intensity;
    if e0 <= 0.0 {
        return V3::ZERO;
    }
    let table: &GpuTable = gpu_table();
    let v = to_celestial(f, d);
    let cell = stratus_astro::stars::cell_of([v.x as f32, v.y as f32, v.z as f32]) as usize;
    let start = table.floats[2 * cell] as usize;
    let count = table.floats[2 * cell + 1] as usize;
    let pixel_angle = 2.0 * f.tan_half_fov / f64::from(f.size[1]);
    let glare = (STAR_GLARE_SHARE * f.star_glare_scale).min(1.0);
    let mut sum = V3::ZERO;
    for k in start..start + count {
        let at = RECORDS_AT as usize + 4 * k;
        let r = &table.floats[at..at + 4];
        let s = V3::new(f64::from(r[0]), f64::from(r[1]), f64::from(r[2]));
        let angle = chord_angle(v, s);
        if angle > STAR_MARGIN {
            continue;
        }
        let (magnitude, bv) = unpack(r[3]);
        let px = angle / pixel_angle;
        let sigma = f
            .star_min_radius
            .max(f.star_radius_scale * 10f64.powf(-0.1 * (magnitude - 6.5)));
        let weight = (1.0 - glare) * splat(px, sigma) + glare * splat(px, STAR_GLARE_WIDTH * sigma);
        sum += star_colour(bv) * (10f64.powf(-0.4 * magnitude) * weight);
    }
    sum * (e0 / (pixel_angle * pixel_angle))
}

// WGSL: night.wgsl::sky_lattice
fn lattice(c: [i32; 3]) -> f64 {
    let h = pcg((c[0] as u32).wrapping_mul(73_856_093)
        ^ (c[1] as u32).wrapping_mul(19_349_663)
        ^ (c[2] as u32).wrapping_mul(83_492_791));
    f64::from(h >> 8) * (1.0 / 16_777_216.0)
}

// WGSL: night.wgsl::sky_noise
fn value_noise(p: V3) -> f64 {
    let i = [p.x.floor(), p.y.floor(), p.z.floor()];
    let fr = [p.x - i[0], p.y - i[1], p.z - i[2]];
    let u = fr.map(|f| f * f * (3.0 - 2.0 * f));
    let c = i.map(|x| x as i32);
    let at = |dx: i32, dy: i32, dz: i32| lattice([c[0] + dx, c[1] + dy, c[2] + dz]);
    let mix = |a: f64, b: f64, t: f64| a + (b - a) * t;
    let x00 = mix(at(0, 0, 0), at(1, 0, 0), u[0]);
    let x10 = mix(at(0, 1, 0), at(1, 1, 0), u[0]);
    let x01 = mix(at(0, 0, 1), at(1, 0, 1), u[0]);
    let x11 = mix(at(0, 1, 1), at(1, 1, 1), u[0]);
    mix(mix(x00, x10, u[1]), mix(x01, x11, u[1]), u[2])
}

// WGSL: night.wgsl::milky_way_s10
/// The Milky Way's surface brightness in S10 at galactic longitude `l` and latitude `b`
/// (degrees).
pub(crate) fn milky_way_s10(l: f64, b: f64) -> f64 {
    let disc =
        200.0 * (-(b / 8.0) * (b / 8.0)).exp() * (0.45 + 0.55 * (-(l / 70.0) * (l / 70.0)).exp());
    let bulge = 900.0 * (-(l / 14.0) * (l / 14.0) - (b / 8.0) * (b / 8.0)).exp();
    let rift = 0.5
        * (-((b - 1.5) / 2.2) * ((b - 1.5) / 2.2)).exp()
        * smoothstep(5.0, 10.0, l)
        * (1.0 - smoothstep(55.0, 60.0, l));
    30.0 + (disc + bulge) * (1.0 - rift)
}

/// Galactic longitude and latitude (degrees) of J2000 unit vector `v`.
pub(crate) fn galactic(v: V3) -> (f64, f64) {
    let g = GALACTIC.map(|row| row[0] * v.x + row[1] * v.y + row[2] * v.z);
    (
        g[1].atan2(g[0]).to_degrees(),
        g[2].clamp(-1.0, 1.0).asin().to_degrees(),
    )
}

// WGSL: night.wgsl::milky_way
/// The Milky Way's radiance along unit world direction `d`.
pub(crate) fn milky_way(f: &Frame, d: V3) -> V3 {
    let e0 = f.star_illuminance * f.milky_way_intensity;
    if e0 <= 0.0 {
        return V3::ZERO;
    }
    let v = to_celestial(f, d);
    let (l, b) = galactic(v);
    let clouds =
        0.7 * value_noise(v * MILKY_WAY_CELLS) + 0.3 * value_noise(v * (2.0 * MILKY_WAY_CELLS));
    let s10 = milky_way_s10(l, b) * (0.85 + 0.3 * clouds);
    star_colour(0.75) * (e0 * S10 * s10)
}

// WGSL: night.wgsl::moon_lit
fn moon_lit(f: &Frame, d: V3, m: V3, cos_r: f64) -> f64 {
    let sin_r = (1.0 - cos_r * cos_r).sqrt();
    let offset = (d - m * d.dot(m)) / sin_r;
    let x2 = offset.dot(offset).min(1.0);
    let normal = offset - m * (1.0 - x2).sqrt();
    smoothstep(-0.02, 0.02, normal.dot(xyz(f.real_sun_direction)))
}

// WGSL: night.wgsl::moon_disc
/// The moon's disc at `pixel` (view direction `d`), its limb anti-aliased by four rotated-grid
/// samples (`FLAG_MOON_MSAA`) or spread over one pixel.
pub(crate) fn moon_disc(f: &Frame, pixel: [u32; 2], d: V3) -> V3 {
    let m = xyz(f.moon_direction);
    let cos_r = f.moon_cos_radius;
    let pixel_angle = 2.0 * f.tan_half_fov / f64::from(f.size[1]);
    if f.moon_illuminance <= 0.0 || d.dot(m) < (cos_r.acos() + 2.0 * pixel_angle).cos() {
        return V3::ZERO;
    }
    let solid_angle = 2.0 * PI * (1.0 - cos_r);
    if f.flags & FLAG_MOON_MSAA != 0 {
        let mut lit = 0.0;
        let mut o = [0.125, 0.375];
        for _ in 0..4 {
            let s = view_ray_at(
                f,
                [
                    f64::from(pixel[0]) + 0.5 + o[0],
                    f64::from(pixel[1]) + 0.5 + o[1],
                ],
            );
            o = [-o[1], o[0]];
            if s.dot(m) >= cos_r {
                lit += moon_lit(f, s, m, cos_r);
            }
        }
        return V3::splat(f.moon_illuminance / solid_angle * 0.25 * lit);
    }
    let angle = chord_angle(d, m);
    let coverage = saturate((cos_r.acos() - angle) / pixel_angle + 0.5);
    V3::splat(f.moon_illuminance / solid_angle * coverage * moon_lit(f, d, m, cos_r))
}

// WGSL: night.wgsl::night_sky
/// Everything of the night sky along `d` at `pixel`, before the air's transmittance.
pub(crate) fn night_sky(f: &Frame, pixel: [u32; 2], d: V3) -> V3 {
    moon_disc(f, pixel, d) + stars(f, d) + milky_way(f, d)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Milky Way's brightest direction is the galactic centre's, within 5 degrees: its
    /// model over the whole sky on a half-degree grid in galactic coordinates.
    #[test]
    fn the_milky_way_peaks_at_the_galactic_centre() {
        let mut best = (f64::MIN, 0.0, 0.0);
        for i in -360..360 {
            for j in -180..=180 {
                let (l, b) = (f64::from(i) * 0.5, f64::from(j) * 0.5);
                let s = milky_way_s10(l, b);
                if s > best.0 {
                    best = (s, l, b);
                }
            }
        }
        let (_, l, b) = best;
        assert!(l.hypot(b) < 5.0, "brightest at l {l}, b {b}");
    }

    /// Colours run from orange for red stars to blue-white for hot ones, each of luminance 1.
    #[test]
    fn star_colours_follow_the_colour_index() {
        let hot = star_colour(-0.3);
        let sunlike = star_colour(0.65);
        let red = star_colour(1.8);
        for c in [hot, sunlike, red] {
            assert!((c.dot(V3::new(0.2126, 0.7152, 0.0722)) - 1.0).abs() < 1e-12);
        }
        assert!(hot.z > hot.x && red.x > red.z && sunlike.x > sunlike.z);
    }
}
