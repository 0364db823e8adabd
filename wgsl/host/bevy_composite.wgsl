// Stratus over a Bevy camera's image (stratus-bevy), after Bevy's main pass and before its
// tone mapping. Not part of Stratus's own modules: the plugin compiles it with the host helpers
// cloud_shadow.wgsl and aerial_perspective.wgsl in front of it.
//
// One full-screen triangle blended One, SrcAlpha into the camera's HDR image: what Bevy drew
// times the returned alpha, plus the returned colour. The colour is the clouds' HDR output
// (Clouds::render_hdr: premultiplied radiance, transmittance in alpha; opaque sky where Bevy
// drew nothing) in Bevy's units. Over Bevy's geometry the air in front of it scatters light
// toward the camera and dims it (stratus_aerial_perspective, under the physical sky), and the
// alpha also carries the clouds' shadow: the share of the geometry's light that comes from the
// key light is dimmed by the light's transmittance through the clouds at the point
// (stratus_cloud_shadow).

struct Composite {
    // Host-world-from-clip with the camera at the origin (the camera's position is added
    // after, in f32 from an f64 subtraction on the host, so far-off cameras stay precise).
    world_from_clip: mat4x4<f32>,
    // The camera's host-world position (xyz), and the depth of a pixel with no geometry (w).
    camera: vec4<f32>,
    // The target's size (pixels).
    size: vec2<f32>,
    // Bevy's exposed radiance per Stratus unit: lux per unit of Stratus's sun illuminance
    // times the camera's exposure (Bevy exposes its lights in its PBR shaders).
    scale: f32,
    // The share of the geometry's light that is the key light's (0: cloud shadows off).
    direct: f32,
    // x: 1 where the geometry takes the air's aerial perspective (the physical sky), else 0.
    haze: vec4<f32>,
}

@group(0) @binding(0) var clouds: texture_2d<f32>;
@group(0) @binding(1) var depth: texture_depth_2d;
@group(0) @binding(2) var shadow_map: texture_2d<f32>;
@group(0) @binding(3) var<uniform> composite: Composite;
@group(0) @binding(4) var<uniform> shadow: StratusCloudShadow;
@group(0) @binding(5) var aerial_map: texture_2d<f32>;
@group(0) @binding(6) var<uniform> aerial: StratusAerial;

// The triangle (-1, -1), (3, -1), (-1, 3) covers the viewport; no vertex buffer.
@vertex
fn composite_vertex(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let corner = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(corner * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn composite_fragment(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let pixel = vec2<u32>(position.xy);
    let cloud = textureLoad(clouds, pixel, 0);
    var light = cloud.rgb;
    var keep = cloud.a;
    let d = textureLoad(depth, pixel, 0);
    if keep > 0.0 && d != composite.camera.w {
        let uv = position.xy / composite.size;
        let clip = vec4<f32>(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, d, 1.0);
        let h = composite.world_from_clip * clip;
        let rel = h.xyz / h.w;
        // The air between the camera and the geometry, seen through the clouds in front.
        if composite.haze.x > 0.0 {
            let ap = stratus_aerial_perspective(aerial_map, aerial, uv, length(rel));
            light += keep * ap.rgb;
            keep *= ap.a;
        }
        if composite.direct > 0.0 {
            let lit = stratus_cloud_shadow(shadow_map, shadow, rel + composite.camera.xyz);
            keep *= mix(1.0, lit, composite.direct);
        }
    }
    return vec4<f32>(light * composite.scale, keep);
}
