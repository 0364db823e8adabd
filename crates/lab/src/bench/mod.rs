//! `stratus bench`: speed against accuracy.
//!
//! For every scene of a fixed set and every configuration of a sweep (view steps, light steps,
//! step integral, phase model, Beer-Powder, octaves, jitter, shape texture) it renders the frame
//! on the GPU and measures
//!
//! * **error** against the CPU reference: the converged quadrature of the configuration's own
//!   model when it is single scattering (0 octaves), else the Monte Carlo path tracer with all
//!   scattering orders (the truth the octaves approximate); RMSE on linear radiance (rgb) and
//!   FLIP (mean) on the tone-mapped, composited images;
//! * **cost**: the GPU time of every pass (timestamp queries, median of repeats) and the work
//!   counters of the statistics variant per pixel (view steps, density evaluations, light
//!   samples; "samples per pixel" = density evaluations per pixel, view and light samples both).
//!
//! References are rendered once and cached by a hash of the scene (normalised: fields the
//! reference ignores are reset) and the reference settings, under `$XDG_CACHE_HOME/stratus`
//! or else `target/stratus-cache/` (relative to the working directory).
//!
//! Outputs in `--out`: `results.csv` (one row per scene and configuration, `pareto` = on the
//! scene's front of GPU time against FLIP), `results.json` (the same plus the run's settings;
//! `stratus render --max-error` reads it) and `chart.png` / `chart.svg` (FLIP against GPU time
//! per scene, front joined and named; the PNG has no text, the SVG names everything).

use std::{fmt::Write as _, path::PathBuf};

use anyhow::{Context, Result};
use clap::{Args, ValueEnum};
use indicatif::{ProgressBar, ProgressStyle};
use stratus_quality::{Config, Results};
use stratus_scene::Scene;

use stratus_tool::{
    backends::{self, Open, open},
    scene_io::parse_size,
};

mod chart;
mod reference_cache;
mod report;
mod sweep;

pub(crate) use self::{
    reference_cache::{
        COMMITTED_TRUTHS, CommittedTruth, Reference, committed_truth, decode as decode_truth,
        fresh_trace, read_index, recheck, reference, reference_key, write_index,
    },
    sweep::{display_errors, errors},
};

use self::{
    chart::chart,
    reference_cache::cache_dir,
    report::{mark_pareto, summary, write_csv},
    sweep::{MeasureSettings, SceneSweep, measure, sweep},
};

/// The GPU backend the bench times.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum BenchBackend {
    /// wgpu on Vulkan.
    Wgpu,
    /// Raw Vulkan (ash) with the committed SPIR-V.
    Ash,
}

/// Options of `stratus bench`.
#[derive(Args, Debug)]
pub struct BenchArgs {
    /// The GPU backend to time (both draw the same bits).
    #[arg(long, value_enum, default_value_t = BenchBackend::Wgpu)]
    backend: BenchBackend,
    /// Comma-separated presets or `stress-thick` (default: cumulus-noon, sunset,
    /// above-clouds, storm without --quick, and the stability case stress-thick).
    #[arg(long, value_delimiter = ',')]
    scenes: Option<Vec<String>>,
    /// Smaller and shorter: 64x36 images, 9 repeats, ~31 configurations a scene, no `storm`
    /// (about 20 minutes on lavapipe once the references are cached).
    #[arg(long)]
    quick: bool,
    /// Output directory.
    #[arg(long, default_value = "target/stratus-bench")]
    out: PathBuf,
    /// Image size (default 64x36 with --quick, else 128x72).
    #[arg(long, value_parser = parse_size)]
    size: Option<(u32, u32)>,
    /// Timed repeats per configuration (median reported; default 9 with --quick, else 15).
    #[arg(long)]
    repeats: Option<u32>,
    /// Paths per pixel of the all-orders references, rendered by the GPU path tracer on the
    /// bench's backend (default 512, as `stratus fit-scattering`, whose cached truths it
    /// shares; minutes a scene on lavapipe, cached).
    #[arg(long)]
    mc_spp: Option<u32>,
    /// Measure nothing: redraw chart.png and chart.svg from the results.json in --out.
    #[arg(long)]
    replot: bool,
    /// Render (or find in the cache) every reference the sweep needs and stop: no timing, no
    /// results. For a machine with a GPU, where the all-orders truths take seconds; the cache
    /// it fills (`$XDG_CACHE_HOME/stratus` or `target/stratus-cache`) then serves a bench run
    /// elsewhere (the key does not name the device).
    #[arg(long, conflicts_with = "replot")]
    references_only: bool,
    /// Measure only the cloud fields seen from above (`stratus measure-field`'s count, D and
    /// b) of the cumulus presets and the fair and broken weather states, write fields.csv
    /// and stop (about half a minute on lavapipe). A full run writes them too.
    #[arg(long, conflicts_with_all = ["replot", "references_only"])]
    fields_only: bool,
}

/// The cumulus presets whose fields the bench measures from above.
const FIELD_PRESETS: [&str; 3] = ["cumulus-noon", "sunset", "above-clouds"];
/// The weather states whose fields the bench measures (on the default scene).
const FIELD_STATES: [&str; 3] = ["few", "scattered", "broken"];

/// The cloud-field statistics (`stratus measure-field`'s defaults) of [`FIELD_PRESETS`] and
/// [`FIELD_STATES`] on `renderer`, printed and written to `out/fields.csv`.
fn fields(renderer: &mut dyn stratus_graph::Backend, out: &std::path::Path) -> Result<()> {
    let how = crate::measure_field::Measure::default();
    let mut scenes = Vec::new();
    for p in FIELD_PRESETS {
        scenes.push((p.to_string(), bench_scene(p)?));
    }
    for st in FIELD_STATES {
        let mut s = Scene::default();
        stratus_weather::states::find(st)
            .map_err(|e| anyhow::anyhow!("{e}"))?
            .params
            .apply(&mut s);
        scenes.push((format!("state {st}"), s));
    }
    let mut csv = String::from(
        "scene,cloud_fraction,clouds,cut,largest_m,d,d_stderr,b,b_stderr,b_from_m,b_to_m\n",
    );
    println!(
        "cloud fields from above ({:.0} m at {} px, cloud below transmittance {}):",
        how.extent_m, how.size, how.threshold
    );
    for (name, scene) in scenes {
        let (s, _, _) = crate::measure_field::measure(renderer, &scene, name.clone(), &how)?;
        let opt = |v: Option<f64>| v.map(|v| format!("{v:.3}")).unwrap_or_default();
        let _ = writeln!(
            csv,
            "{name},{:.3},{},{},{:.0},{},{},{},{},{},{}",
            s.cloud_fraction,
            s.clouds,
            s.cut,
            s.largest_m,
            opt(s.d.map(|d| d.slope)),
            opt(s.d.map(|d| d.stderr)),
            opt(s.b.map(|b| b.slope)),
            opt(s.b.map(|b| b.stderr)),
            s.b_range_m
                .map(|r| format!("{:.0}", r[0]))
                .unwrap_or_default(),
            s.b_range_m
                .map(|r| format!("{:.0}", r[1]))
                .unwrap_or_default(),
        );
        println!(
            "  {name:<16} fraction {:.3}, {:>3} clouds, D {}, b {}",
            s.cloud_fraction,
            s.clouds,
            s.d.map(|d| format!("{:.3} ± {:.3}", d.slope, d.stderr))
                .unwrap_or_else(|| "-".into()),
            s.b.map(|b| format!("{:.2} ± {:.2}", b.slope, b.stderr))
                .unwrap_or_else(|| "-".into()),
        );
    }
    std::fs::create_dir_all(out).with_context(|| format!("creating {}", out.display()))?;
    let path = out.join("fields.csv");
    stratus_compare::write_file_atomically(&path, csv.as_bytes())
        .with_context(|| format!("writing {}", path.display()))?;
    println!("wrote {}", path.display());
    Ok(())
}

/// A stability case charted next to the presets: `cumulus-noon` with ten times the
/// scattering coefficient and single scattering, so that a view step's optical depth is far
/// above 1 at the low step counts of the sweep. The Riemann sum overshoots there while the
/// analytic step integral stays bounded; the chart shows both.
pub const STRESS_THICK: &str = "stress-thick";

/// A preset, or the stability case [`STRESS_THICK`].
fn bench_scene(name: &str) -> Result<Scene> {
    if name == STRESS_THICK {
        let mut s = Scene::preset("cumulus-noon").map_err(|e| anyhow::anyhow!("{e}"))?;
        s.lighting.scattering *= 10.0;
        s.lighting.multiple_scattering.octaves = 0;
        return Ok(s);
    }
    Scene::preset(name).map_err(|e| anyhow::anyhow!("{e}"))
}

/// Runs `stratus bench`.
pub fn run(args: BenchArgs) -> Result<()> {
    if args.replot {
        let results = stratus_quality::Results::load(&args.out.join("results.json"))?;
        chart::chart(&args.out, &results)?;
        println!(
            "wrote {0}/chart.png, {0}/chart.svg from {0}/results.json",
            args.out.display()
        );
        return Ok(());
    }
    let scenes = args.scenes.clone().unwrap_or_else(|| {
        let mut v = vec!["cumulus-noon", "sunset", "above-clouds"];
        if !args.quick {
            v.push("storm");
        }
        v.push(STRESS_THICK);
        v.into_iter().map(String::from).collect()
    });
    let (w, h) = args
        .size
        .unwrap_or(if args.quick { (64, 36) } else { (128, 72) });
    let repeats = args
        .repeats
        .unwrap_or(if args.quick { 9 } else { 15 })
        .max(1);
    let mc_spp = args.mc_spp.unwrap_or(512).max(1);
    let backend = match args.backend {
        BenchBackend::Wgpu => backends::Backend::Wgpu,
        BenchBackend::Ash => backends::Backend::Ash,
    };
    // `wall`: time every pass by submitting it alone and waiting (see `sweep::measure`).
    let make = move |wall: bool| {
        open(
            backend,
            &Open {
                cpu_wall_timing: wall,
                ..Open::default()
            },
        )
    };
    let mut renderer = make(false)?;
    if args.fields_only {
        return fields(renderer.as_mut(), &args.out);
    }
    let device = renderer.describe();
    eprintln!(
        "bench on {device}: {w}x{h}, {repeats} repeats, references cached in {}",
        cache_dir().display()
    );

    let mut plan_scenes = Vec::new();
    for name in &scenes {
        let scene = bench_scene(name)?.with_size(w, h);
        let base = Config::of(&scene);
        let mut configs = sweep(&base, args.quick);
        if name == STRESS_THICK {
            // Single scattering only: its reference is the converged quadrature. An all-orders
            // path tracer in a medium this dense would take far too long for a sweep.
            configs.retain(|c| c.octaves == 0);
        }
        plan_scenes.push(SceneSweep {
            name: name.clone(),
            scene,
            configs,
            base,
        });
    }
    let total: usize = plan_scenes.iter().map(|p| p.configs.len()).sum();
    let bar = ProgressBar::new(total as u64);
    if let Ok(style) = ProgressStyle::with_template(
        "{msg:40} [{elapsed_precise}] {wide_bar} {pos}/{len} configurations",
    ) {
        bar.set_style(style);
    }

    let mut rows = measure(
        renderer.as_mut(),
        &make,
        &plan_scenes,
        MeasureSettings {
            repeats,
            mc_spp,
            references_only: args.references_only,
        },
        &bar,
    )?;
    bar.finish_and_clear();
    if args.references_only {
        println!(
            "every reference of the sweep ({total} configurations) is in {}",
            cache_dir().display()
        );
        return Ok(());
    }
    mark_pareto(&mut rows);

    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("creating {}", args.out.display()))?;
    let results = Results {
        device,
        backend: format!("{:?}", args.backend).to_lowercase(),
        size: [w, h],
        repeats,
        mc_spp,
        rows,
    };
    write_csv(&args.out.join("results.csv"), &results.rows)?;
    let json = args.out.join("results.json");
    stratus_compare::write_file_atomically(
        &json,
        (serde_json::to_string_pretty(&results)? + "\n").as_bytes(),
    )
    .with_context(|| format!("writing {}", json.display()))?;
    chart(&args.out, &results)?;
    summary(&results);
    fields(renderer.as_mut(), &args.out)?;
    println!(
        "wrote {0}/results.csv, {0}/results.json, {0}/chart.png, {0}/chart.svg",
        args.out.display()
    );
    Ok(())
}
