//! `cargo xtask view-test`: the viewer under Xvfb, driven by a script, on wgpu and on ash; on
//! each the window must present frames and the screenshots must differ, have contrast and show
//! the overlay's text, and the two backends' clouds must be the same pixels.

use std::{
    path::{Path, PathBuf},
    process::Command,
    time::Instant,
};

use anyhow::{Context, Result, bail};

use crate::{cargo, target_dir};

/// The viewer's screenshots must differ by at least this mean FLIP (the camera moved, turned
/// and the sun went low: measured 0.2).
pub(crate) const VIEW_MIN_DIFFERENCE: f64 = 0.02;
/// Neither screenshot is flat: the standard deviation of its luminance (0-1) outside the
/// overlay is at least this (a sky with clouds and ground: measured about 0.2).
pub(crate) const VIEW_MIN_CONTRAST: f64 = 0.03;
/// The overlay's text shows: glyph edges (a light pixel next to the overlay's dark fill)
/// inside the overlay's rectangle, at least this many (measured over 2000 at 480x270).
pub(crate) const VIEW_MIN_TEXT_EDGES: usize = 300;

/// Frames the window must present between the two screenshots: the script advances 24 frames
/// from the first (0.1 s) to the second (0.9 s); under Xvfb every one presents (measured 24), and
/// half allows a surface reconfigured for a frame or two.
pub(crate) const VIEW_MIN_PRESENTED_BETWEEN: u64 = 12;

pub(crate) fn view_test(root: &Path) -> Result<()> {
    let t = Instant::now();
    let target = target_dir(root);
    let out = target.join("view-test");
    let _ = std::fs::remove_dir_all(&out);
    cargo(root, &["build", "-q", "-p", "stratus-cli"])?;
    let exe = target.join("debug").join("stratus");
    let mut problems = Vec::new();
    // Each backend runs the script; their clouds must be the same pixels.
    for backend in ["wgpu", "ash"] {
        let dir = out.join(backend);
        let found = run_script(root, &exe, backend, &dir)?;
        problems.extend(found.into_iter().map(|p| format!("{backend}: {p}")));
    }
    for name in ["first", "second"] {
        let load = |backend: &str| {
            stratus_compare::Image::load(&out.join(backend).join(format!("{name}.clouds.png")))
        };
        let (w, a) = (load("wgpu")?, load("ash")?);
        let d = stratus_compare::compare(&w, &a, &stratus_compare::CompareOptions::default())?;
        println!(
            "view-test: {name}: wgpu and ash clouds differ by FLIP mean {:.4} (max {:.4})",
            d.flip.mean, d.flip.max
        );
        if w.rgba != a.rgba {
            problems.push(format!(
                "{name}: the clouds on wgpu and ash are not the same pixels (FLIP mean {:.4})",
                d.flip.mean
            ));
        }
    }
    println!(
        "view-test: {:.0?}; screenshots in {}",
        t.elapsed(),
        out.display()
    );
    if !problems.is_empty() {
        bail!("view-test: {}", problems.join("; "));
    }
    Ok(())
}

/// Runs the viewer's script on `backend` under Xvfb into `out`, and returns what is wrong with
/// its screenshots.
fn run_script(root: &Path, exe: &Path, backend: &str, out: &Path) -> Result<Vec<String>> {
    let (xvfb, display) = start_xvfb()?;
    let script = root.join("tests/view/script.toml");
    let result = Command::new(exe)
        .args(["view", "--backend", backend, "--script"])
        .arg(&script)
        .args(["--size", "480x270", "--vsync", "off", "--out-dir"])
        .arg(out)
        .env("DISPLAY", &display)
        .env("STRATUS_VALIDATION", "1")
        .env(
            "XDG_RUNTIME_DIR",
            std::env::var_os("XDG_RUNTIME_DIR").unwrap_or_else(|| std::env::temp_dir().into()),
        )
        .status();
    stop_xvfb(xvfb);
    let status = result.context("running stratus view")?;
    if !status.success() {
        bail!("stratus view --backend {backend} --script failed ({status})");
    }
    let shot = |name: &str| -> Result<(stratus_compare::Image, [f64; 4], u64)> {
        let image = stratus_compare::Image::load(&out.join(format!("{name}.png")))?;
        let info: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join(format!("{name}.json")))?)?;
        let r = info["overlay_px"]
            .as_array()
            .with_context(|| format!("{name}.json: no overlay rectangle (overlay hidden?)"))?;
        let r: Vec<f64> = r.iter().filter_map(serde_json::Value::as_f64).collect();
        let presented = info["presented_frames"]
            .as_u64()
            .with_context(|| format!("{name}.json: no presented_frames"))?;
        Ok((image, [r[0], r[1], r[2], r[3]], presented))
    };
    let path = std::fs::read_to_string(out.join("path-001.toml"))
        .context("the recorded camera path (path-001.toml) was not written")?;
    let keyframes = path.matches("[[animation.keyframes]]").count();
    println!("view-test ({backend}): the recorded camera path has {keyframes} keyframes");
    let (first, r1, p1) = shot("first")?;
    let (second, r2, p2) = shot("second")?;
    let mut problems = Vec::new();
    let diff =
        stratus_compare::compare(&first, &second, &stratus_compare::CompareOptions::default())?;
    println!(
        "view-test ({backend}): the screenshots differ by FLIP mean {:.3}; {p1} frames presented by the first, {p2} by the second",
        diff.flip.mean
    );
    if keyframes < 2 {
        problems.push(format!("the recorded path has {keyframes} keyframes"));
    }
    if p1 == 0 || p2 < p1 + VIEW_MIN_PRESENTED_BETWEEN {
        problems.push(format!(
            "the window presented {p1} frames by the first screenshot and {p2} by the second (at least one, then {VIEW_MIN_PRESENTED_BETWEEN} more)"
        ));
    }
    if diff.flip.mean < VIEW_MIN_DIFFERENCE {
        problems.push(format!(
            "the screenshots barely differ (FLIP mean {:.4} < {VIEW_MIN_DIFFERENCE})",
            diff.flip.mean
        ));
    }
    for (name, image, rect) in [("first", &first, r1), ("second", &second, r2)] {
        let (contrast, edges) = overlay_stats(image, rect);
        println!(
            "view-test ({backend}): {name}: luminance std-dev {contrast:.3} outside the overlay, {edges} text edges in it"
        );
        if contrast < VIEW_MIN_CONTRAST {
            problems.push(format!("{name} is flat (luminance std-dev {contrast:.4})"));
        }
        if edges < VIEW_MIN_TEXT_EDGES {
            problems.push(format!(
                "{name}: no overlay text ({edges} glyph edges < {VIEW_MIN_TEXT_EDGES})"
            ));
        }
    }
    Ok(problems)
}

/// The luminance standard deviation outside the overlay's rectangle `[x0, y0, x1, y1]`, and
/// the glyph edges inside it: light pixels (luminance > 0.45) next to dark ones (< 0.12).
pub(crate) fn overlay_stats(image: &stratus_compare::Image, rect: [f64; 4]) -> (f64, usize) {
    let (w, h) = (image.width as usize, image.height as usize);
    let lum = |x: usize, y: usize| {
        let p = &image.rgba[4 * (y * w + x)..4 * (y * w + x) + 3];
        0.2126 * f64::from(p[0]) + 0.7152 * f64::from(p[1]) + 0.0722 * f64::from(p[2])
    };
    let inside = |x: usize, y: usize| {
        (x as f64) >= rect[0]
            && (x as f64) < rect[2]
            && (y as f64) >= rect[1]
            && (y as f64) < rect[3]
    };
    let (mut n, mut sum, mut sum2, mut edges) = (0.0f64, 0.0f64, 0.0f64, 0usize);
    for y in 0..h {
        for x in 0..w {
            let l = lum(x, y);
            if !inside(x, y) {
                n += 1.0;
                sum += l;
                sum2 += l * l;
            } else if l > 0.45
                && x + 1 < w
                && y + 1 < h
                && (lum(x + 1, y) < 0.12 || lum(x, y + 1) < 0.12)
            {
                edges += 1;
            }
        }
    }
    let mean = sum / n.max(1.0);
    ((sum2 / n.max(1.0) - mean * mean).max(0.0).sqrt(), edges)
}

/// Whether display `:n` is taken: by a lock file naming a running process, or by a socket
/// without a lock. A lock whose process is gone (a server that was killed, which leaves its
/// lock and socket behind) is stale: both are removed and the display is free again.
pub(crate) fn display_taken(n: u32) -> bool {
    let socket = PathBuf::from(format!("/tmp/.X11-unix/X{n}"));
    let lock = PathBuf::from(format!("/tmp/.X{n}-lock"));
    match std::fs::read_to_string(&lock) {
        Ok(text) => {
            let alive = match text.trim().parse::<u32>() {
                Ok(pid) => Path::new(&format!("/proc/{pid}")).exists(),
                // Not a lock we can read: leave it alone.
                Err(_) => true,
            };
            if alive {
                return true;
            }
            let _ = std::fs::remove_file(&lock);
            let _ = std::fs::remove_file(&socket);
            lock.exists() || socket.exists()
        }
        Err(_) => lock.exists() || socket.exists(),
    }
}

/// Stops Xvfb with SIGTERM, so that it removes its lock file and socket (SIGKILL leaves them,
/// and twenty runs used up every display this test tries), or kills it after 5 s.
pub(crate) fn stop_xvfb(mut xvfb: std::process::Child) {
    let _ = Command::new("kill")
        .args(["-TERM", &xvfb.id().to_string()])
        .status();
    for _ in 0..50 {
        if let Ok(Some(_)) = xvfb.try_wait() {
            return;
        }
        std::thread::sleep(std::time::Duration::from_millis(100));
    }
    let _ = xvfb.kill();
    let _ = xvfb.wait();
}

/// Starts Xvfb on the first free display from :90 and waits for its socket.
pub(crate) fn start_xvfb() -> Result<(std::process::Child, String)> {
    for n in 90..110 {
        let socket = PathBuf::from(format!("/tmp/.X11-unix/X{n}"));
        if display_taken(n) {
            continue;
        }
        let display = format!(":{n}");
        let mut child = Command::new("Xvfb")
            .args([
                display.as_str(),
                "-screen",
                "0",
                "1024x768x24",
                "-nolisten",
                "tcp",
            ])
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .context("starting Xvfb (install it: apt-get install xvfb)")?;
        for _ in 0..100 {
            if socket.exists() {
                return Ok((child, display));
            }
            if let Ok(Some(status)) = child.try_wait() {
                bail!("Xvfb {display} exited at start ({status})");
            }
            std::thread::sleep(std::time::Duration::from_millis(100));
        }
        stop_xvfb(child);
        bail!("Xvfb {display} did not open its socket in 10 s");
    }
    bail!("no free X display between :90 and :109")
}
