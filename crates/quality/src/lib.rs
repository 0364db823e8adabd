//! Quality tiers as data. `stratus bench` (the lab) sweeps configurations ([`Config`]) and
//! writes what each cost and how far it was from the CPU reference ([`Row`], [`Results`],
//! `results.json`); auto quality ([`auto_quality`]) picks from those results the cheapest
//! configuration whose error meets a budget, so an application can choose its quality the way
//! `stratus render --max-error` does. The schema lives here, apart from the renderer, so that
//! the library does not carry the bench's data types and the lab and the tool share them.

#![warn(missing_docs)]

use std::{collections::BTreeMap, path::Path};

use serde::{Deserialize, Serialize};
use stratus_scene::{
    Integration, Method, MultipleScattering, PhaseModel, Scene, ShapeTexture, Temporal,
};

/// One point of the sweep: the quality and method settings a configuration overrides.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Config {
    /// View steps per ray.
    pub view_steps: u32,
    /// Light-march steps.
    pub light_steps: u32,
    /// Step integral.
    pub integration: Integration,
    /// Phase function.
    pub phase: PhaseModel,
    /// Beer-Powder term.
    pub beer_powder: bool,
    /// Multiple-scattering octaves beyond single scattering.
    pub octaves: u32,
    /// Per-pixel jitter.
    pub jitter: bool,
    /// Shape texture size.
    pub shape_texture: ShapeTexture,
    /// Temporal upsampling.
    #[serde(default)]
    pub temporal: Temporal,
    /// Dynamic step length.
    #[serde(default)]
    pub dynamic_step: bool,
    /// High-transmittance checkerboard skipping (with temporal upsampling).
    #[serde(default)]
    pub checkerboard: bool,
    /// Empty-space skipping.
    #[serde(default)]
    pub empty_space_skip: bool,
    /// The octave constants of [`PREFIT_OCTAVES`] instead of the scene's: the bench charts the
    /// preset before and after `stratus fit-scattering`.
    #[serde(default)]
    pub prefit: bool,
    /// The cloud renderer: the volumetric model, or a baseline (`basic`, `sprites`) measured
    /// against the same truth.
    #[serde(default)]
    pub method: Method,
}

/// The multiple-scattering octaves before `stratus fit-scattering`: the thesis's 2 octaves of
/// a = b = c = 0.5 (Hillaire 2016's example values).
pub const PREFIT_OCTAVES: MultipleScattering = MultipleScattering {
    octaves: 2,
    a: 0.5,
    b: 0.5,
    c: 0.5,
    buildup_m: 0.0,
    side_light: 0.0,
    coverage_exponent: 0.0,
    far_chord_m: 0.0,
    limb_darkening: 0.0,
    forward_lobe: 0.0,
    forward_lobe_g: 0.0,
    vertical_anisotropy: 0.0,
    deck_escape: 0.0,
    steep_light: 0.0,
    steep_light_scale: 1.0,
    downward_dimming: 0.0,
};

impl Config {
    /// The scene's own settings.
    pub fn of(scene: &Scene) -> Self {
        Self {
            view_steps: scene.quality.view_steps,
            light_steps: scene.quality.light_steps,
            integration: scene.quality.integration,
            phase: scene.lighting.phase.model,
            beer_powder: scene.lighting.beer_powder,
            octaves: scene.lighting.multiple_scattering.octaves,
            jitter: scene.quality.jitter,
            shape_texture: scene.noise.shape_texture,
            temporal: scene.quality.temporal,
            dynamic_step: scene.quality.dynamic_step,
            checkerboard: scene.quality.checkerboard,
            empty_space_skip: scene.quality.empty_space_skip,
            prefit: false,
            method: scene.quality.method,
        }
    }

    /// Whether the configuration uses temporal upsampling or a cheap-march technique: its
    /// error is also measured on a moving camera against the full march of each frame.
    pub fn is_method(&self) -> bool {
        self.temporal != Temporal::Off
            || self.dynamic_step
            || self.checkerboard
            || self.empty_space_skip
    }

    /// `scene` with these settings (a fixed step length is dropped: the view steps rule).
    pub fn apply(&self, scene: &Scene) -> Scene {
        let mut s = scene.clone();
        s.quality.view_steps = self.view_steps;
        s.quality.step_length_m = None;
        s.quality.light_steps = self.light_steps;
        s.quality.integration = self.integration;
        s.lighting.phase.model = self.phase;
        s.lighting.beer_powder = self.beer_powder;
        s.lighting.multiple_scattering.octaves = self.octaves;
        s.quality.jitter = self.jitter;
        s.noise.shape_texture = self.shape_texture;
        s.quality.temporal = self.temporal;
        s.quality.dynamic_step = self.dynamic_step;
        s.quality.checkerboard = self.checkerboard;
        s.quality.empty_space_skip = self.empty_space_skip;
        s.quality.method = self.method;
        if self.prefit {
            s.lighting.multiple_scattering = MultipleScattering {
                octaves: self.octaves,
                ..PREFIT_OCTAVES
            };
        }
        s
    }

    /// A short name: every setting, e.g. `v64 l6 analytic hg o2 jitter 128x32x128`, then the
    /// methods in use (`temporal 1/16`, `dynamic-step`, `checkerboard`, `skip`). A baseline is
    /// named by its method and the settings it reads: `basic v64 l6`, `sprites`.
    pub fn name(&self) -> String {
        match self.method {
            Method::Volumetric => {}
            Method::Basic => return format!("basic v{} l{}", self.view_steps, self.light_steps),
            Method::Sprites => return "sprites".to_string(),
        }
        let mut methods = String::new();
        if self.temporal != Temporal::Off {
            methods.push_str(&format!(" temporal {}", self.temporal.name()));
        }
        for (on, name) in [
            (self.dynamic_step, " dynamic-step"),
            (self.checkerboard, " checkerboard"),
            (self.empty_space_skip, " skip"),
            (self.prefit, " pre-fit"),
        ] {
            if on {
                methods.push_str(name);
            }
        }
        format!(
            "v{} l{} {} {} o{}{}{} {}{methods}",
            self.view_steps,
            self.light_steps,
            match self.integration {
                Integration::Analytic => "analytic",
                Integration::Riemann => "riemann",
            },
            phase_name(self.phase),
            self.octaves,
            if self.beer_powder { " powder" } else { "" },
            if self.jitter { " jitter" } else { "" },
            match self.shape_texture {
                ShapeTexture::Thesis => "128x32x128",
                ShapeTexture::Hzd => "128^3",
            }
        )
    }
}

/// The phase model in the short form configuration names use (`hg`, `2hg`, `cs`).
pub fn phase_name(p: PhaseModel) -> &'static str {
    match p {
        PhaseModel::Hg => "hg",
        PhaseModel::TwoLobeHg => "2hg",
        PhaseModel::CornetteShanks => "cs",
    }
}

/// One measured configuration.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Row {
    /// The scene (preset name).
    pub scene: String,
    /// The configuration's name ([`Config::name`]).
    pub name: String,
    /// Whether this is the scene's own (preset) configuration.
    pub preset: bool,
    /// The settings.
    pub config: Config,
    /// Median GPU time of all passes, ms.
    pub gpu_ms: f64,
    /// Median GPU time of each pass, ms.
    pub passes: BTreeMap<String, f64>,
    /// How the times were taken: `gpu-timestamp`, or `cpu-wall` (each pass submitted alone
    /// and waited for).
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub timing: String,
    /// `gpu_ms` over the preset configuration's.
    pub time_vs_preset: f64,
    /// View steps per pixel.
    pub view_steps_pp: f64,
    /// Light samples per pixel.
    pub light_samples_pp: f64,
    /// Density evaluations (view and light samples) per pixel: "samples per pixel".
    pub samples_pp: f64,
    /// RMSE of linear radiance (rgb) against the reference.
    pub rmse: f64,
    /// Mean FLIP of the composited, tone-mapped image against the reference's.
    pub flip: f64,
    /// 95th percentile of FLIP.
    pub flip_p95: f64,
    /// The reference: `quadrature` or `montecarlo-<spp>spp`.
    pub reference: String,
    /// On the scene's Pareto front of (gpu_ms, flip).
    pub pareto: bool,
    /// Methods (temporal upsampling, cheap marching) only: on a moving camera (the bench's
    /// camera move), the mean over frames of the mean FLIP against the full march of
    /// the same frame; `gpu_ms` is then the median frame of that sequence (amortised).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub motion_flip: Option<f64>,
    /// Methods only: the worst frame's mean FLIP in that sequence.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub motion_flip_worst: Option<f64>,
}

impl Row {
    /// `config` on `scene` before anything is measured: every time and error zero, not on the
    /// Pareto front.
    pub fn unmeasured(scene: &str, config: Config, preset: bool) -> Self {
        Self {
            scene: scene.into(),
            name: config.name(),
            preset,
            config,
            gpu_ms: 0.0,
            passes: BTreeMap::new(),
            timing: String::new(),
            time_vs_preset: 1.0,
            view_steps_pp: 0.0,
            light_samples_pp: 0.0,
            samples_pp: 0.0,
            rmse: 0.0,
            flip: 0.0,
            flip_p95: 0.0,
            reference: String::new(),
            pareto: false,
            motion_flip: None,
            motion_flip_worst: None,
        }
    }
}

/// What `results.json` holds.
#[derive(Debug, Serialize, Deserialize)]
pub struct Results {
    /// The device that ran the frames.
    pub device: String,
    /// `wgpu` or `ash`.
    pub backend: String,
    /// Image size.
    pub size: [u32; 2],
    /// Timed repeats per configuration.
    pub repeats: u32,
    /// Monte Carlo samples per pixel of the references.
    pub mc_spp: u32,
    /// Every measurement.
    pub rows: Vec<Row>,
}

/// The default location of the bench's results (where `stratus bench` writes by default).
pub const DEFAULT_RESULTS: &str = "target/stratus-bench/results.json";

/// Why no configuration was picked.
#[derive(Debug, thiserror::Error)]
pub enum QualityError {
    /// The results file could not be read.
    #[error(
        "reading bench results {path} ({message}); run `stratus bench` first, or pass --bench-results FILE"
    )]
    Read {
        /// The file.
        path: String,
        /// The system's message.
        message: String,
    },
    /// The results file is not the bench's JSON.
    #[error("parsing bench results {path}: {message}")]
    Parse {
        /// The file.
        path: String,
        /// The parser's message.
        message: String,
    },
    /// The results hold no configuration.
    #[error("the bench results hold no configuration")]
    Empty,
    /// No configuration meets the budget (says the best achievable).
    #[error("{0}")]
    Unmet(String),
}

impl Results {
    /// Reads `results.json` as `stratus bench` writes it.
    pub fn load(path: &Path) -> Result<Self, QualityError> {
        let text = std::fs::read_to_string(path).map_err(|e| QualityError::Read {
            path: path.display().to_string(),
            message: e.to_string(),
        })?;
        serde_json::from_str(&text).map_err(|e| QualityError::Parse {
            path: path.display().to_string(),
            message: e.to_string(),
        })
    }
}

/// A coarse scene class: where the camera is against the layer, and whether the sun is low.
fn scene_class(scene: &Scene) -> &'static str {
    let alt = scene.camera.position[1];
    let low_sun = scene.sun_elevation_deg() < 10.0;
    if alt > scene.atmosphere.cloud_top_m {
        "camera above the layer"
    } else if alt >= scene.atmosphere.cloud_bottom_m {
        "camera inside the layer"
    } else if low_sun {
        "camera below, low sun"
    } else {
        "camera below, high sun"
    }
}

/// Auto quality (`stratus render --max-error E`): the cheapest measured configuration whose FLIP is at most
/// `max_error` for this scene. A scene the bench measured uses its own rows; any other scene
/// uses the first measured preset of its class ([`scene_class`]), else needs the configuration
/// to meet `max_error` on every measured scene (the worst case). The error was measured at
/// the bench's image size against its reference; the pick is as good as that measurement.
/// Returns the
/// scene with the configuration applied and a sentence saying what was picked and why.
pub fn auto_quality(
    scene: &Scene,
    name: &str,
    max_error: f64,
    results: &Results,
) -> Result<(Scene, String), QualityError> {
    let own: Vec<&Row> = results.rows.iter().filter(|r| r.scene == name).collect();
    // Per configuration: worst error and mean time over the scenes that count.
    let mut table: BTreeMap<String, (Config, f64, f64, f64, usize)> = BTreeMap::new();
    let (rows, basis): (Vec<&Row>, String) = if !own.is_empty() {
        (own, format!("scene {name} as measured"))
    } else {
        // Nearest class: a measured preset whose camera is on the same side of the layer
        // and whose sun is as low (or not); failing that, the worst case over all of them.
        let class = scene_class(scene);
        let same: Vec<&Row> = results
            .rows
            .iter()
            .filter(|r| Scene::preset(&r.scene).is_ok_and(|s| scene_class(&s) == class))
            .collect();
        match same.first().map(|r| r.scene.clone()) {
            Some(near) => (
                same.into_iter().filter(|r| r.scene == near).collect(),
                format!(
                    "measured scene {near}, the nearest class ({class}) to {name}, which was not measured"
                ),
            ),
            None => (
                results.rows.iter().collect(),
                format!(
                    "the worst case over every measured scene ({name} was not measured and no measured scene is of its class, {class})"
                ),
            ),
        }
    };
    // A single still frame gains nothing from temporal upsampling, and the methods' still error
    // is not their error in motion: auto quality picks among the per-frame settings.
    // The baselines (basic, sprites) are there to be compared with, not picked.
    for r in rows
        .iter()
        .filter(|r| !r.config.is_method() && r.config.method == Method::Volumetric)
    {
        let e = table
            .entry(r.name.clone())
            .or_insert((r.config.clone(), 0.0, 0.0, 0.0, 0));
        e.1 = e.1.max(r.flip);
        e.2 += r.gpu_ms;
        e.3 += r.samples_pp;
        e.4 += 1;
    }
    let scenes = {
        let mut s: Vec<&str> = rows.iter().map(|r| r.scene.as_str()).collect();
        s.sort();
        s.dedup();
        s.len()
    };
    let candidates: Vec<_> = table
        .iter()
        .filter(|(_, v)| v.4 == scenes)
        .map(|(n, v)| (n, &v.0, v.1, v.2 / v.4 as f64, v.3 / v.4 as f64))
        .collect();
    let best = candidates
        .iter()
        .min_by(|a, b| a.2.total_cmp(&b.2))
        .ok_or(QualityError::Empty)?;
    let Some(pick) = candidates
        .iter()
        .filter(|c| c.2 <= max_error)
        .min_by(|a, b| a.3.total_cmp(&b.3))
    else {
        return Err(QualityError::Unmet(format!(
            "no measured configuration meets FLIP <= {max_error} on {basis}; the best achievable is {:.4} ({})",
            best.2, best.0
        )));
    };
    let why = format!(
        "auto quality: picked `{}` for FLIP <= {max_error}: measured FLIP {:.4}, {:.3} ms, {:.1} samples/px on {} ({}, {}x{}); the cheapest of {} measured configurations within the budget",
        pick.0,
        pick.2,
        pick.3,
        pick.4,
        basis,
        results.device,
        results.size[0],
        results.size[1],
        candidates.len()
    );
    Ok((pick.1.apply(scene), why))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(scene: &str, view_steps: u32, gpu_ms: f64, flip: f64) -> Row {
        let base = Config::of(&Scene::default());
        let config = Config {
            view_steps,
            ..base.clone()
        };
        let preset = config == base;
        Row {
            gpu_ms,
            samples_pp: f64::from(view_steps),
            rmse: flip,
            flip,
            flip_p95: flip,
            reference: "quadrature".into(),
            ..Row::unmeasured(scene, config, preset)
        }
    }

    fn results() -> Results {
        Results {
            device: "test".into(),
            backend: "wgpu".into(),
            size: [64, 36],
            repeats: 1,
            mc_spp: 1,
            rows: vec![
                row("cumulus-noon", 8, 1.0, 0.2),
                row("cumulus-noon", 16, 2.0, 0.1),
                row("cumulus-noon", 32, 5.0, 0.12),
                row("cumulus-noon", 64, 8.0, 0.01),
                row("sunset", 8, 1.0, 0.3),
                row("sunset", 64, 8.0, 0.05),
            ],
        }
    }

    #[test]
    fn auto_quality_picks_the_cheapest_within_budget_and_never_exceeds_it() {
        let r = results();
        let scene = Scene::default();
        let (s, why) = auto_quality(&scene, "cumulus-noon", 0.15, &r).unwrap();
        assert_eq!(s.quality.view_steps, 16, "{why}");
        let (s, _) = auto_quality(&scene, "cumulus-noon", 0.05, &r).unwrap();
        assert_eq!(s.quality.view_steps, 64);
        let e = auto_quality(&scene, "cumulus-noon", 0.001, &r).unwrap_err();
        assert!(e.to_string().contains("best achievable is 0.0100"), "{e}");
        // `storm` was not measured: the nearest class (camera below, high sun) is cumulus-noon.
        let (s, why) = auto_quality(&scene, "storm", 0.15, &r).unwrap();
        assert_eq!(s.quality.view_steps, 16);
        assert!(why.contains("nearest class"), "{why}");
    }

    #[test]
    fn results_load_names_the_file_and_what_to_do() {
        let e = Results::load(Path::new("/nonexistent/results.json")).unwrap_err();
        let m = e.to_string();
        assert!(
            m.contains("/nonexistent/results.json") && m.contains("stratus bench"),
            "{m}"
        );
    }
}
