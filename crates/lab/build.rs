//! Embeds the fit's training scenes (`scenes/fit/*.toml`), the cloud types' scenes
//! (`scenes/types/*.toml`) and the layered scenes (`scenes/layers/*.toml`), each in file-name
//! order, so that `stratus fit-scattering` runs the
//! same scenes from any folder and on a machine without the checkout.

use std::{env, fs, path::Path};

fn main() {
    let manifest_dir = env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR");
    let mut out = embed(
        &manifest_dir,
        "fit",
        "TRAINING_SCENES",
        "every training scene",
    );
    out.push_str(&embed(
        &manifest_dir,
        "types",
        "TYPE_SCENES",
        "every cloud type's scene",
    ));
    out.push_str(&embed(
        &manifest_dir,
        "layers",
        "LAYER_SCENES",
        "every layered scene",
    ));
    let out_dir = env::var("OUT_DIR").expect("cargo sets OUT_DIR");
    fs::write(Path::new(&out_dir).join("training_scenes.rs"), out).expect("OUT_DIR is writable");
}

/// `static NAME: &[(&str, &str)]`: `(file name, text)` of every `scenes/FOLDER/*.toml`, in
/// file-name order.
fn embed(manifest_dir: &str, folder: &str, name: &str, what: &str) -> String {
    let dir = Path::new(manifest_dir).join("../../scenes").join(folder);
    println!("cargo:rerun-if-changed={}", dir.display());
    let mut files: Vec<(String, String)> = fs::read_dir(&dir)
        .map(|entries| {
            entries
                .flatten()
                .map(|e| e.path())
                .filter(|p| p.extension().is_some_and(|x| x == "toml"))
                .filter_map(|p| {
                    let name = p.file_name()?.to_str()?.to_owned();
                    let abs = fs::canonicalize(&p).ok()?.to_str()?.to_owned();
                    Some((name, abs))
                })
                .collect()
        })
        .unwrap_or_default();
    files.sort();
    let mut out = format!(
        "/// `(file name in scenes/{folder}/, text)` of {what}, in file-name order.\n\
         pub(crate) static {name}: &[(&str, &str)] = &[\n"
    );
    for (file, abs) in &files {
        println!("cargo:rerun-if-changed={abs}");
        out.push_str(&format!("    ({file:?}, include_str!({abs:?})),\n"));
    }
    out.push_str("];\n");
    out
}
