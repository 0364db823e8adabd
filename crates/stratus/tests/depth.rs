//! The host's scene depth: geometry in front of the clouds hides them on every path (wgpu,
//! ash, the CPU reference), geometry inside a cloud sees the transmittance up to it, standard
//! and reversed depth read alike, temporal upsampling leaves no halo around geometry while the
//! camera moves, and depth that cannot be used is refused by name.

use std::sync::Arc;

use stratus::glam::dcamera::rh::proj::directx;
use stratus::{Clouds, HostCamera, Projection, Scene, SceneDepth};
use stratus_graph::{Backend, FrameInput, FrameOutput, FramePlan};
use stratus_noise::NoiseSet;
use stratus_scene::{SkyModel, Temporal};
use stratus_test_support::{assert_no_wgpu_messages, record_wgpu_log};

mod common;

const W: u32 = 64;
const H: u32 = 36;
/// The box's distance along the view axis (m): in front of the cloud layer.
const BOX_DISTANCE: f64 = 400.0;
/// Transmittance to the plane, standard against reversed depth: at most this apart.
const STANDARD_Z_BOUND: f64 = 0.02;

/// Which geometry covers a pixel.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Cover {
    Sky,
    /// The opaque box in front of the clouds.
    Box,
    /// The plane inside a cloud.
    Plane,
}

struct Setup {
    scene: Scene,
    noise: Arc<NoiseSet>,
    /// The GPU's frame without geometry.
    open: FrameOutput,
    /// The plane's distance along the view axis (m).
    plane_distance: f64,
    /// Pixels (x range, y range) of the plane: the window with the most cloud.
    plane: ([u32; 2], [u32; 2]),
}

fn wgpu_renderer() -> stratus_backend_wgpu::Renderer {
    stratus_backend_wgpu::Renderer::new(stratus_backend_wgpu::Options {
        api: stratus_backend_wgpu::Api::Vulkan,
        validation: true,
    })
    .expect("wgpu renderer")
}

fn transmittance(out: &FrameOutput, i: usize) -> f64 {
    f64::from(out.radiance[4 * i + 3])
}

/// cumulus-noon at W x H, its clouds rendered once without geometry, and where the plane goes:
/// the window of the right half with the most cloud, at the median distance of that cloud.
fn setup(gpu: &mut stratus_backend_wgpu::Renderer) -> Setup {
    let mut scene = Scene::preset("cumulus-noon").unwrap().with_size(W, H);
    // The weather map's cumulus, where the bounds below were measured: on the default's
    // convective cells standard and reversed depth parted by 0.055 in transmittance to the
    // plane (bound 0.02), the plane's 3 m cut crossing sharper cloud edges.
    scene.clouds.convective_cells = 0.0;
    let noise = Arc::new(stratus::noise_for(&scene));
    let plan = FramePlan::for_scene(&scene, false).unwrap();
    let open = gpu
        .render(&FrameInput::new(&plan, &scene, &noise))
        .expect("open frame");
    let (ww, wh) = (W / 5, H / 4);
    let mut best = (f64::INFINITY, 0, 0);
    for y0 in 0..H - wh {
        for x0 in W / 2..W - ww {
            let sum: f64 = (y0..y0 + wh)
                .flat_map(|y| (x0..x0 + ww).map(move |x| (y * W + x) as usize))
                .map(|i| transmittance(&open, i))
                .sum();
            if sum < best.0 {
                best = (sum, x0, y0);
            }
        }
    }
    let (_, px, py) = best;
    let (forward, _, _) = scene.camera_basis();
    let mut axis: Vec<f64> = (py..py + wh)
        .flat_map(|y| (px..px + ww).map(move |x| (x, y)))
        .filter_map(|(x, y)| {
            let i = (y * W + x) as usize;
            let d = f64::from(open.depth[i]);
            (transmittance(&open, i) < 0.9 && d > 0.0)
                .then(|| d * dot(view_ray(&scene, x, y), forward))
        })
        .collect();
    assert!(
        !axis.is_empty(),
        "no cloud in the right half to put the plane in"
    );
    axis.sort_by(f64::total_cmp);
    Setup {
        plane_distance: axis[axis.len() / 2],
        plane: ([px, px + ww], [py, py + wh]),
        scene,
        noise,
        open,
    }
}

impl Setup {
    fn cover(&self, x: u32, y: u32) -> Cover {
        let (px, py) = self.plane;
        if (W * 12 / 100..W * 32 / 100).contains(&x) && (H * 35 / 100..H * 75 / 100).contains(&y) {
            Cover::Box
        } else if (px[0]..px[1]).contains(&x) && (py[0]..py[1]).contains(&y) {
            Cover::Plane
        } else {
            Cover::Sky
        }
    }

    /// The host's depth buffer of the box and the plane under `projection`.
    fn depth(&self, projection: &Projection) -> Arc<SceneDepth> {
        let depth: Vec<f32> = (0..H)
            .flat_map(|y| (0..W).map(move |x| (x, y)))
            .map(|(x, y)| match self.cover(x, y) {
                Cover::Box => projection.depth_at(BOX_DISTANCE) as f32,
                Cover::Plane => projection.depth_at(self.plane_distance) as f32,
                Cover::Sky => projection.clear_depth() as f32,
            })
            .collect();
        Arc::new(projection.scene_depth([W, H], &depth).expect("depth"))
    }

    fn pixels(&self, cover: Cover) -> Vec<usize> {
        (0..H)
            .flat_map(|y| (0..W).map(move |x| (x, y)))
            .filter(|&(x, y)| self.cover(x, y) == cover)
            .map(|(x, y)| (y * W + x) as usize)
            .collect()
    }
}

/// The scene's camera with a reversed infinite projection (near 0.1 m).
fn reversed(scene: &Scene) -> Projection {
    HostCamera {
        projection: directx::perspective_infinite_reverse(
            scene.camera.fov_y_deg.to_radians(),
            f64::from(W) / f64::from(H),
            0.1,
        ),
        ..HostCamera::of_scene(scene, 0.1, f64::INFINITY)
    }
    .projection()
    .unwrap()
}

/// The box hides the clouds behind it exactly (no radiance, transmittance 1) on wgpu (Vulkan
/// and GL), ash and the CPU reference; the plane inside the cloud sees more transmittance than the whole
/// cloud's, the GPU's within 0.01 of the CPU's; the display image shows the geometry.
#[test]
fn geometry_hides_and_cuts_the_clouds_on_every_path() {
    record_wgpu_log();
    let mut gpu = wgpu_renderer();
    let s = setup(&mut gpu);
    let depth = s.depth(&reversed(&s.scene));
    let plan = FramePlan::for_scene(&s.scene, false).unwrap();
    let frame = FrameInput::new(&plan, &s.scene, &s.noise).with_scene_depth(Some(&depth));
    let mut ash =
        stratus_backend_ash::Renderer::new(stratus_backend_ash::Options { validation: true })
            .expect("ash renderer");
    let mut gl = stratus_backend_wgpu::Renderer::new(stratus_backend_wgpu::Options {
        api: stratus_backend_wgpu::Api::Gl,
        validation: true,
    })
    .expect("wgpu-gl renderer");
    let mut cpu = stratus_reference::CpuBackend::default();
    let outputs = [
        ("wgpu", gpu.render(&frame).expect("wgpu")),
        ("ash", ash.render(&frame).expect("ash")),
        ("wgpu-gl", gl.render(&frame).expect("wgpu-gl")),
        ("cpu", Backend::render(&mut cpu, &frame).expect("cpu")),
    ];
    let boxed = s.pixels(Cover::Box);
    let plane = s.pixels(Cover::Plane);
    for (name, out) in &outputs {
        for &i in &boxed {
            assert_eq!(
                &out.radiance[4 * i..4 * i + 4],
                &[0.0, 0.0, 0.0, 1.0],
                "{name}: cloud behind the box at pixel {i}"
            );
        }
        let with: f64 = plane.iter().map(|&i| transmittance(out, i)).sum();
        let without: f64 = plane.iter().map(|&i| transmittance(&s.open, i)).sum();
        assert!(
            with > without,
            "{name}: the plane sees transmittance {with} (sum), the whole cloud {without}: the march did not stop at it"
        );
        // The display shows the geometry: one colour over the box, not the sky behind it.
        let colour = &out.image[4 * boxed[0]..4 * boxed[0] + 4];
        for &i in &boxed {
            assert_eq!(
                &out.image[4 * i..4 * i + 4],
                colour,
                "{name}: box pixel {i}"
            );
            assert_ne!(&s.open.image[4 * i..4 * i + 4], colour, "{name}: pixel {i}");
        }
    }
    for (name, out) in &outputs[..3] {
        let err = plane
            .iter()
            .map(|&i| (transmittance(out, i) - transmittance(&outputs[3].1, i)).abs())
            .fold(0.0, f64::max);
        assert!(
            err <= 0.01,
            "{name}: transmittance to the plane {err} off the CPU's"
        );
    }
    ash.finish().expect("ash teardown");
    assert_no_wgpu_messages();
}

/// Standard-Z (finite far plane) and reversed-Z (infinite) depth buffers of the same geometry
/// give the same bits where there is no geometry and in front of the box, and the same
/// transmittance to the plane within the standard buffer's precision.
#[test]
fn standard_and_reversed_depth_read_alike() {
    record_wgpu_log();
    let mut gpu = wgpu_renderer();
    let s = setup(&mut gpu);
    let standard = HostCamera::of_scene(&s.scene, 0.1, 100_000.0)
        .projection()
        .unwrap();
    assert!(!standard.reversed_z);
    let plan = FramePlan::for_scene(&s.scene, false).unwrap();
    let mut render = |p: &Projection| {
        let depth = s.depth(p);
        let frame = FrameInput::new(&plan, &s.scene, &s.noise).with_scene_depth(Some(&depth));
        gpu.render(&frame).expect("frame")
    };
    let (a, b) = (render(&standard), render(&reversed(&s.scene)));
    for &i in &s.pixels(Cover::Box) {
        assert_eq!(&a.radiance[4 * i..4 * i + 4], &[0.0, 0.0, 0.0, 1.0]);
        assert_eq!(&b.radiance[4 * i..4 * i + 4], &[0.0, 0.0, 0.0, 1.0]);
    }
    for &i in &s.pixels(Cover::Sky) {
        assert_eq!(
            &a.radiance[4 * i..4 * i + 4],
            &b.radiance[4 * i..4 * i + 4],
            "pixel {i} without geometry"
        );
    }
    let max = s
        .pixels(Cover::Plane)
        .iter()
        .map(|&i| (transmittance(&a, i) - transmittance(&b, i)).abs())
        .fold(0.0, f64::max);
    eprintln!("plane transmittance, standard against reversed depth: max difference {max:.5}");
    // The standard buffer (near 0.1 m, far 100 km) holds the plane at 3 km to about 3 m
    // (an f32 step of its depth near 1 is 6e-8, which is distance^2 / near x 6e-8): the cut
    // moves by that much, and every sample of the march with it.
    assert!(
        max <= STANDARD_Z_BOUND,
        "standard and reversed depth differ by {max}"
    );
    assert_no_wgpu_messages();
}

/// At 1/16 temporal upsampling with the camera turning and the box fixed on the screen (so it
/// moves through the clouds), every frame: the box's pixels hold no cloud, and the pixels
/// around it are no further from the full march than the rest of the image is (resampled
/// history cut by the box would trail it as a halo of missing cloud).
#[test]
fn temporal_upsampling_leaves_no_halo_around_moving_geometry() {
    record_wgpu_log();
    let mut gpu = wgpu_renderer();
    let s = setup(&mut gpu);
    let mut full = wgpu_renderer();
    let mut scene = s.scene.clone();
    scene.quality.temporal = Temporal::Sixteenth;
    let near_box = |x: u32, y: u32| {
        s.cover(x, y) == Cover::Sky
            && (0..=2).any(|d| {
                s.cover(x.saturating_sub(d), y) == Cover::Box
                    || s.cover((x + d).min(W - 1), y) == Cover::Box
                    || s.cover(x, y.saturating_sub(d)) == Cover::Box
                    || s.cover(x, (y + d).min(H - 1)) == Cover::Box
            })
    };
    let mut worst = (0.0f64, 0.0f64);
    for i in 0..24u32 {
        scene.camera.yaw_deg = s.scene.camera.yaw_deg + 0.4 * f64::from(i);
        scene.quality.frame = i;
        let mut still = scene.clone();
        still.quality.temporal = Temporal::Off;
        let depth = s.depth(&reversed(&scene));
        let plan = FramePlan::for_scene(&scene, false).unwrap();
        let out = gpu
            .render(&FrameInput::new(&plan, &scene, &s.noise).with_scene_depth(Some(&depth)))
            .expect("temporal frame");
        let still_plan = FramePlan::for_scene(&still, false).unwrap();
        let truth = full
            .render(&FrameInput::new(&still_plan, &still, &s.noise).with_scene_depth(Some(&depth)))
            .expect("full frame");
        for &p in &s.pixels(Cover::Box) {
            assert_eq!(
                &out.radiance[4 * p..4 * p + 4],
                &[0.0, 0.0, 0.0, 1.0],
                "frame {i}: cloud over the box at pixel {p}"
            );
        }
        let (mut ring, mut rest) = (Vec::new(), Vec::new());
        for y in 0..H {
            for x in 0..W {
                let p = (y * W + x) as usize;
                let e = (transmittance(&out, p) - transmittance(&truth, p)).abs();
                if near_box(x, y) {
                    ring.push(e);
                } else if s.cover(x, y) == Cover::Sky {
                    rest.push(e);
                }
            }
        }
        let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
        if i > 0 {
            worst = (worst.0.max(mean(&ring)), worst.1.max(mean(&rest)));
        }
    }
    eprintln!(
        "worst mean |T - T_full| around the box {:.4}, elsewhere {:.4}",
        worst.0, worst.1
    );
    assert!(
        worst.0 <= 2.0 * worst.1 + 0.01,
        "a halo around the box: its ring is {:.4} off the full march, the rest {:.4}",
        worst.0,
        worst.1
    );
    assert_no_wgpu_messages();
}

/// Depth the clouds cannot use is refused, naming what is wrong and where.
#[test]
fn unusable_scene_depth_is_refused_by_name() {
    record_wgpu_log();
    let scene = Scene::preset("cumulus-noon").unwrap().with_size(W, H);
    let projection = reversed(&scene);
    let e = projection
        .scene_depth([W, H], &vec![0.5; (W * H - 1) as usize])
        .unwrap_err();
    assert!(e.to_string().contains("values, not 64x36"), "{e}");
    let mut bad = vec![0.0; (W * H) as usize];
    bad[W as usize + 3] = f32::NAN;
    let e = projection.scene_depth([W, H], &bad).unwrap_err();
    assert!(e.to_string().contains("pixel (3, 1) is NaN"), "{e}");

    // Through the library: a depth of another size than the target.
    let (device, queue) = common::device();
    let mut clouds = Clouds::new(&device, &queue, scene.clone()).expect("clouds");
    let small = projection
        .scene_depth([32, 18], &vec![0.0; 32 * 18])
        .unwrap();
    clouds.set_scene_depth(Some(small));
    let texture = common::target(&device, wgpu::TextureFormat::Rgba8Unorm, W, H);
    let view = texture.create_view(&Default::default());
    let mut encoder = device.create_command_encoder(&Default::default());
    let e = clouds.render(&mut encoder, &view).unwrap_err().to_string();
    assert!(
        e.contains("the scene depth is 32x18, the frame 64x36"),
        "{e}"
    );

    // The path tracer does not stop at geometry: refused, not ignored.
    let mut traced = scene;
    traced.quality.integrator = stratus_scene::Integrator::Pathtrace;
    let plan = FramePlan::for_scene(&traced, false).unwrap();
    let depth = Arc::new(
        projection
            .scene_depth([W, H], &vec![0.0; (W * H) as usize])
            .unwrap(),
    );
    let noise = stratus_test_support::small_noise(1);
    let e = wgpu_renderer()
        .render(&FrameInput::new(&plan, &traced, &noise).with_scene_depth(Some(&depth)))
        .unwrap_err()
        .to_string();
    assert!(e.contains("read by the volumetric march only"), "{e}");
    assert_no_wgpu_messages();
}

/// A host depth texture of `format` holding the box and the plane of `s`, drawn as two
/// rectangles at their depths (reversed Z: cleared to 0, the far plane).
fn host_depth_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    s: &Setup,
    projection: &Projection,
    format: wgpu::TextureFormat,
) -> wgpu::Texture {
    let texture = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("host depth"),
        size: wgpu::Extent3d {
            width: W,
            height: H,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
        view_formats: &[],
    });
    // Pixel rectangles [x0, x1) x [y0, y1) in NDC, at clip depth z.
    let rect = |[x0, x1]: [u32; 2], [y0, y1]: [u32; 2], z: f64| {
        let nx = |x: u32| f64::from(x) / f64::from(W) * 2.0 - 1.0;
        let ny = |y: u32| 1.0 - f64::from(y) / f64::from(H) * 2.0;
        let (a, b, c, d) = (nx(x0), nx(x1), ny(y0), ny(y1));
        [(a, c), (b, c), (a, d), (b, c), (b, d), (a, d)]
            .map(|(x, y)| format!("vec3<f32>({x:?}, {y:?}, {z:?})"))
            .join(", ")
    };
    let boxed = rect(
        [W * 12 / 100, W * 32 / 100],
        [H * 35 / 100, H * 75 / 100],
        projection.depth_at(BOX_DISTANCE) as f32 as f64,
    );
    let plane = rect(
        s.plane.0,
        s.plane.1,
        projection.depth_at(s.plane_distance) as f32 as f64,
    );
    let source = format!(
        "const P = array<vec3<f32>, 12>({boxed}, {plane});\n\
         @vertex fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {{\n\
         return vec4<f32>(P[i], 1.0);\n}}"
    );
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("host geometry"),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("host geometry"),
        layout: None,
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vs"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: Default::default(),
        depth_stencil: Some(wgpu::DepthStencilState {
            format,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Always),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: Default::default(),
        fragment: None,
        multiview_mask: None,
        cache: None,
    });
    let view = texture.create_view(&Default::default());
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("host depth"),
            color_attachments: &[],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(projection.clear_depth() as f32),
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: None,
            }),
            ..Default::default()
        });
        pass.set_pipeline(&pipeline);
        pass.draw(0..12, 0..1);
    }
    queue.submit([encoder.finish()]);
    texture
}

/// An IEEE half float's value.
fn f16_to_f32(bits: u16) -> f32 {
    let sign = if bits >> 15 == 1 { -1.0 } else { 1.0 };
    let exp = i32::from((bits >> 10) & 0x1f);
    let frac = f32::from(bits & 0x3ff);
    sign * match exp {
        0 => frac * 2f32.powi(-24),
        31 => f32::INFINITY,
        e => (1.0 + frac / 1024.0) * 2f32.powi(e - 15),
    }
}

/// The library reads the host's own depth texture (Depth32Float and Depth24Plus) on the GPU
/// and writes its HDR output into the host's Rgba16Float target: with Depth32Float it is the
/// renderer's linear output for the same depths, to half-float precision; with either format
/// the box's pixels are exactly (0, 0, 0, 1).
#[test]
fn the_library_reads_the_hosts_depth_texture_and_writes_hdr() {
    record_wgpu_log();
    let mut gpu = wgpu_renderer();
    let s = setup(&mut gpu);
    let projection = reversed(&s.scene);
    let plan = FramePlan::for_scene(&s.scene, false).unwrap();
    let expected = gpu
        .render(
            &FrameInput::new(&plan, &s.scene, &s.noise)
                .with_scene_depth(Some(&s.depth(&projection))),
        )
        .expect("renderer frame");
    let (device, queue) = common::device();
    let hdr = common::target(&device, wgpu::TextureFormat::Rgba16Float, W, H);
    let hdr_view = hdr.create_view(&Default::default());
    for format in [
        wgpu::TextureFormat::Depth32Float,
        wgpu::TextureFormat::Depth24Plus,
    ] {
        let depth = host_depth_texture(&device, &queue, &s, &projection, format);
        let depth_view = depth.create_view(&Default::default());
        let mut clouds = Clouds::new(&device, &queue, s.scene.clone()).expect("clouds");
        clouds
            .set_depth_texture(Some((&depth_view, projection)))
            .expect("depth texture");
        let mut encoder = device.create_command_encoder(&Default::default());
        clouds
            .render_hdr(&mut encoder, &hdr_view)
            .expect("hdr frame");
        queue.submit([encoder.finish()]);
        let texels: Vec<f32> = common::read_texels(&device, &queue, &hdr, 8)
            .chunks_exact(2)
            .map(|c| f16_to_f32(u16::from_le_bytes([c[0], c[1]])))
            .collect();
        for &i in &s.pixels(Cover::Box) {
            assert_eq!(
                &texels[4 * i..4 * i + 4],
                &[0.0, 0.0, 0.0, 1.0],
                "{format:?}: cloud behind the box at pixel {i}"
            );
        }
        if format == wgpu::TextureFormat::Depth32Float {
            for (k, (&got, &want)) in texels.iter().zip(&expected.radiance).enumerate() {
                // Half floats keep 11 significant bits.
                assert!(
                    (got - want).abs() <= want.abs() * 1e-3 + 1e-6,
                    "texel {} channel {}: HDR {got}, renderer {want}",
                    k / 4,
                    k % 4
                );
            }
        }
    }
    // Refused by name: a colour texture as depth, an sRGB or UNORM target as HDR output, a
    // depth texture of another size.
    let colour = common::target(&device, wgpu::TextureFormat::Rgba8Unorm, W, H);
    let mut clouds = Clouds::new(&device, &queue, s.scene.clone()).expect("clouds");
    let e = clouds
        .set_depth_texture(Some((&colour.create_view(&Default::default()), projection)))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("Rgba8Unorm: give a Depth32Float or Depth24Plus"),
        "{e}"
    );
    for format in [
        wgpu::TextureFormat::Rgba8UnormSrgb,
        wgpu::TextureFormat::Rgba8Unorm,
        wgpu::TextureFormat::Rgba16Uint,
    ] {
        let t = device.create_texture(&wgpu::TextureDescriptor {
            label: None,
            size: hdr.size(),
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            view_formats: &[],
        });
        let mut encoder = device.create_command_encoder(&Default::default());
        let e = clouds
            .render_hdr(&mut encoder, &t.create_view(&Default::default()))
            .unwrap_err()
            .to_string();
        assert!(e.contains("give an Rgba16Float"), "{format:?}: {e}");
    }
    let small = device.create_texture(&wgpu::TextureDescriptor {
        label: None,
        size: wgpu::Extent3d {
            width: W / 2,
            height: H / 2,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Depth32Float,
        usage: wgpu::TextureUsages::TEXTURE_BINDING,
        view_formats: &[],
    });
    clouds
        .set_depth_texture(Some((&small.create_view(&Default::default()), projection)))
        .expect("a depth texture");
    let mut encoder = device.create_command_encoder(&Default::default());
    let e = clouds
        .render_hdr(&mut encoder, &hdr_view)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("the depth texture is 32x18, the target 64x36"),
        "{e}"
    );
    assert_no_wgpu_messages();
}

/// ACES fitted (Narkowicz), as the composite's tone curve.
fn aces(x: f64) -> f64 {
    ((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14)).clamp(0.0, 1.0)
}

/// With the sky asked for, the HDR output is the display image before its exposure and tone
/// curve wherever the host has no geometry (opaque there: alpha 0), and the clouds over the
/// host's geometry where it has some (the box's pixels (0, 0, 0, 1), the plane's the clouds'
/// transmittance in front of it), under the analytic sky and the physical one.
#[test]
fn the_hdr_output_carries_the_sky_when_asked() {
    record_wgpu_log();
    let mut gpu = wgpu_renderer();
    let s = setup(&mut gpu);
    let projection = reversed(&s.scene);
    let (device, queue) = common::device();
    let hdr = common::target(&device, wgpu::TextureFormat::Rgba16Float, W, H);
    let display = common::target(&device, wgpu::TextureFormat::Rgba8Unorm, W, H);
    let depth = host_depth_texture(
        &device,
        &queue,
        &s,
        &projection,
        wgpu::TextureFormat::Depth32Float,
    );
    let depth_view = depth.create_view(&Default::default());
    for sky in [SkyModel::Analytic, SkyModel::Physical] {
        let mut scene = s.scene.clone();
        scene.atmosphere.sky = sky;
        let exposure = f64::from(scene.uniforms().exposure);
        let frame = |hdr_out: bool, with_sky: bool| {
            let mut clouds = Clouds::new(&device, &queue, scene.clone()).expect("clouds");
            clouds
                .set_depth_texture(Some((&depth_view, projection)))
                .expect("depth texture");
            clouds.set_hdr_sky(with_sky);
            let mut encoder = device.create_command_encoder(&Default::default());
            if hdr_out {
                let view = hdr.create_view(&Default::default());
                clouds.render_hdr(&mut encoder, &view).expect("hdr frame");
                queue.submit([encoder.finish()]);
                common::read_texels(&device, &queue, &hdr, 8)
                    .chunks_exact(2)
                    .map(|c| f64::from(f16_to_f32(u16::from_le_bytes([c[0], c[1]]))))
                    .collect::<Vec<f64>>()
            } else {
                let view = display.create_view(&Default::default());
                clouds.render(&mut encoder, &view).expect("display frame");
                queue.submit([encoder.finish()]);
                common::read(&device, &queue, &display)
                    .into_iter()
                    .map(|b| f64::from(b) / 255.0)
                    .collect()
            }
        };
        let with_sky = frame(true, true);
        let clouds_only = frame(true, false);
        let shown = frame(false, false);
        let mut worst = 0.0f64;
        for &i in &s.pixels(Cover::Sky) {
            assert_eq!(
                with_sky[4 * i + 3],
                0.0,
                "{sky:?}: sky pixel {i} not opaque"
            );
            for c in 0..3 {
                let encoded = aces(with_sky[4 * i + c] * exposure).powf(1.0 / 2.2);
                worst = worst.max((encoded - shown[4 * i + c]).abs());
            }
        }
        println!("{sky:?}: the HDR sky, tone-mapped, is at most {worst:.5} off the display image");
        // The display image is 8-bit (half a step of rounding) and the HDR output half floats.
        assert!(
            worst <= 1.5 / 255.0,
            "{sky:?}: the HDR sky, tone-mapped, is {worst:.4} off the display image"
        );
        for &i in &s.pixels(Cover::Box) {
            assert_eq!(
                &with_sky[4 * i..4 * i + 4],
                &[0.0, 0.0, 0.0, 1.0],
                "{sky:?}: box pixel {i}"
            );
        }
        for &i in &s.pixels(Cover::Plane) {
            assert_eq!(
                with_sky[4 * i + 3],
                clouds_only[4 * i + 3],
                "{sky:?}: plane pixel {i}: the clouds' transmittance in front of it"
            );
        }
    }
    assert_no_wgpu_messages();
}

/// The unit view ray through the centre of pixel (x, y), as the shaders make it.
fn view_ray(scene: &Scene, x: u32, y: u32) -> [f64; 3] {
    let (f, r, u) = scene.camera_basis();
    let [w, h] = scene.camera.resolution.map(f64::from);
    let tan = (scene.camera.fov_y_deg.to_radians() / 2.0).tan();
    let nx = (f64::from(x) + 0.5) / w * 2.0 - 1.0;
    let ny = (f64::from(y) + 0.5) / h * 2.0 - 1.0;
    let d = [0, 1, 2].map(|k| f[k] + r[k] * nx * tan * w / h - u[k] * ny * tan);
    let len = dot(d, d).sqrt();
    d.map(|c| c / len)
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
