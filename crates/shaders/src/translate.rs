//! Translation of every variant to SPIR-V, GLSL, HLSL and MSL with fixed options, so that the
//! bytes depend only on the WGSL and the naga version.
//!
//! `spirv-out/` keeps what runs ([`Languages::Spirv`]: SPIR-V per variant, the composed WGSL
//! and the manifest). GLSL, HLSL and MSL ([`Languages::All`]) are made on demand: by
//! `cargo xtask build-shaders --languages all`, by the engine kit and by the conformance suite.
//! One small set of them, the [`PINNED`] variant in every language, is committed under
//! `tests/out/` (naga's snapshot layout) so that a translator change shows up in review.

use std::collections::BTreeMap;

use naga::{ShaderStage, back, valid::ModuleInfo};

use stratus_graph::manifest::{glsl_name, output_name, wgsl_name};

use crate::{
    compile::{CompiledModule, compile_all},
    diagnostic::{Diagnostic, Diagnostics},
    manifest::stage_of,
    source::{ShaderTree, VariantSpec},
};

/// The SPIR-V writer options used for `spirv-out/` and (by the ash backend) at run time.
///
/// No `DEBUG` flag: debug and release builds of the tool must write the same bytes, and
/// Debian's validation layer misreads naga's debug info. SPIR-V 1.0 for the widest reach.
pub fn spv_options() -> back::spv::Options<'static> {
    back::spv::Options {
        lang_version: (1, 0),
        flags: back::spv::WriterFlags::empty(),
        ..Default::default()
    }
}

/// Binding numbers a bind group may use (`@binding` below this): the GLSL flattens bindings
/// to `group * BINDINGS_PER_GROUP + binding`, and the HLSL's sampler heap sits above them.
pub const BINDINGS_PER_GROUP: u32 = 32;

/// GLSL `#version 450` core. Bindings are flattened to `group * BINDINGS_PER_GROUP + binding`
/// and written as explicit `layout(binding = N)`, so the GLSL can be compiled without
/// re-mapping.
fn glsl_options(module: &naga::Module) -> back::glsl::Options {
    let mut binding_map = back::glsl::BindingMap::default();
    for (_, var) in module.global_variables.iter() {
        if let Some(rb) = &var.binding {
            binding_map.insert(*rb, (rb.group * BINDINGS_PER_GROUP + rb.binding) as u8);
        }
    }
    back::glsl::Options {
        version: back::glsl::Version::Desktop(450),
        writer_flags: back::glsl::WriterFlags::empty(),
        binding_map,
        zero_initialize_workgroup_memory: true,
    }
}

/// First register (in space 0) of the HLSL's sampler heaps and sampler index buffers: above
/// every WGSL binding of a group.
const HLSL_SAMPLER_REGISTER: u32 = BINDINGS_PER_GROUP;

/// Shader model 5.1 and naga's defaults (`@group` = space, `@binding` = register), except
/// where the sampler heap lives. naga's HLSL reaches every sampler through a heap (an array of
/// 2048 samplers) and, per bind group, a buffer of heap indices; naga puts them at `s0,
/// space0` and `t<group>, space255`. Both defeat glslang's HLSL front end, which maps register
/// to binding and space to descriptor set: `s0` shares binding 0 with the `b0` uniform block,
/// and space 255 is out of its range (it keeps 7 bits of the set, and any re-mapping option
/// fails with "mapped set out of range"). So they move to space 0 above the groups' bindings:
/// the heap at `s32`, the comparison heap at `s33`, group `g`'s index buffer at `t(34 + g)`.
///
/// Workgroup memory is not zero-initialised: naga writes that as a cast of 0 to the array type
/// (`lane_sums = (float4[32])0;`), which glslang's HLSL front end cannot parse. The WGSL
/// writes every workgroup element before a barrier and reads it after (the path tracer's
/// lanes), so it never reads the initial value.
fn hlsl_options(module: &naga::Module) -> back::hlsl::Options {
    let at = |register: u32| back::hlsl::BindTarget {
        space: 0,
        register,
        binding_array_size: None,
        dynamic_storage_buffer_offsets_index: None,
        restrict_indexing: false,
    };
    let mut sampler_buffer_binding_map = back::hlsl::SamplerIndexBufferBindingMap::default();
    for (_, var) in module.global_variables.iter() {
        if let Some(rb) = &var.binding {
            sampler_buffer_binding_map.insert(
                back::hlsl::SamplerIndexBufferKey { group: rb.group },
                at(HLSL_SAMPLER_REGISTER + 2 + rb.group),
            );
        }
    }
    back::hlsl::Options {
        sampler_heap_target: back::hlsl::SamplerHeapBindTargets {
            standard_samplers: at(HLSL_SAMPLER_REGISTER),
            comparison_samplers: at(HLSL_SAMPLER_REGISTER + 1),
        },
        sampler_buffer_binding_map,
        zero_initialize_workgroup_memory: false,
        ..Default::default()
    }
}

/// Bounds-check policies: naga's defaults, the same for every target.
fn policies() -> naga::proc::BoundsCheckPolicies {
    naga::proc::BoundsCheckPolicies::default()
}

/// Which translations [`build_outputs`] makes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Languages {
    /// What `spirv-out/` keeps: SPIR-V of every variant (with the composed WGSL and the
    /// manifest, which [`build_outputs`] always writes).
    Spirv,
    /// SPIR-V, GLSL (one file per entry point), HLSL and MSL of every variant.
    All,
}

/// The `(module, variant)` whose GLSL, HLSL and MSL are committed under `tests/out/`: small,
/// with a vertex and a fragment stage, and untouched by edits to the cloud model.
pub const PINNED: (&str, &str) = ("present", "default");

/// Where a translation of the [`PINNED`] variant lives under `tests/out/` (`glsl/…`, `hlsl/…`,
/// `msl/…`, as naga's own snapshots are laid out), or `None` for any other file.
pub fn pinned_path(name: &str) -> Option<String> {
    let prefix = format!("{}.{}.", PINNED.0, PINNED.1);
    if !name.starts_with(&prefix) {
        return None;
    }
    let lang = if name.ends_with(".glsl") {
        "glsl"
    } else if name.ends_with(".hlsl") {
        "hlsl"
    } else if name.ends_with(".metal") {
        "msl"
    } else {
        return None;
    };
    Some(format!("{lang}/{name}"))
}

/// The pinned translations among `outputs` (a [`Languages::All`] build): path under
/// `tests/out/` -> bytes.
pub fn pinned(outputs: &BTreeMap<String, Vec<u8>>) -> BTreeMap<String, Vec<u8>> {
    outputs
        .iter()
        .filter_map(|(name, bytes)| Some((pinned_path(name)?, bytes.clone())))
        .collect()
}

/// Whether `spirv-out/` keeps the output called `name` (SPIR-V, composed WGSL, manifest).
pub fn is_committed(name: &str) -> bool {
    name == "manifest.json" || name.ends_with(".spv") || name.ends_with(".wgsl")
}

/// Translates one variant to SPIR-V and, with [`Languages::All`], to GLSL, HLSL and MSL.
/// Returns `(file name, bytes)` pairs.
pub fn translate_variant(
    compiled: &CompiledModule,
    variant: &VariantSpec,
    languages: Languages,
) -> Result<Vec<(String, Vec<u8>)>, Diagnostics> {
    let (module, info) = compiled.resolve(&variant.overrides)?;
    let name = &compiled.spec.name;
    let fail = |lang: &str, e: &dyn std::fmt::Display| {
        Diagnostics(vec![Diagnostic::from_spans(
            &compiled.composed,
            format!(
                "module `{name}` variant `{}`: {lang} translation failed: {e}",
                variant.name
            ),
            [],
        )])
    };
    let mut out = Vec::new();

    let words = back::spv::write_vec(&module, &info, &spv_options(), None)
        .map_err(|e| fail("SPIR-V", &e))?;
    out.push((
        output_name(name, &variant.name, "spv"),
        bytemuck_words(&words),
    ));
    if languages == Languages::Spirv {
        return Ok(out);
    }

    for ep in &module.entry_points {
        let text = glsl(&module, &info, ep.stage, &ep.name).map_err(|e| fail("GLSL", &e))?;
        out.push((
            glsl_name(name, &variant.name, &ep.name, stage_of(ep.stage)),
            text.into_bytes(),
        ));
    }

    let mut hlsl = String::new();
    back::hlsl::Writer::new(
        &mut hlsl,
        &hlsl_options(&module),
        &back::hlsl::PipelineOptions::default(),
    )
    .write(&module, &info, None)
    .map_err(|e| fail("HLSL", &e))?;
    out.push((output_name(name, &variant.name, "hlsl"), hlsl.into_bytes()));

    let msl_options = back::msl::Options {
        lang_version: (2, 1),
        ..Default::default()
    };
    let (msl, _) = back::msl::write_string(
        &module,
        &info,
        &msl_options,
        &back::msl::PipelineOptions::default(),
    )
    .map_err(|e| fail("MSL", &e))?;
    out.push((output_name(name, &variant.name, "metal"), msl.into_bytes()));
    Ok(out)
}

fn glsl(
    module: &naga::Module,
    info: &ModuleInfo,
    stage: ShaderStage,
    entry: &str,
) -> Result<String, back::glsl::Error> {
    let options = glsl_options(module);
    let pipeline = back::glsl::PipelineOptions {
        shader_stage: stage,
        entry_point: entry.to_string(),
        multiview: None,
    };
    let mut text = String::new();
    back::glsl::Writer::new(&mut text, module, info, &options, &pipeline, policies())?.write()?;
    Ok(text)
}

fn bytemuck_words(words: &[u32]) -> Vec<u8> {
    words.iter().flat_map(|w| w.to_le_bytes()).collect()
}

/// Every output of the tree in `languages`: file name -> bytes, the composed WGSL of each
/// module and `manifest.json` included. [`Languages::Spirv`] is exactly what `spirv-out/`
/// holds.
pub fn build_outputs(
    tree: &ShaderTree,
    languages: Languages,
) -> Result<BTreeMap<String, Vec<u8>>, Diagnostics> {
    let compiled = compile_all(tree)?;
    let mut files = BTreeMap::new();
    let mut errors = Vec::new();
    for m in &compiled {
        for v in &m.spec.variants {
            match translate_variant(m, v, languages) {
                Ok(list) => files.extend(list),
                Err(d) => errors.extend(d.0),
            }
        }
    }
    if !errors.is_empty() {
        return Err(Diagnostics(errors));
    }
    for m in &compiled {
        // The composed WGSL (overrides unresolved) is what wgpu compiles at run time, with
        // the plan's override values; other engines and browsers can take it too.
        files.insert(
            wgsl_name(&m.spec.name),
            m.composed.text.clone().into_bytes(),
        );
    }
    let manifest = crate::manifest::build(tree, &compiled)?;
    files.insert("manifest.json".into(), manifest.to_json().into_bytes());
    Ok(files)
}
