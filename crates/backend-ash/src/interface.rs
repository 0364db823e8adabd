//! Where a frame's SPIR-V comes from, and what each pass's pipeline binds where.
//!
//! [`Renderer::render`](crate::Renderer::render) runs the program's
//! `<module>.<variant>.spv`, whose interface is the plan's bindings (set = `@group`,
//! binding = `@binding`, separate samplers). With the `conformance` feature,
//! `Renderer::render_with` can instead run SPIR-V supplied per pass, such as naga's GLSL or HLSL compiled by
//! glslang, whose interface differs from the WGSL's: GLSL has no separate samplers (each
//! sampled texture is a combined image sampler), and naga's HLSL reaches its samplers through
//! a sampler heap and an index buffer. A [`PassShader`] therefore lists every descriptor its
//! SPIR-V declares as a [`Slot`]; the backend builds the layouts from the slots and binds the
//! frame's resources there. The validation layer checks the slots against the SPIR-V when the
//! pipeline is created and when it is dispatched.

use ash::vk;
use stratus_graph::{
    FramePlan, Program,
    manifest::BindingKind,
    plan::{Binding, Pass, PassKind, bound_name},
};

use crate::error::Error;

/// The SPIR-V a frame runs.
#[cfg_attr(not(feature = "conformance"), allow(dead_code))]
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
pub enum Shaders {
    /// The program's `<module>.<variant>.spv` the plan names, bound as the plan's bindings
    /// say (what [`Renderer::render`](crate::Renderer::render) runs).
    #[default]
    Committed,
    /// One module per compute pass of the plan, in plan order (raster passes run the
    /// program's SPIR-V).
    PerPass(Vec<PassShader>),
}

/// The SPIR-V of one pass from somewhere other than `spirv-out/*.spv`.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct PassShader {
    /// The module's words.
    pub spirv: Vec<u32>,
    /// Its entry point (glslang names a GLSL entry point `main`).
    pub entry: String,
    /// Every descriptor the module declares, and what to bind there. Descriptors the module
    /// does not use may be listed too; one it uses and this list lacks is a validation error.
    pub slots: Vec<Slot>,
}

impl PassShader {
    /// The program's module of compute pass `pass`, bound as the plan says: what
    /// [`Renderer::render`](crate::Renderer::render) runs, as a supplied module.
    #[cfg_attr(not(feature = "conformance"), allow(dead_code))]
    pub fn from_program(program: &Program, plan: &FramePlan, pass: &Pass) -> Result<Self, Error> {
        let PassKind::Compute { entry, .. } = &pass.kind else {
            return Err(Error::Shader(format!(
                "pass `{}`: supplied modules run compute passes only",
                pass.name
            )));
        };
        let spv = plan
            .modules
            .get(&pass.module)
            .map(|m| &m.spv_file)
            .and_then(|f| program.spirv.get(f))
            .ok_or_else(|| {
                Error::Shader(format!(
                    "the program has no SPIR-V for pass `{}`",
                    pass.name
                ))
            })?;
        Ok(Self {
            spirv: spv.clone(),
            entry: entry.clone(),
            slots: pass
                .bindings
                .iter()
                .map(|b| Slot {
                    set: b.group,
                    binding: b.binding,
                    content: SlotContent::Plan(bound_name(plan, b)),
                })
                .collect(),
        })
    }
}

/// One descriptor of a supplied module: its `DescriptorSet` and `Binding` decorations, and
/// what the frame binds there.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Slot {
    /// Descriptor set.
    pub set: u32,
    /// Binding within the set.
    pub binding: u32,
    /// What is bound.
    pub content: SlotContent,
}

/// What the frame binds at a [`Slot`].
#[cfg_attr(not(feature = "conformance"), allow(dead_code))]
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum SlotContent {
    /// The frame's resource of this name (`name.previous`: last frame's half of a history
    /// pair), of the kind the pass's plan binding declares
    /// (uniform buffer, sampled or storage image, storage buffer, sampler).
    Plan(String),
    /// A sampled image of the frame combined with a sampler (GLSL's `sampler2D`): the noise
    /// sampler for filterable images, a nearest one for the others (which the WGSL only loads).
    CombinedWithSampler(String),
    /// An array of this many samplers, every element the noise sampler (naga's HLSL
    /// `nagaSamplerHeap`).
    SamplerArray(u32),
    /// A read-only storage buffer of this many `u32` zeros (naga's HLSL
    /// `nagaGroup<N>SamplerIndexArray`: the sampler of every binding is heap element 0).
    SamplerIndices(u32),
}

/// The descriptor type of a binding, from its reflected kind.
pub(crate) fn descriptor_type(b: &Binding) -> Result<vk::DescriptorType, Error> {
    Ok(match b.info.kind {
        BindingKind::UniformBuffer => vk::DescriptorType::UNIFORM_BUFFER,
        BindingKind::StorageBuffer => vk::DescriptorType::STORAGE_BUFFER,
        BindingKind::SampledTexture => vk::DescriptorType::SAMPLED_IMAGE,
        BindingKind::StorageTexture => vk::DescriptorType::STORAGE_IMAGE,
        BindingKind::Sampler => vk::DescriptorType::SAMPLER,
        BindingKind::Other => {
            return Err(Error::Shader(format!(
                "binding {}/{} `{}` has a type the ash backend cannot bind",
                b.group, b.binding, b.info.name
            )));
        }
    })
}

/// A slot resolved against the pass: its Vulkan descriptor type and count, and the plan
/// binding it stands for (`None` for the sampler heap and its index buffer).
pub(crate) struct Descriptor<'p> {
    pub set: u32,
    pub binding: u32,
    pub ty: vk::DescriptorType,
    pub count: u32,
    pub content: SlotContent,
    pub plan: Option<&'p Binding>,
}

/// The descriptors of `pass`: the plan's bindings for the program's SPIR-V, else `slots`.
pub(crate) fn descriptors<'p>(
    plan: &FramePlan,
    pass: &'p Pass,
    slots: Option<&[Slot]>,
) -> Result<Vec<Descriptor<'p>>, Error> {
    let Some(slots) = slots else {
        return pass
            .bindings
            .iter()
            .map(|b| {
                Ok(Descriptor {
                    set: b.group,
                    binding: b.binding,
                    ty: descriptor_type(b)?,
                    count: 1,
                    content: SlotContent::Plan(bound_name(plan, b)),
                    plan: Some(b),
                })
            })
            .collect();
    };
    let mut out: Vec<Descriptor<'p>> = Vec::new();
    for slot in slots {
        if out
            .iter()
            .any(|d| (d.set, d.binding) == (slot.set, slot.binding))
        {
            return Err(Error::Shader(format!(
                "pass `{}`: two slots at set {} binding {}",
                pass.name, slot.set, slot.binding
            )));
        }
        let plan_binding = |r: &str| {
            pass.bindings
                .iter()
                .find(|b| bound_name(plan, b) == r)
                .ok_or_else(|| {
                    Error::Shader(format!(
                        "pass `{}`: slot {}/{} binds `{r}`, which the pass's plan does not use",
                        pass.name, slot.set, slot.binding
                    ))
                })
        };
        let (ty, count, bound) = match &slot.content {
            SlotContent::Plan(r) => {
                let b = plan_binding(r)?;
                (descriptor_type(b)?, 1, Some(b))
            }
            SlotContent::CombinedWithSampler(r) => {
                let b = plan_binding(r)?;
                if b.info.kind != BindingKind::SampledTexture {
                    return Err(Error::Shader(format!(
                        "pass `{}`: slot {}/{} combines `{r}` with a sampler, but the WGSL declares a {:?}",
                        pass.name, slot.set, slot.binding, b.info.kind
                    )));
                }
                (vk::DescriptorType::COMBINED_IMAGE_SAMPLER, 1, Some(b))
            }
            SlotContent::SamplerArray(0) | SlotContent::SamplerIndices(0) => {
                return Err(Error::Shader(format!(
                    "pass `{}`: slot {}/{} is empty",
                    pass.name, slot.set, slot.binding
                )));
            }
            SlotContent::SamplerArray(n) => (vk::DescriptorType::SAMPLER, *n, None),
            SlotContent::SamplerIndices(_) => (vk::DescriptorType::STORAGE_BUFFER, 1, None),
        };
        out.push(Descriptor {
            set: slot.set,
            binding: slot.binding,
            ty,
            count,
            content: slot.content.clone(),
            plan: bound,
        });
    }
    Ok(out)
}
