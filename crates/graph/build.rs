//! Embeds what the renderer runs from the committed `spirv-out/`: the reflection manifest
//! (which carries the checked frame graph), every SPIR-V module (for the ash backend) and every
//! composed WGSL module (for wgpu), so that no file is needed at run time and both backends run
//! exactly what `cargo xtask build-shaders` wrote (and CI checked fresh).

use std::{env, fs, path::Path};

fn main() {
    let manifest_dir = env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR");
    let dir = Path::new(&manifest_dir).join("../../spirv-out");
    println!("cargo:rerun-if-changed={}", dir.display());
    let mut files: Vec<(String, String)> = fs::read_dir(&dir)
        .map(|entries| {
            entries
                .flatten()
                .map(|e| e.path())
                .filter(|p| {
                    let name = p.file_name().and_then(|n| n.to_str()).unwrap_or_default();
                    name == "manifest.json" || name.ends_with(".spv") || name.ends_with(".wgsl")
                })
                .filter_map(|p| {
                    let name = p.file_name()?.to_str()?.to_owned();
                    let abs = fs::canonicalize(&p).ok()?.to_str()?.to_owned();
                    Some((name, abs))
                })
                .collect()
        })
        .unwrap_or_default();
    files.sort();
    let mut out = String::from(
        "/// `(file name in spirv-out/, bytes)` of the manifest, SPIR-V and composed WGSL.\n\
         pub(crate) static EMBEDDED: &[(&str, &[u8])] = &[\n",
    );
    for (name, abs) in &files {
        println!("cargo:rerun-if-changed={abs}");
        out.push_str(&format!("    ({name:?}, include_bytes!({abs:?})),\n"));
    }
    out.push_str("];\n");
    let out_dir = env::var("OUT_DIR").expect("cargo sets OUT_DIR");
    fs::write(Path::new(&out_dir).join("embedded.rs"), out).expect("OUT_DIR is writable");
}
