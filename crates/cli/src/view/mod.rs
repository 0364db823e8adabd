//! `stratus view`: an interactive window (winit) that flies a camera through the clouds, with
//! an egui overlay of timings and controls, screenshots, camera-path recording, and a
//! scripted, headless-testable mode (`--script`).
//!
//! Every frame draws into an offscreen texture in the window's format: the clouds (on wgpu,
//! [`stratus::Clouds`] on the viewer's own device; on ash, a frame rendered by the ash backend
//! and uploaded), then the overlay on top; the texture is copied to the swapchain image and
//! read back for screenshots, so a screenshot is exactly what the window shows.

mod script;

use std::{
    collections::HashSet,
    path::{Path, PathBuf},
    sync::Arc,
    time::Instant,
};

use anyhow::{Context, Result, anyhow, bail};
use clap::{Args, ValueEnum};
use stratus_graph::{FrameInput, FramePlan, PassTiming, Readback, Requirements};
use stratus_noise::NoiseSet;
use stratus_scene::{Animation, Integration, Keyframe, Method, Scene, Temporal};
use winit::{
    application::ApplicationHandler,
    dpi::PhysicalSize,
    event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent},
    event_loop::{ActiveEventLoop, EventLoop},
    keyboard::{KeyCode, PhysicalKey},
    window::{Window, WindowId},
};

use crate::{
    render::{Backend, open_realtime},
    scene_io::{load_scene, parse_size},
};
use script::{SCRIPT_DT, Script};

/// Options of `stratus view`.
#[derive(Args)]
#[command(
    after_help = "Keys: W/A/S/D fly, Q/E down/up, Shift faster, mouse drag (right or left \
button) looks, wheel changes the speed, Space pauses the clouds' time, F2 screenshot, R record \
the camera path (again: write it as an [animation] scene), P replay the recorded path (or the \
scene's), F1 hides the overlay, Esc quits."
)]
pub struct ViewArgs {
    /// A built-in preset (see `stratus presets`).
    #[arg(long, conflicts_with = "scene")]
    preset: Option<String>,
    /// A scene file (TOML).
    #[arg(long)]
    scene: Option<PathBuf>,
    /// The renderer: wgpu on the window's own device, or ash (raw Vulkan; its frames are read
    /// back and shown through the window's wgpu swapchain).
    #[arg(long, value_enum, default_value_t = ViewBackend::Wgpu)]
    backend: ViewBackend,
    /// Window size as WIDTHxHEIGHT; the clouds render at this size.
    #[arg(long, value_parser = parse_size, default_value = "640x360")]
    size: (u32, u32),
    /// Wait for the display's refresh (on), or present as fast as frames come (off).
    #[arg(long, value_enum, default_value_t = Vsync::On)]
    vsync: Vsync,
    /// Play timed input events from this TOML file (frames advance 1/30 s each), then quit.
    #[arg(long)]
    script: Option<PathBuf>,
    /// Where screenshots and recorded camera paths go.
    #[arg(long, default_value = "screenshots")]
    out_dir: PathBuf,
}

/// Which renderer the viewer shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ViewBackend {
    /// wgpu (Vulkan) on the window's device.
    Wgpu,
    /// ash: raw Vulkan from the committed SPIR-V, read back and shown.
    Ash,
}

/// Vertical sync.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Vsync {
    /// Present on the display's refresh (FIFO).
    On,
    /// Present at once (IMMEDIATE or MAILBOX where the surface has them).
    Off,
}

/// The key a script or the keyboard names.
pub(crate) fn key_from_name(name: &str) -> Option<KeyCode> {
    Some(match name.to_ascii_uppercase().as_str() {
        "W" => KeyCode::KeyW,
        "A" => KeyCode::KeyA,
        "S" => KeyCode::KeyS,
        "D" => KeyCode::KeyD,
        "Q" => KeyCode::KeyQ,
        "E" => KeyCode::KeyE,
        "R" => KeyCode::KeyR,
        "P" => KeyCode::KeyP,
        "SHIFT" => KeyCode::ShiftLeft,
        "SPACE" => KeyCode::Space,
        "F1" => KeyCode::F1,
        "F2" => KeyCode::F2,
        "ESCAPE" | "ESC" => KeyCode::Escape,
        _ => return None,
    })
}

/// Runs `stratus view`.
pub fn run(args: ViewArgs) -> Result<()> {
    if crate::render::validation() {
        crate::validation::record();
    }
    let (scene, name) = load_scene(args.preset.as_deref(), args.scene.as_ref(), Some(args.size))?;
    let script = args.script.as_deref().map(Script::load).transpose()?;
    std::fs::create_dir_all(&args.out_dir)
        .with_context(|| format!("creating {}", args.out_dir.display()))?;
    let event_loop = EventLoop::new().map_err(|e| {
        anyhow!("no window system ({e}): `stratus view` needs a display (X11; run it under Xvfb when headless)")
    })?;
    let mut app = App {
        options: Options {
            backend: args.backend,
            vsync: args.vsync,
            out_dir: args.out_dir.clone(),
            scripted: script.is_some(),
        },
        state: ViewState {
            controls_open: args.script.is_none(),
            out_dir: args.out_dir.clone(),
            ..ViewState::new(scene, name)
        },
        script,
        gpu: None,
        error: None,
    };
    event_loop.run_app(&mut app)?;
    if let Some(e) = app.error {
        return Err(e);
    }
    let messages = crate::validation::take();
    if !messages.is_empty() {
        bail!("validation messages:\n{}", messages.join("\n"));
    }
    Ok(())
}

struct Options {
    backend: ViewBackend,
    vsync: Vsync,
    out_dir: PathBuf,
    scripted: bool,
}

/// What the user controls and what the overlay shows (no GPU objects).
struct ViewState {
    scene: Scene,
    name: String,
    keys: HashSet<KeyCode>,
    speed_m_s: f64,
    dragging: bool,
    last_cursor: Option<(f64, f64)>,
    time_rate: f64,
    paused: bool,
    overlay: bool,
    /// Viewer time, seconds (fixed steps in script mode).
    t: f64,
    recording: Option<(f64, Vec<Keyframe>)>,
    recorded: Option<Animation>,
    /// Where recorded paths go, and how many were written.
    out_dir: PathBuf,
    paths: u32,
    replay: Option<(f64, Animation)>,
    screenshots: Vec<String>,
    shot_count: u32,
    weather: String,
    message: String,
    /// Running mean of the wall time between frames, seconds (0 before the second frame).
    dt_mean: f64,
    cpu_ms: f64,
    /// Wall time from the frame's start to the GPU being done with it.
    frame_ms: f64,
    timings: Vec<PassTiming>,
    /// View steps, density evaluations and light samples per pixel (the statistics variant).
    samples_per_px: Option<[f64; 3]>,
    measure: bool,
    /// Whether the overlay's controls start open (closed in script mode: the overlay stays
    /// small in a small window).
    controls_open: bool,
    quit: bool,
}

impl ViewState {
    fn new(scene: Scene, name: String) -> Self {
        Self {
            scene,
            name,
            keys: HashSet::new(),
            speed_m_s: 100.0,
            dragging: false,
            last_cursor: None,
            time_rate: 1.0,
            paused: false,
            overlay: true,
            t: 0.0,
            recording: None,
            recorded: None,
            out_dir: PathBuf::from("."),
            paths: 0,
            replay: None,
            screenshots: Vec::new(),
            shot_count: 0,
            weather: "(scene)".into(),
            message: String::new(),
            dt_mean: 0.0,
            cpu_ms: 0.0,
            frame_ms: 0.0,
            timings: Vec::new(),
            samples_per_px: None,
            measure: false,
            controls_open: true,
            quit: false,
        }
    }

    /// Applies a change to the scene if it stays valid; otherwise says why in the overlay.
    fn try_scene(&mut self, change: impl FnOnce(&mut Scene)) {
        let mut s = self.scene.clone();
        change(&mut s);
        match s.validate() {
            Ok(()) => self.scene = s,
            Err(e) => self.message = format!("not applied: {e}"),
        }
    }

    fn look(&mut self, dyaw: f64, dpitch: f64) {
        let c = &mut self.scene.camera;
        c.yaw_deg = (c.yaw_deg + dyaw).rem_euclid(360.0);
        c.pitch_deg = (c.pitch_deg + dpitch).clamp(-89.0, 89.0);
    }

    fn key(&mut self, key: KeyCode, down: bool) {
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

    fn toggle_recording(&mut self) {
        // The path ends where the camera is now.
        if let Some((t0, keys)) = &mut self.recording {
            let time_s = self.t - *t0;
            if keys.last().is_some_and(|k| time_s > k.time_s) {
                let c = &self.scene.camera;
                keys.push(Keyframe {
                    time_s,
                    position: c.position,
                    yaw_deg: c.yaw_deg,
                    pitch_deg: c.pitch_deg,
                });
            }
        }
        match self.recording.take() {
            None => {
                self.recording = Some((self.t, Vec::new()));
                self.message = "recording the camera path (R again to stop)".into();
            }
            Some((_, keys)) if keys.len() < 2 => {
                self.message = "recording stopped: too short to keep".into();
            }
            Some((_, keys)) => {
                let duration = keys.last().map_or(0.0, |k| k.time_s);
                let animation = Animation {
                    duration_s: duration.max(1e-3),
                    keyframes: keys,
                };
                self.paths += 1;
                let path = self.out_dir.join(format!("path-{:03}.toml", self.paths));
                let scene = Scene {
                    animation: Some(animation.clone()),
                    ..self.scene.clone()
                };
                self.message = match std::fs::write(&path, scene.to_toml()) {
                    Ok(()) => format!(
                        "wrote {} (stratus animate --scene plays it); P replays it",
                        path.display()
                    ),
                    Err(e) => format!("writing {}: {e}", path.display()),
                };
                println!("{}", self.message);
                self.recorded = Some(animation);
            }
        }
    }

    fn toggle_replay(&mut self) {
        if self.replay.take().is_some() {
            return;
        }
        match self
            .recorded
            .clone()
            .or_else(|| self.scene.animation.clone())
        {
            Some(a) => self.replay = Some((self.t, a)),
            None => self.message = "nothing to replay: record a path with R first".into(),
        }
    }

    /// One frame's motion, time and recording, `dt` seconds after the last.
    fn advance(&mut self, dt: f64) {
        self.t += dt;
        let fast = if self.keys.contains(&KeyCode::ShiftLeft) {
            5.0
        } else {
            1.0
        };
        let (forward, right, _) = self.scene.camera_basis();
        let mut d = [0.0f64; 3];
        let mut add = |v: [f64; 3], s: f64| (0..3).for_each(|i| d[i] += v[i] * s);
        for (k, v, s) in [
            (KeyCode::KeyW, forward, 1.0),
            (KeyCode::KeyS, forward, -1.0),
            (KeyCode::KeyD, right, 1.0),
            (KeyCode::KeyA, right, -1.0),
            (KeyCode::KeyE, [0.0, 1.0, 0.0], 1.0),
            (KeyCode::KeyQ, [0.0, 1.0, 0.0], -1.0),
        ] {
            if self.keys.contains(&k) {
                add(v, s);
            }
        }
        let step = self.speed_m_s * fast * dt;
        let p = &mut self.scene.camera.position;
        for i in 0..3 {
            p[i] += d[i] * step;
        }
        p[1] = p[1].max(1.0);
        if let Some((t0, a)) = &self.replay {
            let at = self.t - t0;
            if at > a.duration_s {
                self.replay = None;
            } else {
                let s = Scene {
                    animation: Some(a.clone()),
                    ..self.scene.clone()
                }
                .at_time(at);
                self.scene.camera = s.camera;
            }
        }
        if !self.paused {
            self.scene.clouds.time_s += dt * self.time_rate;
        }
        self.scene.quality.frame = self.scene.quality.frame.wrapping_add(1);
        if let Some((t0, keys)) = &mut self.recording {
            let c = &self.scene.camera;
            let time_s = self.t - *t0;
            // A keyframe every quarter second: smoothstep between them follows the path.
            if keys.last().is_none_or(|k| time_s - k.time_s >= 0.25) {
                keys.push(Keyframe {
                    time_s,
                    position: c.position,
                    yaw_deg: c.yaw_deg,
                    pitch_deg: c.pitch_deg,
                });
            }
        }
    }

    fn play(&mut self, e: script::Event) {
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

    fn set_preset(&mut self, name: &str) {
        match Scene::preset(name) {
            Ok(p) => {
                let camera = self.scene.camera.clone();
                self.scene = Scene { camera, ..p };
                self.name = name.to_owned();
                self.weather = "(scene)".into();
            }
            Err(e) => self.message = e.to_string(),
        }
    }

    fn set_weather(&mut self, name: &str) {
        match stratus_weather::states::find(name) {
            Ok(state) => {
                let p = state.params;
                self.try_scene(|s| p.apply(s));
                self.weather = name.to_owned();
            }
            Err(e) => self.message = e.to_string(),
        }
    }

    /// The overlay: timings and the controls. Returns the overlay's rectangle in points.
    fn ui(&mut self, ctx: &egui::Context, backend: &str) -> Option<egui::Rect> {
        if !self.overlay {
            return None;
        }
        let frame =
            egui::Frame::window(&ctx.global_style()).fill(egui::Color32::from_black_alpha(235));
        let response = egui::Window::new("Stratus")
            .frame(frame)
            .default_pos([6.0, 6.0])
            .resizable(false)
            .show(ctx, |ui| {
                ui.label(backend);
                ui.label(format!(
                    "{:.1} fps, CPU {:.2} ms/frame, to GPU idle {:.1} ms, {}x{}",
                    if self.dt_mean > 0.0 {
                        1.0 / self.dt_mean
                    } else {
                        0.0
                    },
                    self.cpu_ms,
                    self.frame_ms,
                    self.scene.camera.resolution[0],
                    self.scene.camera.resolution[1]
                ));
                for t in &self.timings {
                    ui.label(format!("  {:<10} {:7.2} ms GPU", t.pass, t.ms));
                }
                ui.horizontal(|ui| {
                    match self.samples_per_px {
                        Some([v, d, l]) => ui.label(format!(
                            "per px: {v:.1} view steps, {d:.1} density, {l:.1} light samples"
                        )),
                        None => ui.label("samples/px: -"),
                    };
                    if ui.button("measure").clicked() {
                        self.measure = true;
                    }
                });
                let c = &self.scene.camera;
                ui.label(format!(
                    "camera [{:.0}, {:.0}, {:.0}] m, yaw {:.0}, pitch {:.0}, {:.0} m/s",
                    c.position[0],
                    c.position[1],
                    c.position[2],
                    c.yaw_deg,
                    c.pitch_deg,
                    self.speed_m_s
                ));
                egui::CollapsingHeader::new("controls")
                    .default_open(self.controls_open)
                    .show(ui, |ui| {
                        let mut preset = self.name.clone();
                        egui::ComboBox::from_label("preset")
                            .selected_text(&preset)
                            .show_ui(ui, |ui| {
                                for p in stratus_scene::presets() {
                                    ui.selectable_value(&mut preset, p.name.to_string(), p.name);
                                }
                            });
                        if preset != self.name {
                            self.set_preset(&preset);
                        }
                        let mut weather = self.weather.clone();
                        egui::ComboBox::from_label("weather")
                            .selected_text(&weather)
                            .show_ui(ui, |ui| {
                                for s in &stratus_weather::states::STATES {
                                    ui.selectable_value(&mut weather, s.name.to_string(), s.name);
                                }
                            });
                        if weather != self.weather {
                            self.set_weather(&weather);
                        }
                        let mut s = self.scene.clone();
                        ui.add(
                            egui::Slider::new(&mut s.sun.elevation_deg, -10.0..=90.0)
                                .text("sun elevation"),
                        );
                        ui.add(
                            egui::Slider::new(&mut s.sun.azimuth_deg, 0.0..=360.0)
                                .text("sun azimuth"),
                        );
                        ui.horizontal(|ui| {
                            ui.add(
                                egui::Slider::new(&mut self.time_rate, 0.0..=100.0).text("time x"),
                            );
                            ui.checkbox(&mut self.paused, "paused");
                        });
                        ui.label(format!("clouds time {:.1} s", s.clouds.time_s));
                        ui.add(
                            egui::Slider::new(&mut s.quality.view_steps, 1..=512)
                                .text("view steps"),
                        );
                        ui.add(
                            egui::Slider::new(&mut s.quality.light_steps, 0..=16)
                                .text("light steps"),
                        );
                        ui.add(
                            egui::Slider::new(&mut s.lighting.multiple_scattering.octaves, 0..=8)
                                .text("octaves"),
                        );
                        ui.horizontal(|ui| {
                            for t in Temporal::ALL {
                                ui.radio_value(&mut s.quality.temporal, t, t.name());
                            }
                            ui.label("temporal");
                        });
                        ui.horizontal(|ui| {
                            ui.radio_value(
                                &mut s.quality.integration,
                                Integration::Analytic,
                                "analytic",
                            );
                            ui.radio_value(
                                &mut s.quality.integration,
                                Integration::Riemann,
                                "riemann",
                            );
                        });
                        ui.horizontal(|ui| {
                            for m in Method::ALL {
                                ui.radio_value(&mut s.quality.method, m, m.name());
                            }
                        });
                        if s != self.scene {
                            s.sun.direction = None;
                            // Moving the sun's sliders takes the sun from them, not from a
                            // [sky] date and place (which would ignore them).
                            if (s.sun.elevation_deg, s.sun.azimuth_deg)
                                != (self.scene.sun.elevation_deg, self.scene.sun.azimuth_deg)
                            {
                                s.sky = Default::default();
                            }
                            self.try_scene(|x| *x = s);
                        }
                        ui.horizontal(|ui| {
                            if ui.button("screenshot (F2)").clicked() {
                                self.key(KeyCode::F2, true);
                                self.key(KeyCode::F2, false);
                            }
                            let rec = if self.recording.is_some() {
                                "stop (R)"
                            } else {
                                "record (R)"
                            };
                            if ui.button(rec).clicked() {
                                self.toggle_recording();
                            }
                            if ui.button("replay (P)").clicked() {
                                self.toggle_replay();
                            }
                        });
                    });
                if !self.message.is_empty() {
                    ui.label(&self.message);
                }
            });
        response.map(|r| r.response.rect)
    }
}

/// The renderer that draws the clouds.
enum Clouds {
    Wgpu(Box<stratus::Clouds>),
    Ash {
        renderer: Box<dyn stratus_graph::Backend>,
        plan: FramePlan,
        key: (Requirements, [u32; 2]),
        noise: Arc<NoiseSet>,
        noise_seed: stratus_scene::Noise,
    },
}

struct Gpu {
    window: Arc<Window>,
    surface: wgpu::Surface<'static>,
    device: wgpu::Device,
    queue: wgpu::Queue,
    config: wgpu::SurfaceConfiguration,
    offscreen: wgpu::Texture,
    egui_ctx: egui::Context,
    egui_state: egui_winit::State,
    egui_renderer: egui_wgpu::Renderer,
    clouds: Clouds,
    /// Renders stills for EXR screenshots and the work counters, on the viewer's backend.
    offline: Option<Box<dyn stratus_graph::Backend>>,
    describe: String,
    last_frame: Instant,
}

struct App {
    options: Options,
    state: ViewState,
    script: Option<Script>,
    gpu: Option<Gpu>,
    error: Option<anyhow::Error>,
}

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

impl App {
    fn create_gpu(&mut self, event_loop: &ActiveEventLoop) -> Result<Gpu> {
        let [w, h] = self.state.scene.camera.resolution;
        let window = Arc::new(
            event_loop
                .create_window(
                    Window::default_attributes()
                        .with_title(format!("Stratus: {}", self.state.name))
                        .with_inner_size(PhysicalSize::new(w, h))
                        .with_resizable(!self.options.scripted),
                )
                .context("creating the window")?,
        );
        let mut desc = wgpu::InstanceDescriptor::new_with_display_handle(Box::new(window.clone()));
        desc.backends = wgpu::Backends::VULKAN;
        desc.flags = if crate::render::validation() {
            wgpu::InstanceFlags::VALIDATION
        } else {
            wgpu::InstanceFlags::empty()
        };
        let instance = wgpu::Instance::new(desc);
        let surface = instance
            .create_surface(window.clone())
            .context("creating a Vulkan surface for the window")?;
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            compatible_surface: Some(&surface),
            ..Default::default()
        }))
        .context("no Vulkan adapter can present to this window (install mesa-vulkan-drivers for lavapipe)")?;
        let features = adapter.features() & wgpu::Features::TIMESTAMP_QUERY;
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("stratus view"),
            required_features: features,
            required_limits: adapter.limits(),
            ..Default::default()
        }))
        .context("creating the device")?;
        let caps = surface.get_capabilities(&adapter);
        let format = caps
            .formats
            .iter()
            .copied()
            .find(|f| {
                matches!(
                    f,
                    wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Rgba8Unorm
                )
            })
            .or_else(|| caps.formats.first().map(|f| f.remove_srgb_suffix()))
            .context("the surface offers no formats")?;
        if !caps.usages.contains(wgpu::TextureUsages::COPY_DST) {
            bail!("the window's swapchain images cannot be copied into (no COPY_DST usage)");
        }
        let present_mode = present_mode(self.options.vsync, &caps.present_modes);
        let size = window.inner_size();
        let config = wgpu::SurfaceConfiguration {
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_DST,
            format,
            color_space: wgpu::SurfaceColorSpace::Auto,
            width: size.width.max(1),
            height: size.height.max(1),
            present_mode,
            alpha_mode: caps.alpha_modes[0],
            view_formats: vec![],
            desired_maximum_frame_latency: 2,
        };
        surface.configure(&device, &config);
        let offscreen = offscreen_texture(&device, format, config.width, config.height);
        let egui_ctx = egui::Context::default();
        let egui_state = egui_winit::State::new(
            egui_ctx.clone(),
            egui::ViewportId::ROOT,
            &window,
            Some(1.0),
            None,
            None,
        );
        let egui_renderer =
            egui_wgpu::Renderer::new(&device, format, egui_wgpu::RendererOptions::default());
        let info = adapter.get_info();
        let (clouds, describe) = match self.options.backend {
            ViewBackend::Wgpu => (
                Clouds::Wgpu(Box::new(
                    stratus::Clouds::new(&device, &queue, self.state.scene.clone())
                        .map_err(|e| anyhow!("{e}"))?,
                )),
                format!("wgpu (Vulkan) on {}", info.name),
            ),
            ViewBackend::Ash => {
                let renderer = open_realtime(Backend::Ash, false)?;
                let describe = format!(
                    "{}, shown through wgpu on {}",
                    renderer.describe(),
                    info.name
                );
                let scene = &self.state.scene;
                (
                    Clouds::Ash {
                        renderer,
                        plan: FramePlan::for_scene(scene, false)?,
                        key: (Requirements::of(scene, false), scene.camera.resolution),
                        noise: Arc::new(stratus::noise_for(scene)),
                        noise_seed: scene.noise.clone(),
                    },
                    describe,
                )
            }
        };
        Ok(Gpu {
            window,
            surface,
            device,
            queue,
            config,
            offscreen,
            egui_ctx,
            egui_state,
            egui_renderer,
            clouds,
            offline: None,
            describe: format!("{describe}, {:?}", present_mode),
            last_frame: Instant::now(),
        })
    }

    fn frame(&mut self) -> Result<()> {
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
            Clouds::Ash {
                renderer,
                plan,
                key,
                noise,
                noise_seed,
            } => {
                let scene = &state.scene;
                let k = (Requirements::of(scene, false), scene.camera.resolution);
                if k != *key {
                    *plan = FramePlan::for_scene(scene, false)?;
                    *key = k;
                }
                if scene.noise != *noise_seed {
                    *noise = Arc::new(stratus::noise_for(scene));
                    *noise_seed = scene.noise.clone();
                }
                let out = renderer
                    .render(&FrameInput::new(plan, scene, noise).with_readback(Readback::output()))
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
                crate::output::write_image(&dir.join(format!("{name}.exr")), &out)?;
                let ppp = f64::from(pixels_per_point);
                let info = serde_json::json!({
                    "scene": state.name,
                    "weather": state.weather,
                    "backend": gpu.describe,
                    "size": size,
                    "camera": state.scene.camera,
                    "sun": state.scene.sun,
                    "clouds_time_s": state.scene.clouds.time_s,
                    "overlay_px": overlay_rect.map(|r| [
                        f64::from(r.min.x) * ppp, f64::from(r.min.y) * ppp,
                        f64::from(r.max.x) * ppp, f64::from(r.max.y) * ppp,
                    ]),
                });
                std::fs::write(
                    dir.join(format!("{name}.json")),
                    serde_json::to_string_pretty(&info)?,
                )?;
                state.message = format!("wrote {}/{name}.png, .exr", dir.display());
                println!("{}", state.message);
            }
        }
        Ok(())
    }
}

impl Gpu {
    fn resize(&mut self, size: PhysicalSize<u32>) {
        if size.width == 0 || size.height == 0 {
            return;
        }
        self.config.width = size.width;
        self.config.height = size.height;
        self.surface.configure(&self.device, &self.config);
        self.offscreen =
            offscreen_texture(&self.device, self.config.format, size.width, size.height);
    }
}

fn present_mode(vsync: Vsync, modes: &[wgpu::PresentMode]) -> wgpu::PresentMode {
    match vsync {
        Vsync::On => wgpu::PresentMode::Fifo,
        Vsync::Off => [wgpu::PresentMode::Immediate, wgpu::PresentMode::Mailbox]
            .into_iter()
            .find(|m| modes.contains(m))
            .unwrap_or(wgpu::PresentMode::Fifo),
    }
}

fn offscreen_texture(
    device: &wgpu::Device,
    format: wgpu::TextureFormat,
    w: u32,
    h: u32,
) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some("view frame"),
        size: wgpu::Extent3d {
            width: w,
            height: h,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT
            | wgpu::TextureUsages::COPY_SRC
            | wgpu::TextureUsages::COPY_DST
            | wgpu::TextureUsages::TEXTURE_BINDING,
        view_formats: &[],
    })
}

/// RGBA8 bytes in the window's format (BGRA swaps red and blue).
fn to_format(rgba: &[u8], format: wgpu::TextureFormat) -> Vec<u8> {
    let mut out = rgba.to_vec();
    if format == wgpu::TextureFormat::Bgra8Unorm {
        out.chunks_exact_mut(4).for_each(|p| p.swap(0, 2));
    }
    out
}

/// Row pitch of a texture-to-buffer copy (a multiple of 256 bytes).
fn padded_row(width: u32) -> u32 {
    (4 * width).div_ceil(256) * 256
}

fn copy_to_buffer(
    device: &wgpu::Device,
    encoder: &mut wgpu::CommandEncoder,
    texture: &wgpu::Texture,
) -> wgpu::Buffer {
    let size = texture.size();
    let row = padded_row(size.width);
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("screenshot"),
        size: u64::from(row) * u64::from(size.height),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(row),
                rows_per_image: Some(size.height),
            },
        },
        size,
    );
    buffer
}

fn save_png(
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
    image::save_buffer(path, &rgba, w, h, image::ColorType::Rgba8)
        .with_context(|| format!("writing {}", path.display()))
}
