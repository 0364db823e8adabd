//! The `stratus` tool's commands: render, animate, compare, presets, scene check, shaders,
//! weather, astro and export-kit, with what the viewer and the lab share with them: the one
//! backend factory ([`backends`]), scene loading ([`scene_io`]), image output ([`output`]),
//! the validation log ([`validation`]) and block-noise estimates ([`convergence`]).

pub mod animate;
pub mod astro;
pub mod backends;
pub mod compare;
pub mod convergence;
pub mod inspect;
pub mod kit;
pub mod output;
pub mod render;
pub mod scene_io;
pub mod validation;
pub mod weather;
