//! Both integrators against closed forms, on homogeneous media in a flat world (planet radius
//! 1e14 m: over the ten kilometres these rays travel the layer departs from a plane by less
//! than 1e-6 m).
//!
//! # Single scattering from a homogeneous slab
//!
//! Slab of thickness `H` (the cloud layer), extinction `sigma_t = sigma_s + sigma_a`, lit by the
//! sun (illuminance `E`, unit vector `s` toward it, `mu_s = s.y > 0`), seen along unit `v`. The
//! phase function is evaluated at `cos = dot(v, s)` (the WGSL's convention), and `t` is the
//! distance travelled inside the slab along the view ray.
//!
//! *Transmission* (camera below the slab, `mu_v = v.y > 0`): the point at distance `t` is at
//! height `mu_v t` above the slab bottom, so its sun path to the top is `(H - mu_v t) / mu_s`:
//!
//! ```text
//! L = E p sigma_s int_0^{H/mu_v} exp(-sigma_t t) exp(-sigma_t (H - mu_v t) / mu_s) dt
//!   = E p sigma_s exp(-sigma_t H / mu_s) (1 - exp(-k H / mu_v)) / k,
//!     k = sigma_t (1 - mu_v / mu_s)            (and H / mu_v when k = 0).
//! ```
//!
//! *Reflection* (camera above, `mu_v = -v.y > 0`): the point at distance `t` is `mu_v t` below
//! the top, its sun path `mu_v t / mu_s`:
//!
//! ```text
//! L = E p sigma_s int_0^{H/mu_v} exp(-sigma_t t (1 + mu_v / mu_s)) dt
//!   = E p sigma_s (1 - exp(-sigma_t H (1/mu_v + 1/mu_s))) / (sigma_t (1 + mu_v / mu_s)).
//! ```
//!
//! Transmittance: `exp(-sigma_t H / mu_v)` through the slab, `exp(-sigma_t c)` through a ball
//! along a chord of length `c = 2 sqrt(r^2 - b^2)` (`b`: the ray's distance from the centre).
//!
//! # Ambient light: the real-time term and its environment counterpart
//!
//! The real-time model adds `sigma_s * A` per unit length (`A` = ambient radiance, here uniform:
//! bottom colour = top colour), unattenuated: seen from below along `mu_v`,
//! `L_rt = A sigma_s (1 - exp(-sigma_t H / mu_v)) / sigma_t`. The path tracer lights each
//! scattering point by a uniform environment of radiance `A` seen through the medium. For an
//! isotropic phase function the point at height `z` above the slab bottom receives
//! `A * (E2(sigma_t (H - z)) + E2(sigma_t z)) / 2`, where `E2(x) = int_0^1 exp(-x / mu) dmu`
//! (half the directions leave through the top, half through the bottom), so
//!
//! ```text
//! L_env = A sigma_s int_0^{H/mu_v} exp(-sigma_t t) (E2(sigma_t (H - mu_v t)) + E2(sigma_t mu_v t)) / 2 dt,
//! ```
//!
//! evaluated by nested midpoint rules. `L_env < L_rt`, and `L_env / L_rt -> 1` as the slab thins.
//!
//! With every order and no absorption the radiance field inside a slab bathed in a uniform
//! environment `A` is `A` everywhere (equilibrium, for any phase function), so the camera sees
//! `A (1 - exp(-sigma_t H / mu_v))`: exactly the real-time term at albedo 1. The real-time
//! ambient is thus the all-orders answer of a conservative medium, not single scattering.
//!
//! # Energy conservation
//!
//! Sunlight falling on the slab top carries `E mu_s` per unit horizontal area. With no
//! absorption it leaves as reflected flux `F_up` (above the slab), diffusely transmitted flux
//! `F_down` (below it) and unscattered sunlight `E mu_s exp(-sigma_t H / mu_s)`:
//! `F_up + F_down + E mu_s exp(-tau / mu_s) = E mu_s`. A flux is `int L |cos| dw` over a
//! hemisphere, estimated as `pi * mean(L)` over cosine-distributed directions. The ground is
//! black, so nothing comes back up from below.

use stratus_reference::{Integrator, Medium, QuadratureSettings, RenderOptions, Shape, Tracer};
use stratus_scene::{Integration, PhaseModel, Scene};

const BOTTOM: f64 = 1000.0;
const TOP: f64 = 2000.0;
const H: f64 = TOP - BOTTOM;

/// A flat world with the slab between 1000 m and 2000 m, lit by the sun from `sun`, with every
/// real-time-only term off (no ambient, octaves, Beer-Powder or precipitation): the real-time
/// model is then exactly single scattering.
fn flat_scene(camera_altitude: f64, sun: [f64; 3], g: f64) -> Scene {
    let mut s = Scene::default().with_size(4, 4);
    s.atmosphere.planet_radius_m = 1e14;
    s.atmosphere.cloud_bottom_m = BOTTOM;
    s.atmosphere.cloud_top_m = TOP;
    s.camera.position = [0.0, camera_altitude, 0.0];
    s.sun.direction = Some(sun);
    s.sun.illuminance = [1.0, 2.0, 3.0];
    s.lighting.ambient_strength = 0.0;
    s.lighting.multiple_scattering.octaves = 0;
    s.lighting.beer_powder = false;
    s.lighting.phase.model = PhaseModel::Hg;
    s.lighting.phase.g = g;
    s.clouds.precipitation = 0.0;
    s.quality.cutoff_distance_m = 1e6;
    s
}

/// The sun direction and illuminance exactly as the renderer sees them (f32 uniforms).
fn sun_of(scene: &Scene) -> ([f64; 3], [f64; 3]) {
    let u = scene.uniforms();
    let d = u.sun_direction.map(f64::from);
    let e = u.sun_illuminance.map(f64::from);
    ([d[0], d[1], d[2]], [e[0], e[1], e[2]])
}

fn normalize(v: [f64; 3]) -> [f64; 3] {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|c| c / l)
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn hg(cos: f64, g: f64) -> f64 {
    (1.0 - g * g) / (4.0 * std::f64::consts::PI * (1.0 + g * g - 2.0 * g * cos).powf(1.5))
}

/// Closed-form single scattering (see the module documentation), per unit illuminance.
fn single_scattering(sigma_s: f64, sigma_t: f64, v: [f64; 3], s: [f64; 3], g: f64) -> f64 {
    let p = hg(dot(v, s), g);
    let mu_s = s[1];
    if v[1] > 0.0 {
        let mu_v = v[1];
        let k = sigma_t * (1.0 - mu_v / mu_s);
        let integral = if k.abs() < 1e-12 {
            H / mu_v
        } else {
            (1.0 - (-k * H / mu_v).exp()) / k
        };
        p * sigma_s * (-sigma_t * H / mu_s).exp() * integral
    } else {
        let mu_v = -v[1];
        p * sigma_s * (1.0 - (-sigma_t * H * (1.0 / mu_v + 1.0 / mu_s)).exp())
            / (sigma_t * (1.0 + mu_v / mu_s))
    }
}

fn slab(sigma_s: f64, sigma_a: f64) -> Medium<'static> {
    Medium::Homogeneous {
        sigma_s,
        sigma_a,
        shape: Shape::Slab,
    }
}

/// The real-time settings without the early exit (which stops at transmittance 0.01).
fn no_early_exit() -> QuadratureSettings {
    QuadratureSettings {
        early_exit: Some(0.0),
        ..QuadratureSettings::realtime()
    }
}

fn converged_with(view_steps: u32) -> QuadratureSettings {
    QuadratureSettings {
        view_steps: Some(view_steps),
        ..QuadratureSettings::converged()
    }
}

#[test]
fn slab_transmittance_matches_beer_lambert() {
    let scene = flat_scene(500.0, [0.3, 0.8, 0.2], 0.6);
    let sigma_t = 0.0015;
    let tracer = Tracer::new(&scene, slab(0.001, 0.0005));
    for dir in [[0.0, 1.0, 0.0], [0.5, 0.7, 0.1], [0.9, 0.2, -0.3]] {
        let v = normalize(dir);
        let expected = (-sigma_t * H / v[1]).exp();
        let q = tracer.quadrature(v, &no_early_exit());
        assert!(
            (q.transmittance - expected).abs() < 1e-8 * expected,
            "quadrature {v:?}: {} vs {expected}",
            q.transmittance
        );
        let mc = tracer.monte_carlo(v, 64, 1, 7);
        assert!(
            (mc.transmittance - expected).abs() < 1e-8 * expected,
            "ratio tracking {v:?}: {} vs {expected}",
            mc.transmittance
        );
    }
    // From above, looking down through the slab to the ground.
    let scene = flat_scene(3000.0, [0.3, 0.8, 0.2], 0.6);
    let tracer = Tracer::new(&scene, slab(0.001, 0.0005));
    let v = normalize([0.2, -0.6, 0.4]);
    let expected = (-sigma_t * H / -v[1]).exp();
    let q = tracer.quadrature(v, &no_early_exit());
    assert!(
        (q.transmittance - expected).abs() < 1e-8 * expected,
        "{}",
        q.transmittance
    );
}

#[test]
fn sphere_transmittance_matches_the_chord() {
    let scene = flat_scene(0.0, [0.3, 0.8, 0.2], 0.6);
    let (center, radius) = ([100.0, 1500.0, 1200.0], 400.0);
    let sigma_t = 0.004;
    let medium = Medium::Homogeneous {
        sigma_s: 0.003,
        sigma_a: 0.001,
        shape: Shape::Sphere { center, radius },
    };
    let tracer = Tracer::new(&scene, medium);
    // Rays from the camera at the origin toward points around the centre.
    for target in [
        [100.0, 1500.0, 1200.0],
        [250.0, 1400.0, 1200.0],
        [100.0, 1500.0, 1550.0],
        [-300.0, 1500.0, 1200.0],
    ] {
        let v = normalize(target);
        let c = center;
        let along = dot(c, v);
        let b2 = dot(c, c) - along * along;
        let chord = if b2 < radius * radius {
            2.0 * (radius * radius - b2).sqrt()
        } else {
            0.0
        };
        let expected = (-sigma_t * chord).exp();
        let q = tracer.quadrature(v, &no_early_exit());
        assert!(
            (q.transmittance - expected).abs() < 1e-8 * expected,
            "quadrature toward {target:?}: {} vs {expected} (chord {chord})",
            q.transmittance
        );
        let mc = tracer.monte_carlo(v, 16, 1, 3);
        assert!(
            (mc.transmittance - expected).abs() < 1e-8 * expected,
            "ratio tracking toward {target:?}: {} vs {expected}",
            mc.transmittance
        );
    }
}

/// Directions of both geometries, with a sun from several elevations.
fn ss_cases() -> Vec<(f64, [f64; 3], [f64; 3])> {
    vec![
        (500.0, [0.0, 1.0, 0.0], [0.3, 0.8, 0.2]),
        (500.0, [0.4, 0.6, -0.2], [0.3, 0.8, 0.2]),
        (500.0, [0.2, 0.5, 0.3], [0.2, 0.5, 0.3]), // looking at the sun: k = 0
        (3000.0, [0.1, -1.0, 0.3], [0.3, 0.8, 0.2]),
        (3000.0, [-0.5, -0.4, 0.1], [0.7, 0.35, 0.1]),
    ]
}

#[test]
fn quadrature_single_scattering_matches_the_closed_form() {
    let (sigma_s, sigma_a, g) = (0.0012, 0.0003, 0.6);
    for (alt, view, sun) in ss_cases() {
        let scene = flat_scene(alt, sun, g);
        let (s, e) = sun_of(&scene);
        let v = normalize(view);
        let expected = single_scattering(sigma_s, sigma_s + sigma_a, v, s, g);
        let tracer = Tracer::new(&scene, slab(sigma_s, sigma_a));
        let q = tracer.quadrature(v, &QuadratureSettings::converged());
        for (l, e) in q.radiance.iter().zip(e) {
            let rel = (l / e - expected).abs() / expected;
            assert!(
                rel < 1e-5,
                "alt {alt} view {view:?}: {} vs {} (rel {rel:.2e})",
                l / e,
                expected
            );
        }
    }
}

#[test]
fn monte_carlo_single_scattering_matches_the_closed_form() {
    let (sigma_s, sigma_a, g) = (0.0012, 0.0003, 0.6);
    for (i, (alt, view, sun)) in ss_cases().into_iter().enumerate() {
        let scene = flat_scene(alt, sun, g);
        let (s, e) = sun_of(&scene);
        let v = normalize(view);
        let expected = single_scattering(sigma_s, sigma_s + sigma_a, v, s, g);
        let tracer = Tracer::new(&scene, slab(sigma_s, sigma_a));
        let mc = tracer.monte_carlo(v, 20_000, 1, i as u64);
        let (got, se) = (mc.radiance[0] / e[0], mc.std_error[0] / e[0]);
        assert!(
            (got - expected).abs() < 3.0 * se,
            "alt {alt} view {view:?}: {got} +- {se} vs {expected}"
        );
        assert!(se < 0.02 * expected, "noisy: {se} vs {expected}");
        // Grey medium: the channels are the illuminance's colour exactly.
        assert!((mc.radiance[2] / e[2] - got).abs() < 1e-12 * got.max(1.0));
    }
}

#[test]
fn quadrature_error_shrinks_with_the_step() {
    // Thick slab (tau = 3), seen from below at 60 degrees from the zenith, sun 30 degrees up.
    let (sigma_s, sigma_a, g) = (0.0025, 0.0005, 0.3);
    let scene = flat_scene(500.0, [0.0, 0.5, 0.866], g);
    let (s, _) = sun_of(&scene);
    let v = normalize([0.866, 0.5, 0.0]);
    let expected = single_scattering(sigma_s, sigma_s + sigma_a, v, s, g);
    let tracer = Tracer::new(&scene, slab(sigma_s, sigma_a));
    let error = |steps: u32, integration: Integration| {
        let settings = QuadratureSettings {
            integration: Some(integration),
            ..converged_with(steps)
        };
        (tracer.quadrature(v, &settings).radiance[0] / scene.sun.illuminance[0] - expected).abs()
            / expected
    };
    let analytic: Vec<f64> = [4, 8, 16, 32, 64]
        .iter()
        .map(|&n| error(n, Integration::Analytic))
        .collect();
    let riemann: Vec<f64> = [4, 8, 16, 32, 64]
        .iter()
        .map(|&n| error(n, Integration::Riemann))
        .collect();
    eprintln!("relative errors at 4..64 steps: analytic {analytic:?}, riemann {riemann:?}");
    // The analytic step integral (constant source per step) is second order: each doubling
    // divides the error by about 4. The Riemann sum is first order: about 2.
    for w in analytic.windows(2) {
        assert!(w[1] < w[0] / 3.5, "analytic errors {analytic:?}");
    }
    for w in riemann.windows(2) {
        assert!(w[1] < w[0] / 1.8, "riemann errors {riemann:?}");
    }
    assert!(analytic[4] < 1e-3 && riemann[4] > 10.0 * analytic[4]);
}

/// `E2(x) = int_0^1 exp(-x / mu) dmu` by the midpoint rule.
fn e2(x: f64) -> f64 {
    let n = 400;
    (0..n)
        .map(|i| (-x / ((f64::from(i) + 0.5) / f64::from(n))).exp())
        .sum::<f64>()
        / f64::from(n)
}

#[test]
fn ambient_matches_the_real_time_term_and_its_occluded_environment() {
    let g = 0.0;
    let ambient = 0.7;
    for (sigma_s, sigma_a) in [(0.001, 0.0002), (0.00002, 0.000004)] {
        let mut scene = flat_scene(500.0, [0.3, 0.8, 0.2], g);
        scene.sun.illuminance = [0.0; 3];
        scene.lighting.ambient_strength = 1.0;
        scene.lighting.ambient_bottom = [ambient; 3];
        scene.lighting.ambient_top = [ambient; 3];
        let a = f64::from(scene.uniforms().ambient_bottom[0]);
        let sigma_t = sigma_s + sigma_a;
        let v = normalize([0.3, 0.8, 0.0]);
        let mu_v = v[1];
        let real_time = a * sigma_s * (1.0 - (-sigma_t * H / mu_v).exp()) / sigma_t;
        let n = 1000;
        let dt = H / mu_v / f64::from(n);
        let environment: f64 = (0..n)
            .map(|i| {
                let t = (f64::from(i) + 0.5) * dt;
                let z = mu_v * t;
                (-sigma_t * t).exp() * 0.5 * (e2(sigma_t * (H - z)) + e2(sigma_t * z)) * dt
            })
            .sum::<f64>()
            * a
            * sigma_s;

        let tracer = Tracer::new(&scene, slab(sigma_s, sigma_a));
        let q = tracer
            .quadrature(v, &QuadratureSettings::converged())
            .radiance[0];
        assert!(
            (q - real_time).abs() < 1e-6 * real_time,
            "quadrature {q} vs real-time closed form {real_time}"
        );
        let mc = tracer.monte_carlo(v, 40_000, 1, 11);
        let (l, se) = (mc.radiance[0], mc.std_error[0]);
        eprintln!(
            "sigma_t H = {:.3}: real-time {real_time:.6}, environment {environment:.6}, MC {l:.6} +- {se:.6}",
            sigma_t * H
        );
        assert!(
            (l - environment).abs() < 3.0 * se + 1e-4 * environment,
            "Monte Carlo {l} +- {se} vs occluded environment {environment}"
        );
        assert!(environment < real_time);
    }

    // All orders, no absorption: the equilibrium A (1 - T), whatever the phase function (this
    // checks that every model's sampling weight averages to 1).
    for (i, model) in [
        PhaseModel::Hg,
        PhaseModel::TwoLobeHg,
        PhaseModel::CornetteShanks,
    ]
    .into_iter()
    .enumerate()
    {
        let mut scene = flat_scene(500.0, [0.3, 0.8, 0.2], 0.6);
        scene.sun.illuminance = [0.0; 3];
        scene.lighting.ambient_strength = 1.0;
        scene.lighting.ambient_bottom = [ambient; 3];
        scene.lighting.ambient_top = [ambient; 3];
        scene.lighting.phase.model = model;
        scene.lighting.phase.g = 0.8;
        scene.lighting.phase.g2 = -0.3;
        scene.lighting.phase.blend = 0.3;
        let a = f64::from(scene.uniforms().ambient_bottom[0]);
        let v = normalize([0.3, 0.8, 0.0]);
        let sigma = 0.0012;
        let equilibrium = a * (1.0 - (-sigma * H / v[1]).exp());
        let tracer = Tracer::new(&scene, slab(sigma, 0.0));
        let mc = tracer.monte_carlo(v, 20_000, 0, 5 + i as u64);
        let q = tracer
            .quadrature(v, &QuadratureSettings::converged())
            .radiance[0];
        eprintln!(
            "{model:?}, all orders: equilibrium {equilibrium:.6}, MC {:.6} +- {:.6}, real-time {q:.6}",
            mc.radiance[0], mc.std_error[0]
        );
        assert!((mc.radiance[0] - equilibrium).abs() < 3.0 * mc.std_error[0]);
        assert!((q - equilibrium).abs() < 1e-6 * equilibrium);
    }
}

/// The scene's phase function at `cos`, from its (f32) uniforms; independent of the crate's.
fn scene_phase(scene: &Scene, cos: f64) -> f64 {
    let u = scene.uniforms();
    let [g, g2, blend] = [u.phase_g, u.phase_g2, u.phase_blend].map(f64::from);
    match scene.lighting.phase.model {
        PhaseModel::Hg => hg(cos, g),
        PhaseModel::TwoLobeHg => (1.0 - blend) * hg(cos, g) + blend * hg(cos, g2),
        PhaseModel::CornetteShanks => {
            3.0 * (1.0 - g * g) * (1.0 + cos * cos)
                / (8.0
                    * std::f64::consts::PI
                    * (2.0 + g * g)
                    * (1.0 + g * g - 2.0 * g * cos).powf(1.5))
        }
    }
}

/// Single scattering of a uniform environment `A` seen through the slab, camera below looking
/// straight up, for an anisotropic phase function: the scattering angle's cosine is the
/// direction's `mu`, so
/// `L = A sigma_s int_0^H exp(-sigma_t z) 2 pi int_{-1}^{1} p(mu) exp(-sigma_t d(z, mu)) dmu dz`
/// with `d = (H - z) / mu` upward and `z / |mu|` downward. This checks the *shape* of the
/// directions the path tracer samples from each phase model.
#[test]
fn environment_single_scattering_samples_the_phase_function() {
    let (sigma_s, sigma_a) = (0.0008, 0.0002);
    let sigma_t = sigma_s + sigma_a;
    for (i, model) in [
        PhaseModel::Hg,
        PhaseModel::TwoLobeHg,
        PhaseModel::CornetteShanks,
    ]
    .into_iter()
    .enumerate()
    {
        let mut scene = flat_scene(500.0, [0.3, 0.8, 0.2], 0.8);
        scene.sun.illuminance = [0.0; 3];
        scene.lighting.ambient_strength = 1.0;
        scene.lighting.ambient_bottom = [0.5; 3];
        scene.lighting.ambient_top = [0.5; 3];
        scene.lighting.phase.model = model;
        scene.lighting.phase.g2 = -0.3;
        scene.lighting.phase.blend = 0.3;
        let a = f64::from(scene.uniforms().ambient_bottom[0]);
        let (nz, nmu) = (200, 4000);
        let dz = H / f64::from(nz);
        let dmu = 2.0 / f64::from(nmu);
        let mut expected = 0.0;
        for iz in 0..nz {
            let z = (f64::from(iz) + 0.5) * dz;
            let mut inner = 0.0;
            for im in 0..nmu {
                let mu = -1.0 + (f64::from(im) + 0.5) * dmu;
                let d = if mu > 0.0 { (H - z) / mu } else { z / -mu };
                inner += scene_phase(&scene, mu) * (-sigma_t * d).exp() * dmu;
            }
            expected += (-sigma_t * z).exp() * 2.0 * std::f64::consts::PI * inner * dz;
        }
        expected *= a * sigma_s;
        let tracer = Tracer::new(&scene, slab(sigma_s, sigma_a));
        let mc = tracer.monte_carlo([0.0, 1.0, 0.0], 40_000, 1, 100 + i as u64);
        let (l, se) = (mc.radiance[0], mc.std_error[0]);
        eprintln!("{model:?}: environment single scattering {expected:.6}, MC {l:.6} +- {se:.6}");
        assert!(
            (l - expected).abs() < 3.0 * se + 1e-3 * expected,
            "{model:?}: {l} +- {se} vs {expected}"
        );
        assert!(se < 0.01 * expected);
    }
}

/// Reflected (camera above) or transmitted (camera below) diffuse flux per unit illuminance:
/// `pi * mean(L)` over `n` cosine-distributed directions.
fn flux(scene: &Scene, medium: Medium, up: bool, n: u32, orders: u32) -> (f64, f64) {
    let tracer = Tracer::new(scene, medium);
    let mut sum = 0.0;
    let mut sum2 = 0.0;
    let e = scene.sun.illuminance[0];
    for i in 0..n {
        // Cosine-weighted hemisphere by a 2D Halton sequence (bases 2 and 3).
        let radical = |mut k: u32, b: u32| {
            let (mut f, mut r) = (1.0, 0.0);
            while k > 0 {
                f /= f64::from(b);
                r += f * f64::from(k % b);
                k /= b;
            }
            r
        };
        let (u1, u2) = (radical(i + 1, 2), radical(i + 1, 3));
        let (r, phi) = (u1.sqrt(), 2.0 * std::f64::consts::PI * u2);
        let y = (1.0 - u1).max(1e-6).sqrt();
        let dir = [r * phi.cos(), if up { y } else { -y }, r * phi.sin()];
        let l = tracer.monte_carlo(dir, 1, orders, u64::from(i)).radiance[0] / e;
        sum += l;
        sum2 += l * l;
    }
    let nf = f64::from(n);
    let mean = sum / nf;
    let var = (sum2 / nf - mean * mean) * nf / (nf - 1.0);
    let pi = std::f64::consts::PI;
    (pi * mean, pi * (var / nf).sqrt())
}

#[test]
fn energy_is_conserved_without_absorption() {
    let sun = [0.0, 0.8, 0.6];
    let g = 0.6;
    let sigma = 0.002; // tau = 2
    let above = flat_scene(3000.0, sun, g);
    let below = flat_scene(500.0, sun, g);
    let (s, _) = sun_of(&above);
    let mu_s = s[1];
    let n = 20_000;
    let (up, up_se) = flux(&above, slab(sigma, 0.0), false, n, 0);
    let (down, down_se) = flux(&below, slab(sigma, 0.0), true, n, 0);
    let direct = mu_s * (-sigma * H / mu_s).exp();
    let total = up + down + direct;
    let se = (up_se * up_se + down_se * down_se).sqrt();
    eprintln!(
        "reflected {up:.4} + transmitted {down:.4} + direct {direct:.4} = {total:.4} +- {se:.4}, incident {mu_s:.4}"
    );
    assert!(
        (total - mu_s).abs() < 3.0 * se,
        "reflected {up:.4} + transmitted {down:.4} + direct {direct:.4} = {total:.4} +- {se:.4}, incident {mu_s:.4}"
    );
    assert!(se < 0.01 * mu_s, "noisy: {se}");

    // With absorption the same slab returns strictly less.
    let (up_a, up_a_se) = flux(&above, slab(0.0015, 0.0005), false, n, 0);
    let (down_a, down_a_se) = flux(&below, slab(0.0015, 0.0005), true, n, 0);
    let total_a = up_a + down_a + direct;
    let se_a = (up_a_se * up_a_se + down_a_se * down_a_se).sqrt();
    eprintln!("with absorption: {total_a:.4} +- {se_a:.4}");
    assert!(
        total_a < mu_s - 3.0 * se_a && total_a < total,
        "with absorption: {total_a:.4} +- {se_a:.4} vs incident {mu_s:.4}"
    );

    // Single scattering alone is only part of it.
    let (up_1, _) = flux(&above, slab(sigma, 0.0), false, n, 1);
    assert!(up_1 < up - 3.0 * up_se, "orders 1 {up_1} vs all {up}");
}

#[test]
fn homogeneous_slab_renders_through_the_image_api() {
    // The whole render path (pixels, threads, composite) on a medium with a closed form.
    let mut scene = flat_scene(500.0, [0.3, 0.8, 0.2], 0.6);
    scene.camera.pitch_deg = 90.0;
    scene.camera.fov_y_deg = 1e-3; // every pixel looks straight up
    let sigma_t = 0.0015;
    let r = stratus_reference::render_medium(
        &scene,
        slab(0.001, 0.0005),
        &Integrator::Quadrature(QuadratureSettings::converged()),
        &RenderOptions::default(),
    );
    let expected_t = (-sigma_t * H).exp();
    let (s, e) = sun_of(&scene);
    let expected_l = single_scattering(0.001, sigma_t, [0.0, 1.0, 0.0], s, 0.6);
    for p in r.output.radiance.chunks_exact(4) {
        assert!((f64::from(p[3]) - expected_t).abs() < 1e-5);
        assert!((f64::from(p[0]) / e[0] - expected_l).abs() < 1e-4 * expected_l);
    }
    assert!(r.std_error.is_none());
    let stats = r.output.stats.as_ref().unwrap();
    assert_eq!(stats["pixels"], 16);
    assert_eq!(stats["marched_pixels"], 16);
    assert_eq!(stats["view_steps"], 16 * 1024);
}
