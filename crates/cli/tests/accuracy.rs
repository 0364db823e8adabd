//! The accuracy the README claims, held by CI: every preset's real-time render measured again
//! against its all-orders truth (the GPU path tracer's, committed in `docs/fit/truths` under a
//! key that hashes the tracer's code, noise and uniforms) as `stratus fit-scattering --evaluate
//! --committed` measures it, in seconds and without rendering any truth, and held to the table
//! the README's claim is read from (`docs/fit/scenes.csv`, whose claim `docs_numbers` checks):
//! a change that moves a preset's error fails here until the table says so.

mod common;

use std::path::Path;

/// How far a preset's FLIP may be from the committed table's: the table's rounding (4
/// decimals). The march and the composite are deterministic on lavapipe, where the table was
/// measured.
const TABLE_ROUNDING: f64 = 5e-5;

/// `stratus fit-scattering --evaluate --committed --octaves 3 --scenes SCENES --out OUT` in
/// `dir` (`--committed` finds the truths from the working directory), with its cache in
/// `cache` (not read with --committed; kept out of the repository all the same).
fn evaluate_committed(dir: &Path, cache: &Path, scenes: &str, out: &str) -> (bool, String) {
    let cache = cache.to_str().expect("a UTF-8 cache path");
    common::stratus_in(
        dir,
        &[
            "fit-scattering",
            "--evaluate",
            "--committed",
            "--octaves",
            "3",
            "--scenes",
            scenes,
            "--out",
            out,
        ],
        &[("XDG_CACHE_HOME", cache)],
    )
}

/// `scenes.csv`'s rows: scene, set and FLIP after (the current defaults).
fn rows(csv: &str) -> Vec<(String, String, f64)> {
    csv.lines()
        .skip(1)
        .map(|line| {
            // The scene is quoted where it holds commas.
            let (scene, rest) = match line.strip_prefix('"') {
                Some(q) => {
                    let (s, r) = q.split_once("\",").expect("a closing quote");
                    (s.to_string(), r)
                }
                None => {
                    let (s, r) = line.split_once(',').expect("a scene");
                    (s.to_string(), r)
                }
            };
            let f: Vec<&str> = rest.split(',').collect();
            (scene, f[0].to_string(), f[3].parse().expect("flip_after"))
        })
        .collect()
}

/// Every preset, every weather state the table has a row of (`weather NAME`; a state's truth
/// is committed with its row), every cloud type's scene (`type NAME`) and layered scene
/// (`layers NAME`), measured again
/// against its committed truth, and the table held to what is measured.
#[test]
fn every_preset_measures_against_its_committed_truth_as_the_table_says() {
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("accuracy");
    let _ = std::fs::remove_dir_all(&out);
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let table = rows(&std::fs::read_to_string(root.join("docs/fit/scenes.csv")).unwrap());
    let mut expected: Vec<String> = stratus_scene::presets()
        .iter()
        .map(|p| p.name.to_string())
        .collect();
    expected.extend(
        table
            .iter()
            .filter(|(s, set, _)| set == "held-out" && s.starts_with("weather "))
            .map(|(s, _, _)| s.clone()),
    );
    // Every cloud type's scene (`scenes/types/NAME.toml`, `type NAME`) and layered scene
    // (`scenes/layers/NAME.toml`, `layers NAME`): each has its truth and its row, as a preset
    // does.
    for (folder, label) in [("types", "type"), ("layers", "layers")] {
        for e in std::fs::read_dir(root.join("scenes").join(folder)).expect(folder) {
            let path = e.unwrap().path();
            if path.extension().is_some_and(|x| x == "toml") {
                let stem = path.file_stem().unwrap().to_str().unwrap().to_string();
                expected.push(format!("{label} {stem}"));
            }
        }
    }
    // As `--scenes` spells them: `weather few` is `weather-few`.
    let slugs: Vec<String> = expected.iter().map(|s| s.replace(' ', "-")).collect();
    let (ok, text) = evaluate_committed(
        &root,
        &Path::new(env!("CARGO_TARGET_TMPDIR")).join("cache"),
        &slugs.join(","),
        out.to_str().unwrap(),
    );
    assert!(ok, "{text}");
    let csv = std::fs::read_to_string(out.join("scenes.csv")).expect("scenes.csv");
    let measured = rows(&csv);
    // Every scene is measured: none is left out for want of a truth.
    let mut names: Vec<&str> = measured.iter().map(|(s, _, _)| s.as_str()).collect();
    names.sort_unstable();
    expected.sort_unstable();
    assert_eq!(names, expected, "{csv}");

    // Another device rounds the march differently: only the table's own device is held to it.
    let other_device = std::env::var("STRATUS_DEVICE_CLASS").is_ok_and(|c| c == "other");
    let mut differ = Vec::new();
    for (scene, _, flip) in &measured {
        let committed = table
            .iter()
            .find(|(s, set, _)| s == scene && set == "held-out")
            .unwrap_or_else(|| panic!("docs/fit/scenes.csv has no row of preset `{scene}`"));
        eprintln!("{scene}: FLIP {flip:.4} (table {:.4})", committed.2);
        if !other_device && (flip - committed.2).abs() > TABLE_ROUNDING {
            differ.push(format!(
                "{scene}: measured {flip:.4}, table {:.4}",
                committed.2
            ));
        }
    }
    assert!(
        differ.is_empty(),
        "docs/fit/scenes.csv no longer says what the presets measure against their truths (update its rows from this run's {}): {differ:?}",
        out.join("scenes.csv").display()
    );
}

/// A truth filed under another key (here: an index row whose file is no key of this build) is
/// refused by name rather than measured against or rendered.
#[test]
fn committed_evaluation_refuses_a_stale_or_missing_truth() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("accuracy-stale");
    let _ = std::fs::remove_dir_all(&dir);
    // Nothing else runs from here: --committed reads docs/fit/truths relative to the working
    // directory, which holds none.
    std::fs::create_dir_all(dir.join("docs/fit/truths")).unwrap();
    std::fs::write(
        dir.join("docs/fit/truths/index.csv"),
        "file,scene,set,paths_per_pixel,width,height\nref-000000000000000000000000.bin,\"storm\",held-out,8192,64,36\n",
    )
    .unwrap();
    let (ok, text) = evaluate_committed(&dir, &dir.join("cache"), "storm", "out");
    assert!(!ok, "{text}");
    assert!(
        text.contains("`storm`")
            && text.contains("another key")
            && text.contains("--recheck-truths"),
        "{text}"
    );
    // Mesa keeps its shader cache there too; no truth may be.
    assert!(
        !dir.join("cache/stratus").exists(),
        "a truth was rendered: {text}"
    );
}
