// The view march (placeholder until the cloud model lands).

override STATS: bool = false;

struct Stats {
    pixels: atomic<u32>,
}

@group(0) @binding(1) var out_image: texture_storage_2d<rgba16float, write>;
@group(0) @binding(2) var<storage, read_write> stats: Stats;

@compute @workgroup_size(8, 8, 1)
fn march(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.resolution.xy) {
        return;
    }
    if STATS {
        atomicAdd(&stats.pixels, 1u);
    }
    let uv = (vec2<f32>(id.xy) + 0.5) / vec2<f32>(frame.resolution.xy);
    textureStore(out_image, id.xy, vec4<f32>(uv, 0.0, 1.0));
}
