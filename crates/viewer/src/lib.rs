//! `stratus view`: an interactive window (winit) that flies a camera through the clouds, with
//! an egui overlay of timings and controls, screenshots, camera-path recording, and a
//! scripted, headless-testable mode (`--script`).
//!
//! Every frame draws into an offscreen texture in the window's format: the clouds (on wgpu,
//! [`stratus::Clouds`] on the viewer's own device; on ash, a frame rendered by the ash backend
//! and uploaded), then the overlay on top; the texture is copied to the swapchain image and
//! read back for screenshots, so a screenshot is exactly what the window shows.
//!
//! One concern a module: [`state`] (the scene, the camera's motion, recording), [`input`]
//! (window and scripted events), [`ui`] (the overlay), [`gpu`] (the device, surface and
//! renderers), [`frame`] (drawing one frame, screenshots).

mod frame;
mod gpu;
mod input;
mod script;
mod state;
mod ui;

use gpu::{Clouds, Gpu};
use state::ViewState;

use std::{
    collections::HashSet,
    path::{Path, PathBuf},
    sync::Arc,
    time::Instant,
};

use anyhow::{Context, Result, anyhow, bail};
use clap::{Args, ValueEnum};
use stratus_graph::{FrameInput, FramePlan, PassTiming, Readback};
use stratus_scene::{Animation, Integration, Keyframe, Method, Scene, Temporal};
use winit::{
    application::ApplicationHandler,
    dpi::PhysicalSize,
    event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent},
    event_loop::{ActiveEventLoop, EventLoop},
    keyboard::{KeyCode, PhysicalKey},
    window::{Window, WindowId},
};

use script::{SCRIPT_DT, Script};
use stratus_tool::{
    backends::{Backend, open_realtime},
    scene_io::{load_scene, parse_size},
};

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
    if stratus_tool::backends::validation() {
        stratus_tool::validation::record();
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
    let messages = stratus_tool::validation::take();
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

struct App {
    options: Options,
    state: ViewState,
    script: Option<Script>,
    gpu: Option<Gpu>,
    error: Option<anyhow::Error>,
}
