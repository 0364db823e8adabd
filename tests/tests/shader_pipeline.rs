//! Snapshot tests of the shader pipeline: the reflection manifest and the diagnostics format.

use std::collections::BTreeMap;

use stratus_shaders::{ShaderTree, build_outputs, source::MODULES_FILE};

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
    match build_outputs(&tree) {
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
    let outputs = build_outputs(&tree).unwrap_or_else(|d| panic!("{d}"));
    let manifest: serde_json::Value = serde_json::from_slice(&outputs["manifest.json"]).unwrap();
    insta::assert_json_snapshot!(manifest, { ".wgsl_sha256" => "[sha256]" });
}

/// The committed `spirv-out/` matches what the embedded WGSL produces (the same check as
/// `cargo xtask build-shaders --check`, so that `cargo test` alone catches a stale tree).
#[test]
fn spirv_out_is_fresh() {
    let tree = ShaderTree::embedded().unwrap();
    let outputs = build_outputs(&tree).unwrap_or_else(|d| panic!("{d}"));
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../spirv-out");
    for (name, bytes) in &outputs {
        let committed = std::fs::read(format!("{dir}/{name}"))
            .unwrap_or_else(|e| panic!("spirv-out/{name}: {e}; run `cargo xtask build-shaders`"));
        assert!(
            &committed == bytes,
            "spirv-out/{name} is stale; run `cargo xtask build-shaders`"
        );
    }
}

/// The Rust uniform block and the WGSL `Frame` struct agree member for member: same names,
/// types, offsets and total size as naga lays the WGSL out. A drift fails here instead of
/// drawing garbage.
#[test]
fn frame_uniforms_match_the_wgsl_layout() {
    use stratus_scene::FrameUniforms;
    let manifest = stratus_shaders::plan::embedded_manifest().unwrap();
    let module = manifest.module(stratus_shaders::plan::MODULE).unwrap();
    let frame = module
        .struct_layout("Frame")
        .expect("WGSL declares struct Frame");
    assert_eq!(frame.size as usize, FrameUniforms::SIZE, "size");
    assert_eq!(
        frame.members.len(),
        FrameUniforms::MEMBERS.len(),
        "member count"
    );
    for (i, (m, (name, ty))) in frame.members.iter().zip(FrameUniforms::MEMBERS).enumerate() {
        assert_eq!((m.name.as_str(), m.ty.as_str()), (name, ty), "member {i}");
        assert_eq!(m.offset as usize, 16 * i, "offset of {name}");
    }
}
