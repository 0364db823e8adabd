//! The speed-against-accuracy chart: FLIP against GPU time per scene, the Pareto front joined
//! and named; drawn once on an SVG canvas (with text) and once on a PNG (without).

use std::{fmt::Write as _, path::Path};

use anyhow::{Context, Result};
use stratus_quality::{Results, Row};

/// A drawing surface: the chart is drawn once on each (SVG with text, PNG without).
trait Canvas {
    fn line(&mut self, a: (f64, f64), b: (f64, f64), rgb: (u8, u8, u8), width: u32);
    fn circle(&mut self, c: (f64, f64), r: f64, rgb: (u8, u8, u8), fill: bool);
    fn rect(&mut self, a: (f64, f64), b: (f64, f64), rgb: (u8, u8, u8));
    fn text(&mut self, p: (f64, f64), s: &str, size: u32, rgb: (u8, u8, u8), anchor: &str);
}

struct Svg(String);

fn hex(c: (u8, u8, u8)) -> String {
    format!("#{:02x}{:02x}{:02x}", c.0, c.1, c.2)
}

fn xml(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

impl Canvas for Svg {
    fn line(&mut self, a: (f64, f64), b: (f64, f64), rgb: (u8, u8, u8), width: u32) {
        let _ = writeln!(
            self.0,
            r#"<line x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="{}" stroke-width="{width}"/>"#,
            a.0,
            a.1,
            b.0,
            b.1,
            hex(rgb)
        );
    }
    fn circle(&mut self, c: (f64, f64), r: f64, rgb: (u8, u8, u8), fill: bool) {
        let paint = if fill {
            format!(r#"fill="{}""#, hex(rgb))
        } else {
            format!(r#"fill="none" stroke="{}""#, hex(rgb))
        };
        let _ = writeln!(
            self.0,
            r#"<circle cx="{:.1}" cy="{:.1}" r="{r:.1}" {paint}/>"#,
            c.0, c.1
        );
    }
    fn rect(&mut self, a: (f64, f64), b: (f64, f64), rgb: (u8, u8, u8)) {
        let _ = writeln!(
            self.0,
            r#"<rect x="{:.1}" y="{:.1}" width="{:.1}" height="{:.1}" fill="none" stroke="{}"/>"#,
            a.0,
            a.1,
            b.0 - a.0,
            b.1 - a.1,
            hex(rgb)
        );
    }
    fn text(&mut self, p: (f64, f64), s: &str, size: u32, rgb: (u8, u8, u8), anchor: &str) {
        let _ = writeln!(
            self.0,
            r#"<text x="{:.1}" y="{:.1}" font-family="sans-serif" font-size="{size}" fill="{}" text-anchor="{anchor}">{}</text>"#,
            p.0,
            p.1,
            hex(rgb),
            xml(s)
        );
    }
}

/// The PNG: plotters' bitmap backend, shapes only (no font is needed or looked for).
struct Png<'a>(plotters::prelude::BitMapBackend<'a>);

impl Canvas for Png<'_> {
    fn line(&mut self, a: (f64, f64), b: (f64, f64), rgb: (u8, u8, u8), width: u32) {
        use plotters::prelude::*;
        let style = RGBColor(rgb.0, rgb.1, rgb.2).stroke_width(width);
        let _ = self
            .0
            .draw_line((a.0 as i32, a.1 as i32), (b.0 as i32, b.1 as i32), &style);
    }
    fn circle(&mut self, c: (f64, f64), r: f64, rgb: (u8, u8, u8), fill: bool) {
        use plotters::prelude::*;
        let _ = self.0.draw_circle(
            (c.0 as i32, c.1 as i32),
            r.round() as u32,
            &RGBColor(rgb.0, rgb.1, rgb.2),
            fill,
        );
    }
    fn rect(&mut self, a: (f64, f64), b: (f64, f64), rgb: (u8, u8, u8)) {
        use plotters::prelude::*;
        let _ = self.0.draw_rect(
            (a.0 as i32, a.1 as i32),
            (b.0 as i32, b.1 as i32),
            &RGBColor(rgb.0, rgb.1, rgb.2),
            false,
        );
    }
    fn text(&mut self, _: (f64, f64), _: &str, _: u32, _: (u8, u8, u8), _: &str) {}
}

const PANEL_W: f64 = 460.0;
const PANEL_H: f64 = 380.0;
const MARGIN: (f64, f64, f64, f64) = (56.0, 24.0, 30.0, 44.0); // left, right, top, bottom

/// FLIP (log) against GPU time (log) per scene, one panel each: every configuration a grey
/// dot, the preset a blue ring, the Pareto front red and joined, each front point numbered
/// and named (SVG). Methods (temporal upsampling, cheap marching) are green and labelled: a
/// dot for their error on a still camera, joined to a ring for their error in motion (against
/// the full march of each frame). An orange ring joined to the preset is the preset with the
/// octave constants from before the multiple-scattering fit.
fn draw(canvas: &mut dyn Canvas, results: &Results) {
    let mut scenes: Vec<&str> = results.rows.iter().map(|r| r.scene.as_str()).collect();
    scenes.dedup();
    let grey = (150, 150, 150);
    let black = (0, 0, 0);
    let red = (200, 30, 30);
    let blue = (30, 80, 200);
    let green = (20, 140, 60);
    let orange = (225, 120, 0);
    let purple = (130, 50, 170);
    for (k, scene) in scenes.iter().enumerate() {
        let ox = k as f64 * PANEL_W;
        let rows: Vec<&Row> = results.rows.iter().filter(|r| r.scene == *scene).collect();
        let lo = |f: fn(&Row) -> f64| {
            rows.iter()
                .map(|r| f(r).max(1e-5))
                .fold(f64::INFINITY, f64::min)
                .log10()
        };
        let hi = |f: fn(&Row) -> f64| {
            rows.iter()
                .map(|r| f(r).max(1e-5))
                .fold(0.0, f64::max)
                .log10()
        };
        let (x0, x1) = (lo(|r| r.gpu_ms) - 0.05, hi(|r| r.gpu_ms) + 0.05);
        // A motion error of 0 (a method that changes no sample) is labelled, not plotted.
        let motion = |r: &Row| r.motion_flip.filter(|m| *m > 0.0);
        let flip_or_motion = |r: &Row| motion(r).map_or(r.flip, |m| m.max(r.flip));
        let flip_or_motion_lo = |r: &Row| motion(r).map_or(r.flip, |m| m.min(r.flip));
        let y0 = rows
            .iter()
            .map(|r| flip_or_motion_lo(r).max(1e-5))
            .fold(f64::INFINITY, f64::min)
            .log10()
            - 0.05;
        let y1 = rows
            .iter()
            .map(|r| flip_or_motion(r).max(1e-5))
            .fold(0.0, f64::max)
            .log10()
            + 0.05;
        let (l, r_, t, b) = MARGIN;
        let px = |v: f64| ox + l + (v.max(1e-5).log10() - x0) / (x1 - x0) * (PANEL_W - l - r_);
        let py = |v: f64| PANEL_H - b - (v.max(1e-5).log10() - y0) / (y1 - y0) * (PANEL_H - t - b);
        canvas.rect((ox + l, t), (ox + PANEL_W - r_, PANEL_H - b), black);
        canvas.text((ox + PANEL_W / 2.0, 18.0), scene, 14, black, "middle");
        canvas.text(
            (ox + PANEL_W / 2.0, PANEL_H - 8.0),
            "GPU time, ms (log)",
            11,
            black,
            "middle",
        );
        canvas.text((ox + 4.0, t - 8.0), "FLIP (log)", 11, black, "start");
        // Decade and half-decade ticks.
        for e in -5..4 {
            for m in [1.0, 2.0, 5.0] {
                let v = m * 10f64.powi(e);
                let lv = v.log10();
                if lv >= x0 && lv <= x1 {
                    let x = px(v);
                    canvas.line((x, PANEL_H - b), (x, PANEL_H - b + 4.0), black, 1);
                    canvas.text(
                        (x, PANEL_H - b + 15.0),
                        &format!("{v}"),
                        10,
                        black,
                        "middle",
                    );
                }
                if lv >= y0 && lv <= y1 {
                    let y = py(v);
                    canvas.line((ox + l - 4.0, y), (ox + l, y), black, 1);
                    canvas.text((ox + l - 6.0, y + 3.0), &format!("{v}"), 10, black, "end");
                }
            }
        }
        // FLIP 0.05 guide.
        if (0.05f64).log10() >= y0 && (0.05f64).log10() <= y1 {
            let y = py(0.05);
            canvas.line((ox + l, y), (ox + PANEL_W - r_, y), (200, 200, 120), 1);
        }
        for r in &rows {
            canvas.circle((px(r.gpu_ms), py(r.flip)), 2.5, grey, true);
            if r.preset {
                canvas.circle((px(r.gpu_ms), py(r.flip)), 6.0, blue, false);
            }
        }
        // Each preset before the multiple-scattering fit, joined to the preset (after).
        if let Some(now) = rows.iter().find(|r| r.preset) {
            for r in rows.iter().filter(|r| r.config.prefit) {
                let before = (px(r.gpu_ms), py(r.flip));
                canvas.line(before, (px(now.gpu_ms), py(now.flip)), orange, 1);
                canvas.circle(before, 5.0, orange, false);
                canvas.text(
                    (before.0 + 7.0, before.1 + 3.0),
                    &format!("preset before the fit: FLIP {:.3}", r.flip),
                    9,
                    orange,
                    "start",
                );
            }
        }
        for r in rows.iter().filter(|r| r.config.is_method()) {
            let still = (px(r.gpu_ms), py(r.flip));
            canvas.circle(still, 3.5, green, true);
            let label = method_label(&r.config);
            if r.motion_flip == Some(0.0) {
                canvas.text(
                    (still.0 + 6.0, still.1 + 13.0),
                    "(exact in motion)",
                    9,
                    green,
                    "start",
                );
            }
            if let Some(m) = motion(r) {
                let moving = (px(r.gpu_ms), py(m));
                canvas.line(still, moving, green, 1);
                canvas.circle(moving, 4.0, green, false);
                canvas.text(
                    (moving.0 + 6.0, moving.1 + 3.0),
                    &format!("{label} moving"),
                    9,
                    green,
                    "start",
                );
            }
            canvas.text((still.0 + 6.0, still.1 + 3.0), &label, 9, green, "start");
        }
        // The baselines (seed methods measured against the same truth), named.
        for r in rows
            .iter()
            .filter(|r| r.config.method != stratus_scene::Method::Volumetric)
        {
            let at = (px(r.gpu_ms), py(r.flip));
            canvas.circle(at, 4.0, purple, true);
            canvas.text(
                (at.0 + 6.0, at.1 + 3.0),
                &format!("{}: FLIP {:.3}", r.config.method.name(), r.flip),
                9,
                purple,
                "start",
            );
        }
        let mut front: Vec<&&Row> = rows.iter().filter(|r| r.pareto).collect();
        front.sort_by(|a, b| a.gpu_ms.total_cmp(&b.gpu_ms));
        for w in front.windows(2) {
            canvas.line(
                (px(w[0].gpu_ms), py(w[0].flip)),
                (px(w[1].gpu_ms), py(w[1].flip)),
                red,
                2,
            );
        }
        for (i, r) in front.iter().enumerate() {
            let c = (px(r.gpu_ms), py(r.flip));
            canvas.circle(c, 4.0, red, true);
            canvas.text(
                (c.0 + 6.0, c.1 - 5.0),
                &format!("{}", i + 1),
                10,
                red,
                "start",
            );
            canvas.text(
                (ox + l + 6.0, t + 14.0 + 12.0 * i as f64),
                &format!("{} {}", i + 1, r.name),
                9,
                red,
                "start",
            );
        }
    }
}

/// A method's short label: `1/16`, `1/4 chk`, `dyn`, `skip`.
fn method_label(c: &stratus_quality::Config) -> String {
    let mut parts = Vec::new();
    if c.temporal != stratus_scene::Temporal::Off {
        parts.push(c.temporal.name().to_string());
    }
    for (on, name) in [
        (c.checkerboard, "chk"),
        (c.dynamic_step, "dyn"),
        (c.empty_space_skip, "skip"),
    ] {
        if on {
            parts.push(name.to_string());
        }
    }
    parts.join(" ")
}

pub(super) fn chart(out: &Path, results: &Results) -> Result<()> {
    let mut n: Vec<&str> = results.rows.iter().map(|r| r.scene.as_str()).collect();
    n.dedup();
    let (w, h) = ((PANEL_W * n.len().max(1) as f64) as u32, PANEL_H as u32);
    let mut svg = Svg(format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}">
<title>Stratus: FLIP against GPU time ({} at {}x{}); red = Pareto front, blue ring = preset settings, orange ring = preset before the multiple-scattering fit, green = methods (dot: still camera; ring: in motion, against the full march of each frame), purple = baselines (basic marcher, sprites)</title>
<rect width="100%" height="100%" fill="white"/>
"#,
        xml(&results.device),
        results.size[0],
        results.size[1]
    ));
    draw(&mut svg, results);
    svg.0.push_str("</svg>\n");
    let svg_path = out.join("chart.svg");
    stratus_compare::write_file_atomically(&svg_path, svg.0.as_bytes())
        .with_context(|| format!("writing {}", svg_path.display()))?;

    let png_path = out.join("chart.png");
    stratus_compare::write_atomically(&png_path, |tmp| -> Result<()> {
        use plotters::prelude::*;
        let mut backend = BitMapBackend::new(tmp, (w, h));
        backend
            .draw_rect((0, 0), (w as i32, h as i32), &WHITE, true)
            .map_err(|e| anyhow::anyhow!("drawing {}: {e:?}", png_path.display()))?;
        let mut png = Png(backend);
        draw(&mut png, results);
        png.0
            .present()
            .map_err(|e| anyhow::anyhow!("writing {}: {e:?}", png_path.display()))?;
        Ok(())
    })
    .map_err(|e| anyhow::anyhow!("{e}"))
}
