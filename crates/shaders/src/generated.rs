//! The WGSL files generated from Rust declarations rather than written by hand: today the
//! per-frame uniform block's `struct Frame` (`wgsl/frame.wgsl`), from
//! `stratus_scene::frame_members!`. `cargo xtask build-shaders` writes them into `wgsl/` before
//! it reads the tree, and `--check` fails when one differs, so the WGSL, the Rust block, its
//! member table and the CPU reference's mirror cannot drift apart.

/// Every generated WGSL file: its name under `wgsl/` and its text.
pub fn generated_sources() -> Vec<(&'static str, String)> {
    vec![("frame.wgsl", stratus_scene::FrameUniforms::wgsl())]
}
