//! A flight over a terrain under Stratus's clouds in Bevy: a few towers, a small plane that
//! flies into a cloud, and a camera you fly.
//!
//! ```text
//! cargo run --release -p stratus-bevy --example flight                 # a window
//! cargo run --release -p stratus-bevy --example flight -- --headless --frames 60 --out flight.png
//! ```
//!
//! In the window: W/S forward and back, A/D sideways, Q/E down and up, the arrow keys turn,
//! Shift goes ten times faster. `--headless` renders `--frames` frames into an image of
//! `--size` (no window) from a camera that watches the plane, writes the last one to `--out`
//! and prints the median wall time a frame took (Bevy's main and render work and the GPU's).

use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use bevy::app::PluginsState;
use bevy::asset::RenderAssetUsages;
use bevy::camera::RenderTarget;
use bevy::core_pipeline::tonemapping::Tonemapping;
use bevy::image::Image;
use bevy::mesh::{Indices, PrimitiveTopology};
use bevy::prelude::*;
use bevy::render::RenderPlugin;
use bevy::render::render_resource::{Extent3d, TextureDimension, TextureFormat, TextureUsages};
use bevy::render::settings::{InstanceFlags, RenderCreation, WgpuSettings};
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured};
use bevy::time::TimeUpdateStrategy;
use bevy::window::ExitCondition;
use bevy::winit::WinitPlugin;
use stratus::Scene;
use stratus_bevy::{StratusCamera, StratusPlugin, StratusSun};

const HELP: &str = "\
flight: Stratus's clouds over a terrain in Bevy, with a plane that flies into a cloud.

USAGE: flight [--headless] [--frames N] [--out PNG] [--size WxH] [--preset NAME]

  --headless      no window: render --frames frames into an image and write the last one
  --frames N      frames to render headless (default 60)
  --out PNG       where the headless image goes (default flight.png)
  --size WxH      the headless image's size (default 320x180)
  --preset NAME   the scene preset (default cumulus-noon, under the physical sky)

In the window: W/S/A/D/Q/E fly, the arrow keys turn, Shift is ten times faster.";

struct Args {
    headless: bool,
    frames: u32,
    out: PathBuf,
    size: [u32; 2],
    preset: String,
}

fn parse_args() -> Result<Args, String> {
    let mut args = Args {
        headless: false,
        frames: 60,
        out: "flight.png".into(),
        size: [320, 180],
        preset: "cumulus-noon".into(),
    };
    let mut it = std::env::args().skip(1);
    while let Some(a) = it.next() {
        let mut value = |name: &str| it.next().ok_or(format!("{name} needs a value"));
        match a.as_str() {
            "--headless" => args.headless = true,
            "--frames" => {
                let v = value("--frames")?;
                args.frames = v
                    .parse()
                    .ok()
                    .filter(|&n| n > 0)
                    .ok_or(format!("--frames: `{v}` is not a whole number above 0"))?;
            }
            "--out" => args.out = value("--out")?.into(),
            "--size" => {
                let v = value("--size")?;
                let parsed = v
                    .split_once('x')
                    .and_then(|(w, h)| Some([w.parse::<u32>().ok()?, h.parse::<u32>().ok()?]));
                args.size = parsed
                    .filter(|s| (16..=8192).contains(&s[0]) && (16..=8192).contains(&s[1]))
                    .ok_or(format!(
                        "--size: `{v}` is not WIDTHxHEIGHT with each within 16..8192"
                    ))?;
            }
            "--preset" => args.preset = value("--preset")?,
            "-h" | "--help" => {
                println!("{HELP}");
                std::process::exit(0);
            }
            other => return Err(format!("unknown argument `{other}` (see --help)")),
        }
    }
    Ok(args)
}

fn main() {
    let args = match parse_args() {
        Ok(a) => a,
        Err(e) => {
            eprintln!("flight: {e}");
            std::process::exit(2);
        }
    };
    let mut scene = match Scene::preset(&args.preset) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("flight: --preset: {e}");
            std::process::exit(2);
        }
    };
    scene.atmosphere.sky = stratus_scene::SkyModel::Physical;
    let course = Course::through_a_cloud(&scene);
    let mut app = App::new();
    app.insert_resource(course)
        .insert_resource(ClearColor(Color::BLACK))
        .add_plugins(StratusPlugin { scene })
        .add_systems(Startup, setup_world)
        .add_systems(Update, fly_plane);
    if args.headless {
        std::process::exit(match headless(app, &args) {
            Ok(()) => 0,
            Err(e) => {
                eprintln!("flight: {e}");
                1
            }
        });
    }
    app.add_plugins(
        DefaultPlugins
            .set(WindowPlugin {
                primary_window: Some(Window {
                    title: "Stratus over Bevy: flight".into(),
                    ..default()
                }),
                ..default()
            })
            .set(render_plugin(false)),
    )
    .add_systems(Startup, spawn_window_camera)
    .add_systems(Update, fly_camera)
    .run();
}

/// Bevy's renderer: in debug builds with wgpu's validation but without shader debug info (naga
/// marks such SPIR-V as WGSL, source language 10, which older Vulkan validation layers reject
/// with a message per shader).
fn render_plugin(synchronous_pipeline_compilation: bool) -> RenderPlugin {
    RenderPlugin {
        synchronous_pipeline_compilation,
        render_creation: RenderCreation::Automatic(Box::new(WgpuSettings {
            instance_flags: if cfg!(debug_assertions) {
                InstanceFlags::VALIDATION
            } else {
                InstanceFlags::empty()
            },
            ..default()
        })),
        ..default()
    }
}

/// Renders `args.frames` frames into an image and writes the last.
fn headless(mut app: App, args: &Args) -> Result<(), String> {
    app.add_plugins(
        DefaultPlugins
            .set(WindowPlugin {
                primary_window: None,
                exit_condition: ExitCondition::DontExit,
                ..default()
            })
            // Every pipeline ready the frame it is first used: the image does not depend on how
            // fast shaders compile.
            .set(render_plugin(true))
            .disable::<WinitPlugin>(),
    )
    // A fixed time step: the same frames every run.
    .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f64(
        1.0 / 30.0,
    )));
    let size = args.size;
    let target = {
        let mut images = app.world_mut().resource_mut::<Assets<Image>>();
        let mut image = Image::new_fill(
            Extent3d {
                width: size[0],
                height: size[1],
                depth_or_array_layers: 1,
            },
            TextureDimension::D2,
            &[0, 0, 0, 255],
            TextureFormat::Rgba8UnormSrgb,
            RenderAssetUsages::default(),
        );
        image.texture_descriptor.usage |=
            TextureUsages::RENDER_ATTACHMENT | TextureUsages::COPY_SRC;
        images.add(image)
    };
    let course = app.world().resource::<Course>().clone();
    app.world_mut().spawn((
        Camera3d::default(),
        RenderTarget::Image(target.clone().into()),
        Tonemapping::AcesFitted,
        StratusCamera::default(),
        course.watcher(),
    ));
    while app.plugins_state() == PluginsState::Adding {
        bevy::tasks::tick_global_task_pools_on_main_thread();
    }
    app.finish();
    app.cleanup();
    let mut times = Vec::new();
    let started = Instant::now();
    for frame in 0..args.frames {
        let t = Instant::now();
        app.update();
        times.push(t.elapsed());
        if frame % 10 == 9 || frame + 1 == args.frames {
            eprintln!(
                "flight: frame {}/{} ({:.1} s)",
                frame + 1,
                args.frames,
                started.elapsed().as_secs_f64()
            );
        }
    }
    // The screenshot is read back a frame or two later.
    let captured: Arc<Mutex<Option<Image>>> = Arc::default();
    let slot = captured.clone();
    app.world_mut().spawn(Screenshot::image(target)).observe(
        move |shot: On<ScreenshotCaptured>| {
            *slot.lock().expect("screenshot slot") = Some(shot.image.clone());
        },
    );
    for _ in 0..10 {
        app.update();
        if captured.lock().expect("screenshot slot").is_some() {
            break;
        }
    }
    let image = captured
        .lock()
        .expect("screenshot slot")
        .take()
        .ok_or("the last frame's image was not read back within 10 frames")?;
    let rgba = image.data.ok_or("the read-back image holds no data")?;
    let [w, h] = size;
    let png = image::RgbaImage::from_raw(w, h, rgba)
        .ok_or("the read-back image is not the target's size")?;
    let distinct = png
        .pixels()
        .map(|p| p.0)
        .collect::<std::collections::HashSet<_>>()
        .len();
    png.save(&args.out)
        .map_err(|e| format!("writing {}: {e}", args.out.display()))?;
    times.sort();
    let median = times[times.len() / 2];
    println!(
        "flight: wrote {} ({w}x{h}, {distinct} distinct colours); median frame {:.1} ms over {} frames (Bevy's CPU work, Stratus's recording and the GPU's, on {})",
        args.out.display(),
        median.as_secs_f64() * 1e3,
        args.frames,
        adapter_name(&app),
    );
    if distinct < 16 {
        return Err(format!(
            "the image is flat ({distinct} distinct colours): nothing was drawn"
        ));
    }
    Ok(())
}

fn adapter_name(app: &App) -> String {
    app.world()
        .get_resource::<bevy::render::renderer::RenderAdapterInfo>()
        .map_or_else(|| "an unknown adapter".into(), |i| i.name.clone())
}

/// Where the plane flies: climbing into the densest cloud near the origin through its base.
#[derive(Resource, Clone)]
struct Course {
    /// The cloud's centre (Bevy's world).
    cloud: Vec3,
    /// The plane's start and its velocity (m/s).
    start: Vec3,
    velocity: Vec3,
}

impl Course {
    /// Samples the scene's density on a grid a little above the cloud base around the origin
    /// and picks the densest cell, 1 to 4 km out.
    fn through_a_cloud(scene: &Scene) -> Self {
        let noise = stratus::noise_for(scene);
        let alt = scene.atmosphere.cloud_bottom_m + 150.0;
        let n = 48;
        let half = 4000.0;
        let grid = stratus_reference::sample_density_grid(
            scene,
            &noise,
            [-half, alt - 10.0, -half],
            [half, alt + 10.0, half],
            [n, 1, n],
        );
        let mut best = (f32::MIN, [0.0, alt, -2000.0]);
        for z in 0..n {
            for x in 0..n {
                let c = grid.cell_center([x, 0, z]);
                let r = (c[0] * c[0] + c[2] * c[2]).sqrt();
                let d = grid.data[z * n + x];
                if (1000.0..4000.0).contains(&r) && d > best.0 {
                    best = (d, c);
                }
            }
        }
        let cloud = stratus::host_from_world(best.1).as_vec3();
        // Climbing east: two seconds before it is in the cloud, the plane is 90 m below it.
        let velocity = Vec3::new(110.0, 45.0, 0.0);
        Self {
            cloud,
            start: cloud - velocity * 2.0,
            velocity,
        }
    }

    /// A camera under the cloud base, 700 m south of where the plane goes in, looking up at
    /// it: the plane against the cloud's base, the sky beside it.
    fn watcher(&self) -> Transform {
        let at = self.cloud - self.velocity * 0.4;
        Transform::from_translation(self.cloud + Vec3::new(-250.0, -450.0, 700.0))
            .looking_at(at, Vec3::Y)
    }
}

#[derive(Component)]
struct Plane;

/// The terrain, the towers, the plane and the sun.
fn setup_world(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    course: Res<Course>,
) {
    commands.spawn((
        DirectionalLight {
            shadow_maps_enabled: false,
            ..default()
        },
        StratusSun::from_scene(),
    ));
    commands.spawn((
        Mesh3d(meshes.add(terrain(24_000.0, 96))),
        MeshMaterial3d(materials.add(StandardMaterial {
            base_color: Color::srgb(0.25, 0.33, 0.18),
            perceptual_roughness: 0.95,
            ..default()
        })),
    ));
    let concrete = materials.add(StandardMaterial {
        base_color: Color::srgb(0.6, 0.6, 0.62),
        perceptual_roughness: 0.8,
        ..default()
    });
    for (i, (x, z, h)) in [
        (300.0, -900.0, 180.0),
        (-500.0, -1400.0, 260.0),
        (900.0, -2200.0, 320.0),
    ]
    .into_iter()
    .enumerate()
    {
        commands.spawn((
            Mesh3d(meshes.add(Cuboid::new(60.0 + 20.0 * i as f32, h, 60.0))),
            MeshMaterial3d(concrete.clone()),
            Transform::from_xyz(x, height_at(x, z) + h / 2.0, z),
        ));
    }
    let paint = materials.add(StandardMaterial {
        base_color: Color::srgb(0.8, 0.1, 0.1),
        metallic: 0.3,
        perceptual_roughness: 0.4,
        ..default()
    });
    commands
        .spawn((
            Plane,
            Transform::from_translation(course.start).looking_to(course.velocity, Vec3::Y),
            Visibility::default(),
        ))
        .with_children(|plane| {
            // Fuselage along -z (forward), wings and a tail: 24 m long, 30 m wide.
            for (size, at) in [
                (Vec3::new(3.0, 3.0, 24.0), Vec3::ZERO),
                (Vec3::new(30.0, 0.6, 4.0), Vec3::new(0.0, 0.0, -1.0)),
                (Vec3::new(10.0, 0.5, 2.5), Vec3::new(0.0, 0.5, 10.5)),
                (Vec3::new(0.5, 5.0, 3.0), Vec3::new(0.0, 3.0, 10.5)),
            ] {
                plane.spawn((
                    Mesh3d(meshes.add(Cuboid::from_size(size))),
                    MeshMaterial3d(paint.clone()),
                    Transform::from_translation(at),
                ));
            }
        });
}

/// Rolling hills (m) at host-world (x, z).
fn height_at(x: f32, z: f32) -> f32 {
    let (x, z) = (x / 1000.0, z / 1000.0);
    40.0 * (x * 0.9).sin() * (z * 0.7).cos() + 25.0 * (x * 2.3 + z * 1.7).sin() + 40.0
}

/// A square heightfield `side` metres wide, `cells` cells a side, centred on the origin.
fn terrain(side: f32, cells: u32) -> Mesh {
    let n = cells + 1;
    let step = side / cells as f32;
    let mut positions = Vec::with_capacity((n * n) as usize);
    let mut normals = Vec::with_capacity((n * n) as usize);
    for j in 0..n {
        for i in 0..n {
            let x = -side / 2.0 + i as f32 * step;
            let z = -side / 2.0 + j as f32 * step;
            positions.push([x, height_at(x, z), z]);
            let e = 1.0;
            let dx = (height_at(x + e, z) - height_at(x - e, z)) / (2.0 * e);
            let dz = (height_at(x, z + e) - height_at(x, z - e)) / (2.0 * e);
            normals.push(Vec3::new(-dx, 1.0, -dz).normalize().to_array());
        }
    }
    let mut indices = Vec::with_capacity((cells * cells * 6) as usize);
    for j in 0..cells {
        for i in 0..cells {
            let a = j * n + i;
            let (b, c, d) = (a + 1, a + n, a + n + 1);
            indices.extend_from_slice(&[a, c, b, b, c, d]);
        }
    }
    Mesh::new(
        PrimitiveTopology::TriangleList,
        RenderAssetUsages::default(),
    )
    .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, positions)
    .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, normals)
    .with_inserted_indices(Indices::U32(indices))
}

/// Flies the plane along its course.
fn fly_plane(time: Res<Time>, course: Res<Course>, mut planes: Query<&mut Transform, With<Plane>>) {
    for mut t in &mut planes {
        t.translation = course.start + course.velocity * time.elapsed_secs();
    }
}

/// The window's camera: where the headless one is, flown by the keys.
fn spawn_window_camera(mut commands: Commands, course: Res<Course>) {
    commands.spawn((
        Camera3d::default(),
        Tonemapping::AcesFitted,
        StratusCamera::default(),
        course.watcher(),
    ));
}

/// W/S/A/D/Q/E move, the arrows turn, Shift is ten times faster.
fn fly_camera(
    keys: Res<ButtonInput<KeyCode>>,
    time: Res<Time>,
    mut cameras: Query<&mut Transform, With<StratusCamera>>,
) {
    let dt = time.delta_secs();
    let speed = if keys.pressed(KeyCode::ShiftLeft) {
        1000.0
    } else {
        100.0
    };
    for mut t in &mut cameras {
        let mut go = Vec3::ZERO;
        for (key, dir) in [
            (KeyCode::KeyW, t.forward().as_vec3()),
            (KeyCode::KeyS, t.back().as_vec3()),
            (KeyCode::KeyA, t.left().as_vec3()),
            (KeyCode::KeyD, t.right().as_vec3()),
            (KeyCode::KeyQ, Vec3::NEG_Y),
            (KeyCode::KeyE, Vec3::Y),
        ] {
            if keys.pressed(key) {
                go += dir;
            }
        }
        t.translation += go * speed * dt;
        let turn = 0.8 * dt;
        if keys.pressed(KeyCode::ArrowLeft) {
            t.rotate_y(turn);
        }
        if keys.pressed(KeyCode::ArrowRight) {
            t.rotate_y(-turn);
        }
        if keys.pressed(KeyCode::ArrowUp) {
            t.rotate_local_x(turn);
        }
        if keys.pressed(KeyCode::ArrowDown) {
            t.rotate_local_x(-turn);
        }
    }
}
