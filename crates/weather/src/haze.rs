//! Haze from the weather: a reported visibility, or a haze, smoke, dust or mist group, sets the
//! physical sky's aerosol (the Mie terms of `[atmosphere.air]`) so that the air near the ground
//! has the extinction Koschmieder's relation gives for that visibility.

use stratus_scene::Air;

/// Koschmieder's constant: visibility = 3.912 / extinction, for the 2% contrast threshold at
/// which a dark object on the horizon disappears (Koschmieder 1924; WMO's meteorological
/// optical range uses 5%, 2.996).
pub const KOSCHMIEDER: f64 = 3.912;

/// Reported visibilities at or above this (metres) say "10 km or more" (`9999`, `CAVOK`): no
/// haze is derived from them.
pub const CLEAR_VISIBILITY_M: f64 = 9_999.0;

/// The visibility assumed for a haze, smoke, dust or mist group reported without one, metres:
/// the largest at which ICAO Annex 3 has them reported (5000 m), so the least haze the group
/// says there is.
pub const HAZE_VISIBILITY_M: f64 = 5_000.0;

/// What the aerosol is, and so how much of what it removes from a ray it scatters rather
/// than absorbs (the single-scattering albedo at 550 nm).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Aerosol {
    /// Water: mist, rain, drizzle (droplets absorb almost nothing): 0.99.
    Water,
    /// Haze of mixed continental aerosol: 0.93 (OPAC's "continental average" at 50% relative
    /// humidity; Hess, Koepke and Schult 1998, Bull. Amer. Meteor. Soc. 79:831).
    Continental,
    /// Smoke and urban aerosol (soot absorbs): 0.82 (OPAC "urban").
    Smoke,
    /// Dust and sand: 0.89 (OPAC "desert").
    Dust,
}

impl Aerosol {
    /// The single-scattering albedo at 550 nm.
    pub fn albedo(self) -> f64 {
        match self {
            Self::Water => 0.99,
            Self::Continental => 0.93,
            Self::Smoke => 0.82,
            Self::Dust => 0.89,
        }
    }

    /// In words, for the notes.
    pub fn name(self) -> &'static str {
        match self {
            Self::Water => "water droplets",
            Self::Continental => "continental haze",
            Self::Smoke => "smoke",
            Self::Dust => "dust",
        }
    }
}

/// The extinction of `air` at the ground in the green channel (550 nm), per metre: Rayleigh
/// scattering plus the aerosol's scattering and absorption (the ozone's tent is zero at the
/// ground for any profile that starts above it).
pub fn ground_extinction(air: &Air) -> f64 {
    air.rayleigh_scattering[1] + air.mie_scattering + air.mie_absorption
}

/// The visibility `air` gives at the ground, metres (Koschmieder).
pub fn visibility(air: &Air) -> f64 {
    KOSCHMIEDER / ground_extinction(air)
}

/// The least visibility the haze is made for, metres: a report of `0000` (fog as thick as it
/// is reported) would ask for infinite extinction.
pub const MIN_VISIBILITY_M: f64 = 50.0;

/// `air` with its aerosol replaced so that the visibility at the ground is `visibility_m`
/// (at least [`MIN_VISIBILITY_M`]), the aerosol being `kind`; its scale height and phase are
/// kept. `None` where the air is already at least that hazy (the clean air's own visibility
/// is about 180 km).
pub fn hazy_air(air: &Air, visibility_m: f64, kind: Aerosol) -> Option<Air> {
    let aerosol = KOSCHMIEDER / visibility_m.max(MIN_VISIBILITY_M) - air.rayleigh_scattering[1];
    if aerosol.partial_cmp(&(air.mie_scattering + air.mie_absorption))
        != Some(std::cmp::Ordering::Greater)
    {
        return None;
    }
    Some(Air {
        mie_scattering: aerosol * kind.albedo(),
        mie_absorption: aerosol * (1.0 - kind.albedo()),
        ..air.clone()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_hazy_air_has_the_visibility_asked_for() {
        for v in [500.0, 3000.0, 8000.0] {
            for kind in [
                Aerosol::Water,
                Aerosol::Continental,
                Aerosol::Smoke,
                Aerosol::Dust,
            ] {
                let air = hazy_air(&Air::default(), v, kind).unwrap();
                assert!((visibility(&air) - v).abs() < 1e-9 * v, "{v} {kind:?}");
                let albedo = air.mie_scattering / (air.mie_scattering + air.mie_absorption);
                assert!((albedo - kind.albedo()).abs() < 1e-12);
                assert_eq!(air.mie_scale_height_m, Air::default().mie_scale_height_m);
            }
        }
    }

    #[test]
    fn a_zero_visibility_is_the_thickest_haze_not_an_infinite_one() {
        let air = hazy_air(&Air::default(), 0.0, Aerosol::Water).unwrap();
        assert!((visibility(&air) - MIN_VISIBILITY_M).abs() < 1e-9);
    }

    #[test]
    fn clean_air_is_not_made_clearer() {
        // The Earth's default air sees about 178 km; a 200 km visibility changes nothing.
        let v = visibility(&Air::default());
        assert!((170e3..190e3).contains(&v), "{v}");
        assert!(hazy_air(&Air::default(), 200e3, Aerosol::Continental).is_none());
    }
}
