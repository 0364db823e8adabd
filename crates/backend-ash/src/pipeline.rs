//! Shader modules (from the program's SPIR-V, or supplied words), and per pass the descriptor
//! set layouts (built from the plan's bindings, i.e. the manifest's reflection, or from a
//! supplied module's slots), the pipeline layout and the pipeline: compute, or graphics with
//! its render pass (one subpass; attachments as the graph's colour and depth targets say).

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
