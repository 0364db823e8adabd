//! The graph's vocabulary in wgpu's terms: formats, binding types, samplers, blend and depth
//! state. One function per concept, so the rest of the backend never matches on strings.

use stratus_graph::{
    desc::{AddressMode, Blend, Compare, Filter, LoadOp, TexelFormat},
    manifest::{Access, BindingKind, Dimension},
    plan::{Binding, FramePlan, PlanResource, SamplerDesc, Usage},
};

/// The wgpu format of a graph format.
pub(crate) fn format(f: TexelFormat) -> wgpu::TextureFormat {
    match f {
        TexelFormat::Rgba8Unorm => wgpu::TextureFormat::Rgba8Unorm,
        TexelFormat::Rgba16Float => wgpu::TextureFormat::Rgba16Float,
        TexelFormat::Rgba32Float => wgpu::TextureFormat::Rgba32Float,
        TexelFormat::R32Float => wgpu::TextureFormat::R32Float,
        TexelFormat::Depth32Float => wgpu::TextureFormat::Depth32Float,
    }
}

/// The texture usages a resource needs. Colour textures also get COPY_SRC (readback on
/// request) and COPY_DST: with COPY_DST wgpu zero-initialises a texture with a copy. Without
/// it wgpu clears it with a render pass, which leaves a framebuffer bound in llvmpipe; lavapipe
/// then bins timestamps into its tiles and takes them at the next flush, so a compute pass
/// measured ~0 ms and its cost landed in the next pass (found with a perf probe on
/// clock_gettime; the ash backend, which binds framebuffers only for raster passes, agrees).
pub(crate) fn texture_usage(usage: Usage, f: TexelFormat) -> wgpu::TextureUsages {
    let mut u = wgpu::TextureUsages::empty();
    if usage.sampled {
        u |= wgpu::TextureUsages::TEXTURE_BINDING;
    }
    if usage.storage {
        u |= wgpu::TextureUsages::STORAGE_BINDING;
    }
    if usage.color || usage.depth {
        u |= wgpu::TextureUsages::RENDER_ATTACHMENT;
    }
    if usage.upload {
        u |= wgpu::TextureUsages::COPY_DST;
    }
    if !f.is_depth() {
        u |= wgpu::TextureUsages::COPY_SRC | wgpu::TextureUsages::COPY_DST;
    }
    u
}

/// The wgpu dimension of a graph dimension.
pub(crate) fn dimension(d: Dimension) -> (wgpu::TextureDimension, wgpu::TextureViewDimension) {
    match d {
        Dimension::D1 => (wgpu::TextureDimension::D1, wgpu::TextureViewDimension::D1),
        Dimension::D3 => (wgpu::TextureDimension::D3, wgpu::TextureViewDimension::D3),
        Dimension::D2 | Dimension::Cube => {
            (wgpu::TextureDimension::D2, wgpu::TextureViewDimension::D2)
        }
    }
}

/// The bind group layout entry type of a binding, from the manifest's reflection and the
/// resource bound there.
pub(crate) fn binding_type(b: &Binding, plan: &FramePlan) -> wgpu::BindingType {
    let r: &PlanResource = &plan.resources[b.resource];
    let view_dimension = dimension(b.info.dimension.unwrap_or(Dimension::D2)).1;
    match b.info.kind {
        BindingKind::UniformBuffer => wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        BindingKind::StorageBuffer => wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage {
                read_only: b.info.access == Some(Access::Read),
            },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        BindingKind::SampledTexture => wgpu::BindingType::Texture {
            sample_type: match r.format {
                Some(f) if f.is_depth() => wgpu::TextureSampleType::Depth,
                f => wgpu::TextureSampleType::Float {
                    filterable: f.is_some_and(TexelFormat::filterable),
                },
            },
            view_dimension,
            multisampled: false,
        },
        BindingKind::StorageTexture => wgpu::BindingType::StorageTexture {
            access: match b.info.access {
                Some(Access::Read) => wgpu::StorageTextureAccess::ReadOnly,
                Some(Access::ReadWrite) => wgpu::StorageTextureAccess::ReadWrite,
                _ => wgpu::StorageTextureAccess::WriteOnly,
            },
            format: format(r.format.unwrap_or(TexelFormat::Rgba8Unorm)),
            view_dimension,
        },
        BindingKind::Sampler | BindingKind::Other => {
            wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering)
        }
    }
}

/// A sampler descriptor from the graph's sampler state.
pub(crate) fn sampler(s: SamplerDesc) -> wgpu::SamplerDescriptor<'static> {
    let address = match s.address {
        AddressMode::Repeat => wgpu::AddressMode::Repeat,
        AddressMode::ClampToEdge => wgpu::AddressMode::ClampToEdge,
    };
    let filter = match s.filter {
        Filter::Linear => wgpu::FilterMode::Linear,
        Filter::Nearest => wgpu::FilterMode::Nearest,
    };
    wgpu::SamplerDescriptor {
        label: Some("sampler"),
        address_mode_u: address,
        address_mode_v: address,
        address_mode_w: address,
        mag_filter: filter,
        min_filter: filter,
        mipmap_filter: wgpu::MipmapFilterMode::Nearest,
        lod_min_clamp: SamplerDesc::LOD_CLAMP[0],
        lod_max_clamp: SamplerDesc::LOD_CLAMP[1],
        ..Default::default()
    }
}

/// The blend state of a colour target.
pub(crate) fn blend(b: Blend) -> Option<wgpu::BlendState> {
    use wgpu::{BlendComponent as C, BlendFactor as F, BlendOperation as O};
    match b {
        Blend::Replace => None,
        Blend::Transmittance => Some(wgpu::BlendState {
            color: C {
                src_factor: F::One,
                dst_factor: F::SrcAlpha,
                operation: O::Add,
            },
            alpha: C {
                src_factor: F::Zero,
                dst_factor: F::One,
                operation: O::Add,
            },
        }),
        Blend::Additive => Some(wgpu::BlendState {
            color: C {
                src_factor: F::One,
                dst_factor: F::One,
                operation: O::Add,
            },
            alpha: C {
                src_factor: F::One,
                dst_factor: F::One,
                operation: O::Add,
            },
        }),
        Blend::Over => Some(wgpu::BlendState::PREMULTIPLIED_ALPHA_BLENDING),
    }
}

/// The depth comparison.
pub(crate) fn compare(c: Compare) -> wgpu::CompareFunction {
    match c {
        Compare::Always => wgpu::CompareFunction::Always,
        Compare::Less => wgpu::CompareFunction::Less,
        Compare::LessEqual => wgpu::CompareFunction::LessEqual,
        Compare::Greater => wgpu::CompareFunction::Greater,
    }
}

/// The load operation of a colour target (clear to transparent black).
pub(crate) fn color_load(l: LoadOp) -> wgpu::LoadOp<wgpu::Color> {
    match l {
        LoadOp::Clear => wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
        LoadOp::Load => wgpu::LoadOp::Load,
    }
}

/// The load operation of a depth target (clear to the far plane).
pub(crate) fn depth_load(l: LoadOp) -> wgpu::LoadOp<f32> {
    match l {
        LoadOp::Clear => wgpu::LoadOp::Clear(1.0),
        LoadOp::Load => wgpu::LoadOp::Load,
    }
}
