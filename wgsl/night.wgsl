// The night sky behind the air (seed 001's night parameters, `[night]`): the moon's disc, the
// catalogue's stars and the Milky Way. The physical composite adds them above the horizon
// through the air's transmittance. Stars and the Milky Way live in J2000 equatorial
// coordinates; `frame.celestial_x/y/z` (the J2000 axes' world directions at the scene's date
// and place) turn a view direction into them.

@group(0) @binding(48) var star_table_in: texture_2d<f32>;  // stratus_astro::stars::gpu_table

// The table's layout (stratus_astro::stars): cells along a cube face's edge, the texture's
// width, and the first record's float index (two floats a cell before it).
const STAR_CELLS: u32 = 16u;
const STAR_TABLE_WIDTH: u32 = 1024u;
const STAR_RECORDS_AT: u32 = 3072u;
// How far from its cell a listed star may lie (radians, 1 degree): a star's light is drawn
// out to here and no farther.
const STAR_MARGIN: f32 = 0.017453293;
// The glare's share of a star's light per unit `star_glare_scale`, and its width over the
// core's.
const STAR_GLARE_SHARE: f32 = 0.02;
const STAR_GLARE_WIDTH: f32 = 4.0;

fn star_float(i: u32) -> f32 {
    return textureLoad(star_table_in, vec2<u32>(i % STAR_TABLE_WIDTH, i / STAR_TABLE_WIDTH), 0).r;
}

// `d` (world) in J2000 equatorial axes.
fn to_celestial(d: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(dot(d, frame.celestial_x), dot(d, frame.celestial_y), dot(d, frame.celestial_z));
}

// The cube-map cell that unit `v` falls in (as stratus_astro::stars::cell_of).
fn star_cell(v: vec3<f32>) -> u32 {
    let a = abs(v);
    var face = 0u;
    var uv = vec2<f32>(0.0);
    var major = 0.0;
    if a.x >= a.y && a.x >= a.z {
        face = select(1u, 0u, v.x > 0.0);
        uv = v.zy;
        major = a.x;
    } else if a.y >= a.z {
        face = select(3u, 2u, v.y > 0.0);
        uv = v.xz;
        major = a.y;
    } else {
        face = select(5u, 4u, v.z > 0.0);
        uv = v.xy;
        major = a.z;
    }
    let st = clamp((uv / major) * 0.5 + 0.5, vec2<f32>(0.0), vec2<f32>(0.999999));
    let cell = vec2<u32>(st * f32(STAR_CELLS));
    return (face * STAR_CELLS + cell.y) * STAR_CELLS + cell.x;
}

// The linear sRGB colour, of luminance 1, of a star of colour index `bv`: its temperature by
// Ballesteros 2012 (EPL 97, 34008), T = 4600 (1 / (0.92 bv + 1.7) + 1 / (0.92 bv + 0.62)),
// and the Planckian locus's chromaticity at T by Kim et al. 2002's cubic spline (IEEE Trans.
// Consumer Electronics 48, 1667-25000 K).
fn star_colour(bv: f32) -> vec3<f32> {
    let t = clamp(4600.0 * (1.0 / (0.92 * bv + 1.7) + 1.0 / (0.92 * bv + 0.62)), 1667.0, 25000.0);
    let k = 1000.0 / t;  // the spline in 1e3 / T keeps its powers in range in f32
    var x = 0.0;
    if t <= 4000.0 {
        x = -0.2661239 * k * k * k - 0.2343589 * k * k + 0.8776956 * k + 0.179910;
    } else {
        x = -3.0258469 * k * k * k + 2.1070379 * k * k + 0.2226347 * k + 0.240390;
    }
    var y = 0.0;
    if t <= 2222.0 {
        y = -1.1063814 * x * x * x - 1.34811020 * x * x + 2.18555832 * x - 0.20219683;
    } else if t <= 4000.0 {
        y = -0.9549476 * x * x * x - 1.37418593 * x * x + 2.09137015 * x - 0.16748867;
    } else {
        y = 3.0817580 * x * x * x - 5.87338670 * x * x + 3.75112997 * x - 0.37001483;
    }
    let xyz = vec3<f32>(x / y, 1.0, (1.0 - x - y) / y);
    let rgb = max(vec3<f32>(
        3.2406 * xyz.x - 1.5372 * xyz.y - 0.4986 * xyz.z,
        -0.9689 * xyz.x + 1.8758 * xyz.y + 0.0415 * xyz.z,
        0.0557 * xyz.x - 0.2040 * xyz.y + 1.0570 * xyz.z,
    ), vec3<f32>(0.0));
    return rgb / dot(rgb, vec3<f32>(0.2126, 0.7152, 0.0722));
}

// A normalised 2D Gaussian of deviation `sigma` at distance `r` (pixels).
fn splat(r: f32, sigma: f32) -> f32 {
    return exp(-r * r / (2.0 * sigma * sigma)) / (2.0 * PI * sigma * sigma);
}

// The stars' radiance along unit world direction `d`: each catalogue star of the direction's
// cell a point of illuminance E0 10^(-0.4 m) (`frame.star_illuminance` the magnitude-0 star's,
// times `frame.star_intensity`), spread over a Gaussian of at least `star_min_radius`
// pixels, growing by `star_radius_scale` with the fourth root of its light, 2% of it times
// `star_glare_scale` in a glare four times as wide; the light does not depend on the size.
fn stars(d: vec3<f32>) -> vec3<f32> {
    let e0 = frame.star_illuminance * frame.star_intensity;
    if e0 <= 0.0 {
        return vec3<f32>(0.0);
    }
    let v = to_celestial(d);
    let cell = star_cell(v);
    let start = u32(star_float(2u * cell));
    let count = u32(star_float(2u * cell + 1u));
    // Angular size of a pixel at the image centre.
    let pixel_angle = 2.0 * frame.tan_half_fov / f32(frame.size.y);
    let glare = min(STAR_GLARE_SHARE * frame.star_glare_scale, 1.0);
    var sum = vec3<f32>(0.0);
    for (var k = 0u; k < count; k++) {
        let at = STAR_RECORDS_AT + 4u * (start + k);
        let s = vec3<f32>(star_float(at), star_float(at + 1u), star_float(at + 2u));
        // The angle from its chord: accurate where acos of a dot product near 1 is not.
        let angle = 2.0 * asin(min(0.5 * length(v - s), 1.0));
        if angle > STAR_MARGIN {
            continue;
        }
        let packed = u32(star_float(at + 3u));
        let magnitude = f32(packed / 1024u) * 0.01 - 2.0;
        let bv = f32(packed % 1024u) / 300.0 - 0.5;
        let r = angle / pixel_angle;
        let sigma = max(frame.star_min_radius, frame.star_radius_scale * pow(10.0, -0.1 * (magnitude - 6.5)));
        let weight = (1.0 - glare) * splat(r, sigma) + glare * splat(r, STAR_GLARE_WIDTH * sigma);
        sum += star_colour(bv) * (pow(10.0, -0.4 * magnitude) * weight);
    }
    return sum * (e0 / (pixel_angle * pixel_angle));
}

// The J2000 equatorial axes' galactic coordinates (rows: toward the galactic centre, l = 90,
// and the north galactic pole; stratus_astro::celestial::equatorial_to_galactic, the
// Hipparcos definition).
const GALACTIC_X: vec3<f32> = vec3<f32>(-0.05487556, -0.87343709, -0.48383502);
const GALACTIC_Y: vec3<f32> = vec3<f32>(0.49410943, -0.44482963, 0.74698224);
const GALACTIC_Z: vec3<f32> = vec3<f32>(-0.86766615, -0.19807637, 0.45598378);
// One S10 (a tenth-magnitude star per square degree) in units of a magnitude-0 star's
// illuminance per steradian: 1e-4 / (pi / 180)^2.
const S10: f32 = 0.32828063;
// Value noise over the sphere (cells of about 2 degrees): the star clouds' mottling.
const MILKY_WAY_CELLS: f32 = 28.0;

fn sky_lattice(c: vec3<i32>) -> f32 {
    let h = pcg((u32(c.x) * 73856093u) ^ (u32(c.y) * 19349663u) ^ (u32(c.z) * 83492791u));
    return f32(h >> 8u) * (1.0 / 16777216.0);
}

// Trilinear value noise in [0, 1) at `p`.
fn sky_noise(p: vec3<f32>) -> f32 {
    let i = floor(p);
    let f = p - i;
    let u = f * f * (3.0 - 2.0 * f);
    let c = vec3<i32>(i);
    let x00 = mix(sky_lattice(c), sky_lattice(c + vec3<i32>(1, 0, 0)), u.x);
    let x10 = mix(sky_lattice(c + vec3<i32>(0, 1, 0)), sky_lattice(c + vec3<i32>(1, 1, 0)), u.x);
    let x01 = mix(sky_lattice(c + vec3<i32>(0, 0, 1)), sky_lattice(c + vec3<i32>(1, 0, 1)), u.x);
    let x11 = mix(sky_lattice(c + vec3<i32>(0, 1, 1)), sky_lattice(c + vec3<i32>(1, 1, 1)), u.x);
    return mix(mix(x00, x10, u.y), mix(x01, x11, u.y), u.z);
}

// The Milky Way's surface brightness in S10 at galactic longitude `l` and latitude `b`
// (degrees, l in (-180, 180]), the starlight of the stars fainter than the catalogue's: a
// floor of 30 at the galactic poles, a disc 8 degrees thick (Gaussian) of 200 toward the
// centre falling to 90 toward the anticentre, the bulge of 900 more around the centre
// (14 by 8 degrees), shaped after Leinert et al. 1998 (A&AS 127, 1, figure 35's map of the
// integrated starlight). The Great Rift's dust dims a lane just north of the plane between
// l = 10 and 60 degrees by up to half.
fn milky_way_s10(l: f32, b: f32) -> f32 {
    let disc = 200.0 * exp(-(b / 8.0) * (b / 8.0)) * (0.45 + 0.55 * exp(-(l / 70.0) * (l / 70.0)));
    let bulge = 900.0 * exp(-(l / 14.0) * (l / 14.0) - (b / 8.0) * (b / 8.0));
    let rift = 0.5 * exp(-((b - 1.5) / 2.2) * ((b - 1.5) / 2.2))
        * smoothstep(5.0, 10.0, l) * (1.0 - smoothstep(55.0, 60.0, l));
    return 30.0 + (disc + bulge) * (1.0 - rift);
}

// The Milky Way's radiance along unit world direction `d` (`night.milky_way_intensity`
// times the model's): warm white (integrated starlight's colour index, about 0.75), mottled
// by +-15% of value noise on the sphere into star clouds.
fn milky_way(d: vec3<f32>) -> vec3<f32> {
    let e0 = frame.star_illuminance * frame.milky_way_intensity;
    if e0 <= 0.0 {
        return vec3<f32>(0.0);
    }
    let v = to_celestial(d);
    let g = vec3<f32>(dot(v, GALACTIC_X), dot(v, GALACTIC_Y), dot(v, GALACTIC_Z));
    let b = degrees(asin(clamp(g.z, -1.0, 1.0)));
    let l = degrees(atan2(g.y, g.x));
    let clouds = 0.7 * sky_noise(v * MILKY_WAY_CELLS) + 0.3 * sky_noise(v * (2.0 * MILKY_WAY_CELLS));
    let s10 = milky_way_s10(l, b) * (0.85 + 0.3 * clouds);
    return star_colour(0.75) * (e0 * S10 * s10);
}

// The moon's disc at `pixel` (view direction `d`): the full moon's illuminance over the
// disc's solid angle where the sun lights the moon's sphere, 0 on its night side and off the
// disc. The full moon shows almost no limb darkening, so the lit part is of even brightness;
// the terminator is softened over 2% of the radius. The limb is anti-aliased by
// `night.moon_msaa`: four samples of the pixel on a rotated grid, or (default) the disc's
// edge spread over one pixel.
fn moon_disc(pixel: vec2<u32>, d: vec3<f32>) -> vec3<f32> {
    let m = frame.moon_direction;
    let cos_r = frame.moon_cos_radius;
    let pixel_angle = 2.0 * frame.tan_half_fov / f32(frame.size.y);
    if frame.moon_illuminance <= 0.0 || dot(d, m) < cos(acos(cos_r) + 2.0 * pixel_angle) {
        return vec3<f32>(0.0);
    }
    let solid_angle = 2.0 * PI * (1.0 - cos_r);
    if (frame.flags & FLAG_MOON_MSAA) != 0u {
        var lit = 0.0;
        // The rotated grid: (1/8, 3/8) of a pixel from its centre, turned by quarter turns.
        var o = vec2<f32>(0.125, 0.375);
        for (var k = 0u; k < 4u; k++) {
            let s = view_ray_at(vec2<f32>(pixel) + 0.5 + o);
            o = vec2<f32>(-o.y, o.x);
            if dot(s, m) >= cos_r {
                lit += moon_lit(s, m, cos_r);
            }
        }
        return vec3<f32>(frame.moon_illuminance / solid_angle * 0.25 * lit);
    }
    let angle = 2.0 * asin(min(0.5 * length(d - m), 1.0));
    let coverage = saturate((acos(cos_r) - angle) / pixel_angle + 0.5);
    return vec3<f32>(frame.moon_illuminance / solid_angle * coverage * moon_lit(d, m, cos_r));
}

// How lit the moon's sphere is where direction `d` meets it (`m` its centre, `cos_r` its
// radius): 1 on the day side, 0 on the night side, over 2% of the radius between.
fn moon_lit(d: vec3<f32>, m: vec3<f32>, cos_r: f32) -> f32 {
    let sin_r = sqrt(1.0 - cos_r * cos_r);
    let offset = (d - m * dot(d, m)) / sin_r;   // in units of the disc's radius
    let x2 = min(dot(offset, offset), 1.0);
    let normal = offset - m * sqrt(1.0 - x2);  // the visible hemisphere faces the camera
    return smoothstep(-0.02, 0.02, dot(normal, frame.real_sun_direction));
}

// Everything of the night sky along `d` at `pixel`, before the air's transmittance.
fn night_sky(pixel: vec2<u32>, d: vec3<f32>) -> vec3<f32> {
    return moon_disc(pixel, d) + stars(d) + milky_way(d);
}
