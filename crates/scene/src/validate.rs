//! Validation rules for every field of a [`Scene`].

use crate::error::{Problem, ProblemKind};
use crate::scene::{MAX_EXTRA_LAYERS, Scene};
use crate::text::{num, nums};

/// One broken rule. `path` is the field the message names. A rule between two fields also has
/// `related`: the other field and the same problem told from its side, used when a file
/// spells only that field (`cloud_top_m = 1000` is the culprit, not the default bottom).
pub(crate) struct Issue {
    pub path: &'static str,
    pub message: String,
    pub related: Option<(&'static str, String)>,
}

impl Issue {
    /// The problem, told from the side of `related` instead of `path` if asked.
    pub(crate) fn into_problem(self, from_related_side: bool) -> Problem {
        let (path, message) = match self.related {
            Some(related) if from_related_side => related,
            _ => (self.path, self.message),
        };
        Problem::new(ProblemKind::InvalidValue, Some(path.to_owned()), message)
    }
}

/// An interval end: inclusive or exclusive, or absent.
#[derive(Clone, Copy)]
enum End {
    Incl(f64),
    Excl(f64),
    None,
}
use End::{Excl, Incl};

#[derive(Default)]
struct Checker {
    issues: Vec<Issue>,
}

impl Checker {
    fn push(&mut self, path: &'static str, value: String, rule: impl Into<String>) {
        self.issues.push(Issue {
            path,
            message: format!("{path} = {value}: {}", rule.into()),
            related: None,
        });
    }

    /// A broken rule between `path` and `other`, told from both sides: `(value, rule)` each.
    fn push_pair(
        &mut self,
        (path, value, rule): (&'static str, String, String),
        (other, other_value, other_rule): (&'static str, String, String),
    ) {
        self.issues.push(Issue {
            path,
            message: format!("{path} = {value}: {rule}"),
            related: Some((other, format!("{other} = {other_value}: {other_rule}"))),
        });
    }

    /// `v` must be finite and inside the interval; returns whether it is.
    fn float(&mut self, path: &'static str, v: f64, lo: End, hi: End) -> bool {
        if !v.is_finite() {
            self.push(path, num(v), "must be a finite number");
            return false;
        }
        let lo_ok = match lo {
            Incl(l) => v >= l,
            Excl(l) => v > l,
            End::None => true,
        };
        let hi_ok = match hi {
            Incl(h) => v <= h,
            Excl(h) => v < h,
            End::None => true,
        };
        if !(lo_ok && hi_ok) {
            self.push(path, num(v), interval_rule(lo, hi));
            return false;
        }
        true
    }

    fn finite(&mut self, path: &'static str, v: f64) -> bool {
        self.float(path, v, End::None, End::None)
    }

    fn unit(&mut self, path: &'static str, v: f64) -> bool {
        self.float(path, v, Incl(0.0), Incl(1.0))
    }

    fn positive(&mut self, path: &'static str, v: f64) -> bool {
        self.float(path, v, Excl(0.0), End::None)
    }

    fn non_negative(&mut self, path: &'static str, v: f64) -> bool {
        self.float(path, v, Incl(0.0), End::None)
    }

    fn uint(&mut self, path: &'static str, v: u64, lo: u64, hi: u64) {
        if v < lo || v > hi {
            self.push(path, v.to_string(), format!("must be within [{lo}, {hi}]"));
        }
    }

    /// Every component finite; returns whether they are.
    fn finite_vec(&mut self, path: &'static str, v: &[f64]) -> bool {
        if v.iter().all(|x| x.is_finite()) {
            true
        } else {
            self.push(path, nums(v), "every component must be a finite number");
            false
        }
    }

    /// A camera orientation: unit, orthogonal vectors with right x up = forward (within 1e-6:
    /// a host's f32 matrices are orthonormal to about 1e-7).
    fn orientation(&mut self, o: &crate::scene::Orientation) {
        const PATHS: [&str; 3] = [
            "camera.orientation.forward",
            "camera.orientation.right",
            "camera.orientation.up",
        ];
        let vs = [o.forward, o.right, o.up];
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        for (path, v) in PATHS.into_iter().zip(vs) {
            if !self.finite_vec(path, &v) {
                return;
            }
            if (dot(v, v).sqrt() - 1.0).abs() > 1e-6 {
                self.push(
                    path,
                    nums(&v),
                    "must be a unit vector (length 1 within 1e-6)",
                );
                return;
            }
        }
        for (i, j) in [(0, 1), (0, 2), (1, 2)] {
            if dot(vs[i], vs[j]).abs() > 1e-6 {
                let (a, b) = (PATHS[i], PATHS[j]);
                let name = &b[b.rfind('.').unwrap() + 1..];
                self.push(
                    a,
                    nums(&vs[i]),
                    format!(
                        "must be orthogonal to {name} (dot product {:.3e})",
                        dot(vs[i], vs[j])
                    ),
                );
                return;
            }
        }
        let (r, u) = (o.right, o.up);
        let cross = [
            r[1] * u[2] - r[2] * u[1],
            r[2] * u[0] - r[0] * u[2],
            r[0] * u[1] - r[1] * u[0],
        ];
        if dot(cross, o.forward) < 0.0 {
            self.push(
                PATHS[0],
                nums(&o.forward),
                "must be right x up (this is its opposite: a mirrored camera; a right-handed host's view matrix is converted by stratus::HostCamera)",
            );
        }
    }

    /// A colour: every component finite and >= 0.
    fn colour(&mut self, path: &'static str, v: &[f64; 3]) {
        if self.finite_vec(path, v) && v.iter().any(|&x| x < 0.0) {
            self.push(path, nums(v), "every component must be >= 0");
        }
    }
}

fn interval_rule(lo: End, hi: End) -> String {
    match (lo, hi) {
        (Incl(l), End::None) => format!("must be >= {}", num(l)),
        (Excl(l), End::None) => format!("must be > {}", num(l)),
        (End::None, Incl(h)) => format!("must be <= {}", num(h)),
        (End::None, Excl(h)) => format!("must be < {}", num(h)),
        (End::None, End::None) => "must be a finite number".to_owned(),
        (lo, hi) => {
            let (open, l) = match lo {
                Incl(l) => ('[', l),
                Excl(l) => ('(', l),
                End::None => unreachable!(),
            };
            let (close, h) = match hi {
                Incl(h) => (']', h),
                Excl(h) => (')', h),
                End::None => unreachable!(),
            };
            format!("must be within {open}{}, {}{close}", num(l), num(h))
        }
    }
}

/// Checks every field of `scene`; returns the broken rules in field order.
pub(crate) fn check(scene: &Scene) -> Vec<Issue> {
    let mut c = Checker::default();

    let cam = &scene.camera;
    if c.finite_vec("camera.position", &cam.position) && cam.position[1] < 0.0 {
        c.push(
            "camera.position",
            nums(&cam.position),
            "the altitude (second component) must be >= 0: the camera cannot be below the ground",
        );
    }
    c.finite("camera.yaw_deg", cam.yaw_deg);
    c.float("camera.pitch_deg", cam.pitch_deg, Incl(-90.0), Incl(90.0));
    c.float("camera.fov_y_deg", cam.fov_y_deg, Excl(0.0), Excl(180.0));
    let [w, h] = cam.resolution;
    if !(1..=MAX_RESOLUTION).contains(&w) || !(1..=MAX_RESOLUTION).contains(&h) {
        c.push(
            "camera.resolution",
            format!("[{w}, {h}]"),
            format!("width and height must be within [1, {MAX_RESOLUTION}]"),
        );
    }
    c.positive("camera.exposure", cam.exposure);
    if let Some(range) = &cam.exposure_range {
        let lo_ok = c.positive("camera.exposure_range", range[0]);
        let hi_ok = c.positive("camera.exposure_range", range[1]);
        if lo_ok && hi_ok && range[0] > range[1] {
            c.push(
                "camera.exposure_range",
                nums(range),
                "must be [min, max] with min <= max",
            );
        }
    }
    let post = &scene.post;
    c.float(
        "post.kuwahara_radius",
        post.kuwahara_radius,
        Excl(0.0),
        Incl(0.05),
    );
    c.float("post.saturation", post.saturation, Incl(0.0), Incl(4.0));
    c.float(
        "post.lens_flare_intensity",
        post.lens_flare_intensity,
        Incl(0.0),
        Incl(10.0),
    );
    let night = &scene.night;
    c.float(
        "night.star_intensity",
        night.star_intensity,
        Incl(0.0),
        Incl(100.0),
    );
    c.float(
        "night.star_min_radius_px",
        night.star_min_radius_px,
        Incl(0.25),
        Incl(8.0),
    );
    c.float(
        "night.star_radius_scale",
        night.star_radius_scale,
        Incl(0.0),
        Incl(4.0),
    );
    c.float(
        "night.star_glare_scale",
        night.star_glare_scale,
        Incl(0.0),
        Incl(10.0),
    );
    c.float(
        "night.milky_way_intensity",
        night.milky_way_intensity,
        Incl(0.0),
        Incl(100.0),
    );
    c.float("night.moon_size", night.moon_size, Incl(0.5), Incl(8.0));
    let bow = &scene.rainbow;
    if c.float("rainbow.moisture", bow.moisture, Incl(0.0), Incl(4.0))
        && bow.moisture > 0.0
        && !scene.atmosphere.sky.is_physical()
    {
        c.push(
            "rainbow.moisture",
            num(bow.moisture),
            "needs atmosphere.sky = \"physical\": the bows are drawn in the physical sky's composite",
        );
    }
    c.float(
        "rainbow.drop_radius_um",
        bow.drop_radius_um,
        Incl(5.0),
        Incl(2500.0),
    );
    let rain = &scene.precipitation;
    c.float(
        "precipitation.particles",
        rain.particles,
        Incl(0.0),
        Incl(4.0),
    );
    c.float("precipitation.shafts", rain.shafts, Incl(0.0), Incl(4.0));
    let bolt = &scene.lightning;
    c.float(
        "lightning.flashes_per_minute",
        bolt.flashes_per_minute,
        Incl(0.0),
        Incl(120.0),
    );
    c.float(
        "lightning.brightness",
        bolt.brightness,
        Incl(0.0),
        Incl(10.0),
    );
    if let Some(o) = &cam.orientation {
        c.orientation(o);
    }

    let sun = &scene.sun;
    c.float(
        "sun.elevation_deg",
        sun.elevation_deg,
        Incl(-90.0),
        Incl(90.0),
    );
    c.finite("sun.azimuth_deg", sun.azimuth_deg);
    if let Some(d) = &sun.direction {
        if c.finite_vec("sun.direction", d) && d.iter().all(|&x| x == 0.0) {
            c.push("sun.direction", nums(d), "must not be the zero vector");
        }
    }
    c.colour("sun.illuminance", &sun.illuminance);
    check_sky(&mut c, scene);
    c.float(
        "sun.angular_radius_deg",
        sun.angular_radius_deg,
        Incl(0.0),
        Incl(45.0),
    );

    let atm = &scene.atmosphere;
    c.positive("atmosphere.planet_radius_m", atm.planet_radius_m);
    let bottom_ok = c.non_negative("atmosphere.cloud_bottom_m", atm.cloud_bottom_m);
    let top_ok = c.positive("atmosphere.cloud_top_m", atm.cloud_top_m);
    if bottom_ok && top_ok && atm.cloud_bottom_m >= atm.cloud_top_m {
        let (bottom, top) = (num(atm.cloud_bottom_m), num(atm.cloud_top_m));
        c.push_pair(
            (
                "atmosphere.cloud_bottom_m",
                bottom.clone(),
                format!("must be below atmosphere.cloud_top_m ({top})"),
            ),
            (
                "atmosphere.cloud_top_m",
                top,
                format!("must be above atmosphere.cloud_bottom_m ({bottom})"),
            ),
        );
    }

    check_air(&mut c, &atm.air);
    if atm.light_shafts && !atm.sky.is_physical() {
        c.push(
            "atmosphere.light_shafts",
            "true".to_owned(),
            "needs atmosphere.sky = \"physical\": the shafts are the physical air's light",
        );
    }

    let cl = &scene.clouds;
    c.unit("clouds.coverage", cl.coverage);
    c.positive("clouds.density", cl.density);
    c.unit("clouds.cloud_type", cl.cloud_type);
    c.unit("clouds.precipitation", cl.precipitation);
    c.finite("clouds.wind_direction_deg", cl.wind_direction_deg);
    c.non_negative("clouds.wind_speed_m_s", cl.wind_speed_m_s);
    c.finite("clouds.time_s", cl.time_s);
    c.positive("clouds.weather_period_m", cl.weather_period_m);
    c.positive("clouds.shape_period_m", cl.shape_period_m);
    c.positive("clouds.detail_period_m", cl.detail_period_m);
    c.positive("clouds.curl_period_m", cl.curl_period_m);
    c.unit("clouds.detail_strength", cl.detail_strength);
    c.unit("clouds.erosion_threshold", cl.erosion_threshold);
    c.non_negative("clouds.curl_strength_m", cl.curl_strength_m);
    c.unit("clouds.height_gradient", cl.height_gradient);
    c.unit("clouds.wispy_billowy", cl.wispy_billowy);
    c.unit("clouds.convective_cells", cl.convective_cells);
    c.unit("clouds.anvil", cl.anvil);
    c.non_negative("clouds.anvil_shear_m", cl.anvil_shear_m);
    c.unit("clouds.cirrus", cl.cirrus);
    c.unit("clouds.cellular", cl.cellular);
    c.unit("clouds.cell_rolls", cl.cell_rolls);
    c.unit("clouds.close_detail", cl.close_detail);
    c.uint(
        "clouds.close_detail_scale",
        cl.close_detail_scale.into(),
        2,
        32,
    );
    let range_ok = c.positive("clouds.close_detail_range_m", cl.close_detail_range_m);
    let step_ok = c.positive("quality.close_step_m", scene.quality.close_step_m);
    // The bound on close-range detail's cost: at most MAX_CLOSE_STEPS steps span the range.
    if cl.close_detail > 0.0 && range_ok && step_ok {
        let steps = cl.close_detail_range_m / scene.quality.close_step_m;
        if steps > f64::from(crate::scene::MAX_CLOSE_STEPS) {
            c.push_pair(
                (
                    "quality.close_step_m",
                    num(scene.quality.close_step_m),
                    format!(
                        "takes {} steps to cross clouds.close_detail_range_m; at most {} may (a longer step or a shorter range)",
                        steps.ceil(),
                        crate::scene::MAX_CLOSE_STEPS
                    ),
                ),
                (
                    "clouds.close_detail_range_m",
                    num(cl.close_detail_range_m),
                    format!(
                        "is more than {} of quality.close_step_m",
                        crate::scene::MAX_CLOSE_STEPS
                    ),
                ),
            );
        }
    }
    // The second erosion reads the first's lookup and only where the first eroded: without it
    // the close steps would cost their samples and change nothing.
    if cl.close_detail > 0.0 && cl.detail_strength <= 0.0 {
        c.push(
            "clouds.close_detail",
            num(cl.close_detail),
            "erodes the edges a second time where the detail erosion does: it needs clouds.detail_strength > 0 (or close_detail = 0)",
        );
    }
    // The baselines draw the shape noise's water cloud alone.
    for (field, share, what) in [
        (
            "clouds.cirrus",
            cl.cirrus,
            "draws water cloud only: cirrus needs",
        ),
        (
            "clouds.cellular",
            cl.cellular,
            "draws the shape noise's clouds only: cellular layers need",
        ),
        (
            "clouds.close_detail",
            cl.close_detail,
            "marches its own steps with one erosion: close-range detail needs",
        ),
    ] {
        if share > 0.0 && scene.quality.method != crate::Method::Volumetric {
            c.push(
                field,
                num(share),
                format!(
                    "quality.method = \"{}\" {what} \"volumetric\"",
                    scene.quality.method.name()
                ),
            );
        }
    }
    check_layers(&mut c, scene);

    if scene.noise.seed > i64::MAX as u64 {
        c.push(
            "noise.seed",
            scene.noise.seed.to_string(),
            format!("must be <= {} (TOML integers are signed 64-bit)", i64::MAX),
        );
    }

    let li = &scene.lighting;
    let s_ok = c.non_negative("lighting.scattering", li.scattering);
    let a_ok = c.non_negative("lighting.absorption", li.absorption);
    if s_ok && a_ok && li.scattering + li.absorption <= 0.0 {
        let rule = "lighting.scattering + lighting.absorption must be > 0 (the clouds would be \
                    invisible)";
        c.push_pair(
            ("lighting.scattering", num(li.scattering), rule.to_owned()),
            ("lighting.absorption", num(li.absorption), rule.to_owned()),
        );
    }
    c.non_negative("lighting.powder_strength", li.powder_strength);
    c.colour("lighting.ambient_bottom", &li.ambient_bottom);
    c.colour("lighting.ambient_top", &li.ambient_top);
    c.non_negative("lighting.ambient_strength", li.ambient_strength);
    c.unit(
        "lighting.precipitation_darkening",
        li.precipitation_darkening,
    );
    c.float("lighting.phase.g", li.phase.g, Excl(-1.0), Excl(1.0));
    c.float("lighting.phase.g2", li.phase.g2, Excl(-1.0), Excl(1.0));
    c.unit("lighting.phase.blend", li.phase.blend);
    let ms = &li.multiple_scattering;
    c.uint(
        "lighting.multiple_scattering.octaves",
        ms.octaves.into(),
        0,
        MAX_OCTAVES.into(),
    );
    // Wrenninge's a <= b (each octave dimmer than the one before in energy) is not required:
    // against the path tracer's all-orders truth it keeps thick clouds far too dark, and the
    // fitted octaves have a > b (docs/fit). a > 1 (each octave brighter than single
    // scattering's phase lobe) is allowed too: the fitted octaves stand for all the orders
    // beyond the first, which in thick cloud carry most of the light.
    c.float(
        "lighting.multiple_scattering.a",
        ms.a,
        Excl(0.0),
        Incl(MAX_OCTAVE_A),
    );
    c.float("lighting.multiple_scattering.b", ms.b, Excl(0.0), Incl(1.0));
    c.float("lighting.multiple_scattering.c", ms.c, Excl(0.0), Incl(1.0));
    c.float(
        "lighting.multiple_scattering.buildup_m",
        ms.buildup_m,
        Incl(0.0),
        Incl(10_000.0),
    );
    c.float(
        "lighting.multiple_scattering.side_light",
        ms.side_light,
        Incl(0.0),
        Incl(4.0),
    );
    c.float(
        "lighting.multiple_scattering.coverage_exponent",
        ms.coverage_exponent,
        Incl(0.0),
        Incl(4.0),
    );
    c.float(
        "lighting.multiple_scattering.limb_darkening",
        ms.limb_darkening,
        Incl(0.0),
        Incl(4.0),
    );
    // Above 1 the lobe's factor would go negative behind the viewer.
    c.float(
        "lighting.multiple_scattering.forward_lobe",
        ms.forward_lobe,
        Incl(0.0),
        Incl(1.0),
    );
    c.float(
        "lighting.multiple_scattering.forward_lobe_g",
        ms.forward_lobe_g,
        Incl(0.0),
        Incl(0.95),
    );
    // Above 1 the factor would go negative looking straight down at a layer's base.
    c.float(
        "lighting.multiple_scattering.vertical_anisotropy",
        ms.vertical_anisotropy,
        Incl(0.0),
        Incl(1.0),
    );
    // Above 2 the factor would go negative under a sun at the horizon over a full deck.
    c.float(
        "lighting.multiple_scattering.deck_escape",
        ms.deck_escape,
        Incl(0.0),
        Incl(2.0),
    );
    c.float(
        "lighting.multiple_scattering.steep_light",
        ms.steep_light,
        Incl(0.0),
        Incl(1.0),
    );
    c.float(
        "lighting.multiple_scattering.steep_light_scale",
        ms.steep_light_scale,
        Incl(0.5),
        Incl(8.0),
    );
    c.float(
        "lighting.multiple_scattering.downward_dimming",
        ms.downward_dimming,
        Incl(0.0),
        Incl(8.0),
    );
    // 0 turns the far shadow off; a chord below 100 m would shadow like a solid deck.
    let chord = ms.far_chord_m;
    if !chord.is_finite() {
        c.finite("lighting.multiple_scattering.far_chord_m", chord);
    } else if chord != 0.0 && !(100.0..=1_000_000.0).contains(&chord) {
        c.push(
            "lighting.multiple_scattering.far_chord_m",
            num(chord),
            "must be 0 (off) or within [100, 1000000]",
        );
    }

    let q = &scene.quality;
    c.uint(
        "quality.view_steps",
        q.view_steps.into(),
        1,
        MAX_VIEW_STEPS.into(),
    );
    if let Some(step) = q.step_length_m {
        c.positive("quality.step_length_m", step);
    }
    c.uint(
        "quality.light_steps",
        q.light_steps.into(),
        0,
        MAX_LIGHT_STEPS.into(),
    );
    c.float(
        "quality.light_step_growth",
        q.light_step_growth,
        Incl(1.0),
        Incl(16.0),
    );
    c.positive("quality.first_light_step_m", q.first_light_step_m);
    c.positive("quality.cutoff_distance_m", q.cutoff_distance_m);
    c.float(
        "quality.early_exit_transmittance",
        q.early_exit_transmittance,
        Incl(0.0),
        Excl(1.0),
    );
    if q.checkerboard && q.temporal == crate::Temporal::Off {
        c.push(
            "quality.checkerboard",
            "true".into(),
            "needs quality.temporal = \"1/4\" or \"1/16\": it skips pixels whose reprojected history is clear",
        );
    }

    if q.integrator == crate::Integrator::Pathtrace && q.temporal != crate::Temporal::Off {
        c.push(
            "quality.temporal",
            format!("\"{}\"", q.temporal.name()),
            "must be \"off\" with quality.integrator = \"pathtrace\": the path tracer accumulates every pixel itself",
        );
    }

    if q.method != crate::Method::Volumetric {
        if q.integrator != crate::Integrator::March {
            c.push(
                "quality.integrator",
                format!("\"{}\"", q.integrator.name()),
                format!(
                    "must be \"march\" with quality.method = \"{}\": the path tracer renders the volumetric model",
                    q.method.name()
                ),
            );
        }
        if q.temporal != crate::Temporal::Off {
            c.push(
                "quality.temporal",
                format!("\"{}\"", q.temporal.name()),
                format!(
                    "must be \"off\" with quality.method = \"{}\": temporal upsampling reprojects the volumetric march",
                    q.method.name()
                ),
            );
        }
    }

    if let Some(a) = &scene.animation {
        c.positive("animation.duration_s", a.duration_s);
        if a.keyframes.is_empty() {
            c.push(
                "animation.keyframes",
                "[]".into(),
                "needs at least one keyframe ([[animation.keyframes]] with time_s, position, yaw_deg, pitch_deg)",
            );
        }
        let mut last = f64::NEG_INFINITY;
        for (i, k) in a.keyframes.iter().enumerate() {
            let values = [
                k.time_s,
                k.yaw_deg,
                k.pitch_deg,
                k.position[0],
                k.position[1],
                k.position[2],
            ];
            if values.iter().any(|v| !v.is_finite()) {
                c.push(
                    "animation.keyframes",
                    format!("keyframe {i}"),
                    "every value must be a finite number",
                );
                continue;
            }
            if k.time_s < 0.0 || k.time_s < last || k.time_s > a.duration_s.max(0.0) {
                c.push(
                    "animation.keyframes",
                    format!("keyframe {i}: time_s = {}", num(k.time_s)),
                    "keyframe times must be in increasing order within [0, animation.duration_s]",
                );
            }
            if k.position[1] < 0.0 {
                c.push(
                    "animation.keyframes",
                    format!("keyframe {i}: position = {}", nums(&k.position)),
                    "the altitude (second component) must be >= 0",
                );
            }
            if !(-90.0..=90.0).contains(&k.pitch_deg) {
                c.push(
                    "animation.keyframes",
                    format!("keyframe {i}: pitch_deg = {}", num(k.pitch_deg)),
                    "must be within [-90, 90]",
                );
            }
            last = k.time_s;
        }
    }

    c.issues
}

/// `[atmosphere.air]`: coefficients that make a finite, non-negative medium.
fn check_air(c: &mut Checker, air: &crate::Air) {
    c.positive("atmosphere.air.thickness_m", air.thickness_m);
    c.colour(
        "atmosphere.air.rayleigh_scattering",
        &air.rayleigh_scattering,
    );
    c.positive(
        "atmosphere.air.rayleigh_scale_height_m",
        air.rayleigh_scale_height_m,
    );
    c.non_negative("atmosphere.air.mie_scattering", air.mie_scattering);
    c.non_negative("atmosphere.air.mie_absorption", air.mie_absorption);
    c.positive("atmosphere.air.mie_scale_height_m", air.mie_scale_height_m);
    c.float("atmosphere.air.mie_g", air.mie_g, Excl(-1.0), Excl(1.0));
    c.colour("atmosphere.air.ozone_absorption", &air.ozone_absorption);
    c.non_negative("atmosphere.air.ozone_center_m", air.ozone_center_m);
    c.positive("atmosphere.air.ozone_width_m", air.ozone_width_m);
    c.unit("atmosphere.air.ground_albedo", air.ground_albedo);
}

/// `[sky]`: a date and a place together, each in range, and not alongside `sun.direction`.
fn check_sky(c: &mut Checker, scene: &Scene) {
    let sky = &scene.sky;
    if sky.is_unset() {
        return;
    }
    let lat_ok = sky
        .latitude_deg
        .is_none_or(|v| c.float("sky.latitude_deg", v, Incl(-90.0), Incl(90.0)));
    let lon_ok = sky
        .longitude_deg
        .is_none_or(|v| c.float("sky.longitude_deg", v, Incl(-180.0), Excl(360.0)));
    match (sky.date_utc, sky.latitude_deg, sky.longitude_deg) {
        (Some(_), Some(_), Some(_)) => {}
        (date, lat, lon) => {
            let missing: Vec<&str> = [
                (date.is_none(), "sky.date_utc"),
                (lat.is_none(), "sky.latitude_deg"),
                (lon.is_none(), "sky.longitude_deg"),
            ]
            .iter()
            .filter(|(m, _)| *m)
            .map(|(_, n)| *n)
            .collect();
            c.push(
                "sky",
                "(incomplete)".into(),
                format!(
                    "a date and a place go together: give {} too (or remove [sky] to set the sun by [sun])",
                    missing.join(" and ")
                ),
            );
            return;
        }
    }
    if lat_ok && lon_ok && scene.sun.direction.is_some() {
        c.push(
            "sun.direction",
            "(given)".into(),
            "[sky] gives a date and place, which set the sun's direction: remove one of them",
        );
    }
}

/// The extra cloud layers: each in range, at most [`MAX_EXTRA_LAYERS`], no two layers
/// overlapping, and only where the renderer marches them (the volumetric model without
/// empty-space skipping, whose occupancy grid covers one layer).
fn check_layers(c: &mut Checker, scene: &Scene) {
    let layers = &scene.clouds.layers;
    if layers.is_empty() {
        return;
    }
    const PATH: &str = "clouds.layers";
    if layers.len() > MAX_EXTRA_LAYERS {
        c.push(
            PATH,
            format!("{} layers", layers.len()),
            format!("at most {MAX_EXTRA_LAYERS} extra layers (four with the main one)"),
        );
    }
    let mut ranges_ok = true;
    for (i, l) in layers.iter().enumerate() {
        let n = i + 1;
        let fields = [
            ("bottom_m", l.bottom_m, l.bottom_m >= 0.0, "must be >= 0"),
            (
                "top_m",
                l.top_m,
                l.top_m > l.bottom_m,
                "must be above bottom_m",
            ),
            (
                "coverage",
                l.coverage,
                (0.0..=1.0).contains(&l.coverage),
                "must be within [0, 1]",
            ),
            ("density", l.density, l.density > 0.0, "must be > 0"),
            (
                "cloud_type",
                l.cloud_type,
                (0.0..=1.0).contains(&l.cloud_type),
                "must be within [0, 1]",
            ),
            (
                "precipitation",
                l.precipitation,
                (0.0..=1.0).contains(&l.precipitation),
                "must be within [0, 1]",
            ),
            (
                "cirrus",
                l.cirrus,
                (0.0..=1.0).contains(&l.cirrus),
                "must be within [0, 1]",
            ),
            (
                "cellular",
                l.cellular,
                (0.0..=1.0).contains(&l.cellular),
                "must be within [0, 1]",
            ),
        ];
        for (field, v, ok, rule) in fields {
            if !v.is_finite() || !ok {
                ranges_ok &= !matches!(field, "bottom_m" | "top_m");
                c.push(
                    PATH,
                    format!("layer {n}: {field} = {}", num(v)),
                    if v.is_finite() {
                        rule
                    } else {
                        "must be a finite number"
                    },
                );
            }
        }
    }
    if ranges_ok {
        let all = scene.layer_altitudes();
        let names: Vec<String> = std::iter::once("the main layer (atmosphere)".to_owned())
            .chain((1..all.len()).map(|n| format!("layer {n}")))
            .collect();
        let mut order: Vec<usize> = (0..all.len()).collect();
        order.sort_by(|&a, &b| all[a].0.total_cmp(&all[b].0));
        for w in order.windows(2) {
            let (lo, hi) = (w[0], w[1]);
            if all[hi].0 < all[lo].1 {
                c.push(
                    PATH,
                    format!(
                        "{} ({}-{} m) and {} ({}-{} m)",
                        names[lo],
                        num(all[lo].0),
                        num(all[lo].1),
                        names[hi],
                        num(all[hi].0),
                        num(all[hi].1)
                    ),
                    "cloud layers must not overlap in altitude",
                );
            }
        }
    }
    let q = &scene.quality;
    if q.method != crate::Method::Volumetric {
        c.push(
            PATH,
            format!("{} layers", layers.len()),
            format!(
                "quality.method = \"{}\" draws one layer: several layers need \"volumetric\"",
                q.method.name()
            ),
        );
    }
    if q.empty_space_skip {
        c.push(
            PATH,
            format!("{} layers", layers.len()),
            "quality.empty_space_skip covers the main layer only: turn it off with several layers",
        );
    }
}

/// Largest accepted image width or height, pixels.
pub const MAX_RESOLUTION: u32 = 16384;
/// Largest accepted `quality.view_steps`.
pub const MAX_VIEW_STEPS: u32 = 65536;
/// Largest accepted `quality.light_steps`.
pub const MAX_LIGHT_STEPS: u32 = 16;
/// Largest accepted `lighting.multiple_scattering.a` (the fit's grid ends there).
pub const MAX_OCTAVE_A: f64 = 2.0;
/// Largest accepted `lighting.multiple_scattering.octaves`.
pub const MAX_OCTAVES: u32 = 8;
