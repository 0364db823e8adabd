//! Stateless integer hashing.
//!
//! Every random quantity in the crate (Perlin gradients, Worley feature points, per-octave seeds)
//! is a pure function of `(seed, lattice coordinates)`, computed with the 64-bit finaliser of
//! SplitMix64 (the same avalanche construction as the xxHash/PCG output functions). No sequential
//! RNG is used anywhere, so a texel's value cannot depend on evaluation order or thread scheduling.

/// Odd 64-bit constant (2^64 / golden ratio) used to spread small integers over all bits.
const GOLDEN: u64 = 0x9E37_79B9_7F4A_7C15;
/// Arbitrary non-zero constant (hex digits of pi) so that seed 0 does not start from state 0.
const SEED_SALT: u64 = 0x243F_6A88_85A3_08D3;
/// Salt used for derived seeds, distinct from [`SEED_SALT`].
const DERIVE_SALT: u64 = 0x1319_8A2E_0370_7344;

/// SplitMix64 finaliser: a bijective mixing function with full avalanche.
#[inline]
pub(crate) fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// Hashes a seed and up to three lattice coordinates into 64 well-mixed bits.
#[inline]
pub(crate) fn hash_coords(seed: u64, coords: &[u32]) -> u64 {
    let mut h = mix64(seed ^ SEED_SALT);
    for &c in coords {
        h = mix64(h ^ u64::from(c).wrapping_mul(GOLDEN));
    }
    h
}

/// Derives an independent seed for a sub-stream (a channel, an octave) from a parent seed.
#[inline]
pub(crate) fn derive_seed(seed: u64, tag: u64) -> u64 {
    mix64(mix64(seed ^ DERIVE_SALT) ^ tag.wrapping_mul(GOLDEN))
}

/// Maps 21 bits of `h` starting at bit `shift` to a value in `[0, 1)`.
#[inline]
pub(crate) fn unit21(h: u64, shift: u32) -> f64 {
    ((h >> shift) & 0x1F_FFFF) as f64 * (1.0 / 2_097_152.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seed_zero_is_not_degenerate() {
        assert_ne!(hash_coords(0, &[0, 0, 0]), 0);
        assert_ne!(hash_coords(0, &[0, 0, 0]), hash_coords(0, &[0, 0]));
        assert_ne!(hash_coords(0, &[1, 0, 0]), hash_coords(0, &[0, 1, 0]));
        assert_ne!(derive_seed(0, 0), derive_seed(0, 1));
        assert_ne!(derive_seed(0, 0), derive_seed(1, 0));
    }

    #[test]
    fn unit21_range() {
        assert_eq!(unit21(0, 0), 0.0);
        assert!(unit21(u64::MAX, 0) < 1.0);
        assert!(unit21(u64::MAX, 42) < 1.0);
    }
}
