//! The ash backend (committed SPIR-V) and the wgpu backend (wgpu's own translation of the
//! WGSL) draw the same frame bit for bit on the same device, for every preset, with and
//! without the statistics variant (so the counters are compared too), plus an unshadowed
//! scene so that every committed `.spv` runs. Both run with validation; any validation
//! message fails the test.

use std::collections::BTreeSet;

use stratus_backend_ash as ash_backend;
use stratus_backend_wgpu as wgpu_backend;
use stratus_graph::{FrameInput, FrameOutput, FramePlan, Readback};
use stratus_scene::Scene;
use stratus_test_support::{
    NoiseCache, assert_no_wgpu_messages, frame_differences, record_wgpu_log, small,
};

/// Both renderers on the same device, with validation.
fn renderers() -> (ash_backend::Renderer, wgpu_backend::Renderer) {
    let ash = ash_backend::Renderer::new(ash_backend::Options { validation: true })
        .expect("ash renderer");
    let wgpu = wgpu_backend::Renderer::new(wgpu_backend::Options {
        api: wgpu_backend::Api::Vulkan,
        validation: true,
    })
    .expect("wgpu renderer");
    (ash, wgpu)
}

#[test]
fn ash_and_wgpu_are_bit_identical_on_every_preset() {
    record_wgpu_log();
    let (mut ash, mut wgpu) = renderers();
    assert_eq!(ash.adapter(), wgpu.adapter(), "both backends on one device");
    let mut noise = NoiseCache::default();
    let mut scenes: Vec<(String, Scene)> = stratus_scene::presets()
        .iter()
        .map(|p| (p.name.to_string(), small(p.name, 64, 36)))
        .collect();
    // No preset is unshadowed; this one picks the `unshadowed` variants.
    let mut flat = small("cumulus-noon", 64, 36);
    flat.quality.light_steps = 0;
    flat.lighting.multiple_scattering.octaves = 0;
    flat.clouds.detail_strength = 0.0;
    scenes.push(("cumulus-noon, unshadowed".into(), flat));

    let mut problems = Vec::new();
    let mut variants = BTreeSet::new();
    for (name, scene) in &scenes {
        let noise = noise.get(scene);
        for stats in [true, false] {
            let plan = FramePlan::for_scene(scene, stats).expect("plan");
            let frame = FrameInput::new(&plan, scene, &noise);
            let a = ash.render(&frame).expect("ash render");
            let w = wgpu.render(&frame).expect("wgpu render");
            assert_eq!(a.radiance.len(), 64 * 36 * 4);
            assert_eq!(a.stats.is_some(), stats);
            if let Some(s) = &a.stats {
                assert_eq!(s["pixels"], 64 * 36, "{name}: {s:?}");
            }
            assert!(
                a.radiance.iter().any(|&v| v > 0.0) && a.image.iter().any(|&v| v > 0),
                "{name}: an empty frame proves nothing"
            );
            // The same passes ran on both: every pass but those only a host asks for (present,
            // hdr, shadow), less computed tables still valid from before.
            let ran =
                |f: &FrameOutput| f.timings.iter().map(|t| t.pass.clone()).collect::<Vec<_>>();
            assert_eq!(ran(&a), ran(&w), "{name}");
            let once = plan
                .passes
                .iter()
                .filter(|p| {
                    p.when
                        .as_ref()
                        .is_some_and(|c| c.flag.starts_with("stale:"))
                })
                .count();
            let all = plan.passes.len() - host_target_passes(&plan);
            assert!(
                (all - once..=all).contains(&a.timings.len()),
                "{name}: {:?}",
                ran(&a)
            );
            assert_eq!(a.device, w.device);
            problems.extend(frame_differences(
                &format!("{name} ({})", plan.variant),
                &a,
                &w,
            ));
            variants.insert(plan.modules["clouds"].spv_file.clone());
        }
    }
    ash.finish().expect("ash teardown");
    drop(wgpu);
    assert_no_wgpu_messages();
    assert_eq!(
        variants.len(),
        6,
        "every committed SPIR-V ran: {variants:?}"
    );
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// A real-time loop: both backends render the same 24 frames (wind moving, statistics counted,
/// the display target presented by the raster pass) bit for bit alike, frame by frame, and
/// neither creates a GPU object after the first frame.
#[test]
fn a_steady_loop_is_bit_identical_frame_by_frame_and_creates_nothing() {
    record_wgpu_log();
    let (mut ash, mut wgpu) = renderers();
    let base = small("cumulus-noon", 48, 27);
    let noise = NoiseCache::default().get(&base);
    let plan = FramePlan::for_scene(&base, true).expect("plan");
    let mut after_first = None;
    let mut problems = Vec::new();
    for i in 0..24 {
        let mut scene = base.clone();
        scene.clouds.time_s += f64::from(i) * 5.0;
        // Read back every 6th frame only (and the display target, which only the present
        // pass writes, so it must equal the composite's image).
        let readback = if i % 6 == 5 {
            Readback {
                output: true,
                resources: vec!["display".into()],
            }
        } else {
            Readback::none()
        };
        let frame = FrameInput::new(&plan, &scene, &noise)
            .with_readback(readback)
            .with_flags(&["present"]);
        let a = ash.render(&frame).expect("ash render");
        let w = wgpu.render(&frame).expect("wgpu render");
        assert_eq!(
            a.timings.len(),
            plan.passes.len() - host_target_passes(&plan) + 1,
            "frame {i}: every pass ran (the present pass of the host-target passes)"
        );
        if i % 6 == 5 {
            assert_eq!(
                a.resources["display"], a.image,
                "frame {i}: present copies the image"
            );
            problems.extend(frame_differences(&format!("frame {i}"), &a, &w));
        } else {
            assert!(
                a.image.is_empty() && a.radiance.is_empty(),
                "frame {i} read nothing back"
            );
        }
        let now = (ash.objects_created(), wgpu.objects_created());
        match i {
            0 => after_first = Some(now),
            // Frames 1-4 read nothing back: nothing new at all.
            4 => assert_eq!(after_first, Some(now), "objects created in frames 1-4"),
            // Frame 5 reads back for the first time: its readback buffers are new.
            5 => after_first = Some(now),
            _ => {}
        }
    }
    assert_eq!(
        after_first,
        Some((ash.objects_created(), wgpu.objects_created())),
        "GPU objects created after the first read-back frame (frames 6-23)"
    );
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    ash.finish().expect("ash teardown");
    drop(wgpu);
    assert_no_wgpu_messages();
}

/// Passes that run only for a host that asks (`when = "present"`, `"hdr"`: drawing into its
/// target; `"shadow"`: the map for its geometry).
fn host_target_passes(plan: &FramePlan) -> usize {
    plan.passes
        .iter()
        .filter(|p| {
            p.when.as_ref().is_some_and(|c| {
                !c.negate && matches!(c.flag.as_str(), "present" | "hdr" | "shadow")
            })
        })
        .count()
}
