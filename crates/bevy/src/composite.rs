//! The composite of the clouds' HDR output into a Bevy camera's image
//! (`wgsl/host/bevy_composite.wgsl`), on Bevy's wgpu device.

use bevy::math::{Mat4, Vec3};

/// The host helpers the composite calls, then the composite itself.
const SHADER: [&str; 3] = [
    include_str!("../../../wgsl/host/cloud_shadow.wgsl"),
    include_str!("../../../wgsl/host/aerial_perspective.wgsl"),
    include_str!("../../../wgsl/host/bevy_composite.wgsl"),
];

/// The `Composite` uniform block: world-from-clip (16), camera and clear depth (4), size,
/// scale and direct share (4), haze (4).
const UNIFORM_FLOATS: usize = 28;

/// The composite's pipeline for one target format, its uniform buffers and a stand-in shadow
/// map for frames without one.
pub(crate) struct Composite {
    format: wgpu::TextureFormat,
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    uniform: wgpu::Buffer,
    shadow_uniform: wgpu::Buffer,
    aerial_uniform: wgpu::Buffer,
    /// 1x1, read only where the shadow or the haze is on (never, for frames without them).
    no_table: wgpu::TextureView,
}

/// What one frame's composite reads and writes.
pub(crate) struct Frame<'a> {
    /// The camera's HDR image (blended into).
    pub target: &'a wgpu::TextureView,
    /// The clouds' HDR output.
    pub clouds: &'a wgpu::TextureView,
    /// The camera's depth.
    pub depth: &'a wgpu::TextureView,
    /// The cloud-shadow map and its `StratusCloudShadow` uniform, when computed.
    pub shadow: Option<(&'a wgpu::TextureView, [f32; 12])>,
    /// The aerial-perspective table and its `StratusAerial` uniform (the physical sky).
    pub aerial: Option<(&'a wgpu::TextureView, [f32; 8])>,
    /// Host-world-from-clip with the camera at the origin.
    pub world_from_clip: Mat4,
    /// The camera's host-world position.
    pub camera: Vec3,
    /// The depth of a pixel with no geometry.
    pub clear_depth: f32,
    /// The target's size.
    pub size: [u32; 2],
    /// Bevy's units per Stratus unit.
    pub scale: f32,
    /// The key light's share of the geometry's light.
    pub direct: f32,
}

impl Composite {
    pub(crate) fn new(device: &wgpu::Device, format: wgpu::TextureFormat) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("stratus composite"),
            source: wgpu::ShaderSource::Wgsl(SHADER.concat().into()),
        });
        let texture = |binding, sample_type| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::FRAGMENT,
            ty: wgpu::BindingType::Texture {
                sample_type,
                view_dimension: wgpu::TextureViewDimension::D2,
                multisampled: false,
            },
            count: None,
        };
        let uniform = |binding| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::FRAGMENT,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        let unfilterable = wgpu::TextureSampleType::Float { filterable: false };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("stratus composite"),
            entries: &[
                texture(0, unfilterable),
                texture(1, wgpu::TextureSampleType::Depth),
                texture(2, unfilterable),
                uniform(3),
                uniform(4),
                texture(5, unfilterable),
                uniform(6),
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("stratus composite"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        // The camera's image times the returned alpha (the clouds' transmittance, with their
        // shadow on the geometry), plus the returned colour (their radiance, premultiplied).
        let blend = wgpu::BlendState {
            color: wgpu::BlendComponent {
                src_factor: wgpu::BlendFactor::One,
                dst_factor: wgpu::BlendFactor::SrcAlpha,
                operation: wgpu::BlendOperation::Add,
            },
            alpha: wgpu::BlendComponent {
                src_factor: wgpu::BlendFactor::Zero,
                dst_factor: wgpu::BlendFactor::One,
                operation: wgpu::BlendOperation::Add,
            },
        };
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("stratus composite"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("composite_vertex"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: Default::default(),
            depth_stencil: None,
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("composite_fragment"),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format,
                    blend: Some(blend),
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        });
        let buffer = |label, floats: usize| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: (floats * 4) as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let no_table = device
            .create_texture(&wgpu::TextureDescriptor {
                label: Some("stratus no table"),
                size: wgpu::Extent3d {
                    width: 1,
                    height: 1,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: wgpu::TextureFormat::R32Float,
                usage: wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            })
            .create_view(&Default::default());
        Self {
            format,
            pipeline,
            layout,
            uniform: buffer("stratus composite", UNIFORM_FLOATS),
            shadow_uniform: buffer("stratus cloud shadow", 12),
            aerial_uniform: buffer("stratus aerial perspective", 8),
            no_table,
        }
    }

    /// The target format this pipeline draws into.
    pub(crate) fn format(&self) -> wgpu::TextureFormat {
        self.format
    }

    /// Records the composite of one frame.
    pub(crate) fn draw(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        frame: Frame<'_>,
    ) {
        let direct = if frame.shadow.is_some() {
            frame.direct
        } else {
            0.0
        };
        let mut u = [0f32; UNIFORM_FLOATS];
        u[..16].copy_from_slice(&frame.world_from_clip.to_cols_array());
        u[16..20].copy_from_slice(&[
            frame.camera.x,
            frame.camera.y,
            frame.camera.z,
            frame.clear_depth,
        ]);
        u[20..24].copy_from_slice(&[
            frame.size[0] as f32,
            frame.size[1] as f32,
            frame.scale,
            direct,
        ]);
        u[24] = if frame.aerial.is_some() { 1.0 } else { 0.0 };
        queue.write_buffer(&self.uniform, 0, &floats_to_bytes(&u));
        let (shadow_view, shadow_uniform) = frame.shadow.unwrap_or((&self.no_table, [0.0; 12]));
        queue.write_buffer(&self.shadow_uniform, 0, &floats_to_bytes(&shadow_uniform));
        let (aerial_view, aerial_uniform) = frame.aerial.unwrap_or((&self.no_table, [0.0; 8]));
        queue.write_buffer(&self.aerial_uniform, 0, &floats_to_bytes(&aerial_uniform));
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("stratus composite"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(frame.clouds),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(frame.depth),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::TextureView(shadow_view),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: self.uniform.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 4,
                    resource: self.shadow_uniform.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 5,
                    resource: wgpu::BindingResource::TextureView(aerial_view),
                },
                wgpu::BindGroupEntry {
                    binding: 6,
                    resource: self.aerial_uniform.as_entire_binding(),
                },
            ],
        });
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("stratus composite"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: frame.target,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Load,
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: None,
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.draw(0..3, 0..1);
    }
}

fn floats_to_bytes(v: &[f32]) -> Vec<u8> {
    v.iter().flat_map(|f| f.to_le_bytes()).collect()
}
