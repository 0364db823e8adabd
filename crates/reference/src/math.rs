//! A minimal f64 3-vector and the scalar helpers of `common.wgsl` (`saturate`, `remap`) plus the
//! WGSL built-ins the model uses (`mix`, `smoothstep`), with WGSL's exact definitions.

use std::ops::{Add, AddAssign, Div, Mul, Neg, Sub};

/// A 3-vector of f64 (the CPU twin of WGSL's `vec3<f32>`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct V3 {
    /// x (east).
    pub x: f64,
    /// y (up).
    pub y: f64,
    /// z (north).
    pub z: f64,
}

impl V3 {
    /// The zero vector.
    pub const ZERO: V3 = V3::new(0.0, 0.0, 0.0);

    /// A vector from its components.
    pub const fn new(x: f64, y: f64, z: f64) -> Self {
        Self { x, y, z }
    }

    /// All three components equal to `v`.
    pub const fn splat(v: f64) -> Self {
        Self::new(v, v, v)
    }

    /// From an array `[x, y, z]`.
    pub fn from_array(a: [f64; 3]) -> Self {
        Self::new(a[0], a[1], a[2])
    }

    /// From the first three members of a uniform vec4 (widened to f64).
    pub fn from_f32(a: [f32; 4]) -> Self {
        Self::new(f64::from(a[0]), f64::from(a[1]), f64::from(a[2]))
    }

    /// As an array `[x, y, z]`.
    pub fn to_array(self) -> [f64; 3] {
        [self.x, self.y, self.z]
    }

    /// Dot product.
    pub fn dot(self, o: V3) -> f64 {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    /// Cross product.
    pub fn cross(self, o: V3) -> V3 {
        V3::new(
            self.y * o.z - self.z * o.y,
            self.z * o.x - self.x * o.z,
            self.x * o.y - self.y * o.x,
        )
    }

    /// Euclidean length.
    pub fn length(self) -> f64 {
        self.dot(self).sqrt()
    }

    /// This vector scaled to unit length (WGSL `normalize`).
    pub fn normalize(self) -> V3 {
        self / self.length()
    }

    /// Component-wise product.
    pub fn mul_v(self, o: V3) -> V3 {
        V3::new(self.x * o.x, self.y * o.y, self.z * o.z)
    }

    /// An orthonormal basis `(t, b)` perpendicular to unit `self` (Duff et al. 2017).
    pub fn basis(self) -> (V3, V3) {
        let sign = if self.z >= 0.0 { 1.0 } else { -1.0 };
        let a = -1.0 / (sign + self.z);
        let b = self.x * self.y * a;
        (
            V3::new(1.0 + sign * self.x * self.x * a, sign * b, -sign * self.x),
            V3::new(b, sign + self.y * self.y * a, -self.y),
        )
    }
}

impl Add for V3 {
    type Output = V3;
    fn add(self, o: V3) -> V3 {
        V3::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl AddAssign for V3 {
    fn add_assign(&mut self, o: V3) {
        *self = *self + o;
    }
}

impl Sub for V3 {
    type Output = V3;
    fn sub(self, o: V3) -> V3 {
        V3::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl Neg for V3 {
    type Output = V3;
    fn neg(self) -> V3 {
        V3::new(-self.x, -self.y, -self.z)
    }
}

impl Mul<f64> for V3 {
    type Output = V3;
    fn mul(self, s: f64) -> V3 {
        V3::new(self.x * s, self.y * s, self.z * s)
    }
}

impl Mul<V3> for f64 {
    type Output = V3;
    fn mul(self, v: V3) -> V3 {
        v * self
    }
}

impl Div<f64> for V3 {
    type Output = V3;
    fn div(self, s: f64) -> V3 {
        V3::new(self.x / s, self.y / s, self.z / s)
    }
}

// WGSL: common.wgsl::saturate
/// `clamp(x, 0, 1)`.
pub fn saturate(x: f64) -> f64 {
    x.clamp(0.0, 1.0)
}

// WGSL: common.wgsl::remap
/// Linear remap of `x` from `[lo0, hi0]` to `[lo1, hi1]`, unclamped (HZD's remap).
pub fn remap(x: f64, lo0: f64, hi0: f64, lo1: f64, hi1: f64) -> f64 {
    lo1 + (x - lo0) * (hi1 - lo1) / (hi0 - lo0)
}

/// WGSL built-in `mix(a, b, t) = a * (1 - t) + b * t`.
pub fn mix(a: f64, b: f64, t: f64) -> f64 {
    a * (1.0 - t) + b * t
}

/// WGSL built-in `mix` on vectors.
pub fn mix_v(a: V3, b: V3, t: f64) -> V3 {
    a * (1.0 - t) + b * t
}

/// WGSL built-in `smoothstep(lo, hi, x)`: `t = clamp((x - lo) / (hi - lo), 0, 1); t * t * (3 - 2 t)`.
pub fn smoothstep(lo: f64, hi: f64, x: f64) -> f64 {
    let t = saturate((x - lo) / (hi - lo));
    t * t * (3.0 - 2.0 * t)
}
