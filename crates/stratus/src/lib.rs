//! Stratus for a wgpu application: physically based volumetric clouds, rendered on the
//! application's own `wgpu::Device` into a texture the application owns.
//!
//! ```no_run
//! # fn frame(device: &wgpu::Device, queue: &wgpu::Queue, view: &wgpu::TextureView) -> Result<(), stratus::Error> {
//! let scene = stratus::Scene::preset("cumulus-noon")?;
//! let mut clouds = stratus::Clouds::new(device, queue, scene)?;
//! // Every frame:
//! clouds.update(stratus::Update { time_s: Some(1.0 / 60.0), ..Default::default() })?;
//! let mut encoder = device.create_command_encoder(&Default::default());
//! clouds.render(&mut encoder, view)?;
//! queue.submit([encoder.finish()]);
//! # Ok(()) }
//! ```
//!
//! [`Clouds`] is persistent: its first frame creates pipelines, textures and bind groups and
//! uploads the noise; later frames write one uniform block and record the passes of the frame
//! graph. The clouds reach the application's texture through the graph's raster present pass,
//! so any renderable UNORM colour format works (sRGB views are refused: the image is already
//! gamma-encoded). Pass times come from GPU timestamps where the device has
//! `TIMESTAMP_QUERY` ([`Clouds::pass_timings`]).

#![deny(missing_docs)]

mod aerial;
mod camera;
mod shadow;

use std::sync::Arc;

pub use aerial::{AERIAL_SIDE, AERIAL_SLICE_M, AERIAL_SLICES, AerialPerspective};
pub use camera::{HostCamera, Projection, host_from_world, world_from_host};
/// The glam Stratus's [`HostCamera`] takes (the version Bevy 0.20 uses).
pub use glam;
pub use shadow::{
    CloudShadow, SHADOW_FADE_START, SHADOW_HALF_EXTENT, SHADOW_SIZE, ShadowTransform,
};

use stratus_backend_wgpu::Renderer;
use stratus_graph::FrameInput;
pub use stratus_graph::{FramePlan, PassTiming, PlanError, Program, Readback, SceneDepth};
use stratus_noise::{NoiseConfig, NoiseSet, ShapeSize};
pub use stratus_scene::Scene;
use stratus_scene::ShapeTexture;

/// What can go wrong, each with a sentence an application developer can act on.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The scene is invalid (names the field and why).
    #[error("{0}")]
    Scene(String),
    /// No frame plan for the scene (size out of range, or no shader variant has a feature).
    #[error(transparent)]
    Plan(#[from] PlanError),
    /// The renderer failed (wgpu validation, shaders).
    #[error(transparent)]
    Render(#[from] stratus_backend_wgpu::Error),
    /// The target texture cannot take the clouds.
    #[error("the target texture {0}")]
    Target(String),
    /// The host's camera cannot be used (names the matrix and why).
    #[error("the camera's {0}")]
    Camera(String),
    /// The host's scene depth cannot be used (names what and where).
    #[error("{0}")]
    Depth(String),
}

impl From<stratus_scene::SceneError> for Error {
    fn from(e: stratus_scene::SceneError) -> Self {
        Self::Scene(e.to_string())
    }
}

/// A per-frame change: whatever is `Some` replaces the current value. An update that keeps
/// the scene (no `scene`) starts the next frame: the frame index advances, so temporal
/// upsampling marches the next pixel of each block and the jitter takes its next seed (without
/// it, 1/16 upsampling marched the same pixel of each block every frame).
#[derive(Clone, Debug, Default)]
pub struct Update {
    /// A whole new scene (weather, lighting, quality...).
    pub scene: Option<Scene>,
    /// Camera position `[x (east), altitude, z (north)]` in metres.
    pub camera_position: Option<[f64; 3]>,
    /// Camera heading in degrees (0 north, 90 east) and elevation in degrees (clears a
    /// host camera's orientation).
    pub camera_yaw_pitch_deg: Option<[f64; 2]>,
    /// The host engine's camera: view and projection matrices (see [`HostCamera`] for the
    /// conventions). It sets the position, orientation and field of view; the projection's
    /// aspect must match the target's. Not together with `camera_position` or
    /// `camera_yaw_pitch_deg`.
    pub camera: Option<HostCamera>,
    /// Seconds to advance the clouds' time (the wind moves them).
    pub time_s: Option<f64>,
}

/// The frame plan and the noise textures a scene is rendered with, kept across frames and
/// remade only when they go stale: the plan when the scene's plan key changes (its shader
/// features, plan options such as temporal upsampling, method and sky, or its size), the
/// noise when its seed or shape size does. Every persistent renderer (the library's
/// [`Clouds`], the viewer on either backend) keeps one, so none can render with a stale plan.
pub struct Prepared {
    plan: FramePlan,
    noise: Arc<NoiseSet>,
    noise_settings: stratus_scene::Noise,
}

impl Prepared {
    /// The plan (without work counters) and noise of `scene`.
    pub fn new(scene: &Scene) -> Result<Self, PlanError> {
        Ok(Self {
            plan: FramePlan::for_scene(scene, false)?,
            noise: Arc::new(noise_for(scene)),
            noise_settings: scene.noise.clone(),
        })
    }

    /// Makes the plan and noise `scene`'s, remaking only what is stale.
    pub fn update(&mut self, scene: &Scene) -> Result<(), PlanError> {
        if !self.plan.serves(scene) {
            self.plan = FramePlan::for_scene(scene, false)?;
        }
        if scene.noise != self.noise_settings {
            self.noise = Arc::new(noise_for(scene));
            self.noise_settings = scene.noise.clone();
        }
        Ok(())
    }

    /// The current plan.
    pub fn plan(&self) -> &FramePlan {
        &self.plan
    }

    /// The current noise textures.
    pub fn noise(&self) -> &Arc<NoiseSet> {
        &self.noise
    }

    /// The frame of `scene` (which [`Prepared::update`] was last given) to hand a backend.
    pub fn frame<'a>(&'a self, scene: &'a Scene) -> FrameInput<'a> {
        FrameInput::new(&self.plan, scene, &self.noise)
    }
}

/// Persistent volumetric clouds on an application's wgpu device.
pub struct Clouds {
    renderer: Renderer,
    scene: Scene,
    prepared: Prepared,
    /// Passes recorded in the last frame, for [`Clouds::pass_timings`].
    recorded: Vec<String>,
    /// The host camera's projection aspect, checked against the target's when rendering.
    host_aspect: Option<f64>,
    /// The host's scene depth, if it gave one ([`Clouds::set_depth_texture`],
    /// [`Clouds::set_scene_depth`]).
    depth: Option<Depth>,
    /// Whether the host reads the cloud-shadow map ([`Clouds::set_cloud_shadow`]).
    shadow: bool,
    /// Whether the HDR output carries the sky ([`Clouds::set_hdr_sky`]).
    hdr_sky: bool,
}

/// Where the host's scene depth is.
enum Depth {
    /// Depths the host gave ([`Clouds::set_scene_depth`]), uploaded.
    Image(Arc<SceneDepth>),
    /// The host's depth texture, bound where it is, and what the frames are told of it (its
    /// size and projection).
    Texture(wgpu::TextureView, Arc<SceneDepth>),
}

impl Clouds {
    /// Clouds for `scene` on the application's device and queue (cloned handles; the
    /// application keeps its own). Generates the scene's noise textures (a few seconds on a
    /// CPU in debug builds; once per seed).
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue, scene: Scene) -> Result<Self, Error> {
        scene.validate()?;
        let program = Program::embedded()?;
        let renderer = Renderer::from_device(device.clone(), queue.clone(), program)?;
        let prepared = Prepared::new(&scene)?;
        Ok(Self {
            renderer,
            scene,
            prepared,
            recorded: Vec::new(),
            host_aspect: None,
            depth: None,
            shadow: false,
            hdr_sky: false,
        })
    }

    /// The current scene.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The current plan (variant, passes, resources).
    pub fn plan(&self) -> &FramePlan {
        self.prepared.plan()
    }

    /// GPU objects created so far: a steady loop creates none after its first frame.
    pub fn objects_created(&self) -> u64 {
        self.renderer.objects_created()
    }

    /// Applies a per-frame change. A new plan is made only when the scene's plan key changes
    /// (its shader features, plan options such as temporal upsampling, method and sky, or its
    /// size), and new noise only when its seed or shape size does.
    pub fn update(&mut self, update: Update) -> Result<(), Error> {
        if update.camera.is_some()
            && (update.camera_position.is_some() || update.camera_yaw_pitch_deg.is_some())
        {
            return Err(Error::Camera(
                "matrices came with camera_position or camera_yaw_pitch_deg in one Update: give one camera".into(),
            ));
        }
        // A new scene brings its own camera; a host camera in this update applies over it.
        let mut host_aspect = self.host_aspect.filter(|_| update.scene.is_none());
        let new_scene = update.scene.is_some();
        let mut scene = update.scene.unwrap_or_else(|| self.scene.clone());
        if let Some(p) = update.camera_position {
            scene.camera.position = p;
        }
        if let Some([yaw, pitch]) = update.camera_yaw_pitch_deg {
            scene.camera.yaw_deg = yaw;
            scene.camera.pitch_deg = pitch;
            scene.camera.orientation = None;
            host_aspect = None;
        }
        if let Some(camera) = &update.camera {
            host_aspect = Some(camera.apply(&mut scene)?.aspect);
        }
        if let Some(dt) = update.time_s {
            scene.clouds.time_s += dt;
        }
        if !new_scene {
            scene.quality.frame = scene.quality.frame.wrapping_add(1);
        }
        scene.validate()?;
        self.set_scene(scene)?;
        self.host_aspect = host_aspect;
        Ok(())
    }

    fn set_scene(&mut self, scene: Scene) -> Result<(), Error> {
        self.prepared.update(&scene)?;
        self.scene = scene;
        Ok(())
    }

    /// Records the frame into `encoder`, drawing the clouds (over the analytic sky) into
    /// `target`, which must be a 2D view of a texture with `RENDER_ATTACHMENT` usage and a
    /// UNORM colour format. The scene's resolution follows the target's size. The application
    /// submits the encoder.
    pub fn render(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
    ) -> Result<(), Error> {
        let format = target.texture().format();
        if format.is_srgb() {
            return Err(Error::Target(format!(
                "is {format:?}, an sRGB format: the clouds are already gamma-encoded; render into a view with the UNORM format ({:?})",
                format.remove_srgb_suffix()
            )));
        }
        self.record(encoder, target, "present")
    }

    /// Records the frame into `encoder`, writing the clouds' HDR output into `target` for the
    /// host's compositor: linear in-scattered radiance (rgb, premultiplied: the host's image
    /// behind the clouds times alpha, plus rgb) and transmittance (alpha), with no sky,
    /// exposure or tone curve (the host's tone mapping comes after; [`Clouds::set_hdr_sky`]
    /// adds the sky). `target` is an
    /// `Rgba16Float` (or `Rgba32Float`) texture with `RENDER_ATTACHMENT` usage, the frame's
    /// size. Where the host's depth ([`Clouds::set_depth_texture`]) holds geometry in front of
    /// the clouds, the output is (0, 0, 0, 1).
    pub fn render_hdr(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
    ) -> Result<(), Error> {
        let format = target.texture().format();
        if !matches!(
            format,
            wgpu::TextureFormat::Rgba16Float | wgpu::TextureFormat::Rgba32Float
        ) {
            return Err(Error::Target(format!(
                "is {format:?}: the HDR output is linear radiance, give an Rgba16Float (or Rgba32Float) target"
            )));
        }
        self.record(encoder, target, "hdr")
    }

    /// Records the frame with the host flag `flag` (`present` or `hdr`: which pass draws into
    /// `target`).
    fn record(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        flag: &'static str,
    ) -> Result<(), Error> {
        let texture = target.texture();
        if !texture
            .usage()
            .contains(wgpu::TextureUsages::RENDER_ATTACHMENT)
        {
            return Err(Error::Target(
                "lacks RENDER_ATTACHMENT usage; create it with that usage".into(),
            ));
        }
        let size = [texture.width(), texture.height()];
        if let Some(aspect) = self.host_aspect {
            let target = f64::from(size[0]) / f64::from(size[1]);
            if (aspect / target - 1.0).abs() > 1e-3 {
                return Err(Error::Camera(format!(
                    "projection: its aspect {aspect:.4} is not the target's, {}x{} ({target:.4})",
                    size[0], size[1]
                )));
            }
        }
        if size != self.scene.camera.resolution {
            let scene = self.scene.clone().with_size(size[0], size[1]);
            self.set_scene(scene)?;
        }
        let (depth, view) = match &self.depth {
            None => (None, None),
            Some(Depth::Image(d)) => (Some(d.clone()), None),
            Some(Depth::Texture(view, depth)) => {
                if depth.size() != size {
                    return Err(Error::Depth(format!(
                        "the depth texture is {}x{}, the target {}x{}: give a depth texture of the target's size",
                        depth.size()[0],
                        depth.size()[1],
                        size[0],
                        size[1]
                    )));
                }
                (Some(depth.clone()), Some(view))
            }
        };
        self.renderer.bind_host_texture("scene-depth", view);
        let mut flags = vec![flag];
        if self.shadow {
            flags.push("shadow");
        }
        if self.hdr_sky && flag == "hdr" {
            flags.push("sky");
        }
        let frame = self
            .prepared
            .frame(&self.scene)
            .with_readback(Readback::none())
            .with_flags(&flags)
            .with_scene_depth(depth.as_ref());
        self.recorded = self.renderer.record(encoder, &frame, Some(target))?;
        Ok(())
    }

    /// The host's depth buffer for the frames to come ([`Projection::scene_depth`] makes one
    /// from the host's depths; `None` removes it): the clouds stop at its geometry, so
    /// geometry in front of a cloud hides it and geometry inside one is seen through the
    /// cloud in front of it only. It must be the target's size when rendering.
    pub fn set_scene_depth(&mut self, depth: Option<SceneDepth>) {
        self.depth = depth.map(|d| Depth::Image(Arc::new(d)));
    }

    /// The host's depth texture for the frames to come, read on the GPU where it is (`None`
    /// removes it): a `Depth32Float` or `Depth24Plus` texture with `TEXTURE_BINDING` usage,
    /// the target's size, written with `projection` (standard or reversed Z, finite or
    /// infinite far plane; [`HostCamera::projection`]). The host renders its depth before
    /// recording the clouds. The clouds stop at its geometry, as with
    /// [`Clouds::set_scene_depth`].
    pub fn set_depth_texture(
        &mut self,
        depth: Option<(&wgpu::TextureView, Projection)>,
    ) -> Result<(), Error> {
        let Some((view, projection)) = depth else {
            self.depth = None;
            return Ok(());
        };
        let texture = view.texture();
        let format = texture.format();
        if !matches!(
            format,
            wgpu::TextureFormat::Depth32Float | wgpu::TextureFormat::Depth24Plus
        ) {
            return Err(Error::Depth(format!(
                "the depth texture is {format:?}: give a Depth32Float or Depth24Plus texture"
            )));
        }
        if !texture
            .usage()
            .contains(wgpu::TextureUsages::TEXTURE_BINDING)
        {
            return Err(Error::Depth(
                "the depth texture lacks TEXTURE_BINDING usage: create it with that usage so the clouds can read it".into(),
            ));
        }
        let depth = projection.texture_depth([texture.width(), texture.height()])?;
        self.depth = Some(Depth::Texture(view.clone(), Arc::new(depth)));
        Ok(())
    }

    /// Whether the HDR output ([`Clouds::render_hdr`]) of the frames to come carries the sky
    /// (off by default: the host draws its own). On, wherever the host's depth holds no
    /// geometry the sky (the scene's, physical or analytic, with the sun, moon and stars) is
    /// drawn behind the clouds and the pixel is opaque (alpha 0): the radiance the display image
    /// tone-maps. Over the host's geometry the output stays the clouds over it, with the air in
    /// front of them under the physical sky. For a host with no sky of its own.
    pub fn set_hdr_sky(&mut self, on: bool) {
        self.hdr_sky = on;
    }

    /// Whether the frames to come compute the cloud-shadow map for the host's geometry
    /// ([`Clouds::cloud_shadow`]; one more pass a frame, `host-shadow`).
    pub fn set_cloud_shadow(&mut self, on: bool) {
        self.shadow = on;
    }

    /// The cloud-shadow map the last frame computed, with the transform from the host's world
    /// to its texels, for the host's own lighting (`stratus_cloud_shadow` in
    /// `wgsl/host/cloud_shadow.wgsl`): the key light's transmittance through every cloud layer
    /// on a square 40 km wide around the camera. `None` unless the last frame computed it
    /// (turn it on with [`Clouds::set_cloud_shadow`]). The view is valid until the next frame;
    /// fetch it every frame.
    pub fn cloud_shadow(&self) -> Option<CloudShadow<'_>> {
        if !self.recorded.iter().any(|p| p == "host-shadow") {
            return None;
        }
        Some(CloudShadow {
            view: self.renderer.resource_view("host-shadow")?,
            transform: ShadowTransform::of_scene(&self.scene),
        })
    }

    /// The aerial-perspective table of the frames' view, for the host's own geometry
    /// (`stratus_aerial_perspective` in `wgsl/host/aerial_perspective.wgsl`): what the air
    /// scatters toward the camera and lets through, per pixel and distance, the haze Stratus's
    /// clouds and sky have. `None` without the physical sky (`atmosphere.sky = "physical"`)
    /// or before the first frame. The table follows the camera's orientation and the sun; it
    /// is made again only when they change, so fetch the view every frame.
    pub fn aerial_perspective(&self) -> Option<AerialPerspective<'_>> {
        if self.recorded.is_empty() {
            return None;
        }
        Some(AerialPerspective {
            view: self.renderer.resource_view("aerial-perspective")?,
            uniform: aerial::uniform(&self.scene),
        })
    }

    /// The GPU time of every pass of the last frame, once the application has submitted it
    /// (this waits for the GPU). Empty where the device has no `TIMESTAMP_QUERY`.
    pub fn pass_timings(&mut self) -> Result<Vec<PassTiming>, Error> {
        Ok(self.renderer.last_timings(&self.recorded)?)
    }
}

/// The noise textures a scene reads (deterministic from its seed).
pub fn noise_for(scene: &Scene) -> NoiseSet {
    NoiseSet::generate(&NoiseConfig {
        seed: scene.noise.seed,
        shape: match scene.noise.shape_texture {
            ShapeTexture::Thesis => ShapeSize::Thesis,
            ShapeTexture::Hzd => ShapeSize::Hzd,
        },
        ..NoiseConfig::default()
    })
}
