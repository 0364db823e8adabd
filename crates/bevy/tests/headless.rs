//! The plugin in a headless Bevy app on lavapipe: frames rendered into an image and read back.
//!
//! - Occlusion: an unlit magenta box in front of the sky and the clouds shows exactly its own
//!   colour (one colour without cloud shadows; dimmed by them with): no cloud or sky light
//!   leaks onto it, and nothing magenta lies outside it.
//! - Shadowing: an unlit grey ground, with the whole of its light counted as the key light's,
//!   is dimmed by the key light's transmittance through the clouds at each point: the ratio of
//!   a frame with cloud shadows to one without matches the CPU reference's transmittance toward
//!   the sun at the pixel's ground point.

use std::sync::{Arc, Mutex};
use std::time::Duration;

use bevy::app::PluginsState;
use bevy::asset::RenderAssetUsages;
use bevy::camera::RenderTarget;
use bevy::core_pipeline::tonemapping::Tonemapping;
use bevy::log::LogPlugin;
use bevy::prelude::*;
use bevy::render::RenderPlugin;
use bevy::render::render_resource::{Extent3d, TextureDimension, TextureFormat, TextureUsages};
use bevy::render::settings::{Backends, InstanceFlags, RenderCreation, WgpuSettings};
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured};
use bevy::time::TimeUpdateStrategy;
use bevy::window::ExitCondition;
use bevy::winit::WinitPlugin;
use stratus::Scene;
use stratus_bevy::{StratusCamera, StratusPlugin};
use stratus_test_support::{assert_no_wgpu_messages, record_wgpu_log};

const W: u32 = 128;
const H: u32 = 72;
/// The camera's height above the ground (m); it looks north, level.
const EYE: f32 = 150.0;
/// The box: centre and half side (m), up and to the right of the view's centre.
const BOX_CENTRE: Vec3 = Vec3::new(12.0, EYE + 8.0, -80.0);
const BOX_HALF: f32 = 6.0;

fn scene() -> Scene {
    let mut scene = Scene::preset("cumulus-noon").unwrap();
    scene.atmosphere.sky = stratus_scene::SkyModel::Physical;
    // The weather map's kilometres-wide cumulus: the ground's shadow comes from the shadow map,
    // 312 m a texel, which does not resolve the default's convective cells (measured there:
    // 0.116 off the CPU's on average, against the bound's 0.05).
    scene.clouds.convective_cells = 0.0;
    scene
}

/// The app: a level camera over an unlit grey ground, an unlit magenta box in front of it.
fn app(target: &mut Option<Handle<Image>>) -> App {
    let mut app = App::new();
    app.add_plugins(
        DefaultPlugins
            .set(WindowPlugin {
                primary_window: None,
                exit_condition: ExitCondition::DontExit,
                ..default()
            })
            .set(RenderPlugin {
                synchronous_pipeline_compilation: true,
                // Vulkan's validation layers on, on Vulkan (lavapipe): any message fails the
                // test. No shader debug info: naga's marks its SPIR-V as WGSL (source language
                // 10), which Debian's layers do not know yet.
                render_creation: RenderCreation::Automatic(Box::new(WgpuSettings {
                    backends: Some(Backends::VULKAN),
                    instance_flags: InstanceFlags::VALIDATION,
                    ..default()
                })),
                ..default()
            })
            .disable::<WinitPlugin>()
            // The test's logger records wgpu's messages instead.
            .disable::<LogPlugin>(),
    )
    .add_plugins(StratusPlugin { scene: scene() })
    // No time passes: the clouds stay where the CPU reference has them.
    .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::ZERO));
    let world = app.world_mut();
    let image = {
        let mut image = Image::new_fill(
            Extent3d {
                width: W,
                height: H,
                depth_or_array_layers: 1,
            },
            TextureDimension::D2,
            &[0, 0, 0, 255],
            TextureFormat::Rgba8UnormSrgb,
            RenderAssetUsages::default(),
        );
        image.texture_descriptor.usage |=
            TextureUsages::RENDER_ATTACHMENT | TextureUsages::COPY_SRC;
        world.resource_mut::<Assets<Image>>().add(image)
    };
    *target = Some(image.clone());
    let ground = world
        .resource_mut::<Assets<Mesh>>()
        .add(Plane3d::default().mesh().size(60_000.0, 60_000.0));
    let cube = world.resource_mut::<Assets<Mesh>>().add(Cuboid::new(
        2.0 * BOX_HALF,
        2.0 * BOX_HALF,
        2.0 * BOX_HALF,
    ));
    let grey = world
        .resource_mut::<Assets<StandardMaterial>>()
        .add(StandardMaterial {
            base_color: Color::linear_rgb(0.5, 0.5, 0.5),
            unlit: true,
            ..default()
        });
    let magenta = world
        .resource_mut::<Assets<StandardMaterial>>()
        .add(StandardMaterial {
            base_color: Color::linear_rgb(1.0, 0.0, 1.0),
            unlit: true,
            ..default()
        });
    world.spawn((Mesh3d(ground), MeshMaterial3d(grey)));
    world.spawn((
        Mesh3d(cube),
        MeshMaterial3d(magenta),
        Transform::from_translation(BOX_CENTRE),
    ));
    world.spawn((
        Camera3d::default(),
        RenderTarget::Image(image.into()),
        // No tone curve: the image is the linear radiance, sRGB-encoded.
        Tonemapping::None,
        StratusCamera {
            direct_share: 0.0,
            follow_exposure: false,
            // The air's haze on the ground would mix with its shadow; the library's test
            // holds the haze to the CPU's (crates/stratus/tests/aerial.rs).
            haze: false,
            ..default()
        },
        Transform::from_xyz(0.0, EYE, 0.0).looking_to(Vec3::NEG_Z, Vec3::Y),
    ));
    while app.plugins_state() == PluginsState::Adding {
        bevy::tasks::tick_global_task_pools_on_main_thread();
    }
    app.finish();
    app.cleanup();
    app
}

/// Renders a few frames, then reads the next one back: RGBA8 sRGB.
fn frame(app: &mut App, target: &Handle<Image>) -> Vec<u8> {
    for _ in 0..3 {
        app.update();
    }
    let captured: Arc<Mutex<Option<Image>>> = Arc::default();
    let slot = captured.clone();
    app.world_mut()
        .spawn(Screenshot::image(target.clone()))
        .observe(move |shot: On<ScreenshotCaptured>| {
            *slot.lock().unwrap() = Some(shot.image.clone());
        });
    for _ in 0..10 {
        app.update();
        if let Some(image) = captured.lock().unwrap().take() {
            let data = image.data.expect("pixels");
            assert_eq!(data.len(), (W * H * 4) as usize);
            return data;
        }
    }
    panic!("the frame was not read back within 10 frames");
}

fn srgb_to_linear(b: u8) -> f64 {
    let c = f64::from(b) / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// The unit view ray through pixel (x, y)'s centre (Bevy's default projection: 45 degrees
/// vertical), in the host's world for the level camera looking north.
fn ray(x: u32, y: u32) -> Vec3 {
    let tan = (std::f32::consts::FRAC_PI_4 / 2.0).tan();
    let aspect = W as f32 / H as f32;
    let nx = (x as f32 + 0.5) / W as f32 * 2.0 - 1.0;
    let ny = 1.0 - (y as f32 + 0.5) / H as f32 * 2.0;
    Vec3::new(nx * tan * aspect, ny * tan, -1.0).normalize()
}

/// The pixel rectangle the box's front face (z = centre + half, facing the camera) covers,
/// and the one all of the box's corners span.
fn box_rects() -> ([f32; 4], [f32; 4]) {
    let tan = (std::f32::consts::FRAC_PI_4 / 2.0).tan();
    let aspect = W as f32 / H as f32;
    let project = |p: Vec3| {
        let d = -p.z;
        let nx = p.x / d / (tan * aspect);
        let ny = (p.y - EYE) / d / tan;
        [(nx + 1.0) / 2.0 * W as f32, (1.0 - ny) / 2.0 * H as f32]
    };
    let rect = |points: Vec<[f32; 2]>| {
        let mut r = [f32::MAX, f32::MAX, f32::MIN, f32::MIN];
        for [x, y] in points {
            r = [r[0].min(x), r[1].min(y), r[2].max(x), r[3].max(y)];
        }
        r
    };
    let corners = |z: f32| {
        [-1.0, 1.0].into_iter().flat_map(move |sx| {
            [-1.0, 1.0].into_iter().map(move |sy| {
                Vec3::new(
                    BOX_CENTRE.x + sx * BOX_HALF,
                    BOX_CENTRE.y + sy * BOX_HALF,
                    z,
                )
            })
        })
    };
    let front = BOX_CENTRE.z + BOX_HALF;
    let back = BOX_CENTRE.z - BOX_HALF;
    (
        rect(corners(front).map(project).collect()),
        rect(corners(front).chain(corners(back)).map(project).collect()),
    )
}

#[test]
fn bevy_geometry_hides_the_clouds_and_takes_their_shadow() {
    record_wgpu_log();
    let mut target = None;
    let mut app = app(&mut target);
    let target = target.unwrap();
    let unshadowed = frame(&mut app, &target);
    for mut camera in app
        .world_mut()
        .query::<&mut StratusCamera>()
        .iter_mut(app.world_mut())
    {
        camera.direct_share = 1.0;
    }
    let shadowed = frame(&mut app, &target);

    // Occlusion, in both frames.
    let (front, all) = box_rects();
    for (image, even) in [(&unshadowed, true), (&shadowed, false)] {
        let mut inside = Vec::new();
        for y in 0..H {
            for x in 0..W {
                let (cx, cy) = (x as f32 + 0.5, y as f32 + 0.5);
                let i = ((y * W + x) * 4) as usize;
                let px = &image[i..i + 4];
                if cx > front[0] + 1.0
                    && cx < front[2] - 1.0
                    && cy > front[1] + 1.0
                    && cy < front[3] - 1.0
                {
                    inside.push(px.to_vec());
                } else if cx < all[0] - 1.0
                    || cx > all[2] + 1.0
                    || cy < all[1] - 1.0
                    || cy > all[3] + 1.0
                {
                    assert!(
                        !(px[1] == 0 && px[0] > 64 && px[0] == px[2]),
                        "pixel ({x}, {y}) outside the box is magenta: {px:?}"
                    );
                }
            }
        }
        assert!(inside.len() >= 20, "the box covers {} pixels", inside.len());
        for px in &inside {
            assert_eq!(px[1], 0, "cloud or sky light on the box: {px:?}");
            assert_eq!(px[0], px[2], "the box is not magenta: {px:?}");
            // Without the cloud shadow, one colour; with it, as the shadow falls on it.
            assert!(
                !even || px[0].abs_diff(inside[0][0]) <= 1,
                "the box is not even: {px:?} and {:?}",
                inside[0]
            );
        }
    }

    // Shadowing: the ground's pixels within 12 km, against the CPU's transmittance.
    let mut points = Vec::new();
    let mut ratios = Vec::new();
    for y in H / 2 + 1..H {
        for x in 0..W {
            let d = ray(x, y);
            let t = EYE / -d.y;
            let p = Vec3::new(0.0, EYE, 0.0) + d * t;
            if t > 12_000.0 {
                continue;
            }
            let i = ((y * W + x) * 4) as usize;
            let off = srgb_to_linear(unshadowed[i]);
            let on = srgb_to_linear(shadowed[i]);
            assert!(off > 0.3, "ground pixel ({x}, {y}) without shadow is {off}");
            ratios.push(on / off);
            points.push(stratus::world_from_host(p.as_dvec3()));
        }
    }
    let mut scene = scene();
    scene.camera.position =
        stratus::world_from_host(stratus::glam::DVec3::new(0.0, f64::from(EYE), 0.0));
    let noise = stratus::noise_for(&scene);
    let cpu = stratus_reference::sun_transmittance(&scene, &noise, &points, 64);
    let spread =
        cpu.iter().cloned().fold(f64::MIN, f64::max) - cpu.iter().cloned().fold(f64::MAX, f64::min);
    assert!(
        spread > 0.2,
        "the ground's shadow hardly varies ({spread}): nothing is tested"
    );
    if let Ok(dir) = std::env::var("STRATUS_BEVY_TEST_OUT") {
        for (name, img) in [("unshadowed", &unshadowed), ("shadowed", &shadowed)] {
            image::RgbaImage::from_raw(W, H, img.clone())
                .unwrap()
                .save(format!("{dir}/{name}.png"))
                .unwrap();
        }
        let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
        println!(
            "mean ratio {:.3}, mean CPU {:.3}",
            mean(&ratios),
            mean(&cpu)
        );
        for k in (0..cpu.len()).step_by(cpu.len() / 20) {
            println!("{:?}: ratio {:.3} cpu {:.3}", points[k], ratios[k], cpu[k]);
        }
    }
    let mean_error = ratios
        .iter()
        .zip(&cpu)
        .map(|(r, c)| (r - c).abs())
        .sum::<f64>()
        / cpu.len() as f64;
    println!(
        "{} ground pixels: transmittance {:.3}..{:.3}, mean |shadowed / unshadowed - CPU| {mean_error:.4}",
        cpu.len(),
        cpu.iter().cloned().fold(f64::MAX, f64::min),
        cpu.iter().cloned().fold(f64::MIN, f64::max),
    );
    // The map is 312 m a texel, read bilinearly; the image 8-bit.
    assert!(
        mean_error < 0.05,
        "the ground's shadow is {mean_error:.4} off the CPU's on average"
    );
    assert_no_wgpu_messages();
}
