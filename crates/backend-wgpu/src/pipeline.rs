//! Shader modules (the composed WGSL, compiled with the plan's override values), per pass the
//! bind group layout and the pipeline (compute, or raster with its targets), and the bind
//! groups of a plan. ash's `pipeline.rs` holds the same for Vulkan.

use crate::*;

/// A pipeline of one pass of one variant, with its bind group layout.
pub(crate) struct Pipeline {
    pub(crate) layout: wgpu::BindGroupLayout,
    pub(crate) kind: PipelineKind,
}

pub(crate) enum PipelineKind {
    Compute(wgpu::ComputePipeline),
    Raster(wgpu::RenderPipeline),
}

/// Module, variant, pass, and the formats of its colour targets (an external target may
/// differ from the graph's).
pub(crate) type PipelineKey = (String, String, String, Vec<wgpu::TextureFormat>);

impl Renderer {
    /// The shader module of a WGSL module (created once).
    pub(crate) fn module(&mut self, name: &str) -> Result<wgpu::ShaderModule, Error> {
        if let Some(m) = self.modules.get(name) {
            return Ok(m.clone());
        }
        let source = self
            .program
            .wgsl
            .get(name)
            .ok_or_else(|| Error::Shader(format!("the program has no WGSL module `{name}`")))?;
        let m = self
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(name),
                source: wgpu::ShaderSource::Wgsl(source.clone().into()),
            });
        self.created += 1;
        self.modules.insert(name.into(), m.clone());
        Ok(m)
    }

    pub(crate) fn pipeline_key(
        plan: &FramePlan,
        i: usize,
        target: Option<wgpu::TextureFormat>,
    ) -> PipelineKey {
        let pass = &plan.passes[i];
        let variant = plan
            .modules
            .get(&pass.module)
            .map(|m| m.variant.clone())
            .unwrap_or_default();
        let formats = match &pass.kind {
            PassKind::Compute { .. } => Vec::new(),
            PassKind::Raster { colors, .. } => colors
                .iter()
                .map(|c| {
                    let r = &plan.resources[c.resource];
                    match target {
                        Some(f) if r.external => f,
                        _ => convert::format(
                            r.format
                                .unwrap_or(stratus_graph::desc::TexelFormat::Rgba8Unorm),
                        ),
                    }
                })
                .collect(),
        };
        (pass.module.clone(), variant, pass.pipeline_name(), formats)
    }

    /// Creates (once per module variant, pass and target formats) a pass's pipeline.
    pub(crate) fn pipeline(
        &mut self,
        plan: &FramePlan,
        i: usize,
        target: Option<wgpu::TextureFormat>,
    ) -> Result<(), Error> {
        let key = Self::pipeline_key(plan, i, target);
        if self.pipelines.contains_key(&key) {
            return Ok(());
        }
        let pass = &plan.passes[i];
        let module = self.module(&pass.module)?;
        let visibility = match pass.kind {
            PassKind::Compute { .. } => wgpu::ShaderStages::COMPUTE,
            PassKind::Raster { .. } => wgpu::ShaderStages::VERTEX_FRAGMENT,
        };
        if let Some(b) = pass.bindings.iter().find(|b| b.group != 0) {
            return Err(Error::Shader(format!(
                "pass `{}`: `{}` is in @group({}); the backends bind group 0 only",
                pass.name, b.info.name, b.group
            )));
        }
        let entries: Vec<_> = pass
            .bindings
            .iter()
            .map(|b| wgpu::BindGroupLayoutEntry {
                binding: b.binding,
                visibility,
                ty: convert::binding_type(b, plan),
                count: None,
            })
            .collect();
        // A pipeline for another target format shares the pass's bind group layout, so the
        // pass's bind groups serve both.
        let base = Self::pipeline_key(plan, i, None);
        let layout = match self.pipelines.get(&base) {
            Some(p) if base != key => p.layout.clone(),
            _ => self
                .device
                .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                    label: Some(&pass.name),
                    entries: &entries,
                }),
        };
        let pipeline_layout = self
            .device
            .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(&pass.name),
                bind_group_layouts: &[Some(&layout)],
                immediate_size: 0,
            });
        // Exactly the variant's override values, so wgpu runs the code the SPIR-V holds.
        let overrides = plan.modules.get(&pass.module).map(|m| &m.overrides);
        let constants: Vec<(&str, f64)> = overrides
            .into_iter()
            .flatten()
            .map(|(k, v)| (k.as_str(), *v))
            .collect();
        let options = || wgpu::PipelineCompilationOptions {
            constants: &constants,
            zero_initialize_workgroup_memory: true,
        };
        let kind = match &pass.kind {
            PassKind::Compute { entry, .. } => PipelineKind::Compute(
                self.device
                    .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                        label: Some(&pass.name),
                        layout: Some(&pipeline_layout),
                        module: &module,
                        entry_point: Some(entry),
                        compilation_options: options(),
                        cache: None,
                    }),
            ),
            PassKind::Raster {
                vertex,
                fragment,
                colors,
                depth,
                ..
            } => {
                let targets: Vec<Option<wgpu::ColorTargetState>> = colors
                    .iter()
                    .zip(&key.3)
                    .map(|(c, &format)| {
                        Some(wgpu::ColorTargetState {
                            format,
                            blend: convert::blend(c.blend),
                            write_mask: wgpu::ColorWrites::ALL,
                        })
                    })
                    .collect();
                let depth_stencil = depth.as_ref().map(|d| wgpu::DepthStencilState {
                    format: wgpu::TextureFormat::Depth32Float,
                    depth_write_enabled: Some(d.write),
                    depth_compare: Some(convert::compare(d.compare)),
                    stencil: Default::default(),
                    bias: Default::default(),
                });
                PipelineKind::Raster(self.device.create_render_pipeline(
                    &wgpu::RenderPipelineDescriptor {
                        label: Some(&pass.name),
                        layout: Some(&pipeline_layout),
                        vertex: wgpu::VertexState {
                            module: &module,
                            entry_point: Some(vertex),
                            compilation_options: options(),
                            buffers: &[],
                        },
                        primitive: wgpu::PrimitiveState::default(),
                        depth_stencil,
                        multisample: wgpu::MultisampleState::default(),
                        fragment: Some(wgpu::FragmentState {
                            module: &module,
                            entry_point: Some(fragment),
                            compilation_options: options(),
                            targets: &targets,
                        }),
                        multiview_mask: None,
                        cache: None,
                    },
                ))
            }
        };
        self.created += 3;
        self.pipelines.insert(key, Pipeline { layout, kind });
        Ok(())
    }

    /// One bind group per pass and history parity (two where the plan has history resources:
    /// frame N binds half N % 2 as `name` and the other as `name.previous`).
    pub(crate) fn build_groups(&mut self, plan: &FramePlan) -> Result<(), Error> {
        let parities = if plan.has_history() { 2 } else { 1 };
        let mut groups = Vec::new();
        for (i, pass) in plan.passes.iter().enumerate() {
            let layout = &self.pipelines[&self.keys[i]].layout;
            let mut per_parity = Vec::new();
            for parity in 0..parities {
                let mut entries = Vec::new();
                for b in &pass.bindings {
                    let r = &plan.resources[b.resource];
                    let object = &self.resources[&r.name].object;
                    let resource = match object {
                        Object::Textures(_) if self.bound.contains_key(&r.name) => {
                            wgpu::BindingResource::TextureView(&self.bound[&r.name])
                        }
                        Object::Buffer(buf) => buf.as_entire_binding(),
                        Object::Sampler(s) => wgpu::BindingResource::Sampler(s),
                        Object::Textures(t) => {
                            let half = if r.lifetime == Lifetime::History {
                                history_half(parity, b.previous)
                            } else {
                                0
                            };
                            wgpu::BindingResource::TextureView(&t[half].1)
                        }
                    };
                    entries.push(wgpu::BindGroupEntry {
                        binding: b.binding,
                        resource,
                    });
                }
                per_parity.push(self.device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some(&pass.name),
                    layout,
                    entries: &entries,
                }));
                self.created += 1;
            }
            groups.push(per_parity);
        }
        self.groups = groups;
        Ok(())
    }
}
