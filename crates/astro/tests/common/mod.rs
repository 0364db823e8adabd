//! What the tests against astropy share.

/// Great-circle angle between two (elevation, azimuth) directions, degrees.
pub fn separation(a: (f64, f64), b: (f64, f64)) -> f64 {
    let v = |(el, az): (f64, f64)| {
        let (el, az) = (el.to_radians(), az.to_radians());
        [el.cos() * az.sin(), el.cos() * az.cos(), el.sin()]
    };
    let (p, q) = (v(a), v(b));
    let dot = p[0] * q[0] + p[1] * q[1] + p[2] * q[2];
    let cross = [
        p[1] * q[2] - p[2] * q[1],
        p[2] * q[0] - p[0] * q[2],
        p[0] * q[1] - p[1] * q[0],
    ];
    let sin = (cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]).sqrt();
    sin.atan2(dot).to_degrees()
}
