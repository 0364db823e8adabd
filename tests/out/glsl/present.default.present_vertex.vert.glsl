#version 450 core

void main() {
    uint i = uint(gl_VertexID);
    vec2 corner = vec2(float(((i << 1u) & 2u)), float((i & 2u)));
    gl_Position = vec4(((corner * 2.0) - vec2(1.0)), 0.0, 1.0);
    return;
}

