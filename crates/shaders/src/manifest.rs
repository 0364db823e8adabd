//! The reflection manifest (`spirv-out/manifest.json`): entry points, resources, struct
//! layouts as naga computes them, override constants, variants and their files.
//!
//! Other engines read it to bind the exported shaders; the ash backend reads it to build its
//! descriptor set layouts; a test checks the Rust uniform struct against its layout.

use std::collections::BTreeMap;

use naga::{AddressSpace, ImageClass, ImageDimension, ScalarKind, StorageAccess, TypeInner};
use serde::{Deserialize, Serialize};

use crate::{
    compile::CompiledModule,
    diagnostic::Diagnostics,
    source::ShaderTree,
    translate::{glsl_name, output_name},
};

/// The whole manifest.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Manifest {
    /// The naga version that translated the shaders.
    pub naga_version: String,
    /// SHA-256 of every file under `wgsl/` (see [`ShaderTree::sha256`]).
    pub wgsl_sha256: String,
    /// One entry per module.
    pub modules: Vec<ModuleManifest>,
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

/// An entry point.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EntryPointInfo {
    /// Function name.
    pub name: String,
    /// `compute`, `vertex`, ...
    pub stage: String,
    /// Workgroup size (after override resolution with the defaults).
    pub workgroup_size: [u32; 3],
    /// Resources (by `group`/`binding`) that this entry point uses.
    pub uses: Vec<[u32; 2]>,
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
    /// `uniform-buffer`, `storage-buffer`, `sampled-texture`, `storage-texture`, `sampler`.
    pub kind: String,
    /// Storage texture format (WGSL spelling) or `null`.
    pub format: Option<String>,
    /// `read`, `read-write`, `write` for storage resources, `null` otherwise.
    pub access: Option<String>,
    /// Texture dimension (`1d`, `2d`, `3d`, `cube`) or `null`.
    pub dimension: Option<String>,
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

/// The files of one variant in `spirv-out/`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct VariantFiles {
    /// SPIR-V binary.
    pub spv: String,
    /// GLSL per compute entry point.
    pub glsl: BTreeMap<String, String>,
    /// HLSL (all entry points).
    pub hlsl: String,
    /// Metal Shading Language (all entry points).
    pub metal: String,
}

impl Manifest {
    /// Reflects every compiled module.
    pub fn build(tree: &ShaderTree, compiled: &[CompiledModule]) -> Result<Self, Diagnostics> {
        let mut modules = Vec::new();
        for m in compiled {
            modules.push(reflect(tree, m)?);
        }
        Ok(Self {
            naga_version: crate::NAGA_VERSION.to_string(),
            wgsl_sha256: tree.sha256(),
            modules,
        })
    }

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
}

fn reflect(tree: &ShaderTree, m: &CompiledModule) -> Result<ModuleManifest, Diagnostics> {
    // Workgroup sizes may depend on overrides: reflect the module resolved with its defaults.
    let (module, _) = m.resolve(&BTreeMap::new())?;
    let mut layouter = naga::proc::Layouter::default();
    layouter
        .update(module.to_ctx())
        .expect("a validated module has a layout");

    let mut resources = Vec::new();
    let mut struct_types = Vec::new();
    for (_, var) in module.global_variables.iter() {
        let Some(rb) = &var.binding else { continue };
        let inner = &module.types[var.ty].inner;
        let (kind, format, access, dimension) = match (var.space, inner) {
            (AddressSpace::Uniform, _) => ("uniform-buffer", None, None, None),
            (AddressSpace::Storage { access }, _) => {
                ("storage-buffer", None, Some(access_name(access)), None)
            }
            (_, TypeInner::Image { dim, class, .. }) => match class {
                ImageClass::Storage { format, access } => (
                    "storage-texture",
                    Some(format!("{format:?}").to_lowercase()),
                    Some(access_name(*access)),
                    Some(dim_name(*dim)),
                ),
                _ => ("sampled-texture", None, None, Some(dim_name(*dim))),
            },
            (_, TypeInner::Sampler { .. }) => ("sampler", None, None, None),
            _ => ("other", None, None, None),
        };
        if matches!(
            var.space,
            AddressSpace::Uniform | AddressSpace::Storage { .. }
        ) {
            collect_structs(&module, var.ty, &mut struct_types);
        }
        resources.push(ResourceInfo {
            name: var.name.clone().unwrap_or_default(),
            group: rb.group,
            binding: rb.binding,
            kind: kind.into(),
            format,
            access: access.map(Into::into),
            dimension: dimension.map(Into::into),
            ty: type_name(&module, var.ty),
        });
    }
    resources.sort_by_key(|r| (r.group, r.binding));

    let structs = struct_types
        .iter()
        .filter_map(|&ty| {
            let t = &module.types[ty];
            let TypeInner::Struct { members, span } = &t.inner else {
                return None;
            };
            let members = members
                .iter()
                .map(|mem| MemberInfo {
                    name: mem.name.clone().unwrap_or_default(),
                    offset: mem.offset,
                    size: module.types[mem.ty].inner.size(module.to_ctx()),
                    alignment: layouter[mem.ty].alignment.round_up(1),
                    ty: type_name(&module, mem.ty),
                })
                .collect();
            Some(StructInfo {
                name: t.name.clone().unwrap_or_default(),
                size: *span,
                alignment: layouter[ty].alignment.round_up(1),
                members,
            })
        })
        .collect();

    let entry_points = module
        .entry_points
        .iter()
        .map(|ep| EntryPointInfo {
            name: ep.name.clone(),
            stage: format!("{:?}", ep.stage).to_lowercase(),
            workgroup_size: ep.workgroup_size,
            uses: uses(&module, ep),
        })
        .collect();

    let overrides = m
        .module
        .overrides
        .iter()
        .map(|(_, o)| OverrideInfo {
            name: o.name.clone().unwrap_or_default(),
            ty: type_name(&m.module, o.ty),
            default: o
                .init
                .and_then(|e| literal_value(&m.module.global_expressions[e])),
        })
        .collect();

    let variants = m
        .spec
        .variants
        .iter()
        .map(|v| VariantInfo {
            name: v.name.clone(),
            description: v.description.clone(),
            overrides: v.overrides.clone(),
            files: VariantFiles {
                spv: output_name(&m.spec.name, &v.name, "spv"),
                glsl: module
                    .entry_points
                    .iter()
                    .filter(|ep| ep.stage == naga::ShaderStage::Compute)
                    .map(|ep| (ep.name.clone(), glsl_name(&m.spec.name, &v.name, &ep.name)))
                    .collect(),
                hlsl: output_name(&m.spec.name, &v.name, "hlsl"),
                metal: output_name(&m.spec.name, &v.name, "metal"),
            },
        })
        .collect();

    Ok(ModuleManifest {
        name: m.spec.name.clone(),
        sources: m
            .spec
            .files
            .iter()
            .map(|f| format!("{}/{f}", tree.label))
            .collect(),
        entry_points,
        resources,
        structs,
        overrides,
        variants,
    })
}

/// Which bound globals an entry point's function (and everything it calls) references.
fn uses(module: &naga::Module, ep: &naga::EntryPoint) -> Vec<[u32; 2]> {
    let mut seen = std::collections::BTreeSet::new();
    let mut stack = vec![&ep.function];
    let mut visited_fns = std::collections::BTreeSet::new();
    while let Some(f) = stack.pop() {
        for (_, expr) in f.expressions.iter() {
            if let naga::Expression::GlobalVariable(g) = expr
                && let Some(rb) = &module.global_variables[*g].binding
            {
                seen.insert([rb.group, rb.binding]);
            }
        }
        visit_calls(&f.body, &mut |h| {
            if visited_fns.insert(h.index()) {
                stack.push(&module.functions[h]);
            }
        });
    }
    seen.into_iter().collect()
}

fn visit_calls(block: &naga::Block, f: &mut impl FnMut(naga::Handle<naga::Function>)) {
    use naga::Statement as S;
    for st in block.iter() {
        match st {
            S::Call { function, .. } => f(*function),
            S::Block(b) => visit_calls(b, f),
            S::If { accept, reject, .. } => {
                visit_calls(accept, f);
                visit_calls(reject, f);
            }
            S::Switch { cases, .. } => cases.iter().for_each(|c| visit_calls(&c.body, f)),
            S::Loop {
                body, continuing, ..
            } => {
                visit_calls(body, f);
                visit_calls(continuing, f);
            }
            _ => {}
        }
    }
}

fn collect_structs(
    module: &naga::Module,
    ty: naga::Handle<naga::Type>,
    out: &mut Vec<naga::Handle<naga::Type>>,
) {
    match &module.types[ty].inner {
        TypeInner::Struct { members, .. } if !out.contains(&ty) => {
            out.push(ty);
            for m in members {
                collect_structs(module, m.ty, out);
            }
        }
        TypeInner::Array { base, .. } | TypeInner::BindingArray { base, .. } => {
            collect_structs(module, *base, out)
        }
        _ => {}
    }
}

fn literal_value(e: &naga::Expression) -> Option<f64> {
    match e {
        naga::Expression::Literal(l) => Some(match *l {
            naga::Literal::Bool(b) => f64::from(u8::from(b)),
            naga::Literal::F32(x) => f64::from(x),
            naga::Literal::F64(x) => x,
            naga::Literal::U32(x) => f64::from(x),
            naga::Literal::I32(x) => f64::from(x),
            naga::Literal::AbstractInt(x) => x as f64,
            naga::Literal::AbstractFloat(x) => x,
            _ => return None,
        }),
        _ => None,
    }
}

fn access_name(a: StorageAccess) -> &'static str {
    let r = a.contains(StorageAccess::LOAD);
    let w = a.contains(StorageAccess::STORE);
    match (r, w) {
        (true, true) => "read-write",
        (false, true) => "write",
        _ => "read",
    }
}

fn dim_name(d: ImageDimension) -> &'static str {
    match d {
        ImageDimension::D1 => "1d",
        ImageDimension::D2 => "2d",
        ImageDimension::D3 => "3d",
        ImageDimension::Cube => "cube",
    }
}

fn scalar_name(s: naga::Scalar) -> String {
    let k = match s.kind {
        ScalarKind::Float => "f",
        ScalarKind::Sint => "i",
        ScalarKind::Uint => "u",
        ScalarKind::Bool => return "bool".into(),
        ScalarKind::AbstractInt => "abstract-int",
        ScalarKind::AbstractFloat => "abstract-float",
    };
    format!("{k}{}", s.width * 8)
}

/// A WGSL-like spelling of a type, for humans reading the manifest.
fn type_name(module: &naga::Module, ty: naga::Handle<naga::Type>) -> String {
    let t = &module.types[ty];
    if let Some(n) = &t.name {
        return n.clone();
    }
    match &t.inner {
        TypeInner::Scalar(s) => scalar_name(*s),
        TypeInner::Vector { size, scalar } => {
            format!("vec{}<{}>", *size as u8, scalar_name(*scalar))
        }
        TypeInner::Matrix {
            columns,
            rows,
            scalar,
        } => format!(
            "mat{}x{}<{}>",
            *columns as u8,
            *rows as u8,
            scalar_name(*scalar)
        ),
        TypeInner::Atomic(s) => format!("atomic<{}>", scalar_name(*s)),
        TypeInner::Array { base, size, .. } => match size {
            naga::ArraySize::Constant(n) => format!("array<{}, {n}>", type_name(module, *base)),
            _ => format!("array<{}>", type_name(module, *base)),
        },
        TypeInner::Image { dim, class, .. } => match class {
            ImageClass::Storage { format, access } => format!(
                "texture_storage_{}<{}, {}>",
                dim_name(*dim),
                format!("{format:?}").to_lowercase(),
                access_name(*access).replace('-', "_")
            ),
            ImageClass::Sampled { kind, .. } => format!(
                "texture_{}<{}>",
                dim_name(*dim),
                scalar_name(naga::Scalar {
                    kind: *kind,
                    width: 4
                })
            ),
            _ => format!("texture_{}", dim_name(*dim)),
        },
        TypeInner::Sampler { comparison } => if *comparison {
            "sampler_comparison"
        } else {
            "sampler"
        }
        .into(),
        other => format!("{other:?}"),
    }
}
