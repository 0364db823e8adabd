// Shared declarations: the per-frame uniforms (mirrors `FrameUniforms` in the scene crate).

struct Frame {
    camera_position: vec4<f32>,
    resolution: vec4<u32>,
}

@group(0) @binding(0) var<uniform> frame: Frame;
