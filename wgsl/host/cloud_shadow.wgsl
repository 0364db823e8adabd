// Stratus's cloud shadow for the host's shaders: the key light's transmittance through every
// cloud layer at a point of the host's world (y up, metres, the ground at y = 0), for its PBR
// lighting. Not part of Stratus's own modules: copy it into the host's shader, bind the map
// (`Clouds::cloud_shadow`: an r32float texture, read with loads, no sampler) and the uniform
// (`CloudShadow::uniform`, 48 bytes), and multiply the key light by the result.
//
// The map holds the transmittance from the ground up along the light, on a square around the
// camera; a point above the ground is shadowed by the clouds above its projection along the
// light onto the ground, exactly so below the cloud base (points inside or above a cloud
// layer get the whole column's shadow). Beyond the square there is no shadow; it fades out
// over the outer quarter.

struct StratusCloudShadow {
    // Rows 0 and 1 of the host-world-to-texel transform: for p1 = (position, 1), the map's
    // texel coordinates are (dot(texel_x, p1), dot(texel_y, p1)), texel i at coordinate i.
    texel_x: vec4<f32>,
    texel_y: vec4<f32>,
    // The map's side (texels).
    size: f32,
    // Where the fade to no shadow starts, as a fraction of the half side.
    fade_start: f32,
    pad0: f32,
    pad1: f32,
}

// The key light's transmittance through the clouds at host-world position `p`.
fn stratus_cloud_shadow(map: texture_2d<f32>, s: StratusCloudShadow, p: vec3<f32>) -> f32 {
    let p1 = vec4<f32>(p, 1.0);
    let t = vec2<f32>(dot(s.texel_x, p1), dot(s.texel_y, p1));
    let last = s.size - 1.0;
    let edge = max(abs(2.0 * t.x / last - 1.0), abs(2.0 * t.y / last - 1.0));
    if edge >= 1.0 {
        return 1.0;
    }
    let f = clamp(t, vec2<f32>(0.0), vec2<f32>(last));
    let n = u32(last);
    let i0 = min(vec2<u32>(floor(f)), vec2<u32>(n));
    let i1 = min(i0 + 1u, vec2<u32>(n));
    let w = f - vec2<f32>(i0);
    let a = mix(textureLoad(map, vec2<u32>(i0.x, i0.y), 0).r, textureLoad(map, vec2<u32>(i1.x, i0.y), 0).r, w.x);
    let b = mix(textureLoad(map, vec2<u32>(i0.x, i1.y), 0).r, textureLoad(map, vec2<u32>(i1.x, i1.y), 0).r, w.x);
    return mix(mix(a, b, w.y), 1.0, smoothstep(s.fade_start, 1.0, edge));
}
