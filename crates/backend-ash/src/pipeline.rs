//! Shader modules from the embedded committed SPIR-V (or from supplied words), and per pass
//! the descriptor set layouts (built from the plan's bindings, i.e. the manifest's reflection,
//! or from a supplied module's slots), the pipeline layout and the compute pipeline.

use std::{collections::BTreeMap, ffi::CString, io::Cursor};

use ash::vk;
use stratus_shaders::{Resource, plan::Binding};

use crate::{
    error::{Error, vk},
    frame::is_noise,
    interface::Descriptor,
};

include!(concat!(env!("OUT_DIR"), "/spirv.rs"));

/// The words of the committed SPIR-V file `name` (as the plan's `spv_file` names it).
pub(crate) fn spirv_words(name: &str) -> Result<Vec<u32>, Error> {
    let bytes = EMBEDDED_SPIRV
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, b)| *b)
        .ok_or_else(|| {
            Error::Shader(format!(
                "spirv-out/{name} was not embedded when stratus-backend-ash was built; run `cargo xtask build-shaders` and rebuild"
            ))
        })?;
    // `read_spv` copies into aligned words and checks the magic number and length.
    ash::util::read_spv(&mut Cursor::new(bytes))
        .map_err(|e| Error::Shader(format!("spirv-out/{name} is not SPIR-V: {e}")))
}

/// The descriptor type of a binding, from its reflected kind.
pub(crate) fn descriptor_type(b: &Binding) -> Result<vk::DescriptorType, Error> {
    Ok(match b.info.kind.as_str() {
        "uniform-buffer" => vk::DescriptorType::UNIFORM_BUFFER,
        "storage-buffer" => vk::DescriptorType::STORAGE_BUFFER,
        "sampled-texture" => vk::DescriptorType::SAMPLED_IMAGE,
        "storage-texture" => vk::DescriptorType::STORAGE_IMAGE,
        "sampler" => vk::DescriptorType::SAMPLER,
        other => {
            return Err(Error::Shader(format!(
                "binding {}/{} `{}` has kind `{other}`, which the ash backend cannot bind",
                b.group, b.binding, b.info.name
            )));
        }
    })
}

/// The view type of an image resource: the 3D noise textures, 2D for the rest.
pub(crate) fn view_type(resource: Resource) -> vk::ImageViewType {
    match resource {
        Resource::Shape | Resource::Detail => vk::ImageViewType::TYPE_3D,
        _ => vk::ImageViewType::TYPE_2D,
    }
}

/// Checks that what the WGSL declares at a binding is what the backend binds there: the
/// dimension of a texture, the format of a storage texture, the kind of resource. A drift
/// between the WGSL and the plan's resources fails here, not as garbage on screen.
pub(crate) fn check_binding(b: &Binding) -> Result<(), Error> {
    let wrong = |what: String| {
        Error::Shader(format!(
            "binding {}/{} `{}` declares {what}, but the frame binds {:?} there",
            b.group, b.binding, b.info.name, b.resource
        ))
    };
    let is_image = b.resource.texture_format().is_some();
    let kind = b.info.kind.as_str();
    match kind {
        "sampled-texture" | "storage-texture" if !is_image => {
            return Err(wrong(format!("a {kind}")));
        }
        "uniform-buffer" if b.resource != Resource::Frame => return Err(wrong(kind.into())),
        "storage-buffer" if b.resource != Resource::Stats => return Err(wrong(kind.into())),
        "sampler" if b.resource != Resource::NoiseSampler => return Err(wrong(kind.into())),
        _ => {}
    }
    if is_image {
        let dim = match view_type(b.resource) {
            vk::ImageViewType::TYPE_3D => "3d",
            _ => "2d",
        };
        if b.info.dimension.as_deref() != Some(dim) {
            return Err(wrong(format!(
                "dimension {:?}",
                b.info.dimension.as_deref().unwrap_or("none")
            )));
        }
        if kind == "storage-texture" && b.info.format.as_deref() != b.resource.texture_format() {
            return Err(wrong(format!(
                "format {:?}",
                b.info.format.as_deref().unwrap_or("none")
            )));
        }
        if kind == "storage-texture" && is_noise(b.resource) {
            return Err(wrong("a storage texture".into()));
        }
    }
    Ok(())
}

/// The pipeline of one pass of one variant.
pub(crate) struct PassPipeline {
    /// One layout per descriptor set (`@group`), 0 to the highest group the pass uses.
    pub set_layouts: Vec<vk::DescriptorSetLayout>,
    pub layout: vk::PipelineLayout,
    pub pipeline: vk::Pipeline,
}

impl PassPipeline {
    /// Builds the set layouts from the pass's descriptors, the pipeline layout, and the
    /// compute pipeline of `entry` in `module`.
    pub fn new(
        device: &ash::Device,
        module: vk::ShaderModule,
        entry: &str,
        descriptors: &[Descriptor<'_>],
    ) -> Result<Self, Error> {
        let mut built = Self {
            set_layouts: Vec::new(),
            layout: vk::PipelineLayout::null(),
            pipeline: vk::Pipeline::null(),
        };
        match built.build(device, module, entry, descriptors) {
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
        entry: &str,
        descriptors: &[Descriptor<'_>],
    ) -> Result<(), Error> {
        let mut groups: BTreeMap<u32, Vec<vk::DescriptorSetLayoutBinding>> = BTreeMap::new();
        for d in descriptors {
            groups.entry(d.set).or_default().push(
                vk::DescriptorSetLayoutBinding::default()
                    .binding(d.binding)
                    .descriptor_type(d.ty)
                    .descriptor_count(d.count)
                    .stage_flags(vk::ShaderStageFlags::COMPUTE),
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
        let entry = CString::new(entry)
            .map_err(|_| Error::Shader(format!("entry point `{entry}` contains NUL")))?;
        let stage = vk::PipelineShaderStageCreateInfo::default()
            .stage(vk::ShaderStageFlags::COMPUTE)
            .module(module)
            .name(&entry);
        let info = vk::ComputePipelineCreateInfo::default()
            .stage(stage)
            .layout(self.layout);
        // SAFETY: the module and layout are alive; the entry name outlives the call.
        let pipelines =
            unsafe { device.create_compute_pipelines(vk::PipelineCache::null(), &[info], None) }
                .map_err(|(_, result)| Error::Vulkan {
                    call: "vkCreateComputePipelines",
                    result,
                })?;
        self.pipeline = pipelines.first().copied().unwrap_or_default();
        Ok(())
    }

    /// Destroys the pipeline and its layouts (null handles are skipped by Vulkan).
    pub fn destroy(&mut self, device: &ash::Device) {
        // SAFETY: the caller guarantees the GPU no longer uses them.
        unsafe {
            device.destroy_pipeline(std::mem::take(&mut self.pipeline), None);
            device.destroy_pipeline_layout(std::mem::take(&mut self.layout), None);
            for layout in self.set_layouts.drain(..) {
                device.destroy_descriptor_set_layout(layout, None);
            }
        }
    }
}

/// Creates a shader module from the embedded SPIR-V file `name`.
pub(crate) fn shader_module(device: &ash::Device, name: &str) -> Result<vk::ShaderModule, Error> {
    module_from_words(device, &spirv_words(name)?)
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
