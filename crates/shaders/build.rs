//! Embeds every file under the workspace's `wgsl/` folder, so that the tools carry the
//! exact WGSL they were built from (one source of truth) and need no files at run time.

use std::{env, fs, path::Path};

fn main() {
    let manifest_dir = env::var("CARGO_MANIFEST_DIR").unwrap();
    let root = Path::new(&manifest_dir).join("../..");
    let wgsl = root.join("wgsl");
    println!("cargo:rerun-if-changed={}", wgsl.display());
    let mut files = Vec::new();
    collect(&wgsl, &wgsl, &mut files);
    files.sort();
    let mut out = String::from(
        "/// `(path relative to wgsl/, contents)` of every embedded shader source file.\n",
    );
    out.push_str("pub static EMBEDDED_FILES: &[(&str, &str)] = &[\n");
    for (rel, abs) in &files {
        println!("cargo:rerun-if-changed={abs}");
        out.push_str(&format!("    ({rel:?}, include_str!({abs:?})),\n"));
    }
    out.push_str("];\n");

    // The naga version goes into the manifest; read it from the lock file so it cannot drift.
    let lock = fs::read_to_string(root.join("Cargo.lock")).unwrap_or_default();
    println!(
        "cargo:rerun-if-changed={}",
        root.join("Cargo.lock").display()
    );
    let version = lock
        .split("[[package]]")
        .find(|p| p.contains("name = \"naga\"\n"))
        .and_then(|p| p.lines().find_map(|l| l.strip_prefix("version = \"")))
        .map(|v| v.trim_end_matches('"').to_string())
        .unwrap_or_else(|| "unknown".into());
    out.push_str(&format!(
        "/// The naga version this crate was built against (from Cargo.lock).\npub const NAGA_VERSION: &str = {version:?};\n"
    ));
    fs::write(
        Path::new(&env::var("OUT_DIR").unwrap()).join("embedded.rs"),
        out,
    )
    .unwrap();
}

fn collect(base: &Path, dir: &Path, files: &mut Vec<(String, String)>) {
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            println!("cargo:rerun-if-changed={}", path.display());
            collect(base, &path, files);
        } else {
            let rel = path
                .strip_prefix(base)
                .unwrap()
                .to_string_lossy()
                .replace('\\', "/");
            let abs = fs::canonicalize(&path)
                .unwrap()
                .to_string_lossy()
                .into_owned();
            files.push((rel, abs));
        }
    }
}
