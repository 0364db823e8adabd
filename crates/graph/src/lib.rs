//! Stratus's frame graph at run time, backend-neutral and free of naga.
//!
//! - [`desc`]: the graph as written in `wgsl/graph.toml` (passes and resources as data);
//! - [`check`]: the graph checked against the shaders' reflection;
//! - [`error`]: why no plan could be made;
//! - [`manifest`]: the reflection manifest's types (`spirv-out/manifest.json`);
//! - [`program`]: the graph, manifest and shader code a renderer runs (embedded from
//!   `spirv-out/`, or built by a test);
//! - [`options`]: the plan options (one table), and what a scene asks for;
//! - [`plan`]: a graph resolved for a plan key (features, options, size): variants, resources,
//!   passes;
//! - [`backend`]: the one backend trait and what every backend shares;
//! - [`depth`]: the host's scene depth, which the march stops at;
//! - [`output`]: what a frame hands back.

#![deny(missing_docs)]

pub mod backend;
pub mod check;
pub mod depth;
pub mod desc;
pub mod error;
pub mod manifest;
pub mod options;
pub mod output;
pub mod plan;
pub mod program;

pub use backend::{Backend, BackendError, FrameInput, Readback};
pub use depth::SceneDepth;
pub use desc::{GraphDesc, GraphError};
pub use manifest::Manifest;
pub use options::PlanOptions;
pub use output::{BlockMean, FrameOutput, PassTiming, block_means, named_counters};
pub use plan::{FramePlan, MAX_RESOLUTION, PlanError, PlanKey, Requirements};
pub use program::Program;
