//! The built-in presets: they load, validate, round-trip and show what their names promise.

use stratus_scene::{DEFAULT_PRESET, PhaseModel, Scene, presets};

#[test]
fn every_preset_loads_validates_and_round_trips() {
    assert!(presets().len() >= 6);
    for preset in presets() {
        let scene = Scene::preset(preset.name).unwrap_or_else(|e| panic!("{}:\n{e}", preset.name));
        scene.validate().unwrap();
        let text = scene.to_toml();
        let back = Scene::from_toml_str(&text, preset.name).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(back, scene, "{} does not round-trip", preset.name);
        assert!(
            !preset.description.is_empty() && !preset.description.contains('\n'),
            "{} needs a one-line description",
            preset.name
        );
    }
}

#[test]
fn preset_names_are_unique_and_the_default_comes_first() {
    let mut names: Vec<&str> = presets().iter().map(|p| p.name).collect();
    assert_eq!(names[0], DEFAULT_PRESET);
    names.sort_unstable();
    names.dedup();
    assert_eq!(names.len(), presets().len());
}

#[test]
fn default_is_cumulus_noon() {
    assert_eq!(Scene::preset("cumulus-noon").unwrap(), Scene::default());
    assert_eq!(
        Scene::from_toml_str("", "empty.toml").unwrap(),
        Scene::default()
    );
}

#[test]
fn presets_show_what_their_names_promise() {
    let p = |name| Scene::preset(name).unwrap();

    let above = p("above-clouds");
    assert!(above.camera.position[1] > above.atmosphere.cloud_top_m);
    assert!(above.camera.pitch_deg < 0.0);

    let inside = p("inside-layer");
    let alt = inside.camera.position[1];
    assert!(inside.atmosphere.cloud_bottom_m < alt && alt < inside.atmosphere.cloud_top_m);

    // The sun of sunset's date and place (the physical sky's astronomy), low in the west.
    let sunset = p("sunset");
    let elevation = sunset.sun_elevation_deg();
    assert!(
        (0.0..10.0).contains(&elevation),
        "sunset's sun at {elevation} degrees"
    );
    let d = sunset.sun_direction();
    let azimuth = d[0].atan2(d[2]).to_degrees();
    let facing = (sunset.camera.yaw_deg - azimuth).rem_euclid(360.0);
    assert!(
        facing.min(360.0 - facing) < 30.0,
        "camera must face the sun"
    );
    assert_eq!(sunset.lighting.phase.model, PhaseModel::TwoLobeHg);

    let storm = p("storm");
    assert!(storm.clouds.coverage >= 0.85 && storm.clouds.precipitation >= 0.5);
    assert!(storm.clouds.density > 1.0);

    let overcast = p("stratocumulus-overcast");
    assert!(overcast.clouds.coverage >= 0.75);
    assert_eq!(overcast.clouds.cloud_type, 0.5);
}

#[test]
fn base_is_deep_merged() {
    let src = "base = \"sunset\"\n\n[lighting.phase]\ng = 0.7\n\n[clouds]\ncoverage = 0.6\n";
    let scene = Scene::from_toml_str(src, "mine.toml").unwrap();
    let sunset = Scene::preset("sunset").unwrap();
    assert_eq!(scene.lighting.phase.g, 0.7);
    assert_eq!(scene.lighting.phase.model, sunset.lighting.phase.model);
    assert_eq!(scene.lighting.phase.blend, sunset.lighting.phase.blend);
    assert_eq!(scene.clouds.coverage, 0.6);
    assert_eq!(scene.sun, sunset.sun);
}

#[test]
fn optional_fields_round_trip() {
    let mut scene = Scene::default().with_size(320, 180);
    scene.sun.direction = Some([1.0, 2.0, -0.5]);
    scene.quality.step_length_m = Some(75.0);
    scene.noise.seed = 42;
    let back = Scene::from_toml_str(&scene.to_toml(), "round-trip").unwrap();
    assert_eq!(back, scene);
    assert_eq!(back.camera.resolution, [320, 180]);
}

#[test]
fn from_file_reads_a_scene() {
    let path = std::env::temp_dir().join(format!("stratus-scene-{}.toml", std::process::id()));
    std::fs::write(&path, "base = \"storm\"\n[camera]\nresolution = [64, 32]\n").unwrap();
    let scene = Scene::from_file(&path);
    std::fs::remove_file(&path).unwrap();
    let scene = scene.unwrap();
    assert_eq!(scene.camera.resolution, [64, 32]);
    assert_eq!(scene.clouds, Scene::preset("storm").unwrap().clouds);
}

/// Seed 001's stylised presets carry its table (hour, minute, auto exposure, exposure min and
/// max): the hour is local time in Hangzhou (UTC+8) on the seed's date, the filter and the
/// stronger colour are on, and the exposure range keeps the seed's width, max / min, centred
/// (geometrically) on the hour's exposure here, since the seed's units are its renderer's.
#[test]
fn the_kuwahara_presets_carry_the_seed_table() {
    // name, hour, minute, auto exposure, exposure min, exposure max (seed 001, 1.3.2).
    let table = [
        ("kuwahara-day", 12, 0, false, 0.05, 0.28),
        ("kuwahara-dusk", 18, 30, true, 0.20, 3.00),
        ("kuwahara-night", 19, 0, true, 0.60, 3.00),
    ];
    for (name, hour, minute, auto, lo, hi) in table {
        let mut s = Scene::preset(name).unwrap();
        assert!(s.post.kuwahara && s.post.saturation > 1.0, "{name}");
        assert_eq!(s.camera.auto_exposure, auto, "{name}");
        let when = format!("2023-03-24T{:02}:{minute:02}:00Z", hour - 8);
        assert_eq!(s.sky.date_utc, when.parse().ok(), "{name}");
        assert_eq!(
            (s.sky.latitude_deg, s.sky.longitude_deg),
            (Some(30.2741), Some(120.1551))
        );
        let [min, max] = s.camera.exposure_range.expect(name);
        let width = (max / min) / (hi / lo);
        assert!(
            (width - 1.0).abs() < 1e-3,
            "{name}: range width {} against the seed's {}",
            max / min,
            hi / lo
        );
        let bounded = s.auto_exposure();
        s.camera.exposure_range = None;
        let free = s.auto_exposure();
        let centre = (min * max).sqrt();
        assert!(
            (centre / free - 1.0).abs() < 1e-3,
            "{name}: range centred on {centre}, the hour's exposure is {free}"
        );
        assert_eq!(bounded, free, "{name}: the range bounds its own hour");
        // Hours later, in the dark, the exposure adapts only up to the range's top.
        s.camera.exposure_range = Some([min, max]);
        s.sky.date_utc = "2023-03-24T13:00:00Z".parse().ok();
        if auto {
            assert_eq!(
                s.auto_exposure(),
                max,
                "{name}: a darker hour adapts only to the range's top"
            );
        }
    }
}
