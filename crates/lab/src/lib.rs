//! The lab: the commands that measure Stratus rather than use it. `bench` (speed against
//! accuracy), `fit-scattering` (the multiple-scattering fit against the GPU path tracer),
//! `gpu-bench` (a frame's cost per preset on this GPU), `measure-field` (a cloud field's
//! statistics seen from above), `soak` (many frames of one renderer) and `export-volume` (a
//! gridded cloud for Mitsuba 3).

pub mod bench;
pub mod export_volume;
pub mod fit;
pub mod gpu_bench;
pub mod measure_field;
pub mod soak;
