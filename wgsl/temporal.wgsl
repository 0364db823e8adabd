// Temporal upsampling (thesis 6.1; Horizon Zero Dawn's 1-in-16 update). Each frame marches
// one pixel of every k x k block (k = frame.block_side), visiting the block's pixels in Bayer
// order, each march with the next van der Corput start offset. The resolve pass rebuilds the
// full-resolution image: the marched pixel blends into its history; every other pixel takes
// last frame's result, reprojected through last frame's camera at the clouds' transmittance-
// weighted depth and clamped to the current frame's neighbourhood while the camera moves;
// pixels whose history is off screen or disoccluded are marched in full.

@group(0) @binding(13) var history_in: texture_2d<f32>;                         // last frame: radiance, transmittance
@group(0) @binding(14) var meta_in: texture_2d<f32>;                            // last frame: depth (m), samples
@group(0) @binding(15) var sparse_in: texture_2d<f32>;                          // this frame's marched pixels
@group(0) @binding(16) var sparse_depth_in: texture_2d<f32>;                    // their depth
@group(0) @binding(17) var history_out: texture_storage_2d<rgba32float, write>; // this frame: radiance, transmittance
@group(0) @binding(18) var meta_out: texture_storage_2d<rgba32float, write>;    // this frame: depth, samples, 1 where the host's geometry cut the march

// Samples a pixel's history averages at most: a running mean of its marches (so a still
// camera converges to the mean over the van der Corput offsets), then an exponential blend of
// 1/16, near the thesis's 5% (its appendix B). While the camera moves, 2 (and history that was
// only resampled counts as none, so a march replaces it): new marches weigh more, so less
// ghosting.
const HISTORY_SAMPLES: f32 = 16.0;
const HISTORY_SAMPLES_MOVING: f32 = 2.0;
// History whose depth differs from the reprojected point's by more than this fraction is
// something else: disoccluded, marched again. (0.2 re-marched much of every cloud edge while
// moving, where the block's depth is another pixel's: at 1/16 the resolve cost more than the
// sparse march.)
const DISOCCLUSION_DEPTH: f32 = 0.5;

// The position in a 2 x 2 block of the pixel with Bayer rank `v` (the ordered-dither matrix
// [[0, 2], [3, 1]]: rank 0 at (0, 0), 1 at (1, 1), 2 at (1, 0), 3 at (0, 1)).
fn bayer2(v: u32) -> vec2<u32> {
    return vec2<u32>((v ^ (v >> 1u)) & 1u, v & 1u);
}

// The pixel of each k x k block marched in frame `f`: Bayer order, so consecutive frames
// spread over the block. The 4 x 4 matrix is 4 M2(x mod 2, y mod 2) + M2(x / 2, y / 2), so
// rank b sits at bayer2(b / 4) + 2 bayer2(b mod 4). (Arithmetic, not a table: lavapipe
// crashed compiling glslang's SPIR-V for a dynamically indexed local array.)
fn block_offset(f: u32, k: u32) -> vec2<u32> {
    if k == 2u {
        return bayer2(f % 4u);
    }
    if k == 4u {
        let b = f % 16u;
        return bayer2(b >> 2u) + 2u * bayer2(b & 3u);
    }
    return vec2<u32>(0u);
}

// Whether this frame's camera is last frame's: same place, orientation, field of view, aspect
// and exposure (a moved camera restarts the path tracer's accumulation).
fn camera_still() -> bool {
    return all(frame.camera_position == frame.previous_position)
        && frame.tan_half_fov == frame.previous_tan_half_fov
        && all(frame.camera_forward == frame.previous_forward)
        && frame.aspect == frame.previous_aspect
        && all(frame.camera_right == frame.previous_right)
        && frame.exposure == frame.previous_exposure
        && all(frame.camera_up == frame.previous_up);
}

// Where the point at distance `depth` along the current view ray of `pixel` was in last
// frame's image (pixel coordinates, centres at integers + 0.5 - 0.5 = integers). `depth` 0:
// a point at infinity (only the direction moves). x = -1e9 when it was behind the camera.
fn reproject(pixel: vec2<u32>, depth: f32) -> vec2<f32> {
    let same = camera_still();
    if same {
        // A still camera reprojects exactly onto itself (no resampling blur).
        return vec2<f32>(pixel);
    }
    let view = view_ray(pixel);
    var dir = view;
    if depth > 0.0 {
        dir = view * depth + (frame.camera_position - frame.previous_position);
    }
    let z = dot(dir, frame.previous_forward);
    if z <= 0.0 {
        return vec2<f32>(-1e9);
    }
    let tan_half = frame.previous_tan_half_fov;
    let aspect = frame.previous_aspect;
    let ndc = vec2<f32>(
        dot(dir, frame.previous_right) / (z * tan_half * aspect),
        -dot(dir, frame.previous_up) / (z * tan_half),
    );
    return (ndc * 0.5 + 0.5) * vec2<f32>(frame.size) - 0.5;
}

fn on_screen(q: vec2<f32>) -> bool {
    let size = vec2<f32>(frame.size);
    return all(q >= vec2<f32>(-0.5)) && all(q <= size - 0.5);
}

// Catmull-Rom weights of the four taps around a sample at fraction `t` past the second.
fn catmull_rom(t: f32) -> vec4<f32> {
    return vec4<f32>(
        t * (-0.5 + t * (1.0 - 0.5 * t)),
        1.0 + t * t * (-2.5 + 1.5 * t),
        t * (0.5 + t * (2.0 - 1.5 * t)),
        t * t * (-0.5 + 0.5 * t),
    );
}

// Last frame's radiance and transmittance at `q`: Catmull-Rom over 4 x 4 texels (by hand:
// loads, the same on every backend and for float formats that cannot be filtered). A bicubic
// keeps the detail that bilinear resampling would blur away a little more every frame the
// camera moves; its overshoot is clamped to the physical range.
fn history_at(q: vec2<f32>) -> vec4<f32> {
    let size = vec2<i32>(frame.size);
    let c = clamp(q, vec2<f32>(0.0), vec2<f32>(size - 1));
    let base = vec2<i32>(floor(c));
    let f = c - vec2<f32>(base);
    let wx = catmull_rom(f.x);
    let wy = catmull_rom(f.y);
    // Written out, no dynamically indexed vectors (lavapipe crashed compiling glslang's
    // SPIR-V for those).
    let sum = history_row(base, -1, wx) * wy.x + history_row(base, 0, wx) * wy.y
        + history_row(base, 1, wx) * wy.z + history_row(base, 2, wx) * wy.w;
    return vec4<f32>(max(sum.rgb, vec3<f32>(0.0)), saturate(sum.a));
}

// One row (`dy` from `base`) of the Catmull-Rom footprint, weighted by `wx`; clamped at the
// image's edges.
fn history_row(base: vec2<i32>, dy: i32, wx: vec4<f32>) -> vec4<f32> {
    let size = vec2<i32>(frame.size);
    let y = clamp(base.y + dy, 0, size.y - 1);
    let x0 = clamp(base.x - 1, 0, size.x - 1);
    let x1 = clamp(base.x, 0, size.x - 1);
    let x2 = clamp(base.x + 1, 0, size.x - 1);
    let x3 = clamp(base.x + 2, 0, size.x - 1);
    return textureLoad(history_in, vec2<i32>(x0, y), 0) * wx.x
        + textureLoad(history_in, vec2<i32>(x1, y), 0) * wx.y
        + textureLoad(history_in, vec2<i32>(x2, y), 0) * wx.z
        + textureLoad(history_in, vec2<i32>(x3, y), 0) * wx.w;
}

fn history_nearest(q: vec2<f32>) -> vec4<f32> {
    let size = vec2<i32>(frame.size);
    let p = clamp(vec2<i32>(round(q)), vec2<i32>(0), size - 1);
    return textureLoad(history_in, p, 0);
}

fn meta_at(q: vec2<f32>) -> vec4<f32> {
    let size = vec2<i32>(frame.size);
    let p = clamp(vec2<i32>(round(q)), vec2<i32>(0), size - 1);
    return textureLoad(meta_in, p, 0);
}

// Whether any texel of the Catmull-Rom footprint at `q` (history_at's 4 x 4) was cut by the
// host's geometry last frame: resampled there, the geometry's hole in the clouds would trail
// the geometry as a halo.
fn footprint_cut(q: vec2<f32>) -> bool {
    let size = vec2<i32>(frame.size);
    let base = vec2<i32>(floor(clamp(q, vec2<f32>(0.0), vec2<f32>(size - 1))));
    var cut = 0.0;
    for (var dy = -1; dy <= 2; dy++) {
        for (var dx = -1; dx <= 2; dx++) {
            let p = clamp(base + vec2<i32>(dx, dy), vec2<i32>(0), size - 1);
            cut = max(cut, textureLoad(meta_in, p, 0).z);
        }
    }
    return cut > 0.0;
}

// The marching pass: one pixel per block (`march_sparse`), or the same with thesis 6.2.2's
// checkerboard skipping (`march_sparse_checkerboard`). Two entry points rather than a runtime
// switch: the skipping code alone, never run, made the whole march 2.5 times slower on
// lavapipe (128x72: 10.3 ms against 4.0 ms).

// Whether block `id` is inside the sparse target.
fn in_blocks(id: vec2<u32>) -> bool {
    let k = frame.block_side;
    return all(id < (frame.size + k - 1u) / k);
}

// The pixel block `id` marches this frame.
fn sparse_pixel(id: vec2<u32>) -> vec2<u32> {
    let k = frame.block_side;
    return id * k + block_offset(frame.frame_index, k);
}

fn store_sparse(id: vec2<u32>, r: MarchResult) {
    textureStore(cloud_out, id, vec4<f32>(r.radiance, r.transmittance));
    textureStore(depth_out, id, vec4<f32>(r.depth, 0.0, 0.0, 0.0));
}

@compute @workgroup_size(8, 8, 1)
fn march_sparse(@builtin(global_invocation_id) id: vec3<u32>) {
    if !in_blocks(id.xy) {
        return;
    }
    let pixel = sparse_pixel(id.xy);
    var r = MarchResult(vec3<f32>(0.0), 1.0, 0.0);
    if all(pixel < frame.size) {
        r = march_pixel(pixel);
    }
    store_sparse(id.xy, r);
}

@compute @workgroup_size(8, 8, 1)
fn march_sparse_checkerboard(@builtin(global_invocation_id) id: vec3<u32>) {
    if !in_blocks(id.xy) {
        return;
    }
    let pixel = sparse_pixel(id.xy);
    var r = MarchResult(vec3<f32>(0.0), 1.0, 0.0);
    var skip = any(pixel >= frame.size);
    if !skip && frame.history_valid != 0u && !has_surface(pixel) {
        // Where last frame saw clear sky in this direction (the nearest texel), skip the
        // march in every other turn of the pixel, alternating between neighbouring blocks,
        // so clouds that the wind moves in are found within two turns. (Not where the host's
        // geometry is: its pixels are marched every frame.)
        let k = frame.block_side;
        let turn = frame.frame_index / (k * k);
        let q = reproject(pixel, 0.0);
        if ((id.x + id.y + turn) & 1u) == 0u && on_screen(q) && history_nearest(q).a >= 1.0 {
            skip = true;
        }
    }
    if !skip {
        r = march_pixel(pixel);
    }
    store_sparse(id.xy, r);
}

// The resolve pass: every pixel of the output.
@compute @workgroup_size(8, 8, 1)
fn resolve(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.size) {
        return;
    }
    let pixel = id.xy;
    let k = frame.block_side;
    let block = pixel / k;
    let marched = all(pixel == block * k + block_offset(frame.frame_index, k));
    let current = textureLoad(sparse_in, block, 0);
    let current_depth = textureLoad(sparse_depth_in, block, 0).r;

    // The depth to reproject at: this block's march; where it saw no cloud, the middle of
    // the layer along the ray (where clouds would be); a ray that misses the layer has only
    // sky, which moves with the direction.
    var depth = current_depth;
    if depth <= 0.0 {
        let span = nearest_layer_interval(frame.camera_position.y, view_ray(pixel));
        if span.kind == RAY_MARCH {
            depth = span.start + 0.5 * span.length;
        }
    }
    let q = reproject(pixel, depth);
    // The host's geometry: a pixel it covers is marched every frame (its march is cut at the
    // surface, so history from any other depth would be wrong, and in front of the layer the
    // march costs nothing), and history cut by last frame's geometry is not resampled.
    let surface = has_surface(pixel);
    let moving = any(q != vec2<f32>(pixel));
    var valid = frame.history_valid != 0u && on_screen(q) && !surface;
    if valid && (frame.flags & FLAG_SCENE_DEPTH) != 0u {
        valid = !select(meta_at(q).z > 0.0, footprint_cut(q), moving);
    }
    var history = vec4<f32>(0.0, 0.0, 0.0, 1.0);
    var past = vec4<f32>(0.0);
    if valid {
        history = history_at(q);
        past = meta_at(q);
        // Disoccluded: while the camera moves, history seen at another depth than where this
        // frame's march puts the cloud. (A still camera uncovers nothing; and this block's
        // depth is another pixel's, which at cloud edges would reject good history.)
        if moving && current_depth > 0.0 && past.x > 0.0 {
            let expected = distance(frame.camera_position + view_ray(pixel) * current_depth,
                frame.previous_position);
            valid = abs(past.x - expected) <= DISOCCLUSION_DEPTH * expected;
        }
    }
    if valid && moving {
        // Neighbourhood clamp: last frame's value may not leave the range of this frame's
        // marches around the pixel (3 x 3 blocks), which rejects stale, ghosting history.
        let blocks = vec2<i32>((frame.size + k - 1u) / k);
        let b = vec2<i32>(block);
        let x0 = max(b.x - 1, 0);
        let x2 = min(b.x + 1, blocks.x - 1);
        let y0 = max(b.y - 1, 0);
        let y2 = min(b.y + 1, blocks.y - 1);
        let s00 = textureLoad(sparse_in, vec2<i32>(x0, y0), 0);
        let s10 = textureLoad(sparse_in, vec2<i32>(b.x, y0), 0);
        let s20 = textureLoad(sparse_in, vec2<i32>(x2, y0), 0);
        let s01 = textureLoad(sparse_in, vec2<i32>(x0, b.y), 0);
        let s11 = textureLoad(sparse_in, b, 0);
        let s21 = textureLoad(sparse_in, vec2<i32>(x2, b.y), 0);
        let s02 = textureLoad(sparse_in, vec2<i32>(x0, y2), 0);
        let s12 = textureLoad(sparse_in, vec2<i32>(b.x, y2), 0);
        let s22 = textureLoad(sparse_in, vec2<i32>(x2, y2), 0);
        let lo = min(min(min(s00, s10), min(s20, s01)), min(min(s11, s21), min(min(s02, s12), s22)));
        let hi = max(max(max(s00, s10), max(s20, s01)), max(max(s11, s21), max(max(s02, s12), s22)));
        history = clamp(history, lo, hi);
    }

    var result: vec4<f32>;
    var samples: f32;
    var out_depth: f32;
    if marched {
        if valid {
            samples = min(past.y + 1.0, select(HISTORY_SAMPLES, HISTORY_SAMPLES_MOVING, moving));
            result = mix(history, current, 1.0 / samples);
        } else {
            samples = 1.0;
            result = current;
        }
        out_depth = select(past.x, current_depth, current_depth > 0.0 || !valid);
    } else if valid {
        // History resampled while the camera moves counts as no march: the pixel's next
        // march replaces it. (Counted on, a blurred history outweighed the marches after a
        // stop: at 1/16 more than 128 frames to come within FLIP 0.01 of the still.)
        samples = select(past.y, 0.0, moving);
        result = history;
        out_depth = past.x;
    } else {
        // Off screen or disoccluded, and not this pixel's turn: march it now.
        let r = march_pixel(pixel);
        samples = 1.0;
        result = vec4<f32>(r.radiance, r.transmittance);
        out_depth = r.depth;
    }
    textureStore(history_out, pixel, result);
    textureStore(meta_out, pixel, vec4<f32>(out_depth, samples, select(0.0, 1.0, surface), 0.0));
    textureStore(cloud_out, pixel, result);
    textureStore(depth_out, pixel, vec4<f32>(out_depth, 0.0, 0.0, 0.0));
}
