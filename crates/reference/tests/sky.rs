//! The CPU's physical-sky tables (`stratus_reference::sky`, the twin of the GPU's passes in
//! wgsl/atmosphere.wgsl) against the f64 atmosphere integrated directly along each ray
//! (`stratus_reference::atmosphere`), with the tolerances tests/tests/atmosphere.rs holds the
//! GPU's tables to. Each texel is mapped back to its ray here by the parametrisation the WGSL
//! documents, written out again, so that a parametrisation wrong in both directions shows.
//! The measured errors are printed (`--nocapture`); measured (the same numbers as the GPU's
//! within a few percent: the error is the quadrature's, not f32's): transmittance RMSE 2.0e-5,
//! worst texel 2.4e-4 (absolute); multi-scattering RMSE 0.014%, worst 0.064%; sky view RMSE
//! 0.64%, worst 1.38%.

use std::f64::consts::PI;

use rayon::prelude::*;
use stratus_reference::atmosphere::AtmosphereModel;
use stratus_reference::sky::{self, SkyTables};
use stratus_scene::{Scene, SkyModel};

/// cumulus-noon under the physical sky, as the GPU test renders it.
fn scene() -> Scene {
    let mut s = Scene::preset("cumulus-noon")
        .expect("preset")
        .with_size(64, 36);
    s.atmosphere.sky = SkyModel::Physical;
    s.validate().expect("a valid scene");
    s
}

/// Root mean square and largest of `errors`.
fn stats(errors: &[f64]) -> (f64, f64) {
    let rms = (errors.iter().map(|e| e * e).sum::<f64>() / errors.len() as f64).sqrt();
    (rms, errors.iter().cloned().fold(0.0, f64::max))
}

/// Relative error of `got` against `truth` over channels, against the larger of the truth's
/// channel and `floor` (where the truth is near 0 the absolute error counts).
fn relative(got: [f64; 4], truth: [f64; 3], floor: f64) -> f64 {
    (0..3)
        .map(|c| (got[c] - truth[c]).abs() / truth[c].abs().max(floor))
        .fold(0.0, f64::max)
}

/// (r, mu) of transmittance coordinates `x` (Bruneton 2017's parametrisation, metres).
fn transmittance_r_mu(m: &AtmosphereModel, x: [f64; 2]) -> (f64, f64) {
    let (bottom, top) = (m.bottom_radius_m, m.top_radius_m);
    let h = (top * top - bottom * bottom).sqrt();
    let rho = h * x[1];
    let r = (rho * rho + bottom * bottom).sqrt();
    let (d_min, d_max) = (top - r, rho + h);
    let d = d_min + x[0] * (d_max - d_min);
    let mu = if d > 0.0 {
        ((h * h - rho * rho - d * d) / (2.0 * r * d)).clamp(-1.0, 1.0)
    } else {
        1.0
    };
    (r, mu)
}

fn distance_to_top(m: &AtmosphereModel, r: f64, mu: f64) -> f64 {
    let disc = r * r * (mu * mu - 1.0) + m.top_radius_m * m.top_radius_m;
    (-r * mu + disc.max(0.0).sqrt()).max(0.0)
}

/// The direct integration's transmittance from radius `r` along zenith cosine `mu` to the top
/// (Simpson on 512 intervals), the ground ignored as the table ignores it.
fn direct_transmittance(m: &AtmosphereModel, r: f64, mu: f64) -> [f64; 3] {
    let p = [0.0, r, 0.0];
    let d = [(1.0 - mu * mu).max(0.0).sqrt(), mu, 0.0];
    m.optical_depth(p, d, distance_to_top(m, r, mu), 512)
        .map(|tau| (-tau).exp())
}

#[test]
fn the_scenes_air_is_bruneton_s_earth() {
    let scene = scene();
    let air = sky::air_model(&scene.uniforms());
    let earth = AtmosphereModel::earth(scene.atmosphere.planet_radius_m);
    // The uniform block holds f32: equal to about 1e-7.
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-6 * b.abs();
    assert!(close(air.top_radius_m, earth.top_radius_m));
    for c in 0..3 {
        assert!(close(
            air.rayleigh_scattering[c],
            earth.rayleigh_scattering[c]
        ));
        assert!(close(air.ozone_absorption[c], earth.ozone_absorption[c]));
    }
    assert!(close(air.mie_scattering, earth.mie_scattering));
    assert!(close(air.mie_absorption, earth.mie_absorption));
    assert!(close(air.mie_g, earth.mie_g));
}

#[test]
fn cpu_sky_tables_match_the_direct_integration() {
    let scene = scene();
    let u = scene.uniforms();
    let tables = SkyTables::new(&u);
    for t in &tables.timings {
        eprintln!("{}: {:.1} ms", t.pass, t.ms);
    }
    let names: Vec<&str> = tables.timings.iter().map(|t| t.pass.as_str()).collect();
    // The cloud-shadow map needs the medium: the renderer makes it (`SkyTables::shade`).
    assert_eq!(names, sky::PASSES[..6]);
    for (name, t) in [
        ("transmittance", &tables.transmittance),
        ("multi-scattering", &tables.multiscatter),
        ("sky view", &tables.sky_view),
        ("sky ambient", &tables.sky_ambient),
        ("aerial perspective", &tables.aerial),
    ] {
        assert_eq!(t.texels.len(), t.width * t.height, "{name}");
        assert!(
            t.texels
                .iter()
                .flatten()
                .all(|v| v.is_finite() && *v >= 0.0),
            "{name}: a texel is negative or not finite"
        );
    }
    let model = AtmosphereModel::earth(scene.atmosphere.planet_radius_m);

    // Transmittance: every texel, against Simpson on 512 intervals to the top.
    let [tw, th] = sky::TRANSMITTANCE_SIZE;
    let errors: Vec<f64> = (0..tw * th)
        .into_par_iter()
        .map(|k| {
            let (i, j) = (k % tw, k / tw);
            let x = [i as f64 / (tw - 1) as f64, j as f64 / (th - 1) as f64];
            let (r, mu) = transmittance_r_mu(&model, x);
            let truth = direct_transmittance(&model, r, mu);
            let got = tables.transmittance.load(i, j);
            (0..3)
                .map(|c| (got[c] - truth[c]).abs())
                .fold(0.0, f64::max)
        })
        .collect();
    let (rms, worst) = stats(&errors);
    eprintln!("transmittance: RMSE {rms:.2e}, worst texel {worst:.2e} (absolute)");
    assert!(
        rms < 6e-5 && worst < 8e-4,
        "transmittance: RMSE {rms:.2e}, worst {worst:.2e}"
    );

    // Between texels: the lookup (coordinates and bilinear interpolation) at radii and angles
    // off the grid, against the direct integration. Interpolation in Bruneton's coordinates
    // is what the GPU's march reads. Measured: RMSE 9.6e-5, worst 2.8e-4 (absolute).
    let mut errors = Vec::new();
    for k in 0..200 {
        let h = (k as f64 * 0.618_034).fract() * 20_000.0;
        let mu = (k as f64 * 0.414_214).fract() * 2.0 - 1.0;
        let r = model.bottom_radius_m + h;
        let horizon = -(1.0 - (model.bottom_radius_m / r).powi(2)).sqrt();
        if mu < horizon {
            continue; // into the ground: the caller's case
        }
        let truth = direct_transmittance(&model, r, mu);
        let got = tables.transmittance(r, mu);
        errors.push(
            (0..3)
                .map(|c| (got[c] - truth[c]).abs())
                .fold(0.0, f64::max),
        );
    }
    let (rms, worst) = stats(&errors);
    eprintln!(
        "transmittance lookups ({} off the grid): RMSE {rms:.2e}, worst {worst:.2e} (absolute)",
        errors.len()
    );
    assert!(
        rms < 3e-4 && worst < 1e-3,
        "lookups: RMSE {rms:.2e}, worst {worst:.2e}"
    );

    // Multi-scattering: every fourth texel each way, against the reference's Psi_ms (the same
    // 64 directions and 32 steps, with exact transmittance where the table is read).
    let n = 32usize;
    let top = model.top_radius_m - model.bottom_radius_m;
    let cells: Vec<(usize, usize)> = (0..n)
        .step_by(4)
        .chain([n - 1])
        .flat_map(|j| (0..n).step_by(4).chain([n - 1]).map(move |i| (i, j)))
        .collect();
    let errors: Vec<f64> = cells
        .par_iter()
        .map(|&(i, j)| {
            let mu_s = i as f64 / (n - 1) as f64 * 2.0 - 1.0;
            let r = model.bottom_radius_m + j as f64 / (n - 1) as f64 * top;
            let sun = [(1.0 - mu_s * mu_s).max(0.0).sqrt(), mu_s, 0.0];
            let truth = model.multiple_scattering([0.0, r, 0.0], sun, 32, 64);
            let floor = 1e-3 * truth.iter().cloned().fold(0.0, f64::max).max(1e-9);
            relative(tables.multiscatter.load(i, j), truth, floor.max(1e-6))
        })
        .collect();
    let (rms, worst) = stats(&errors);
    eprintln!(
        "multi-scattering: RMSE {:.3}%, worst texel {:.3}%",
        rms * 100.0,
        worst * 100.0
    );
    assert!(
        rms < 5e-4 && worst < 3e-3,
        "multi-scattering: RMSE {rms:.2e}, worst {worst:.2e}"
    );

    // Sky view: 16 texels spread over the table (above and below the horizon), against the
    // reference's sky radiance with multiple scattering integrated at each of 64 steps.
    let [sw, sh] = sky::SKY_VIEW_SIZE;
    let r = model.bottom_radius_m + scene.camera.position[1].max(0.0);
    let horizon = -(model.bottom_radius_m / r).clamp(-1.0, 1.0).acos();
    let sun = u.sun_direction.map(f64::from);
    let sun = [sun[0], sun[1], sun[2]];
    let sun_azimuth = sun[2].atan2(sun[0]);
    let texels: Vec<(usize, usize)> = [2usize, 20, 40, 52, 56, 60, 80, 105]
        .into_iter()
        .flat_map(|j| [0usize, 95].map(|i| (i, j)))
        .collect();
    let errors: Vec<f64> = texels
        .par_iter()
        .map(|&(i, j)| {
            let v = j as f64 / (sh - 1) as f64;
            let elevation = if v >= 0.5 {
                let a = 2.0 * v - 1.0;
                horizon + (0.5 * PI - horizon) * a * a
            } else {
                let a = 1.0 - 2.0 * v;
                horizon - (horizon + 0.5 * PI) * a * a
            };
            let phi = sun_azimuth + i as f64 / (sw - 1) as f64 * PI;
            let d = [
                elevation.cos() * phi.cos(),
                elevation.sin(),
                elevation.cos() * phi.sin(),
            ];
            // The ground lit by the sky too, through the irradiance table (held to the direct
            // integral below).
            let e = |mu_s: f64| {
                let t = tables.ground_irradiance.bilinear([mu_s * 0.5 + 0.5, 0.0]);
                [t[0], t[1], t[2]]
            };
            let truth = model.sky_radiance_over_ground([0.0, r, 0.0], d, sun, true, 64, e);
            let floor = 1e-3 * truth.iter().cloned().fold(0.0, f64::max).max(1e-9);
            relative(tables.sky_view.load(i, j), truth, floor)
        })
        .collect();
    let (rms, worst) = stats(&errors);
    eprintln!(
        "sky view: RMSE {:.2}%, worst texel {:.2}%",
        rms * 100.0,
        worst * 100.0
    );
    assert!(
        rms < 0.02 && worst < 0.045,
        "sky view: RMSE {rms:.3}, worst {worst:.3}"
    );

    // Ground irradiance: a high and a low sun, against the hemisphere integrated directly (4
    // rings by 6 azimuths of 64-step sky radiance with multiple scattering; at the zenith sun
    // 16 steps were 7% low and 96 steps moved the sum by 0.3%, 48 rings against 6 by 0.5%).
    // Measured: worst 3.3% (red, zenith sun: the table's 64 upward directions).
    let n = sky::GROUND_IRRADIANCE_SIZE;
    let errors: Vec<f64> = [n - 1, (n - 1) * 11 / 20]
        .par_iter()
        .map(|&i| {
            let mu_s = i as f64 / (n - 1) as f64 * 2.0 - 1.0;
            let truth = model.ground_irradiance(mu_s, 4, 6, 64);
            let got = tables.ground_irradiance.load(i, 0);
            eprintln!("ground irradiance at mu_s {mu_s:.3}: {got:?} against {truth:?}");
            relative(got, truth, 1e-9)
        })
        .collect();
    let (rms, worst) = stats(&errors);
    eprintln!(
        "ground irradiance: RMSE {:.2}%, worst {:.2}%",
        rms * 100.0,
        worst * 100.0
    );
    assert!(
        worst < 0.05,
        "ground irradiance: RMSE {rms:.3}, worst {worst:.3}"
    );
}
