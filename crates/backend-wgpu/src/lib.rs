//! Runs Stratus's frame graph on wgpu: on a device of its own (Vulkan first, GL on request),
//! or on an application's device, recording into the application's command encoder.
//!
//! The renderer is persistent. The first frame of a plan creates what the plan needs (resources
//! by name, a pipeline per pass and variant, bind groups, timestamp queries); later frames only
//! write the uniform block and record commands. A new plan (another size or variant) rebuilds
//! only the resources whose size, format or usage changed, and the pipelines it lacks. Noise is
//! uploaded when a different `Arc<NoiseSet>` arrives. History resources ping-pong: frame N's
//! `name.previous` is what frame N-1 wrote as `name`.
//!
//! The steps mirror the ash backend's: the same plan, the same order, the same shared helpers
//! from `stratus-graph`. wgpu compiles the composed WGSL itself with exactly the plan's
//! override values, so it runs the code the committed SPIR-V (which ash loads) holds.

#![deny(missing_docs)]

mod convert;
mod error;
mod gpu;
mod pipeline;
mod resources;

pub use error::Error;
use gpu::{Queries, poll};
use pipeline::{Pipeline, PipelineKey, PipelineKind};
use resources::{Copied, Object, Resource, extent3d, read_buffer};

use std::{
    collections::HashMap,
    sync::{Arc, Mutex},
    time::Instant,
};

use stratus_graph::{
    Backend, BackendError, FrameInput, FrameOutput, FramePlan, Program,
    backend::{
        DeviceClass, FrameState, Made, Readout, best_device, cpu_wall_timings, describe_device,
        history_half, timings_from_ticks, uploads,
    },
    desc::{Lifetime, ResourceKind},
    plan::PassKind,
};
use stratus_noise::NoiseSet;
use stratus_scene::FrameUniforms;

/// Which graphics API wgpu runs on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Api {
    /// Vulkan (lavapipe on machines without a GPU).
    Vulkan,
    /// OpenGL ES through EGL (llvmpipe on machines without a GPU).
    Gl,
}

/// How to create the renderer.
#[derive(Clone, Copy, Debug)]
pub struct Options {
    /// The API to run on.
    pub api: Api,
    /// Turn on wgpu's validation (and the Vulkan validation layer where installed). wgpu's
    /// DEBUG flag stays off: Debian's validation layer misreads the WGSL debug info it adds.
    pub validation: bool,
}

/// A wgpu device ready to render frames of Stratus's frame graph.
pub struct Renderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    description: String,
    timestamps: bool,
    program: Arc<Program>,
    modules: HashMap<String, wgpu::ShaderModule>,
    pipelines: HashMap<PipelineKey, Pipeline>,
    resources: HashMap<String, Resource>,
    /// The plan the bind groups were built for.
    plan: Option<FramePlan>,
    /// Per pass of `plan`, one bind group per history parity.
    groups: Vec<Vec<wgpu::BindGroup>>,
    /// The host's textures bound in place of a resource's own (the host's depth texture for
    /// `scene-depth`), and whether the bind groups still bind the previous ones.
    bound: HashMap<String, wgpu::TextureView>,
    bound_changed: bool,
    /// Per pass of `plan`, its pipeline's key (with the graph's own target formats), made
    /// once per plan so that recording a frame builds no key.
    keys: Vec<PipelineKey>,
    uniform: Option<wgpu::Buffer>,
    noise: Option<Arc<NoiseSet>>,
    /// The scene depth uploaded last.
    scene_depth: Option<Arc<stratus_graph::SceneDepth>>,
    /// Frame count, history validity, computed persistent resources (the shared rules).
    frames: FrameState,
    queries: Option<Queries>,
    readbacks: HashMap<String, wgpu::Buffer>,
    /// Uncaptured errors, where the renderer owns the device (an application keeps its own
    /// handler).
    errors: Option<Arc<Mutex<Vec<String>>>>,
    /// Why the device was lost, once it is, where the renderer owns the device (an application
    /// keeps its own callback; its errors then say "lost" instead).
    lost: Arc<Mutex<Option<String>>>,
    /// Whether the renderer's own instance has validation on.
    validation: bool,
    created: u64,
}

impl Renderer {
    /// Times every pass by submitting it alone and waiting for it on the CPU (`cpu-wall`),
    /// as devices without timestamp queries do (as backend-ash's). On lavapipe a raster pass's
    /// timestamps, and those of every pass after it on the device, are not exact.
    pub fn set_cpu_wall_timing(&mut self, on: bool) {
        self.timestamps = !on
            && self
                .device
                .features()
                .contains(wgpu::Features::TIMESTAMP_QUERY);
    }

    /// GPU objects this renderer has created so far.
    pub fn objects_created(&self) -> u64 {
        self.created
    }

    /// The program the renderer runs.
    pub fn program(&self) -> &Arc<Program> {
        &self.program
    }

    /// Renders one frame on the renderer's queue, waits for it, and reads back what
    /// `frame.readback` asks for. Without timestamp queries every pass is submitted alone and
    /// timed on the CPU.
    pub fn render(&mut self, frame: &FrameInput<'_>) -> Result<FrameOutput, Error> {
        self.check_lost()?;
        let scope = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let result = self.render_inner(frame);
        let scoped = pollster::block_on(scope.pop());
        self.check_errors()?;
        if let Some(e) = scoped {
            return Err(self.classify(e.to_string()));
        }
        result.map_err(|e| match e {
            Error::Wgpu(m) => self.classify(m),
            other => other,
        })
    }

    /// Records one frame into the application's `encoder`, drawing passes whose colour target
    /// is an external resource (the graph's `display`) into `target` where one is given. The
    /// application submits; [`Renderer::last_timings`] reads the pass times after that.
    pub fn record(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameInput<'_>,
        target: Option<&wgpu::TextureView>,
    ) -> Result<Vec<String>, Error> {
        self.check_lost()?;
        let scope = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let result = self.record_frame(encoder, frame, target);
        let scoped = pollster::block_on(scope.pop());
        if let Some(e) = scoped {
            return Err(self.classify(e.to_string()));
        }
        result
    }

    /// The GPU time of every pass of the last recorded frame, once the application has
    /// submitted it (this waits for the GPU). Empty without timestamp queries.
    pub fn last_timings(
        &mut self,
        passes: &[String],
    ) -> Result<Vec<stratus_graph::PassTiming>, Error> {
        let Some(plan) = &self.plan else {
            return Ok(Vec::new());
        };
        if !self.timestamps || passes.is_empty() {
            return Ok(Vec::new());
        }
        let ran: Vec<&stratus_graph::plan::Pass> = plan
            .passes
            .iter()
            .filter(|p| passes.contains(&p.name))
            .collect();
        let q = self
            .queries
            .as_ref()
            .expect("queries exist with timestamps");
        let bytes = read_buffer(&self.device, &q.read, None)?;
        let ticks: Vec<u64> = bytes
            .chunks_exact(8)
            .map(|c| u64::from_le_bytes(c.try_into().expect("8 bytes")))
            .collect();
        let period_ns = f64::from(self.queue.get_timestamp_period());
        Ok(timings_from_ticks(&ran, &ticks, period_ns, 64))
    }

    fn record_frame(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameInput<'_>,
        target: Option<&wgpu::TextureView>,
    ) -> Result<Vec<String>, Error> {
        let target_format = target.map(|t| t.texture().format());
        self.prepare(frame, target_format)?;
        let plan = frame.plan;
        let run = self.frames.passes(frame);
        let uniforms = self.begin_frame(encoder, frame);
        for (k, &i) in run.iter().enumerate() {
            self.record_pass(encoder, i, Some(k as u32), target, target_format)?;
        }
        self.resolve_queries(encoder, run.len() as u32);
        self.frames.finished(frame, &run, &uniforms);
        Ok(run.iter().map(|&i| plan.passes[i].name.clone()).collect())
    }

    fn render_inner(&mut self, frame: &FrameInput<'_>) -> Result<FrameOutput, Error> {
        let t0 = Instant::now();
        self.prepare(frame, None)?;
        let plan = frame.plan;
        let indices = self.frames.passes(frame);
        let run: Vec<&stratus_graph::plan::Pass> =
            indices.iter().map(|&i| &plan.passes[i]).collect();
        let mut encoder = self.device.create_command_encoder(&Default::default());
        let uniforms = self.begin_frame(&mut encoder, frame);
        let mut wall = Vec::new();
        // CPU time of recording and submitting: the waits of the CPU-wall fallback excluded.
        let mut waited = 0.0;
        if self.timestamps {
            for (k, &i) in indices.iter().enumerate() {
                self.record_pass(&mut encoder, i, Some(k as u32), None, None)?;
            }
            self.resolve_queries(&mut encoder, indices.len() as u32);
        } else {
            // No timestamps: submit every pass alone and time it on the CPU.
            for &i in &indices {
                self.queue.submit([encoder.finish()]);
                let t = Instant::now();
                self.wait()?;
                waited += t.elapsed().as_secs_f64() * 1e3;
                let t = Instant::now();
                encoder = self.device.create_command_encoder(&Default::default());
                self.record_pass(&mut encoder, i, None, None, None)?;
                self.queue.submit([encoder.finish()]);
                self.wait()?;
                let ms = t.elapsed().as_secs_f64() * 1e3;
                wall.push(ms);
                waited += ms;
                encoder = self.device.create_command_encoder(&Default::default());
            }
        }
        let copies = self.copy_readbacks(&mut encoder, frame)?;
        self.queue.submit([encoder.finish()]);
        let cpu_ms = t0.elapsed().as_secs_f64() * 1e3 - waited;
        self.frames.finished(frame, &indices, &uniforms);
        self.wait()?;

        let mut out = FrameOutput {
            width: plan.width,
            height: plan.height,
            cpu_ms,
            device: self.adapter(),
            ..Default::default()
        };
        for Copied {
            index,
            readout,
            rows,
        } in copies
        {
            let name = &plan.resources[index].name;
            let bytes = read_buffer(&self.device, &self.readbacks[name], rows)?;
            out.store(plan, index, readout, bytes);
        }
        out.timings = if self.timestamps {
            let q = self
                .queries
                .as_ref()
                .expect("queries exist with timestamps");
            let bytes = read_buffer(&self.device, &q.read, None)?;
            let ticks: Vec<u64> = bytemuck::pod_collect_to_vec(&bytes);
            let period_ns = f64::from(self.queue.get_timestamp_period());
            timings_from_ticks(&run, &ticks, period_ns, 64)
        } else {
            cpu_wall_timings(&run, &wall)
        };
        Ok(out)
    }

    /// Writes the uniforms and clears the counters of a counting frame; returns the uniforms.
    fn begin_frame(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameInput<'_>,
    ) -> FrameUniforms {
        let uniforms: FrameUniforms = self.frames.uniforms(frame);
        if let Some(u) = &self.uniform {
            self.queue.write_buffer(u, 0, bytemuck::bytes_of(&uniforms));
        }
        if frame.plan.stats {
            for r in self.resources.values() {
                if let (ResourceKind::Counters, Object::Buffer(b)) = (r.made.desc.kind, &r.object) {
                    encoder.clear_buffer(b, 0, None);
                }
            }
        }
        uniforms
    }

    /// Creates or updates what `frame` needs: resources, pipelines, bind groups, uploads.
    fn prepare(
        &mut self,
        frame: &FrameInput<'_>,
        target_format: Option<wgpu::TextureFormat>,
    ) -> Result<(), Error> {
        let plan = frame.plan;
        if self.plan.as_ref() != Some(plan) {
            self.check_limits(plan)?;
        }
        let noise_changed = !self
            .noise
            .as_ref()
            .is_some_and(|n| Arc::ptr_eq(n, frame.noise));
        stratus_graph::backend::check_scene_depth(frame, self.bound.contains_key("scene-depth"))
            .map_err(Error::Shader)?;
        // Other host data than uploaded last (the scene depth changes every frame it moves).
        let uploads_stale = frame.uploads_changed(self.noise.as_ref(), self.scene_depth.as_ref());
        let plan_changed = self.plan.as_ref() != Some(plan);
        if !plan_changed && !uploads_stale && !self.bound_changed {
            if let Some(format) = target_format {
                // Another external target format needs its own raster pipelines.
                for (i, pass) in plan.passes.iter().enumerate() {
                    if matches!(pass.kind, PassKind::Raster { .. }) {
                        self.pipeline(plan, i, Some(format))?;
                    }
                }
            }
            return Ok(());
        }
        if plan_changed {
            self.groups.clear();
            self.plan = None;
            if self.uniform.is_none() {
                self.uniform = Some(self.device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("frame"),
                    size: std::mem::size_of::<FrameUniforms>() as u64,
                    usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                }));
                self.created += 1;
            }
        }
        let mut rebuilt = false;
        for r in &plan.resources {
            let want = Made::for_frame(r, frame).map_err(Error::Shader)?;
            let keep = self
                .resources
                .get(&r.name)
                .is_some_and(|have| have.made.serves(&want));
            if !keep {
                let object = self.create_resource(&want)?;
                self.resources
                    .insert(r.name.clone(), Resource { made: want, object });
                rebuilt = true;
                self.frames.created(r);
            }
        }
        self.resources
            .retain(|name, _| plan.resources.iter().any(|r| &r.name == name));
        if rebuilt || uploads_stale {
            for (r, size, data) in
                uploads(frame, rebuilt || noise_changed).map_err(Error::Shader)?
            {
                let Object::Textures(t) = &self.resources[&r.name].object else {
                    continue;
                };
                self.queue.write_texture(
                    t[0].0.as_image_copy(),
                    data,
                    wgpu::TexelCopyBufferLayout {
                        offset: 0,
                        bytes_per_row: Some(size[0] * 4),
                        rows_per_image: Some(size[1]),
                    },
                    extent3d(size),
                );
            }
            self.noise = Some(frame.noise.clone());
            self.scene_depth = frame.scene_depth.cloned();
        }
        if plan_changed || rebuilt {
            for i in 0..plan.passes.len() {
                self.pipeline(plan, i, None)?;
                if let Some(format) = target_format {
                    self.pipeline(plan, i, Some(format))?;
                }
            }
            self.keys = (0..plan.passes.len())
                .map(|i| Self::pipeline_key(plan, i, None))
                .collect();
            self.build_groups(plan)?;
            self.ensure_queries(2 * plan.passes.len() as u32);
            self.plan = Some(plan.clone());
        } else if self.bound_changed {
            self.build_groups(plan)?;
        }
        self.bound_changed = false;
        Ok(())
    }

    /// The view of texture resource `name` as the last frame left it (the current half of a
    /// history pair), for a host that reads it in its own passes (the cloud-shadow map); `None`
    /// where the plan has no such texture. Valid until the next frame that remakes it (a new
    /// plan).
    pub fn resource_view(&self, name: &str) -> Option<&wgpu::TextureView> {
        match &self.resources.get(name)?.object {
            Object::Textures(t) => {
                let last = self.frames.frame().wrapping_sub(1);
                let half = if t.len() > 1 {
                    history_half(last, false)
                } else {
                    0
                };
                Some(&t[half].1)
            }
            _ => None,
        }
    }

    /// Binds the host's texture `view` in place of the plan's resource `resource` (the host's
    /// depth texture for `scene-depth`; `None` unbinds it): passes read the host's texture
    /// where it is, without a copy. The bind groups are made again when the view changes.
    pub fn bind_host_texture(&mut self, resource: &str, view: Option<&wgpu::TextureView>) {
        let same = match (self.bound.get(resource), view) {
            (Some(a), Some(b)) => a == b,
            (None, None) => true,
            _ => false,
        };
        if same {
            return;
        }
        match view {
            Some(v) => self.bound.insert(resource.to_string(), v.clone()),
            None => self.bound.remove(resource),
        };
        self.bound_changed = true;
    }

    /// Records pass `i` of the current plan, with timestamps at `query` (pair index).
    fn record_pass(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        i: usize,
        query: Option<u32>,
        target: Option<&wgpu::TextureView>,
        target_format: Option<wgpu::TextureFormat>,
    ) -> Result<(), Error> {
        let plan = self.plan.as_ref().expect("prepared");
        let pass = &plan.passes[i];
        let parity = if plan.has_history() {
            (self.frames.frame() % 2) as usize
        } else {
            0
        };
        let group = &self.groups[i][parity];
        // Only a raster pass drawing into a host's target of another format has another key.
        let external;
        let key = match (&pass.kind, target_format) {
            (PassKind::Raster { .. }, Some(format)) => {
                external = Self::pipeline_key(plan, i, Some(format));
                &external
            }
            _ => &self.keys[i],
        };
        let pipeline = &self.pipelines[key];
        let queries = query.and_then(|k| self.queries.as_ref().map(|q| (k, &q.set)));
        match (&pass.kind, &pipeline.kind) {
            (PassKind::Compute { dispatch, .. }, PipelineKind::Compute(p)) => {
                let mut cpass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some(&pass.name),
                    timestamp_writes: queries.map(|(k, set)| wgpu::ComputePassTimestampWrites {
                        query_set: set,
                        beginning_of_pass_write_index: Some(2 * k),
                        end_of_pass_write_index: Some(2 * k + 1),
                    }),
                });
                cpass.set_pipeline(p);
                cpass.set_bind_group(0, group, &[]);
                let [x, y, z] = *dispatch;
                cpass.dispatch_workgroups(x, y, z);
            }
            (
                PassKind::Raster {
                    vertices,
                    colors,
                    depth,
                    ..
                },
                PipelineKind::Raster(p),
            ) => {
                let mut attachments = Vec::new();
                for c in colors {
                    let view = match target {
                        Some(t) if plan.resources[c.resource].external => t,
                        _ => self.view(plan, c.resource)?,
                    };
                    attachments.push(Some(wgpu::RenderPassColorAttachment {
                        view,
                        depth_slice: None,
                        resolve_target: None,
                        ops: wgpu::Operations {
                            load: convert::color_load(c.load),
                            store: wgpu::StoreOp::Store,
                        },
                    }));
                }
                let depth_view = match depth {
                    Some(d) => Some((d, self.view(plan, d.resource)?)),
                    None => None,
                };
                let mut rpass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some(&pass.name),
                    color_attachments: &attachments,
                    depth_stencil_attachment: depth_view.map(|(d, view)| {
                        wgpu::RenderPassDepthStencilAttachment {
                            view,
                            depth_ops: Some(wgpu::Operations {
                                load: convert::depth_load(d.load),
                                store: wgpu::StoreOp::Store,
                            }),
                            stencil_ops: None,
                        }
                    }),
                    timestamp_writes: queries.map(|(k, set)| wgpu::RenderPassTimestampWrites {
                        query_set: set,
                        beginning_of_pass_write_index: Some(2 * k),
                        end_of_pass_write_index: Some(2 * k + 1),
                    }),
                    occlusion_query_set: None,
                    multiview_mask: None,
                });
                let [w, h] = pass.extent;
                rpass.set_viewport(0.0, 0.0, w as f32, h as f32, 0.0, 1.0);
                rpass.set_pipeline(p);
                rpass.set_bind_group(0, group, &[]);
                rpass.draw(0..*vertices, 0..1);
            }
            _ => {
                return Err(Error::Shader(format!(
                    "pass `{}`: pipeline kind does not match the pass",
                    pass.name
                )));
            }
        }
        Ok(())
    }
}

impl Backend for Renderer {
    fn describe(&self) -> String {
        format!("wgpu on {}", self.adapter())
    }
    fn has_timestamps(&self) -> bool {
        self.timestamps
    }
    fn render(&mut self, frame: &FrameInput<'_>) -> Result<FrameOutput, BackendError> {
        Ok(Renderer::render(self, frame)?)
    }
    fn objects_created(&self) -> u64 {
        self.created
    }
    fn validated(&self) -> bool {
        self.validation
    }
    fn lose_device(&mut self) -> bool {
        self.device().destroy();
        true
    }
}
