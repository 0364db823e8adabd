//! What a frame plan executes on a GPU, as one hash: the key under which a result of that plan
//! (the path tracer's all-orders truth) may be kept and reused.
//!
//! Hashing the composed WGSL would change with every comment and every pass the plan does not
//! run; hashing the scene alone would miss a change to the shader. So each module's variant is
//! resolved (its overrides substituted), cut down to the entry points the plan's passes call,
//! compacted by naga (every function, global and anonymous constant those entry points do not
//! reach is dropped), and written as SPIR-V without debug information: an edit that cannot
//! change what the plan computes leaves the hash alone, and any edit that can changes it. Named
//! constants stay (naga never drops them), so the hash errs on the side of "changed".

use std::collections::BTreeMap;

use naga::valid::Validator;
use sha2::{Digest, Sha256};
use stratus_graph::plan::{FramePlan, PassKind};

use crate::{
    compile::{capabilities, compile},
    source::{ShaderTree, hex},
    translate::spv_options,
};

/// SHA-256 (hex) of what `plan` runs: per module (in name order), the variant's overrides and
/// the compacted SPIR-V of the entry points its passes call; then every pass and resource of
/// the plan as the plan describes them (order, extents, formats, samplers, bindings).
/// Fails, in words, where the plan names a module the tree lacks or the WGSL does not compile.
pub fn plan_digest(tree: &ShaderTree, plan: &FramePlan) -> Result<String, String> {
    let mut entries: BTreeMap<&str, Vec<&str>> = BTreeMap::new();
    for pass in &plan.passes {
        let e = entries.entry(pass.module.as_str()).or_default();
        match &pass.kind {
            PassKind::Compute { entry, .. } => e.push(entry),
            PassKind::Raster {
                vertex, fragment, ..
            } => e.extend([vertex.as_str(), fragment.as_str()]),
        }
    }
    let mut h = Sha256::new();
    for (name, used) in &entries {
        let spec = tree.module(name).ok_or_else(|| {
            format!("the plan runs module `{name}`, which the shader tree does not declare")
        })?;
        let overrides = plan
            .modules
            .get(*name)
            .map(|m| m.overrides.clone())
            .unwrap_or_default();
        let compiled = compile(tree, spec).map_err(|d| d.to_string())?;
        let (mut module, _) = compiled.resolve(&overrides).map_err(|d| d.to_string())?;
        module
            .entry_points
            .retain(|ep| used.contains(&ep.name.as_str()));
        // Compaction keeps every named constant, used or not; unnamed, the ones the entry
        // points never read go, so a constant added for another pass leaves the digest.
        for (_, c) in module.constants.iter_mut() {
            c.name = None;
        }
        naga::compact::compact(&mut module, naga::compact::KeepUnused::No);
        let info = Validator::new(naga::valid::ValidationFlags::all(), capabilities())
            .validate(&module)
            .map_err(|e| format!("module `{name}` cut to the plan's entry points: {e}"))?;
        let words = naga::back::spv::write_vec(&module, &info, &spv_options(), None)
            .map_err(|e| format!("module `{name}`: SPIR-V of the plan's entry points: {e}"))?;
        h.update(name.as_bytes());
        h.update(format!("{overrides:?}").as_bytes());
        for w in words {
            h.update(w.to_le_bytes());
        }
    }
    h.update(format!("{:?}", plan.passes).as_bytes());
    h.update(format!("{:?}", plan.resources).as_bytes());
    Ok(hex(&h.finalize()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use stratus_scene::Scene;

    /// The GPU path tracer's plan for the default scene, as its truths are traced.
    fn traced_plan() -> FramePlan {
        let mut s = Scene::default().with_size(32, 18);
        s.quality.integrator = stratus_scene::Integrator::Pathtrace;
        s.quality.path_orders = 0;
        FramePlan::for_scene(&s, false).expect("the path tracer's plan")
    }

    /// The embedded tree with `from` replaced by `to` in `file` (which must hold it).
    fn edited(file: &str, from: &str, to: &str) -> ShaderTree {
        let tree = ShaderTree::embedded().expect("the embedded WGSL");
        let mut files = tree.files.clone();
        let text = files.get_mut(file).unwrap_or_else(|| panic!("no {file}"));
        assert!(text.contains(from), "{file} has no `{from}`");
        *text = text.replacen(from, to, 1);
        ShaderTree::from_files("wgsl", files).expect("the edited tree")
    }

    /// The digest changes with what the tracer runs, and only with that: a comment, or a
    /// function only the temporal resolve calls, or a constant it alone declares, leaves it; a
    /// constant of the tracer's random numbers changes it.
    #[test]
    fn the_digest_sees_what_the_tracer_runs_and_nothing_else() {
        let plan = traced_plan();
        let tree = ShaderTree::embedded().unwrap();
        let d = plan_digest(&tree, &plan).unwrap();
        assert_eq!(d, plan_digest(&tree, &plan).unwrap(), "deterministic");

        let commented = edited("pathtrace.wgsl", "fn rng_seed(", "// why\nfn rng_seed(");
        assert_eq!(d, plan_digest(&commented, &plan).unwrap(), "a comment");

        let temporal = edited(
            "temporal.wgsl",
            "return vec2<u32>((v ^ (v >> 1u)) & 1u, v & 1u);",
            "return vec2<u32>(v & 1u, (v ^ (v >> 1u)) & 1u);",
        );
        assert_eq!(
            d,
            plan_digest(&temporal, &plan).unwrap(),
            "a function the tracer never calls"
        );

        let constant = edited(
            "temporal.wgsl",
            "fn ",
            "const ONLY_FOR_THE_RESOLVE: f32 = 0.25;\nfn ",
        );
        assert_eq!(
            d,
            plan_digest(&constant, &plan).unwrap(),
            "a constant the tracer never reads"
        );

        let tracer = edited("pathtrace.wgsl", "(1.0 / 16777216.0)", "(1.0 / 16777215.0)");
        assert_ne!(
            d,
            plan_digest(&tracer, &plan).unwrap(),
            "the tracer's own code"
        );
    }
}
