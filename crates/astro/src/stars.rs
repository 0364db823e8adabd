//! The naked-eye stars: a catalogue to visual magnitude 6.5 (see `data/README.md` for its
//! source and licence), and the table the GPU reads it from.
//!
//! The table bins the stars by the cells of a cube map over the J2000 celestial sphere, so
//! that a pixel reads only the few stars near its direction: each cell lists every star within
//! [`MARGIN_DEG`] of it (a star near a cell's edge is listed in both cells), so the cell a
//! direction falls in, rounded either way at an edge, holds every star whose light can reach
//! it. It is one `r32float` texture [`TABLE_WIDTH`] texels wide, read as a flat array of
//! floats: first two per cell (the first record's index and the count), then four per record
//! (the star's J2000 unit vector and its magnitude and colour index packed in one exact
//! integer, [`pack`]).

use std::sync::OnceLock;

use crate::celestial::equatorial_vector;

/// The catalogue (CSV: `ra_deg,dec_deg,vmag,bv,hip`, J2000; see `data/README.md`).
const CATALOGUE: &str = include_str!("../data/stars.csv");

/// Cells along a cube face's edge (about 5.6 degrees each).
pub const CELLS: u32 = 16;
/// How far from a cell its stars may lie (degrees): the largest reach of a star's light on
/// screen the renderer draws.
pub const MARGIN_DEG: f64 = 1.0;
/// The table's width in texels.
pub const TABLE_WIDTH: u32 = 1024;
/// The first record's float index: after two floats for each of the 6 x CELLS^2 cells.
pub const RECORDS_AT: u32 = 2 * 6 * CELLS * CELLS;
/// The colour index given to a star the catalogue has none for (a G star's, as the sun's).
pub const DEFAULT_BV: f64 = 0.65;

/// A catalogue star.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Star {
    /// Right ascension, J2000 (degrees).
    pub ra_deg: f64,
    /// Declination, J2000 (degrees).
    pub dec_deg: f64,
    /// Visual magnitude (Johnson V).
    pub vmag: f64,
    /// Colour index B - V ([`DEFAULT_BV`] where the catalogue has none).
    pub bv: f64,
}

/// Every star of the catalogue, brightest first.
pub fn catalogue() -> &'static [Star] {
    static STARS: OnceLock<Vec<Star>> = OnceLock::new();
    STARS.get_or_init(|| parse(CATALOGUE).unwrap_or_else(|e| panic!("data/stars.csv: {e}")))
}

/// The catalogue's stars from its CSV text (`#` lines and the header skipped).
fn parse(text: &str) -> Result<Vec<Star>, String> {
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') || line.starts_with("ra_deg") {
            continue;
        }
        let fields: Vec<&str> = line.split(',').collect();
        let num = |k: usize| -> Result<Option<f64>, String> {
            match fields.get(k).map(|s| s.trim()) {
                None | Some("") => Ok(None),
                Some(s) => s
                    .parse::<f64>()
                    .map(Some)
                    .map_err(|e| format!("line {}: field {}: {e}", i + 1, k + 1)),
            }
        };
        let need =
            |k: usize| num(k)?.ok_or_else(|| format!("line {}: field {} empty", i + 1, k + 1));
        out.push(Star {
            ra_deg: need(0)?,
            dec_deg: need(1)?,
            vmag: need(2)?,
            bv: num(3)?.unwrap_or(DEFAULT_BV),
        });
    }
    Ok(out)
}

/// A star's magnitude and colour index in one float that holds an integer exactly: the
/// magnitude in hundredths above -2 (to 8.5) times 1024, plus the colour index in 300ths above
/// -0.5 (to 2.9).
pub fn pack(vmag: f64, bv: f64) -> f32 {
    let m = ((vmag.clamp(-2.0, 8.5) + 2.0) * 100.0).round() as u32;
    let c = ((bv.clamp(-0.5, 2.9) + 0.5) * 300.0).round() as u32;
    (m * 1024 + c) as f32
}

/// The magnitude and colour index [`pack`] holds (to its hundredth and 300th).
pub fn unpack(packed: f32) -> (f64, f64) {
    let p = packed as u32;
    (
        f64::from(p / 1024) * 0.01 - 2.0,
        f64::from(p % 1024) / 300.0 - 0.5,
    )
}

/// The cube-map cell that unit vector `v` falls in (the same arithmetic in f32 as the WGSL's
/// `star_cell`).
pub fn cell_of(v: [f32; 3]) -> u32 {
    let a = v.map(f32::abs);
    let (face, uv, major) = if a[0] >= a[1] && a[0] >= a[2] {
        (if v[0] > 0.0 { 0 } else { 1 }, [v[2], v[1]], a[0])
    } else if a[1] >= a[2] {
        (if v[1] > 0.0 { 2 } else { 3 }, [v[0], v[2]], a[1])
    } else {
        (if v[2] > 0.0 { 4 } else { 5 }, [v[0], v[1]], a[2])
    };
    let st = uv.map(|u| ((u / major) * 0.5 + 0.5).clamp(0.0, 0.999_999));
    let cell = st.map(|s| (s * CELLS as f32) as u32);
    (face * CELLS + cell[1]) * CELLS + cell[0]
}

/// The GPU's star table.
pub struct GpuTable {
    /// Its size in texels (x, y, 1).
    pub size: [u32; 3],
    /// Its floats, row by row ([`TABLE_WIDTH`] a row), the last row padded with zeros.
    pub floats: Vec<f32>,
    /// The same floats' bytes (little-endian), as uploaded.
    pub bytes: Vec<u8>,
}

/// The table of [`catalogue`] (built once).
pub fn gpu_table() -> &'static GpuTable {
    static TABLE: OnceLock<GpuTable> = OnceLock::new();
    TABLE.get_or_init(|| build(catalogue()))
}

/// Points within `MARGIN_DEG` of unit `v`, enough to touch every cell that comes that near:
/// the centre, and rings at half and the whole margin, 24 points each (cells are 5.6 degrees
/// across, so a cell that reaches into the disc holds one of them).
fn reach(v: [f64; 3]) -> Vec<[f64; 3]> {
    // Two unit vectors across v.
    let helper = if v[2].abs() < 0.9 {
        [0.0, 0.0, 1.0]
    } else {
        [1.0, 0.0, 0.0]
    };
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let e1 = {
        let c = cross(v, helper);
        let n = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
        c.map(|x| x / n)
    };
    let e2 = cross(v, e1);
    let mut out = vec![v];
    for radius in [0.5 * MARGIN_DEG, MARGIN_DEG] {
        let (s, c) = radius.to_radians().sin_cos();
        for k in 0..24 {
            let (sk, ck) = (f64::from(k) * std::f64::consts::TAU / 24.0).sin_cos();
            out.push(std::array::from_fn(|i| {
                c * v[i] + s * (ck * e1[i] + sk * e2[i])
            }));
        }
    }
    out
}

fn build(stars: &[Star]) -> GpuTable {
    let cells = (6 * CELLS * CELLS) as usize;
    let mut lists: Vec<Vec<usize>> = vec![Vec::new(); cells];
    for (i, s) in stars.iter().enumerate() {
        let v = equatorial_vector(s.ra_deg, s.dec_deg);
        let mut touched: Vec<u32> = reach(v)
            .into_iter()
            .map(|p| cell_of(p.map(|x| x as f32)))
            .collect();
        touched.sort_unstable();
        touched.dedup();
        for c in touched {
            lists[c as usize].push(i);
        }
    }
    let mut floats = vec![0.0f32; RECORDS_AT as usize];
    let mut records = Vec::new();
    for (c, list) in lists.iter().enumerate() {
        floats[2 * c] = (records.len() / 4) as f32;
        floats[2 * c + 1] = list.len() as f32;
        for &i in list {
            let s = &stars[i];
            let v = equatorial_vector(s.ra_deg, s.dec_deg);
            records.extend([v[0] as f32, v[1] as f32, v[2] as f32, pack(s.vmag, s.bv)]);
        }
    }
    floats.extend(records);
    let rows = floats.len().div_ceil(TABLE_WIDTH as usize);
    floats.resize(rows * TABLE_WIDTH as usize, 0.0);
    let bytes = floats.iter().flat_map(|f| f.to_le_bytes()).collect();
    GpuTable {
        size: [TABLE_WIDTH, rows as u32, 1],
        floats,
        bytes,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn packing_keeps_magnitude_and_colour() {
        for (m, bv) in [(-1.46, 0.0), (6.5, 1.62), (0.03, -0.02), (3.33, 2.9)] {
            let (m2, bv2) = unpack(pack(m, bv));
            assert!(
                (m2 - m).abs() < 0.0051 && (bv2 - bv).abs() < 0.0017,
                "{m} {bv}"
            );
        }
    }

    /// The catalogue holds the real sky's count per magnitude: about 4800 x 10^(0.48 (m - 6))
    /// stars brighter than m (Allen's Astrophysical Quantities), 8340 to 6.5, within 10%; and
    /// 10 to 25 brighter than magnitude 1.
    #[test]
    fn the_catalogue_has_the_skys_count_per_magnitude() {
        let stars = catalogue();
        let all = stars.iter().filter(|s| s.vmag <= 6.5).count();
        let bright = stars.iter().filter(|s| s.vmag < 1.0).count();
        assert_eq!(all, stars.len(), "every star is brighter than 6.5");
        assert!((all as f64 / 8340.0 - 1.0).abs() < 0.1, "{all} stars");
        assert!((10..=25).contains(&bright), "{bright} brighter than 1");
        assert!(
            stars.windows(2).all(|w| w[0].vmag <= w[1].vmag),
            "brightest first"
        );
    }

    /// Every star lies in its own cell's list, and in every cell that a point within the
    /// margin of it falls in; no cell lists a star farther than the margin plus a cell's
    /// diagonal.
    #[test]
    fn each_cell_lists_the_stars_near_it() {
        let t = gpu_table();
        let stars = catalogue();
        let cell_stars = |c: u32| -> Vec<[f32; 3]> {
            let start = t.floats[2 * c as usize] as usize;
            let count = t.floats[2 * c as usize + 1] as usize;
            (start..start + count)
                .map(|r| {
                    let at = RECORDS_AT as usize + 4 * r;
                    [t.floats[at], t.floats[at + 1], t.floats[at + 2]]
                })
                .collect()
        };
        for s in stars.iter().step_by(7) {
            let v = equatorial_vector(s.ra_deg, s.dec_deg).map(|x| x as f32);
            for p in reach(equatorial_vector(s.ra_deg, s.dec_deg)) {
                let c = cell_of(p.map(|x| x as f32));
                assert!(
                    cell_stars(c).contains(&v),
                    "star {s:?} missing from cell {c}"
                );
            }
        }
        let total: f32 = (0..6 * CELLS * CELLS)
            .map(|c| t.floats[2 * c as usize + 1])
            .sum();
        let most = (0..6 * CELLS * CELLS)
            .map(|c| t.floats[2 * c as usize + 1])
            .fold(0.0f32, f32::max);
        println!(
            "{total} records for {} stars: {:.1} a cell on average, {most} at most",
            stars.len(),
            total / (6 * CELLS * CELLS) as f32
        );
        assert!(total as usize >= stars.len());
        assert!((total as usize) < 2 * stars.len(), "{total} records");
    }
}
