//! Reflection: naga's view of every compiled module, written as the manifest
//! (`spirv-out/manifest.json`; its types live in `stratus-graph`, which reads it at run time
//! without naga), with the frame graph checked against it.

use std::collections::BTreeMap;

use naga::{AddressSpace, ImageClass, ImageDimension, ScalarKind, StorageAccess, TypeInner};
use stratus_graph::{
    GraphDesc,
    manifest::{
        Access, BindingKind, Dimension, EntryPointInfo, Manifest, MemberInfo, ModuleManifest,
        OverrideInfo, ResourceInfo, Stage, StructInfo, VariantFiles, VariantInfo, glsl_name,
        output_name,
    },
};

use crate::{
    compile::CompiledModule,
    diagnostic::{Diagnostic, Diagnostics},
    source::ShaderTree,
};

pub use crate::source::GRAPH_FILE;

/// Reflects every compiled module and, where the tree has a [`GRAPH_FILE`], checks the frame
/// graph against that reflection and puts it in the manifest.
pub fn build(tree: &ShaderTree, compiled: &[CompiledModule]) -> Result<Manifest, Diagnostics> {
    let mut modules = Vec::new();
    for m in compiled {
        modules.push(reflect(tree, m)?);
    }
    let mut manifest = Manifest {
        naga_version: crate::NAGA_VERSION.to_string(),
        wgsl_sha256: tree.sha256(),
        modules,
        graph: None,
    };
    if let Some(text) = tree.files.get(GRAPH_FILE) {
        let origin = format!("{}/{GRAPH_FILE}", tree.label);
        let fail = |e: stratus_graph::GraphError| {
            Diagnostics(vec![Diagnostic {
                location: None,
                file: e.origin.clone(),
                message: e.to_string(),
                label: String::new(),
                width: 1,
                notes: Vec::new(),
            }])
        };
        let graph = GraphDesc::from_toml(text, &origin).map_err(fail)?;
        let constant = |module: &str, name: &str| -> Option<f64> {
            let m = compiled.iter().find(|c| c.spec.name == module)?;
            m.module
                .constants
                .iter()
                .find(|(_, c)| c.name.as_deref() == Some(name))
                .and_then(|(_, c)| literal_value(&m.module.global_expressions[c.init]))
        };
        graph
            .check(&manifest, &origin, Some(&constant))
            .map_err(fail)?;
        manifest.graph = Some(graph);
    }
    Ok(manifest)
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
            (AddressSpace::Uniform, _) => (BindingKind::UniformBuffer, None, None, None),
            (AddressSpace::Storage { access }, _) => (
                BindingKind::StorageBuffer,
                None,
                Some(access_of(access)),
                None,
            ),
            (_, TypeInner::Image { dim, class, .. }) => match class {
                ImageClass::Storage { format, access } => (
                    BindingKind::StorageTexture,
                    Some(format!("{format:?}").to_lowercase()),
                    Some(access_of(*access)),
                    Some(dimension_of(*dim)),
                ),
                _ => (
                    BindingKind::SampledTexture,
                    None,
                    None,
                    Some(dimension_of(*dim)),
                ),
            },
            (_, TypeInner::Sampler { .. }) => (BindingKind::Sampler, None, None, None),
            _ => (BindingKind::Other, None, None, None),
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
            kind,
            format,
            access,
            dimension,
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
            stage: stage_of(ep.stage),
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
                    .map(|ep| {
                        (
                            ep.name.clone(),
                            glsl_name(&m.spec.name, &v.name, &ep.name, stage_of(ep.stage)),
                        )
                    })
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

/// The manifest's stage of a naga stage.
pub fn stage_of(s: naga::ShaderStage) -> Stage {
    match s {
        naga::ShaderStage::Vertex => Stage::Vertex,
        naga::ShaderStage::Fragment => Stage::Fragment,
        naga::ShaderStage::Compute => Stage::Compute,
        _ => Stage::Other,
    }
}

fn access_of(a: StorageAccess) -> Access {
    match access_name(a) {
        "read-write" => Access::ReadWrite,
        "write" => Access::Write,
        _ => Access::Read,
    }
}

fn dimension_of(d: ImageDimension) -> Dimension {
    match d {
        ImageDimension::D1 => Dimension::D1,
        ImageDimension::D2 => Dimension::D2,
        ImageDimension::D3 => Dimension::D3,
        ImageDimension::Cube => Dimension::Cube,
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
