#version 450 core
layout(binding = 1) uniform sampler2D _group_0_binding_1_fs;

layout(location = 0) out vec4 _fs2p_location0;

void main() {
    vec4 position_1 = gl_FragCoord;
    vec4 _e5 = texelFetch(_group_0_binding_1_fs, ivec2(uvec2(position_1.xy)), 0);
    _fs2p_location0 = _e5;
    return;
}

