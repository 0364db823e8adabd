//! The egui overlay: pass timings, a dated sky's readout (date, place, sun, sunrise and sunset,
//! moon), and the controls over the scene, method, quality and sky.

use crate::*;

impl ViewState {
    /// The overlay: timings and the controls. Returns the overlay's rectangle in points.
    pub(crate) fn ui(&mut self, ctx: &egui::Context, backend: &str) -> Option<egui::Rect> {
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
                // A dated sky: the debug readout of its date and place (seed 001's).
                if let Some((t, place)) = self.scene.sky.when_and_where() {
                    ui.label(format!(
                        "{t} at {:.2}, {:.2}",
                        place.latitude_deg, place.longitude_deg
                    ));
                    ui.label(stratus_astro::readout(place, t, 0.0));
                }
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
