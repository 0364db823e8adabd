// Empty-space skipping: a coarse occupancy grid over one tile of the weather map. Each cell
// holds the largest coverage value (the map's R) that a bilinear lookup inside the cell can
// return; where even that leaves no cloud under the scene's coverage, the density is 0 in the
// whole cell, at every altitude, and the view ray jumps to the cell's edge.

const OCCUPANCY_CELLS: u32 = 64u; // cells per side of the grid (one weather-map tile)

@group(0) @binding(11) var occupancy_in: texture_2d<f32>;                         // max coverage per cell
@group(0) @binding(12) var occupancy_out: texture_storage_2d<r32float, write>;   // the same, written once

// Builds the grid (a computed persistent resource: once, and again only when invalidated).
@compute @workgroup_size(8, 8, 1)
fn occupancy(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= vec2<u32>(OCCUPANCY_CELLS)) {
        return;
    }
    let size = vec2<i32>(textureDimensions(weather_tex));
    let cells = i32(OCCUPANCY_CELLS);
    // Texels whose bilinear footprint reaches into the cell: the cell's own and a one-texel
    // border (wrapping, as the sampler repeats).
    let lo = vec2<i32>(id.xy) * size / cells - 1;
    let hi = (vec2<i32>(id.xy) + 1) * size / cells;
    var m = 0.0;
    for (var y = lo.y; y <= hi.y; y++) {
        for (var x = lo.x; x <= hi.x; x++) {
            let t = (vec2<i32>(x, y) % size + size) % size;
            m = max(m, textureLoad(weather_tex, t, 0).r);
        }
    }
    textureStore(occupancy_out, id.xy, vec4<f32>(m, 0.0, 0.0, 0.0));
}

// At world position `p` on a ray along unit `d`: the distance to the edge of p's cell if
// the cell is empty (no cloud at any altitude), else 0.
fn empty_cell_exit(p: vec3<f32>, d: vec3<f32>) -> f32 {
    // The grid holds the map's coverage (R) alone: cumulus on convective cells stands where
    // the cell field (A) says, with or without it, and an anvil spreads kilometres beyond
    // its tower's cell, so no cell is known empty then.
    if frame.convective_cells > 0.0 || frame.anvil > 0.0 {
        return 0.0;
    }
    let cells = f32(OCCUPANCY_CELLS);
    let uv = fract((p.xz - frame.weather_offset) / frame.weather_period) * cells;
    let cell = min(vec2<u32>(uv), vec2<u32>(OCCUPANCY_CELLS - 1u));
    let m = textureLoad(occupancy_in, cell, 0).r;
    // sample_weather's coverage: saturate(r + 2 (coverage - 0.5)); a margin of one 8-bit
    // step covers rounding in the filtered lookup.
    if m + 2.0 * (frame.coverage - 0.5) > -1.0 / 255.0 {
        return 0.0;
    }
    // The ray's horizontal motion is linear in t: the nearer of the two cell walls it heads to.
    let cell_m = frame.weather_period / cells;
    let inside = (uv - vec2<f32>(cell)) * cell_m; // metres from the cell's low corner
    var exit = 1e30;
    if d.x > 1e-6 {
        exit = min(exit, (cell_m - inside.x) / d.x);
    } else if d.x < -1e-6 {
        exit = min(exit, inside.x / -d.x);
    }
    if d.z > 1e-6 {
        exit = min(exit, (cell_m - inside.y) / d.z);
    } else if d.z < -1e-6 {
        exit = min(exit, inside.y / -d.z);
    }
    return max(exit, 0.0);
}
