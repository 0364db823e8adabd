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

mod camera;

use std::sync::Arc;

pub use camera::{HostCamera, Projection, host_from_world, world_from_host};
/// The glam Stratus's [`HostCamera`] takes (the version Bevy 0.20 uses).
pub use glam;

use stratus_backend_wgpu::Renderer;
use stratus_graph::FrameInput;
pub use stratus_graph::{FramePlan, PassTiming, PlanError, Program, Readback};
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
}

impl From<stratus_scene::SceneError> for Error {
    fn from(e: stratus_scene::SceneError) -> Self {
        Self::Scene(e.to_string())
    }
}

/// A per-frame change: whatever is `Some` replaces the current value.
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
        let texture = target.texture();
        if !texture
            .usage()
            .contains(wgpu::TextureUsages::RENDER_ATTACHMENT)
        {
            return Err(Error::Target(
                "lacks RENDER_ATTACHMENT usage; create it with that usage".into(),
            ));
        }
        let format = texture.format();
        if format.is_srgb() {
            return Err(Error::Target(format!(
                "is {format:?}, an sRGB format: the clouds are already gamma-encoded; render into a view with the UNORM format ({:?})",
                format.remove_srgb_suffix()
            )));
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
        let frame = self
            .prepared
            .frame(&self.scene)
            .with_readback(Readback::none())
            .with_flags(&["present"]);
        self.recorded = self.renderer.record(encoder, &frame, Some(target))?;
        Ok(())
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
