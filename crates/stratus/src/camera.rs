//! The host engine's camera: its view and projection matrices.
//!
//! # Conventions
//!
//! The host's world is right-handed and y-up, in metres: x east, y up, z south (so -z is
//! north), glam's and Bevy's convention. Stratus's own world axes are x east, y up, z north
//! (its scene files, sun azimuths and wind directions use them); [`world_from_host`] and
//! [`host_from_world`] convert, by negating z. The host's ground is at y = 0.
//!
//! - `view` is world-to-view, a rigid transform (rotation and translation, no scale): the
//!   camera looks down its view-space -z with +y up and +x right (`DMat4::look_to_rh`, the
//!   inverse of Bevy's camera `GlobalTransform`). It is f64 so that a camera far from the
//!   origin keeps its position to the millimetre; the shaders work relative to the camera.
//! - `projection` is view-to-clip, a symmetric perspective into wgpu's clip space (y up, depth
//!   in [0, 1]): standard (near at 0) or reversed Z (near at 1), with a finite or an infinite
//!   far plane (glam's `dcamera::rh::proj::directx::perspective`, `perspective_infinite`,
//!   `perspective_infinite_reverse`, or `perspective(fov, aspect, far, near)` for a reversed
//!   finite one; Bevy's `PerspectiveProjection`). Off-centre (asymmetric or jittered) and
//!   y-down (Vulkan-style) projections are refused.
//!
//! The yaw and pitch of a scene's camera are a convenience over the same thing:
//! [`HostCamera::of_scene`] gives the matrices of a scene's camera, and a scene given those
//! matrices renders bit-identical images.

use glam::dcamera::rh::proj::directx;
use glam::{DMat4, DVec3};
use stratus_graph::SceneDepth;
use stratus_scene::{Orientation, Scene};

use crate::Error;

/// A camera as a host engine has it: view and projection matrices (see the [module
/// conventions](self)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HostCamera {
    /// World-to-view: a rigid transform, the camera looking down view-space -z.
    pub view: DMat4,
    /// View-to-clip: a symmetric perspective, clip depth in [0, 1], standard or reversed Z,
    /// finite or infinite far plane.
    pub projection: DMat4,
}

/// What a projection matrix says, once checked ([`HostCamera::projection`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Projection {
    /// tan(vertical field of view / 2).
    pub tan_half_fov_y: f64,
    /// Width / height.
    pub aspect: f64,
    /// The near plane's distance along the view axis (m).
    pub near: f64,
    /// The far plane's (m; infinite for an infinite projection).
    pub far: f64,
    /// Whether clip depth is reversed (1 at the near plane, 0 at the far one).
    pub reversed_z: bool,
    /// The projection's depth terms `(A, B)`: clip depth = `B / distance - A` (row 2,
    /// columns 2 and 3).
    depth_terms: (f64, f64),
}

impl Projection {
    /// The distance along the view axis (view-space -z, m) of a point at clip depth `depth`:
    /// `depth = B / distance - A` with `A`, `B` the projection's row-2 terms (columns 2 and
    /// 3), so `distance = B / (depth + A)`. Infinite where the depth is the infinite far
    /// plane's.
    pub fn view_distance(&self, depth: f64) -> f64 {
        let (a, b) = self.depth_terms;
        b / (depth + a)
    }

    /// The clip depth of a point at `distance` along the view axis (m): `B / distance - A`
    /// (the far plane's depth for an infinite distance).
    pub fn depth_at(&self, distance: f64) -> f64 {
        let (a, b) = self.depth_terms;
        if distance.is_infinite() {
            return self.clear_depth();
        }
        b / distance - a
    }

    /// The depth a cleared depth buffer holds (the far plane's): 1 for standard Z, 0 for
    /// reversed Z.
    pub fn clear_depth(&self) -> f64 {
        if self.reversed_z { 0.0 } else { 1.0 }
    }

    /// The host's depth buffer as Stratus's scene depth: `depth` holds one clip-space depth a
    /// pixel of a `size` target, row-major from the top-left, written with this projection;
    /// pixels at [`Projection::clear_depth`] hold no geometry. Errors name the argument.
    pub fn scene_depth(&self, size: [u32; 2], depth: &[f32]) -> Result<SceneDepth, Error> {
        let (a, b) = self.depth_terms;
        SceneDepth::new(size, depth, [a, b], self.clear_depth() as f32).map_err(Error::Depth)
    }

    /// The scene depth of a host depth texture of `size` written with this projection (its
    /// depths stay on the GPU).
    pub(crate) fn texture_depth(&self, size: [u32; 2]) -> Result<SceneDepth, Error> {
        let (a, b) = self.depth_terms;
        SceneDepth::in_texture(size, [a, b], self.clear_depth() as f32).map_err(Error::Depth)
    }
}

/// Stratus's world axes (x east, y up, z north) of a vector in the host's (z south).
pub fn world_from_host(v: DVec3) -> [f64; 3] {
    [v.x, v.y, -v.z]
}

/// The host's axes (z south) of a vector in Stratus's world axes (z north).
pub fn host_from_world(v: [f64; 3]) -> DVec3 {
    DVec3::new(v[0], v[1], -v[2])
}

fn camera_error(argument: &str, why: impl std::fmt::Display) -> Error {
    Error::Camera(format!("{argument}: {why}"))
}

/// The first element of `m` that is not finite, as "row r, column c".
fn non_finite(m: &DMat4) -> Option<String> {
    (0..4)
        .flat_map(|c| (0..4).map(move |r| (r, c)))
        .find(|&(r, c)| !m.col(c)[r].is_finite())
        .map(|(r, c)| format!("row {r}, column {c} is {}", m.col(c)[r]))
}

impl HostCamera {
    /// The matrices of `scene`'s camera (its position, yaw and pitch or orientation, field of
    /// view and resolution), with a standard-Z projection from `near` to `far` (m; `far` may
    /// be infinite). A scene given them back ([`HostCamera::apply`]) renders the same bits.
    pub fn of_scene(scene: &Scene, near: f64, far: f64) -> Self {
        let (forward, right, up) = scene.camera_basis();
        let (r, u, b) = (
            host_from_world(right),
            host_from_world(up),
            -host_from_world(forward),
        );
        let p = host_from_world(scene.camera.position);
        // Rows right, up, back; translation -R p.
        let view = DMat4::from_cols(
            glam::DVec4::new(r.x, u.x, b.x, 0.0),
            glam::DVec4::new(r.y, u.y, b.y, 0.0),
            glam::DVec4::new(r.z, u.z, b.z, 0.0),
            glam::DVec4::new(-r.dot(p), -u.dot(p), -b.dot(p), 1.0),
        );
        let [w, h] = scene.camera.resolution;
        let aspect = f64::from(w) / f64::from(h.max(1));
        let fov = scene.camera.fov_y_deg.to_radians();
        let projection = if far.is_finite() {
            directx::perspective(fov, aspect, near, far)
        } else {
            directx::perspective_infinite(fov, aspect, near)
        };
        Self { view, projection }
    }

    /// The checked projection: finite, a right-handed symmetric perspective with clip depth
    /// in [0, 1], 0 < near < far.
    pub fn projection(&self) -> Result<Projection, Error> {
        let p = &self.projection;
        if let Some(at) = non_finite(p) {
            return Err(camera_error("projection", at));
        }
        let zero = [
            ("row 1, column 0", p.x_axis.y),
            ("row 3, column 0", p.x_axis.w),
            ("row 0, column 1", p.y_axis.x),
            ("row 3, column 1", p.y_axis.w),
            ("row 0, column 3", p.w_axis.x),
            ("row 1, column 3", p.w_axis.y),
            ("row 3, column 3", p.w_axis.w),
        ];
        if let Some((at, v)) = zero.into_iter().find(|(_, v)| *v != 0.0) {
            return Err(camera_error(
                "projection",
                format!("{at} is {v}, not 0: not a perspective projection"),
            ));
        }
        if p.z_axis.x != 0.0 || p.z_axis.y != 0.0 {
            return Err(camera_error(
                "projection",
                format!(
                    "its centre is off the view axis (row 0 and 1 of column 2: {}, {}); off-centre (asymmetric or jittered) projections are not supported",
                    p.z_axis.x, p.z_axis.y
                ),
            ));
        }
        if p.z_axis.w != -1.0 {
            return Err(camera_error(
                "projection",
                format!(
                    "row 3, column 2 is {}, not -1: not a right-handed perspective (the camera looks down view-space -z)",
                    p.z_axis.w
                ),
            ));
        }
        let (sx, sy) = (p.x_axis.x, p.y_axis.y);
        if sy < 0.0 {
            return Err(camera_error(
                "projection",
                format!(
                    "row 1, column 1 is {sy}: a y-down (Vulkan-style) projection; Stratus takes wgpu's y-up clip space"
                ),
            ));
        }
        if sx <= 0.0 || sy <= 0.0 {
            return Err(camera_error(
                "projection",
                format!("its scales ({sx}, {sy}) must be positive"),
            ));
        }
        // Clip depth = B / distance - A with A = row 2, column 2 and B = row 2, column 3.
        let (a, b) = (p.z_axis.z, p.w_axis.z);
        let (reversed_z, near, far) = if b < 0.0 {
            // Standard: 0 at the near plane (distance B / A), 1 at the far one.
            (false, b / a, b / (1.0 + a))
        } else if b > 0.0 {
            // Reversed: 1 at the near plane, 0 at the far one.
            (true, b / (1.0 + a), b / a)
        } else {
            return Err(camera_error(
                "projection",
                "row 2, column 3 is 0: no near plane",
            ));
        };
        let far = if far.is_finite() && far > 0.0 {
            far
        } else {
            f64::INFINITY
        };
        if !(near > 0.0 && near.is_finite()) || near >= far {
            return Err(camera_error(
                "projection",
                format!(
                    "its near plane ({near} m) must be in front of the camera and before its far plane ({far} m)"
                ),
            ));
        }
        Ok(Projection {
            tan_half_fov_y: 1.0 / sy,
            aspect: sy / sx,
            near,
            far,
            reversed_z,
            depth_terms: (a, b),
        })
    }

    /// The camera's position and orientation in Stratus's world axes, checked: `view` is
    /// finite and rigid (orthonormal rotation within 1e-6, not a mirror; bottom row 0 0 0 1
    /// within 1e-6, what inverting a host's f32 camera transform leaves).
    pub fn pose(&self) -> Result<([f64; 3], Orientation), Error> {
        let v = &self.view;
        if let Some(at) = non_finite(v) {
            return Err(camera_error("view", at));
        }
        let bottom = [v.x_axis.w, v.y_axis.w, v.z_axis.w, v.w_axis.w];
        if bottom
            .iter()
            .zip([0.0, 0.0, 0.0, 1.0])
            .any(|(got, want)| (got - want).abs() > 1e-6)
        {
            return Err(camera_error(
                "view",
                format!("its bottom row is {bottom:?}, not [0, 0, 0, 1]: not a rigid transform"),
            ));
        }
        // Rows of the rotation: right, up, back (the camera looks down -z).
        let row = |i: usize| DVec3::new(v.x_axis[i], v.y_axis[i], v.z_axis[i]);
        let (r, u, b) = (row(0), row(1), row(2));
        let unit = |x: DVec3| (x.length() - 1.0).abs() <= 1e-6;
        if !(unit(r) && unit(u) && unit(b))
            || r.dot(u).abs() > 1e-6
            || r.dot(b).abs() > 1e-6
            || u.dot(b).abs() > 1e-6
        {
            return Err(camera_error(
                "view",
                "its rotation is not orthonormal within 1e-6 (scale or shear): a view matrix is a rigid transform",
            ));
        }
        if r.cross(u).dot(b) < 0.0 {
            return Err(camera_error(
                "view",
                "it mirrors the world (its rotation's determinant is -1)",
            ));
        }
        let t = v.w_axis.truncate();
        let position = -(r * t.x + u * t.y + b * t.z);
        let orientation = Orientation {
            forward: world_from_host(-b),
            right: world_from_host(r),
            up: world_from_host(u),
        };
        // `+ 0.0` makes a -0 (from the negations) the +0 a scene's position has.
        Ok((world_from_host(position).map(|c| c + 0.0), orientation))
    }

    /// Puts this camera into `scene`: its position, orientation and vertical field of view.
    /// The projection's aspect must be the target's (checked when rendering).
    pub fn apply(&self, scene: &mut Scene) -> Result<Projection, Error> {
        let projection = self.projection()?;
        let (position, orientation) = self.pose()?;
        scene.camera.position = position;
        scene.camera.orientation = Some(orientation);
        scene.camera.fov_y_deg = 2.0 * projection.tan_half_fov_y.atan().to_degrees();
        Ok(projection)
    }
}
