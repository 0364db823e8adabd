//! The reflection manifest (`spirv-out/manifest.json`): entry points, resources, struct
//! layouts as naga computes them, override constants, variants and their files, and the frame
//! graph checked against all of it.
//!
//! `stratus-shaders` writes it at build time (from naga); everything here only reads it, so the
//! renderer, the reference and the comparison tools need no naga. Other engines read the same
//! file to bind the exported shaders.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

pub use crate::desc::Dimension;
use crate::desc::GraphDesc;

/// The whole manifest.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Manifest {
    /// The naga version that translated the shaders.
    pub naga_version: String,
    /// SHA-256 of every file under `wgsl/`.
    pub wgsl_sha256: String,
    /// One entry per module.
    pub modules: Vec<ModuleManifest>,
    /// The frame graph (`wgsl/graph.toml`), as checked against this reflection.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub graph: Option<GraphDesc>,
}

/// Reflection of one module.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ModuleManifest {
    /// Module name.
    pub name: String,
    /// Source files, in composition order.
    pub sources: Vec<String>,
    /// Entry points with their stage and workgroup size.
    pub entry_points: Vec<EntryPointInfo>,
    /// Every bound resource.
    pub resources: Vec<ResourceInfo>,
    /// Layout of every struct used by a uniform or storage resource, as naga lays it out.
    pub structs: Vec<StructInfo>,
    /// Pipeline-overridable constants with their WGSL defaults.
    pub overrides: Vec<OverrideInfo>,
    /// The exported variants.
    pub variants: Vec<VariantInfo>,
}

/// A shader stage.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Stage {
    /// Vertex shader.
    Vertex,
    /// Fragment shader.
    Fragment,
    /// Compute shader.
    Compute,
    /// Any other stage (mesh, task, ray tracing: naga validates Stratus's WGSL without the
    /// capabilities they need, so none occurs).
    Other,
}

/// An entry point.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EntryPointInfo {
    /// Function name.
    pub name: String,
    /// Its stage.
    pub stage: Stage,
    /// Workgroup size (after override resolution with the defaults; zeros for raster stages).
    pub workgroup_size: [u32; 3],
    /// Resources (by `group`/`binding`) that this entry point uses.
    pub uses: Vec<[u32; 2]>,
}

/// What kind of resource a WGSL global binds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum BindingKind {
    /// `var<uniform>`.
    UniformBuffer,
    /// `var<storage>`.
    StorageBuffer,
    /// `texture_2d<f32>` and the like.
    SampledTexture,
    /// `texture_storage_*`.
    StorageTexture,
    /// `sampler`.
    Sampler,
    /// Anything else (no backend binds it).
    Other,
}

/// How a storage resource is accessed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Access {
    /// Read only.
    Read,
    /// Write only.
    Write,
    /// Read and write.
    ReadWrite,
}

impl Access {
    /// Whether the access writes.
    pub fn writes(self) -> bool {
        matches!(self, Self::Write | Self::ReadWrite)
    }
}

/// A bound resource.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ResourceInfo {
    /// WGSL variable name.
    pub name: String,
    /// `@group`.
    pub group: u32,
    /// `@binding`.
    pub binding: u32,
    /// What it binds.
    pub kind: BindingKind,
    /// Storage texture format (WGSL spelling) or `null`.
    pub format: Option<String>,
    /// Access of storage resources, `null` otherwise.
    pub access: Option<Access>,
    /// Texture dimension or `null`.
    pub dimension: Option<Dimension>,
    /// The WGSL type.
    #[serde(rename = "type")]
    pub ty: String,
}

/// A struct's layout.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StructInfo {
    /// Struct name.
    pub name: String,
    /// Size in bytes (naga's span).
    pub size: u32,
    /// Alignment in bytes.
    pub alignment: u32,
    /// Members in order.
    pub members: Vec<MemberInfo>,
}

/// A struct member's layout.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MemberInfo {
    /// Member name.
    pub name: String,
    /// Byte offset.
    pub offset: u32,
    /// Size in bytes.
    pub size: u32,
    /// Alignment in bytes.
    pub alignment: u32,
    /// The WGSL type.
    #[serde(rename = "type")]
    pub ty: String,
}

/// An override constant.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct OverrideInfo {
    /// WGSL identifier.
    pub name: String,
    /// Its type.
    #[serde(rename = "type")]
    pub ty: String,
    /// Its default value (booleans as 0/1), if it has a literal default.
    pub default: Option<f64>,
}

/// An exported variant.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct VariantInfo {
    /// Variant name.
    pub name: String,
    /// What it is for.
    pub description: String,
    /// The override values it sets (others keep their defaults).
    pub overrides: BTreeMap<String, f64>,
    /// Output files: `spv`, `hlsl`, `metal` and `glsl` (entry point -> file).
    pub files: VariantFiles,
}

/// The file names of one variant's translations: the SPIR-V is committed in `spirv-out/`;
/// GLSL, HLSL and MSL are made on demand under the same names (`cargo xtask build-shaders
/// --languages all`, the engine kit's `shaders/`, the conformance suite).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct VariantFiles {
    /// SPIR-V binary.
    pub spv: String,
    /// GLSL per entry point.
    pub glsl: BTreeMap<String, String>,
    /// HLSL (all entry points).
    pub hlsl: String,
    /// Metal Shading Language (all entry points).
    pub metal: String,
}

/// The file name of a variant's output in a language (`ext` like `spv`, `hlsl`, `metal`).
pub fn output_name(module: &str, variant: &str, ext: &str) -> String {
    format!("{module}.{variant}.{ext}")
}

/// The file name of a variant's GLSL for one entry point (`comp`, `vert` or `frag` by stage).
pub fn glsl_name(module: &str, variant: &str, entry: &str, stage: Stage) -> String {
    format!("{module}.{variant}.{entry}.{}.glsl", stage.glsl_suffix())
}

/// The file name of a module's composed WGSL (overrides unresolved), which wgpu compiles.
pub fn wgsl_name(module: &str) -> String {
    format!("{module}.wgsl")
}

impl Stage {
    /// The stage as glslang's `-S` option and GLSL file suffix spell it.
    pub fn glsl_suffix(self) -> &'static str {
        match self {
            Self::Vertex => "vert",
            Self::Fragment => "frag",
            Self::Compute => "comp",
            Self::Other => "other",
        }
    }
}

impl Manifest {
    /// Pretty JSON with a trailing newline (byte-deterministic: fields in declaration order).
    pub fn to_json(&self) -> String {
        let mut s = serde_json::to_string_pretty(self).expect("manifest serialises");
        s.push('\n');
        s
    }

    /// Parses a manifest.
    pub fn from_json(text: &str) -> Result<Self, serde_json::Error> {
        serde_json::from_str(text)
    }

    /// The module called `name`.
    pub fn module(&self, name: &str) -> Option<&ModuleManifest> {
        self.modules.iter().find(|m| m.name == name)
    }
}

impl ModuleManifest {
    /// The struct layout called `name`.
    pub fn struct_layout(&self, name: &str) -> Option<&StructInfo> {
        self.structs.iter().find(|s| s.name == name)
    }

    /// The entry point called `name`.
    pub fn entry_point(&self, name: &str) -> Option<&EntryPointInfo> {
        self.entry_points.iter().find(|e| e.name == name)
    }

    /// The resource bound at `group`/`binding`.
    pub fn resource_at(&self, group: u32, binding: u32) -> Option<&ResourceInfo> {
        self.resources
            .iter()
            .find(|r| r.group == group && r.binding == binding)
    }
}
