//! `stratus weather`: a METAR report, a weather-service JSON file or a named weather state
//! turned into a scene file; and the `--weather` option of `stratus render`.

use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use clap::Args;
use stratus_scene::Scene;
use stratus_weather::{Derived, states};

use crate::scene_io::load_scene;

/// Options of `stratus weather`.
#[derive(Args)]
#[command(
    after_help = "Examples:\n  stratus weather \"KJFK 221651Z 31012G20KT 10SM FEW045 SCT120 BKN250 12/M02 A3012\"\n  stratus weather --json now.json --out scene.toml\n  stratus weather --state rain\n  stratus weather --list"
)]
pub struct WeatherArgs {
    /// A METAR report (quote it): wind, visibility, present weather (RA, SN, TS, FG, BR, ...),
    /// up to four cloud groups (FEW/SCT/BKN/OVC with bases in hundreds of feet, CB/TCU) or
    /// CAVOK. Each cloud group becomes a cloud layer.
    #[arg(conflicts_with_all = ["json", "state"])]
    metar: Option<String>,
    /// A weather-service response (seed 001's JSON: `result.now.text` is the condition,
    /// `wind_class` a Beaufort force such as "2级", `wind_dir` the direction).
    #[arg(long, conflicts_with = "state")]
    json: Option<PathBuf>,
    /// A named weather state (see --list).
    #[arg(long)]
    state: Option<String>,
    /// List the weather states and what each looks like.
    #[arg(long)]
    list: bool,
    /// The scene the weather is applied to: its camera, sun, noise and quality are kept.
    #[arg(long, conflicts_with = "scene")]
    preset: Option<String>,
    /// A scene file to apply the weather to (instead of a preset).
    #[arg(long)]
    scene: Option<PathBuf>,
    /// Write the scene here (TOML) instead of printing it.
    #[arg(long)]
    out: Option<PathBuf>,
}

/// The scene for a METAR report on `base`, or an error naming the bad token.
pub fn derive_metar(report: &str, base: &Scene) -> Result<Derived> {
    validated(
        stratus_weather::scene_from_metar_text(report, base).map_err(|e| anyhow::anyhow!("{e}"))?,
    )
}

/// `d` if its scene is valid: every derivation should give a valid scene, so an invalid one is
/// a bug, said as such.
fn validated(d: Derived) -> Result<Derived> {
    d.scene
        .validate()
        .map_err(|e| anyhow::anyhow!("the derived scene is invalid (a bug): {e}"))?;
    Ok(d)
}

/// Runs `stratus weather`.
pub fn run(args: WeatherArgs) -> Result<()> {
    if args.list {
        for s in &states::STATES {
            println!("{:<13} {}", s.name, s.about);
        }
        return Ok(());
    }
    let (base, _) = load_scene(args.preset.as_deref(), args.scene.as_ref(), None)?;
    let (derived, source) = if let Some(report) = &args.metar {
        (derive_metar(report, &base)?, report.clone())
    } else if let Some(path) = &args.json {
        let text =
            std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
        let d = stratus_weather::scene_from_service_json(&text, &base)
            .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
        (validated(d)?, path.display().to_string())
    } else if let Some(name) = &args.state {
        let state = states::find(name).map_err(|e| anyhow::anyhow!("--state: {e}"))?;
        let mut scene = base.clone();
        state.params.apply(&mut scene);
        let notes = vec![format!("state: {}: {}", state.name, state.about)];
        (
            validated(Derived {
                scene,
                state,
                notes,
            })?,
            format!("--state {name}"),
        )
    } else {
        bail!(
            "give a METAR report, --json FILE or --state NAME (see --help; --list names the states)"
        );
    };
    let text = derived.to_toml(&source);
    match &args.out {
        Some(path) => {
            stratus_compare::write_file_atomically(path, text.as_bytes())
                .with_context(|| format!("writing {}", path.display()))?;
            for n in &derived.notes {
                eprintln!("{n}");
            }
            println!("wrote {}", path.display());
        }
        None => print!("{text}"),
    }
    Ok(())
}
