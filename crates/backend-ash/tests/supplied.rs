//! `Renderer::render_with`: the committed SPIR-V supplied per pass, with the plan's bindings as
//! its slots, draws exactly what `render` draws (so everything but the modules and layouts is
//! the same frame), and a wrong number of modules is an error, not a crash.

mod common;

use stratus_backend_ash::{Error, Options, PassShader, Renderer, Shaders, Slot, SlotContent};
use stratus_shaders::FramePlan;

/// The committed module of the plan's variant for every pass, bound as the plan says.
fn committed_per_pass(plan: &FramePlan) -> Vec<PassShader> {
    let path = format!(
        "{}/../../spirv-out/{}",
        env!("CARGO_MANIFEST_DIR"),
        plan.spv_file
    );
    let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let words: Vec<u32> = bytes
        .chunks_exact(4)
        .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    plan.passes
        .iter()
        .map(|pass| PassShader {
            spirv: words.clone(),
            entry: pass.entry_point.clone(),
            slots: pass
                .bindings
                .iter()
                .map(|b| Slot {
                    set: b.group,
                    binding: b.binding,
                    content: SlotContent::Plan(b.resource),
                })
                .collect(),
        })
        .collect()
}

#[test]
fn supplied_modules_draw_what_render_draws() {
    let mut renderer = Renderer::new(Options { validation: true }).expect("renderer");
    let mut noise = common::NoiseCache::default();
    let scene = common::small("cumulus-noon", 64, 36);
    let plan = FramePlan::for_scene(&scene, true).expect("plan");
    let uniforms = scene.uniforms();
    let noise = noise.get(&scene);

    let plain = renderer.render(&plan, &uniforms, noise).expect("render");
    let committed = renderer
        .render_with(&plan, &Shaders::Committed, &uniforms, noise)
        .expect("render_with committed");
    let supplied = renderer
        .render_with(
            &plan,
            &Shaders::PerPass(committed_per_pass(&plan)),
            &uniforms,
            noise,
        )
        .expect("render_with per pass");
    let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    for other in [&committed, &supplied] {
        assert_eq!(bits(&plain.radiance), bits(&other.radiance));
        assert_eq!(bits(&plain.depth), bits(&other.depth));
        assert_eq!(plain.image, other.image);
        assert_eq!(plain.stats, other.stats);
        assert_eq!(plain.timings.len(), other.timings.len());
    }

    let one = Shaders::PerPass(committed_per_pass(&plan).into_iter().take(1).collect());
    match renderer.render_with(&plan, &one, &uniforms, noise) {
        Err(Error::Shader(m)) => assert!(m.contains("1 supplied shader module"), "{m}"),
        other => panic!("one module for two passes: {:?}", other.map(|_| ())),
    }
    renderer.finish().expect("clean teardown");
}
