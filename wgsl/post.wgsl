// Post effects on the display image (`[post]`): the stylised Kuwahara filter (seed 001's
// stylised presets). The composite writes the tone-mapped image into `unstyled_in`; this pass
// writes the display image from it.

@group(0) @binding(45) var unstyled_in: texture_2d<f32>;   // the composite's display image

// Taps from the centre to the window's edge along each axis: a quadrant is (TAPS + 1)^2
// samples, whatever the resolution.
const KUWAHARA_TAPS: i32 = 4;

// The quadrants' weights: 1 / (1 + (v / KUWAHARA_FLAT)^4) for a quadrant whose channels'
// variances sum to v (levels^2). Quadrants flatter than about 2 levels' deviation a channel
// weigh alike, so a smooth gradient stays smooth (their means average to the centre's);
// a quadrant across an edge weighs next to nothing beside one on either side.
const KUWAHARA_FLAT: f32 = 12.0;

// The 8-bit levels (0-255) of a display texel's red, green and blue.
fn display_levels(texel: vec2<i32>) -> vec3<u32> {
    let c = round(clamp(textureLoad(unstyled_in, texel, 0).rgb, vec3<f32>(0.0), vec3<f32>(1.0)) * 255.0);
    return vec3<u32>(u32(c.x), u32(c.y), u32(c.z));
}

// The Kuwahara filter (Kuwahara et al. 1976), with smooth weights (Papari et al. 2007): of the
// four square windows that have the pixel at a corner (left-up, right-up, left-down,
// right-down), the pixel takes the mean colour of those whose colours vary least (the sum of
// the channels' variances), weighted as KUWAHARA_FLAT says. Inside a noisy flat region the
// means smooth it to an even patch; at an edge the windows that straddle it vary most, so the
// pixel takes its colour from its own side and the edge stays; a smooth gradient, which the
// classic filter's choice of one window breaks into terraces, stays smooth.
// The window's radius is `kuwahara_radius` of the image's height, so the taps' offsets are
// UV distances turned to whole texels (rounded, one product of exact floats, the same on
// every backend); where the radius is under TAPS texels several taps share a texel. The sums
// are integers of the 8-bit levels, exact on every backend and in the CPU reference.
@compute @workgroup_size(8, 8, 1)
fn kuwahara(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.size) {
        return;
    }
    let radius_px = frame.kuwahara_radius * f32(frame.size.y);
    let last = vec2<i32>(frame.size) - 1;
    let centre = vec2<i32>(id.xy);
    // Per channel, the four quadrants' sums and sums of squares, quadrant q in component q:
    // bit 0 of q the right half (i >= 0), bit 1 the lower half (j >= 0); the centre row and
    // column belong to both sides. (Vectors, not arrays: naga's HLSL writes an array's zero
    // value as a cast that glslang's HLSL front end refuses.)
    var sum_r = vec4<u32>(0u);
    var sum_g = vec4<u32>(0u);
    var sum_b = vec4<u32>(0u);
    var sq_r = vec4<u32>(0u);
    var sq_g = vec4<u32>(0u);
    var sq_b = vec4<u32>(0u);
    for (var j = -KUWAHARA_TAPS; j <= KUWAHARA_TAPS; j++) {
        let dy = i32(floor(f32(j) * radius_px * 0.25 + 0.5));
        for (var i = -KUWAHARA_TAPS; i <= KUWAHARA_TAPS; i++) {
            let dx = i32(floor(f32(i) * radius_px * 0.25 + 0.5));
            let c = display_levels(clamp(centre + vec2<i32>(dx, dy), vec2<i32>(0), last));
            let left = i <= 0;
            let right = i >= 0;
            let up = j <= 0;
            let down = j >= 0;
            let m = vec4<u32>(vec4<bool>(left && up, right && up, left && down, right && down));
            sum_r += m * c.r;
            sum_g += m * c.g;
            sum_b += m * c.b;
            sq_r += m * (c.r * c.r);
            sq_g += m * (c.g * c.g);
            sq_b += m * (c.b * c.b);
        }
    }
    let n = u32((KUWAHARA_TAPS + 1) * (KUWAHARA_TAPS + 1));
    let nf = f32(n);
    // n^2 times each quadrant's variance, summed over the channels (at most 3 x 25 x 25 x
    // 255^2, well within a u32).
    let spread = (n * sq_r - sum_r * sum_r) + (n * sq_g - sum_g * sum_g) + (n * sq_b - sum_b * sum_b);
    let v = vec4<f32>(spread) / (nf * nf) / KUWAHARA_FLAT;
    let v2 = v * v;
    let w = 1.0 / (1.0 + v2 * v2);
    let colour = vec3<f32>(dot(w, vec4<f32>(sum_r)), dot(w, vec4<f32>(sum_g)), dot(w, vec4<f32>(sum_b))) / nf;
    let weights = w.x + w.y + w.z + w.w;
    textureStore(image_out, id.xy, vec4<f32>(colour / (weights * 255.0), 1.0));
}
