//! Device limits as a user meets them: a clear error naming the limit, never a panic.

mod common;

use common::{stratus, stratus_with};

/// The largest accepted size on wgpu: a clear error naming the device limit before anything
/// is allocated where the read-back would not fit (lavapipe: 4 GiB against 2 GiB), never a
/// panic (an NVIDIA H100 panicked here on an empty mapped buffer before).
#[test]
fn the_largest_size_is_refused_clearly_where_it_does_not_fit() {
    let (ok, text) = stratus(&[
        "render",
        "--backend",
        "wgpu",
        "--size",
        "16384x16384",
        "--out",
        "/nonexistent-dir/big.png",
    ]);
    assert!(!text.contains("panicked"), "{text}");
    if !ok {
        assert!(
            text.contains("max_buffer_size") || text.contains("max_texture_dimension"),
            "{text}"
        );
    }
}

/// The largest accepted size on ash: the plan's images against the device's memory before
/// anything is allocated (lavapipe: 7.0 GiB against its 2 GiB heap), never a failed allocation
/// half-way or a panic. A GPU with the memory renders it (an H100: 88 ms of GPU time).
#[test]
fn the_largest_size_on_ash_is_checked_against_device_memory_first() {
    let (ok, text) = stratus(&[
        "render",
        "--backend",
        "ash",
        "--size",
        "16384x16384",
        "--out",
        "/nonexistent-dir/big.png",
    ]);
    assert!(!text.contains("panicked"), "{text}");
    if !ok {
        assert!(
            text.contains("GiB of images") && text.contains("render a smaller image"),
            "{text}"
        );
    }
}

/// A GL device without compute shaders (llvmpipe with the compute extension masked, as
/// NVIDIA's EGL gives wgpu) is refused by name, and `auto` moves on to the CPU saying why.
#[test]
fn a_gl_device_without_compute_is_named_and_auto_moves_on() {
    let no_compute = ("MESA_EXTENSION_OVERRIDE", "-GL_ARB_compute_shader");
    let dir = std::env::temp_dir().join(format!("stratus-limits-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch dir");
    let out = dir.join("gl.png");
    let out = out.to_str().expect("utf-8 path");
    let (ok, text) = stratus_with(
        &[
            "render",
            "--backend",
            "wgpu-gl",
            "--size",
            "16x9",
            "--out",
            out,
        ],
        &[no_compute],
    );
    assert!(!ok, "{text}");
    assert!(
        text.contains("it has no compute shaders") && text.contains("use the Vulkan backend"),
        "{text}"
    );
    let (ok, text) = stratus_with(
        &["render", "--size", "16x9", "--out", out],
        &[
            no_compute,
            ("VK_ICD_FILENAMES", "/nonexistent/icd.json"),
            ("VK_DRIVER_FILES", "/nonexistent/icd.json"),
        ],
    );
    assert!(ok, "{text}");
    assert!(
        text.contains("or GL device (") && text.contains("no compute shaders"),
        "{text}"
    );
    assert!(text.contains("rendering on the CPU"), "{text}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A GL context that reports compute shaders while wgpu translates for a GLSL version without
/// them (llvmpipe held to GL 3.3 with its compute extension still listed: the failure NVIDIA's
/// EGL gave the device suite, "The selected version doesn't support Features(COMPUTE_SHADER)")
/// is refused at creation by the backend's compute probe, by name, instead of failing every
/// pipeline later; `auto` moves on.
#[test]
fn a_gl_context_whose_glsl_lacks_compute_is_refused_at_creation() {
    let old_glsl = [
        ("MESA_GL_VERSION_OVERRIDE", "3.3"),
        ("MESA_GLSL_VERSION_OVERRIDE", "330"),
    ];
    let dir = std::env::temp_dir().join(format!("stratus-glsl-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch dir");
    let out = dir.join("gl.png");
    let out = out.to_str().expect("utf-8 path");
    let (ok, text) = stratus_with(
        &[
            "render",
            "--backend",
            "wgpu-gl",
            "--size",
            "16x9",
            "--out",
            out,
        ],
        &old_glsl,
    );
    assert!(!ok, "{text}");
    assert!(!text.contains("panicked"), "{text}");
    assert!(
        text.contains("a one-line compute pipeline failed")
            && text.contains("COMPUTE_SHADER")
            && text.contains("it has no compute shaders"),
        "{text}"
    );
    let (ok, text) = stratus_with(
        &["render", "--size", "16x9", "--out", out],
        &[
            old_glsl[0],
            old_glsl[1],
            ("VK_ICD_FILENAMES", "/nonexistent/icd.json"),
            ("VK_DRIVER_FILES", "/nonexistent/icd.json"),
        ],
    );
    assert!(ok, "{text}");
    assert!(text.contains("rendering on the CPU"), "{text}");
    let _ = std::fs::remove_dir_all(&dir);
}
