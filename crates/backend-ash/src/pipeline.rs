//! Shader modules (from the program's SPIR-V, or supplied words), and per pass the descriptor
//! set layouts (built from the plan's bindings, i.e. the manifest's reflection, or from a
//! supplied module's slots), the pipeline layout and the pipeline: compute, or graphics with
//! its render pass (one subpass; attachments as the graph's colour and depth targets say).
//!
//! The renderer's side of it lives here too: what a plan builds once (descriptor sets per pass
//! and history parity, framebuffers) and a pipeline per pass (as wgpu's `pipeline.rs`).

use crate::*;

use std::{collections::BTreeMap, ffi::CString};

use ash::vk;
use stratus_graph::{
    desc::{Blend, Compare, LoadOp},
    plan::{ColorTarget, DepthTarget},
};

use crate::{
    error::{Error, vk},
    interface::Descriptor,
};

/// The shader stages a pass's descriptors are visible to.
pub(crate) fn stages(raster: bool) -> vk::ShaderStageFlags {
    if raster {
        vk::ShaderStageFlags::VERTEX | vk::ShaderStageFlags::FRAGMENT
    } else {
        vk::ShaderStageFlags::COMPUTE
    }
}

/// What a graphics pipeline draws into: formats, blend, depth state, load operations.
pub(crate) struct RasterTargets<'a> {
    pub colors: Vec<(vk::Format, &'a ColorTarget)>,
    pub depth: Option<&'a DepthTarget>,
}

/// Which entry points a pass's pipeline runs.
pub(crate) enum Entries<'a> {
    Compute(&'a str),
    Raster {
        vertex: &'a str,
        fragment: &'a str,
        targets: RasterTargets<'a>,
    },
}

/// The pipeline of one pass of one variant (and its render pass, for a raster pass).
pub(crate) struct PassPipeline {
    /// One layout per descriptor set (`@group`), 0 to the highest group the pass uses.
    pub set_layouts: Vec<vk::DescriptorSetLayout>,
    pub layout: vk::PipelineLayout,
    pub pipeline: vk::Pipeline,
    /// Null for a compute pass.
    pub render_pass: vk::RenderPass,
}

impl PassPipeline {
    /// Builds the set layouts from the pass's descriptors, the pipeline layout, and the
    /// pipeline of `entries` in `module`.
    pub fn new(
        device: &ash::Device,
        module: vk::ShaderModule,
        entries: &Entries<'_>,
        descriptors: &[Descriptor<'_>],
    ) -> Result<Self, Error> {
        let mut built = Self {
            set_layouts: Vec::new(),
            layout: vk::PipelineLayout::null(),
            pipeline: vk::Pipeline::null(),
            render_pass: vk::RenderPass::null(),
        };
        match built.build(device, module, entries, descriptors) {
            Ok(()) => Ok(built),
            Err(e) => {
                built.destroy(device);
                Err(e)
            }
        }
    }

    fn build(
        &mut self,
        device: &ash::Device,
        module: vk::ShaderModule,
        entries: &Entries<'_>,
        descriptors: &[Descriptor<'_>],
    ) -> Result<(), Error> {
        let visible = stages(matches!(entries, Entries::Raster { .. }));
        let mut groups: BTreeMap<u32, Vec<vk::DescriptorSetLayoutBinding>> = BTreeMap::new();
        for d in descriptors {
            groups.entry(d.set).or_default().push(
                vk::DescriptorSetLayoutBinding::default()
                    .binding(d.binding)
                    .descriptor_type(d.ty)
                    .descriptor_count(d.count)
                    .stage_flags(visible),
            );
        }
        let sets = groups.keys().next_back().map_or(0, |g| g + 1);
        for group in 0..sets {
            let bindings = groups.get(&group).map_or(&[][..], |v| v.as_slice());
            let info = vk::DescriptorSetLayoutCreateInfo::default().bindings(bindings);
            // SAFETY: valid device; the bindings outlive the call.
            let layout = unsafe { device.create_descriptor_set_layout(&info, None) }
                .map_err(vk("vkCreateDescriptorSetLayout"))?;
            self.set_layouts.push(layout);
        }
        let info = vk::PipelineLayoutCreateInfo::default().set_layouts(&self.set_layouts);
        // SAFETY: valid device; the set layouts are alive.
        self.layout = unsafe { device.create_pipeline_layout(&info, None) }
            .map_err(vk("vkCreatePipelineLayout"))?;
        let name = |entry: &str| {
            CString::new(entry)
                .map_err(|_| Error::Shader(format!("entry point `{entry}` contains NUL")))
        };
        match entries {
            Entries::Compute(entry) => {
                let entry = name(entry)?;
                let stage = vk::PipelineShaderStageCreateInfo::default()
                    .stage(vk::ShaderStageFlags::COMPUTE)
                    .module(module)
                    .name(&entry);
                let info = vk::ComputePipelineCreateInfo::default()
                    .stage(stage)
                    .layout(self.layout);
                // SAFETY: the module and layout are alive; the entry name outlives the call.
                let pipelines = unsafe {
                    device.create_compute_pipelines(vk::PipelineCache::null(), &[info], None)
                }
                .map_err(|(_, result)| Error::Vulkan {
                    call: "vkCreateComputePipelines",
                    result,
                })?;
                self.pipeline = pipelines.first().copied().unwrap_or_default();
            }
            Entries::Raster {
                vertex,
                fragment,
                targets,
            } => {
                self.render_pass = render_pass(device, targets)?;
                let (vertex, fragment) = (name(vertex)?, name(fragment)?);
                let stages = [
                    vk::PipelineShaderStageCreateInfo::default()
                        .stage(vk::ShaderStageFlags::VERTEX)
                        .module(module)
                        .name(&vertex),
                    vk::PipelineShaderStageCreateInfo::default()
                        .stage(vk::ShaderStageFlags::FRAGMENT)
                        .module(module)
                        .name(&fragment),
                ];
                let vertex_input = vk::PipelineVertexInputStateCreateInfo::default();
                let assembly = vk::PipelineInputAssemblyStateCreateInfo::default()
                    .topology(vk::PrimitiveTopology::TRIANGLE_LIST);
                let viewport = vk::PipelineViewportStateCreateInfo::default()
                    .viewport_count(1)
                    .scissor_count(1);
                // As wgpu's default primitive state: no culling, counter-clockwise front.
                let raster = vk::PipelineRasterizationStateCreateInfo::default()
                    .polygon_mode(vk::PolygonMode::FILL)
                    .cull_mode(vk::CullModeFlags::NONE)
                    .front_face(vk::FrontFace::COUNTER_CLOCKWISE)
                    .line_width(1.0);
                let multisample = vk::PipelineMultisampleStateCreateInfo::default()
                    .rasterization_samples(vk::SampleCountFlags::TYPE_1);
                let depth = targets.depth.map(|d| {
                    vk::PipelineDepthStencilStateCreateInfo::default()
                        .depth_test_enable(true)
                        .depth_write_enable(d.write)
                        .depth_compare_op(compare(d.compare))
                });
                let blends: Vec<_> = targets.colors.iter().map(|(_, c)| blend(c.blend)).collect();
                let blend_state =
                    vk::PipelineColorBlendStateCreateInfo::default().attachments(&blends);
                let dynamic = [vk::DynamicState::VIEWPORT, vk::DynamicState::SCISSOR];
                let dynamic =
                    vk::PipelineDynamicStateCreateInfo::default().dynamic_states(&dynamic);
                let mut info = vk::GraphicsPipelineCreateInfo::default()
                    .stages(&stages)
                    .vertex_input_state(&vertex_input)
                    .input_assembly_state(&assembly)
                    .viewport_state(&viewport)
                    .rasterization_state(&raster)
                    .multisample_state(&multisample)
                    .color_blend_state(&blend_state)
                    .dynamic_state(&dynamic)
                    .layout(self.layout)
                    .render_pass(self.render_pass)
                    .subpass(0);
                if let Some(depth) = &depth {
                    info = info.depth_stencil_state(depth);
                }
                // SAFETY: every state, the module, layout and render pass are alive.
                let pipelines = unsafe {
                    device.create_graphics_pipelines(vk::PipelineCache::null(), &[info], None)
                }
                .map_err(|(_, result)| Error::Vulkan {
                    call: "vkCreateGraphicsPipelines",
                    result,
                })?;
                self.pipeline = pipelines.first().copied().unwrap_or_default();
            }
        }
        Ok(())
    }

    /// Destroys the pipeline, its layouts and render pass (null handles are skipped).
    pub fn destroy(&mut self, device: &ash::Device) {
        // SAFETY: the caller guarantees the GPU no longer uses them.
        unsafe {
            device.destroy_pipeline(std::mem::take(&mut self.pipeline), None);
            device.destroy_pipeline_layout(std::mem::take(&mut self.layout), None);
            device.destroy_render_pass(std::mem::take(&mut self.render_pass), None);
            for layout in self.set_layouts.drain(..) {
                device.destroy_descriptor_set_layout(layout, None);
            }
        }
    }
}

/// One subpass writing the colour targets (and depth). The tracker moves every attachment to
/// its attachment layout before the pass begins, so the render pass itself changes no layout.
fn render_pass(device: &ash::Device, targets: &RasterTargets<'_>) -> Result<vk::RenderPass, Error> {
    let load = |l: LoadOp| match l {
        LoadOp::Clear => vk::AttachmentLoadOp::CLEAR,
        LoadOp::Load => vk::AttachmentLoadOp::LOAD,
    };
    let mut attachments = Vec::new();
    let mut color_refs = Vec::new();
    for (format, c) in &targets.colors {
        color_refs.push(
            vk::AttachmentReference::default()
                .attachment(attachments.len() as u32)
                .layout(vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL),
        );
        attachments.push(
            vk::AttachmentDescription::default()
                .format(*format)
                .samples(vk::SampleCountFlags::TYPE_1)
                .load_op(load(c.load))
                .store_op(vk::AttachmentStoreOp::STORE)
                .stencil_load_op(vk::AttachmentLoadOp::DONT_CARE)
                .stencil_store_op(vk::AttachmentStoreOp::DONT_CARE)
                .initial_layout(vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL)
                .final_layout(vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL),
        );
    }
    let depth_ref = targets.depth.map(|d| {
        let r = vk::AttachmentReference::default()
            .attachment(attachments.len() as u32)
            .layout(vk::ImageLayout::DEPTH_STENCIL_ATTACHMENT_OPTIMAL);
        attachments.push(
            vk::AttachmentDescription::default()
                .format(vk::Format::D32_SFLOAT)
                .samples(vk::SampleCountFlags::TYPE_1)
                .load_op(load(d.load))
                .store_op(vk::AttachmentStoreOp::STORE)
                .stencil_load_op(vk::AttachmentLoadOp::DONT_CARE)
                .stencil_store_op(vk::AttachmentStoreOp::DONT_CARE)
                .initial_layout(vk::ImageLayout::DEPTH_STENCIL_ATTACHMENT_OPTIMAL)
                .final_layout(vk::ImageLayout::DEPTH_STENCIL_ATTACHMENT_OPTIMAL),
        );
        r
    });
    let mut subpass = vk::SubpassDescription::default()
        .pipeline_bind_point(vk::PipelineBindPoint::GRAPHICS)
        .color_attachments(&color_refs);
    if let Some(r) = &depth_ref {
        subpass = subpass.depth_stencil_attachment(r);
    }
    let subpasses = [subpass];
    let info = vk::RenderPassCreateInfo::default()
        .attachments(&attachments)
        .subpasses(&subpasses);
    // SAFETY: valid device; everything the info points at outlives the call.
    unsafe { device.create_render_pass(&info, None) }.map_err(vk("vkCreateRenderPass"))
}

/// The blend state of a colour target (as backend-wgpu's).
fn blend(b: Blend) -> vk::PipelineColorBlendAttachmentState {
    let all = vk::ColorComponentFlags::RGBA;
    let state = vk::PipelineColorBlendAttachmentState::default().color_write_mask(all);
    match b {
        Blend::Replace => state,
        Blend::Transmittance => state
            .blend_enable(true)
            .src_color_blend_factor(vk::BlendFactor::ONE)
            .dst_color_blend_factor(vk::BlendFactor::SRC_ALPHA)
            .color_blend_op(vk::BlendOp::ADD)
            .src_alpha_blend_factor(vk::BlendFactor::ZERO)
            .dst_alpha_blend_factor(vk::BlendFactor::ONE)
            .alpha_blend_op(vk::BlendOp::ADD),
        Blend::Additive => state
            .blend_enable(true)
            .src_color_blend_factor(vk::BlendFactor::ONE)
            .dst_color_blend_factor(vk::BlendFactor::ONE)
            .color_blend_op(vk::BlendOp::ADD)
            .src_alpha_blend_factor(vk::BlendFactor::ONE)
            .dst_alpha_blend_factor(vk::BlendFactor::ONE)
            .alpha_blend_op(vk::BlendOp::ADD),
        Blend::Over => state
            .blend_enable(true)
            .src_color_blend_factor(vk::BlendFactor::ONE)
            .dst_color_blend_factor(vk::BlendFactor::ONE_MINUS_SRC_ALPHA)
            .color_blend_op(vk::BlendOp::ADD)
            .src_alpha_blend_factor(vk::BlendFactor::ONE)
            .dst_alpha_blend_factor(vk::BlendFactor::ONE_MINUS_SRC_ALPHA)
            .alpha_blend_op(vk::BlendOp::ADD),
    }
}

fn compare(c: Compare) -> vk::CompareOp {
    match c {
        Compare::Always => vk::CompareOp::ALWAYS,
        Compare::Less => vk::CompareOp::LESS,
        Compare::LessEqual => vk::CompareOp::LESS_OR_EQUAL,
        Compare::Greater => vk::CompareOp::GREATER,
    }
}

/// Creates a shader module from SPIR-V words.
pub(crate) fn module_from_words(
    device: &ash::Device,
    words: &[u32],
) -> Result<vk::ShaderModule, Error> {
    if words.first() != Some(&0x0723_0203) {
        return Err(Error::Shader(
            "the supplied shader is not SPIR-V (no magic number)".into(),
        ));
    }
    let info = vk::ShaderModuleCreateInfo::default().code(words);
    // SAFETY: valid device; `words` is SPIR-V (magic number checked) and outlives the call.
    unsafe { device.create_shader_module(&info, None) }.map_err(vk("vkCreateShaderModule"))
}

// The renderer's pipelines and what a plan builds once: descriptor sets per pass and history
// parity, framebuffers, and a pipeline per pass (the program's SPIR-V or a supplied module).

/// Which pipeline a pass runs: the program's SPIR-V, by file and pass, or a supplied module's,
/// by a hash of the [`PassShader`] (words, entry point and slots).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub(crate) enum PipelineKey {
    Program { spv: String, pass: String },
    Supplied(u64),
}

/// What was built for one plan (and set of shaders): descriptor sets and framebuffers.
pub(crate) struct State {
    pub(crate) plan: FramePlan,
    pub(crate) shaders: Shaders,
    pub(crate) keys: Vec<PipelineKey>,
    pub(crate) pool: vk::DescriptorPool,
    /// Per pass, per history parity, one set per `@group`.
    pub(crate) sets: Vec<Vec<Vec<vk::DescriptorSet>>>,
    /// Per raster pass, per history parity (empty for compute passes).
    pub(crate) framebuffers: Vec<Vec<vk::Framebuffer>>,
    /// Supplied modules only: a nearest sampler for non-filterable combined images, and the
    /// zeros naga's HLSL sampler index buffers read.
    pub(crate) nearest: vk::Sampler,
    pub(crate) indices: Option<GpuBuffer>,
}

/// The supplied module of pass `i`: supplied modules replace the compute passes, in order;
/// raster passes run the program's SPIR-V.
pub(crate) fn supplied<'s>(
    shaders: &'s Shaders,
    plan: &FramePlan,
    i: usize,
) -> Option<&'s PassShader> {
    let Shaders::PerPass(list) = shaders else {
        return None;
    };
    if !matches!(plan.passes[i].kind, PassKind::Compute { .. }) {
        return None;
    }
    let k = plan.passes[..i]
        .iter()
        .filter(|p| matches!(p.kind, PassKind::Compute { .. }))
        .count();
    list.get(k)
}

/// The pipeline stage of a pass's shaders.
pub(crate) fn shader_stage(raster: bool) -> vk::PipelineStageFlags {
    if raster {
        vk::PipelineStageFlags::VERTEX_SHADER | vk::PipelineStageFlags::FRAGMENT_SHADER
    } else {
        vk::PipelineStageFlags::COMPUTE_SHADER
    }
}

impl Renderer {
    /// Pipelines (cached), the descriptor pool and sets (one per pass, parity and group),
    /// and the framebuffers of raster passes.
    pub(crate) fn build_state(&mut self, plan: &FramePlan, shaders: &Shaders) -> Result<(), Error> {
        let mut keys = Vec::new();
        for (i, pass) in plan.passes.iter().enumerate() {
            keys.push(self.pipeline(plan, pass, supplied(shaders, plan, i))?);
        }
        let mut state = State {
            plan: plan.clone(),
            shaders: shaders.clone(),
            keys,
            pool: vk::DescriptorPool::null(),
            sets: Vec::new(),
            framebuffers: Vec::new(),
            nearest: vk::Sampler::null(),
            indices: None,
        };
        let result = self.build_sets(&mut state, shaders);
        let result = result.and_then(|()| self.build_framebuffers(&mut state));
        self.state = Some(state);
        result
    }

    pub(crate) fn build_sets(&mut self, state: &mut State, shaders: &Shaders) -> Result<(), Error> {
        let plan = &state.plan;
        let parities = if plan.has_history() { 2 } else { 1 };
        let device = &self.gpu.device;
        let per_pass = plan
            .passes
            .iter()
            .enumerate()
            .map(|(i, pass)| {
                let slots = supplied(shaders, plan, i).map(|s| &s.slots[..]);
                descriptors(plan, pass, slots)
            })
            .collect::<Result<Vec<_>, Error>>()?;
        if let Shaders::PerPass(_) = shaders {
            // For images that a supplied module reads through a combined image sampler but
            // that are not filterable (GLSL has no image without a sampler to load from).
            let info = sampler_info(stratus_graph::plan::SamplerDesc {
                filter: stratus_graph::desc::Filter::Nearest,
                address: stratus_graph::desc::AddressMode::Repeat,
            });
            // SAFETY: valid device and info.
            state.nearest =
                unsafe { device.create_sampler(&info, None) }.map_err(vk("vkCreateSampler"))?;
            self.created += 1;
            let words = per_pass
                .iter()
                .flatten()
                .filter_map(|d| match d.content {
                    Content::SamplerIndices(n) => Some(n),
                    _ => None,
                })
                .max()
                .unwrap_or(0);
            if words > 0 {
                let mut b = GpuBuffer::new(
                    device,
                    &mut self.gpu.allocator,
                    "sampler indices",
                    u64::from(words) * 4,
                    vk::BufferUsageFlags::STORAGE_BUFFER,
                    MemoryLocation::CpuToGpu,
                )?;
                b.mapped()?.fill(0);
                state.indices = Some(b);
                self.created += 1;
            }
        }
        for (i, list) in per_pass.iter().enumerate() {
            self.check_limits(&plan.passes[i], list)?;
        }
        let mut counts: HashMap<vk::DescriptorType, u32> = HashMap::new();
        let mut max_sets = 0;
        for (key, list) in state.keys.iter().zip(&per_pass) {
            for d in list {
                *counts.entry(d.ty).or_default() += d.count * parities;
            }
            max_sets += self.pipelines[key].set_layouts.len() as u32 * parities;
        }
        let sizes: Vec<vk::DescriptorPoolSize> = counts
            .iter()
            .map(|(&ty, &n)| vk::DescriptorPoolSize::default().ty(ty).descriptor_count(n))
            .collect();
        if max_sets > 0 && !sizes.is_empty() {
            let info = vk::DescriptorPoolCreateInfo::default()
                .max_sets(max_sets)
                .pool_sizes(&sizes);
            // SAFETY: valid device and info.
            state.pool = unsafe { device.create_descriptor_pool(&info, None) }
                .map_err(vk("vkCreateDescriptorPool"))?;
            self.created += 1;
        }
        let first_sampler = plan
            .resources
            .iter()
            .find_map(|r| match self.resources.get(&r.name).map(|g| &g.object) {
                Some(Object::Sampler(s)) => Some(*s),
                _ => None,
            })
            .unwrap_or_default();
        enum Info {
            Buffer(vk::DescriptorBufferInfo),
            Images(Vec<vk::DescriptorImageInfo>),
        }
        let buffer = |b: vk::Buffer| {
            Info::Buffer(
                vk::DescriptorBufferInfo::default()
                    .buffer(b)
                    .offset(0)
                    .range(vk::WHOLE_SIZE),
            )
        };
        let mut infos = Vec::new();
        for (i, (pass, list)) in plan.passes.iter().zip(&per_pass).enumerate() {
            let layouts = &self.pipelines[&state.keys[i]].set_layouts;
            let raster = matches!(pass.kind, PassKind::Raster { .. });
            let mut per_parity = Vec::new();
            for parity in 0..parities {
                if layouts.is_empty() {
                    per_parity.push(Vec::new());
                    continue;
                }
                let info = vk::DescriptorSetAllocateInfo::default()
                    .descriptor_pool(state.pool)
                    .set_layouts(layouts);
                // SAFETY: the pool has room for every set of the plan.
                let sets = unsafe { device.allocate_descriptor_sets(&info) }
                    .map_err(vk("vkAllocateDescriptorSets"))?;
                self.created += sets.len() as u64;
                for d in list {
                    let missing = |what: String| {
                        Error::Shader(format!(
                            "set {} binding {} of pass `{}` needs {what}, which the frame does not have",
                            d.set, d.binding, pass.name
                        ))
                    };
                    let image = |name: &str| -> Result<(vk::DescriptorImageInfo, bool), Error> {
                        // `name.previous`: the pair's resource; the binding picks the half.
                        let r = self
                            .resources
                            .get(name.strip_suffix(PREVIOUS).unwrap_or(name))
                            .ok_or_else(|| missing(format!("`{name}`")))?;
                        let Object::Images(images) = &r.object else {
                            return Err(missing(format!("image `{name}`")));
                        };
                        let b = d.plan.ok_or_else(|| missing(format!("`{name}`")))?;
                        let half = if r.made.desc.lifetime == Lifetime::History {
                            history_half(parity as u64, b.previous)
                        } else {
                            0
                        };
                        let layout = Use::of_binding(b, shader_stage(raster))
                            .ok_or_else(|| missing(format!("`{name}`")))?
                            .layout;
                        let filterable = r.made.desc.format.is_some_and(|f| f.filterable());
                        Ok((
                            vk::DescriptorImageInfo::default()
                                .image_view(images[half].view)
                                .image_layout(layout),
                            filterable,
                        ))
                    };
                    let info = match &d.content {
                        Content::Plan(name) => match self
                            .resources
                            .get(name.strip_suffix(PREVIOUS).unwrap_or(name))
                            .map(|r| &r.object)
                        {
                            Some(Object::Uniform) => {
                                buffer(self.uniform.as_ref().expect("created by prepare").buffer)
                            }
                            Some(Object::Buffer(b)) => buffer(b.buffer),
                            Some(Object::Sampler(s)) => {
                                Info::Images(vec![vk::DescriptorImageInfo::default().sampler(*s)])
                            }
                            Some(Object::Images(_)) => Info::Images(vec![image(name)?.0]),
                            None => return Err(missing(format!("`{name}`"))),
                        },
                        Content::CombinedWithSampler(name) => {
                            let (info, filterable) = image(name)?;
                            let sampler = if filterable {
                                first_sampler
                            } else {
                                state.nearest
                            };
                            Info::Images(vec![info.sampler(sampler)])
                        }
                        Content::SamplerArray(n) => Info::Images(vec![
                            vk::DescriptorImageInfo::default()
                                .sampler(first_sampler);
                            *n as usize
                        ]),
                        Content::SamplerIndices(_) => buffer(
                            state
                                .indices
                                .as_ref()
                                .ok_or_else(|| missing("a sampler index buffer".into()))?
                                .buffer,
                        ),
                    };
                    let set = *sets
                        .get(d.set as usize)
                        .ok_or_else(|| missing(format!("descriptor set {}", d.set)))?;
                    infos.push((set, d.binding, d.ty, info));
                }
                per_parity.push(sets);
            }
            state.sets.push(per_parity);
        }
        let writes: Vec<_> = infos
            .iter()
            .map(|(set, binding, ty, info)| {
                let write = vk::WriteDescriptorSet::default()
                    .dst_set(*set)
                    .dst_binding(*binding)
                    .descriptor_type(*ty);
                match info {
                    Info::Buffer(i) => write.buffer_info(std::slice::from_ref(i)),
                    Info::Images(i) => write.image_info(i),
                }
            })
            .collect();
        // SAFETY: every set, buffer, view and sampler is alive and matches its layout.
        unsafe { device.update_descriptor_sets(&writes, &[]) };
        Ok(())
    }

    pub(crate) fn build_framebuffers(&mut self, state: &mut State) -> Result<(), Error> {
        let plan = &state.plan;
        let parities = if plan.has_history() { 2 } else { 1 };
        for (i, pass) in plan.passes.iter().enumerate() {
            let PassKind::Raster { colors, depth, .. } = &pass.kind else {
                state.framebuffers.push(Vec::new());
                continue;
            };
            let mut list = Vec::new();
            for parity in 0..parities {
                let targets = colors
                    .iter()
                    .map(|c| c.resource)
                    .chain(depth.iter().map(|d| d.resource));
                let mut views = Vec::new();
                let mut extent = vk::Extent3D::default();
                for index in targets {
                    let image = self.target(plan, index, parity as u64)?;
                    views.push(image.view);
                    extent = image.extent;
                }
                let info = vk::FramebufferCreateInfo::default()
                    .render_pass(self.pipelines[&state.keys[i]].render_pass)
                    .attachments(&views)
                    .width(extent.width)
                    .height(extent.height)
                    .layers(1);
                // SAFETY: the render pass and views are alive and compatible.
                let fb = unsafe { self.gpu.device.create_framebuffer(&info, None) }
                    .map_err(vk("vkCreateFramebuffer"))?;
                self.created += 1;
                list.push(fb);
            }
            state.framebuffers.push(list);
        }
        Ok(())
    }

    /// Creates (once per SPIR-V file and pass, or per supplied module) the shader module,
    /// the descriptor set layouts (from the plan's bindings or the module's slots) and the
    /// pipeline of a pass. Returns its key.
    pub(crate) fn pipeline(
        &mut self,
        plan: &FramePlan,
        pass: &Pass,
        shader: Option<&PassShader>,
    ) -> Result<PipelineKey, Error> {
        let spv = plan
            .modules
            .get(&pass.module)
            .map(|m| m.spv_file.clone())
            .ok_or_else(|| {
                Error::Shader(format!(
                    "pass `{}`: no variant of module `{}`",
                    pass.name, pass.module
                ))
            })?;
        let key = match shader {
            None => PipelineKey::Program {
                spv: spv.clone(),
                pass: pass.pipeline_name(),
            },
            Some(s) => {
                let mut h = std::collections::hash_map::DefaultHasher::new();
                s.hash(&mut h);
                pass.name.hash(&mut h);
                PipelineKey::Supplied(h.finish())
            }
        };
        if self.pipelines.contains_key(&key) {
            return Ok(key);
        }
        let list = descriptors(plan, pass, shader.map(|s| &s.slots[..]))?;
        self.check_limits(pass, &list)?;
        let colors: Vec<_>;
        let entries = match &pass.kind {
            PassKind::Compute { entry, .. } => {
                Entries::Compute(shader.map_or(entry.as_str(), |s| s.entry.as_str()))
            }
            PassKind::Raster {
                vertex,
                fragment,
                colors: targets,
                depth,
                ..
            } => {
                if shader.is_some() {
                    return Err(Error::Shader(format!(
                        "pass `{}`: supplied modules run compute passes only",
                        pass.name
                    )));
                }
                colors = targets
                    .iter()
                    .map(|c| {
                        let f = plan.resources[c.resource]
                            .format
                            .unwrap_or(stratus_graph::desc::TexelFormat::Rgba8Unorm);
                        (vk_format(f), c)
                    })
                    .collect();
                Entries::Raster {
                    vertex,
                    fragment,
                    targets: RasterTargets {
                        colors,
                        depth: depth.as_ref(),
                    },
                }
            }
        };
        let device = &self.gpu.device;
        let p = match shader {
            None => {
                let module = match self.modules.get(&spv) {
                    Some(&m) => m,
                    None => {
                        let words = self.program.spirv.get(&spv).ok_or_else(|| {
                            Error::Shader(format!(
                                "the program has no {spv}; run `cargo xtask build-shaders` and rebuild"
                            ))
                        })?;
                        let m = module_from_words(device, words)?;
                        self.created += 1;
                        self.modules.insert(spv.clone(), m);
                        m
                    }
                };
                PassPipeline::new(device, module, &entries, &list)?
            }
            Some(s) => {
                // The pipeline keeps what it needs; the module can go right away.
                let module = module_from_words(device, &s.spirv)?;
                let p = PassPipeline::new(device, module, &entries, &list);
                // SAFETY: only the pipeline creation used the module.
                unsafe { device.destroy_shader_module(module, None) };
                p?
            }
        };
        self.created += 3;
        self.pipelines.insert(key.clone(), p);
        Ok(key)
    }

    /// Destroys what was built for the current plan (the GPU is idle).
    pub(crate) fn drop_state(&mut self) {
        if let Some(mut state) = self.state.take() {
            let device = &self.gpu.device;
            // SAFETY: the GPU is idle (every submit is waited for); frees the sets too.
            unsafe {
                device.destroy_descriptor_pool(state.pool, None);
                for fb in state.framebuffers.iter().flatten() {
                    device.destroy_framebuffer(*fb, None);
                }
                device.destroy_sampler(state.nearest, None);
            }
            if let Some(mut b) = state.indices.take() {
                b.destroy(device, &mut self.gpu.allocator);
            }
        }
    }
}
