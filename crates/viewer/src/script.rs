//! `stratus view --script FILE`: timed input events played into the viewer, so that a
//! headless run (CI under Xvfb) flies the camera, changes settings and takes screenshots.
//!
//! A script is TOML: a list of `[[event]]` tables, each with `at` (seconds of viewer time) and
//! exactly one action. In script mode every frame advances exactly 1/30 s, so a script gives
//! the same frames on any machine, however slow.

use std::path::Path;

use anyhow::{Context, Result, bail};
use serde::Deserialize;

/// Viewer seconds one frame advances in script mode.
pub const SCRIPT_DT: f64 = 1.0 / 30.0;

/// One timed event.
#[derive(Clone, Debug, Default, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Event {
    /// When it fires, seconds from the start (frames advance 1/30 s each).
    pub at: f64,
    /// A key: `W`, `A`, `S`, `D`, `Q`, `E` and `Shift` are pressed (`down = true`, the
    /// default) or released (`down = false`); `R`, `P`, `F1`, `F2`, `Space` and `Esc` are
    /// pressed and released at once (they toggle).
    pub key: Option<String>,
    /// With `key`: pressed (true, the default) or released.
    pub down: Option<bool>,
    /// A mouse look: yaw and pitch change in degrees.
    pub look: Option<[f64; 2]>,
    /// Mouse-wheel steps (each scales the fly speed by 1.25).
    pub wheel: Option<f64>,
    /// The sun's elevation and azimuth in degrees (time of day until the sky has dates).
    pub sun: Option<[f64; 2]>,
    /// Set the clouds' animation time, seconds.
    pub time_s: Option<f64>,
    /// Switch to a preset.
    pub preset: Option<String>,
    /// Apply a weather state (`stratus weather --list`).
    pub weather: Option<String>,
    /// Set the view steps.
    pub view_steps: Option<u32>,
    /// Take a screenshot: writes NAME.png (the window with its overlay), NAME.clouds.png (the
    /// clouds alone), NAME.exr (linear radiance) and NAME.json (what was shown, and where the
    /// overlay is).
    pub screenshot: Option<String>,
    /// Measure the work (density samples per pixel) with the statistics variant, as the
    /// overlay's `measure` button does.
    pub measure: Option<bool>,
    /// Stop the viewer.
    pub quit: Option<bool>,
}

impl Event {
    fn actions(&self) -> usize {
        [
            self.key.is_some(),
            self.look.is_some(),
            self.wheel.is_some(),
            self.sun.is_some(),
            self.time_s.is_some(),
            self.preset.is_some(),
            self.weather.is_some(),
            self.view_steps.is_some(),
            self.screenshot.is_some(),
            self.measure.is_some(),
            self.quit.is_some(),
        ]
        .iter()
        .filter(|&&b| b)
        .count()
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    event: Vec<Event>,
}

/// A loaded script: its events in time order, and how far it has played.
pub struct Script {
    events: Vec<Event>,
    next: usize,
}

impl Script {
    /// Loads and checks a script file.
    pub fn load(path: &Path) -> Result<Self> {
        let text =
            std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
        Self::parse(&text).with_context(|| format!("script {}", path.display()))
    }

    /// Parses a script.
    pub fn parse(text: &str) -> Result<Self> {
        let file: File = toml::from_str(text).context("not a valid script")?;
        for (i, e) in file.event.iter().enumerate() {
            if !(e.at.is_finite() && e.at >= 0.0) {
                bail!("event {}: at = {} must be a time >= 0", i + 1, e.at);
            }
            if e.actions() != 1 {
                bail!(
                    "event {} (at {} s): needs exactly one action (key, look, wheel, sun, time_s, preset, weather, view_steps, screenshot, measure or quit), has {}",
                    i + 1,
                    e.at,
                    e.actions()
                );
            }
            if e.down.is_some() && e.key.is_none() {
                bail!("event {}: `down` goes with `key`", i + 1);
            }
            if let Some(k) = &e.key {
                if super::key_from_name(k).is_none() {
                    bail!("event {}: unknown key `{k}`", i + 1);
                }
            }
        }
        let mut events = file.event;
        // Stable: events at the same time fire in file order.
        events.sort_by(|a, b| a.at.total_cmp(&b.at));
        Ok(Self { events, next: 0 })
    }

    /// The events due by time `t` not yet played.
    pub fn due(&mut self, t: f64) -> Vec<Event> {
        let mut out = Vec::new();
        while let Some(e) = self.events.get(self.next) {
            // Half a frame of slack: an event at 1.0 s fires on the frame at 1.0 s.
            if e.at > t + 0.5 * SCRIPT_DT {
                break;
            }
            out.push(e.clone());
            self.next += 1;
        }
        out
    }

    /// Whether every event has been played.
    pub fn finished(&self) -> bool {
        self.next >= self.events.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn events_fire_in_time_order_once() {
        let mut s = Script::parse(
            "[[event]]\nat = 1.0\nquit = true\n[[event]]\nat = 0.0\nkey = \"W\"\n[[event]]\nat = 0.5\nlook = [10.0, 0.0]\n",
        )
        .unwrap();
        assert_eq!(s.due(0.0).len(), 1);
        assert!(s.due(0.0).is_empty());
        let later = s.due(1.0);
        assert_eq!(later.len(), 2);
        assert_eq!(later[1].quit, Some(true));
        assert!(s.finished());
    }

    #[test]
    fn bad_scripts_say_which_event() {
        let e = Script::parse("[[event]]\nat = 1.0\n").err().unwrap();
        assert!(format!("{e:#}").contains("exactly one action"), "{e:#}");
        let e = Script::parse("[[event]]\nat = 0.0\nkey = \"Z9\"\n")
            .err()
            .unwrap();
        assert!(format!("{e:#}").contains("unknown key `Z9`"), "{e:#}");
    }
}
