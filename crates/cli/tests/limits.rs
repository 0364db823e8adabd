//! Device limits as a user meets them: a clear error naming the limit, never a panic.

mod common;

use common::{scratch, stratus, stratus_with};

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

/// Renders on `wgpu-gl` under the GL environment `gl`, then on `auto` with the same GL and no
/// Vulkan driver: what each printed, after checking that the first failed without a panic and
/// the second succeeded on the CPU.
fn refused_gl_then_auto(name: &str, gl: &[(&str, &str)]) -> (String, String) {
    let dir = scratch(name);
    let out = dir.join("gl.png");
    let out = out.to_str().expect("utf-8 path");
    let (ok, refused) = stratus_with(
        &[
            "render",
            "--backend",
            "wgpu-gl",
            "--size",
            "16x9",
            "--out",
            out,
        ],
        gl,
    );
    assert!(!ok, "{refused}");
    assert!(!refused.contains("panicked"), "{refused}");
    assert!(refused.contains("it has no compute shaders"), "{refused}");
    let mut env = gl.to_vec();
    env.extend([
        ("VK_ICD_FILENAMES", "/nonexistent/icd.json"),
        ("VK_DRIVER_FILES", "/nonexistent/icd.json"),
    ]);
    let (ok, auto) = stratus_with(&["render", "--size", "16x9", "--out", out], &env);
    assert!(ok, "{auto}");
    assert!(auto.contains("rendering on the CPU"), "{auto}");
    (refused, auto)
}

/// A GL device without compute shaders (llvmpipe with the compute extension masked) is refused
/// by name, and `auto` moves on to the CPU saying why.
#[test]
fn a_gl_device_without_compute_is_named_and_auto_moves_on() {
    let (refused, auto) = refused_gl_then_auto(
        "gl-no-compute",
        &[("MESA_EXTENSION_OVERRIDE", "-GL_ARB_compute_shader")],
    );
    assert!(refused.contains("use the Vulkan backend"), "{refused}");
    assert!(
        auto.contains("or GL device (") && auto.contains("no compute shaders"),
        "{auto}"
    );
}

/// A GL context that reports compute shaders while wgpu translates for a GLSL version without
/// them (llvmpipe held to GL 3.3 with its compute extension still listed: the failure NVIDIA's
/// EGL gave the device suite, "The selected version doesn't support Features(COMPUTE_SHADER)")
/// is refused at creation by the backend's compute probe, by name, instead of failing every
/// pipeline later; `auto` moves on.
#[test]
fn a_gl_context_whose_glsl_lacks_compute_is_refused_at_creation() {
    let (refused, _) = refused_gl_then_auto(
        "gl-old-glsl",
        &[
            ("MESA_GL_VERSION_OVERRIDE", "3.3"),
            ("MESA_GLSL_VERSION_OVERRIDE", "330"),
        ],
    );
    assert!(
        refused.contains("a one-line compute pipeline failed")
            && refused.contains("COMPUTE_SHADER"),
        "{refused}"
    );
    // The driver's reason, not wgpu's wording of it as its own fault.
    assert!(!refused.contains("Internal error"), "{refused}");
}
