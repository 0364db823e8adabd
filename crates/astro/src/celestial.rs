//! The celestial sphere seen from a place: the rotation from J2000 equatorial coordinates (the
//! catalogue's frame) to the place's horizon at an instant, and galactic coordinates.
//!
//! The chain is precession from J2000 to the mean equator and equinox of date (IAU 1976,
//! Lieske et al. 1977, "Expressions for the precession quantities based upon the IAU (1976)
//! system of astronomical constants", A&A 58, 1; as Meeus gives them, ch. 21), nutation to the
//! true equator of date (Meeus ch. 22, the abridged series of [`crate::ephemeris::nutation`]),
//! Greenwich apparent sidereal time (Meeus ch. 12) and the place's meridian and latitude.
//! Left out, each below 0.01 degrees for the naked-eye stars: annual aberration (at most
//! 20.5"), the stars' parallax (under 1"), and their proper motion since J2000 (the largest
//! of a bright star, alpha Centauri's 3.7" a year, moves it 0.03 degrees by 2030).

use crate::ephemeris::{apparent_sidereal_time, nutation};
use crate::{Place, UtcDateTime};

/// A 3x3 rotation, row-major: `m[i]` is row i.
pub type Matrix3 = [[f64; 3]; 3];

fn mul(a: &Matrix3, b: &Matrix3) -> Matrix3 {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

/// `m v`.
pub fn apply(m: &Matrix3, v: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2])
}

/// The transpose (the inverse of a rotation).
pub fn transpose(m: &Matrix3) -> Matrix3 {
    std::array::from_fn(|i| std::array::from_fn(|j| m[j][i]))
}

/// Rotations of the axes (not of the vector) by `a` radians about x, y and z: a vector's
/// coordinates in axes turned by `a`.
fn r1(a: f64) -> Matrix3 {
    let (s, c) = a.sin_cos();
    [[1.0, 0.0, 0.0], [0.0, c, s], [0.0, -s, c]]
}
fn r2(a: f64) -> Matrix3 {
    let (s, c) = a.sin_cos();
    [[c, 0.0, -s], [0.0, 1.0, 0.0], [s, 0.0, c]]
}
fn r3(a: f64) -> Matrix3 {
    let (s, c) = a.sin_cos();
    [[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]]
}

/// The unit vector of right ascension `ra_deg` and declination `dec_deg` in their equatorial
/// axes (x toward the equinox, z toward the north pole).
pub fn equatorial_vector(ra_deg: f64, dec_deg: f64) -> [f64; 3] {
    let (ra, dec) = (ra_deg.to_radians(), dec_deg.to_radians());
    [dec.cos() * ra.cos(), dec.cos() * ra.sin(), dec.sin()]
}

/// Precession from J2000 to the mean equator and equinox of `t` (IAU 1976 angles zeta, z and
/// theta in Julian centuries of TT).
fn precession(t: UtcDateTime) -> Matrix3 {
    let c = (t.julian_ephemeris_day() - 2_451_545.0) / 36_525.0;
    let arcsec = |x: f64| (x / 3600.0).to_radians();
    let zeta = arcsec(2306.2181 * c + 0.30188 * c * c + 0.017_998 * c * c * c);
    let z = arcsec(2306.2181 * c + 1.09468 * c * c + 0.018_203 * c * c * c);
    let theta = arcsec(2004.3109 * c - 0.42665 * c * c - 0.041_833 * c * c * c);
    mul(&r3(-z), &mul(&r2(theta), &r3(-zeta)))
}

/// Nutation from the mean to the true equator and equinox of `t`.
fn nutation_matrix(t: UtcDateTime) -> Matrix3 {
    let n = nutation(t);
    let eps = n.epsilon.to_radians();
    let eps0 = (n.epsilon - n.delta_epsilon).to_radians();
    mul(&r1(-eps), &mul(&r3(-n.delta_psi.to_radians()), &r1(eps0)))
}

/// The rotation that takes a J2000 equatorial unit vector to the direction it is seen in from
/// `place` at `t`, in Stratus's world axes: x east, y up (the ellipsoid's normal), z north.
/// Geometric (no refraction), as the sun's and moon's positions are.
pub fn equatorial_to_world(place: Place, t: UtcDateTime) -> Matrix3 {
    let of_date = mul(&nutation_matrix(t), &precession(t));
    // Turned to the local meridian: x toward hour angle 0, y toward hour angle -6 h (east).
    let last = (apparent_sidereal_time(t) + place.longitude_deg).to_radians();
    let meridian = mul(&r3(last), &of_date);
    let (s, c) = place.latitude_deg.to_radians().sin_cos();
    // East is y; up sin(phi) x + cos(phi) z; north -sin(phi) x + cos(phi) z.
    let horizon = [[0.0, 1.0, 0.0], [c, 0.0, s], [-s, 0.0, c]];
    mul(&horizon, &meridian)
}

/// The rotation from J2000 equatorial to galactic axes (x toward the galactic centre, z
/// toward the north galactic pole): the pole at right ascension 192.85948 degrees,
/// declination 27.12825, and the north celestial pole at galactic longitude 122.93192 (the
/// Hipparcos catalogue's definition, ESA 1997, vol. 1, section 1.5.3).
pub fn equatorial_to_galactic() -> Matrix3 {
    let (ra_p, dec_p, l_ncp) = (192.859_48f64, 27.128_25f64, 122.931_92f64);
    // Rows: the galactic axes in equatorial coordinates. z is the pole; x the direction at
    // l = 0, b = 0, which lies 90 degrees from the pole at position angle l_ncp from it.
    let z = equatorial_vector(ra_p, dec_p);
    let ncp = [0.0, 0.0, 1.0];
    // The NCP's galactic coordinates: b = dec_p, l = l_ncp. So NCP = cos(b)(cos l x + sin l y)
    // + sin(b) z; with y = z x x, solve for x from the component of the NCP across z.
    let across: [f64; 3] = std::array::from_fn(|i| ncp[i] - dec_p.to_radians().sin() * z[i]);
    let norm = across.iter().map(|a| a * a).sum::<f64>().sqrt();
    let u: [f64; 3] = std::array::from_fn(|i| across[i] / norm);
    // u = cos(l_ncp) x + sin(l_ncp) y, and y = z x x: x = cos(l) u - sin(l) (z x u).
    let zxu = [
        z[1] * u[2] - z[2] * u[1],
        z[2] * u[0] - z[0] * u[2],
        z[0] * u[1] - z[1] * u[0],
    ];
    let (sl, cl) = l_ncp.to_radians().sin_cos();
    let x: [f64; 3] = std::array::from_fn(|i| cl * u[i] - sl * zxu[i]);
    let y = [
        z[1] * x[2] - z[2] * x[1],
        z[2] * x[0] - z[0] * x[2],
        z[0] * x[1] - z[1] * x[0],
    ];
    [x, y, z]
}

/// A direction in world axes as elevation above the horizon and azimuth clockwise from
/// north, degrees.
pub fn world_to_horizontal(v: [f64; 3]) -> (f64, f64) {
    let el = v[1].clamp(-1.0, 1.0).asin().to_degrees();
    let az = v[0].atan2(v[2]).to_degrees().rem_euclid(360.0);
    (el, az)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The galactic centre and pole land where the Hipparcos definition puts them in J2000:
    /// the centre at right ascension 266.405, declination -28.936 (its published J2000
    /// position, to 0.001 degrees).
    #[test]
    fn the_galactic_axes_match_their_definition() {
        let g = equatorial_to_galactic();
        let centre = g[0];
        let ra = centre[1].atan2(centre[0]).to_degrees().rem_euclid(360.0);
        let dec = centre[2].asin().to_degrees();
        assert!((ra - 266.405).abs() < 1e-3, "centre RA {ra}");
        assert!((dec + 28.936).abs() < 1e-3, "centre dec {dec}");
        let m = mul(&g, &transpose(&g));
        for (i, row) in m.iter().enumerate() {
            for (j, v) in row.iter().enumerate() {
                let want = if i == j { 1.0 } else { 0.0 };
                assert!((v - want).abs() < 1e-12);
            }
        }
    }

    /// The celestial pole stands at the place's latitude above the north point (to
    /// precession's and nutation's small tilt: within 0.5 degrees for any date this century).
    #[test]
    fn the_pole_stands_at_the_latitude() {
        let t: UtcDateTime = "2026-08-12T22:00:00Z".parse().unwrap();
        let m = equatorial_to_world(Place::new(46.0, 8.0).unwrap(), t);
        let (el, az) = world_to_horizontal(apply(&m, [0.0, 0.0, 1.0]));
        assert!((el - 46.0).abs() < 0.5, "pole at {el}");
        assert!(!(1.0..=359.0).contains(&az), "pole azimuth {az}");
    }
}
