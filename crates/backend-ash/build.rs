//! Embeds every `spirv-out/*.spv`, so that the renderer runs the exact committed SPIR-V bytes
//! and needs no files at run time (the same idea as `crates/shaders/build.rs` for the WGSL).

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
                .filter(|p| p.extension().is_some_and(|x| x == "spv"))
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
        "/// `(file name in spirv-out/, bytes)` of every committed SPIR-V module.\n\
         pub(crate) static EMBEDDED_SPIRV: &[(&str, &[u8])] = &[\n",
    );
    for (name, abs) in &files {
        println!("cargo:rerun-if-changed={abs}");
        out.push_str(&format!("    ({name:?}, include_bytes!({abs:?})),\n"));
    }
    out.push_str("];\n");
    let out_dir = env::var("OUT_DIR").expect("cargo sets OUT_DIR");
    fs::write(Path::new(&out_dir).join("spirv.rs"), out).expect("OUT_DIR is writable");
}
