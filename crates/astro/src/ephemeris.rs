//! Geocentric positions of the sun and moon, nutation, sidereal time, and the step to a
//! place's horizon. Angles in degrees unless a name says radians.
//!
//! Sources: Jean Meeus, *Astronomical Algorithms*, 2nd ed. (Willmann-Bell, 1998): the sun of
//! chapter 25 (its lower accuracy, about 0.01 degrees), nutation and obliquity of chapter 22
//! (the abridged series, 0.5"), sidereal time of chapter 12, and the moon of chapter 47 (the
//! largest periodic terms of the ELP-2000/82 theory of Chapront-Touzé and Chapront; the
//! terms kept here leave errors of a few hundredths of a degree).

use crate::time::UtcDateTime;

/// Astronomical unit in km (IAU 2012).
pub const AU_KM: f64 = 149_597_870.7;
/// WGS 84 equatorial radius in km and flattening.
const EARTH_A_KM: f64 = 6378.137;
const EARTH_F: f64 = 1.0 / 298.257_223_563;

fn sin(deg: f64) -> f64 {
    deg.to_radians().sin()
}
fn cos(deg: f64) -> f64 {
    deg.to_radians().cos()
}

/// Julian centuries of TT since J2000.0.
fn centuries(t: UtcDateTime) -> f64 {
    (t.julian_ephemeris_day() - 2_451_545.0) / 36_525.0
}

/// Nutation in longitude and obliquity, and the true obliquity of the ecliptic, in degrees.
pub struct Nutation {
    /// Nutation in longitude.
    pub delta_psi: f64,
    /// Nutation in obliquity.
    pub delta_epsilon: f64,
    /// The true obliquity of the ecliptic (mean plus nutation in obliquity).
    pub epsilon: f64,
}

/// Meeus ch. 22, the abridged series.
pub fn nutation(t: UtcDateTime) -> Nutation {
    let c = centuries(t);
    let omega = 125.04452 - 1934.136261 * c;
    let l_sun = 280.4665 + 36000.7698 * c;
    let l_moon = 218.3165 + 481267.8813 * c;
    let delta_psi = (-17.20 * sin(omega) - 1.32 * sin(2.0 * l_sun) - 0.23 * sin(2.0 * l_moon)
        + 0.21 * sin(2.0 * omega))
        / 3600.0;
    let delta_eps = (9.20 * cos(omega) + 0.57 * cos(2.0 * l_sun) + 0.10 * cos(2.0 * l_moon)
        - 0.09 * cos(2.0 * omega))
        / 3600.0;
    let eps0 = 23.0
        + 26.0 / 60.0
        + 21.448 / 3600.0
        + (-46.8150 * c - 0.00059 * c * c + 0.001_813 * c * c * c) / 3600.0;
    Nutation {
        delta_psi,
        delta_epsilon: delta_eps,
        epsilon: eps0 + delta_eps,
    }
}

/// A geocentric position: apparent ecliptic longitude and latitude (of date) and distance.
#[derive(Clone, Copy, Debug)]
pub struct Ecliptic {
    /// Apparent ecliptic longitude of date.
    pub longitude: f64,
    /// Ecliptic latitude.
    pub latitude: f64,
    /// Distance from Earth's centre in km.
    pub distance_km: f64,
}

/// The sun's apparent geocentric position (Meeus ch. 25, with chapter 22's nutation and the
/// annual aberration of 20.4898"/R).
pub fn sun(t: UtcDateTime) -> Ecliptic {
    let c = centuries(t);
    let l0 = 280.466_46 + 36_000.769_83 * c + 0.000_303_2 * c * c;
    let m = 357.529_11 + 35_999.050_29 * c - 0.000_153_7 * c * c;
    let e = 0.016_708_634 - 0.000_042_037 * c - 0.000_000_126_7 * c * c;
    let centre = (1.914_602 - 0.004_817 * c - 0.000_014 * c * c) * sin(m)
        + (0.019_993 - 0.000_101 * c) * sin(2.0 * m)
        + 0.000_289 * sin(3.0 * m);
    let true_longitude = l0 + centre;
    let anomaly = m + centre;
    let r_au = 1.000_001_018 * (1.0 - e * e) / (1.0 + e * cos(anomaly));
    let n = nutation(t);
    Ecliptic {
        longitude: true_longitude + n.delta_psi - 20.4898 / 3600.0 / r_au,
        latitude: 0.0,
        distance_km: r_au * AU_KM,
    }
}

/// One periodic term of the moon's series: multiples of D, M, M', F and the coefficient.
type Term = (i8, i8, i8, i8, f64);

/// Longitude (1e-6 degrees, sine) and distance (1e-3 km, cosine) terms: the largest of
/// Meeus Table 47.A, down to about 2000e-6 degrees in longitude (the 0.0 distance terms are
/// below that table's precision or absent).
const LONGITUDE_DISTANCE: [(i8, i8, i8, i8, f64, f64); 34] = [
    (0, 0, 1, 0, 6_288_774.0, -20_905_355.0),
    (2, 0, -1, 0, 1_274_027.0, -3_699_111.0),
    (2, 0, 0, 0, 658_314.0, -2_955_968.0),
    (0, 0, 2, 0, 213_618.0, -569_925.0),
    (0, 1, 0, 0, -185_116.0, 48_888.0),
    (0, 0, 0, 2, -114_332.0, -3_149.0),
    (2, 0, -2, 0, 58_793.0, 246_158.0),
    (2, -1, -1, 0, 57_066.0, -152_138.0),
    (2, 0, 1, 0, 53_322.0, -170_733.0),
    (2, -1, 0, 0, 45_758.0, -204_586.0),
    (0, 1, -1, 0, -40_923.0, -129_620.0),
    (1, 0, 0, 0, -34_720.0, 108_743.0),
    (0, 1, 1, 0, -30_383.0, 104_755.0),
    (2, 0, 0, -2, 15_327.0, 10_321.0),
    (0, 0, 1, 2, -12_528.0, 0.0),
    (0, 0, 1, -2, 10_980.0, 79_661.0),
    (4, 0, -1, 0, 10_675.0, -34_782.0),
    (0, 0, 3, 0, 10_034.0, -23_210.0),
    (4, 0, -2, 0, 8_548.0, -21_636.0),
    (2, 1, -1, 0, -7_888.0, 24_208.0),
    (2, 1, 0, 0, -6_766.0, 30_824.0),
    (1, 0, -1, 0, -5_163.0, -8_379.0),
    (1, 1, 0, 0, 4_987.0, -16_675.0),
    (2, -1, 1, 0, 4_036.0, -12_831.0),
    (2, 0, 2, 0, 3_994.0, -10_445.0),
    (4, 0, 0, 0, 3_861.0, -11_650.0),
    (2, 0, -3, 0, 3_665.0, 14_403.0),
    (0, 1, -2, 0, -2_689.0, -7_003.0),
    (2, 0, -1, 2, -2_602.0, 0.0),
    (2, -1, -2, 0, 2_390.0, 10_056.0),
    (1, 0, 1, 0, -2_348.0, 6_322.0),
    (2, -2, 0, 0, 2_236.0, -9_884.0),
    (0, 1, 2, 0, -2_120.0, 5_751.0),
    (0, 2, 0, 0, -2_069.0, 0.0),
];

/// Latitude terms (1e-6 degrees, sine): the largest of Meeus Table 47.B, down to about
/// 1100e-6 degrees.
const LATITUDE: [Term; 28] = [
    (0, 0, 0, 1, 5_128_122.0),
    (0, 0, 1, 1, 280_602.0),
    (0, 0, 1, -1, 277_693.0),
    (2, 0, 0, -1, 173_237.0),
    (2, 0, -1, 1, 55_413.0),
    (2, 0, -1, -1, 46_271.0),
    (2, 0, 0, 1, 32_573.0),
    (0, 0, 2, 1, 17_198.0),
    (2, 0, 1, -1, 9_266.0),
    (0, 0, 2, -1, 8_822.0),
    (2, -1, 0, -1, 8_216.0),
    (2, 0, -2, -1, 4_324.0),
    (2, 0, 1, 1, 4_200.0),
    (2, 1, 0, -1, -3_359.0),
    (2, -1, -1, 1, 2_463.0),
    (2, -1, 0, 1, 2_211.0),
    (2, -1, -1, -1, 2_065.0),
    (0, 1, -1, -1, -1_870.0),
    (4, 0, -1, -1, 1_828.0),
    (0, 1, 0, 1, -1_794.0),
    (0, 0, 0, 3, -1_749.0),
    (0, 1, -1, 1, -1_565.0),
    (1, 0, 0, 1, -1_491.0),
    (0, 1, 1, 1, -1_475.0),
    (0, 1, 1, -1, -1_410.0),
    (0, 1, 0, -1, -1_344.0),
    (1, 0, 0, -1, -1_335.0),
    (0, 0, 3, 1, 1_107.0),
];

/// The moon's apparent geocentric position (Meeus ch. 47 with the terms above, plus the
/// additive terms of Venus, Jupiter and the Earth's flattening, and nutation in longitude).
pub fn moon(t: UtcDateTime) -> Ecliptic {
    let c = centuries(t);
    let (c2, c3, c4) = (c * c, c * c * c, c * c * c * c);
    let l = 218.316_447_7 + 481_267.881_234_21 * c - 0.001_578_6 * c2 + c3 / 538_841.0
        - c4 / 65_194_000.0;
    let d = 297.850_192_1 + 445_267.111_403_4 * c - 0.001_881_9 * c2 + c3 / 545_868.0
        - c4 / 113_065_000.0;
    let m = 357.529_109_2 + 35_999.050_290_9 * c - 0.000_153_6 * c2 + c3 / 24_490_000.0;
    let mp = 134.963_396_4 + 477_198.867_505_5 * c + 0.008_741_4 * c2 + c3 / 69_699.0
        - c4 / 14_712_000.0;
    let f = 93.272_095_0 + 483_202.017_523_3 * c - 0.003_653_9 * c2 - c3 / 3_526_000.0
        + c4 / 863_310_000.0;
    let a1 = 119.75 + 131.849 * c;
    let a2 = 53.09 + 479_264.290 * c;
    let a3 = 313.45 + 481_266.484 * c;
    // The sun's eccentricity decreases: terms in M are scaled by E, in 2M by E squared.
    let ecc = 1.0 - 0.002_516 * c - 0.000_007_4 * c2;
    let scale = |mm: i8| match mm.abs() {
        1 => ecc,
        2 => ecc * ecc,
        _ => 1.0,
    };
    let arg = |dd: i8, mm: i8, mpp: i8, ff: i8| {
        f64::from(dd) * d + f64::from(mm) * m + f64::from(mpp) * mp + f64::from(ff) * f
    };
    let (mut sl, mut sr, mut sb) = (0.0, 0.0, 0.0);
    for &(dd, mm, mpp, ff, cl, cr) in &LONGITUDE_DISTANCE {
        let a = arg(dd, mm, mpp, ff);
        sl += cl * scale(mm) * sin(a);
        sr += cr * scale(mm) * cos(a);
    }
    for &(dd, mm, mpp, ff, cb) in &LATITUDE {
        sb += cb * scale(mm) * sin(arg(dd, mm, mpp, ff));
    }
    sl += 3958.0 * sin(a1) + 1962.0 * sin(l - f) + 318.0 * sin(a2);
    sb += -2235.0 * sin(l)
        + 382.0 * sin(a3)
        + 175.0 * sin(a1 - f)
        + 175.0 * sin(a1 + f)
        + 127.0 * sin(l - mp)
        - 115.0 * sin(l + mp);
    Ecliptic {
        longitude: l + sl / 1e6 + nutation(t).delta_psi,
        latitude: sb / 1e6,
        distance_km: 385_000.56 + sr / 1000.0,
    }
}

/// Greenwich apparent sidereal time in degrees (Meeus ch. 12, with the equation of the
/// equinoxes). UT1 is taken as UTC (they differ by less than 0.9 s).
pub fn apparent_sidereal_time(t: UtcDateTime) -> f64 {
    let jd = t.julian_day();
    let c = (jd - 2_451_545.0) / 36_525.0;
    let mean = 280.460_618_37 + 360.985_647_366_29 * (jd - 2_451_545.0) + 0.000_387_933 * c * c
        - c * c * c / 38_710_000.0;
    let n = nutation(t);
    (mean + n.delta_psi * cos(n.epsilon)).rem_euclid(360.0)
}

/// A body seen from a place: elevation above the horizon (geometric, no refraction) and
/// azimuth clockwise from north, in degrees, and the distance in km.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Horizontal {
    /// Degrees above the horizon (geometric: no refraction).
    pub elevation_deg: f64,
    /// Degrees clockwise from north.
    pub azimuth_deg: f64,
    /// Distance from the place in km.
    pub distance_km: f64,
}

/// `body` seen from the place at geodetic `latitude`, east `longitude` (degrees) on the
/// WGS 84 ellipsoid at sea level: the topocentric position (the moon shifts by up to a
/// degree from the geocentric one), then the horizon of the ellipsoid's normal.
pub fn horizontal(t: UtcDateTime, body: Ecliptic, latitude: f64, longitude: f64) -> Horizontal {
    let eps = nutation(t).epsilon;
    // Geocentric equatorial vector of the body (of date).
    let (lam, beta) = (body.longitude, body.latitude);
    let ecl = [cos(beta) * cos(lam), cos(beta) * sin(lam), sin(beta)];
    let eq = [
        ecl[0],
        ecl[1] * cos(eps) - ecl[2] * sin(eps),
        ecl[1] * sin(eps) + ecl[2] * cos(eps),
    ];
    // The observer's geocentric vector in the same axes (Meeus ch. 11).
    let theta = apparent_sidereal_time(t) + longitude;
    let u = ((1.0 - EARTH_F) * latitude.to_radians().tan()).atan();
    let rho_sin = (1.0 - EARTH_F) * u.sin();
    let rho_cos = u.cos();
    let obs = [
        EARTH_A_KM * rho_cos * cos(theta),
        EARTH_A_KM * rho_cos * sin(theta),
        EARTH_A_KM * rho_sin,
    ];
    let topo = [
        body.distance_km * eq[0] - obs[0],
        body.distance_km * eq[1] - obs[1],
        body.distance_km * eq[2] - obs[2],
    ];
    let distance_km = (topo[0] * topo[0] + topo[1] * topo[1] + topo[2] * topo[2]).sqrt();
    let dec = (topo[2] / distance_km).asin().to_degrees();
    let ra = topo[1].atan2(topo[0]).to_degrees();
    let h = theta - ra;
    let phi = latitude;
    let elevation = (sin(phi) * sin(dec) + cos(phi) * cos(dec) * cos(h))
        .clamp(-1.0, 1.0)
        .asin()
        .to_degrees();
    // Measured from the south, westward; turned to clockwise from north.
    let from_south = (cos(dec) * sin(h))
        .atan2(cos(dec) * cos(h) * sin(phi) - sin(dec) * cos(phi))
        .to_degrees();
    Horizontal {
        elevation_deg: elevation,
        azimuth_deg: (from_south + 180.0).rem_euclid(360.0),
        distance_km,
    }
}

/// The moon's illuminated fraction, 0 (new) to 1 (full): from the geocentric elongation of
/// the moon from the sun and the phase angle (Meeus ch. 48).
pub fn moon_illuminated_fraction(t: UtcDateTime) -> f64 {
    let (s, m) = (sun(t), moon(t));
    let cos_psi = cos(m.latitude) * cos(m.longitude - s.longitude);
    let psi = cos_psi.clamp(-1.0, 1.0).acos();
    let i = (s.distance_km * psi.sin()).atan2(m.distance_km - s.distance_km * psi.cos());
    (1.0 + i.cos()) / 2.0
}
