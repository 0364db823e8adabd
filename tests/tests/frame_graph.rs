//! Adding a pass touches the WGSL and the graph file, and no backend code: this test adds a
//! WGSL module and four passes to a copy of the real tree (a compute pass that accumulates a
//! history resource, a conditional one that starts it, one that computes a persistent LUT only
//! while it is stale, and a raster pass with a depth target, blending and a fixed extent), builds it with the real tool chain (naga, the graph check), and runs it on
//! both backends under validation. They must agree bit for bit, frame by frame, and the
//! values must be what the WGSL computes.

use std::sync::Arc;

use stratus_backend_ash as ash_backend;
use stratus_backend_wgpu as wgpu_backend;
use stratus_graph::{FrameInput, FramePlan, Program, Readback, Requirements};
use stratus_shaders::{Languages, ShaderTree, build_outputs};
use stratus_test_support::{assert_no_wgpu_messages, record_wgpu_log, small, small_noise};

const PROBE_WGSL: &str = r#"
@group(0) @binding(1) var image_in: texture_2d<f32>;
@group(0) @binding(2) var count_in: texture_2d<f32>;
@group(0) @binding(3) var count_out: texture_storage_2d<r32float, write>;
@group(0) @binding(4) var lut_out: texture_storage_2d<r32float, write>;
@group(0) @binding(5) var lut_in: texture_2d<f32>;

// A "LUT", computed once and again only when the host invalidates it: every texel 1.
@compute @workgroup_size(8, 8, 1)
fn bake(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= textureDimensions(lut_out)) { return; }
    textureStore(lut_out, id.xy, vec4<f32>(1.0, 0.0, 0.0, 1.0));
}

// First frame (no history yet): every texel starts at the red of the display image.
@compute @workgroup_size(8, 8, 1)
fn start(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= textureDimensions(count_out)) { return; }
    textureStore(count_out, id.xy, vec4<f32>(textureLoad(image_in, id.xy, 0).r, 0.0, 0.0, 1.0));
}

// Later frames: last frame's value plus the LUT's (one): the LUT must have kept its contents.
@compute @workgroup_size(8, 8, 1)
fn accumulate(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= textureDimensions(count_out)) { return; }
    let previous = textureLoad(count_in, id.xy, 0).r;
    let step = textureLoad(lut_in, vec2<u32>(id.x % 4u, 0u), 0).r;
    textureStore(count_out, id.xy, vec4<f32>(previous + step, 0.0, 0.0, 1.0));
}

// Vertices 0-2: a triangle over the top-left quadrant (x < 0, y > 0 in clip space, y up) at
// depth 0.25; 3-5: one over everything at depth 0.75, hidden where the first is.
@vertex
fn cover(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    var quadrant = array<vec2<f32>, 3>(vec2(0.0, 0.0), vec2(0.0, 4.0), vec2(-4.0, 0.0));
    var whole = array<vec2<f32>, 3>(vec2(-1.0, -1.0), vec2(3.0, -1.0), vec2(-1.0, 3.0));
    if i < 3u {
        return vec4<f32>(quadrant[i], 0.25, 1.0);
    }
    return vec4<f32>(whole[i - 3u], 0.75, 1.0);
}

@fragment
fn shade(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    return vec4<f32>(p.z, 0.125, 0.0, 1.0);
}
"#;

const PROBE_GRAPH: &str = r#"
[[resource]]
name = "count"
kind = "texture"
format = "r32float"
extent = "output/2"
lifetime = "history"

[[resource]]
name = "lut"
kind = "texture"
format = "r32float"
extent = [4, 1]
lifetime = "persistent"

[[resource]]
name = "probe-target"
kind = "texture"
format = "rgba8unorm"
extent = [16, 8]

[[resource]]
name = "probe-depth"
kind = "texture"
format = "depth32float"
extent = [16, 8]

[[pass]]
name = "bake"
module = "probe"
compute = "bake"
extent = [4, 1]
when = "stale:lut"
[pass.bind]
lut_out = "lut"

[[pass]]
name = "start"
module = "probe"
compute = "start"
extent = "output/2"
when = "!history"
[pass.bind]
image_in = "image"
count_out = "count"

[[pass]]
name = "accumulate"
module = "probe"
compute = "accumulate"
extent = "output/2"
when = "history"
[pass.bind]
count_in = "count.previous"
count_out = "count"
lut_in = "lut"

[[pass]]
name = "cover"
module = "probe"
vertex = "cover"
fragment = "shade"
vertices = 6
extent = [16, 8]
color = [{ target = "probe-target", blend = "additive" }]
depth = { target = "probe-depth", compare = "less" }
"#;

/// The real tree plus the probe module and passes, built as `cargo xtask build-shaders` would.
fn probe_program() -> Arc<Program> {
    let tree = ShaderTree::embedded().expect("embedded WGSL");
    let mut files = tree.files.clone();
    files.insert("probe.wgsl".into(), PROBE_WGSL.into());
    files.get_mut("modules.toml").unwrap().push_str(
        "\n[[module]]\nname = \"probe\"\nfiles = [\"probe.wgsl\"]\n[[module.variant]]\nname = \"default\"\ndescription = \"test-only\"\n",
    );
    files.get_mut("graph.toml").unwrap().push_str(PROBE_GRAPH);
    let tree = ShaderTree::from_files("wgsl", files).expect("tree");
    let outputs = build_outputs(&tree, Languages::Spirv).unwrap_or_else(|e| panic!("{e}"));
    Arc::new(Program::from_files(&outputs).expect("program"))
}

#[test]
fn a_pass_added_only_through_the_graph_runs_on_both_backends() {
    record_wgpu_log();
    let program = probe_program();
    let scene = small("cumulus-noon", 20, 12);
    let noise = small_noise(scene.noise.seed);
    let plan = FramePlan::new(&program, &Requirements::of(&scene, false), 20, 12).expect("plan");
    let mut ash = ash_backend::Renderer::with_program(
        ash_backend::Options { validation: true },
        program.clone(),
    )
    .expect("ash");
    let mut wgpu = wgpu_backend::Renderer::with_program(
        wgpu_backend::Options {
            api: wgpu_backend::Api::Vulkan,
            validation: true,
        },
        program,
    )
    .expect("wgpu");
    let readback = Readback {
        output: true,
        resources: vec!["count".into(), "probe-target".into()],
    };
    let mut expected: Vec<f32> = Vec::new();
    for i in 0..5 {
        // Frame 3 invalidates the LUT (its inputs changed): it is baked again then only.
        let invalidate: &[&str] = if i == 3 { &["lut"] } else { &[] };
        let frame = FrameInput::new(&plan, &scene, &noise)
            .with_readback(readback.clone())
            .with_invalidated(invalidate);
        let a = ash.render(&frame).expect("ash frame");
        let w = wgpu.render(&frame).expect("wgpu frame");
        let ran: Vec<&str> = a.timings.iter().map(|t| t.pass.as_str()).collect();
        let expected_passes: &[&str] = match i {
            0 => &["march", "composite", "bake", "start", "cover"],
            3 => &["march", "composite", "bake", "accumulate", "cover"],
            _ => &["march", "composite", "accumulate", "cover"],
        };
        assert_eq!(ran, expected_passes, "frame {i}");
        let ran_wgpu: Vec<&str> = w.timings.iter().map(|t| t.pass.as_str()).collect();
        assert_eq!(ran_wgpu, ran, "frame {i}: the same passes on wgpu");
        let diffs = stratus_test_support::frame_differences(&format!("frame {i}"), &a, &w);
        assert!(diffs.is_empty(), "{}", diffs.join("\n"));

        // count: 10x6 texels (output/2), each the red of the display image at frame 0 (as the
        // device converts UNORM to float: within 1e-6 of n / 255), plus one per frame since
        // (f32 additions, correctly rounded on every Vulkan device).
        let count: Vec<f32> = a.resources["count"]
            .chunks_exact(4)
            .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
            .collect();
        assert_eq!(count.len(), 10 * 6);
        if i == 0 {
            for (k, &c) in count.iter().enumerate() {
                let (x, y) = (k % 10, k / 10);
                let red = f32::from(a.image[(y * 20 + x) * 4]) / 255.0;
                assert!(
                    (c - red).abs() < 1e-6,
                    "texel {k}: {c} is not the red {red}"
                );
            }
            expected = count.clone();
        } else {
            expected.iter_mut().for_each(|e| *e += 1.0);
        }
        assert_eq!(count, expected, "frame {i}");

        // probe-target: cleared, then depth 0.25 (top-left quadrant: rows are top-down, clip
        // space y up) over depth 0.75; additive red = depth of the nearer triangle, green
        // 0.125 (exactly one fragment per pixel passes the depth test).
        let target = &a.resources["probe-target"];
        assert_eq!(target.len(), 16 * 8 * 4);
        for y in 0..8 {
            for x in 0..16 {
                let p = &target[(y * 16 + x) * 4..][..4];
                let red = if x < 8 && y < 4 { 64 } else { 191 };
                assert_eq!(p, [red, 32, 0, 255], "pixel ({x}, {y}) of frame {i}");
            }
        }
    }
    ash.finish().expect("ash teardown");
    drop(wgpu);
    assert_no_wgpu_messages();
}
