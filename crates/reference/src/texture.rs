//! Texture filtering exactly as the GPU's `noise_sampler` does it (linear min/mag filter, repeat
//! addressing, level 0 only; `textureSampleLevel(..., 0.0)` in the WGSL), over the 8-bit texels
//! of the [`stratus_noise`] textures.
//!
//! Conventions (Vulkan/WebGPU): texel `i` of an axis of `n` texels covers `[i, i + 1) / n`, so a
//! coordinate `u` is looked up at `x = u * n - 0.5`: texels `floor(x)` and `floor(x) + 1`
//! (wrapped into `[0, n)`), blended by `fract(x)`. A texel's value is `byte / 255`.
//!
//! Where the two must agree: the texel-centre convention and the wrap are exact; the filter's
//! arithmetic is not. The CPU blends in f64; GPUs quantise the blend weights (typically to 8
//! fractional bits) and may filter 8-bit formats in reduced precision. Measured against
//! lavapipe (llvmpipe 15): a single density sample differs by about 0.1% (coverage 1) to 0.5%
//! (coverage 0.45) of its value, unbiased, about 1.3 times what rounding every filtered texel
//! to 8 bits does to the CPU's own density, and it grows with the coverage remap's gain as
//! filtering noise does; it is not a mismatch of conventions (shifting the lookup by half a
//! texel makes it 10 times worse).

use stratus_noise::{Texture2, Texture3};

/// One axis of a linear lookup: the two texel indices and the weight of the second.
#[inline]
fn axis(u: f64, n: u32) -> (usize, usize, f64) {
    let x = u * f64::from(n) - 0.5;
    let fl = x.floor();
    let f = x - fl;
    let n = i64::from(n);
    // REPEAT: wrap the integer texel index into [0, n).
    let i0 = (fl as i64).rem_euclid(n);
    let i1 = (i0 + 1) % n;
    (i0 as usize, i1 as usize, f)
}

/// Trilinear sample of an RGBA8 3D texture at normalised coordinates `uvw` (repeat).
pub(crate) fn sample3(tex: &Texture3, uvw: [f64; 3]) -> [f64; 4] {
    let [w, h, d] = tex.size;
    let (x0, x1, fx) = axis(uvw[0], w);
    let (y0, y1, fy) = axis(uvw[1], h);
    let (z0, z1, fz) = axis(uvw[2], d);
    let (w, h) = (w as usize, h as usize);
    let data = &tex.data;
    let at = |x: usize, y: usize, z: usize| ((z * h + y) * w + x) * 4;
    let mut out = [0.0; 4];
    let corners = [
        (at(x0, y0, z0), (1.0 - fx) * (1.0 - fy) * (1.0 - fz)),
        (at(x1, y0, z0), fx * (1.0 - fy) * (1.0 - fz)),
        (at(x0, y1, z0), (1.0 - fx) * fy * (1.0 - fz)),
        (at(x1, y1, z0), fx * fy * (1.0 - fz)),
        (at(x0, y0, z1), (1.0 - fx) * (1.0 - fy) * fz),
        (at(x1, y0, z1), fx * (1.0 - fy) * fz),
        (at(x0, y1, z1), (1.0 - fx) * fy * fz),
        (at(x1, y1, z1), fx * fy * fz),
    ];
    for (i, wgt) in corners {
        for (c, o) in out.iter_mut().enumerate() {
            *o += wgt * f64::from(data[i + c]);
        }
    }
    out.map(|v| v / 255.0)
}

/// Bilinear sample of an RGBA8 2D texture at normalised coordinates `uv` (repeat).
pub(crate) fn sample2(tex: &Texture2, uv: [f64; 2]) -> [f64; 4] {
    let [w, h] = tex.size;
    let (x0, x1, fx) = axis(uv[0], w);
    let (y0, y1, fy) = axis(uv[1], h);
    let w = w as usize;
    let data = &tex.data;
    let at = |x: usize, y: usize| (y * w + x) * 4;
    let mut out = [0.0; 4];
    let corners = [
        (at(x0, y0), (1.0 - fx) * (1.0 - fy)),
        (at(x1, y0), fx * (1.0 - fy)),
        (at(x0, y1), (1.0 - fx) * fy),
        (at(x1, y1), fx * fy),
    ];
    for (i, wgt) in corners {
        for (c, o) in out.iter_mut().enumerate() {
            *o += wgt * f64::from(data[i + c]);
        }
    }
    out.map(|v| v / 255.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tex2() -> Texture2 {
        // 4x2 texture, R = 10 * x + 100 * y.
        let mut data = Vec::new();
        for y in 0..2u8 {
            for x in 0..4u8 {
                data.extend([10 * x + 100 * y, 0, 255, 255]);
            }
        }
        Texture2 { size: [4, 2], data }
    }

    #[test]
    fn texel_centres_return_texels() {
        let t = tex2();
        for y in 0..2 {
            for x in 0..4 {
                let uv = [(x as f64 + 0.5) / 4.0, (y as f64 + 0.5) / 2.0];
                let v = sample2(&t, uv);
                assert!((v[0] * 255.0 - f64::from(10 * x + 100 * y)).abs() < 1e-9);
                assert!((v[2] - 1.0).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn halfway_blends_and_wraps() {
        let t = tex2();
        // Between texel 3 (30) and texel 0 (0) of row 0 across the repeat seam: u = 1.0.
        let v = sample2(&t, [1.0, 0.25]);
        assert!((v[0] * 255.0 - 15.0).abs() < 1e-9);
        // Same at u = 0 and u = -3 (repeat).
        assert_eq!(sample2(&t, [0.0, 0.25]), v);
        assert!((sample2(&t, [-3.0, 0.25])[0] - v[0]).abs() < 1e-12);
        // Quarter of the way from texel 1 to texel 2: 10 + 0.25 * 10.
        let v = sample2(&t, [(1.5 + 0.25) / 4.0, 0.25]);
        assert!((v[0] * 255.0 - 12.5).abs() < 1e-9);
    }

    #[test]
    fn trilinear_of_a_linear_ramp_is_exact_inside() {
        // 8x4x2, R = 20 * x + 3 * y + 50 * z: linear away from the seams.
        let mut data = Vec::new();
        for z in 0..2u8 {
            for y in 0..4u8 {
                for x in 0..8u8 {
                    data.extend([20 * x + 3 * y + 50 * z, 0, 0, 0]);
                }
            }
        }
        let t = Texture3 {
            size: [8, 4, 2],
            data,
        };
        let (x, y, z) = (3.3, 1.7, 0.75);
        let v = sample3(&t, [(x + 0.5) / 8.0, (y + 0.5) / 4.0, (z + 0.5) / 2.0]);
        assert!((v[0] * 255.0 - (20.0 * x + 3.0 * y + 50.0 * z)).abs() < 1e-9);
    }
}
