//! The engine kit and its browser consumer: `cargo xtask export`, `cargo xtask web-test`
//! (the kit's goldens rendered by `web/stratus-kit.js` in headless Chromium, against the
//! goldens by FLIP) and `cargo xtask web` (the interactive page).

use std::{path::Path, process::Command, time::Instant};

use anyhow::{Context, Result, bail};

use crate::{cargo, target_dir};

/// `cargo xtask export --out DIR`: `stratus export-kit` from this checkout.
pub(crate) fn export(root: &Path, out: &Path) -> Result<()> {
    let out = if out.is_absolute() {
        out.to_path_buf()
    } else {
        std::env::current_dir()?.join(out)
    };
    let out = out.to_string_lossy().into_owned();
    cargo(
        root,
        &[
            "run",
            "-q",
            "-p",
            "stratus-cli",
            "--",
            "export-kit",
            "--out",
            &out,
        ],
    )
}

/// Runs `node` with `args` in `web/`, failing with what to install when it cannot start.
pub(crate) fn node(root: &Path, args: &[&str]) -> Result<()> {
    let status = Command::new("node")
        .args(args)
        .current_dir(root.join("web"))
        .status()
        .context("running node (install Node.js 20 or later)")?;
    if !status.success() {
        bail!("`node {}` failed ({status})", args.join(" "));
    }
    Ok(())
}

/// The page's npm dependencies (playwright-core, pinned by web/package-lock.json).
pub(crate) fn npm_ci(root: &Path) -> Result<()> {
    if root.join("web/node_modules/playwright-core").exists() {
        return Ok(());
    }
    let status = Command::new("npm")
        .args(["ci", "--no-audit", "--no-fund"])
        .current_dir(root.join("web"))
        .status()
        .context("running npm (install Node.js 20 or later, with npm)")?;
    if !status.success() {
        bail!("`npm ci` in web/ failed ({status})");
    }
    Ok(())
}

/// FLIP of the browser's image of each golden against the kit's golden image (Tint and
/// SwiftShader against naga and lavapipe). Measured on the six presets: mean 2.10e-3 to
/// 9.61e-3, p99 up to 5.70e-2 (inside-layer): the CPU reference's pattern and size (both
/// filter textures at full precision where lavapipe quantises the weights). The same bounds as
/// the conformance suite's for the CPU and for this path (`web-tint`).
pub(crate) const WEB_TINT_FLIP_MEAN: f64 = 2e-2;
/// See [`WEB_TINT_FLIP_MEAN`].
pub(crate) const WEB_TINT_FLIP_P99: f64 = 8e-2;

/// `cargo xtask web-test`: returns each golden's FLIP mean.
pub(crate) fn web_test(root: &Path) -> Result<Vec<(String, f64)>> {
    let t = Instant::now();
    npm_ci(root)?;
    let target = target_dir(root);
    let kit = target.join("kit");
    let out = target.join("web-test");
    let _ = std::fs::remove_dir_all(&out);
    export(root, &kit)?;
    let (kit_s, out_s) = (
        kit.to_string_lossy().into_owned(),
        out.to_string_lossy().into_owned(),
    );
    node(root, &["test/run.mjs", "--kit", &kit_s, "--out", &out_s])?;
    let index: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(kit.join("kit.json"))?)?;
    let results: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("results.json"))?)?;
    let goldens = index["goldens"]
        .as_array()
        .context("kit.json: no goldens")?;
    let mut flips = Vec::new();
    let mut problems = Vec::new();
    println!("web-tint ({}):", results["adapter"]);
    // The bounds were measured on SwiftShader, which the browser is told to use: any other
    // adapter (a real GPU, or none reporting itself) is not the path these bounds hold.
    let architecture = results["adapter"]["architecture"].as_str().unwrap_or("");
    if architecture != "swiftshader" {
        bail!(
            "web-test: the browser's WebGPU adapter is {} (from {}), not SwiftShader, which \
             `--use-webgpu-adapter=swiftshader` asks for and the web-tint bounds were measured on",
            results["adapter"],
            out.join("results.json").display()
        );
    }
    for g in goldens {
        let name = g["name"].as_str().context("a golden without a name")?;
        let golden = stratus_compare::Image::load(&kit.join(g["image"].as_str().unwrap_or("")))?;
        let web = stratus_compare::Image::load(&out.join(format!("{name}.png")))?;
        let r =
            stratus_compare::compare(&golden, &web, &stratus_compare::CompareOptions::default())?;
        println!(
            "  {name:24} FLIP mean {:.2e}  p99 {:.2e}  max {:.3}",
            r.flip.mean, r.flip.p99, r.flip.max
        );
        if !(r.flip.mean <= WEB_TINT_FLIP_MEAN && r.flip.p99 <= WEB_TINT_FLIP_P99) {
            problems.push(format!(
                "{name}: FLIP mean {:.2e} (bound {WEB_TINT_FLIP_MEAN:.0e}), p99 {:.2e} (bound {WEB_TINT_FLIP_P99:.0e})",
                r.flip.mean, r.flip.p99
            ));
        }
        flips.push((name.to_string(), r.flip.mean));
    }
    let summary = serde_json::json!({
        "adapter": results["adapter"],
        "bound_flip_mean": WEB_TINT_FLIP_MEAN,
        "goldens": flips.iter().map(|(n, f)| serde_json::json!({"name": n, "flip_mean": f})).collect::<Vec<_>>(),
        "problems": problems,
    });
    std::fs::write(
        target.join("web-tint.json"),
        serde_json::to_string_pretty(&summary)? + "\n",
    )?;
    println!(
        "web-test: {} goldens in {:.0?}; results in {}",
        flips.len(),
        t.elapsed(),
        target.join("web-tint.json").display()
    );
    if !problems.is_empty() {
        bail!("web-tint: {}", problems.join("; "));
    }
    Ok(flips)
}

/// `cargo xtask web`: a fresh kit under target/kit, and the page served with it.
pub(crate) fn web(root: &Path, port: u16) -> Result<()> {
    let kit = target_dir(root).join("kit");
    export(root, &kit)?;
    node(
        root,
        &[
            "test/server.mjs",
            "--kit",
            &kit.to_string_lossy(),
            "--port",
            &port.to_string(),
        ],
    )
}
