// Stratus's aerial perspective for the host's shaders: the light the air scatters toward the
// camera in front of a point of the host's geometry, and the air's transmittance to it, so the
// host's distant geometry takes the same haze as Stratus's clouds and sky. Not part of
// Stratus's own modules: copy it into the host's shader, bind the table
// (`Clouds::aerial_perspective`: an rgba32float texture, read with loads, no sampler) and the
// uniform (`AerialPerspective::uniform`, 32 bytes), then shade the point as
// `colour * ap.a + ap.rgb` (before the host's exposure, in Stratus's radiance units).
//
// The table is a froxel grid over this frame's view (the physical sky only): froxel columns
// over the image, slices along each column's ray, each slice holding what the air scatters
// and lets through from the camera to its far end; it is read bilinearly across columns and
// linearly between slices, as Stratus reads it for its clouds.

struct StratusAerial {
    // The key light's illuminance (rgb, Stratus's units) and the slice depth (w, m).
    illuminance: vec4<f32>,
    // The grid: columns a side (x), slices (y); z and w unused.
    grid: vec4<f32>,
}

fn stratus_aerial_texel(map: texture_2d<f32>, side: u32, c0: vec2<u32>, c1: vec2<u32>, w: vec2<f32>, z: u32) -> vec4<f32> {
    let o = z * side;
    let a = mix(textureLoad(map, vec2<u32>(o + c0.x, c0.y), 0), textureLoad(map, vec2<u32>(o + c1.x, c0.y), 0), w.x);
    let b = mix(textureLoad(map, vec2<u32>(o + c0.x, c1.y), 0), textureLoad(map, vec2<u32>(o + c1.x, c1.y), 0), w.x);
    return mix(a, b, w.y);
}

// (in-scattered radiance, mean transmittance) of the air between the camera and the point at
// `distance_m` along the ray through image position `uv` (0 at the top-left corner, 1 at the
// bottom-right; the pixel centre of the frame the table was made for).
fn stratus_aerial_perspective(map: texture_2d<f32>, a: StratusAerial, uv: vec2<f32>, distance_m: f32) -> vec4<f32> {
    let side = u32(a.grid.x);
    let slices = u32(a.grid.y);
    // Column centres sit at (c + 0.5) / side.
    let f = clamp(uv * f32(side) - 0.5, vec2<f32>(0.0), vec2<f32>(f32(side - 1u)));
    let c0 = min(vec2<u32>(floor(f)), vec2<u32>(side - 1u));
    let c1 = min(c0 + 1u, vec2<u32>(side - 1u));
    let w = f - vec2<f32>(c0);
    // Slice z ends at (z + 1) slice depths; the camera is at 0, where there is no air.
    let s = clamp(distance_m / a.illuminance.w, 0.0, f32(slices));
    let z1 = min(u32(ceil(s)), slices);
    let z0 = select(0u, z1 - 1u, z1 > 0u);
    var near = vec4<f32>(0.0, 0.0, 0.0, 1.0);
    if z0 > 0u {
        near = stratus_aerial_texel(map, side, c0, c1, w, z0 - 1u);
    }
    var far = vec4<f32>(0.0, 0.0, 0.0, 1.0);
    if z1 > 0u {
        far = stratus_aerial_texel(map, side, c0, c1, w, z1 - 1u);
    }
    let ap = mix(near, far, s - f32(z0));
    return vec4<f32>(ap.rgb * a.illuminance.rgb, ap.a);
}
