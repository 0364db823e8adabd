//! Input: the window's events (keys, mouse, resize, close) into the view state, and the
//! scripted events a `--script` plays.

use crate::*;

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.gpu.is_some() {
            return;
        }
        match self.create_gpu(event_loop) {
            Ok(g) => {
                g.window.request_redraw();
                self.gpu = Some(g);
            }
            Err(e) => {
                self.error = Some(e);
                event_loop.exit();
            }
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        let Some(gpu) = &mut self.gpu else { return };
        let consumed = gpu.egui_state.on_window_event(&gpu.window, &event).consumed;
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => gpu.resize(size),
            WindowEvent::KeyboardInput { event: k, .. }
                if !consumed || !gpu.egui_ctx.egui_wants_keyboard_input() =>
            {
                if let PhysicalKey::Code(code) = k.physical_key {
                    self.state.key(code, k.state == ElementState::Pressed);
                }
            }
            WindowEvent::MouseInput {
                state,
                button: MouseButton::Left | MouseButton::Right,
                ..
            } => {
                let over_ui = gpu.egui_ctx.is_pointer_over_egui();
                self.state.dragging = state == ElementState::Pressed && !over_ui;
                self.state.last_cursor = None;
            }
            WindowEvent::CursorMoved { position, .. } if self.state.dragging => {
                if let Some((x, y)) = self.state.last_cursor {
                    self.state
                        .look((position.x - x) * 0.2, -(position.y - y) * 0.2);
                }
                self.state.last_cursor = Some((position.x, position.y));
            }
            WindowEvent::MouseWheel { delta, .. } if !consumed => {
                let steps = match delta {
                    MouseScrollDelta::LineDelta(_, y) => f64::from(y),
                    MouseScrollDelta::PixelDelta(p) => p.y / 40.0,
                };
                self.state.speed_m_s =
                    (self.state.speed_m_s * 1.25f64.powf(steps)).clamp(1.0, 100_000.0);
            }
            WindowEvent::RedrawRequested => {
                if let Err(e) = self.frame() {
                    self.error = Some(e);
                    event_loop.exit();
                    return;
                }
                if self.state.quit {
                    event_loop.exit();
                    return;
                }
                if let Some(g) = &self.gpu {
                    g.window.request_redraw();
                }
            }
            _ => {}
        }
    }
}

impl ViewState {
    pub(crate) fn look(&mut self, dyaw: f64, dpitch: f64) {
        let c = &mut self.scene.camera;
        c.yaw_deg = (c.yaw_deg + dyaw).rem_euclid(360.0);
        c.pitch_deg = (c.pitch_deg + dpitch).clamp(-89.0, 89.0);
    }

    pub(crate) fn key(&mut self, key: KeyCode, down: bool) {
        if !down {
            self.keys.remove(&key);
            return;
        }
        if !self.keys.insert(key) {
            return; // a held key repeats: act once
        }
        match key {
            KeyCode::F1 => self.overlay = !self.overlay,
            KeyCode::F2 => {
                self.shot_count += 1;
                self.screenshots
                    .push(format!("shot-{:03}", self.shot_count));
            }
            KeyCode::Space => self.paused = !self.paused,
            KeyCode::KeyR => self.toggle_recording(),
            KeyCode::KeyP => self.toggle_replay(),
            KeyCode::Escape => self.quit = true,
            _ => {}
        }
    }

    pub(crate) fn play(&mut self, e: script::Event) {
        if let Some(k) = &e.key {
            let key = key_from_name(k).expect("checked when the script loaded");
            let held = matches!(
                key,
                KeyCode::KeyW
                    | KeyCode::KeyA
                    | KeyCode::KeyS
                    | KeyCode::KeyD
                    | KeyCode::KeyQ
                    | KeyCode::KeyE
                    | KeyCode::ShiftLeft
            );
            self.key(key, e.down.unwrap_or(true));
            // Toggles (R, P, F1, F2, Space, Esc) are a press and a release.
            if !held {
                self.key(key, false);
            }
        }
        if let Some([dy, dp]) = e.look {
            self.look(dy, dp);
        }
        if let Some(w) = e.wheel {
            self.speed_m_s = (self.speed_m_s * 1.25f64.powf(w)).clamp(1.0, 100_000.0);
        }
        if let Some([el, az]) = e.sun {
            self.try_scene(|s| {
                s.sun.elevation_deg = el;
                s.sun.azimuth_deg = az;
                s.sun.direction = None;
                // The sun set by hand replaces one set by a date and place.
                s.sky = Default::default();
            });
        }
        if let Some(t) = e.time_s {
            self.scene.clouds.time_s = t;
        }
        if let Some(p) = &e.preset {
            self.set_preset(p);
        }
        if let Some(w) = &e.weather {
            self.set_weather(w);
        }
        if let Some(n) = e.view_steps {
            self.try_scene(|s| s.quality.view_steps = n);
        }
        if let Some(name) = e.screenshot {
            self.screenshots.push(name);
        }
        if e.measure == Some(true) {
            self.measure = true;
        }
        if e.quit == Some(true) {
            self.quit = true;
        }
    }
}
