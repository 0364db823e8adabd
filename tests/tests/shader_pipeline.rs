//! Snapshot tests of the shader pipeline: the reflection manifest and the diagnostics format.

use std::collections::BTreeMap;

use stratus_shaders::{Languages, ShaderTree, build_outputs, source::MODULES_FILE};

/// Compiles one broken WGSL file from `tests/broken/` as its own module and returns the
/// diagnostics text exactly as `cargo xtask build-shaders` prints it.
fn diagnostics_of(file: &str) -> String {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/broken");
    let text = std::fs::read_to_string(format!("{dir}/{file}")).unwrap();
    let modules = format!(
        "[[module]]\nname = \"broken\"\nfiles = [{file:?}]\n[[module.variant]]\nname = \"default\"\ndescription = \"\"\n"
    );
    let files = BTreeMap::from([
        (MODULES_FILE.to_string(), modules),
        (file.to_string(), text),
    ]);
    let tree = ShaderTree::from_files("tests/broken", files).unwrap();
    match build_outputs(&tree, Languages::Spirv) {
        Ok(_) => panic!("{file} compiled, but it is meant to be broken"),
        Err(d) => d.to_string(),
    }
}

#[test]
fn diagnostic_type_mismatch() {
    insta::assert_snapshot!(diagnostics_of("type_mismatch.wgsl"));
}

#[test]
fn diagnostic_unknown_identifier() {
    insta::assert_snapshot!(diagnostics_of("unknown_identifier.wgsl"));
}

#[test]
fn diagnostic_duplicate_binding() {
    insta::assert_snapshot!(diagnostics_of("duplicate_binding.wgsl"));
}

#[test]
fn diagnostic_bad_attribute() {
    insta::assert_snapshot!(diagnostics_of("bad_attribute.wgsl"));
}

#[test]
fn every_diagnostic_starts_with_file_line_col() {
    for f in [
        "type_mismatch.wgsl",
        "unknown_identifier.wgsl",
        "duplicate_binding.wgsl",
        "bad_attribute.wgsl",
    ] {
        let d = diagnostics_of(f);
        let first = d.lines().next().unwrap();
        let prefix = format!("tests/broken/{f}:");
        assert!(
            first.starts_with(&prefix) && first.contains(": error: "),
            "{first}"
        );
    }
}

/// The manifest of the real WGSL. The source hash is redacted so that editing a comment does
/// not churn the snapshot; `build-shaders --check` already pins the bytes.
#[test]
fn manifest_snapshot() {
    let tree = ShaderTree::embedded().unwrap();
    let outputs = build_outputs(&tree, Languages::Spirv).unwrap_or_else(|d| panic!("{d}"));
    let manifest: serde_json::Value = serde_json::from_slice(&outputs["manifest.json"]).unwrap();
    insta::assert_json_snapshot!(manifest, { ".wgsl_sha256" => "[sha256]" });
}

/// The committed `spirv-out/` is exactly what the embedded WGSL produces, no file more (the
/// same check as `cargo xtask build-shaders --check`, so that `cargo test` alone catches a
/// stale tree).
#[test]
fn spirv_out_is_fresh() {
    let tree = ShaderTree::embedded().unwrap();
    let outputs = build_outputs(&tree, Languages::Spirv).unwrap_or_else(|d| panic!("{d}"));
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../spirv-out");
    for (name, bytes) in &outputs {
        let committed = std::fs::read(format!("{dir}/{name}"))
            .unwrap_or_else(|e| panic!("spirv-out/{name}: {e}; run `cargo xtask build-shaders`"));
        assert!(
            &committed == bytes,
            "spirv-out/{name} is stale; run `cargo xtask build-shaders`"
        );
    }
    for entry in std::fs::read_dir(dir).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().into_owned();
        assert!(
            outputs.contains_key(&name),
            "spirv-out/{name} is not generated (GLSL, HLSL and MSL are made on demand: \
             `cargo xtask build-shaders --languages all`); run `cargo xtask build-shaders`"
        );
    }
}

/// The pinned translations in `tests/out/` (one variant in GLSL, HLSL and MSL) are what naga
/// writes today: a translator change shows up as a diff of these files.
#[test]
fn pinned_translations_are_fresh() {
    let tree = ShaderTree::embedded().unwrap();
    let outputs = build_outputs(&tree, Languages::All).unwrap_or_else(|d| panic!("{d}"));
    let pinned = stratus_shaders::pinned(&outputs);
    let langs: std::collections::BTreeSet<&str> =
        pinned.keys().filter_map(|p| p.split('/').next()).collect();
    assert_eq!(
        langs.into_iter().collect::<Vec<_>>(),
        ["glsl", "hlsl", "msl"],
        "every language is pinned"
    );
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/out");
    for (path, bytes) in &pinned {
        let committed = std::fs::read(format!("{dir}/{path}"))
            .unwrap_or_else(|e| panic!("tests/out/{path}: {e}; run `cargo xtask build-shaders`"));
        assert!(
            &committed == bytes,
            "tests/out/{path} is stale; run `cargo xtask build-shaders`"
        );
    }
}

/// `wgsl/frame.wgsl` is what the uniform block's one declaration generates (the same check as
/// `cargo xtask build-shaders --check`): the WGSL `struct Frame` is never edited by hand.
#[test]
fn the_wgsl_frame_struct_is_generated_from_the_declaration() {
    let tree = ShaderTree::embedded().unwrap();
    for (name, text) in stratus_shaders::generated_sources() {
        assert_eq!(
            tree.files.get(name),
            Some(&text),
            "wgsl/{name} differs from its declaration; run `cargo xtask build-shaders`"
        );
    }
}

/// The Rust uniform block and the WGSL `Frame` struct agree member for member: same names,
/// types, offsets and total size as naga lays the WGSL out. A drift fails here instead of
/// drawing garbage.
#[test]
fn frame_uniforms_match_the_wgsl_layout() {
    use stratus_scene::FrameUniforms;
    let program = stratus_graph::Program::embedded().unwrap();
    let module = program.manifest.module("clouds").unwrap();
    let frame = module
        .struct_layout("Frame")
        .expect("WGSL declares struct Frame");
    assert_eq!(frame.size as usize, FrameUniforms::SIZE, "size");
    assert_eq!(
        frame.members.len(),
        FrameUniforms::MEMBERS.len(),
        "member count"
    );
    for (i, (m, ours)) in frame.members.iter().zip(FrameUniforms::MEMBERS).enumerate() {
        assert_eq!(
            (m.name.as_str(), m.ty.as_str()),
            (ours.name, ours.wgsl),
            "member {i}"
        );
        assert_eq!(m.offset as usize, ours.offset, "offset of {}", ours.name);
        assert_eq!(m.size as usize, ours.size, "size of {}", ours.name);
    }
}

/// The mode codes and flags the Rust uniform block writes are the WGSL's constants, by name
/// and value (naga reads the constants from the composed module): a renumbering on either
/// side fails here.
#[test]
fn mode_codes_and_flags_match_the_wgsl_constants() {
    use stratus_scene::{FrameUniforms, HeightModel, Integration, PhaseModel};
    let tree = ShaderTree::embedded().unwrap();
    let compiled = stratus_shaders::compile_all(&tree).unwrap();
    let clouds = compiled.iter().find(|m| m.spec.name == "clouds").unwrap();
    let constant = |name: &str| -> u32 {
        let (_, c) = clouds
            .module
            .constants
            .iter()
            .find(|(_, c)| c.name.as_deref() == Some(name))
            .unwrap_or_else(|| panic!("the WGSL declares no const {name}"));
        match clouds.module.global_expressions[c.init] {
            naga::Expression::Literal(naga::Literal::U32(v)) => v,
            ref other => panic!("{name} is {other:?}, not a u32 literal"),
        }
    };
    let pairs = [
        ("PHASE_HG", PhaseModel::Hg.code()),
        ("PHASE_TWO_LOBE_HG", PhaseModel::TwoLobeHg.code()),
        ("PHASE_CORNETTE_SHANKS", PhaseModel::CornetteShanks.code()),
        ("INTEGRATION_ANALYTIC", Integration::Analytic.code()),
        ("INTEGRATION_RIEMANN", Integration::Riemann.code()),
        ("HEIGHT_PARABOLA", HeightModel::Parabola.code()),
        ("HEIGHT_CLOUD_TYPES", HeightModel::CloudTypes.code()),
        ("FLAG_BEER_POWDER", FrameUniforms::FLAG_BEER_POWDER),
        ("FLAG_JITTER", FrameUniforms::FLAG_JITTER),
        ("FLAG_DYNAMIC_STEP", FrameUniforms::FLAG_DYNAMIC_STEP),
        ("FLAG_CHECKERBOARD", FrameUniforms::FLAG_CHECKERBOARD),
        ("FLAG_EMPTY_SKIP", FrameUniforms::FLAG_EMPTY_SKIP),
        ("FLAG_PHYSICAL_SKY", FrameUniforms::FLAG_PHYSICAL_SKY),
        ("FLAG_MOONLIT", FrameUniforms::FLAG_MOONLIT),
        ("FLAG_SCENE_DEPTH", FrameUniforms::FLAG_SCENE_DEPTH),
        ("FLAG_HDR_SKY", FrameUniforms::FLAG_HDR_SKY),
        ("FLAG_LIGHT_SHAFTS", FrameUniforms::FLAG_LIGHT_SHAFTS),
        ("FLAG_LEE_DIAGRAM", FrameUniforms::FLAG_LEE_DIAGRAM),
    ];
    for (name, rust) in pairs {
        assert_eq!(constant(name), rust, "{name}");
    }
}

/// The frame graph is checked against the reflection at build time: a graph that binds a
/// WGSL global to a resource of the wrong kind, forgets a binding, or numbers a counter
/// differently from the WGSL is refused with a message naming the pass or resource.
#[test]
fn a_graph_that_disagrees_with_the_wgsl_is_refused() {
    let tree = ShaderTree::embedded().unwrap();
    let graph = &tree.files["graph.toml"];
    let cases = [
        (
            graph.replace("cloud_out = \"cloud\"", "cloud_out = \"depth\""),
            "stores Some(\"rgba32float\") texels",
        ),
        (
            graph.replace("depth_out = \"depth\"\n", ""),
            "the WGSL uses `depth_out`",
        ),
        (
            graph.replace(
                "{ name = \"pixels\", wgsl = \"STAT_PIXELS\" },\n    { name = \"marched_pixels\", wgsl = \"STAT_MARCHED\" },",
                "{ name = \"marched_pixels\", wgsl = \"STAT_MARCHED\" },\n    { name = \"pixels\", wgsl = \"STAT_PIXELS\" },",
            ),
            "counter `marched_pixels` is number 0 here",
        ),
        (
            graph.replace("frame = \"frame\"\nshape_tex", "frame = \"shape\"\nshape_tex"),
            "`frame` is a uniform buffer in the WGSL",
        ),
        (
            graph.replace("when = \"present\"", "when = \"stale:cloud\""),
            "names no computed persistent resource",
        ),
        (
            // Two passes named `march` planned together once temporal upsampling is on.
            graph.replace(
                "plan = \"!temporal & !pathtrace & !basic & !sprites\"",
                "plan = \"!empty_skip\"",
            ),
            "pass `march` is declared more than once, and some plan options plan two of them",
        ),
        (
            graph.replace("plan = \"empty_skip\"", "plan = \"emptyskip\""),
            "names `emptyskip`, which is no plan option",
        ),
        (
            graph.replace("inputs = [\"planet_radius\", \"cloud_bottom\"", "inputs = [\"air\", \"cloud_bottom\""),
            "input `air` is no member of the uniform block `Frame`",
        ),
        (
            graph.replace("\"camera_position.y\", \"tan_half_fov\"", "\"camera_position.y\", \"camera_position.fov\""),
            "input `camera_position.fov` is no member of the uniform block `Frame`, nor a component",
        ),
        (
            // The cloud-shadow map's resource (declared before its pass): made every frame.
            graph.replacen(
                "format = \"r32float\"\nextent = [128, 128]\n",
                "format = \"r32float\"\nextent = [128, 128]\ninputs = [\"sun_direction\"]\n",
                1,
            ),
            "only a computed persistent resource has `inputs`",
        ),
        (
            graph.replacen(
                "tolerance = { sun_direction = 1.7e-4 }",
                "tolerance = { camera_forward = 1.7e-4 }",
                1,
            ),
            "`tolerance` names `camera_forward`, which is not one of its `inputs`",
        ),
        (
            graph.replacen(
                "tolerance = { sun_direction = 1.7e-4 }",
                "tolerance = { sun_direction = 0.0 }",
                1,
            ),
            "the tolerance of `sun_direction` is 0: it must be a finite number > 0",
        ),
    ];
    for (text, expected) in cases {
        assert_ne!(&text, graph, "the case changes the graph");
        let mut files = tree.files.clone();
        files.insert("graph.toml".into(), text);
        let bad = ShaderTree::from_files("wgsl", files).unwrap();
        let err = build_outputs(&bad, Languages::Spirv)
            .expect_err("a bad graph is refused")
            .to_string();
        assert!(
            err.contains("wgsl/graph.toml") && err.contains(expected),
            "expected {expected:?} in:\n{err}"
        );
    }
}

/// The uniform members a function reads, with every function it calls: `frame.<member>` is
/// an `AccessIndex` into the `frame` global.
fn frame_members_read(
    module: &naga::Module,
    function: &naga::Function,
    frame: naga::Handle<naga::GlobalVariable>,
    out: &mut std::collections::BTreeSet<u32>,
) {
    for (_, e) in function.expressions.iter() {
        if let naga::Expression::AccessIndex { base, index } = *e
            && matches!(function.expressions[base], naga::Expression::GlobalVariable(g) if g == frame)
        {
            out.insert(index);
        }
    }
    fn calls(block: &naga::Block, found: &mut Vec<naga::Handle<naga::Function>>) {
        for s in block.iter() {
            match s {
                naga::Statement::Call { function, .. } => found.push(*function),
                naga::Statement::Block(b) => calls(b, found),
                naga::Statement::If { accept, reject, .. } => {
                    calls(accept, found);
                    calls(reject, found);
                }
                naga::Statement::Switch { cases, .. } => {
                    for c in cases {
                        calls(&c.body, found);
                    }
                }
                naga::Statement::Loop {
                    body, continuing, ..
                } => {
                    calls(body, found);
                    calls(continuing, found);
                }
                _ => {}
            }
        }
    }
    let mut callees = Vec::new();
    calls(&function.body, &mut callees);
    for f in callees {
        frame_members_read(module, &module.functions[f], frame, out);
    }
}

/// A computed persistent resource is computed again only when one of its `inputs` changes,
/// so every uniform member its pass reads (through any function it calls) must be among them:
/// a member left out would leave the table stale when it changes. Read from naga's IR of the
/// composed module, not from the text.
#[test]
fn computed_resources_list_every_uniform_member_their_pass_reads() {
    let program = stratus_graph::Program::embedded().unwrap();
    let tree = ShaderTree::embedded().unwrap();
    let compiled = stratus_shaders::compile_all(&tree).unwrap();
    let mut checked = 0;
    for pass in &program.graph.passes {
        let Some(entry) = &pass.compute else { continue };
        let written: Vec<_> = pass
            .bind
            .iter()
            .filter(|(global, _)| global.ends_with("_out"))
            .filter_map(|(_, resource)| program.graph.resource(resource))
            .filter(|r| !r.inputs.is_empty())
            .collect();
        if written.is_empty() {
            continue;
        }
        let module = &compiled
            .iter()
            .find(|m| m.spec.name == pass.module)
            .expect("the pass's module")
            .module;
        let (frame, global) = module
            .global_variables
            .iter()
            .find(|(_, g)| g.name.as_deref() == Some("frame"))
            .expect("the module binds frame");
        let naga::TypeInner::Struct { members, .. } = &module.types[global.ty].inner else {
            panic!("frame is not a struct");
        };
        let function = &module
            .entry_points
            .iter()
            .find(|e| &e.name == entry)
            .expect("the pass's entry point")
            .function;
        let mut read = std::collections::BTreeSet::new();
        frame_members_read(module, function, frame, &mut read);
        assert!(!read.is_empty(), "{}: reads no uniform member", pass.name);
        for resource in written {
            let listed: Vec<&str> = resource
                .inputs
                .iter()
                .map(|i| i.split('.').next().unwrap())
                .collect();
            let missing: Vec<&str> = read
                .iter()
                .map(|&i| members[i as usize].name.as_deref().unwrap())
                .filter(|m| !listed.contains(m))
                .collect();
            assert!(
                missing.is_empty(),
                "resource `{}` (pass `{}`) lists inputs {:?} but its pass also reads {missing:?}: \
                 add them to its `inputs` in wgsl/graph.toml",
                resource.name,
                pass.name,
                resource.inputs
            );
            // A table computed from another goes stale with it: it lists its inputs too.
            for (_, upstream) in pass.bind.iter().filter(|(g, _)| g.ends_with("_in")) {
                let Some(upstream) = program.graph.resource(upstream) else {
                    continue;
                };
                let lacking: Vec<&String> = upstream
                    .inputs
                    .iter()
                    .filter(|i| !resource.inputs.contains(i))
                    .collect();
                assert!(
                    lacking.is_empty(),
                    "resource `{}` is computed from `{}` but lacks its inputs {lacking:?}",
                    resource.name,
                    upstream.name
                );
            }
            checked += 1;
        }
    }
    // The six sky tables and the rainbow's.
    assert_eq!(checked, 7, "computed resources with inputs checked");
}
