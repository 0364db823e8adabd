//! The CPU twin of `common.wgsl` and `frame.wgsl`: the `Frame` uniform block widened to f64
//! (generated from the block's one declaration), the mode codes and the PCG jitter hash.

use stratus_scene::FrameUniforms;

use crate::math::V3;

// WGSL: common.wgsl (constants). Must agree with the WGSL and with the scene crate's codes.
pub(crate) const PHASE_TWO_LOBE_HG: u32 = 1;
pub(crate) const PHASE_CORNETTE_SHANKS: u32 = 2;
pub(crate) const INTEGRATION_ANALYTIC: u32 = 0;
pub(crate) const INTEGRATION_RIEMANN: u32 = 1;
pub(crate) const HEIGHT_CLOUD_TYPES: u32 = 1;
pub(crate) const FLAG_BEER_POWDER: u32 = 1;
pub(crate) const FLAG_JITTER: u32 = 2;
pub(crate) const FLAG_DYNAMIC_STEP: u32 = 4;
pub(crate) const FLAG_CHECKERBOARD: u32 = 8;
pub(crate) const FLAG_EMPTY_SKIP: u32 = 16;
pub(crate) const FLAG_PHYSICAL_SKY: u32 = 32;
pub(crate) const FLAG_MOONLIT: u32 = 64;
pub(crate) const FLAG_SCENE_DEPTH: u32 = 128;
pub(crate) const FLAG_LIGHT_SHAFTS: u32 = 512;
pub(crate) const FLAG_LEE_DIAGRAM: u32 = 1024;
pub(crate) const FLAG_MOON_MSAA: u32 = 2048;
pub(crate) const PI: f64 = std::f64::consts::PI;
// WGSL: common.wgsl::MAX_VIEW_STEPS (the bound in step-length mode).
pub(crate) const MAX_VIEW_STEPS: u32 = 1024;

/// The Rust type of a member kind, widened: f32 to f64, u32 kept.
macro_rules! wide_type {
    (f32) => {
        f64
    };
    (u32) => {
        u32
    };
    (vec2f) => {
        [f64; 2]
    };
    (vec2u) => {
        [u32; 2]
    };
    (vec3f) => {
        [f64; 3]
    };
}

/// A member of the uniform block, widened.
macro_rules! widen {
    (f32, $v:expr) => {
        f64::from($v)
    };
    (u32, $v:expr) => {
        $v
    };
    (vec2f, $v:expr) => {
        $v.map(f64::from)
    };
    (vec2u, $v:expr) => {
        $v
    };
    (vec3f, $v:expr) => {
        $v.map(f64::from)
    };
}

/// The f64 mirror of the uniform block, generated from its one declaration
/// (`stratus_scene::frame_members!`).
macro_rules! wide_frame {
    ($( $(#[doc = $doc:literal])* $name:ident : $kind:ident, )*) => {
        /// `Frame` of `wgsl/frame.wgsl`, member for member, every f32 widened to f64 so that the
        /// CPU sees exactly the values the GPU gets (read from
        /// [`stratus_scene::Scene::uniforms`]).
        #[derive(Clone, Debug)]
        #[allow(dead_code, reason = "the mirror holds every member, read by the CPU or not")]
        pub(crate) struct Frame {
            $( $(#[doc = $doc])* pub $name: wide_type!($kind), )*
        }

        impl Frame {
            /// The uniform block widened to f64.
            pub fn from_uniforms(u: &FrameUniforms) -> Self {
                Self { $( $name: widen!($kind, u.$name), )* }
            }
        }
    };
}

stratus_scene::frame_members!(wide_frame);

impl Frame {
    /// `frame.sun_direction`.
    pub fn sun(&self) -> V3 {
        xyz(self.sun_direction)
    }

    /// The camera's unit axes: forward, image right and image up.
    pub fn camera_axes(&self) -> (V3, V3, V3) {
        (
            xyz(self.camera_forward),
            xyz(self.camera_right),
            xyz(self.camera_up),
        )
    }

    /// `frame.sun_illuminance`.
    pub fn sun_illuminance(&self) -> V3 {
        xyz(self.sun_illuminance)
    }

    // WGSL: temporal.wgsl::camera_still
    /// Whether this frame's camera is last frame's: same place, orientation, field of view,
    /// aspect and exposure.
    pub fn camera_still(&self) -> bool {
        self.camera_position == self.previous_position
            && self.tan_half_fov == self.previous_tan_half_fov
            && self.camera_forward == self.previous_forward
            && self.aspect == self.previous_aspect
            && self.camera_right == self.previous_right
            && self.exposure == self.previous_exposure
            && self.camera_up == self.previous_up
    }

    // WGSL: atmosphere.wgsl::physical_sky
    /// Whether the scene is under the physical sky (`FLAG_PHYSICAL_SKY`).
    pub fn physical_sky(&self) -> bool {
        self.flags & FLAG_PHYSICAL_SKY != 0
    }
}

/// A widened vec3 member as a [`V3`].
pub(crate) fn xyz(v: [f64; 3]) -> V3 {
    V3::new(v[0], v[1], v[2])
}

// WGSL: common.wgsl::pcg
// Must agree bit for bit: u32 arithmetic that wraps (WGSL's u32 `*` and `+` wrap), and the same
// shifts. `tests::pcg_matches_reference_values` pins a few outputs.
/// PCG hash (O'Neill), the per-pixel jitter hash of the WGSL.
pub(crate) fn pcg(v: u32) -> u32 {
    let state = v.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277_803_737);
    (word >> 22) ^ word
}

// WGSL: common.wgsl::hash_unit
// Must agree exactly: 24 bits times 2^-24 is exact in f32 and in f64, so the jitter offsets of the
// CPU and the GPU are the same numbers.
/// A value in `[0, 1)` from a pixel and a frame index.
pub(crate) fn hash_unit(pixel: [u32; 2], frame_index: u32) -> f64 {
    let h = pcg(pixel[0] ^ pcg(pixel[1] ^ pcg(frame_index)));
    f64::from(h >> 8) * (1.0 / 16_777_216.0)
}

// WGSL: common.wgsl::van_der_corput
// Must agree exactly: the top 24 bits of the reversed index times 2^-24.
/// The base-2 radical inverse of `n`.
pub(crate) fn van_der_corput(n: u32) -> f64 {
    f64::from(n.reverse_bits() >> 8) * (1.0 / 16_777_216.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The PCG hash computed by hand for a few inputs (u64 arithmetic reduced mod 2^32, an
    /// independent evaluation of the same formula).
    #[test]
    fn pcg_matches_reference_values() {
        fn pcg64(v: u64) -> u64 {
            let m = 1u64 << 32;
            let state = (v * 747_796_405 + 2_891_336_453) % m;
            let word = (((state >> ((state >> 28) + 4)) ^ state) * 277_803_737) % m;
            (word >> 22) ^ word
        }
        for v in [0u32, 1, 2, 77, 12345, u32::MAX, 0x8000_0000] {
            assert_eq!(u64::from(pcg(v)), pcg64(u64::from(v)), "pcg({v})");
        }
        let u = hash_unit([3, 5], 0);
        // The mode flags the sky reads are the scene crate's bits.
        assert_eq!(FLAG_PHYSICAL_SKY, FrameUniforms::FLAG_PHYSICAL_SKY);
        assert_eq!(FLAG_MOONLIT, FrameUniforms::FLAG_MOONLIT);
        assert_eq!(FLAG_SCENE_DEPTH, FrameUniforms::FLAG_SCENE_DEPTH);
        assert!((0.0..1.0).contains(&u));
        assert_eq!(u * 16_777_216.0, (u * 16_777_216.0).floor());
    }
}
