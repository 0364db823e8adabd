//! The host's scene depth: what its geometry hides and where. The march stops at the
//! geometry's surface, so clouds behind a mountain are not drawn and a plane inside a cloud
//! is seen through the cloud in front of it only.

use stratus_scene::FrameUniforms;

/// A depth image as the host's depth buffer holds it: one clip-space depth per pixel
/// (`[0, 1]`, standard or reversed Z), row-major from the top-left, the frame's size, with
/// the projection terms that turn a depth into a distance. Pixels at `clear` (the far
/// plane's depth: 1 for standard Z, 0 for reversed Z) hold no geometry.
///
/// The depths are either here ([`SceneDepth::new`], uploaded; what the CPU reference, ash and
/// the CLI read) or in the host's own depth texture on the GPU ([`SceneDepth::in_texture`],
/// bound in place of the upload by the wgpu library).
#[derive(Clone, Debug, PartialEq)]
pub struct SceneDepth {
    size: [u32; 2],
    /// The depths as little-endian f32 bytes (the `scene-depth` texture's data); `None` when
    /// they are in the host's texture.
    bytes: Option<Vec<u8>>,
    terms: [f32; 2],
    clear: f32,
}

impl SceneDepth {
    /// A depth image of `size` pixels. `terms` are the projection's row-2 terms `(A, B)`
    /// (column 2 and 3): clip depth = `B / distance - A`, so the distance along the view axis
    /// is `B / (depth + A)`; `clear` is the depth of a pixel without geometry. Errors name
    /// the argument: a size that is not the data's, a depth outside `[0, 1]` or not finite,
    /// terms that are not finite or give no distance in front of the camera.
    pub fn new(size: [u32; 2], depth: &[f32], terms: [f64; 2], clear: f32) -> Result<Self, String> {
        let pixels = u64::from(size[0]) * u64::from(size[1]);
        if pixels == 0 || depth.len() as u64 != pixels {
            return Err(format!(
                "the scene depth has {} values, not {}x{} = {pixels}",
                depth.len(),
                size[0],
                size[1]
            ));
        }
        if let Some(i) = depth
            .iter()
            .position(|d| !d.is_finite() || !(0.0..=1.0).contains(d))
        {
            return Err(format!(
                "the scene depth at pixel ({}, {}) is {}: a clip-space depth is in [0, 1]",
                i as u64 % u64::from(size[0]),
                i as u64 / u64::from(size[0]),
                depth[i]
            ));
        }
        let mut d = Self::in_texture(size, terms, clear)?;
        d.bytes = Some(depth.iter().flat_map(|d| d.to_le_bytes()).collect());
        Ok(d)
    }

    /// The host's depth texture of `size` pixels, read on the GPU where it is (the terms and
    /// clear value as in [`SceneDepth::new`]).
    pub fn in_texture(size: [u32; 2], terms: [f64; 2], clear: f32) -> Result<Self, String> {
        if size[0] == 0 || size[1] == 0 {
            return Err(format!(
                "the scene depth is {}x{}: it has no pixels",
                size[0], size[1]
            ));
        }
        let [a, b] = terms;
        if !(a.is_finite() && b.is_finite()) || b == 0.0 {
            return Err(format!(
                "the scene depth's projection terms (A {a}, B {b}) must be finite with B not 0"
            ));
        }
        if clear != 0.0 && clear != 1.0 {
            return Err(format!(
                "the scene depth's clear value is {clear}: the far plane is at depth 1 (standard Z) or 0 (reversed Z)"
            ));
        }
        Ok(Self {
            size,
            bytes: None,
            terms: [a as f32, b as f32],
            clear,
        })
    }

    /// Width and height (pixels).
    pub fn size(&self) -> [u32; 2] {
        self.size
    }

    /// The depths as little-endian f32 bytes, row-major (what is uploaded); `None` when they
    /// are in the host's texture.
    pub fn bytes(&self) -> Option<&[u8]> {
        self.bytes.as_deref()
    }

    /// The depth of pixel `(x, y)` (the far plane's where the depths are in the host's
    /// texture: a renderer that cannot read it refuses such a depth first).
    pub fn depth(&self, x: u32, y: u32) -> f32 {
        let Some(bytes) = &self.bytes else {
            return self.clear;
        };
        let i = 4 * (y as usize * self.size[0] as usize + x as usize);
        f32::from_le_bytes([bytes[i], bytes[i + 1], bytes[i + 2], bytes[i + 3]])
    }

    /// Puts the projection terms and `FLAG_SCENE_DEPTH` into a frame's uniform block (what
    /// every backend and the CPU reference render with).
    pub fn apply(&self, u: &mut FrameUniforms) {
        u.flags |= FrameUniforms::FLAG_SCENE_DEPTH;
        u.scene_depth_a = self.terms[0];
        u.scene_depth_b = self.terms[1];
        u.scene_depth_clear = self.clear;
    }
}

/// The `scene-depth` texture when a frame has no scene depth: one texel, never read
/// (`FLAG_SCENE_DEPTH` is off).
pub(crate) const NO_SCENE_DEPTH: [u8; 4] = [0; 4];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_depth_images_are_refused_by_name() {
        let ok = SceneDepth::new([2, 1], &[0.5, 1.0], [0.0, 0.1], 1.0).unwrap();
        assert_eq!(ok.depth(1, 0), 1.0);
        let e = SceneDepth::new([2, 2], &[0.5, 1.0], [0.0, 0.1], 1.0).unwrap_err();
        assert!(e.contains("2 values, not 2x2"), "{e}");
        let e = SceneDepth::new([2, 1], &[0.5, f32::NAN], [0.0, 0.1], 1.0).unwrap_err();
        assert!(e.contains("pixel (1, 0) is NaN"), "{e}");
        let e = SceneDepth::new([2, 1], &[0.5, 1.5], [0.0, 0.1], 1.0).unwrap_err();
        assert!(e.contains("in [0, 1]"), "{e}");
        let e = SceneDepth::new([2, 1], &[0.5, 1.0], [f64::NAN, 0.1], 1.0).unwrap_err();
        assert!(e.contains("projection terms"), "{e}");
        let e = SceneDepth::new([2, 1], &[0.5, 1.0], [0.0, 0.1], 0.5).unwrap_err();
        assert!(e.contains("clear value"), "{e}");
    }
}
