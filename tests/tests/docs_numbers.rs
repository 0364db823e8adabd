//! The numbers of the README and docs/ against the committed results they come from: a claim
//! that a new fit, bench or preset made stale fails here instead of going on being read. The
//! tables between `<!-- generated: SOURCE -->` and `<!-- end generated -->` are written from
//! their source (`STRATUS_UPDATE_DOCS=1` rewrites them); prose numbers name their source.

use std::path::Path;

fn read(path: &str) -> String {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    std::fs::read_to_string(root.join(path)).unwrap_or_else(|e| panic!("reading {path}: {e}"))
}

/// The README folded to single spaces, so that a claim may wrap across lines.
fn readme() -> String {
    read("README.md")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
}

/// "at most FLIP 0.05 on all N presets (largest: `NAME`, VALUE)": the held-out rows of
/// `docs/fit/scenes.csv` (the fit's evaluation of every preset), their count, bound and largest.
#[test]
fn the_accuracy_claim_matches_docs_fit_scenes_csv() {
    let csv = read("docs/fit/scenes.csv");
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().expect("a header").split(',').collect();
    let column = |name: &str| {
        header
            .iter()
            .position(|h| *h == name)
            .unwrap_or_else(|| panic!("docs/fit/scenes.csv has no column {name}"))
    };
    let (set, flip) = (column("set"), column("flip_after"));
    let mut presets: Vec<(String, f64, String)> = Vec::new();
    for line in lines {
        // The scene name is quoted and may hold commas; the other fields do not.
        let (name, rest) = line
            .strip_prefix('"')
            .and_then(|l| l.split_once("\","))
            .unwrap_or_else(|| panic!("unquoted scene in {line:?}"));
        let fields: Vec<&str> = std::iter::once("").chain(rest.split(',')).collect();
        if fields[set] == "held-out" {
            let text = fields[flip].to_string();
            let value: f64 = text.parse().unwrap_or_else(|e| panic!("{line:?}: {e}"));
            presets.push((name.to_string(), value, text));
        }
    }
    assert_eq!(
        presets.len(),
        stratus_scene::presets().len(),
        "every preset is evaluated"
    );
    let (name, value, text) = presets
        .iter()
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .expect("presets");
    assert!(
        *value <= 0.05,
        "{name} is at FLIP {value}, above the README's 0.05"
    );
    let words = [
        "", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten",
        "eleven", "twelve",
    ];
    let claim = format!(
        "at most FLIP 0.05 on all {} presets (largest: `{name}`, {text})",
        words.get(presets.len()).copied().unwrap_or("many")
    );
    assert!(
        readme().contains(&claim),
        "the README should say {claim:?} (from docs/fit/scenes.csv)"
    );
}

/// The rows of a committed bench results file.
fn bench_rows(path: &str) -> Vec<serde_json::Value> {
    let json: serde_json::Value = serde_json::from_str(&read(path)).unwrap();
    json["rows"].as_array().expect("rows").clone()
}

/// The row of `scene` that `pick` chooses among its still (not temporal) rows, if any.
fn bench_row<'a>(
    rows: &'a [serde_json::Value],
    scene: &str,
    pick: &dyn Fn(&serde_json::Value) -> bool,
) -> Option<&'a serde_json::Value> {
    rows.iter().find(|r| {
        r["scene"] == scene && r["config"]["temporal"].as_str().unwrap_or("off") == "off" && pick(r)
    })
}

fn is_preset(r: &serde_json::Value) -> bool {
    r["preset"] == true
}
fn is_prefit(r: &serde_json::Value) -> bool {
    r["config"]["prefit"] == true && r["config"]["method"] == "volumetric"
}
fn is_method(method: &'static str) -> impl Fn(&serde_json::Value) -> bool {
    move |r| r["config"]["method"] == method
}

/// What the tables call a scene: its name, with what sets it apart.
fn scene_label(scene: &str) -> String {
    match scene {
        "sunset" => "`sunset` (physical sky)".into(),
        "stress-thick" => "`stress-thick` (single scattering)".into(),
        s => format!("`{s}`"),
    }
}

/// The scenes of a results file, in the order of their first row.
fn scenes_of(rows: &[serde_json::Value]) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for r in rows {
        let s = r["scene"].as_str().unwrap().to_string();
        if !out.contains(&s) {
            out.push(s);
        }
    }
    out
}

fn f(r: &serde_json::Value, key: &str) -> f64 {
    r[key].as_f64().unwrap_or_else(|| panic!("{key} in {r}"))
}

/// docs/bench.md's full-bench table, from docs/bench-full.json.
fn full_bench_table() -> String {
    let rows = bench_rows("docs/bench-full.json");
    let mut t = String::from(
        "| scene | preset: FLIP (RMSE) | pre-fit constants | `basic` | `sprites` | samples/px (preset) | frame (preset), lavapipe |\n|---|---|---|---|---|---|---|\n",
    );
    let flip =
        |r: Option<&serde_json::Value>| r.map_or("-".into(), |r| format!("{:.3}", f(r, "flip")));
    for scene in scenes_of(&rows) {
        let preset = bench_row(&rows, &scene, &is_preset).expect("a preset row");
        t += &format!(
            "| {} | {:.3} ({:.3}) | {} | {} | {} | {:.1} | {:.1} ms |\n",
            scene_label(&scene),
            f(preset, "flip"),
            f(preset, "rmse"),
            flip(bench_row(&rows, &scene, &is_prefit)),
            flip(bench_row(&rows, &scene, &is_method("basic"))),
            flip(bench_row(&rows, &scene, &is_method("sprites"))),
            f(preset, "samples_pp"),
            f(preset, "gpu_ms"),
        );
    }
    t
}

/// docs/bench.md's baselines table, from docs/bench-quick.json.
fn baselines_table() -> String {
    let rows = bench_rows("docs/bench-quick.json");
    let mut t =
        String::from("| scene | model (preset) | `basic` | `sprites` |\n|---|---|---|---|\n");
    let cell = |r: Option<&serde_json::Value>| {
        r.map_or("-".into(), |r| {
            format!("{:.3}, {:.1} ms", f(r, "flip"), f(r, "gpu_ms"))
        })
    };
    for scene in scenes_of(&rows) {
        t += &format!(
            "| {} | {} | {} | {} |\n",
            scene_label(&scene),
            cell(bench_row(&rows, &scene, &is_preset)),
            cell(bench_row(&rows, &scene, &is_method("basic"))),
            cell(bench_row(&rows, &scene, &is_method("sprites"))),
        );
    }
    t
}

/// Holds the block of `doc` between `<!-- generated: ID -->` and `<!-- end generated -->` to
/// `expected`; with `STRATUS_UPDATE_DOCS=1` rewrites it instead.
fn generated_block(doc: &str, id: &str, expected: &str) {
    let text = read(doc);
    let begin = format!("<!-- generated: {id} -->\n");
    let end = "<!-- end generated -->";
    let start = text
        .find(&begin)
        .unwrap_or_else(|| panic!("{doc} has no `{}`", begin.trim()))
        + begin.len();
    let stop = start
        + text[start..]
            .find(end)
            .unwrap_or_else(|| panic!("{doc}: `{}` is not closed", begin.trim()));
    if text[start..stop] == *expected {
        return;
    }
    if std::env::var_os("STRATUS_UPDATE_DOCS").is_some() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        let new = format!("{}{expected}{}", &text[..start], &text[stop..]);
        std::fs::write(root.join(doc), new).unwrap();
        return;
    }
    panic!(
        "{doc}'s table `{id}` no longer matches its source; run `STRATUS_UPDATE_DOCS=1 cargo test -p stratus-tests --test docs_numbers` to rewrite it.\nexpected:\n{expected}\nfound:\n{}",
        &text[start..stop]
    );
}

#[test]
fn the_bench_tables_match_the_committed_results() {
    generated_block("docs/bench.md", "docs/bench-full.json", &full_bench_table());
    generated_block("docs/bench.md", "docs/bench-quick.json", &baselines_table());
}

/// docs/bench.md's prose on temporal upsampling: the ranges of time (against the preset's) and
/// of motion FLIP over `cumulus-noon`, `above-clouds` and `stress-thick` at 1/16 and 1/4, and
/// `sunset`'s time range over its temporal rows, each from docs/bench-quick.json.
#[test]
fn the_bench_prose_on_temporal_upsampling_matches_the_quick_results() {
    let rows = bench_rows("docs/bench-quick.json");
    let doc = read("docs/bench.md")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    // "lo-hi" of `key` over the rows of `scenes` whose temporal mode `temporal` accepts.
    let range = |scenes: &[&str], temporal: &dyn Fn(&str) -> bool, key: &str, digits: usize| {
        let values: Vec<f64> = rows
            .iter()
            .filter(|r| {
                scenes.contains(&r["scene"].as_str().unwrap())
                    && temporal(r["config"]["temporal"].as_str().unwrap_or("off"))
            })
            .map(|r| f(r, key))
            .collect();
        assert!(!values.is_empty(), "no such rows of {scenes:?}");
        let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        format!("{lo:.digits$}-{hi:.digits$}")
    };
    let three = ["cumulus-noon", "above-clouds", "stress-thick"];
    type Mode<'a> = &'a dyn Fn(&str) -> bool;
    let at16: Mode = &|t| t == "1/16";
    let at4: Mode = &|t| t == "1/4";
    let any: Mode = &|t| t != "off";
    let claims = [
        format!(
            "at {} of the time at 1/16",
            range(&three, at16, "time_vs_preset", 2)
        ),
        format!("and {} at 1/4", range(&three, at4, "time_vs_preset", 2)),
        format!(
            "costs FLIP {} in motion at 1/16",
            range(&three, at16, "motion_flip", 3)
        ),
        format!(", {} at 1/4", range(&three, at4, "motion_flip", 3)),
        format!(
            "({} in `docs/bench-quick.json`)",
            range(&["sunset"], any, "time_vs_preset", 2)
        ),
    ];
    for claim in claims {
        assert!(
            doc.contains(&claim),
            "docs/bench.md should say {claim:?} (from docs/bench-quick.json)"
        );
    }
}
