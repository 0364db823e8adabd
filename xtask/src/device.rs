//! `cargo xtask device-bundle`: what the conformance suite needs on a machine with a real GPU
//! and no cargo (the `device` machine), packed into `.device/bundle.tar.gz`: the suite's test
//! binary, the `stratus` CLI, glslang and SPIRV-Tools (the ash-glsl and ash-hlsl paths), and
//! the Khronos validation layer (every GPU path runs with it). `tests/device/run.sh` unpacks
//! it on that machine and runs the suite against the checkout there (`INSTA_WORKSPACE_ROOT`).

use std::{
    path::{Path, PathBuf},
    process::Command,
};

use anyhow::{Context, Result, bail};

/// The programs the suite runs (ash-glsl, ash-hlsl and `spirv-val`), from the PATH.
const TOOLS: [&str; 3] = ["glslangValidator", "spirv-opt", "spirv-val"];

/// Where Debian's `vulkan-validationlayers` puts the layer and its manifest.
const LAYER_LIBRARY: &str = "/usr/lib/x86_64-linux-gnu/libVkLayer_khronos_validation.so";
const LAYER_MANIFEST: &str = "/usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json";

/// The test binary cargo built for `--test conformance` (from `--message-format=json`).
fn conformance_binary(root: &Path) -> Result<PathBuf> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let out = Command::new(&cargo)
        .current_dir(root)
        .args([
            "test",
            "-p",
            "stratus-tests",
            "--test",
            "conformance",
            "--no-run",
            "--message-format=json",
        ])
        .stderr(std::process::Stdio::inherit())
        .output()
        .context("running cargo test --no-run")?;
    if !out.status.success() {
        bail!("building the conformance suite failed ({})", out.status);
    }
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .filter_map(|l| serde_json::from_str::<serde_json::Value>(l).ok())
        .filter(|v| v["target"]["name"] == "conformance")
        .find_map(|v| v["executable"].as_str().map(PathBuf::from))
        .context("cargo named no executable for the conformance test")
}

/// Finds `tool` on the PATH.
fn which(tool: &str) -> Result<PathBuf> {
    std::env::var_os("PATH")
        .iter()
        .flat_map(std::env::split_paths)
        .map(|d| d.join(tool))
        .find(|p| p.is_file())
        .with_context(|| {
            format!("{tool} is not on the PATH (`cargo xtask ci` installs it: glslang-tools, spirv-tools)")
        })
}

/// Copies `from` to `to`, without its debug information where `strip` is installed (the
/// suite's test binary is about 250 MB with it, 13 MB without; the device machine takes 64 MiB
/// in all).
fn copy_stripped(from: &Path, to: &Path) -> Result<()> {
    let stripped = Command::new("strip")
        .arg("--strip-debug")
        .arg("-o")
        .arg(to)
        .arg(from)
        .status()
        .is_ok_and(|s| s.success());
    if !stripped {
        std::fs::copy(from, to)
            .with_context(|| format!("copying {} to {}", from.display(), to.display()))?;
    }
    Ok(())
}

/// `cargo xtask device-bundle`.
pub fn bundle(root: &Path) -> Result<()> {
    let suite = conformance_binary(root)?;
    crate::cargo(root, &["build", "--release", "-p", "stratus-cli"])?;
    let stage = crate::target_dir(root).join("device-bundle");
    let _ = std::fs::remove_dir_all(&stage);
    let (bin, layers) = (stage.join("bin"), stage.join("layers"));
    for d in [&bin, &layers] {
        std::fs::create_dir_all(d).with_context(|| format!("creating {}", d.display()))?;
    }
    copy_stripped(&suite, &bin.join("conformance"))?;
    copy_stripped(
        &crate::target_dir(root).join("release/stratus"),
        &bin.join("stratus"),
    )?;
    for tool in TOOLS {
        copy_stripped(&which(tool)?, &bin.join(tool))?;
    }
    if !Path::new(LAYER_LIBRARY).is_file() {
        bail!("{LAYER_LIBRARY} is missing: `apt-get install vulkan-validationlayers`");
    }
    std::fs::copy(
        LAYER_LIBRARY,
        layers.join("libVkLayer_khronos_validation.so"),
    )
    .context("copying the validation layer")?;
    // The manifest names the library by file name, which the loader looks up on the system's
    // library path; a relative path is taken relative to the manifest instead.
    let manifest = std::fs::read_to_string(LAYER_MANIFEST)
        .with_context(|| format!("reading {LAYER_MANIFEST}"))?;
    let manifest = manifest.replace(
        "\"libVkLayer_khronos_validation.so\"",
        "\"./libVkLayer_khronos_validation.so\"",
    );
    if !manifest.contains("./libVkLayer_khronos_validation.so") {
        bail!("{LAYER_MANIFEST} does not name libVkLayer_khronos_validation.so as expected");
    }
    std::fs::write(layers.join("VkLayer_khronos_validation.json"), manifest)?;

    let out_dir = root.join(".device");
    std::fs::create_dir_all(&out_dir)?;
    let tarball = out_dir.join("bundle.tar.gz");
    crate::run(
        Command::new("tar")
            .arg("czf")
            .arg(&tarball)
            .arg("-C")
            .arg(&stage)
            .args(["bin", "layers"]),
    )?;
    let size = std::fs::metadata(&tarball)?.len();
    println!(
        "wrote {} ({:.1} MiB): the conformance suite, stratus, {} and the validation layer",
        tarball.display(),
        size as f64 / 1048576.0,
        TOOLS.join(", ")
    );
    println!(
        "on the device machine, from the checkout's root (carry `.device`, and `.gl` for the Vulkan loader):\n  bash tests/device/run.sh"
    );
    Ok(())
}

/// Where the peer harness lives, beside the checkout (it is not part of the repository).
const PEER_BENCH: &str = "../shared/peer-bench";

/// The peer's two WGSL files the harness needs (its README names them and their blob ids).
const PEER_FILES: [&str; 2] = ["clouds_compute.wgsl", "common.wgsl"];

/// `cargo xtask device-bench`: `stratus` (whose `gpu-bench` measures), and with `peer_wgsl`
/// the peer harness and the peer's WGSL, packed into `.device/bench.tar.gz` (ignored by git:
/// the peer's code is never committed).
pub fn bench(root: &Path, peer_wgsl: Option<&Path>) -> Result<()> {
    crate::cargo(root, &["build", "--release", "-p", "stratus-cli"])?;
    let stage = crate::target_dir(root).join("device-bench");
    let _ = std::fs::remove_dir_all(&stage);
    let bin = stage.join("bin");
    std::fs::create_dir_all(&bin).with_context(|| format!("creating {}", bin.display()))?;
    copy_stripped(
        &crate::target_dir(root).join("release/stratus"),
        &bin.join("stratus"),
    )?;
    let mut parts = vec!["bin"];
    let peer = match peer_wgsl {
        Some(dir) => {
            let harness = root.join(PEER_BENCH);
            if !harness.join("Cargo.toml").is_file() {
                bail!(
                    "--peer-wgsl: the peer harness is not at {} (it lives beside the checkout, in ../shared)",
                    harness.display()
                );
            }
            let wgsl = stage.join("peer-wgsl");
            std::fs::create_dir_all(&wgsl)?;
            for f in PEER_FILES {
                let from = dir.join(f);
                std::fs::copy(&from, wgsl.join(f)).with_context(|| {
                    format!(
                        "--peer-wgsl: {} (extract it as ../shared/peer-bench/README.md says)",
                        from.display()
                    )
                })?;
            }
            let manifest = harness.join("Cargo.toml");
            let target = crate::target_dir(root).join("peer-bench");
            crate::run(
                Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()))
                    .args(["build", "--release", "--manifest-path"])
                    .arg(&manifest)
                    .arg("--target-dir")
                    .arg(&target),
            )?;
            copy_stripped(&target.join("release/peer-bench"), &bin.join("peer-bench"))?;
            parts.push("peer-wgsl");
            "the peer harness and the peer's WGSL"
        }
        None => "no peer (give --peer-wgsl DIR to compare with it)",
    };
    let out_dir = root.join(".device");
    std::fs::create_dir_all(&out_dir)?;
    let tarball = out_dir.join("bench.tar.gz");
    crate::run(
        Command::new("tar")
            .arg("czf")
            .arg(&tarball)
            .arg("-C")
            .arg(&stage)
            .args(&parts),
    )?;
    let size = std::fs::metadata(&tarball)?.len();
    println!(
        "wrote {} ({:.1} MiB): stratus; {peer}",
        tarball.display(),
        size as f64 / 1048576.0,
    );
    println!(
        "on the device machine, from the checkout's root (carry `.device`, and `.gl` for the Vulkan loader):\n  bash tests/device/bench.sh            # every preset, wgpu and ash, temporal off, 1/4, 1/16, 1080p and 4K\n  bash tests/device/bench.sh --presets cumulus-noon --frames 60   # options go to stratus gpu-bench"
    );
    Ok(())
}
