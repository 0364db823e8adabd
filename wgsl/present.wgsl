// Present: draws the display image into a colour target with one full-screen triangle. A
// host's own texture (a swapchain image, say) often cannot be a storage image, but any colour
// format can be a render target, so this raster pass is how the clouds reach it. The image is
// already tone-mapped and gamma-encoded: give it a UNORM (not sRGB) view.

@group(0) @binding(0) var image_in: texture_2d<f32>;
@group(0) @binding(1) var radiance_in: texture_2d<f32>; // the clouds: in-scattered radiance, transmittance

// The triangle (-1, -1), (3, -1), (-1, 3) covers the whole viewport; no vertex buffer.
@vertex
fn present_vertex(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let corner = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(corner * 2.0 - 1.0, 0.0, 1.0);
}

// Pixel centres land on texel centres (viewport = image size), so this is an exact copy.
@fragment
fn present_fragment(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    return textureLoad(image_in, vec2<u32>(position.xy), 0);
}

// The clouds' HDR output for a host's compositor: linear in-scattered radiance (premultiplied:
// the host adds it over its own image times the transmittance), transmittance in alpha, before
// any exposure or tone mapping (the host's own come after).
@fragment
fn hdr_fragment(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    return textureLoad(radiance_in, vec2<u32>(position.xy), 0);
}
