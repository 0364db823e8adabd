//! A [`Program`]: the checked frame graph, the reflection manifest, and the shader code both
//! backends run (composed WGSL for wgpu, committed SPIR-V for ash). The embedded one is the
//! committed `spirv-out/`; tests build their own from a WGSL tree of their own.

use std::{
    collections::BTreeMap,
    sync::{Arc, OnceLock},
};

use crate::{
    desc::GraphDesc,
    error::PlanError,
    manifest::{Manifest, wgsl_name},
};

include!(concat!(env!("OUT_DIR"), "/embedded.rs"));

/// Everything a renderer needs to run frames: the graph, the reflection, the code.
#[derive(Debug)]
pub struct Program {
    /// The reflection manifest.
    pub manifest: Manifest,
    /// The frame graph (from the manifest, where `cargo xtask build-shaders` put it after
    /// checking it against the reflection).
    pub graph: GraphDesc,
    /// Composed WGSL by module name.
    pub wgsl: BTreeMap<String, String>,
    /// SPIR-V words by file name (`<module>.<variant>.spv`).
    pub spirv: BTreeMap<String, Vec<u32>>,
}

impl Program {
    /// The program of the committed `spirv-out/`, embedded at build time (parsed once and
    /// shared by every renderer).
    pub fn embedded() -> Result<Arc<Program>, PlanError> {
        static EMBEDDED_PROGRAM: OnceLock<Result<Arc<Program>, String>> = OnceLock::new();
        EMBEDDED_PROGRAM
            .get_or_init(|| {
                let files: BTreeMap<String, Vec<u8>> = EMBEDDED
                    .iter()
                    .map(|(n, b)| (n.to_string(), b.to_vec()))
                    .collect();
                Program::from_files(&files)
                    .map(Arc::new)
                    .map_err(|e| e.to_string())
            })
            .clone()
            .map_err(|e| PlanError::Manifest(format!("embedded spirv-out/: {e}")))
    }

    /// A program from the files `cargo xtask build-shaders` writes (file name -> bytes):
    /// `manifest.json`, `<module>.wgsl` and `<module>.<variant>.spv` are read, the rest
    /// ignored.
    pub fn from_files(files: &BTreeMap<String, Vec<u8>>) -> Result<Program, PlanError> {
        let bad = PlanError::Manifest;
        let text = files
            .get("manifest.json")
            .ok_or_else(|| bad("no manifest.json".into()))?;
        let text = std::str::from_utf8(text).map_err(|e| bad(format!("manifest.json: {e}")))?;
        let manifest = Manifest::from_json(text).map_err(|e| bad(format!("manifest.json: {e}")))?;
        let graph = manifest
            .graph
            .clone()
            .ok_or_else(|| bad("manifest.json has no frame graph".into()))?;
        let mut wgsl = BTreeMap::new();
        let mut spirv = BTreeMap::new();
        for m in &manifest.modules {
            let name = wgsl_name(&m.name);
            let text = files.get(&name).ok_or_else(|| bad(format!("no {name}")))?;
            let text = String::from_utf8(text.clone()).map_err(|e| bad(format!("{name}: {e}")))?;
            wgsl.insert(m.name.clone(), text);
            for v in &m.variants {
                let bytes = files
                    .get(&v.files.spv)
                    .ok_or_else(|| bad(format!("no {}", v.files.spv)))?;
                spirv.insert(v.files.spv.clone(), words(&v.files.spv, bytes)?);
            }
        }
        Ok(Program {
            manifest,
            graph,
            wgsl,
            spirv,
        })
    }
}

/// SPIR-V bytes as little-endian words, with the magic number checked.
fn words(name: &str, bytes: &[u8]) -> Result<Vec<u32>, PlanError> {
    if !bytes.len().is_multiple_of(4) || bytes.len() < 20 {
        return Err(PlanError::Manifest(format!(
            "{name} is not SPIR-V ({} bytes)",
            bytes.len()
        )));
    }
    let words: Vec<u32> = bytes
        .chunks_exact(4)
        .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    if words[0] != 0x0723_0203 {
        return Err(PlanError::Manifest(format!(
            "{name} is not SPIR-V (no magic number)"
        )));
    }
    Ok(words)
}
