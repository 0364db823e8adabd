// Sprite clouds (Wang 2003, "Realistic and Fast Cloud Rendering", Microsoft Flight Simulator
// 2004): alpha-blended camera-facing sprites in boxes, sorted back to front, shaded by artist
// colour levels rather than light transport. A measured baseline for the volumetric model.
//
// The paper's artists place boxes in a modelling tool; here the boxes are the cells of a
// world-anchored grid around the camera (4 rings of 8x8 cells, each ring's cells twice the
// size of the ring inside it, so sprites keep about the same size on screen), and the clouds
// come from the same weather map and density field the march draws (`cloud_density`): every
// cell holds 16 sprites at fixed (hashed) places, and each sprite's alpha follows the density
// at its centre, so clouds form and dissipate through alpha as the weather moves (the paper's
// inner sprites first, outer ones with wider transitions). A cell is one shading group.
//
// Passes (wgsl/graph.toml): `sprite_atlas` draws the 16 sprite textures once; `sprite_build`
// places the sprites; `sprite_sort` orders them back to front (a rank sort); `sprite_draw` rasterises them (premultiplied "over" blending); and
// `sprite_resolve` turns the blended opacity into the transmittance the composite expects.

@group(0) @binding(19) var sprites_out: texture_storage_2d<rgba32float, write>;
@group(0) @binding(20) var sprites_in: texture_2d<f32>;
@group(0) @binding(21) var sprite_order_out: texture_storage_2d<r32float, write>;
@group(0) @binding(22) var sprite_order_in: texture_2d<f32>;
@group(0) @binding(23) var sprite_atlas_out: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(24) var sprite_atlas_in: texture_2d<f32>;
@group(0) @binding(25) var sprite_radiance_in: texture_2d<f32>;
@group(0) @binding(26) var sprite_depth_in: texture_2d<f32>;

const SPRITE_LEVELS: u32 = 4u;          // rings of cells
const SPRITE_CELLS_PER_SIDE: i32 = 8;   // cells per ring side
const SPRITES_PER_CELL: u32 = 16u;      // sprites per cell (box)
const SPRITE_COUNT: u32 = 4096u;        // 4 x 64 cells x 16; the sort holds them all
const SPRITE_CELL0: f32 = 1500.0;       // innermost cell side (m); ring k: 1500 * 2^k
const SPRITE_ALPHA: f32 = 0.7;          // a fully formed sprite's alpha
const SPRITE_MAX_DISTANCE: f32 = 131072.0; // sort keys quantise distances up to this (m)
const ATLAS_TILE: u32 = 64u;            // texels per sprite texture side; 4x4 tiles
// Sun shading levels (the paper's Cmin, Cmed, Cmax, fractions of the sun's light) for the
// far side, the rim and the near side of a shading group.
const SPRITE_C_MIN: f32 = 0.22;
const SPRITE_C_MED: f32 = 0.55;
const SPRITE_C_MAX: f32 = 1.0;
const SPRITE_SKY: f32 = 0.35;           // skylight at noon, as a fraction of the sun's light

// ---------------------------------------------------------------------------------------
// Sprite textures: 16 procedural alpha masks in a 4x4 atlas (0-3 wispy streaks, 4 flat-
// bottomed, 5-15 puffy billows), deterministic from the tile index.

fn atlas_hash(a: u32, b: u32) -> f32 {
    return f32(pcg(a ^ pcg(b)) >> 8u) * (1.0 / 16777216.0);
}

// Value noise on the integer lattice, smoothly interpolated.
fn value_noise(p: vec2<f32>, seed: u32) -> f32 {
    let i = vec2<u32>(floor(p));
    let f = fract(p);
    let s = f * f * (3.0 - 2.0 * f);
    let h = seed * 7919u;
    let a = atlas_hash(i.x + h, i.y);
    let b = atlas_hash(i.x + 1u + h, i.y);
    let c = atlas_hash(i.x + h, i.y + 1u);
    let d = atlas_hash(i.x + 1u + h, i.y + 1u);
    return mix(mix(a, b, s.x), mix(c, d, s.x), s.y);
}

fn value_fbm(p: vec2<f32>, seed: u32) -> f32 {
    var sum = 0.0;
    var weight = 0.5;
    var q = p;
    for (var o = 0u; o < 4u; o += 1u) {
        sum += weight * value_noise(q, seed + o);
        q = q * 2.0;
        weight *= 0.5;
    }
    return sum / 0.9375;
}

// Alpha of sprite texture `tile` at `uv` in [0, 1]^2 (v down). Zero beyond radius 0.48, so
// bilinear filtering never bleeds between tiles.
fn sprite_texture(tile: u32, uv: vec2<f32>) -> f32 {
    let c = uv - 0.5;
    let mask = smoothstep(0.48, 0.36, length(c));
    let noise = value_fbm(uv * 6.0 + vec2<f32>(f32(tile) * 13.0), tile);
    if tile < 4u {
        // Wispy: a stretched streak, broken up by noise stretched the same way.
        let q = c * vec2<f32>(1.0, 3.2);
        let streak = 1.0 - smoothstep(0.05, 0.45, length(q));
        let n = value_fbm(uv * vec2<f32>(3.0, 12.0) + vec2<f32>(f32(tile) * 5.0), tile + 16u);
        return mask * streak * saturate(n * 1.6 - 0.3) * 0.8;
    }
    var billow = 0.0;
    let blobs = 5u + (tile % 4u);
    for (var i = 0u; i < blobs; i += 1u) {
        let centre = vec2<f32>(atlas_hash(tile, 2u * i), atlas_hash(tile, 2u * i + 1u)) - 0.5;
        var at = 0.5 + centre * 0.34;
        if tile == 4u {
            at.y = 0.5 + (centre.y - 0.5) * 0.24; // flat-bottomed: the blobs sit above the base
        }
        let r = 0.14 + 0.1 * atlas_hash(tile, 100u + i);
        let d = length(uv - at) / r;
        billow = max(billow, saturate(1.0 - d * d));
    }
    var a = mask * saturate(billow * 1.5) * (0.55 + 0.45 * noise);
    if tile == 4u {
        a *= smoothstep(0.62, 0.54, uv.y); // a flat base
    }
    return a;
}

@compute @workgroup_size(8, 8, 1)
fn sprite_atlas(@builtin(global_invocation_id) id: vec3<u32>) {
    let tile = (id.y / ATLAS_TILE) * 4u + id.x / ATLAS_TILE;
    let uv = (vec2<f32>(id.xy % ATLAS_TILE) + 0.5) / f32(ATLAS_TILE);
    let a = sprite_texture(tile, uv);
    textureStore(sprite_atlas_out, id.xy, vec4<f32>(a, a, a, a));
}

// ---------------------------------------------------------------------------------------
// Placement.

// The camera-relative position (relative to the ground point below the camera, as the march's
// `rel`) of the point at world `xz` and altitude `alt` on the curved planet: y solves
// x^2 + z^2 + y (y + 2 Rp) = alt (alt + 2 Rp), in the form without cancellation.
fn sprite_rel(xz: vec2<f32>, alt: f32) -> vec3<f32> {
    let rp = frame.planet_radius;
    let d = xz - frame.camera_position.xz;
    let k = alt * (alt + 2.0 * rp) - dot(d, d);
    let y = k / (rp + sqrt(max(rp * rp + k, 0.0)));
    return vec3<f32>(d.x, y, d.y);
}

// A cell of the grid: its world index, side (m) and whether the ring inside covers it.
struct SpriteCell {
    index: vec2<i32>,
    size: f32,
    covered: bool,
}

// Cell `cell` (0..255: ring = cell / 64, then 8x8 in the ring) around the camera. Ring k
// starts at `start`; the ring inside it covers its cells [2, 6)^2 exactly.
fn sprite_cell(cell: u32) -> SpriteCell {
    let level = cell / 64u;
    let local = vec2<i32>(i32(cell % 8u), i32((cell / 8u) % 8u));
    let coarsest = SPRITE_CELL0 * f32(1u << (SPRITE_LEVELS - 1u));
    var start = vec2<i32>(floor(frame.camera_position.xz / coarsest)) - SPRITE_CELLS_PER_SIDE / 2;
    for (var k = SPRITE_LEVELS - 1u; k > level; k -= 1u) {
        start = 2 * (start + 2);
    }
    let covered = level > 0u && all(local >= vec2<i32>(2)) && all(local < vec2<i32>(6));
    return SpriteCell(start + local, SPRITE_CELL0 * f32(1u << level), covered);
}

// One sprite's place and hashed choices, and the density there.
struct SpriteCandidate {
    xz: vec2<f32>,
    alt: f32,
    h: f32,         // height fraction in the layer
    size_hash: f32,
    texture_hash: f32,
    rotation_hash: f32,
    density: f32,
    precipitation: f32,
}

// Sprite `s` of cell `c`: a fixed (hashed) place in the cell, the same every frame, at a
// height where the cell's cloud type puts cloud (stratus low, cumulus through the layer).
fn sprite_candidate(c: SpriteCell, level: u32, s: u32, counters: ptr<function, Counters>) -> SpriteCandidate {
    let seed = pcg(bitcast<u32>(c.index.x) ^ pcg(bitcast<u32>(c.index.y) ^ pcg(level)));
    let u = vec4<f32>(atlas_hash(seed, 8u * s), atlas_hash(seed, 8u * s + 1u), atlas_hash(seed, 8u * s + 2u), atlas_hash(seed, 8u * s + 3u));
    let v = vec2<f32>(atlas_hash(seed, 8u * s + 4u), atlas_hash(seed, 8u * s + 5u));
    let xz = (vec2<f32>(c.index) + u.xy) * c.size;
    let w = sample_weather(vec3<f32>(xz.x, 0.0, xz.y), cloud_layer(0u));
    let h = 0.04 + u.z * (mix(0.3, 0.95, w.cloud_type) - 0.04);
    let alt = frame.cloud_bottom + h * (frame.cloud_top - frame.cloud_bottom);
    var density = 0.0;
    if !c.covered {
        let rel = sprite_rel(xz, alt);
        density = cloud_density(vec3<f32>(xz.x, rel.y, xz.y), alt, counters);
    }
    return SpriteCandidate(xz, alt, h, u.w, v.x, v.y, density, w.precipitation);
}

// One invocation per sprite; each evaluates its whole cell (16 density samples) for the
// shading group's centre rather than share them through workgroup memory, whose WGSL zero
// initialisation naga writes in HLSL as `(float4[16])0`, which glslang's HLSL front end
// rejects. Writes four texels per sprite: row 0 (x, altitude, z, half width), row 1 (group
// centre x, altitude, z; alpha, 0 = not drawn), row 2 (texture, rotation, half height, colour
// level), row 3 (sort key: 0 when not drawn, else 2^20 - quantised distance; far first).
@compute @workgroup_size(64, 1, 1)
fn sprite_build(@builtin(global_invocation_id) id: vec3<u32>) {
    let slot = id.x;
    let cell_index = slot / SPRITES_PER_CELL;
    let level = cell_index / 64u;
    let cell = sprite_cell(cell_index);
    let own = slot % SPRITES_PER_CELL;
    var counters = Counters(0u, 0u, 0u, 0u);

    // The shading group's centre: the density-weighted mean of its sprites.
    var sum = vec4<f32>(0.0);
    var me = sprite_candidate(cell, level, own, &counters);
    for (var i = 0u; i < SPRITES_PER_CELL; i += 1u) {
        let c = sprite_candidate(cell, level, i, &counters);
        sum += vec4<f32>(c.xz.x, c.alt, c.xz.y, 1.0) * c.density;
    }
    count(STAT_DENSITY, counters.density);
    count(STAT_DETAIL, counters.detail);
    let bottom = frame.cloud_bottom;
    let thickness = frame.cloud_top - bottom;
    let middle = (vec2<f32>(cell.index) + 0.5) * cell.size;
    var centre = vec3<f32>(middle.x, bottom + 0.4 * thickness, middle.y);
    if sum.w > 0.0 {
        centre = sum.xyz / sum.w;
    }

    // Forming and dissipating through alpha: inner sprites appear at lower density than outer
    // ones, whose transition is also wider.
    let inner = length(me.xz - centre.xz) < 0.25 * cell.size;
    let morph = select(smoothstep(0.03, 0.15, me.density), smoothstep(0.0, 0.06, me.density), inner);
    let alpha = SPRITE_ALPHA * morph;
    let half_width = 0.5 * cell.size * (0.7 + 0.6 * me.size_hash);
    let half_height = min(half_width, 0.35 * thickness);
    var tile = 5u + min(u32(me.texture_hash * 11.0), 10u);
    var rotation = me.rotation_hash * 2.0 * PI;
    if me.h < 0.12 {
        tile = 4u; // flat bottoms, rotated by at most 5 degrees
        rotation = (me.rotation_hash - 0.5) * (10.0 * PI / 180.0);
    } else if !inner && me.density < 0.1 {
        tile = min(u32(me.texture_hash * 4.0), 3u);
    }
    var key = 0.0;
    if alpha > 0.0 {
        let rel = sprite_rel(me.xz, me.alt) - vec3<f32>(0.0, frame.camera_position.y, 0.0);
        key = 1048576.0 - floor(saturate(length(rel) / SPRITE_MAX_DISTANCE) * 1048575.0);
    }
    textureStore(sprites_out, vec2<u32>(slot, 0u), vec4<f32>(me.xz.x, me.alt, me.xz.y, half_width));
    textureStore(sprites_out, vec2<u32>(slot, 1u), vec4<f32>(centre, alpha));
    // Wang's artists pick darker colour levels for rain clouds; here the weather's
    // precipitation picks them: a fifth of the brightness at precipitation 0.7 (storm).
    let colour_level = 1.0 / (1.0 + 6.0 * max(me.precipitation, 0.0));
    textureStore(sprites_out, vec2<u32>(slot, 2u), vec4<f32>(f32(tile), rotation, half_height, colour_level));
    textureStore(sprites_out, vec2<u32>(slot, 3u), vec4<f32>(key, 0.0, 0.0, 0.0));
}

// ---------------------------------------------------------------------------------------
// Back-to-front order.

// A rank sort: each sprite counts the sprites that come before it (a lower key, or the same
// key and a lower slot, so the ranks are a permutation and ties order the same way every
// time) and writes its slot at its rank. O(n^2) independent comparisons and no sort network,
// which in one workgroup would need 16 KiB of workgroup memory (see sprite_build on why
// there is none). Keys are whole numbers below 2^21: exact in f32.
@compute @workgroup_size(64, 1, 1)
fn sprite_sort(@builtin(global_invocation_id) id: vec3<u32>) {
    let slot = id.x;
    let key = textureLoad(sprites_in, vec2<u32>(slot, 3u), 0).x;
    var rank = 0u;
    for (var j = 0u; j < SPRITE_COUNT; j += 1u) {
        let other = textureLoad(sprites_in, vec2<u32>(j, 3u), 0).x;
        rank += select(0u, 1u, other < key || (other == key && j < slot));
    }
    textureStore(sprite_order_out, vec2<u32>(rank, 0u), vec4<f32>(f32(slot), 0.0, 0.0, 0.0));
}

// ---------------------------------------------------------------------------------------
// Drawing.

struct SpriteVertex {
    @builtin(position) position: vec4<f32>,
    @location(0) uv: vec2<f32>,                    // [-1, 1]^2 in the (rotated) texture
    @location(1) @interpolate(flat) tile: u32,
    @location(2) colour: vec4<f32>,                // radiance; alpha
    @location(3) distance: f32,                    // from the camera (m)
}

struct SpriteTargets {
    @location(0) radiance: vec4<f32>,              // premultiplied radiance; opacity
    @location(1) depth: vec4<f32>,                 // premultiplied distance; opacity
}

// Sky colour by height in the layer, the paper's five artist levels (bases grey-blue, tops
// white), before the time-of-day factor. (Levels as separate constants and a chain of
// branches rather than a constant array: naga writes a module-scope array constant in HLSL as
// a call that glslang's HLSL front end mistakes for recursion.)
const SKY_LEVEL0: vec3<f32> = vec3<f32>(0.42, 0.46, 0.55);
const SKY_LEVEL1: vec3<f32> = vec3<f32>(0.55, 0.59, 0.67);
const SKY_LEVEL2: vec3<f32> = vec3<f32>(0.70, 0.73, 0.80);
const SKY_LEVEL3: vec3<f32> = vec3<f32>(0.84, 0.86, 0.90);
const SKY_LEVEL4: vec3<f32> = vec3<f32>(0.95, 0.96, 0.98);

fn sprite_sky_level(h: f32) -> vec3<f32> {
    let x = saturate(h) * 4.0;
    if x < 1.0 {
        return mix(SKY_LEVEL0, SKY_LEVEL1, x);
    }
    if x < 2.0 {
        return mix(SKY_LEVEL1, SKY_LEVEL2, x - 1.0);
    }
    if x < 3.0 {
        return mix(SKY_LEVEL2, SKY_LEVEL3, x - 2.0);
    }
    return mix(SKY_LEVEL3, SKY_LEVEL4, x - 3.0);
}

// Wang's sun shading: the cosine between (group centre -> vertex) and (group centre -> sun)
// mapped [-1, 0] to [Cmin, Cmed] and [0, 1] to [Cmed, Cmax].
fn sprite_sun_level(cos_angle: f32) -> f32 {
    if cos_angle < 0.0 {
        return mix(SPRITE_C_MIN, SPRITE_C_MED, cos_angle + 1.0);
    }
    return mix(SPRITE_C_MED, SPRITE_C_MAX, cos_angle);
}

// Corner `k` (0..5) of a sprite's two triangles: (-1, -1), (1, -1), (1, 1), (-1, -1), (1, 1),
// (-1, 1), through quad vertices 0, 1, 2, 0, 2, 3.
fn sprite_corner(k: u32) -> vec2<f32> {
    let q = select(k, select(k - 2u, 0u, k == 3u), k >= 3u);
    return vec2<f32>(select(-1.0, 1.0, q == 1u || q == 2u), select(-1.0, 1.0, q >= 2u));
}

@vertex
fn sprite_vertex(@builtin(vertex_index) index: u32) -> SpriteVertex {
    var out: SpriteVertex;
    let slot = u32(textureLoad(sprite_order_in, vec2<u32>(index / 6u, 0u), 0).x);
    let a = textureLoad(sprites_in, vec2<u32>(slot, 0u), 0);
    let b = textureLoad(sprites_in, vec2<u32>(slot, 1u), 0);
    let c = textureLoad(sprites_in, vec2<u32>(slot, 2u), 0);
    if b.w <= 0.0 {
        // Not drawn: a degenerate triangle behind the camera (clipped).
        out.position = vec4<f32>(0.0, 0.0, -1.0, 1.0);
        return out;
    }
    let cam = vec3<f32>(0.0, frame.camera_position.y, 0.0);
    let rel = sprite_rel(a.xz, a.y);
    let to_sprite = rel - cam;
    let distance = length(to_sprite);
    // Facing the camera; within half its width the sprite stops turning toward the camera
    // (Wang: its rotation is obvious up close) and faces the view plane instead, which does
    // not turn as the camera moves through it.
    let half_width = a.w;
    let facing = smoothstep(0.5 * half_width, half_width, distance);
    let to_camera = -to_sprite / max(distance, 1e-3);
    let n = normalize(mix(-frame.camera_forward, to_camera, facing));
    let radial = normalize(rel + vec3<f32>(0.0, frame.planet_radius, 0.0));
    var right = cross(radial, n);
    if length(right) < 1e-3 {
        right = frame.camera_right; // looking straight up or down at it
    }
    right = normalize(right);
    let up = cross(n, right);
    let corner = sprite_corner(index % 6u);
    let offset = right * (corner.x * half_width) + up * (corner.y * c.z);
    let vertex = to_sprite + offset;

    // Camera space to clip space: x right, y up, w = depth along the view (z in [0, w]).
    let x = dot(vertex, frame.camera_right);
    let y = dot(vertex, frame.camera_up);
    let z = dot(vertex, frame.camera_forward);
    let tan_half = frame.tan_half_fov;
    out.position = vec4<f32>(x / (tan_half * frame.aspect), y / tan_half, 0.5 * z, z);

    // Texture coordinates: v down, turned by the sprite's rotation.
    let cs = vec2<f32>(cos(c.y), sin(c.y));
    let t = vec2<f32>(corner.x, -corner.y);
    out.uv = vec2<f32>(t.x * cs.x - t.y * cs.y, t.x * cs.y + t.y * cs.x);
    out.tile = u32(c.x);

    // Shading per vertex: C = (C_sky + C_sun) * alpha_morph.
    let sun = frame.sun_direction;
    let centre = sprite_rel(b.xz, b.y) - cam;
    let from_centre = vertex - centre;
    let cos_angle = dot(from_centre, sun) / max(length(from_centre), 1e-3);
    let day = saturate(sun.y * 4.0 + 0.3);
    let h = saturate((altitude_of(vertex + cam) - frame.cloud_bottom) / (frame.cloud_top - frame.cloud_bottom));
    let e = frame.sun_illuminance;
    let light = e * (sprite_sky_level(h) * (SPRITE_SKY * day) + sprite_sun_level(cos_angle)) * (c.w / PI);
    out.colour = vec4<f32>(light, b.w);
    out.distance = length(vertex);
    return out;
}

@fragment
fn sprite_fragment(in: SpriteVertex) -> SpriteTargets {
    var out: SpriteTargets;
    var a = 0.0;
    if all(abs(in.uv) <= vec2<f32>(1.0)) {
        let tile = vec2<f32>(f32(in.tile % 4u), f32(in.tile / 4u));
        let uv = (tile + 0.5 + 0.5 * in.uv) * 0.25;
        a = textureSampleLevel(sprite_atlas_in, noise_sampler, uv, 0.0).r * in.colour.a;
    }
    out.radiance = vec4<f32>(in.colour.rgb * a, a);
    out.depth = vec4<f32>(in.distance * a, 0.0, 0.0, a);
    return out;
}

// The blended sprites as the march's output: radiance, transmittance = 1 - opacity, and the
// opacity-weighted distance.
@compute @workgroup_size(8, 8, 1)
fn sprite_resolve(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.size) {
        return;
    }
    count(STAT_PIXELS, 1u);
    let c = textureLoad(sprite_radiance_in, id.xy, 0);
    let d = textureLoad(sprite_depth_in, id.xy, 0);
    let opacity = saturate(c.a);
    textureStore(cloud_out, id.xy, vec4<f32>(c.rgb, 1.0 - opacity));
    textureStore(depth_out, id.xy, vec4<f32>(select(0.0, d.r / d.a, d.a > 1e-4), 0.0, 0.0, 0.0));
}
