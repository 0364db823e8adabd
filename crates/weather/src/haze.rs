//! Haze from the weather: a reported visibility, or a haze, smoke, dust or mist group, sets the
//! physical sky's aerosol (the Mie terms of `[atmosphere.air]`) so that the air near the ground
//! has the extinction Koschmieder's relation gives for that visibility.

use stratus_scene::{Air, Scene};

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

/// The mass extinction efficiency of dry fine particles at 550 nm, m²/g: the IMPROVE
/// reconstruction's 3 for sulfate and nitrate and 4 for organics (Malm et al. 1994, J.
/// Geophys. Res. 99:1347) between them, absorption included. `PM2.5` in µg/m³ times this is
/// the dry aerosol's extinction in 1/Mm.
pub const PM25_EFFICIENCY_M2_PER_G: f64 = 3.5;

/// The exponent of the aerosol's hygroscopic growth, `f(RH) = (1 - RH)^-GROWTH_EXPONENT`
/// (Kasten 1969's form, Tellus 21:631): 0.5 follows the growth of ammonium sulfate's light
/// scattering the IMPROVE algorithm uses (about 2.2 at 80%, 3.2 at 90%).
pub const GROWTH_EXPONENT: f64 = 0.5;

/// The largest relative humidity the growth is evaluated at: at saturation the formula
/// diverges, and what forms there is fog, which the weather's fog handles.
pub const MAX_GROWTH_RH: f64 = 0.95;

/// How much wetter aerosol at relative humidity `rh` (0-1) removes from a ray than the dry
/// aerosol does.
pub fn growth(rh: f64) -> f64 {
    (1.0 - rh.clamp(0.0, MAX_GROWTH_RH)).powf(-GROWTH_EXPONENT)
}

/// The relative humidity (0-1) of air at `temperature_c` with dew point `dewpoint_c` (Magnus'
/// formula with Alduchov and Eskridge 1996's constants, J. Appl. Meteor. 35:601).
pub fn relative_humidity(temperature_c: f64, dewpoint_c: f64) -> f64 {
    let e = |t: f64| (17.625 * t / (243.04 + t)).exp();
    (e(dewpoint_c) / e(temperature_c)).clamp(0.0, 1.0)
}

/// The visibility fine particles of `pm25` µg/m³ give at relative humidity `rh` (0-1), metres,
/// in air whose other extinction at the ground is `rayleigh` per metre.
pub fn visibility_for_pm25(pm25: f64, rh: f64, rayleigh: f64) -> f64 {
    let aerosol = PM25_EFFICIENCY_M2_PER_G * pm25 * 1e-6 * growth(rh);
    KOSCHMIEDER / (aerosol + rayleigh)
}

/// `air` with its aerosol grown to relative humidity `rh` (0-1), the air's own aerosol taken
/// as dry; its albedo and profile kept.
pub fn humid_air(air: &Air, rh: f64) -> Air {
    let g = growth(rh);
    Air {
        mie_scattering: air.mie_scattering * g,
        mie_absorption: air.mie_absorption * g,
        ..air.clone()
    }
}

/// Sets `scene`'s aerosol for visibility `v` of `kind`, with a note (and one more where the
/// scene's analytic sky will not show it).
pub fn apply(scene: &mut Scene, v: f64, kind: Aerosol, why: &str, notes: &mut Vec<String>) {
    match hazy_air(&scene.atmosphere.air, v, kind) {
        Some(air) => {
            notes.push(format!(
                "haze: {why} -> aerosol extinction {:.3e}/m at the ground ({}, single-scattering albedo {}; Koschmieder: 3.912 / extinction)",
                air.mie_scattering + air.mie_absorption,
                kind.name(),
                kind.albedo()
            ));
            scene.atmosphere.air = air;
            if !scene.atmosphere.sky.is_physical() {
                notes.push(
                    "haze: the analytic sky has no air to thicken; it shows with a physical-sky base (`--preset noon`)".into(),
                );
            }
        }
        None => notes.push(format!("haze: {why}: the air is already that hazy, kept")),
    }
}

/// The scene's aerosol grown to relative humidity `rh` (0-1), with a note.
pub fn humid(scene: &mut Scene, rh: f64, notes: &mut Vec<String>) {
    scene.atmosphere.air = humid_air(&scene.atmosphere.air, rh);
    notes.push(format!(
        "humidity {:.0}%: the aerosol grows {:.2}x (Kasten 1969, exponent {}) -> visibility {:.0} km",
        100.0 * rh,
        growth(rh),
        GROWTH_EXPONENT,
        visibility(&scene.atmosphere.air) / 1000.0
    ));
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
    fn humidity_grows_the_aerosol_as_measured_for_sulfate() {
        assert_eq!(growth(0.0), 1.0);
        assert!((growth(0.8) - 2.236).abs() < 1e-3);
        assert!((growth(0.9) - 3.162).abs() < 1e-3);
        assert_eq!(growth(1.0), growth(MAX_GROWTH_RH));
        // Dew point equal to the temperature is saturation; 12/08 is about 77%.
        assert!((relative_humidity(12.0, 12.0) - 1.0).abs() < 1e-12);
        assert!((relative_humidity(12.0, 8.0) - 0.766).abs() < 5e-3);
        // 75 µg/m³ (China's daily limit, GB 3095-2012) at 50% humidity: about 10.2 km, the
        // visibility below which haze is reported.
        let v = visibility_for_pm25(75.0, 0.5, Air::default().rayleigh_scattering[1]);
        assert!((10.1e3..10.3e3).contains(&v), "{v}");
        let wet = humid_air(&Air::default(), 0.8);
        assert!((wet.mie_scattering / Air::default().mie_scattering - growth(0.8)).abs() < 1e-12);
    }

    #[test]
    fn clean_air_is_not_made_clearer() {
        // The Earth's default air sees about 178 km; a 200 km visibility changes nothing.
        let v = visibility(&Air::default());
        assert!((170e3..190e3).contains(&v), "{v}");
        assert!(hazy_air(&Air::default(), 200e3, Aerosol::Continental).is_none());
    }
}
