//! The WGSL loading and diagnostic path on arbitrary source: a one-file module compiled by
//! naga through Stratus's tree (composition, validation, file:line:col diagnostics).
#![no_main]

use std::collections::BTreeMap;

use libfuzzer_sys::fuzz_target;

const MODULES: &str = r#"
[[module]]
name = "fuzz"
files = ["a.wgsl", "b.wgsl"]

[[module.variant]]
name = "default"
description = "the fuzzed source"
"#;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    // Two files, so that diagnostics must map composed positions back to a file.
    let Some((a, b)) = text.split_at_checked(text.len() / 2) else {
        return;
    };
    let files = BTreeMap::from([
        ("modules.toml".to_string(), MODULES.to_string()),
        ("a.wgsl".to_string(), a.to_string()),
        ("b.wgsl".to_string(), b.to_string()),
    ]);
    let Ok(tree) = stratus_shaders::ShaderTree::from_files("wgsl", files) else {
        return;
    };
    if let Err(diagnostics) = stratus_shaders::compile_all(&tree) {
        let _ = diagnostics.to_string();
    }
});
