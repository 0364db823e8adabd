//! Parsing and validation with naga, and resolution of a variant's override constants.

use std::collections::BTreeMap;

use naga::valid::{Capabilities, ModuleInfo, ValidationFlags, Validator};

use crate::{
    diagnostic::{Diagnostic, Diagnostics},
    source::{Composed, ModuleSpec, ShaderTree},
};

/// The naga capabilities Stratus's WGSL may use. Kept to what the shaders need, so that
/// the translated code runs on every backend (lavapipe, llvmpipe GL, D3D, Metal).
pub fn capabilities() -> Capabilities {
    Capabilities::empty()
}

/// A parsed and validated module (overrides still unresolved).
#[derive(Debug)]
pub struct CompiledModule {
    /// The module's declaration.
    pub spec: ModuleSpec,
    /// The composed source and its map back to files.
    pub composed: Composed,
    /// naga's IR.
    pub module: naga::Module,
    /// naga's validation info for `module`.
    pub info: ModuleInfo,
}

/// Parses and validates `spec` from `tree`; on failure every diagnostic names the original
/// `file:line:col`.
pub fn compile(tree: &ShaderTree, spec: &ModuleSpec) -> Result<CompiledModule, Diagnostics> {
    let composed = tree.compose(spec);
    let module = naga::front::wgsl::parse_str(&composed.text).map_err(|e| {
        Diagnostics(vec![Diagnostic::from_spans(
            &composed,
            e.message().to_string(),
            e.labels(),
        )])
    })?;
    let info = Validator::new(ValidationFlags::all(), capabilities())
        .validate(&module)
        .map_err(|e| Diagnostics(vec![Diagnostic::from_with_span(&composed, &e)]))?;
    Ok(CompiledModule {
        spec: spec.clone(),
        composed,
        module,
        info,
    })
}

/// Parses and validates every module of the tree, collecting all failures.
pub fn compile_all(tree: &ShaderTree) -> Result<Vec<CompiledModule>, Diagnostics> {
    let mut ok = Vec::new();
    let mut errors = Vec::new();
    for spec in &tree.modules {
        match compile(tree, spec) {
            Ok(m) => ok.push(m),
            Err(d) => errors.extend(d.0),
        }
    }
    if errors.is_empty() {
        Ok(ok)
    } else {
        Err(Diagnostics(errors))
    }
}

impl CompiledModule {
    /// Resolves override constants to the given values (missing ones keep their WGSL
    /// defaults) and re-validates, giving a module every naga backend can translate.
    pub fn resolve(
        &self,
        overrides: &BTreeMap<String, f64>,
    ) -> Result<(naga::Module, ModuleInfo), Diagnostics> {
        let mut constants = naga::back::PipelineConstants::default();
        for (k, v) in overrides {
            constants.insert(k.clone(), *v);
        }
        let (module, info) = naga::back::pipeline_constants::process_overrides(
            &self.module,
            &self.info,
            None,
            &constants,
        )
        .map_err(|e| {
            let d = match &e {
                naga::back::pipeline_constants::PipelineConstantError::ValidationError(v) => {
                    Diagnostic::from_with_span(&self.composed, v)
                }
                other => Diagnostic::from_spans(
                    &self.composed,
                    format!(
                        "module `{}`: overrides {overrides:?}: {other}",
                        self.spec.name
                    ),
                    [],
                ),
            };
            Diagnostics(vec![d])
        })?;
        Ok((module.into_owned(), info.into_owned()))
    }
}
