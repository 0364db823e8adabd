//! The scenes of the suite: every preset, and stress variants of `cumulus-noon` where
//! methods fail, all at [`WIDTH`] x [`HEIGHT`].

use stratus_scene::{CloudLayer, Integration, Method, Scene, ShapeTexture};

/// Image width of every scene (16:9, a quarter of 256x144 in pixels: the suite's ~60 GPU
/// frames and 12 CPU frames cost seconds, not minutes, on lavapipe in the dev profile).
pub const WIDTH: u32 = 128;
/// Image height of every scene.
pub const HEIGHT: u32 = 72;

/// A named scene of the suite.
pub struct Case {
    /// File-name-safe name (snapshots, goldens, table rows).
    pub name: String,
    /// What it stresses.
    pub about: &'static str,
    pub scene: Scene,
}

fn stress(name: &str, about: &'static str, edit: impl FnOnce(&mut Scene)) -> Case {
    let mut scene = Scene::preset("cumulus-noon")
        .expect("preset")
        .with_size(WIDTH, HEIGHT);
    edit(&mut scene);
    Case {
        name: format!("stress-{name}"),
        about,
        scene,
    }
}

/// Whether the suite's scene `name` is a preset (the engine kit's goldens are the presets).
pub fn is_preset(name: &str) -> bool {
    stratus_scene::presets().iter().any(|p| p.name == name)
}

/// Every preset, then the stress variants. Each scene is validated.
pub fn all() -> Vec<Case> {
    let mut cases: Vec<Case> = stratus_scene::presets()
        .iter()
        .map(|p| Case {
            name: p.name.to_string(),
            about: "preset",
            scene: Scene::preset(p.name)
                .expect("preset")
                .with_size(WIDTH, HEIGHT),
        })
        .collect();
    cases.extend([
        stress(
            "sun-horizon",
            "sun at 0 degrees: grazing light paths through the layer",
            |s| s.sun.elevation_deg = 0.0,
        ),
        stress(
            "camera-at-layer-bottom",
            "camera exactly on the lower boundary of the layer",
            |s| s.camera.position[1] = s.atmosphere.cloud_bottom_m,
        ),
        stress("full-coverage", "coverage 1: overcast", |s| {
            // The weather map's coverage: on convective cells (the preset's) coverage 1 still
            // leaves the map's thin regions broken.
            s.clouds.convective_cells = 0.0;
            s.clouds.coverage = 1.0;
        }),
        stress("zero-coverage", "coverage 0: clear sky", |s| {
            s.clouds.coverage = 0.0
        }),
        stress(
            "riemann",
            "the naive Riemann step integral instead of the analytic one",
            |s| {
                // The weather map's cumulus, on which the paths' bounds were measured: on the
                // preset's convective cells the CPU's f64 Riemann sum and the GPU's f32 one
                // part by up to 5.2 at single pixels (bound 1.2).
                s.clouds.convective_cells = 0.0;
                s.quality.integration = Integration::Riemann;
            },
        ),
        stress(
            "one-view-step",
            "a single view step through the layer",
            |s| s.quality.view_steps = 1,
        ),
        stress(
            "layers",
            "three cloud layers, the camera between two: per-layer marches in order, decks shadowing the clouds below",
            |s| {
                s.camera.position[1] = 5000.0;
                s.camera.pitch_deg = -4.0;
                s.clouds.layers = vec![
                    CloudLayer {
                        bottom_m: 6000.0,
                        top_m: 7000.0,
                        coverage: 0.7,
                        density: 0.4,
                        cloud_type: 0.2,
                        precipitation: 0.0,
                        cirrus: 0.0,
                        cellular: 0.0,
                    },
                    CloudLayer {
                        bottom_m: 600.0,
                        top_m: 1200.0,
                        coverage: 0.5,
                        density: 1.0,
                        cloud_type: 0.5,
                        precipitation: 0.3,
                        cirrus: 0.0,
                        cellular: 0.0,
                    },
                ];
            },
        ),
        stress(
            "cirrus",
            "cirrus at 8-9.5 km over the cumulus, looking 30 degrees up: fibres read in the wind's frame, bent by the curl noise",
            |s| {
                s.camera.pitch_deg = 30.0;
                s.clouds.layers = vec![CloudLayer {
                    bottom_m: 8000.0,
                    top_m: 9500.0,
                    coverage: 0.45,
                    density: stratus_scene::DEFAULT_CIRRUS_DENSITY,
                    cloud_type: 0.0,
                    precipitation: 0.0,
                    cirrus: 1.0,
                    cellular: 0.0,
                }];
            },
        ),
        stress(
            "cellular",
            "stratocumulus cloudlets at 1-1.7 km under altocumulus at 4-4.5 km, looking 30 degrees up: one domed cloudlet on each Worley cell, sized by the layer's depth",
            |s| {
                s.camera.pitch_deg = 30.0;
                s.atmosphere.cloud_bottom_m = 1000.0;
                s.atmosphere.cloud_top_m = 1700.0;
                s.clouds.coverage = 0.6;
                s.clouds.cloud_type = 0.5;
                s.clouds.cellular = 1.0;
                s.clouds.layers = vec![CloudLayer {
                    bottom_m: 4000.0,
                    top_m: 4500.0,
                    coverage: 0.5,
                    density: 0.6,
                    cloud_type: 0.35,
                    precipitation: 0.0,
                    cirrus: 0.0,
                    cellular: 1.0,
                }];
            },
        ),
        stress(
            "close-detail",
            "close-range detail at the edge of a cumulus's fringe at 2700 m, looking east into it: the edges eroded again by the detail noise read four times finer within 1 km, marched there in 20 m steps, the rest of each ray at its own step",
            |s| {
                s.camera.position = [-1800.0, 2700.0, -11750.0];
                s.camera.yaw_deg = 90.0;
                s.camera.pitch_deg = 0.0;
                // scenes/close-detail.toml: the fringe of one of the weather map's clouds.
                s.clouds.convective_cells = 0.0;
                s.clouds.close_detail = 1.0;
            },
        ),
        stress(
            "light-shafts",
            "light shafts in the physical sky: the clouds' shadows in the air, looking toward a sun 24 degrees up",
            |s| {
                // The weather map's cumulus, on which the paths' bounds were measured (on the
                // preset's cells the CPU's max abs was 1.4, bound 1.2).
                s.clouds.convective_cells = 0.0;
                s.atmosphere.sky = stratus_scene::SkyModel::Physical;
                s.atmosphere.light_shafts = true;
                s.camera.auto_exposure = true;
                s.sun.elevation_deg = 24.0;
                s.sun.azimuth_deg = s.camera.yaw_deg + 20.0;
                s.camera.pitch_deg = 6.0;
            },
        ),
        stress(
            "haze",
            "3000 m of continental haze from a METAR (HZ) in the physical sky: the aerosol Koschmieder's relation gives",
            |s| {
                s.atmosphere.sky = stratus_scene::SkyModel::Physical;
                s.camera.auto_exposure = true;
                s.atmosphere.air = stratus_weather::haze::hazy_air(
                    &s.atmosphere.air,
                    3000.0,
                    stratus_weather::haze::Aerosol::Continental,
                )
                .expect("3000 m is hazier than the clean air");
            },
        ),
        stress(
            "convective-cells",
            "the scattered weather state: cumulus on the weather map's convective cells, each cloud's dome from the cell field smoothed over four taps",
            |s| {
                stratus_weather::states::find("scattered")
                    .expect("state")
                    .params
                    .apply(s);
                s.camera.pitch_deg = 8.0;
            },
        ),
        stress(
            "method-basic",
            "baseline: the basic tutorial ray marcher (GPU only)",
            |s| s.quality.method = Method::Basic,
        ),
        stress(
            "method-sprites",
            "baseline: Wang 2003's sprite clouds, a raster pass (GPU only)",
            |s| {
                s.quality.method = Method::Sprites;
                // Off the sprite rings' grid: their window starts at floor(camera / 12 km), and
                // a camera exactly on a grid line (the preset's origin) shifts every ring by a
                // cell under the counter model's 0.29 m moves (11.6% of the detail
                // evaluations), a step no device's rounding of an exact 0 can take.
                s.camera.position[0] = 3100.0;
                s.camera.position[2] = 4700.0;
            },
        ),
        stress(
            "thunderstorm",
            "a raining deck: rain shafts, rain particles (a raster pass) and a lightning flash in view, at the first frame that shows one",
            |s| {
                // scenes/thunderstorm.toml (docs/effects.md's picture), whose time must be the
                // first frame with a flash in view.
                let file = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                    .join("../scenes/thunderstorm.toml");
                *s = Scene::from_file(&file)
                    .unwrap_or_else(|e| panic!("{e}"))
                    .with_size(WIDTH, HEIGHT);
                let mut from_zero = s.clone();
                from_zero.clouds.time_s = 0.0;
                assert_eq!(
                    stratus_scene::lightning::first_flash_in_view(&from_zero, 20.0, 0.8),
                    Some(s.clouds.time_s),
                    "scenes/thunderstorm.toml's time_s is not its first frame with a flash in view"
                );
            },
        ),
    ]);
    // A frame that rasterises leaves llvmpipe's timestamps late for the device's later frames
    // (`FramePlan::rasterizes_every_frame`): such scenes come last, after every scene whose
    // passes are timed by timestamps.
    let rasterizes: Vec<bool> = cases
        .iter()
        .map(|c| {
            stratus_graph::FramePlan::for_scene(&c.scene, false)
                .is_ok_and(|p| p.rasterizes_every_frame())
        })
        .collect();
    assert!(
        rasterizes.windows(2).all(|w| w[0] <= w[1]),
        "scenes that rasterise every frame must come last: {rasterizes:?}"
    );
    for c in &cases {
        if let Err(e) = c.scene.validate() {
            panic!("scene {} is invalid: {e}", c.name);
        }
        assert_eq!(c.scene.noise.seed, 0, "{}: the suite shares seed 0", c.name);
        assert_eq!(
            c.scene.noise.shape_texture,
            ShapeTexture::Thesis,
            "{}: the suite shares the thesis-size shape texture",
            c.name
        );
    }
    cases
}
