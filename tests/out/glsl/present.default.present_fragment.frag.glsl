#version 450 core
layout(binding = 0) uniform sampler2D _group_0_binding_0_fs;

layout(location = 0) out vec4 _fs2p_location0;

void main() {
    vec4 position = gl_FragCoord;
    vec4 _e5 = texelFetch(_group_0_binding_0_fs, ivec2(uvec2(position.xy)), 0);
    _fs2p_location0 = _e5;
    return;
}

