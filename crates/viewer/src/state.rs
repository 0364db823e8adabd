//! What the viewer shows and where it stands: the scene, the camera's motion, the clouds' time,
//! the recorded camera path and its replay.

use crate::*;

/// What the user controls and what the overlay shows (no GPU objects).
pub(crate) struct ViewState {
    pub(crate) scene: Scene,
    pub(crate) name: String,
    pub(crate) keys: HashSet<KeyCode>,
    pub(crate) speed_m_s: f64,
    pub(crate) dragging: bool,
    pub(crate) last_cursor: Option<(f64, f64)>,
    pub(crate) time_rate: f64,
    pub(crate) paused: bool,
    pub(crate) overlay: bool,
    /// Viewer time, seconds (fixed steps in script mode).
    pub(crate) t: f64,
    pub(crate) recording: Option<(f64, Vec<Keyframe>)>,
    pub(crate) recorded: Option<Animation>,
    /// Where recorded paths go, and how many were written.
    pub(crate) out_dir: PathBuf,
    pub(crate) paths: u32,
    pub(crate) replay: Option<(f64, Animation)>,
    pub(crate) screenshots: Vec<String>,
    pub(crate) shot_count: u32,
    pub(crate) weather: String,
    pub(crate) message: String,
    /// Running mean of the wall time between frames, seconds (0 before the second frame).
    pub(crate) dt_mean: f64,
    pub(crate) cpu_ms: f64,
    /// Frames handed to the window's surface so far (a frame whose surface texture could not
    /// be acquired renders but is not presented); screenshots record it, so that a test can
    /// tell a viewer that shows frames from one that only renders them.
    pub(crate) presented: u64,
    /// Wall time from the frame's start to the GPU being done with it.
    pub(crate) frame_ms: f64,
    pub(crate) timings: Vec<PassTiming>,
    /// View steps, density evaluations and light samples per pixel (the statistics variant).
    pub(crate) samples_per_px: Option<[f64; 3]>,
    pub(crate) measure: bool,
    /// Whether the overlay's controls start open (closed in script mode: the overlay stays
    /// small in a small window).
    pub(crate) controls_open: bool,
    pub(crate) quit: bool,
}

impl ViewState {
    pub(crate) fn new(scene: Scene, name: String) -> Self {
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
            presented: 0,
            frame_ms: 0.0,
            timings: Vec::new(),
            samples_per_px: None,
            measure: false,
            controls_open: true,
            quit: false,
        }
    }

    /// Applies a change to the scene if it stays valid; otherwise says why in the overlay.
    pub(crate) fn try_scene(&mut self, change: impl FnOnce(&mut Scene)) {
        let mut s = self.scene.clone();
        change(&mut s);
        match s.validate() {
            Ok(()) => self.scene = s,
            Err(e) => self.message = format!("not applied: {e}"),
        }
    }

    /// One frame's motion, time and recording, `dt` seconds after the last.
    pub(crate) fn advance(&mut self, dt: f64) {
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

    pub(crate) fn set_preset(&mut self, name: &str) {
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

    pub(crate) fn set_weather(&mut self, name: &str) {
        match stratus_weather::states::find(name) {
            Ok(state) => {
                let p = state.params;
                self.try_scene(|s| p.apply(s));
                self.weather = name.to_owned();
            }
            Err(e) => self.message = e.to_string(),
        }
    }

    pub(crate) fn toggle_recording(&mut self) {
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
                self.message =
                    match stratus_compare::write_file_atomically(&path, scene.to_toml().as_bytes())
                    {
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

    pub(crate) fn toggle_replay(&mut self) {
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
}
