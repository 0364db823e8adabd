//! Plan options: what a plan is made for beyond the shader features. A pass of
//! `wgsl/graph.toml` names them in `plan = "..."` (`option`, `!option`, joined by `&`).
//!
//! The options are declared once, in the table of [`plan_options!`]: the struct's fields, the
//! names a graph may use ([`PLAN_OPTIONS`]), their defaults and when each counts as on
//! ([`PlanOptions::is_set`]) all come from it. [`PlanOptions::of`] says what a scene asks for.

use stratus_scene::Scene;

/// Declares the plan options: `name: type = default, on when |value| condition;`, each with
/// its doc comment.
macro_rules! plan_options {
    ($( $(#[$doc:meta])* $name:ident : $ty:ty = $default:expr, on when |$v:ident| $on:expr; )*) => {
        /// What a plan is made for beyond the shader features: the plan options passes name
        /// in `plan = "..."`.
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        pub struct PlanOptions {
            $( $(#[$doc])* pub $name: $ty, )*
        }

        impl Default for PlanOptions {
            fn default() -> Self {
                Self { $( $name: $default, )* }
            }
        }

        /// Plan options a pass's `plan` may name, in declaration order.
        pub const PLAN_OPTIONS: &[&str] = &[$( stringify!($name) ),*];

        impl PlanOptions {
            /// Whether the plan option `name` is on (`false` for a name that is no option).
            pub fn is_set(&self, name: &str) -> bool {
                match name {
                    $( stringify!($name) => { let $v = self.$name; $on } )*
                    _ => false,
                }
            }
        }
    };
}

plan_options! {
    /// Temporal upsampling block side: 1 = off, 2 = 1/4, 4 = 1/16 of the pixels marched per
    /// frame (option `temporal` holds when > 1; extent `output/temporal` divides by it).
    temporal: u32 = 1, on when |side| side > 1;
    /// Empty-space skipping is on (option `empty_skip`: the occupancy grid is computed).
    empty_skip: bool = false, on when |on| on;
    /// Checkerboard skipping is on (option `checkerboard`: the sparse march reads history).
    checkerboard: bool = false, on when |on| on;
    /// The path tracer runs instead of the march (option `pathtrace`).
    pathtrace: bool = false, on when |on| on;
    /// The basic tutorial ray marcher runs instead of the march (option `basic`).
    basic: bool = false, on when |on| on;
    /// Sprite clouds are drawn instead of the march (option `sprites`).
    sprites: bool = false, on when |on| on;
    /// The physical sky's tables are computed and composited (option `physical_sky`).
    physical_sky: bool = false, on when |on| on;
    /// The Kuwahara filter runs on the display image (option `kuwahara`, `post.kuwahara`).
    kuwahara: bool = false, on when |on| on;
    /// The rainbow's Lee-diagram table is computed (option `rainbow`: `rainbow.moisture` > 0
    /// with `rainbow.lee_diagram`).
    rainbow: bool = false, on when |on| on;
    /// Rain or snow particles are drawn over the display image (option `precipitation`:
    /// `precipitation.particles` > 0).
    precipitation: bool = false, on when |on| on;
}

impl PlanOptions {
    /// The options `scene` asks for.
    pub fn of(scene: &Scene) -> Self {
        Self {
            physical_sky: scene.atmosphere.sky.is_physical(),
            kuwahara: scene.post.kuwahara,
            rainbow: scene.rainbow.uses_table(),
            precipitation: scene.precipitation.particles > 0.0,
            ..Self::of_clouds(scene)
        }
    }

    /// The options of the clouds' method.
    fn of_clouds(scene: &Scene) -> Self {
        let q = &scene.quality;
        // The baselines replace the march; none of its methods apply.
        match q.method {
            stratus_scene::Method::Volumetric => {}
            stratus_scene::Method::Basic => {
                return Self {
                    basic: true,
                    ..Self::default()
                };
            }
            stratus_scene::Method::Sprites => {
                return Self {
                    sprites: true,
                    ..Self::default()
                };
            }
        }
        if q.integrator == stratus_scene::Integrator::Pathtrace {
            // The march's methods do not apply to the path tracer; it skips empty space always
            // (exactly: only cells without cloud), so it needs the occupancy grid.
            return Self {
                pathtrace: true,
                empty_skip: true,
                ..Self::default()
            };
        }
        Self {
            temporal: q.temporal.divisor(),
            empty_skip: q.empty_space_skip,
            checkerboard: q.checkerboard,
            ..Self::default()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every name in the table is a field `is_set` answers for, and nothing else is.
    #[test]
    fn every_option_is_off_by_default_and_answers_by_its_name() {
        let defaults = PlanOptions::default();
        for name in PLAN_OPTIONS {
            assert!(!defaults.is_set(name), "{name} is on by default");
        }
        assert!(!defaults.is_set("no_such_option"));
        let on = PlanOptions {
            temporal: 4,
            empty_skip: true,
            checkerboard: true,
            pathtrace: true,
            basic: true,
            sprites: true,
            physical_sky: true,
            kuwahara: true,
            rainbow: true,
            precipitation: true,
        };
        for name in PLAN_OPTIONS {
            assert!(on.is_set(name), "{name} is not on when its field is");
        }
        assert_eq!(PLAN_OPTIONS.len(), 10);
    }
}
