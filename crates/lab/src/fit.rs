//! `stratus fit-scattering`: fits the real-time march's multiple-scattering octaves (count, a,
//! b, c; Wrenninge 2013, as the Frostbite thesis uses them) to the all-orders truth of the
//! GPU path tracer over a training set of scenes, then measures the fit on held-out scenes it
//! never saw (the presets).
//!
//! Procedure: for every octave count, coordinate descent over a, b and c on a 0.05 grid (0.01
//! below 0.05) and the octaves' build-up with the sample's density
//! (`lighting.wgsl::octave_buildup`), the side light, the coverage exponent, the far
//! shadow's chord, the limb darkening, the forward lobe's strength and eccentricity, the
//! vertical anisotropy, the deck escape, the column above the sample in a deck (weight,
//! scale) and the downward dimming (`lighting.wgsl::sun_scattering`, `far_optical_depth`,
//! `diffuse_limb`, `forward_lobe`, `vertical_anisotropy`, `deck_escape`,
//! `octave_optical_depth`, `downward_dimming`) on grids of their own,
//! minimising the mean FLIP of the training scenes against their truths; the
//! fewest octaves whose mean is within 1% of the lowest win (each octave costs time in every
//! light sample). Wrenninge's a <= b is not imposed: it keeps thick clouds far too dark. Every
//! evaluated point is written to `evaluations.csv`, the per-scene errors before (the thesis's
//! 2 octaves of a = b = c = 0.5) and after to `scenes.csv`, and a summary to `README.md` in
//! `--out`.
//!
//! The truths are cached with the bench's references (the same key), so the bench reuses the
//! presets' truths and a rerun renders nothing it has already rendered.

use std::{collections::BTreeMap, fmt::Write as _, path::PathBuf, sync::Arc};

use anyhow::{Context, Result};
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use stratus_compare::Image;
use stratus_graph::{Backend, FrameInput, FrameOutput, FramePlan};
use stratus_noise::NoiseSet;
use stratus_reference::Compositor;
use stratus_scene::{MultipleScattering, Scene};

use stratus_tool::{
    backends::{self, Open, open},
    scene_io::parse_size,
};

use crate::bench;

/// Options of `stratus fit-scattering`.
#[derive(Args, Debug)]
pub struct FitArgs {
    /// Output directory for evaluations.csv, scenes.csv and README.md [default: docs/fit, or
    /// target/fit-evaluate with --evaluate, which leaves the committed fit alone].
    #[arg(long)]
    out: Option<PathBuf>,
    /// Image size of the truths and the renders.
    #[arg(long, value_parser = parse_size, default_value = "64x36")]
    size: (u32, u32),
    /// Paths per pixel of each truth (GPU path tracer; whole frames of its paths per frame).
    #[arg(long, default_value_t = 512)]
    spp: u32,
    /// Octave counts to try (comma-separated).
    #[arg(long, value_delimiter = ',', default_value = "1,2,3,4,6,8")]
    octaves: Vec<u32>,
    /// One descent per octave count, from the current defaults (with that count), instead of
    /// one from each of a few starting points: a refit after a small change to the model, in
    /// about a third of the evaluations.
    #[arg(long)]
    quick: bool,
    /// Fit nothing: measure the current defaults (with each --octaves count) against the
    /// truths, training scenes and presets alike; "after" in the outputs is the defaults (with
    /// the count a fit would take: the fewest within 1% of the best). For a changed truth or a
    /// new scene, before deciding to refit.
    #[arg(long)]
    evaluate: bool,
    /// With --evaluate, only these scenes (comma-separated: presets, weather states as
    /// `weather-NAME`, cloud types' scenes (`scenes/types/NAME.toml`) as `type-NAME`, layered
    /// scenes (`scenes/layers/NAME.toml`) as `layers-NAME`, or
    /// training scenes by the names of their images, e.g. `storm-deck-sun-25-deg`): their
    /// truths alone are rendered (or loaded) and measured. A truth of 8192 paths a pixel takes 10-30 minutes a scene on
    /// lavapipe; this renders the ones a question needs.
    #[arg(long, value_delimiter = ',', requires = "evaluate")]
    scenes: Vec<String>,
    /// Render no truth: measure FLIP against the truths' display images in DIR/images (a
    /// fit's panels, the truth leftmost, as `--out DIR` wrote them). They are exactly what the
    /// fit compares for a change to the light model alone: the panel's truth went through
    /// the air in front of the march's depth, which the density alone sets. For trying a
    /// change on a machine where the truths would take hours (lavapipe: 10-30 minutes a
    /// scene); RMSE and brightness, which need the truths' radiance, are left out. A scene
    /// with no panel there (a training scene added since) takes its truth from the cache,
    /// the committed truths or the path tracer, as without the flag.
    #[arg(long, value_name = "DIR")]
    display_truths: Option<PathBuf>,
    /// Change a constant of the defaults before measuring (--evaluate) or descending from them
    /// (--quick): NAME=VALUE, NAME a field of a scene file's `[lighting.multiple_scattering]`
    /// (e.g. `limb_darkening=0.5`); repeatable. For trying a constant without a rebuild.
    #[arg(long = "set", value_name = "NAME=VALUE")]
    set: Vec<String>,
    /// With --quick: descend over these constants alone (comma-separated names as for --set,
    /// e.g. `steep_light,steep_light_scale`), the others held: a new term fitted without
    /// moving the rest.
    #[arg(long, value_delimiter = ',', value_name = "NAMES", requires = "quick")]
    only: Vec<String>,
    /// With --evaluate: measure against the committed truths alone (`docs/fit/truths`, each
    /// scene's at the paths per pixel its `index.csv` row records; `--spp` is not used) and
    /// render none. A scene without a truth for this build's path tracer is an error saying
    /// what to run. Seconds, on any machine: what CI holds the presets to.
    #[arg(long, requires = "evaluate", conflicts_with = "display_truths")]
    committed: bool,
    /// Carry the committed truths (`docs/fit/truths`) over to this build's path tracer: a
    /// truth whose key is not this build's (the tracer's code, its noise or the scene's
    /// uniforms changed since it was traced) is compared with a fresh trace of
    /// `--recheck-spp` paths a pixel, per 8x8 block (|z| < 4) and pooled over the cloudy
    /// blocks (|z| < 3); where it agrees it is filed under the new key, else the command
    /// fails naming the truths to render again. About 10 s a truth on lavapipe at 128 paths.
    #[arg(long, conflicts_with_all = ["evaluate", "quick", "display_truths", "committed"])]
    recheck_truths: bool,
    /// Paths per pixel of `--recheck-truths`' fresh traces.
    #[arg(long, default_value_t = 128, value_parser = clap::value_parser!(u32).range(2..))]
    recheck_spp: u32,
}

/// The constants the descent moves, in its order (fields of `[lighting.multiple_scattering]`).
const DESCENT_NAMES: [&str; 15] = [
    "a",
    "b",
    "c",
    "buildup_m",
    "side_light",
    "coverage_exponent",
    "far_chord_m",
    "limb_darkening",
    "forward_lobe",
    "forward_lobe_g",
    "vertical_anisotropy",
    "deck_escape",
    "steep_light",
    "steep_light_scale",
    "downward_dimming",
];

/// Sets the descent's constant `which` (the index of its name in `DESCENT_NAMES`) of `m` to
/// `v`.
fn set_constant(m: &mut MultipleScattering, which: usize, v: f64) {
    match which {
        0 => m.a = v,
        1 => m.b = v,
        2 => m.c = v,
        3 => m.buildup_m = v,
        4 => m.side_light = v,
        5 => m.coverage_exponent = v,
        6 => m.far_chord_m = v,
        7 => m.limb_darkening = v,
        8 => m.forward_lobe = v,
        9 => m.forward_lobe_g = v,
        10 => m.vertical_anisotropy = v,
        11 => m.deck_escape = v,
        12 => m.steep_light = v,
        13 => m.steep_light_scale = v,
        _ => m.downward_dimming = v,
    }
}

/// Which of the descent's constants `only` names (all where it is empty); an unknown name is
/// an error that lists them.
fn descent_mask(only: &[String]) -> Result<[bool; 15]> {
    if only.is_empty() {
        return Ok([true; 15]);
    }
    let mut mask = [false; 15];
    for name in only {
        let Some(i) = DESCENT_NAMES.iter().position(|&n| n == name.trim()) else {
            anyhow::bail!(
                "--only {name}: not a constant the fit descends over (those are: {})",
                DESCENT_NAMES.join(", ")
            );
        };
        mask[i] = true;
    }
    Ok(mask)
}

/// The defaults with `sets` (`NAME=VALUE`, fields of `[lighting.multiple_scattering]`)
/// changed, checked as a scene file's would be.
fn with_sets(sets: &[String]) -> Result<MultipleScattering> {
    let base = MultipleScattering::default();
    if sets.is_empty() {
        return Ok(base);
    }
    let mut table = toml::Table::try_from(base).context("the defaults as TOML")?;
    for set in sets {
        let Some((name, value)) = set.split_once('=') else {
            anyhow::bail!("--set {set}: expected NAME=VALUE, e.g. limb_darkening=0.5");
        };
        let name = name.trim();
        if !table.contains_key(name) {
            anyhow::bail!(
                "--set {set}: `{name}` is not a field of [lighting.multiple_scattering] (those are: {})",
                table.keys().cloned().collect::<Vec<_>>().join(", ")
            );
        }
        let parsed: toml::Table = format!("v = {}", value.trim())
            .parse()
            .with_context(|| format!("--set {set}: `{}` is not a TOML value", value.trim()))?;
        table.insert(name.to_string(), parsed["v"].clone());
    }
    let ms: MultipleScattering = table
        .try_into()
        .with_context(|| format!("--set {}", sets.join(" --set ")))?;
    let mut scene = Scene::default();
    scene.lighting.multiple_scattering = ms;
    scene
        .validate()
        .map_err(|e| anyhow::anyhow!("--set {}: {e}", sets.join(" --set ")))?;
    Ok(ms)
}

include!(concat!(env!("OUT_DIR"), "/training_scenes.rs"));

/// The training scenes: variants of the presets under other suns and views, none of them a
/// preset (the presets are held out). Each is a partial scene file in `scenes/fit/` (embedded
/// at build time), named by its `description`, in file-name order.
fn training_scenes() -> Result<Vec<(String, Scene)>> {
    if TRAINING_SCENES.is_empty() {
        anyhow::bail!("no training scenes were embedded (scenes/fit/*.toml)");
    }
    TRAINING_SCENES
        .iter()
        .map(|(file, text)| {
            let origin = format!("scenes/fit/{file}");
            let name = text
                .parse::<toml::Table>()
                .ok()
                .and_then(|t| t.get("description")?.as_str().map(str::to_string))
                .with_context(|| {
                    format!("{origin}: a training scene needs a `description`, its name")
                })?;
            let scene = Scene::from_toml_str(text, &origin).map_err(|e| anyhow::anyhow!("{e}"))?;
            Ok((name, scene))
        })
        .collect()
}

/// The scenes the fit never trains on: the presets, by their names, the weather states on
/// the default scene (`stratus weather --state NAME`), as `weather NAME`, the cloud types'
/// scenes (`scenes/types/NAME.toml`, partial scene files embedded at build time), as `type
/// NAME`, and the layered scenes (`scenes/layers/NAME.toml`), as `layers NAME`.
fn held_out_scenes() -> Result<Vec<(String, Scene)>> {
    let mut out: Vec<(String, Scene)> = stratus_scene::presets()
        .iter()
        .map(|p| {
            Scene::preset(p.name)
                .map(|s| (p.name.to_string(), s))
                .map_err(|e| anyhow::anyhow!("{e}"))
        })
        .collect::<Result<_>>()?;
    for state in &stratus_weather::states::STATES {
        let mut scene = Scene::default();
        state.params.apply(&mut scene);
        out.push((format!("weather {}", state.name), scene));
    }
    for (folder, label, scenes) in [
        ("types", "type", TYPE_SCENES),
        ("layers", "layers", LAYER_SCENES),
    ] {
        for (file, text) in scenes {
            let origin = format!("scenes/{folder}/{file}");
            let scene = Scene::from_toml_str(text, &origin).map_err(|e| anyhow::anyhow!("{e}"))?;
            out.push((format!("{label} {}", file.trim_end_matches(".toml")), scene));
        }
    }
    Ok(out)
}

/// The training scenes and presets that `--scenes` names (all of them when it names none); an
/// error for a name that is neither.
type Named = Vec<(String, Scene)>;
fn only(names: &[String], training: Named, presets: Named) -> Result<(Named, Named)> {
    if names.is_empty() {
        return Ok((training, presets));
    }
    for n in names {
        if !training
            .iter()
            .chain(&presets)
            .any(|(name, _)| slug(name) == *n)
        {
            let known: Vec<String> = training
                .iter()
                .chain(&presets)
                .map(|(n, _)| slug(n))
                .collect();
            anyhow::bail!("--scenes: no scene `{n}` (known: {})", known.join(", "));
        }
    }
    let keep = |list: Named| -> Named {
        list.into_iter()
            .filter(|(name, _)| names.contains(&slug(name)))
            .collect()
    };
    Ok((keep(training), keep(presets)))
}

/// Copies the truths the fit measured against into `dir` (for `--out docs/fit`, the committed
/// truths the bench and the fit read where their cache lacks one) with `index.csv`, which
/// names each file's scene.
fn write_truths(dir: &std::path::Path, train: &[Case], test: &[Case], spp: u32) -> Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    // A run that measured some scenes against their display images (`--display-truths`)
    // rendered no truth for them: the truths already there stay, and so do their rows.
    let written: Vec<std::ffi::OsString> = train
        .iter()
        .chain(test)
        .filter_map(|c| c.truth_file.as_ref()?.file_name().map(|n| n.to_os_string()))
        .collect();
    let mut index: Vec<bench::CommittedTruth> = match bench::read_index(dir) {
        Ok(rows) => rows
            .into_iter()
            .filter(|r| {
                dir.join(&r.file).exists() && !written.iter().any(|w| w.to_str() == Some(&r.file))
            })
            .collect(),
        Err(_) => Vec::new(),
    };
    for (set, list) in [("train", train), ("held-out", test)] {
        for c in list {
            let Some(file) = &c.truth_file else {
                continue;
            };
            let name = file
                .file_name()
                .context("a truth's cache file has no name")?;
            let to = dir.join(name);
            if to != *file {
                let bytes =
                    std::fs::read(file).with_context(|| format!("reading {}", file.display()))?;
                stratus_compare::write_file_atomically(&to, &bytes)
                    .with_context(|| format!("writing {}", to.display()))?;
            }
            index.push(bench::CommittedTruth {
                file: name.to_string_lossy().into_owned(),
                scene: c.name.clone(),
                set: set.to_string(),
                paths: spp,
                width: c.truth.width,
                height: c.truth.height,
            });
        }
    }
    bench::write_index(dir, &index)
}

/// The renderer the truths are traced and the fit measured on: the GPU path tracer on wgpu's
/// Vulkan backend, without validation (thousands of frames).
fn open_tracer() -> Result<Box<dyn Backend>> {
    open(
        backends::Backend::Wgpu,
        &Open {
            validation: false,
            ..Open::default()
        },
    )
}

/// `--recheck-truths`: every committed truth whose key is not this build's is traced afresh
/// with `paths` a pixel and, where the two agree within noise, filed under the new key.
fn recheck_truths(paths: u32) -> Result<()> {
    let dir = PathBuf::from(bench::COMMITTED_TRUTHS);
    let mut rows = bench::read_index(&dir)?;
    let mut renderer = open_tracer()?;
    eprintln!(
        "rechecking {} truths in {} on {} with {paths} paths a pixel",
        rows.len(),
        dir.display(),
        renderer.describe()
    );
    let scenes: Vec<(String, Scene)> = training_scenes()?
        .into_iter()
        .chain(held_out_scenes()?)
        .collect();
    let mut fresh: BTreeMap<String, FrameOutput> = BTreeMap::new();
    let mut differ = Vec::new();
    // The index is written after every truth filed anew, so that a run cut short (an error,
    // an interrupt) keeps what it checked and a rerun goes on from there.
    for i in 0..rows.len() {
        let row = rows[i].clone();
        let (_, scene) = scenes
            .iter()
            .find(|(n, _)| *n == row.scene)
            .with_context(|| {
                format!(
                    "{}/index.csv: `{}` is neither a training scene nor a preset",
                    dir.display(),
                    row.scene
                )
            })?;
        let scene = scene.clone().with_size(row.width, row.height);
        let noise = Arc::new(stratus::noise_for(&scene));
        let key = bench::reference_key(&scene, &noise, row.paths, true)?;
        if key.file_name() == row.file {
            println!("{} ({} paths): current", row.scene, row.paths);
            continue;
        }
        // A file under this build's key is written only by this command after its check
        // passed (in a run cut short before its index was written) or traced by this build:
        // either way this build's truth.
        if dir.join(key.file_name()).is_file() {
            println!(
                "{} ({} paths): already filed under this build's key",
                row.scene, row.paths
            );
            rows[i].file = key.file_name();
            bench::write_index(&dir, &rows)?;
            continue;
        }
        let old_path = dir.join(&row.file);
        let bytes =
            std::fs::read(&old_path).with_context(|| format!("reading {}", old_path.display()))?;
        let truth = bench::decode_truth(&bytes, row.width, row.height).with_context(|| {
            format!(
                "{}: not a {}x{} truth",
                old_path.display(),
                row.width,
                row.height
            )
        })?;
        if !fresh.contains_key(&row.scene) {
            let f = bench::fresh_trace(renderer.as_mut(), &scene, &noise, paths)?;
            fresh.insert(row.scene.clone(), f);
        }
        let r = bench::recheck(&truth, row.paths, &fresh[&row.scene])
            .with_context(|| format!("rechecking `{}` ({} paths)", row.scene, row.paths))?;
        let verdict = if r.agrees() {
            "carried over"
        } else {
            "DIFFERS"
        };
        println!(
            "{} ({} paths): {verdict}: {} blocks, worst |z| {:.2}, pooled z {:+.2} (fresh - truth {:+.2}%; a uniform {:.2}% would show)",
            row.scene,
            row.paths,
            r.blocks,
            r.worst_block_z,
            r.pooled_z,
            100.0 * r.relative,
            100.0 * r.detectable
        );
        if r.agrees() {
            let to = dir.join(key.file_name());
            stratus_compare::write_file_atomically(&to, &bytes)
                .with_context(|| format!("writing {}", to.display()))?;
            rows[i].file = key.file_name();
            bench::write_index(&dir, &rows)?;
        } else {
            differ.push(format!("{} ({} paths)", row.scene, row.paths));
        }
    }
    // Every truth file the index no longer names (carried-over truths' old keys) goes.
    for entry in std::fs::read_dir(&dir).with_context(|| format!("listing {}", dir.display()))? {
        let name = entry?.file_name().to_string_lossy().into_owned();
        if name.starts_with("ref-")
            && name.ends_with(".bin")
            && !rows.iter().any(|r| r.file == name)
        {
            std::fs::remove_file(dir.join(&name))
                .with_context(|| format!("removing {}", dir.join(&name).display()))?;
        }
    }
    if !differ.is_empty() {
        anyhow::bail!(
            "{} truths differ from a fresh trace and keep their old keys: {}; render them again (stratus fit-scattering --evaluate --scenes NAME --spp N --out docs/fit)",
            differ.len(),
            differ.join(", ")
        );
    }
    Ok(())
}

/// A scene to measure: its truth and the real-time render's settings.
struct Case {
    name: String,
    scene: Scene,
    noise: Arc<NoiseSet>,
    truth: FrameOutput,
    /// The truth's file in the reference cache (copied to `--out`/truths); none with
    /// `--display-truths`.
    truth_file: Option<PathBuf>,
    /// With `--display-truths`: `truth` is its display image alone (no radiance), which FLIP
    /// compares as it is.
    display_only: bool,
    /// The scene's composite on the CPU, which makes the display images the fit compares.
    display: Compositor,
}

/// FLIP (mean, display images) and RMSE (linear radiance) of `frame` against the truth of
/// `case` (both display images composited on the CPU: [`bench::errors`]).
fn errors(case: &Case, frame: &FrameOutput) -> Result<(f64, f64)> {
    let e = if case.display_only {
        let t = &case.truth;
        let truth = Image::from_display_rgba8(t.width, t.height, &t.image);
        bench::display_errors(&truth, frame, &case.display)?
    } else {
        bench::errors(&case.truth, frame, &case.display)?
    };
    Ok((e.flip, e.rmse))
}

/// The pixels of a fit's panels (`images/`) per image pixel, across and down.
const PANEL_ZOOM: u32 = 4;

/// The panel of scene `name` in a fit's output `dir`.
fn panel_path(dir: &std::path::Path, name: &str) -> PathBuf {
    dir.join("images").join(format!("{}.png", slug(name)))
}

/// The truth's display image of `name` from a fit's panel in `dir/images` (`side_by_side`:
/// the truth leftmost, each pixel a `PANEL_ZOOM` square), `w` x `h` pixels.
fn display_truth(dir: &std::path::Path, name: &str, w: u32, h: u32) -> Result<Vec<u8>> {
    let path = panel_path(dir, name);
    let panel = image::open(&path)
        .with_context(|| format!("reading the truth's panel {}", path.display()))?
        .to_rgba8();
    let zoom = PANEL_ZOOM;
    if panel.height() != zoom * h || panel.width() < zoom * w {
        anyhow::bail!(
            "{}: a {}x{} panel is not a fit's panel of {w}x{h} images (--size)",
            path.display(),
            panel.width(),
            panel.height()
        );
    }
    let mut out = Vec::with_capacity((4 * w * h) as usize);
    for y in 0..h {
        for x in 0..w {
            out.extend_from_slice(&panel.get_pixel(x * zoom, y * zoom).0);
        }
    }
    Ok(out)
}

/// The render's mean in-scattered luminance over the truth's, in bins of the truth's
/// transmittance (dense: below 0.05, middle, thin: 0.5 to 0.99); NaN where a bin is empty.
fn brightness(truth: &FrameOutput, frame: &FrameOutput) -> [f64; 3] {
    let mut sums = [[0.0f64; 2]; 3];
    for i in 0..(truth.width * truth.height) as usize {
        let t = truth.radiance[4 * i + 3];
        let bin = match t {
            t if t < 0.05 => 0,
            t if t < 0.5 => 1,
            t if t < 0.99 => 2,
            _ => continue,
        };
        sums[bin][0] += frame.luminance(i);
        sums[bin][1] += truth.luminance(i);
    }
    sums.map(|[r, t]| if t > 0.0 { r / t } else { f64::NAN })
}

/// The real-time frame of `case` with octaves `ms`.
fn render(r: &mut dyn Backend, case: &Case, ms: MultipleScattering) -> Result<FrameOutput> {
    let mut s = case.scene.clone();
    s.lighting.multiple_scattering = ms;
    let plan = FramePlan::for_scene(&s, false)?;
    r.render(&FrameInput::new(&plan, &s, &case.noise))
        .map_err(|e| anyhow::anyhow!("{e}"))
}

/// The fit's objective over `cases` with octaves `ms`, the mean FLIP, and each case's (FLIP,
/// RMSE). (The mean plus the worst was tried: it fitted 0.01-0.02 worse on 5 of the 6 presets
/// and better only on `sunset`.)
fn evaluate(
    r: &mut dyn Backend,
    cases: &[Case],
    ms: MultipleScattering,
) -> Result<(f64, Vec<(f64, f64)>)> {
    let mut per = Vec::new();
    for c in cases {
        per.push(errors(c, &render(r, c, ms)?)?);
    }
    let mean = per.iter().map(|e| e.0).sum::<f64>() / per.len().max(1) as f64;
    Ok((mean, per))
}

/// The grid over (0, `max`]: 0.05 steps, and 0.01 steps below 0.05 (the fitted extinction
/// factor has lain there).
fn grid(max: f64) -> Vec<f64> {
    let steps = (max / 0.05).round() as u32;
    [0.01, 0.02, 0.03, 0.04]
        .into_iter()
        .chain((1..=steps).map(|i| f64::from(i) * 0.05))
        .collect()
}

/// The build-up lengths tried (metres): at the default scattering coefficient (0.04 per metre)
/// 25 m makes a sample of density 0.5 get 39% of the octaves, 400 m all of them.
const BUILDUP_GRID_M: [f64; 12] = [
    0.0, 25.0, 50.0, 75.0, 100.0, 150.0, 200.0, 300.0, 400.0, 600.0, 800.0, 1000.0,
];

/// The side lights tried (`MultipleScattering::side_light`; 0: the octaves fed through the
/// layer's top alone).
const SIDE_LIGHT_GRID: [f64; 9] = [0.0, 0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 2.0, 3.0];

/// The coverage exponents tried (0: the octaves not scaled by the weather map's coverage).
const COVERAGE_EXPONENT_GRID: [f64; 9] = [0.0, 0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 2.0, 3.0];

/// The far shadow's chords tried (metres; 0: off).
const FAR_CHORD_GRID_M: [f64; 7] = [0.0, 2000.0, 4000.0, 8000.0, 16000.0, 32000.0, 64000.0];

/// The limb darkenings tried (`MultipleScattering::limb_darkening`; 0: isotropic octaves,
/// 1.5: the Eddington approximation's).
const LIMB_GRID: [f64; 8] = [0.0, 0.25, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0];

/// The forward lobe's strengths tried (`MultipleScattering::forward_lobe`; 0: off).
const FORWARD_LOBE_GRID: [f64; 9] = [0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.8, 1.0];

/// The forward lobe's eccentricities tried (`MultipleScattering::forward_lobe_g`).
const FORWARD_LOBE_G_GRID: [f64; 8] = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8];

/// The vertical anisotropies tried (`MultipleScattering::vertical_anisotropy`; 0: off).
const VERTICAL_ANISOTROPY_GRID: [f64; 9] = [0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.8, 1.0];

/// The deck escapes tried (`MultipleScattering::deck_escape`; 0: off; the Eddington
/// approximation's 6/7 lies between 0.75 and 1; 2 is the valid range's top).
const DECK_ESCAPE_GRID: [f64; 9] = [0.0, 0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 1.75, 2.0];

/// The deck column's weights tried (`MultipleScattering::steep_light`; 0: off, 1: the column
/// alone).
const STEEP_LIGHT_GRID: [f64; 8] = [0.0, 0.2, 0.4, 0.5, 0.6, 0.7, 0.8, 1.0];

/// The deck column's scales tried (`MultipleScattering::steep_light_scale`; a slab's diffusivity
/// factor, 1.66, lies between 1.6 and 1.7).
const STEEP_LIGHT_SCALE_GRID: [f64; 8] = [1.0, 1.2, 1.4, 1.5, 1.6, 1.7, 1.8, 2.0];

/// The downward dimmings tried (`MultipleScattering::downward_dimming`; 0: off).
const DOWNWARD_DIMMING_GRID: [f64; 10] = [0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0];

/// Build-ups (metres) the descent starts from.
const DESCENT_STARTS_M: [f64; 3] = [0.0, 100.0, 400.0];

/// Coordinate descent over a, b, c, the build-up, the side light, the coverage exponent, the
/// far shadow's chord, the limb darkening, the forward lobe (strength, eccentricity), the
/// vertical anisotropy, the deck escape, the deck's column (weight, scale) and the
/// downward dimming for
/// `octaves`, from a = b = c = 0.5, the later terms off and each of
/// a few build-ups (the descent alone stalled at a build-up of 600 m, 2% worse than
/// the 300 m it missed), or with `quick` from the given start (the defaults, or `--set`'s)
/// alone: each pass tries every grid value of one constant with the others held (only the
/// constants `moves` marks), until a pass changes nothing (at most `rounds` passes; 0
/// evaluates the start alone); the best start wins.
#[allow(clippy::too_many_arguments)]
fn descend(
    r: &mut dyn Backend,
    cases: &[Case],
    octaves: u32,
    quick: Option<MultipleScattering>,
    moves: [bool; 15],
    rounds: usize,
    log: &mut Vec<(MultipleScattering, f64)>,
    bar: &ProgressBar,
) -> Result<(MultipleScattering, f64)> {
    type Key = [u32; 15];
    let mut cache: BTreeMap<Key, f64> = BTreeMap::new();
    let key = |m: &MultipleScattering| -> Key {
        let q = |v: f64| (v * 100.0).round() as u32;
        [
            q(m.a),
            q(m.b),
            q(m.c),
            m.buildup_m.round() as u32,
            q(m.side_light),
            q(m.coverage_exponent),
            m.far_chord_m.round() as u32,
            q(m.limb_darkening),
            q(m.forward_lobe),
            q(m.forward_lobe_g),
            q(m.vertical_anisotropy),
            q(m.deck_escape),
            q(m.steep_light),
            q(m.steep_light_scale),
            q(m.downward_dimming),
        ]
    };
    let mut score =
        |m: MultipleScattering, log: &mut Vec<(MultipleScattering, f64)>| -> Result<f64> {
            if let Some(&v) = cache.get(&key(&m)) {
                return Ok(v);
            }
            let (mean, _) = evaluate(r, cases, m)?;
            cache.insert(key(&m), mean);
            log.push((m, mean));
            bar.inc(1);
            Ok(mean)
        };
    let starts: Vec<MultipleScattering> = if let Some(defaults) = quick {
        vec![MultipleScattering {
            octaves,
            ..defaults
        }]
    } else {
        DESCENT_STARTS_M
            .iter()
            .map(|&start| MultipleScattering {
                octaves,
                a: 0.5,
                b: 0.5,
                c: 0.5,
                buildup_m: start,
                side_light: 0.0,
                coverage_exponent: 0.0,
                far_chord_m: 0.0,
                limb_darkening: 0.0,
                forward_lobe: 0.0,
                forward_lobe_g: 0.5,
                vertical_anisotropy: 0.0,
                deck_escape: 0.0,
                steep_light: 0.0,
                steep_light_scale: MultipleScattering::default().steep_light_scale,
                downward_dimming: 0.0,
            })
            .collect()
    };
    let mut overall: Option<(MultipleScattering, f64)> = None;
    for start in starts {
        let mut best = start;
        let mut best_score = score(best, log)?;
        for _round in 0..rounds {
            let mut changed = false;
            for which in (0..15).filter(|&i| moves[i]) {
                // a may exceed 1 (validate.rs says why); b and c are factors of at most 1.
                let values = match which {
                    0 => grid(stratus_scene::MAX_OCTAVE_A),
                    3 => BUILDUP_GRID_M.to_vec(),
                    4 => SIDE_LIGHT_GRID.to_vec(),
                    5 => COVERAGE_EXPONENT_GRID.to_vec(),
                    6 => FAR_CHORD_GRID_M.to_vec(),
                    7 => LIMB_GRID.to_vec(),
                    8 => FORWARD_LOBE_GRID.to_vec(),
                    9 => FORWARD_LOBE_G_GRID.to_vec(),
                    10 => VERTICAL_ANISOTROPY_GRID.to_vec(),
                    11 => DECK_ESCAPE_GRID.to_vec(),
                    12 => STEEP_LIGHT_GRID.to_vec(),
                    13 => STEEP_LIGHT_SCALE_GRID.to_vec(),
                    14 => DOWNWARD_DIMMING_GRID.to_vec(),
                    _ => grid(1.0),
                };
                for v in values {
                    let mut m = best;
                    set_constant(&mut m, which, v);
                    let s = score(m, log)?;
                    if s < best_score - 1e-9 {
                        best = m;
                        best_score = s;
                        changed = true;
                    }
                }
            }
            if !changed {
                break;
            }
        }
        if overall.is_none_or(|o| best_score < o.1 - 1e-9) {
            overall = Some((best, best_score));
        }
    }
    let (best, best_score) = overall.context("no descent start")?;
    bar.set_message(format!(
        "{octaves} octaves: {}, mean FLIP {best_score:.4}",
        describe(&best)
    ));
    Ok((best, best_score))
}

/// The constants of `m` in a line.
fn describe(m: &MultipleScattering) -> String {
    format!(
        "a {:.2} b {:.2} c {:.2} build-up {} m side light {:.2} coverage exponent {:.2} far chord {} m limb darkening {:.2} forward lobe {:.2} (g {:.2}) vertical anisotropy {:.2} deck escape {:.2} deck column {:.2} (scale {:.2}) downward dimming {:.2}",
        m.a,
        m.b,
        m.c,
        m.buildup_m,
        m.side_light,
        m.coverage_exponent,
        m.far_chord_m,
        m.limb_darkening,
        m.forward_lobe,
        m.forward_lobe_g,
        m.vertical_anisotropy,
        m.deck_escape,
        m.steep_light,
        m.steep_light_scale,
        m.downward_dimming
    )
}

/// A file name for a scene's name: lower-case letters and digits, runs of anything else one `-`.
fn slug(name: &str) -> String {
    let mut out = String::new();
    for ch in name.chars() {
        if ch.is_ascii_alphanumeric() {
            out.push(ch.to_ascii_lowercase());
        } else if !out.ends_with('-') {
            out.push('-');
        }
    }
    out.trim_matches('-').to_string()
}

/// The display images of `frames` left to right, each magnified `zoom` times (nearest texel:
/// the fit's images are small, and their pixels are what is compared), 2 black pixels apart.
fn side_by_side(frames: &[FrameOutput], zoom: u32) -> image::RgbaImage {
    const GAP: u32 = 2;
    let (w, h) = (frames[0].width * zoom, frames[0].height * zoom);
    let n = frames.len() as u32;
    let mut out =
        image::RgbaImage::from_pixel(n * w + (n - 1) * GAP, h, image::Rgba([0, 0, 0, 255]));
    for (k, f) in frames.iter().enumerate() {
        let x0 = k as u32 * (w + GAP);
        for y in 0..h {
            for x in 0..w {
                let i = (((y / zoom) * f.width + x / zoom) * 4) as usize;
                let px = [f.image[i], f.image[i + 1], f.image[i + 2], 255];
                out.put_pixel(x0 + x, y, image::Rgba(px));
            }
        }
    }
    out
}

/// Runs `stratus fit-scattering`.
pub fn run(args: FitArgs) -> Result<()> {
    if args.recheck_truths {
        return recheck_truths(args.recheck_spp);
    }
    let out_dir = args.out.clone().unwrap_or_else(|| {
        PathBuf::from(if args.evaluate {
            "target/fit-evaluate"
        } else {
            "docs/fit"
        })
    });
    if let Some(dir) = &args.display_truths {
        // The panels written there would replace the truths' images the run read.
        let same =
            |a: &std::path::Path, b: &std::path::Path| match (a.canonicalize(), b.canonicalize()) {
                (Ok(a), Ok(b)) => a == b,
                _ => a == b,
            };
        if same(dir, &out_dir) {
            anyhow::bail!(
                "--display-truths {} is --out as well: write this run elsewhere (--out)",
                dir.display()
            );
        }
    }
    if !(args.set.is_empty() || args.quick || args.evaluate) {
        anyhow::bail!(
            "--set changes the start of a --quick descent or what --evaluate measures; add one"
        );
    }
    let defaults = with_sets(&args.set)?;
    let moves = descent_mask(&args.only)?;
    let (w, h) = args.size;
    let mut renderer = open_tracer()?;
    eprintln!(
        "fit on {}: {w}x{h}, truths of {} paths per pixel (GPU path tracer)",
        renderer.describe(),
        args.spp
    );
    let held_out = held_out_scenes()?;
    let mut cases = |list: Vec<(String, Scene)>| -> Result<Vec<Case>> {
        let mut out = Vec::new();
        for (name, scene) in list {
            let scene = scene.with_size(w, h);
            let noise = Arc::new(stratus::noise_for(&scene));
            eprintln!("truth: {name}");
            let display = Compositor::new(&scene, &noise);
            // A scene without a panel there (a training scene added since that fit) takes
            // its truth as the run without the flag would.
            let panel = args
                .display_truths
                .as_ref()
                .filter(|dir| panel_path(dir, &name).exists());
            if let Some(dir) = panel {
                let image = display_truth(dir, &name, w, h)?;
                out.push(Case {
                    name,
                    scene,
                    noise,
                    truth: FrameOutput {
                        width: w,
                        height: h,
                        image,
                        ..Default::default()
                    },
                    truth_file: None,
                    display_only: true,
                    display,
                });
                continue;
            }
            if args.committed {
                let dir = std::path::Path::new(bench::COMMITTED_TRUTHS);
                let truth = bench::committed_truth(dir, &name, &scene, &noise)
                    .with_context(|| format!("--committed: scene `{}`", slug(&name)))?;
                out.push(Case {
                    name,
                    scene,
                    noise,
                    truth,
                    truth_file: None,
                    display_only: false,
                    display,
                });
                continue;
            }
            let bench::Reference {
                frame: truth, file, ..
            } = bench::reference(&scene, &noise, args.spp, Some(renderer.as_mut()))?;
            out.push(Case {
                name,
                scene,
                noise,
                truth,
                truth_file: Some(file),
                display_only: false,
                display,
            });
        }
        Ok(out)
    };
    let (training, held_out) = only(&args.scenes, training_scenes()?, held_out)?;
    let train = cases(training)?;
    let test = cases(held_out)?;

    let bar = ProgressBar::new_spinner();
    if let Ok(style) =
        ProgressStyle::with_template("{spinner} [{elapsed_precise}] {pos} evaluations {msg}")
    {
        bar.set_style(style);
    }
    let mut log = Vec::new();
    let mut per_count = Vec::new();
    for &n in &args.octaves {
        per_count.push(descend(
            renderer.as_mut(),
            &train,
            n,
            (args.quick || args.evaluate).then_some(defaults),
            moves,
            if args.evaluate { 0 } else { 6 },
            &mut log,
            &bar,
        )?);
    }
    bar.finish_and_clear();
    // Each octave costs time in every light sample: the fewest octaves whose mean FLIP is
    // within 1% of the best count's.
    let lowest = per_count.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
    let (fit, _) = per_count
        .iter()
        .filter(|p| p.1 <= lowest * 1.01)
        .min_by_key(|p| p.0.octaves)
        .copied()
        .context("--octaves names no count")?;
    // Before: the thesis's constants (the defaults until this fit).
    let before = stratus_quality::PREFIT_OCTAVES;

    std::fs::create_dir_all(&out_dir).with_context(|| format!("creating {}", out_dir.display()))?;
    let mut csv = String::from(
        "octaves,a,b,c,buildup_m,side_light,coverage_exponent,far_chord_m,limb_darkening,\
         forward_lobe,forward_lobe_g,vertical_anisotropy,deck_escape,steep_light,\
         steep_light_scale,downward_dimming,train_mean_flip\n",
    );
    for (m, s) in &log {
        let _ = writeln!(
            csv,
            "{},{:.2},{:.2},{:.2},{},{:.2},{:.2},{},{:.2},{:.2},{:.2},{:.2},{:.2},{:.2},{:.2},{:.2},{s:.5}",
            m.octaves,
            m.a,
            m.b,
            m.c,
            m.buildup_m,
            m.side_light,
            m.coverage_exponent,
            m.far_chord_m,
            m.limb_darkening,
            m.forward_lobe,
            m.forward_lobe_g,
            m.vertical_anisotropy,
            m.deck_escape,
            m.steep_light,
            m.steep_light_scale,
            m.downward_dimming
        );
    }
    stratus_compare::write_file_atomically(&out_dir.join("evaluations.csv"), csv.as_bytes())?;

    let mut scenes_csv = String::from(
        "scene,set,flip_before,rmse_before,flip_after,rmse_after,\
         bright_dense,bright_mid,bright_thin\n",
    );
    let mut table = String::new();
    let images = out_dir.join("images");
    std::fs::create_dir_all(&images).with_context(|| format!("creating {}", images.display()))?;
    // A brightness ratio for the table; "-" where the truth has no pixel in its bin.
    let ratio = |v: f64| {
        if v.is_finite() {
            format!("{v:.2}")
        } else {
            "-".to_string()
        }
    };
    for (set, list) in [("train", &train), ("held-out", &test)] {
        for c in list.iter() {
            let mut frames = [
                c.truth.clone(),
                render(renderer.as_mut(), c, before)?,
                render(renderer.as_mut(), c, fit)?,
            ];
            let (eb, ea) = (errors(c, &frames[1])?, errors(c, &frames[2])?);
            let br = if c.display_only {
                [f64::NAN; 3]
            } else {
                brightness(&c.truth, &frames[2])
            };
            // The images as compared: composited on the CPU, the truth through the air in
            // front of the fitted frame's depth.
            for i in usize::from(c.display_only)..frames.len() {
                let depth = if i == 0 { 2 } else { i };
                frames[i].image = c
                    .display
                    .display(&frames[i].radiance, &frames[depth].depth)
                    .context("composite of the fit's images")?;
            }
            let path = images.join(format!("{}.png", slug(&c.name)));
            let panel = side_by_side(&frames, PANEL_ZOOM);
            stratus_compare::write_atomically(&path, |tmp| panel.save(tmp))
                .with_context(|| format!("writing {}", path.display()))?;
            let _ = writeln!(
                scenes_csv,
                // Quoted: the training scenes' names hold commas.
                "\"{}\",{set},{:.4},{:.4},{:.4},{:.4},{:.3},{:.3},{:.3}",
                c.name, eb.0, eb.1, ea.0, ea.1, br[0], br[1], br[2]
            );
            let _ = writeln!(
                table,
                "| {} | {set} | {:.3} | {:.3} | {:.3} | {:.3} | {} / {} / {} |",
                c.name,
                eb.0,
                eb.1,
                ea.0,
                ea.1,
                ratio(br[0]),
                ratio(br[1]),
                ratio(br[2])
            );
        }
    }
    stratus_compare::write_file_atomically(&out_dir.join("scenes.csv"), scenes_csv.as_bytes())?;
    write_truths(&out_dir.join("truths"), &train, &test, args.spp)?;
    let readme = format!(
        "# Multiple-scattering fit\n\n\
         Written by `stratus fit-scattering --out {out} --size {w}x{h} --spp {spp} --octaves {counts}{quick}{display}` on {device}.\n\n{evaluated}\
         The octaves (count N, a, b, c; Wrenninge 2013), their build-up, side light and \
         coverage exponent, the far shadow's chord, the octaves' limb darkening, their forward \
         lobe through thin cloud (strength, eccentricity), their vertical anisotropy, their \
         escape from a deck, the column above the sample in a deck (weight, scale) and the downward \
         dimming of the march fitted to the all-orders \
         truth of the GPU path tracer ({spp} paths per pixel) over {nt} training scenes by \
         coordinate descent on a 0.05 grid (0.01 below 0.05), minimising the mean FLIP, \
         taking the fewest octaves within 1% of the lowest mean; checked on the \
         {nh} presets, which the fit never saw. `evaluations.csv` holds every evaluated point, \
         `scenes.csv` the table below, `images/` each scene's truth, before and after (left to \
         right), `truths/` the truths themselves (the reference cache's files, which the bench \
         and a rerun read where their cache lacks one; `index.csv` names their scenes). \"Before\" is the thesis's two octaves of 0.5 in this \
         model (the octaves attenuated by 1 / (1 + b^i tau) and scaled by mu0, the cosine of \
         the sun's zenith angle, no build-up, side light, coverage exponent, far shadow, limb \
         darkening, forward lobe, vertical anisotropy, deck escape, deck column or \
         downward dimming). \"Brightness\" is the fitted render's mean in-scattered \
         luminance over the truth's where the truth's transmittance is below 0.05 (dense), \
         0.05 to 0.5 and 0.5 to 0.99 (thin). FLIP is measured on display images composited \
         on the CPU from each image's linear radiance (`stratus_reference::Compositor`), the \
         truth's through the air in front of the march's depth, so that the device that \
         rendered the truth and the one that marches do not round the same light to \
         different 8-bit levels; the images show the truth and \"after\" as they are compared \
         (\"before\" is compared with the truth through its own depth).\n\n\
         | | N | a | b | c | build-up (m) | side light | coverage exponent | far chord (m) | limb darkening | forward lobe (g) | vertical anisotropy | deck escape | deck column (scale) | downward dimming |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n\
         | before | {} | {:.2} | {:.2} | {:.2} | {} | {:.2} | {:.2} | {} | {:.2} | {:.2} ({:.2}) | {:.2} | {:.2} | {:.2} ({:.2}) | {:.2} |\n\
         | after | {} | {:.2} | {:.2} | {:.2} | {} | {:.2} | {:.2} | {} | {:.2} | {:.2} ({:.2}) | {:.2} | {:.2} | {:.2} ({:.2}) | {:.2} |\n\n\
         | scene | set | FLIP before | RMSE before | FLIP after | RMSE after | brightness after (dense / mid / thin) |\n\
         |---|---|---|---|---|---|---|\n{table}",
        before.octaves,
        before.a,
        before.b,
        before.c,
        before.buildup_m,
        before.side_light,
        before.coverage_exponent,
        before.far_chord_m,
        before.limb_darkening,
        before.forward_lobe,
        before.forward_lobe_g,
        before.vertical_anisotropy,
        before.deck_escape,
        before.steep_light,
        before.steep_light_scale,
        before.downward_dimming,
        fit.octaves,
        fit.a,
        fit.b,
        fit.c,
        fit.buildup_m,
        fit.side_light,
        fit.coverage_exponent,
        fit.far_chord_m,
        fit.limb_darkening,
        fit.forward_lobe,
        fit.forward_lobe_g,
        fit.vertical_anisotropy,
        fit.deck_escape,
        fit.steep_light,
        fit.steep_light_scale,
        fit.downward_dimming,
        out = out_dir.display(),
        spp = args.spp,
        counts = args
            .octaves
            .iter()
            .map(u32::to_string)
            .collect::<Vec<_>>()
            .join(","),
        quick = match (args.quick, args.evaluate) {
            (_, true) => " --evaluate",
            (true, false) => " --quick",
            (false, false) => "",
        }
        .to_string()
            + &args
                .set
                .iter()
                .map(|s| format!(" --set {s}"))
                .collect::<String>()
            + &if args.only.is_empty() {
                String::new()
            } else {
                format!(" --only {}", args.only.join(","))
            },
        evaluated = {
            let mut e = String::new();
            if args.evaluate {
                e.push_str(
                    "**Nothing was fitted** (`--evaluate`): \"after\" is the current defaults, \
                     measured as the fit would measure them.\n\n",
                );
            }
            if let Some(dir) = &args.display_truths {
                let _ = write!(
                    e,
                    "**Measured against the truths' display images** where `{dir}` holds a \
                     panel (`--display-truths {dir}`: the panels of the fit there, whose truths \
                     were rendered as it says): FLIP as the fit measures it; RMSE and \
                     brightness, which need the truths' radiance, are left out for those scenes \
                     (NaN, -). The scenes without a panel there were measured against their \
                     truths ({spp} paths per pixel).\n\n",
                    dir = dir.display(),
                    spp = args.spp,
                );
            }
            e
        },
        display = args
            .display_truths
            .as_ref()
            .map(|d| format!(" --display-truths {}", d.display()))
            .unwrap_or_default(),
        device = renderer.describe(),
        nt = train.len(),
        nh = test.len(),
    );
    stratus_compare::write_file_atomically(&out_dir.join("README.md"), readme.as_bytes())?;
    print!("{readme}");
    println!(
        "wrote {0}/README.md, {0}/scenes.csv, {0}/evaluations.csv",
        out_dir.display()
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The training scenes (scenes/fit/) load, each under its own name and none of them a
    /// preset: the presets are the held-out set.
    #[test]
    fn training_scenes_load_with_their_own_names_and_none_is_a_preset() {
        let training = training_scenes().unwrap();
        assert_eq!(training.len(), TRAINING_SCENES.len());
        assert!(training.len() >= 15, "{} training scenes", training.len());
        let slugs: std::collections::BTreeSet<String> =
            training.iter().map(|(n, _)| slug(n)).collect();
        assert_eq!(slugs.len(), training.len(), "two scenes share a name");
        for (name, scene) in &training {
            for p in stratus_scene::presets() {
                assert_ne!(
                    scene,
                    &Scene::preset(p.name).unwrap(),
                    "{name} is the preset {}",
                    p.name
                );
            }
        }
    }

    /// `--only` names the descent's constants; an unknown one is refused with the list.
    #[test]
    fn only_masks_the_named_constants() {
        assert_eq!(descent_mask(&[]).unwrap(), [true; 15]);
        let m = descent_mask(&["steep_light".into(), "a".into()]).unwrap();
        assert_eq!(m.iter().filter(|&&b| b).count(), 2);
        assert!(m[0] && m[12]);
        let e = format!("{:#}", descent_mask(&["octaves".into()]).unwrap_err());
        assert!(
            e.contains("--only octaves") && e.contains("steep_light_scale"),
            "{e}"
        );
    }

    /// The descent's indices and `DESCENT_NAMES` name the same fields: setting constant i by
    /// index and by its name (as `--set` and `--only` take it) gives the same constants.
    #[test]
    fn descent_names_match_the_descents_fields() {
        for (i, name) in DESCENT_NAMES.iter().enumerate() {
            let mut by_index = MultipleScattering::default();
            // Within every constant's valid range, and unlike every default.
            let v = if *name == "far_chord_m" { 1234.0 } else { 0.7 };
            set_constant(&mut by_index, i, v);
            let by_name = with_sets(&[format!("{name}={v}")]).unwrap();
            assert_eq!(by_index, by_name, "{name}");
        }
    }

    /// `--set` changes exactly the named constants, and a wrong name, a value that is no TOML
    /// or one out of the scene file's range is an error that names it.
    #[test]
    fn sets_change_the_named_constants_and_refuse_bad_ones() {
        let d = MultipleScattering::default();
        assert_eq!(with_sets(&[]).unwrap(), d);
        let m = with_sets(&["limb_darkening=0.5".into(), " a = 1.2".into()]).unwrap();
        assert_eq!(
            m,
            MultipleScattering {
                limb_darkening: 0.5,
                a: 1.2,
                ..d
            }
        );
        let err = |set: &str| format!("{:#}", with_sets(&[set.to_string()]).unwrap_err());
        let e = err("limb=0.5");
        assert!(
            e.contains("`limb` is not a field") && e.contains("limb_darkening"),
            "{e}"
        );
        let e = err("a");
        assert!(e.contains("expected NAME=VALUE"), "{e}");
        let e = err("a=high");
        assert!(e.contains("`high` is not a TOML value"), "{e}");
        let e = err("steep_light=3");
        assert!(
            e.contains("--set steep_light=3") && e.contains("steep_light"),
            "{e}"
        );
    }

    /// A frame of `w` x `h` whose display image is a ramp offset by `k`.
    fn frame(w: u32, h: u32, k: u8) -> FrameOutput {
        let image = (0..4 * w * h)
            .map(|i| (i as u8).wrapping_mul(7).wrapping_add(k))
            .collect();
        FrameOutput {
            width: w,
            height: h,
            image,
            ..Default::default()
        }
    }

    #[test]
    fn display_truth_reads_back_the_panels_truth() {
        let dir = std::env::temp_dir().join(format!("stratus-fit-panel-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("images")).unwrap();
        let (w, h) = (16, 9);
        let frames = [frame(w, h, 0), frame(w, h, 50), frame(w, h, 100)];
        side_by_side(&frames, PANEL_ZOOM)
            .save(
                dir.join("images")
                    .join(format!("{}.png", slug("storm deck, sun 25 deg"))),
            )
            .unwrap();
        let got = display_truth(&dir, "storm deck, sun 25 deg", w, h).unwrap();
        // The panel's alpha is opaque; colour from the truth, leftmost, not its neighbours.
        let want: Vec<u8> = frames[0]
            .image
            .chunks(4)
            .flat_map(|p| [p[0], p[1], p[2], 255])
            .collect();
        assert_eq!(got, want);
        // Another size than the panel's is an error naming the file, not a misread.
        let err = display_truth(&dir, "storm deck, sun 25 deg", 32, 18).unwrap_err();
        assert!(
            format!("{err:#}").contains("storm-deck-sun-25-deg.png"),
            "{err:#}"
        );
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn scenes_filter_keeps_the_named_and_rejects_unknown_names() {
        let s = Scene::default();
        let train = vec![("storm deck, sun 25 deg".to_string(), s.clone())];
        let presets = vec![("storm".to_string(), s.clone()), ("noon".to_string(), s)];
        let (t, p) = only(&["storm".to_string()], train.clone(), presets.clone()).unwrap();
        assert!(t.is_empty());
        assert_eq!(
            p.iter().map(|x| x.0.as_str()).collect::<Vec<_>>(),
            ["storm"]
        );
        let (t, _) = only(
            &["storm-deck-sun-25-deg".to_string()],
            train.clone(),
            presets.clone(),
        )
        .unwrap();
        assert_eq!(t.len(), 1);
        let err = only(&["stormy".to_string()], train, presets).unwrap_err();
        assert!(err.to_string().contains("`stormy`"), "{err}");
    }
}
