//! Lightning's flashes: when and where, from the scene alone.
//!
//! Time is cut into slots of one mean interval (60 / `lightning.flashes_per_minute` s); each
//! slot holds exactly one flash, at a time in it and a place in the sky drawn from
//! `noise.seed` and the slot's number (the place about the camera where it is at that time). So flashes come at the scene's rate without long
//! droughts or bursts, and the same scene at the same time flashes the same way on every
//! backend and every run. A flash is a few return strokes, 40-80 ms apart, each a sharp rise
//! and a 30 ms decay (Rakov and Uman 2003, ch. 4: 3-5 strokes a flash, some tens of
//! milliseconds apart; the channel's light fades in tens of milliseconds).

use crate::Scene;

/// How far from the camera (m, horizontally) flashes are drawn: a storm's cells about it.
pub const FLASH_RANGE_M: f64 = 12_000.0;
/// A flash's longest span (s): the last stroke's start and its decay. A slot is at least this
/// long (`flashes_per_minute` <= 120).
pub const FLASH_SPAN_S: f64 = 0.45;
/// A stroke's decay time (s).
const STROKE_DECAY_S: f64 = 0.03;
/// Below this share of its peak a stroke is over (so a flash ends, exactly).
const STROKE_END: f64 = 0.02;

/// One flash as a frame sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Flash {
    /// The flash's number (its slot): frames of one flash share it.
    pub index: i64,
    /// Where its light is (world metres: x, altitude, z).
    pub position: [f64; 3],
    /// Its light now, a share of its strokes' peak (0-1.5: strokes overlap a little).
    pub intensity: f64,
}

/// A well-mixed 64-bit hash (SplitMix64's finaliser).
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// A uniform number in [0, 1) for slot `k`'s draw `salt` under `seed`.
fn unit(seed: u64, k: i64, salt: u64) -> f64 {
    let h = mix(seed ^ mix((k as u64).wrapping_add(salt.wrapping_mul(0x9E37_79B9_7F4A_7C15))));
    (h >> 11) as f64 / (1u64 << 53) as f64
}

/// Slot `k`'s flash: its start (s), its strokes' starts after it (s), and its place.
fn slot_flash(scene: &Scene, k: i64, slot_s: f64) -> (f64, Vec<f64>, [f64; 3]) {
    let seed = scene.noise.seed;
    let start = k as f64 * slot_s + unit(seed, k, 1) * (slot_s - FLASH_SPAN_S);
    let strokes = 3 + (unit(seed, k, 2) * 3.0) as usize;
    let mut at = 0.0;
    let times = (0..strokes)
        .map(|i| {
            if i > 0 {
                at += 0.04 + 0.04 * unit(seed, k, 10 + i as u64);
            }
            at
        })
        .collect();
    let r = FLASH_RANGE_M * unit(seed, k, 3).sqrt();
    let a = std::f64::consts::TAU * unit(seed, k, 4);
    let atm = &scene.atmosphere;
    let thick = atm.cloud_top_m - atm.cloud_bottom_m;
    // In the lower middle of the main layer, where charge separates (below 5 km into it).
    let alt = atm.cloud_bottom_m + (thick * (0.15 + 0.25 * unit(seed, k, 5))).min(5000.0);
    let cam = scene.camera.position;
    (
        start,
        times,
        [cam[0] + r * a.sin(), alt, cam[2] + r * a.cos()],
    )
}

/// The flash lit at scene time `t` (s; `clouds.time_s` is the scene's own), if any.
pub fn flash_at(scene: &Scene, t: f64) -> Option<Flash> {
    let rate = scene.lightning.flashes_per_minute;
    if rate.is_nan() || rate <= 0.0 || !t.is_finite() {
        return None;
    }
    let slot_s = 60.0 / rate;
    // A flash starts at least FLASH_SPAN_S before its slot's end and is over within it, so only
    // this slot's can be lit.
    let k = (t / slot_s).floor() as i64;
    let (start, strokes, position) = slot_flash(scene, k, slot_s);
    let intensity: f64 = strokes
        .iter()
        .map(|s| t - start - s)
        .filter(|dt| *dt >= 0.0)
        .map(|dt| (-dt / STROKE_DECAY_S).exp())
        .filter(|v| *v >= STROKE_END)
        .sum();
    (intensity > 0.0).then_some(Flash {
        index: k,
        position,
        intensity,
    })
}

/// The flash the scene's own time lights (`clouds.time_s`).
pub fn flash(scene: &Scene) -> Option<Flash> {
    flash_at(scene, scene.clouds.time_s)
}

/// The first scene time (s, a frame of 60 a second from `clouds.time_s` on, within an hour)
/// at which a flash at least `least` of its peak is lit within `within_deg` of the camera's
/// forward direction: a frame that shows one (for tests, conformance and pictures).
pub fn first_flash_in_view(scene: &Scene, within_deg: f64, least: f64) -> Option<f64> {
    let (forward, _, _) = scene.camera_basis();
    let cam = scene.camera.position;
    let cos_within = within_deg.to_radians().cos();
    (0..3600 * 60)
        .map(|i| scene.clouds.time_s + f64::from(i) / 60.0)
        .find(|&t| {
            flash_at(scene, t).is_some_and(|f| {
                let d = [0, 1, 2].map(|k| f.position[k] - cam[k]);
                let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                let cos = (d[0] * forward[0] + d[1] * forward[1] + d[2] * forward[2]) / len;
                f.intensity >= least && cos >= cos_within
            })
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stormy(rate: f64) -> Scene {
        let mut s = Scene::default();
        s.lightning.flashes_per_minute = rate;
        s
    }

    /// Every slot holds one flash: over ten minutes at 20 a minute, 200 flashes, each lit for
    /// a few frames, none before its slot or after FLASH_SPAN_S.
    #[test]
    fn flashes_come_at_the_rate_one_a_slot() {
        let s = stormy(20.0);
        let mut seen = std::collections::BTreeMap::new();
        let fps = 240.0;
        for i in 0..(600.0 * fps) as i64 {
            let t = i as f64 / fps;
            if let Some(f) = flash_at(&s, t) {
                let e = seen.entry(f.index).or_insert((t, t));
                e.1 = t;
                assert!(f.intensity > 0.0 && f.intensity < 2.0, "{f:?}");
            }
        }
        assert_eq!(seen.len(), 200, "{} flashes", seen.len());
        for (k, (first, last)) in &seen {
            assert!(
                *first >= *k as f64 * 3.0 && last - first <= FLASH_SPAN_S,
                "{k}: {first}..{last}"
            );
        }
    }

    /// The same scene flashes the same way; another seed elsewhere and at other times.
    #[test]
    fn flashes_follow_the_seed() {
        let a = stormy(30.0);
        let mut b = a.clone();
        b.noise.seed += 1;
        let times = |s: &Scene| -> Vec<(i64, [f64; 3])> {
            (0..6000)
                .filter_map(|i| flash_at(s, f64::from(i) / 100.0))
                .map(|f| (f.index, f.position))
                .collect()
        };
        assert_eq!(times(&a), times(&a.clone()));
        assert_ne!(times(&a), times(&b));
        assert!(flash_at(&stormy(0.0), 1.0).is_none());
    }

    /// The frame `first_flash_in_view` finds shows a flash that bright, where it says.
    #[test]
    fn a_flash_in_view_is_found_lit() {
        let mut s = stormy(40.0);
        s.clouds.coverage = 0.6;
        let t = first_flash_in_view(&s, 20.0, 0.8).expect("a flash within the hour");
        let f = flash_at(&s, t).expect("lit");
        assert!(f.intensity >= 0.8, "{f:?}");
        println!("first flash in view at {t} s: {f:?}");
        s.camera.yaw_deg += 180.0;
        let behind = first_flash_in_view(&s, 20.0, 0.8).expect("one behind too");
        assert_ne!(behind, t);
    }
}
