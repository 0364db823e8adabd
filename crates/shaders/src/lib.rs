//! Stratus's shader pipeline: the WGSL under `wgsl/` is the one source of truth for every GPU
//! stage. This crate loads it (from disk or embedded at build time), validates it with naga
//! (diagnostics point at the original `file:line:col`), resolves a variant's override
//! constants, translates it to SPIR-V, GLSL, HLSL and MSL with fixed options (`spirv-out/` keeps
//! the SPIR-V; the other languages are made on demand), reflects it into the manifest written
//! to `spirv-out/`, and checks the frame graph (`wgsl/graph.toml`)
//! against that reflection. Build time only: the renderer reads the results through
//! `stratus-graph`, without naga.

#![deny(missing_docs)]

pub mod compile;
pub mod diagnostic;
pub mod digest;
pub mod generated;
pub mod manifest;
pub mod source;
pub mod translate;

pub use compile::{CompiledModule, compile, compile_all};
pub use diagnostic::{Diagnostic, Diagnostics};
pub use digest::plan_digest;
pub use generated::generated_sources;
pub use source::{ModuleSpec, ShaderTree, VariantSpec};
pub use stratus_graph::Manifest;
pub use translate::{Languages, build_outputs, is_committed, pinned, pinned_path, spv_options};

include!(concat!(env!("OUT_DIR"), "/embedded.rs"));
