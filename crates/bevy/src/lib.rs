//! Stratus clouds and sky for a Bevy 0.20 3D camera.
//!
//! Bevy 0.20 renders with wgpu 30, the version Stratus uses, so the plugin runs
//! [`stratus::Clouds`] on Bevy's own device: after Bevy's main pass it reads the camera's depth
//! where it is, writes the clouds' HDR output (with Stratus's sky where Bevy drew no geometry),
//! and blends it into the camera's HDR image before Bevy's tone mapping. Bevy's geometry in
//! front of a cloud hides it; geometry inside one is seen through the cloud in front of it;
//! the key light's cloud shadow dims the geometry's light.
//!
//! ```no_run
//! use bevy::prelude::*;
//! use stratus_bevy::{StratusCamera, StratusPlugin, StratusSun};
//!
//! App::new()
//!     .add_plugins((DefaultPlugins, StratusPlugin::default()))
//!     .add_systems(Startup, |mut commands: Commands| {
//!         commands.spawn((Camera3d::default(), StratusCamera::default()));
//!         commands.spawn((DirectionalLight::default(), StratusSun::from_scene()));
//!     })
//!     .run();
//! ```
//!
//! # Conventions
//!
//! Bevy's world is Stratus's host world ([`stratus::HostCamera`]): y up, metres, the ground at
//! y = 0, -z north. The camera's [`StratusCamera`] makes it an HDR camera without MSAA whose
//! depth texture can be sampled (the clouds read it). Stratus's radiance is in its own relative
//! units (a noon sun of about 10); [`StratusCamera::lux_per_unit`] scales it into Bevy's
//! photometric units, and the sun light and the camera's exposure follow the scene when asked.
//!
//! # Cloud shadows
//!
//! The shadow reaches Bevy's geometry in screen space: the composite finds each pixel's
//! world position from the depth, reads the key light's transmittance through the clouds there
//! (`stratus_cloud_shadow`, `wgsl/host/cloud_shadow.wgsl`) and dims the share of the pixel's
//! light that the key light gives ([`StratusCamera::direct_share`]). It is one frame late (the
//! map is computed with the clouds, after Bevy's main pass).

use std::sync::Arc;

use bevy::core_pipeline::{Core3d, Core3dSystems};
use bevy::ecs::schedule::IntoScheduleConfigs;
use bevy::light::DirectionalLight;
use bevy::prelude::*;
use bevy::render::camera::ExtractedCamera;
use bevy::render::renderer::{RenderContext, RenderDevice, RenderQueue, ViewQuery};
use bevy::render::sync_world::RenderEntity;
use bevy::render::view::{ExtractedView, ViewDepthStencilTexture, ViewTarget};
use bevy::render::{Extract, ExtractSchedule, RenderApp};
use bevy::transform::TransformSystems;
use stratus::glam::{DMat4, DVec3};
use stratus::{Clouds, HostCamera, Scene, Update, host_from_world, world_from_host};

mod composite;

use composite::Composite;

/// Adds Stratus's clouds and sky to every camera with a [`StratusCamera`], and keeps the
/// [`StratusSun`] light and the scene's sun in step.
pub struct StratusPlugin {
    /// The scene the clouds start from (weather, lighting, quality); [`StratusScene`] holds
    /// it afterwards. Its camera is replaced by Bevy's each frame.
    pub scene: Scene,
}

impl Default for StratusPlugin {
    /// The default preset (`cumulus-noon`) under the physical sky.
    fn default() -> Self {
        let mut scene = Scene::default();
        scene.atmosphere.sky = stratus_scene::SkyModel::Physical;
        Self { scene }
    }
}

/// The scene the clouds render (main world): change it to change the weather, the lighting
/// or the quality. Its camera is Bevy's; its sun is the [`StratusSun`] light's unless that
/// light follows the scene.
#[derive(Resource, Clone, Debug)]
pub struct StratusScene(pub Scene);

/// Puts Stratus's clouds and sky into a 3D camera's image. The plugin makes the camera an HDR
/// camera ([`bevy::camera::Hdr`]) without MSAA whose depth texture can be sampled, whatever
/// it was spawned with: the clouds read its depth and blend into its linear image.
#[derive(Component, Clone, Copy, Debug)]
#[require(Camera3d)]
pub struct StratusCamera {
    /// Draw Stratus's sky where the camera sees no geometry (off: Bevy's clear colour or
    /// skybox stays, with the clouds over it).
    pub sky: bool,
    /// The share of the geometry's light that the key light gives, which the clouds' shadow
    /// dims (0 turns cloud shadows off; 1 for a scene lit by the sun alone).
    pub direct_share: f32,
    /// Bevy's photometric units (lux) per unit of Stratus's relative radiance: a noon sun of
    /// 10 units is 100 000 lux with the default 10 000.
    pub lux_per_unit: f32,
    /// Set the camera's [`bevy::camera::Exposure`] to the scene's (its automatic exposure), so
    /// Bevy's geometry and Stratus's sky are exposed alike.
    pub follow_exposure: bool,
    /// Give Bevy's geometry the air's aerial perspective (the haze between it and the camera;
    /// under the physical sky only), as Stratus's clouds have it.
    pub haze: bool,
}

impl Default for StratusCamera {
    fn default() -> Self {
        Self {
            sky: true,
            direct_share: 0.85,
            lux_per_unit: 10_000.0,
            follow_exposure: true,
            haze: true,
        }
    }
}

/// Makes every [`StratusCamera`] one the clouds can draw into: HDR, no MSAA (the clouds read
/// one depth sample a pixel), a depth texture they can sample.
fn configure_cameras(
    mut commands: Commands,
    mut cameras: Query<
        (Entity, &mut Camera3d, &mut Msaa, Has<bevy::camera::Hdr>),
        With<StratusCamera>,
    >,
) {
    use bevy::render::render_resource::TextureUsages;
    for (entity, mut camera, mut msaa, hdr) in &mut cameras {
        let usages = TextureUsages::from(camera.depth_texture_usages);
        if !usages.contains(TextureUsages::TEXTURE_BINDING) {
            camera.depth_texture_usages = (usages | TextureUsages::TEXTURE_BINDING).into();
        }
        if *msaa != Msaa::Off {
            *msaa = Msaa::Off;
        }
        if !hdr {
            commands.entity(entity).insert(bevy::camera::Hdr);
        }
    }
}

/// Marks the [`DirectionalLight`] that is Stratus's sun.
#[derive(Component, Clone, Copy, Debug, Default)]
pub struct StratusSun {
    /// The light follows the scene's sun (its `[sun]` direction, or the real sun of its
    /// `[sky]` date and place) and its illuminance; otherwise the scene's sun follows the
    /// light's direction.
    pub from_scene: bool,
}

impl StratusSun {
    /// A light that follows the scene's sun.
    pub fn from_scene() -> Self {
        Self { from_scene: true }
    }

    /// A light whose direction the scene's sun follows.
    pub fn from_light() -> Self {
        Self { from_scene: false }
    }
}

impl Plugin for StratusPlugin {
    fn build(&self, app: &mut App) {
        app.insert_resource(StratusScene(self.scene.clone()))
            .add_systems(
                PostUpdate,
                (configure_cameras, sync_sun, follow_exposure)
                    .chain()
                    .after(TransformSystems::Propagate),
            );
    }

    /// The render world's part, once every plugin is built (so the plugin can be added before
    /// or after Bevy's `DefaultPlugins`).
    fn finish(&self, app: &mut App) {
        let Some(render_app) = app.get_sub_app_mut(RenderApp) else {
            warn!("stratus: no render app (is Bevy's RenderPlugin added?): no clouds");
            return;
        };
        render_app
            .init_resource::<CloudState>()
            .add_systems(ExtractSchedule, extract)
            .add_systems(
                Core3d,
                render_clouds
                    .after(Core3dSystems::MainPass)
                    .before(Core3dSystems::PostProcess),
            );
    }
}

/// The scene's key light in Bevy's axes: unit direction toward it and its illuminance (lux).
fn key_light(scene: &Scene, lux_per_unit: f32) -> (Vec3, Color, f32) {
    let (dir, rgb, _) = scene.key_light();
    let luminance = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
    let max = rgb[0].max(rgb[1]).max(rgb[2]).max(1e-12);
    let color = Color::linear_rgb(
        (rgb[0] / max) as f32,
        (rgb[1] / max) as f32,
        (rgb[2] / max) as f32,
    );
    (
        host_from_world(dir).as_vec3(),
        color,
        luminance as f32 * lux_per_unit,
    )
}

/// Keeps the [`StratusSun`] light and the scene's sun in step.
fn sync_sun(
    mut scene: ResMut<StratusScene>,
    cameras: Query<&StratusCamera>,
    mut lights: Query<(
        &StratusSun,
        &mut DirectionalLight,
        &mut Transform,
        &GlobalTransform,
    )>,
) {
    let lux_per_unit = cameras
        .iter()
        .next()
        .map_or(StratusCamera::default().lux_per_unit, |c| c.lux_per_unit);
    for (sun, mut light, mut transform, global) in &mut lights {
        if sun.from_scene {
            let (toward, color, lux) = key_light(&scene.0, lux_per_unit);
            let wanted = Transform::from_translation(transform.translation).looking_to(
                -toward,
                if toward.y.abs() > 0.999 {
                    Vec3::Z
                } else {
                    Vec3::Y
                },
            );
            if transform.rotation.angle_between(wanted.rotation) > 1e-5 {
                transform.rotation = wanted.rotation;
            }
            if light.illuminance != lux || light.color != color {
                light.illuminance = lux;
                light.color = color;
            }
        } else {
            let toward = world_from_host(DVec3::from(global.back().as_vec3()));
            let current = scene.0.sun.direction;
            if current != Some(toward) || !scene.0.sky.is_unset() {
                let s = &mut scene.0;
                s.sun.direction = Some(toward);
                // The light's direction replaces the date and place's sun.
                s.sky = Default::default();
            }
        }
    }
}

/// Sets each [`StratusCamera`]'s exposure to the scene's.
fn follow_exposure(
    scene: Res<StratusScene>,
    mut cameras: Query<(&StratusCamera, &mut bevy::camera::Exposure)>,
) {
    for (camera, mut exposure) in &mut cameras {
        if !camera.follow_exposure {
            continue;
        }
        // Bevy's exposure is 2^-ev100 / 1.2; Stratus's multiplies its radiance, which Bevy
        // sees scaled by lux_per_unit.
        let e = scene.0.auto_exposure() / f64::from(camera.lux_per_unit);
        let ev100 = (-(1.2 * e).log2()) as f32;
        if (exposure.ev100 - ev100).abs() > 1e-4 {
            exposure.ev100 = ev100;
        }
    }
}

/// The scene and the time step of this frame, in the render world.
#[derive(Resource, Clone)]
struct ExtractedScene {
    scene: Arc<Scene>,
    /// Seconds since the last frame (the wind moves the clouds).
    dt: f64,
}

/// A [`StratusCamera`] in the render world.
#[derive(Component, Clone, Copy)]
struct ExtractedStratusCamera(StratusCamera);

fn extract(
    mut commands: Commands,
    scene: Extract<Res<StratusScene>>,
    time: Extract<Res<Time>>,
    cameras: Extract<Query<(RenderEntity, &StratusCamera)>>,
    mut last: Local<Option<Arc<Scene>>>,
) {
    // The same Arc while the scene is unchanged, so the render world knows when it changed.
    let scene = match &*last {
        Some(s) if **s == scene.0 => s.clone(),
        _ => Arc::new(scene.0.clone()),
    };
    *last = Some(scene.clone());
    commands.insert_resource(ExtractedScene {
        scene,
        dt: time.delta_secs_f64(),
    });
    for (entity, camera) in &cameras {
        commands
            .entity(entity)
            .insert(ExtractedStratusCamera(*camera));
    }
}

/// The clouds on Bevy's device (render world), made on the first frame.
#[derive(Resource, Default)]
struct CloudState {
    clouds: Option<Clouds>,
    /// The scene the clouds were last given.
    scene: Option<Arc<Scene>>,
    /// Set once the clouds failed (logged once; the camera's image stays Bevy's).
    failed: bool,
    /// The HDR output, the target's size.
    hdr: Option<(wgpu::Texture, wgpu::TextureView)>,
    composite: Option<Composite>,
}

/// Records the clouds and their composite into the camera's HDR image.
fn render_clouds(
    view: ViewQuery<(
        &ExtractedCamera,
        &ExtractedView,
        &ViewTarget,
        &ViewDepthStencilTexture,
        &ExtractedStratusCamera,
    )>,
    scene: Option<Res<ExtractedScene>>,
    mut state: ResMut<CloudState>,
    device: Res<RenderDevice>,
    queue: Res<RenderQueue>,
    mut ctx: RenderContext,
) {
    let Some(scene) = scene else { return };
    if state.failed {
        return;
    }
    let (bevy_camera, extracted, target, depth, camera) = view.into_inner();
    if let Err(e) = record(
        &mut state,
        &scene,
        extracted,
        bevy_camera.exposure,
        target,
        depth,
        camera.0,
        device.wgpu_device(),
        &queue,
        ctx.command_encoder(),
    ) {
        error!("stratus: the clouds are off for this run: {e}");
        state.failed = true;
    }
}

#[allow(
    clippy::too_many_arguments,
    reason = "one frame's inputs, from one system"
)]
fn record(
    state: &mut CloudState,
    frame: &ExtractedScene,
    view: &ExtractedView,
    exposure: f32,
    target: &ViewTarget,
    depth: &ViewDepthStencilTexture,
    camera: StratusCamera,
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    encoder: &mut wgpu::CommandEncoder,
) -> Result<(), stratus::Error> {
    let world_from_view = view.world_from_view.to_matrix().as_dmat4();
    let host = HostCamera {
        view: world_from_view.inverse(),
        projection: view.clip_from_view.as_dmat4(),
    };
    let projection = host.projection()?;
    let new_scene = !state
        .scene
        .as_ref()
        .is_some_and(|s| Arc::ptr_eq(s, &frame.scene));
    if state.clouds.is_none() {
        info!("stratus: generating the scene's noise (once per seed)");
        state.clouds = Some(Clouds::new(device, queue, (*frame.scene).clone())?);
    }
    let clouds = state.clouds.as_mut().expect("made above");
    clouds.update(Update {
        scene: new_scene.then(|| (*frame.scene).clone()),
        camera: Some(host),
        time_s: Some(frame.dt),
        ..Default::default()
    })?;
    state.scene = Some(frame.scene.clone());
    let depth_view: &wgpu::TextureView = &depth.attachment.texture.default_view;
    clouds.set_depth_texture(Some((depth_view, projection)))?;
    clouds.set_hdr_sky(camera.sky);
    clouds.set_cloud_shadow(camera.direct_share > 0.0);
    let main: &wgpu::TextureView = target.main_texture_view();
    let size = [main.texture().width(), main.texture().height()];
    if state
        .hdr
        .as_ref()
        .is_none_or(|(t, _)| [t.width(), t.height()] != size)
    {
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("stratus hdr output"),
            size: wgpu::Extent3d {
                width: size[0],
                height: size[1],
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba16Float,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        });
        let view = texture.create_view(&Default::default());
        state.hdr = Some((texture, view));
    }
    let (_, hdr) = state.hdr.as_ref().expect("made above");
    clouds.render_hdr(encoder, hdr)?;
    let format = main.texture().format();
    if state
        .composite
        .as_ref()
        .is_none_or(|c| c.format() != format)
    {
        state.composite = Some(Composite::new(device, format));
    }
    let composite = state.composite.as_mut().expect("made above");
    let clouds = state.clouds.as_ref().expect("made above");
    let shadow = clouds.cloud_shadow();
    let aerial = if camera.haze {
        clouds.aerial_perspective()
    } else {
        None
    };
    // World-from-clip with the camera at the origin: the view's rotation only.
    let mut rotation = world_from_view;
    rotation.w_axis = stratus::glam::DVec4::W;
    let world_from_clip = rotation * host.projection.inverse();
    let position: DVec3 = world_from_view.w_axis.truncate();
    composite.draw(
        device,
        queue,
        encoder,
        composite::Frame {
            target: main,
            clouds: hdr,
            depth: depth_view,
            shadow: shadow.as_ref().map(|s| (s.view, s.transform.uniform())),
            aerial: aerial.as_ref().map(|a| (a.view, a.uniform)),
            world_from_clip: DMat4::as_mat4(&world_from_clip),
            camera: position.as_vec3(),
            clear_depth: projection.clear_depth() as f32,
            size,
            // Bevy exposes its lights in its PBR shaders; the clouds get the same here.
            scale: camera.lux_per_unit * exposure,
            direct: camera.direct_share,
        },
    );
    Ok(())
}
