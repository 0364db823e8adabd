//! What the bench reports besides the chart: `results.csv` and, per scene, the Pareto front
//! and the cheapest configuration within FLIP 0.05 on stdout.

use std::{io::Write as _, path::Path};

use anyhow::{Context, Result};
use stratus_quality::{Results, Row, phase_name};

/// Writes one CSV row per scene and configuration.
pub(super) fn write_csv(path: &Path, rows: &[Row]) -> Result<()> {
    let mut f: Vec<u8> = Vec::new();
    writeln!(
        f,
        "scene,config,preset,view_steps,light_steps,integration,phase,beer_powder,octaves,jitter,shape_texture,gpu_ms,march_ms,composite_ms,time_vs_preset,view_steps_pp,light_samples_pp,samples_pp,rmse,flip,flip_p95,reference,pareto"
    )?;
    for r in rows {
        let c = &r.config;
        writeln!(
            f,
            "{},{},{},{},{},{:?},{},{},{},{},{:?},{:.4},{:.4},{:.4},{:.3},{:.2},{:.2},{:.2},{:.6},{:.5},{:.5},{},{}",
            r.scene,
            r.name,
            r.preset,
            c.view_steps,
            c.light_steps,
            c.integration,
            phase_name(c.phase),
            c.beer_powder,
            c.octaves,
            c.jitter,
            c.shape_texture,
            r.gpu_ms,
            r.passes.get("march").copied().unwrap_or(0.0),
            r.passes.get("composite").copied().unwrap_or(0.0),
            r.time_vs_preset,
            r.view_steps_pp,
            r.light_samples_pp,
            r.samples_pp,
            r.rmse,
            r.flip,
            r.flip_p95,
            r.reference,
            r.pareto
        )?;
    }
    stratus_compare::write_file_atomically(path, &f)
        .with_context(|| format!("writing {}", path.display()))
}

/// Prints, per scene, the front and the cheapest configuration within FLIP 0.05.
pub(super) fn summary(results: &Results) {
    let mut scenes: Vec<&str> = results.rows.iter().map(|r| r.scene.as_str()).collect();
    scenes.dedup();
    for scene in scenes {
        let rows: Vec<&Row> = results.rows.iter().filter(|r| r.scene == scene).collect();
        println!("{scene}:");
        let mut front: Vec<&&Row> = rows.iter().filter(|r| r.pareto).collect();
        front.sort_by(|a, b| a.gpu_ms.total_cmp(&b.gpu_ms));
        for r in front {
            println!(
                "  front  {:42} {:7.3} ms ({:4.2}x preset) {:7.1} samples/px  FLIP {:.4}  RMSE {:.4} ({})",
                r.name, r.gpu_ms, r.time_vs_preset, r.samples_pp, r.flip, r.rmse, r.reference
            );
        }
        match rows
            .iter()
            .filter(|r| r.flip <= 0.05)
            .min_by(|a, b| a.gpu_ms.total_cmp(&b.gpu_ms))
        {
            Some(r) => println!(
                "  cheapest within FLIP 0.05: {} ({:.3} ms, {:.2}x preset, {:.1} samples/px, FLIP {:.4})",
                r.name, r.gpu_ms, r.time_vs_preset, r.samples_pp, r.flip
            ),
            None => println!("  no configuration within FLIP 0.05"),
        }
    }
}

/// Marks the Pareto front of (gpu_ms, flip) per scene: no other row of the scene is at least
/// as fast and at least as accurate and better in one.
pub(super) fn mark_pareto(rows: &mut [Row]) {
    let keys: Vec<(String, f64, f64)> = rows
        .iter()
        .map(|r| (r.scene.clone(), r.gpu_ms, r.flip))
        .collect();
    for (i, r) in rows.iter_mut().enumerate() {
        let (scene, t, e) = &keys[i];
        r.pareto = !keys.iter().enumerate().any(|(j, (s, t2, e2))| {
            j != i && s == scene && t2 <= t && e2 <= e && (t2 < t || e2 < e)
        });
    }
}

#[cfg(test)]
mod tests {
    use stratus_quality::Config;
    use stratus_scene::Scene;

    use super::*;

    #[test]
    fn pareto_front_drops_dominated_rows() {
        let base = Config::of(&Scene::default());
        let row = |scene: &str, view_steps: u32, gpu_ms: f64, flip: f64| Row {
            gpu_ms,
            flip,
            ..Row::unmeasured(
                scene,
                Config {
                    view_steps,
                    ..base.clone()
                },
                false,
            )
        };
        let mut rows = vec![
            row("cumulus-noon", 8, 1.0, 0.2),
            row("cumulus-noon", 16, 2.0, 0.1),
            row("cumulus-noon", 32, 5.0, 0.12),
            row("cumulus-noon", 64, 8.0, 0.01),
            // Another scene's rows do not dominate these.
            row("sunset", 8, 1.0, 0.3),
            row("sunset", 64, 8.0, 0.05),
        ];
        mark_pareto(&mut rows);
        let front: Vec<(u32, bool)> = rows
            .iter()
            .map(|r| (r.config.view_steps, r.pareto))
            .collect();
        assert_eq!(
            front,
            [
                (8, true),
                (16, true),
                (32, false),
                (64, true),
                (8, true),
                (64, true)
            ]
        );
    }
}
