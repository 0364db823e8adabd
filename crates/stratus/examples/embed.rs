//! An application that owns its wgpu device renders 300 frames of clouds, headless, into its
//! own texture while the camera turns and climbs, then prints the median GPU time of each pass
//! and the median CPU time per frame (recording and submitting; not waiting for the GPU).
//!
//! `cargo run --release -p stratus --example embed [WxH] [--frames N] [--depth] [--hdr] [--sky]
//! [--shadow] [--physical] [--shafts]` (default 256x144, 300 frames). `--depth` gives the
//! clouds a host depth buffer (reversed Z) with an opaque box over a fifth of the view 400 m
//! away; `--hdr` draws the HDR output into an Rgba16Float target instead of the display image,
//! and `--sky` (with `--hdr`) the sky behind the clouds in it; `--shadow` computes the
//! cloud-shadow map for the host's geometry every frame; `--physical` puts the scene under the
//! physical sky, and `--shafts` adds its light shafts. Each adds to the passes it costs.

use std::time::Instant;

use stratus::{Clouds, Scene, Update};
use stratus_graph::output::median;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let flag = |f: &str| args.iter().any(|a| a == f);
    const FLAGS: [&str; 7] = [
        "--depth",
        "--hdr",
        "--sky",
        "--shadow",
        "--physical",
        "--shafts",
        "--frames",
    ];
    if let Some(a) = args
        .iter()
        .find(|a| a.starts_with("--") && !FLAGS.contains(&a.as_str()))
    {
        return Err(format!("unknown option {a}: try WxH, {}", FLAGS.join(", ")).into());
    }
    if flag("--sky") && !flag("--hdr") {
        return Err("--sky is the HDR output's sky: give --hdr too".into());
    }
    let frames_value = match args.iter().position(|a| a == "--frames") {
        Some(i) => Some(args.get(i + 1).ok_or("--frames needs a count")?),
        None => None,
    };
    let frames: u32 = match frames_value {
        Some(v) => v.parse().map_err(|e| format!("--frames: {e}"))?,
        None => 300,
    };
    if frames == 0 {
        return Err("--frames must be at least 1".into());
    }
    let (w, h): (u32, u32) = match args
        .iter()
        .find(|a| !a.starts_with("--") && Some(*a) != frames_value)
    {
        Some(s) => {
            let (w, h) = s.split_once('x').ok_or("size must be WxH, e.g. 256x144")?;
            (w.parse()?, h.parse()?)
        }
        None => (256, 144),
    };
    // The application's device: the best Vulkan adapter, with timestamps where offered.
    let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle());
    let adapter = pollster::block_on(instance.request_adapter(&Default::default()))?;
    let features = adapter.features() & wgpu::Features::TIMESTAMP_QUERY;
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        required_features: features,
        ..Default::default()
    }))?;
    let target = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("app target"),
        size: wgpu::Extent3d {
            width: w,
            height: h,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: if flag("--hdr") {
            wgpu::TextureFormat::Rgba16Float
        } else {
            wgpu::TextureFormat::Rgba8Unorm
        },
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let view = target.create_view(&Default::default());

    let mut scene = Scene::preset("cumulus-noon")?.with_size(w, h);
    if flag("--physical") || flag("--shafts") {
        scene.atmosphere.sky = stratus_scene::SkyModel::Physical;
        scene.camera.auto_exposure = true;
    }
    scene.atmosphere.light_shafts = flag("--shafts");
    let start = scene.camera.position;
    let mut clouds = Clouds::new(&device, &queue, scene.clone())?;
    clouds.set_hdr_sky(flag("--sky"));
    if flag("--depth") {
        let camera = stratus::HostCamera {
            projection: stratus::glam::dcamera::rh::proj::directx::perspective_infinite_reverse(
                scene.camera.fov_y_deg.to_radians(),
                f64::from(w) / f64::from(h),
                0.1,
            ),
            ..stratus::HostCamera::of_scene(&scene, 0.1, f64::INFINITY)
        };
        let p = camera.projection()?;
        let depth: Vec<f32> = (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .map(|(x, y)| {
                let boxed = (w / 5..2 * w / 5).contains(&x) && (h / 4..3 * h / 4).contains(&y);
                (if boxed {
                    p.depth_at(400.0)
                } else {
                    p.clear_depth()
                }) as f32
            })
            .collect();
        clouds.set_scene_depth(Some(p.scene_depth([w, h], &depth)?));
    }
    clouds.set_cloud_shadow(flag("--shadow"));
    let (mut cpu, mut wall, mut passes) =
        (Vec::new(), Vec::new(), std::collections::BTreeMap::new());
    let mut created_after_first = 0;
    for i in 0..frames {
        let t = i as f64 / 60.0;
        clouds.update(Update {
            camera_position: Some([start[0], start[1] + 20.0 * t, start[2] + 50.0 * t]),
            camera_yaw_pitch_deg: Some([10.0 * t, 12.0 - 2.0 * t]),
            time_s: Some(1.0 / 60.0),
            ..Default::default()
        })?;
        let clock = Instant::now();
        let mut encoder = device.create_command_encoder(&Default::default());
        if flag("--hdr") {
            clouds.render_hdr(&mut encoder, &view)?;
        } else {
            clouds.render(&mut encoder, &view)?;
        }
        queue.submit([encoder.finish()]);
        cpu.push(clock.elapsed().as_secs_f64() * 1e3);
        // Reading the pass times waits for the GPU: the frame's wall time ends there.
        let timings = clouds.pass_timings()?;
        wall.push(clock.elapsed().as_secs_f64() * 1e3);
        for timing in timings {
            passes
                .entry(timing.pass)
                .or_insert_with(Vec::new)
                .push(timing.ms);
        }
        if i == 0 {
            created_after_first = clouds.objects_created();
        }
    }
    let info = adapter.get_info();
    println!(
        "{frames} frames at {w}x{h} on {} ({:?}), variant {}",
        info.name,
        info.backend,
        clouds.plan().variant
    );
    for (pass, ms) in passes {
        println!("  {pass:<10} median GPU {:8.3} ms", median(ms));
    }
    println!(
        "  CPU per frame (record + submit), median {:.3} ms",
        median(cpu)
    );
    println!(
        "  wall per frame (record, submit, wait for the GPU), median {:.3} ms",
        median(wall)
    );
    println!(
        "  GPU objects created after frame 1: {}",
        clouds.objects_created() - created_after_first
    );
    if info.device_type == wgpu::DeviceType::Cpu {
        // llvmpipe bins timestamps written while a framebuffer is bound (the present pass
        // leaves one bound) and takes them at the next flush: per-pass GPU times are not
        // exact on a CPU driver. CPU and wall times are unaffected; real GPUs time every pass.
        println!("  note: a CPU driver times passes inexactly once a raster pass has run");
    }
    Ok(())
}
