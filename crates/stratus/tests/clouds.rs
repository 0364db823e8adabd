//! The library face on an application's own device: frames drawn into the application's
//! texture are exactly what the backend's own renderer draws for the same scene, a steady loop
//! creates no GPU object after its first frame, and targets that cannot take the clouds are
//! refused with a sentence saying what to do.

use std::sync::Arc;

use stratus::{Clouds, Error, Scene, Update};
use stratus_graph::{FrameInput, FramePlan};
use stratus_test_support::{assert_no_wgpu_messages, record_wgpu_log};

mod common;

use common::{device, read, target};

#[test]
fn frames_in_the_app_texture_match_the_renderer_and_create_nothing_after_the_first() {
    record_wgpu_log();
    let (device, queue) = device();
    let (w, h) = (40, 24);
    let texture = target(&device, wgpu::TextureFormat::Rgba8Unorm, w, h);
    let view = texture.create_view(&Default::default());
    let scene = Scene::preset("cumulus-noon").unwrap().with_size(w, h);
    let mut clouds = Clouds::new(&device, &queue, scene).expect("clouds");
    let mut reference = stratus_backend_wgpu::Renderer::new(stratus_backend_wgpu::Options {
        api: stratus_backend_wgpu::Api::Vulkan,
        validation: true,
    })
    .expect("renderer");
    let noise = Arc::new(stratus::noise_for(clouds.scene()));
    let mut after_first = 0;
    for i in 0..6 {
        clouds
            .update(Update {
                camera_yaw_pitch_deg: Some([5.0 * f64::from(i), 10.0]),
                time_s: Some(2.0),
                ..Default::default()
            })
            .expect("update");
        let mut encoder = device.create_command_encoder(&Default::default());
        clouds.render(&mut encoder, &view).expect("render");
        queue.submit([encoder.finish()]);
        let timings = clouds.pass_timings().expect("timings");
        assert_eq!(
            timings.iter().map(|t| t.pass.as_str()).collect::<Vec<_>>(),
            ["march", "composite", "present"]
        );
        if i == 0 {
            after_first = clouds.objects_created();
        }
        if i % 3 == 2 {
            let plan = FramePlan::for_scene(clouds.scene(), false).unwrap();
            let expected = reference
                .render(&FrameInput::new(&plan, clouds.scene(), &noise))
                .expect("reference frame");
            assert_eq!(read(&device, &queue, &texture), expected.image, "frame {i}");
        }
    }
    assert_eq!(
        clouds.objects_created(),
        after_first,
        "objects after frame 1"
    );
    assert_no_wgpu_messages();
}

#[test]
fn targets_that_cannot_take_the_clouds_are_refused() {
    let (device, queue) = device();
    let scene = Scene::preset("cumulus-noon").unwrap().with_size(16, 8);
    let mut clouds = Clouds::new(&device, &queue, scene).expect("clouds");
    let srgb = target(&device, wgpu::TextureFormat::Rgba8UnormSrgb, 16, 8);
    let mut encoder = device.create_command_encoder(&Default::default());
    match clouds.render(&mut encoder, &srgb.create_view(&Default::default())) {
        Err(Error::Target(m)) => assert!(m.contains("sRGB") && m.contains("Rgba8Unorm"), "{m}"),
        other => panic!("an sRGB target: {:?}", other.map(|_| ())),
    }
    let mut bad = Scene::preset("cumulus-noon").unwrap();
    bad.camera.fov_y_deg = 0.0;
    match clouds.update(Update {
        scene: Some(bad),
        ..Default::default()
    }) {
        Err(Error::Scene(m)) => assert!(m.contains("fov_y_deg"), "{m}"),
        other => panic!("an invalid scene: {other:?}"),
    }
}

/// A swapchain-like BGRA target gets the same image, its channels in BGRA order (the present
/// pass's pipeline for that format shares the pass's bind group layout and bind groups).
#[test]
fn a_bgra_target_gets_the_same_image() {
    record_wgpu_log();
    let (device, queue) = device();
    let scene = Scene::preset("cumulus-noon").unwrap().with_size(24, 12);
    let mut clouds = Clouds::new(&device, &queue, scene).expect("clouds");
    let mut images = Vec::new();
    for format in [
        wgpu::TextureFormat::Rgba8Unorm,
        wgpu::TextureFormat::Bgra8Unorm,
    ] {
        let texture = target(&device, format, 24, 12);
        let mut encoder = device.create_command_encoder(&Default::default());
        clouds
            .render(&mut encoder, &texture.create_view(&Default::default()))
            .expect("render");
        queue.submit([encoder.finish()]);
        images.push(read(&device, &queue, &texture));
    }
    let swizzled: Vec<u8> = images[1]
        .chunks_exact(4)
        .flat_map(|p| [p[2], p[1], p[0], p[3]])
        .collect();
    assert_eq!(images[0], swizzled);
    assert!(
        images[0].iter().any(|&v| v > 0),
        "an empty image proves nothing"
    );
    assert_no_wgpu_messages();
}

/// With temporal upsampling the library keeps the history between the application's frames:
/// a turning camera gives, frame by frame, the image a standalone renderer gives for the same
/// frames.
#[test]
fn temporal_frames_in_the_app_texture_match_the_renderer_frame_by_frame() {
    record_wgpu_log();
    let (device, queue) = device();
    let (w, h) = (40, 24);
    let texture = target(&device, wgpu::TextureFormat::Rgba8Unorm, w, h);
    let view = texture.create_view(&Default::default());
    let mut scene = Scene::preset("cumulus-noon").unwrap().with_size(w, h);
    scene.quality.temporal = stratus_scene::Temporal::Sixteenth;
    let mut clouds = Clouds::new(&device, &queue, scene).expect("clouds");
    let mut reference = stratus_backend_wgpu::Renderer::new(stratus_backend_wgpu::Options {
        api: stratus_backend_wgpu::Api::Vulkan,
        validation: true,
    })
    .expect("renderer");
    let noise = Arc::new(stratus::noise_for(clouds.scene()));
    for i in 0..8 {
        clouds
            .update(Update {
                camera_yaw_pitch_deg: Some([2.0 * f64::from(i), 10.0]),
                ..Default::default()
            })
            .expect("update");
        let mut encoder = device.create_command_encoder(&Default::default());
        clouds.render(&mut encoder, &view).expect("render");
        queue.submit([encoder.finish()]);
        let timings = clouds.pass_timings().expect("timings");
        assert_eq!(
            timings.iter().map(|t| t.pass.as_str()).collect::<Vec<_>>(),
            ["march", "resolve", "composite", "present"]
        );
        // Each update is a new frame: the next pixel of each 4x4 block is marched (with the
        // frame index left alone, the same pixel was marched every frame).
        assert_eq!(
            clouds.scene().quality.frame,
            i + 1,
            "frame index of frame {i}"
        );
        let plan = FramePlan::for_scene(clouds.scene(), false).unwrap();
        let expected = reference
            .render(&FrameInput::new(&plan, clouds.scene(), &noise))
            .expect("reference frame");
        assert_eq!(read(&device, &queue, &texture), expected.image, "frame {i}");
    }
    assert_no_wgpu_messages();
}

/// The scenes of a stream that switches, frame by frame, every plan option a viewer's controls
/// change: temporal upsampling on and off, the method (basic marcher, sprites, the march), the
/// sky (analytic, physical) and the size. Each differs from the one before in its plan key.
fn switching_stream(w: u32, h: u32) -> Vec<(&'static str, Scene)> {
    use stratus_scene::{Method, SkyModel, Temporal};
    let base = Scene::preset("cumulus-noon").unwrap().with_size(w, h);
    let with = |f: &dyn Fn(&mut Scene)| {
        let mut s = base.clone();
        f(&mut s);
        s
    };
    vec![
        ("march", base.clone()),
        (
            "temporal 1/16",
            with(&|s| s.quality.temporal = Temporal::Sixteenth),
        ),
        ("basic marcher", with(&|s| s.quality.method = Method::Basic)),
        (
            "physical sky",
            with(&|s| s.atmosphere.sky = SkyModel::Physical),
        ),
        ("sprites", with(&|s| s.quality.method = Method::Sprites)),
        (
            "temporal 1/4 under the physical sky",
            with(&|s| {
                s.quality.temporal = Temporal::Quarter;
                s.atmosphere.sky = SkyModel::Physical;
            }),
        ),
        ("march again", base.clone()),
        ("smaller", base.clone().with_size(w / 2, h / 2)),
    ]
}

/// A scene switched mid-stream on the library renders what a fresh `Clouds` renders for it:
/// the plan follows the plan options (temporal, method, sky), not only the shader features and
/// the size (a stale plan drew the old method, or the full march where 1/16 was asked for).
#[test]
fn switching_plan_options_mid_stream_matches_a_fresh_renderer() {
    record_wgpu_log();
    let (device, queue) = device();
    let (w, h) = (40, 24);
    let stream = switching_stream(w, h);
    let mut clouds = Clouds::new(&device, &queue, stream[0].1.clone()).expect("clouds");
    let mut last_key = None;
    for (what, scene) in &stream {
        let key = stratus_graph::PlanKey::of(scene, false);
        assert_ne!(last_key.as_ref(), Some(&key), "{what}: the stream switches");
        last_key = Some(key.clone());
        let [sw, sh] = scene.camera.resolution;
        let texture = target(&device, wgpu::TextureFormat::Rgba8Unorm, sw, sh);
        let view = texture.create_view(&Default::default());
        clouds
            .update(Update {
                scene: Some(scene.clone()),
                ..Default::default()
            })
            .expect("update");
        assert_eq!(clouds.plan().key, key, "{what}: the plan follows the scene");
        let mut encoder = device.create_command_encoder(&Default::default());
        clouds.render(&mut encoder, &view).expect("render");
        queue.submit([encoder.finish()]);
        let switched = read(&device, &queue, &texture);

        let mut fresh = Clouds::new(&device, &queue, scene.clone()).expect("fresh clouds");
        let mut encoder = device.create_command_encoder(&Default::default());
        fresh.render(&mut encoder, &view).expect("fresh render");
        queue.submit([encoder.finish()]);
        assert!(
            switched == read(&device, &queue, &texture),
            "{what}: the switched renderer's frame differs from a fresh renderer's"
        );
    }
    assert_no_wgpu_messages();
}

/// The same stream on the viewer's ash path (the ash renderer with [`stratus::Prepared`]
/// keeping its plan and noise): every frame equals a fresh ash renderer's.
#[test]
fn switching_plan_options_mid_stream_on_ash_matches_a_fresh_renderer() {
    use stratus_graph::{Backend, Readback};
    let (w, h) = (40, 24);
    let stream = switching_stream(w, h);
    let options = stratus_backend_ash::Options { validation: true };
    let mut renderer = stratus_backend_ash::Renderer::new(options).expect("ash renderer");
    let mut prepared = stratus::Prepared::new(&stream[0].1).expect("prepared");
    for (what, scene) in &stream {
        prepared.update(scene).expect("update");
        assert_eq!(
            prepared.plan().key,
            stratus_graph::PlanKey::of(scene, false),
            "{what}: the plan follows the scene"
        );
        let switched = Backend::render(
            &mut renderer,
            &prepared.frame(scene).with_readback(Readback::output()),
        )
        .expect("render");
        let mut fresh_renderer = stratus_backend_ash::Renderer::new(options).expect("fresh");
        let fresh_prepared = stratus::Prepared::new(scene).expect("fresh prepared");
        let fresh = Backend::render(
            &mut fresh_renderer,
            &fresh_prepared
                .frame(scene)
                .with_readback(Readback::output()),
        )
        .expect("fresh render");
        assert!(
            switched.image == fresh.image && switched.radiance == fresh.radiance,
            "{what}: the switched renderer's frame differs from a fresh renderer's"
        );
    }
}
