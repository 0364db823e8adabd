//! One frame: the clouds and the overlay into the offscreen texture, then to the window, and
//! screenshots (PNG of what the window shows, EXR of the linear radiance).

use crate::gpu::{copy_to_buffer, padded_row, to_format};
use crate::*;

pub(crate) fn save_png(
    device: &wgpu::Device,
    buffer: &wgpu::Buffer,
    [w, h]: [u32; 2],
    format: wgpu::TextureFormat,
    path: &Path,
) -> Result<()> {
    let slice = buffer.slice(..);
    slice.map_async(wgpu::MapMode::Read, |_| {});
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| anyhow!("waiting for the screenshot: {e}"))?;
    let data = slice
        .get_mapped_range()
        .map_err(|e| anyhow!("reading the screenshot back: {e}"))?;
    let row = padded_row(w) as usize;
    let mut rgba = Vec::with_capacity((4 * w * h) as usize);
    for y in 0..h as usize {
        rgba.extend_from_slice(&data[y * row..y * row + 4 * w as usize]);
    }
    drop(data);
    buffer.unmap();
    let rgba = to_format(&rgba, format); // the swap is its own inverse
    stratus_compare::write_atomically(path, |tmp| {
        image::save_buffer(tmp, &rgba, w, h, image::ColorType::Rgba8)
    })
    .with_context(|| format!("writing {}", path.display()))
}

impl App {
    pub(crate) fn frame(&mut self) -> Result<()> {
        let gpu = self.gpu.as_mut().expect("a GPU once resumed");
        let state = &mut self.state;
        let now = Instant::now();
        let wall_dt = now.duration_since(gpu.last_frame).as_secs_f64();
        gpu.last_frame = now;
        // Frames per second from a running mean of the frame interval (the first interval,
        // from start-up, is not a frame's).
        if state.t > 0.0 && wall_dt > 0.0 {
            state.dt_mean = if state.dt_mean == 0.0 {
                wall_dt
            } else {
                0.8 * state.dt_mean + 0.2 * wall_dt
            };
        }
        let dt = match &mut self.script {
            Some(script) => {
                for e in script.due(state.t) {
                    state.play(e);
                }
                if script.finished() && state.screenshots.is_empty() {
                    state.quit = true;
                }
                SCRIPT_DT
            }
            None => wall_dt.min(0.25),
        };
        state.advance(dt);
        state.scene.camera.resolution = [gpu.config.width, gpu.config.height];

        let cpu_start = Instant::now();
        let raw_input = gpu.egui_state.take_egui_input(&gpu.window);
        let mut overlay_rect = None;
        let describe = gpu.describe.clone();
        let full = gpu.egui_ctx.run_ui(raw_input, |ui| {
            overlay_rect = state.ui(ui.ctx(), &describe);
        });
        gpu.egui_state
            .handle_platform_output(&gpu.window, full.platform_output);
        let pixels_per_point = full.pixels_per_point;
        let jobs = gpu.egui_ctx.tessellate(full.shapes, pixels_per_point);
        let screen = egui_wgpu::ScreenDescriptor {
            size_in_pixels: [gpu.config.width, gpu.config.height],
            pixels_per_point,
        };

        let offscreen_view = gpu.offscreen.create_view(&Default::default());
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        let mut ash_timings = None;
        match &mut gpu.clouds {
            Clouds::Wgpu(clouds) => {
                clouds
                    .update(stratus::Update {
                        scene: Some(state.scene.clone()),
                        ..Default::default()
                    })
                    .map_err(|e| anyhow!("{e}"))?;
                clouds
                    .render(&mut encoder, &offscreen_view)
                    .map_err(|e| anyhow!("{e}"))?;
            }
            Clouds::Ash { renderer, prepared } => {
                let scene = &state.scene;
                prepared.update(scene)?;
                let out = renderer
                    .render(&prepared.frame(scene).with_readback(Readback::output()))
                    .map_err(|e| anyhow!("ash: {e}"))?;
                let bytes = to_format(&out.image, gpu.config.format);
                gpu.queue.write_texture(
                    gpu.offscreen.as_image_copy(),
                    &bytes,
                    wgpu::TexelCopyBufferLayout {
                        offset: 0,
                        bytes_per_row: Some(4 * out.width),
                        rows_per_image: Some(out.height),
                    },
                    gpu.offscreen.size(),
                );
                ash_timings = Some(out.timings);
            }
        }
        // The clouds alone, before the overlay (for NAME.clouds.png).
        let clouds_copy = (!state.screenshots.is_empty())
            .then(|| copy_to_buffer(&gpu.device, &mut encoder, &gpu.offscreen));
        let mut textures = full.textures_delta;
        for (id, deltas) in textures.set.drain() {
            for delta in &deltas {
                gpu.egui_renderer
                    .update_texture(&gpu.device, &gpu.queue, id, delta);
            }
        }
        gpu.egui_renderer
            .update_buffers(&gpu.device, &gpu.queue, &mut encoder, &jobs, &screen);
        {
            let pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("overlay"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &offscreen_view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Load,
                        store: wgpu::StoreOp::Store,
                    },
                })],
                ..Default::default()
            });
            gpu.egui_renderer
                .render(&mut pass.forget_lifetime(), &jobs, &screen);
        }
        for id in textures.free.drain() {
            gpu.egui_renderer.free_texture(&id);
        }
        let shot_copy = (!state.screenshots.is_empty())
            .then(|| copy_to_buffer(&gpu.device, &mut encoder, &gpu.offscreen));
        let surface_texture = match gpu.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(t)
            | wgpu::CurrentSurfaceTexture::Suboptimal(t) => Some(t),
            _ => {
                gpu.surface.configure(&gpu.device, &gpu.config);
                None
            }
        };
        if let Some(t) = &surface_texture {
            encoder.copy_texture_to_texture(
                gpu.offscreen.as_image_copy(),
                t.texture.as_image_copy(),
                gpu.offscreen.size(),
            );
        }
        gpu.queue.submit([encoder.finish()]);
        state.cpu_ms = cpu_start.elapsed().as_secs_f64() * 1e3;
        if let Some(t) = surface_texture {
            gpu.window.pre_present_notify();
            gpu.queue.present(t);
            state.presented += 1;
        }
        state.timings = match (&mut gpu.clouds, ash_timings) {
            (_, Some(t)) => t,
            (Clouds::Wgpu(c), None) => c.pass_timings().unwrap_or_default(),
            _ => Vec::new(),
        };
        // Pass timings wait for the GPU; the ash frame was read back already.
        state.frame_ms = cpu_start.elapsed().as_secs_f64() * 1e3;

        if (state.measure || !state.screenshots.is_empty()) && gpu.offline.is_none() {
            let backend = match self.options.backend {
                ViewBackend::Wgpu => Backend::Wgpu,
                ViewBackend::Ash => Backend::Ash,
            };
            gpu.offline = Some(open_realtime(backend, false)?);
        }
        if state.measure {
            state.measure = false;
            let r = gpu.offline.as_mut().expect("made above");
            let plan = FramePlan::for_scene(&state.scene, true)?;
            let noise = Arc::new(stratus::noise_for(&state.scene));
            let out = r
                .render(
                    &FrameInput::new(&plan, &state.scene, &noise).with_readback(Readback::output()),
                )
                .map_err(|e| anyhow!("measuring: {e}"))?;
            let c = out
                .stats
                .as_ref()
                .context("the statistics variant returned no counters")?;
            let per_px = |name: &str| {
                c.get(name).copied().unwrap_or(0) as f64
                    / c.get("pixels").copied().unwrap_or(0).max(1) as f64
            };
            state.samples_per_px = Some([
                per_px("view_steps"),
                per_px("density_evaluations"),
                per_px("light_samples"),
            ]);
        }
        let shots: Vec<String> = state.screenshots.drain(..).collect();
        if let (Some(shot), Some(clouds)) = (shot_copy, clouds_copy) {
            for name in shots {
                let dir = &self.options.out_dir;
                let size = [gpu.config.width, gpu.config.height];
                save_png(
                    &gpu.device,
                    &shot,
                    size,
                    gpu.config.format,
                    &dir.join(format!("{name}.png")),
                )?;
                save_png(
                    &gpu.device,
                    &clouds,
                    size,
                    gpu.config.format,
                    &dir.join(format!("{name}.clouds.png")),
                )?;
                let r = gpu.offline.as_mut().expect("made above");
                let plan = FramePlan::for_scene(&state.scene, false)?;
                let noise = Arc::new(stratus::noise_for(&state.scene));
                let out = r
                    .render(
                        &FrameInput::new(&plan, &state.scene, &noise)
                            .with_readback(Readback::output()),
                    )
                    .map_err(|e| anyhow!("screenshot: {e}"))?;
                stratus_tool::output::write_image(&dir.join(format!("{name}.exr")), &out)?;
                let ppp = f64::from(pixels_per_point);
                let info = serde_json::json!({
                    "scene": state.name,
                    "weather": state.weather,
                    "backend": gpu.describe,
                    "size": size,
                    "camera": state.scene.camera,
                    "sun": state.scene.sun,
                    "clouds_time_s": state.scene.clouds.time_s,
                    "presented_frames": state.presented,
                    "overlay_px": overlay_rect.map(|r| [
                        f64::from(r.min.x) * ppp, f64::from(r.min.y) * ppp,
                        f64::from(r.max.x) * ppp, f64::from(r.max.y) * ppp,
                    ]),
                });
                stratus_compare::write_file_atomically(
                    &dir.join(format!("{name}.json")),
                    serde_json::to_string_pretty(&info)?.as_bytes(),
                )?;
                state.message = format!("wrote {}/{name}.png, .exr", dir.display());
                println!("{}", state.message);
            }
        }
        Ok(())
    }
}
