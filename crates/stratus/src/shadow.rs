//! Cloud shadows for the host's geometry: the clouds' transmittance of the key light on a
//! square around the camera (the frame graph's `host-shadow` map, wgsl/ground.wgsl), with the
//! transform from the host's world to its texels. The host's shaders read it with
//! `stratus_cloud_shadow` (`wgsl/host/cloud_shadow.wgsl`).

use glam::DVec3;
use stratus_scene::Scene;

/// The map's side in texels (the graph's `host-shadow` extent; `SHADOW_SIZE` in
/// wgsl/ground.wgsl).
pub const SHADOW_SIZE: u32 = 128;
/// Half the side of the square the map covers (m; `SHADOW_HALF_EXTENT`).
pub const SHADOW_HALF_EXTENT: f64 = 20_000.0;
/// Where the shadow starts fading to none, as a fraction of the half side
/// (`SHADOW_FADE_START`).
pub const SHADOW_FADE_START: f64 = 0.75;

/// How the host's shaders find a point's texel: `StratusCloudShadow` of
/// `wgsl/host/cloud_shadow.wgsl`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadowTransform {
    /// Row 0 of the host-world-to-texel transform (of `(x, y, z, 1)`).
    pub texel_x: [f32; 4],
    /// Row 1.
    pub texel_y: [f32; 4],
    /// The map's side (texels).
    pub size: f32,
    /// Where the fade to no shadow starts (fraction of the half side).
    pub fade_start: f32,
}

impl ShadowTransform {
    /// The transform of `scene`'s frame: its camera (the map's centre) and key light (the
    /// sun, or the moon when it lights the scene). A point of the host's world (y up, z
    /// south, the ground at y = 0) is projected along the light onto the ground, then onto
    /// the map.
    pub fn of_scene(scene: &Scene) -> Self {
        let u = scene.uniforms();
        let s = u.sun_direction.map(f64::from);
        // A light at or below the horizon lights no ground (the map is 1 there); keep the
        // projection finite.
        let sy = s[1].max(1e-3);
        let c = scene.camera.position;
        let last = f64::from(SHADOW_SIZE - 1);
        let k = last / (2.0 * SHADOW_HALF_EXTENT);
        // Texel = k (ground point - camera) + last / 2, the ground point in Stratus's axes:
        // x - y s.x / s.y and (z north = -z_host) - y s.z / s.y.
        let texel_x = [k, -k * s[0] / sy, 0.0, -k * c[0] + last / 2.0];
        let texel_y = [0.0, -k * s[2] / sy, -k, -k * c[2] + last / 2.0];
        Self {
            texel_x: texel_x.map(|v| v as f32),
            texel_y: texel_y.map(|v| v as f32),
            size: SHADOW_SIZE as f32,
            fade_start: SHADOW_FADE_START as f32,
        }
    }

    /// The uniform block `StratusCloudShadow` as 12 floats (48 bytes, std140 and WGSL alike).
    pub fn uniform(&self) -> [f32; 12] {
        let [a, b, c, d] = self.texel_x;
        let [e, f, g, h] = self.texel_y;
        [a, b, c, d, e, f, g, h, self.size, self.fade_start, 0.0, 0.0]
    }

    /// The texel coordinates of host-world point `p` (f64: what the shader computes in f32).
    pub fn texel(&self, p: DVec3) -> [f64; 2] {
        let row = |r: [f32; 4]| {
            f64::from(r[0]) * p.x + f64::from(r[1]) * p.y + f64::from(r[2]) * p.z + f64::from(r[3])
        };
        [row(self.texel_x), row(self.texel_y)]
    }

    /// The host-world point at height `height` (m) whose projection along the light lands on
    /// texel `(i, j)` (for tests and tools: what the map holds there is its shadow).
    pub fn point_over_texel(scene: &Scene, i: u32, j: u32, height: f64) -> DVec3 {
        let last = f64::from(SHADOW_SIZE - 1);
        let rel = |t: u32| (f64::from(t) / last * 2.0 - 1.0) * SHADOW_HALF_EXTENT;
        let c = scene.camera.position;
        let s = scene.uniforms().sun_direction.map(f64::from);
        let sy = s[1].max(1e-3);
        // Stratus's axes, then the host's (z negated).
        let world = [
            c[0] + rel(i) + s[0] / sy * height,
            height,
            c[2] + rel(j) + s[2] / sy * height,
        ];
        crate::camera::host_from_world(world)
    }
}

/// The cloud-shadow map of the last frame and how to read it ([`crate::Clouds::cloud_shadow`]).
pub struct CloudShadow<'a> {
    /// The map: r32float, [`SHADOW_SIZE`] texels square, the key light's transmittance from
    /// the ground up through every cloud layer. Bind it as an unfilterable-float texture.
    pub view: &'a wgpu::TextureView,
    /// Its transform from the host's world.
    pub transform: ShadowTransform,
}
