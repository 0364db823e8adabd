//! The sun, both ways, without a renderer: a [`StratusSun`] light follows the scene's sun (and
//! the real sun of its `[sky]` date and place), or the scene's sun follows the light.

use bevy::prelude::*;
use bevy::transform::TransformPlugin;
use stratus::Scene;
use stratus_bevy::{StratusPlugin, StratusScene, StratusSun};

fn app(scene: Scene) -> App {
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, TransformPlugin, StratusPlugin { scene }));
    app
}

/// cumulus-noon with the real sun of Paris at 18:30 UTC on midsummer's day.
fn paris_midsummer_evening() -> Scene {
    let mut scene = Scene::preset("cumulus-noon").unwrap();
    scene.sky.date_utc = Some("2026-06-21T18:30:00Z".parse().unwrap());
    scene.sky.latitude_deg = Some(48.85);
    scene.sky.longitude_deg = Some(2.35);
    scene
}

/// The light follows the scene: its direction is the scene's key light's, converted to Bevy's
/// axes (z south), and it moves when the scene's date does.
#[test]
fn a_light_follows_the_scenes_sun() {
    let mut scene = paris_midsummer_evening();
    let mut app = app(scene.clone());
    let light = app
        .world_mut()
        .spawn((DirectionalLight::default(), StratusSun::from_scene()))
        .id();
    let toward = |app: &mut App| -> Vec3 {
        app.update();
        // Transforms propagate the next frame.
        app.update();
        app.world()
            .get::<GlobalTransform>(light)
            .unwrap()
            .back()
            .as_vec3()
    };
    let want = |scene: &Scene| stratus::host_from_world(scene.key_light().0).as_vec3();
    let got = toward(&mut app);
    assert!(
        got.distance(want(&scene)) < 1e-5,
        "light toward {got}, the scene's sun {}",
        want(&scene)
    );
    // An hour later the sun is lower in the west (Paris, midsummer evening).
    scene.sky.date_utc = Some("2026-06-21T19:30:00Z".parse().unwrap());
    app.world_mut().resource_mut::<StratusScene>().0 = scene.clone();
    let later = toward(&mut app);
    assert!(later.distance(want(&scene)) < 1e-5);
    assert!(
        later.y < got.y,
        "an hour later the sun is lower: {got} then {later}"
    );
    let lux = app
        .world()
        .get::<DirectionalLight>(light)
        .unwrap()
        .illuminance;
    assert!(lux > 0.0, "the light's illuminance {lux}");
}

/// The scene follows the light: its sun's direction is the light's, and a date and place it
/// had no longer decide it.
#[test]
fn the_scenes_sun_follows_a_light() {
    let mut app = app(paris_midsummer_evening());
    let toward = Vec3::new(0.3, 0.8, -0.5).normalize();
    app.world_mut().spawn((
        DirectionalLight::default(),
        StratusSun::from_light(),
        Transform::default().looking_to(-toward, Vec3::Y),
    ));
    app.update();
    app.update();
    let scene = app.world().resource::<StratusScene>().0.clone();
    assert!(scene.sky.is_unset(), "the date and place are dropped");
    let sun = stratus::host_from_world(scene.sun_direction()).as_vec3();
    assert!(
        sun.distance(toward) < 1e-5,
        "the scene's sun toward {sun}, the light's {toward}"
    );
}
