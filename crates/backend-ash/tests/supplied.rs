//! `Renderer::render_with` (the `conformance` feature): the program's SPIR-V supplied per
//! compute pass, with the plan's bindings as its slots, draws exactly what `render` draws (so
//! everything but the modules and layouts is the same frame), and a wrong number of modules is
//! an error, not a crash.

use stratus_backend_ash::{Error, Options, PassShader, Renderer, Shaders};
use stratus_graph::{FrameInput, FramePlan, Program, plan::PassKind};
use stratus_test_support::{NoiseCache, small};

/// The program's module of the plan's variant for every compute pass, bound as the plan says.
fn committed_per_pass(plan: &FramePlan) -> Vec<PassShader> {
    let program = Program::embedded().expect("program");
    plan.passes
        .iter()
        .filter(|p| matches!(p.kind, PassKind::Compute { .. }))
        .map(|pass| PassShader::from_program(&program, plan, pass).expect("module"))
        .collect()
}

#[test]
fn supplied_modules_draw_what_render_draws() {
    let mut renderer = Renderer::new(Options { validation: true }).expect("renderer");
    let mut noise = NoiseCache::default();
    let scene = small("cumulus-noon", 64, 36);
    let plan = FramePlan::for_scene(&scene, true).expect("plan");
    let noise = noise.get(&scene);
    let frame = FrameInput::new(&plan, &scene, &noise);

    let plain = renderer.render(&frame).expect("render");
    let committed = renderer
        .render_with(&frame, &Shaders::Committed)
        .expect("render_with committed");
    let supplied = renderer
        .render_with(&frame, &Shaders::PerPass(committed_per_pass(&plan)))
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
    match renderer.render_with(&frame, &one) {
        Err(Error::Shader(m)) => assert!(m.contains("1 supplied shader module"), "{m}"),
        other => panic!("one module for two passes: {:?}", other.map(|_| ())),
    }
    renderer.finish().expect("clean teardown");
}
