//! The one backend trait (wgpu, ash and the CPU renderers implement it) and the code every
//! backend shares: ranking devices, turning timestamps into pass timings, the CPU-wall
//! fallback, the frame flags, and where uploaded data comes from.

use std::sync::Arc;

use stratus_noise::NoiseSet;
use stratus_scene::Scene;

use crate::{
    depth::{NO_SCENE_DEPTH, SceneDepth},
    desc::{Lifetime, OutputRole, ResourceKind},
    named_counters,
    output::{FrameOutput, PassTiming},
    plan::{FramePlan, Pass, PlanResource},
};

/// A backend's error, boxed so that one trait object serves every backend.
pub type BackendError = Box<dyn std::error::Error + Send + Sync + 'static>;

/// What to copy back to the host after a frame. Reading back costs a wait and a copy, so a
/// real-time loop asks for nothing.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Readback {
    /// The resources with an output role (radiance, depth, image) and the counters.
    pub output: bool,
    /// Further resources by name, into [`FrameOutput::resources`].
    pub resources: Vec<String>,
}

impl Readback {
    /// Nothing (timings only).
    pub fn none() -> Self {
        Self::default()
    }

    /// The frame's output images and counters.
    pub fn output() -> Self {
        Self {
            output: true,
            resources: Vec::new(),
        }
    }
}

/// Where a read-back resource goes in the frame's output.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Readout {
    /// An output image (radiance, depth, display image).
    Output(OutputRole),
    /// The work counters.
    Counters,
    /// [`FrameOutput::resources`], by name.
    Named,
}

impl Readback {
    /// The resources of `plan` this readback copies (by index into the plan's resources), and
    /// where each goes; the same list on every backend.
    pub fn targets(&self, plan: &FramePlan) -> Result<Vec<(usize, Readout)>, String> {
        let mut wanted = Vec::new();
        if self.output {
            for (i, r) in plan.resources.iter().enumerate() {
                if let Some(role) = r.output {
                    wanted.push((i, Readout::Output(role)));
                } else if r.kind == ResourceKind::Counters && plan.stats {
                    wanted.push((i, Readout::Counters));
                }
            }
        }
        for name in &self.resources {
            let (i, r) = plan
                .resource(name)
                .ok_or_else(|| format!("readback of `{name}`: the plan has no such resource"))?;
            match r.kind {
                ResourceKind::Sampler => {
                    return Err(format!("readback of `{name}`: a sampler holds no data"));
                }
                ResourceKind::Uniform => {
                    return Err(format!(
                        "readback of `{name}`: the uniform block is written by the host"
                    ));
                }
                _ => {}
            }
            wanted.push((i, Readout::Named));
        }
        Ok(wanted)
    }
}

impl FrameOutput {
    /// Puts the bytes read back from resource `index` of `plan` where `readout` says.
    pub fn store(&mut self, plan: &FramePlan, index: usize, readout: Readout, bytes: Vec<u8>) {
        match readout {
            Readout::Output(OutputRole::Radiance) => self.radiance = floats(&bytes),
            Readout::Output(OutputRole::Depth) => self.depth = floats(&bytes),
            Readout::Output(OutputRole::Image) => self.image = bytes,
            Readout::Counters => {
                let raw: Vec<u32> = bytes
                    .chunks_exact(4)
                    .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
                    .collect();
                self.stats = Some(named_counters(plan.counters(), &raw));
            }
            Readout::Named => {
                self.resources
                    .insert(plan.resources[index].name.clone(), bytes);
            }
        }
    }
}

fn floats(bytes: &[u8]) -> Vec<f32> {
    bytes
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect()
}

/// One frame to render.
#[derive(Clone)]
pub struct FrameInput<'a> {
    /// The plan (a backend keeps what it built for the last plan, and rebuilds only what a
    /// new plan changes).
    pub plan: &'a FramePlan,
    /// The scene: the uniforms are derived from it.
    pub scene: &'a Scene,
    /// Noise textures; uploaded when a different `Arc` arrives (or a texture is rebuilt).
    pub noise: &'a Arc<NoiseSet>,
    /// What to read back.
    pub readback: Readback,
    /// Host flags for conditional passes (the backend adds `stats`, `history` and
    /// `stale:NAME`).
    pub flags: &'a [&'a str],
    /// Computed persistent resources whose inputs changed (a LUT when the sun moved): the
    /// passes that compute them run again (`when = "stale:NAME"`).
    pub invalidate: &'a [&'a str],
    /// A camera cut: last frame's history is not used (no `history` flag, temporal
    /// upsampling starts over) although it is valid.
    pub cut: bool,
    /// The host's scene depth (the frame's size): the march stops at its surfaces. Uploaded
    /// when a different `Arc` arrives.
    pub scene_depth: Option<&'a Arc<SceneDepth>>,
}

impl<'a> FrameInput<'a> {
    /// A frame that reads its output back and sets no host flags.
    pub fn new(plan: &'a FramePlan, scene: &'a Scene, noise: &'a Arc<NoiseSet>) -> Self {
        Self {
            plan,
            scene,
            noise,
            readback: Readback::output(),
            flags: &[],
            invalidate: &[],
            cut: false,
            scene_depth: None,
        }
    }

    /// The same frame with the host's scene depth.
    pub fn with_scene_depth(self, scene_depth: Option<&'a Arc<SceneDepth>>) -> Self {
        Self {
            scene_depth,
            ..self
        }
    }

    /// Whether the host data uploaded for `noise` and `scene_depth` (what a backend uploaded
    /// last) is not this frame's, so the uploaded textures are written again.
    pub fn uploads_changed(
        &self,
        noise: Option<&Arc<NoiseSet>>,
        scene_depth: Option<&Arc<SceneDepth>>,
    ) -> bool {
        !noise.is_some_and(|n| Arc::ptr_eq(n, self.noise))
            || match (scene_depth, self.scene_depth) {
                (None, None) => false,
                (Some(a), Some(b)) => !Arc::ptr_eq(a, b),
                _ => true,
            }
    }

    /// The same frame after a camera cut: history starts over.
    pub fn with_cut(self) -> Self {
        Self { cut: true, ..self }
    }

    /// The same frame, reading back `readback` instead.
    pub fn with_readback(self, readback: Readback) -> Self {
        Self { readback, ..self }
    }

    /// The same frame with these host flags.
    pub fn with_flags(self, flags: &'a [&'a str]) -> Self {
        Self { flags, ..self }
    }

    /// The same frame, recomputing these computed persistent resources.
    pub fn with_invalidated(self, invalidate: &'a [&'a str]) -> Self {
        Self { invalidate, ..self }
    }
}

/// A renderer that executes frame plans.
pub trait Backend {
    /// The renderer and device in words, e.g. `wgpu on llvmpipe (...) (Vulkan, Cpu)`.
    fn describe(&self) -> String;
    /// Whether passes are timed with GPU timestamp queries (else by CPU wall time).
    fn has_timestamps(&self) -> bool;
    /// Renders one frame and waits for it; reads back what `frame.readback` asks for.
    fn render(&mut self, frame: &FrameInput<'_>) -> Result<FrameOutput, BackendError>;
    /// GPU objects (resources, views, pipelines, descriptor sets, queries...) this renderer
    /// has created so far: a steady loop creates none after its first frame.
    fn objects_created(&self) -> u64 {
        0
    }
    /// Tears the renderer down and reports what its validation said while doing so (objects
    /// left alive when the device is destroyed); dropping it instead can only print that.
    fn finish(self: Box<Self>) -> Result<(), BackendError> {
        Ok(())
    }
    /// Whether validation checks this renderer's work (a GPU backend created with it on).
    fn validated(&self) -> bool {
        false
    }
    /// Fault injection, for tests of what a host sees when the GPU goes away mid-sequence:
    /// loses this renderer's device now, as a GPU hang or a driver reset would. wgpu destroys
    /// its device (`wgpu::Device::destroy`, a real loss); on raw Vulkan a real loss cannot be
    /// caused at will, so ash's next submission reports `VK_ERROR_DEVICE_LOST` instead of
    /// running, and everything after it takes the path a real loss takes. Returns false
    /// where the renderer has no device to lose (the CPU).
    fn lose_device(&mut self) -> bool {
        false
    }
}

/// What kind of device an adapter is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DeviceClass {
    /// A discrete GPU.
    Discrete,
    /// An integrated GPU.
    Integrated,
    /// A virtual GPU.
    Virtual,
    /// Unknown.
    Other,
    /// A CPU driver (lavapipe, llvmpipe, SwiftShader).
    Cpu,
}

/// Of several devices, the index of the one to use: a real GPU before a CPU driver, the first
/// of equals (both backends rank alike).
pub fn best_device(classes: &[DeviceClass]) -> Option<usize> {
    let rank = |c: &DeviceClass| match c {
        DeviceClass::Discrete => 0,
        DeviceClass::Integrated => 1,
        DeviceClass::Virtual => 2,
        DeviceClass::Other => 3,
        DeviceClass::Cpu => 4,
    };
    (0..classes.len()).min_by_key(|&i| (rank(&classes[i]), i))
}

/// The device in words, the same from both backends: `name (Vulkan, Cpu)`.
pub fn describe_device(name: &str, api: &str, class: DeviceClass) -> String {
    format!("{name} ({api}, {class:?})")
}

/// Pass timings from a begin and an end timestamp per pass (`ticks[2i]`, `ticks[2i+1]`).
/// Only `valid_bits` of a timestamp count, and the counter may wrap between the two.
pub fn timings_from_ticks(
    passes: &[&Pass],
    ticks: &[u64],
    period_ns: f64,
    valid_bits: u32,
) -> Vec<PassTiming> {
    let mask = if valid_bits >= 64 {
        u64::MAX
    } else {
        (1u64 << valid_bits) - 1
    };
    passes
        .iter()
        .enumerate()
        .map(|(i, p)| PassTiming {
            pass: p.name.clone(),
            ms: (ticks[2 * i + 1].wrapping_sub(ticks[2 * i]) & mask) as f64 * period_ns * 1e-6,
            source: "gpu-timestamp",
        })
        .collect()
}

/// Pass timings measured on the CPU, each pass submitted alone and waited for (devices
/// without timestamp queries).
pub fn cpu_wall_timings(passes: &[&Pass], ms: &[f64]) -> Vec<PassTiming> {
    passes
        .iter()
        .zip(ms)
        .map(|(p, &ms)| PassTiming {
            pass: p.name.clone(),
            ms,
            source: "cpu-wall",
        })
        .collect()
}

/// What a backend remembers between frames that decides which passes run and which half of a
/// history pair is current: the frame count, frames since the history resources were made,
/// and which computed persistent resources hold their results. Both backends keep one and
/// tell it what they create; the rules live here once.
#[derive(Clone, Debug, Default)]
pub struct FrameState {
    frame: u64,
    history_frames: u64,
    /// Computed persistent resources that hold their results, with the uniform block of the
    /// frame that computed them (their `inputs` are held to it).
    computed: std::collections::BTreeMap<String, stratus_scene::FrameUniforms>,
    /// The uniform block of the last frame rendered: its camera is the next frame's
    /// `previous_*` (temporal reprojection).
    last: Option<stratus_scene::FrameUniforms>,
    /// The noise the computed resources were computed from (they may read uploaded
    /// textures: the occupancy grid reads the weather map): another noise set makes them stale.
    computed_from: Option<std::sync::Weak<NoiseSet>>,
}

impl FrameState {
    /// Frames rendered so far (its parity picks the current half of history pairs).
    pub fn frame(&self) -> u64 {
        self.frame
    }

    /// A resource was (re)created: a history pair starts without history, a computed
    /// persistent resource without its result.
    pub fn created(&mut self, r: &PlanResource) {
        if r.lifetime == Lifetime::History {
            self.history_frames = 0;
        }
        self.computed.remove(&r.name);
    }

    /// Other shader modules will run the same plan (the conformance suite's ash renderer
    /// runs the committed SPIR-V, then glslang's builds of the GLSL and the HLSL): computed
    /// persistent resources hold what the old modules computed, so they are computed again.
    /// Otherwise a path would be measured on tables another path made.
    pub fn forget_computed(&mut self) {
        self.computed.clear();
    }

    /// The flags of this frame: the host's; `stats` when the plan counts; `history` once last
    /// frame's history is valid; `stale:NAME` for every computed persistent resource that has
    /// no result yet or that the host invalidated.
    pub fn flags(&self, frame: &FrameInput<'_>) -> Vec<String> {
        let mut flags: Vec<String> = frame.flags.iter().map(|f| f.to_string()).collect();
        if frame.plan.stats {
            flags.push("stats".into());
        }
        if self.history_frames > 0 && !frame.cut {
            flags.push("history".into());
        }
        for r in frame
            .plan
            .resources
            .iter()
            .filter(|r| r.is_computed_persistent())
        {
            let new_noise = !self
                .computed_from
                .as_ref()
                .is_some_and(|w| std::sync::Weak::ptr_eq(w, &Arc::downgrade(frame.noise)));
            if !self.computed.contains_key(&r.name)
                || new_noise
                || frame.invalidate.contains(&r.name.as_str())
                || self.inputs_changed(r, frame)
            {
                flags.push(format!("stale:{}", r.name));
            }
        }
        flags
    }

    /// Whether a uniform member that computed resource `r` is computed from (`inputs`)
    /// differs from the frame's that computed it: bit for bit, or by more than its
    /// `tolerance` (so a slow drift, below it from frame to frame, still adds up to a change).
    fn inputs_changed(&self, r: &PlanResource, frame: &FrameInput<'_>) -> bool {
        let Some(then) = self.computed.get(&r.name) else {
            return false;
        };
        if r.inputs.is_empty() {
            return false;
        }
        let now = frame.scene.uniforms();
        r.inputs.iter().any(|input| {
            let tolerance = r.tolerance.get(input).copied();
            crate::desc::input_differs(input, tolerance, now.as_bytes(), then.as_bytes())
        })
    }

    /// The uniform block of `frame`: the scene's, with last frame's camera and
    /// `history_valid` = 1 once the history holds last frame (temporal reprojection reads both).
    pub fn uniforms(&self, frame: &FrameInput<'_>) -> stratus_scene::FrameUniforms {
        let mut u = frame.scene.uniforms();
        if let Some(depth) = frame.scene_depth {
            depth.apply(&mut u);
        }
        if frame.flags.contains(&"sky") {
            u.flags |= stratus_scene::FrameUniforms::FLAG_HDR_SKY;
        }
        if let Some(last) = &self.last
            && self.history_frames > 0
            && !frame.cut
            && frame.plan.has_history()
        {
            u = u.with_previous_camera(last);
            u.history_valid = 1;
        }
        u
    }

    /// The passes of the plan that run in this frame, by index, in order.
    pub fn passes(&self, frame: &FrameInput<'_>) -> Vec<usize> {
        let flags = self.flags(frame);
        let flags: Vec<&str> = flags.iter().map(String::as_str).collect();
        (0..frame.plan.passes.len())
            .filter(|&i| frame.plan.passes[i].runs(&flags))
            .collect()
    }

    /// The frame ran `ran` (indices into the plan's passes): computed persistent resources
    /// they wrote now hold results (computed from this frame's noise), history moves on, and
    /// `uniforms` (the block the frame used) holds the camera the next frame reprojects from.
    pub fn finished(
        &mut self,
        frame: &FrameInput<'_>,
        ran: &[usize],
        uniforms: &stratus_scene::FrameUniforms,
    ) {
        let plan = frame.plan;
        self.last = Some(*uniforms);
        let mut computed_any = false;
        for &i in ran {
            for r in plan.passes[i].writes() {
                let r = &plan.resources[r];
                if r.is_computed_persistent() {
                    self.computed.insert(r.name.clone(), *uniforms);
                    computed_any = true;
                }
            }
        }
        if computed_any || self.computed_from.is_none() {
            self.computed_from = Some(Arc::downgrade(frame.noise));
        }
        self.frame += 1;
        self.history_frames += 1;
    }
}

/// An uploaded texture to write: the resource, its size (x, y, z) and its data.
pub type Upload<'f> = (&'f PlanResource, [u32; 3], &'f [u8]);

/// The uploaded textures of `frame`'s plan to write this frame, each with its size and data:
/// all of them when `all` (resources made again, or another noise set), else only the host's
/// scene depth, which changes every frame it moves while the noise does not. Both backends
/// upload what this lists.
pub fn uploads<'f>(frame: &FrameInput<'f>, all: bool) -> Result<Vec<Upload<'f>>, String> {
    let plan: &'f FramePlan = frame.plan;
    plan.resources
        .iter()
        .filter(|r| r.usage.upload)
        .filter_map(|r| {
            let src = r.upload.as_deref().unwrap_or_default();
            (all || src == "scene.depth").then(|| {
                upload_data(src, frame)
                    .map(|(size, data)| (r, size, data))
                    .map_err(|e| format!("resource `{}`: {e}", r.name))
            })
        })
        .collect()
}

/// Why `frame`'s scene depth cannot be rendered, if it cannot: it is not the frame's size, the
/// scene renders with a method that does not read it (the path tracer and the baselines do
/// not stop at the host's geometry), or its depths are in a host texture that this renderer
/// has not bound (`host_texture`: whether it has). Every backend asks before rendering.
pub fn check_scene_depth(frame: &FrameInput<'_>, host_texture: bool) -> Result<(), String> {
    let Some(d) = frame.scene_depth else {
        return Ok(());
    };
    if d.bytes().is_none() && !host_texture {
        return Err(
            "the scene depth is in the host's GPU texture, which only the wgpu library (stratus::Clouds) binds; give this renderer the depths (SceneDepth::new)".into(),
        );
    }
    let [w, h] = d.size();
    let want = frame.scene.camera.resolution;
    if [w, h] != want {
        return Err(format!(
            "the scene depth is {w}x{h}, the frame {}x{}: give a depth image of the target's size",
            want[0], want[1]
        ));
    }
    let q = &frame.scene.quality;
    if q.integrator == stratus_scene::Integrator::Pathtrace
        || q.method != stratus_scene::Method::Volumetric
    {
        return Err(format!(
            "scene depth is read by the volumetric march only; this scene renders with {} (quality.method = \"{}\"), which does not stop at the host's geometry",
            if q.integrator == stratus_scene::Integrator::Pathtrace {
                "the path tracer"
            } else {
                "a baseline method"
            },
            q.method.name()
        ));
    }
    Ok(())
}

/// The size (x, y, z) and bytes (four a texel: RGBA8, or one f32) of the host data an
/// upload names, checked against each other.
pub fn upload_data<'n>(
    source: &str,
    frame: &FrameInput<'n>,
) -> Result<([u32; 3], &'n [u8]), String> {
    let noise: &'n NoiseSet = frame.noise;
    let (size, data) = match source {
        "scene.depth" => match frame.scene_depth {
            Some(d) => match d.bytes() {
                Some(bytes) => {
                    let [w, h] = d.size();
                    ([w, h, 1], bytes)
                }
                // In the host's texture, bound in place of this one.
                None => ([1, 1, 1], &NO_SCENE_DEPTH[..]),
            },
            None => ([1, 1, 1], &NO_SCENE_DEPTH[..]),
        },
        "noise.shape" => (noise.shape.size, &noise.shape.data[..]),
        "noise.detail" => (noise.detail.size, &noise.detail.data[..]),
        "noise.weather" => (
            [noise.weather.size[0], noise.weather.size[1], 1],
            &noise.weather.data[..],
        ),
        "noise.curl" => (
            [noise.curl.size[0], noise.curl.size[1], 1],
            &noise.curl.data[..],
        ),
        "stars.catalogue" => {
            let table = stratus_astro::stars::gpu_table();
            (table.size, &table.bytes[..])
        }
        other => return Err(format!("no host data called `{other}`")),
    };
    let expected = size.iter().map(|&n| u64::from(n)).product::<u64>() * 4;
    if data.len() as u64 != expected || expected == 0 {
        return Err(format!(
            "the {source} texture has {} bytes, {expected} expected for {}x{}x{} texels",
            data.len(),
            size[0],
            size[1],
            size[2]
        ));
    }
    Ok((size, data))
}

/// What a resource's GPU object was made from: the plan's description and, for an uploaded
/// texture, its data's size. A backend keeps the object, across frames and plans, while it
/// [serves](Made::serves) what the plan asks for.
#[derive(Clone, Debug, PartialEq)]
pub struct Made {
    /// The plan's description.
    pub desc: PlanResource,
    /// The size of an uploaded texture (from its data).
    pub uploaded: Option<[u32; 3]>,
}

impl Made {
    /// What `r` needs this frame (an uploaded texture takes the size of its data).
    pub fn for_frame(r: &PlanResource, frame: &FrameInput<'_>) -> Result<Self, String> {
        let uploaded = match &r.upload {
            Some(src) if r.kind == ResourceKind::Texture => Some(
                upload_data(src, frame)
                    .map_err(|e| format!("resource `{}`: {e}", r.name))?
                    .0,
            ),
            _ => None,
        };
        Ok(Self {
            desc: r.clone(),
            uploaded,
        })
    }

    /// Whether an object made for `self` serves `want` (same kind, size, format, usage...).
    pub fn serves(&self, want: &Made) -> bool {
        self.desc.signature() == want.desc.signature() && self.uploaded == want.uploaded
    }

    /// The texture's size, or why it has none.
    pub fn size(&self) -> Result<[u32; 3], String> {
        self.uploaded
            .or(self.desc.extent)
            .ok_or_else(|| format!("texture `{}` has no size", self.desc.name))
    }
}

/// Which half of a history pair is "current" in frame `frame` (the other is `.previous`).
pub fn history_half(frame: u64, previous: bool) -> usize {
    ((frame % 2) as usize) ^ usize::from(previous)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A computed resource (the occupancy grid reads the weather map) is computed once, and
    /// again when another noise set arrives.
    #[test]
    fn computed_resources_go_stale_with_other_noise() {
        let program = crate::Program::embedded().unwrap();
        let scene = Scene::default();
        let plan = FramePlan::with_options(
            &program,
            &crate::Requirements::of(&scene, false),
            8,
            8,
            crate::PlanOptions {
                empty_skip: true,
                ..Default::default()
            },
        )
        .unwrap();
        let noise = NoiseSet::generate(&stratus_noise::NoiseConfig {
            weather_size: 16,
            curl_size: 8,
            detail_size: 8,
            ..Default::default()
        });
        let (a, b) = (Arc::new(noise.clone()), Arc::new(noise));
        let mut state = FrameState::default();
        let names = |state: &FrameState, noise: &Arc<NoiseSet>| -> Vec<String> {
            state
                .passes(&FrameInput::new(&plan, &scene, noise))
                .into_iter()
                .map(|i| plan.passes[i].name.clone())
                .collect()
        };
        let run = |state: &mut FrameState, noise: &Arc<NoiseSet>| {
            let frame = FrameInput::new(&plan, &scene, noise);
            let ran = state.passes(&frame);
            let u = state.uniforms(&frame);
            state.finished(&frame, &ran, &u);
        };
        assert_eq!(names(&state, &a)[0], "occupancy");
        run(&mut state, &a);
        assert!(!names(&state, &a).contains(&"occupancy".to_string()));
        assert_eq!(names(&state, &b)[0], "occupancy");
        run(&mut state, &b);
        assert!(!names(&state, &b).contains(&"occupancy".to_string()));
    }

    #[test]
    fn ranks_gpus_before_cpu_drivers() {
        use DeviceClass::*;
        assert_eq!(best_device(&[Cpu, Discrete, Integrated]), Some(1));
        assert_eq!(best_device(&[Cpu, Cpu]), Some(0));
        assert_eq!(best_device(&[]), None);
    }

    #[test]
    fn history_halves_alternate() {
        assert_eq!(history_half(0, false), 0);
        assert_eq!(history_half(0, true), 1);
        assert_eq!(history_half(1, false), 1);
        assert_eq!(history_half(1, true), 0);
    }
}
