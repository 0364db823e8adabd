//! Stratus's frame graph at run time, backend-neutral and free of naga.
//!
//! - [`desc`]: the graph as written in `wgsl/graph.toml` (passes and resources as data), and
//!   its check against the reflection;
//! - [`manifest`]: the reflection manifest's types (`spirv-out/manifest.json`);
//! - [`program`]: the graph, manifest and shader code a renderer runs (embedded from
//!   `spirv-out/`, or built by a test);
//! - [`plan`]: a graph resolved for a scene and size: variants, resources, passes;
//! - [`backend`]: the one backend trait and what every backend shares;
//! - [`output`]: what a frame hands back.

#![deny(missing_docs)]

pub mod backend;
pub mod desc;
pub mod manifest;
pub mod output;
pub mod plan;
pub mod program;

pub use backend::{Backend, BackendError, FrameInput, Readback};
pub use desc::{GraphDesc, GraphError};
pub use manifest::Manifest;
pub use output::{BlockMean, FrameOutput, PassTiming, block_means, named_counters};
pub use plan::{FramePlan, MAX_RESOLUTION, PlanError, PlanOptions, Requirements};
pub use program::Program;
