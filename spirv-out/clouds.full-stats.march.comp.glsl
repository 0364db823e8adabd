#version 450 core
#extension GL_ARB_compute_shader : require
#extension GL_ARB_shader_storage_buffer_object : require
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

struct Frame {
    vec4 camera_position;
    uvec4 resolution;
};
struct Stats {
    uint pixels;
};
const bool STATS = true;

layout(std140, binding = 0) uniform Frame_block_0Compute { Frame _group_0_binding_0_cs; };

layout(binding = 1,rgba16f) writeonly uniform image2D _group_0_binding_1_cs;

layout(std430, binding = 2) buffer Stats_block_1Compute { Stats _group_0_binding_2_cs; };


void main() {
    uvec3 id = gl_GlobalInvocationID;
    uvec4 _e4 = _group_0_binding_0_cs.resolution;
    if (any(greaterThanEqual(id.xy, _e4.xy))) {
        return;
    }
    if (STATS) {
        uint _e12 = atomicAdd(_group_0_binding_2_cs.pixels, 1u);
    }
    uvec4 _e20 = _group_0_binding_0_cs.resolution;
    vec2 uv = ((vec2(id.xy) + vec2(0.5)) / vec2(_e20.xy));
    imageStore(_group_0_binding_1_cs, ivec2(id.xy), vec4(uv, 0.0, 1.0));
    return;
}

