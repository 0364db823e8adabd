//! `cargo xtask ci` (every check CI runs, after installing the system packages that are
//! missing) and `cargo xtask conformance` (the conformance suite alone).

use std::{
    path::{Path, PathBuf},
    process::Command,
    time::Instant,
};

use anyhow::{Context, Result, bail};

use crate::{
    cargo, fuzz::fuzz, shaders::build_shaders, shaders::validate, step, view::view_test,
    web::web_test,
};

/// System packages the project needs, and why (also listed in the README).
pub(crate) const APT_PACKAGES: &[&str] = &[
    "mesa-vulkan-drivers",
    "libvulkan1",
    "vulkan-tools",
    "vulkan-validationlayers",
    "spirv-tools",
    "glslang-tools",
    "spirv-cross",
    "libegl1",
    "libgl1-mesa-dri",
    "ffmpeg",
    "chromium",
    // The viewer's test: a virtual X server, and the X libraries winit loads.
    "xvfb",
    "libx11-6",
    "libxcursor1",
    "libxrandr2",
    "libxi6",
    "libxkbcommon-x11-0",
];

pub(crate) fn missing_tools() -> Vec<String> {
    let mut missing = Vec::new();
    for tool in [
        "spirv-val",
        "glslangValidator",
        "vulkaninfo",
        "ffmpeg",
        "chromium",
        "Xvfb",
    ] {
        // ffmpeg takes -version, the others --version; both only need to start.
        if Command::new(tool).arg("--version").output().is_err() {
            missing.push(format!("`{tool}`"));
        }
    }
    let icd_dirs = ["/usr/share/vulkan/icd.d", "/etc/vulkan/icd.d"];
    let has_lavapipe = icd_dirs.iter().any(|d| {
        std::fs::read_dir(d).is_ok_and(|rd| {
            rd.flatten()
                .any(|e| e.file_name().to_string_lossy().starts_with("lvp_icd"))
        })
    });
    if !has_lavapipe {
        missing.push("a Vulkan ICD (lavapipe)".into());
    }
    if !Path::new("/usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json").exists() {
        missing.push("the Vulkan validation layer".into());
    }
    if !Path::new("/usr/lib/x86_64-linux-gnu/libEGL.so.1").exists()
        && !Path::new("/usr/lib/aarch64-linux-gnu/libEGL.so.1").exists()
    {
        missing.push("libEGL (for wgpu's GL backend)".into());
    }
    missing
}

pub(crate) fn ensure_tools() -> Result<()> {
    let missing = missing_tools();
    if missing.is_empty() {
        println!("system tools: all present");
        return Ok(());
    }
    let install = format!(
        "apt-get update && apt-get install -y --no-install-recommends {}",
        APT_PACKAGES.join(" ")
    );
    println!("system tools missing: {}", missing.join(", "));
    let is_root = Command::new("id")
        .arg("-u")
        .output()
        .is_ok_and(|o| o.stdout.starts_with(b"0"));
    let sudo = !is_root
        && Command::new("sudo")
            .args(["-n", "true"])
            .output()
            .is_ok_and(|o| o.status.success());
    if !is_root && !sudo {
        bail!("cannot install system packages without root; run:\n    sudo sh -c '{install}'");
    }
    println!("installing: {}", APT_PACKAGES.join(" "));
    let mut cmd = if sudo {
        let mut c = Command::new("sudo");
        c.args(["sh", "-c", &install]);
        c
    } else {
        let mut c = Command::new("sh");
        c.args(["-c", &install]);
        c
    };
    cmd.env("DEBIAN_FRONTEND", "noninteractive");
    let status = cmd.status().context("running apt-get")?;
    if !status.success() {
        bail!("apt-get failed ({status}); run it by hand:\n    {install}");
    }
    let still = missing_tools();
    if !still.is_empty() {
        bail!("still missing after installing: {}", still.join(", "));
    }
    Ok(())
}

pub(crate) fn ci(root: &Path) -> Result<()> {
    let t = Instant::now();
    // A clean clone builds everything once: incremental caches would only double the disk
    // the workspace's own crates take.
    // SAFETY: xtask is single-threaded; the variable is set before any child is spawned.
    unsafe { std::env::set_var("CARGO_INCREMENTAL", "0") };
    step("system tools", ensure_tools)?;
    step("cargo fmt --check", || {
        cargo(root, &["fmt", "--all", "--check"])
    })?;
    step("cargo clippy", || {
        cargo(
            root,
            &[
                "clippy",
                "--workspace",
                "--all-targets",
                "--",
                "-D",
                "warnings",
            ],
        )
    })?;
    step("build-shaders --check", || {
        build_shaders(
            root,
            &root.join("wgsl"),
            &root.join("spirv-out"),
            true,
            None,
        )
    })?;
    step("validate", || validate(root, &root.join("spirv-out")))?;
    // The browser path first: the conformance suite's `web-tint` column reads its results.
    step("web-test", || web_test(root).map(|_| ()))?;
    step("fuzz (10 s a target)", || {
        let r = fuzz(root, 10, None, &[], false);
        // The sanitizer build is of no use to the steps after it; its disk is.
        let _ = std::fs::remove_dir_all(root.join("fuzz/target"));
        r
    })?;
    step("view-test", || view_test(root))?;
    // ... and there a missing browser image fails the column instead of leaving it empty.
    // SAFETY: xtask is single-threaded; the variable is set before any child is spawned.
    unsafe { std::env::set_var("STRATUS_REQUIRE_WEB_TINT", "1") };
    step("cargo test", || cargo(root, &["test", "--workspace"]))?;
    println!("\nci: all steps passed in {:.0?}", t.elapsed());
    Ok(())
}

/// Runs the conformance suite alone. The suite itself prints the table and writes the
/// Markdown (to the target folder it was built in); this says where, pass or fail.
pub(crate) fn conformance(root: &Path) -> Result<()> {
    let t = Instant::now();
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .map(|d| if d.is_absolute() { d } else { root.join(d) })
        .unwrap_or_else(|| root.join("target"));
    let table = target.join("conformance.md");
    // A table from an earlier run must not pass for this one's.
    let _ = std::fs::remove_file(&table);
    let result = cargo(
        root,
        &["test", "-p", "stratus-tests", "--test", "conformance"],
    );
    println!(
        "\nconformance: {} in {:.0?}",
        if result.is_ok() { "passed" } else { "FAILED" },
        t.elapsed()
    );
    if table.exists() {
        println!("Markdown table: {}", table.display());
    } else {
        println!(
            "no Markdown table was written ({} is missing)",
            table.display()
        );
    }
    result
}
