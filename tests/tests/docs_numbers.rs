//! The numbers of the README and docs/ against where they come from: a claim that a new fit,
//! bench or preset made stale fails here instead of going on being read.
//!
//! Every measurement-like number (a decimal, or a whole number with a unit: "15 ms", "7%",
//! "2x") names its provenance with a marker, `<!-- numbers: KIND ... -->`, on a line of its own
//! (it holds to the next marker or the end of its section, subsections included) or at the end
//! of a line (that line only):
//! - `source FILE, FILE`: each number is one of the committed files' values to its decimals;
//! - `test NAME`: the test `fn NAME` holds these numbers to their source;
//! - `record ...`: a measurement kept as history or taken where CI cannot run it (a GPU), the
//!   marker naming the command that printed it;
//! - `cited ...`: constants of the papers or specifications the marker names.
//!
//! Tables and prose between `<!-- generated: ID -->` and `<!-- end generated -->` are written
//! by the test that computes them (`STRATUS_UPDATE_DOCS=1` rewrites them).

use std::path::Path;

use stratus_test_support::docs_block;

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

/// "at most FLIP 0.05 on all N presets (largest: `NAME`, VALUE)", or where some preset is
/// above 0.05, "at most FLIP 0.05 on K of the N presets (largest: `NAME`, VALUE); above it:
/// `NAME` (VALUE), ...": the held-out rows of `docs/fit/scenes.csv` (the fit's evaluation of
/// every preset), their count, bound, largest within it and every one above it, so that the
/// README says exactly which presets the model gets wrong.
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
        // Held out are the presets and the weather states; the claim is the presets'.
        let preset = stratus_scene::presets().iter().any(|p| p.name == name);
        if fields[set] == "held-out" && preset {
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
    let (within, above): (Vec<_>, Vec<_>) = presets.iter().partition(|p| p.1 <= 0.05);
    let (name, _, text) = within
        .iter()
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .expect("presets within 0.05");
    let words = [
        "", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten",
        "eleven", "twelve", "thirteen", "fourteen", "fifteen", "sixteen",
    ];
    let word = |n: usize| words.get(n).copied().unwrap_or("many");
    let claim = if above.is_empty() {
        format!(
            "at most FLIP 0.05 on all {} presets (largest: `{name}`, {text})",
            word(presets.len())
        )
    } else {
        let list: Vec<String> = above
            .iter()
            .map(|(n, _, t)| format!("`{n}` ({t})"))
            .collect();
        format!(
            "at most FLIP 0.05 on {} of the {} presets (largest: `{name}`, {text}); above it: {}",
            word(within.len()),
            word(presets.len()),
            list.join(", ")
        )
    };
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

/// "lo-hi" of `values` to `digits` decimals, as the prose writes a range.
fn span(values: &[f64], digits: usize) -> String {
    assert!(!values.is_empty(), "a range of no values");
    let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    format!("{lo:.digits$}-{hi:.digits$}")
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
    t + &full_bench_prose(&rows)
}

/// The row of `scene` whose configuration is its preset's with `changes`, if the bench ran it.
fn variant<'a>(
    rows: &'a [serde_json::Value],
    scene: &str,
    changes: &[(&str, serde_json::Value)],
) -> Option<&'a serde_json::Value> {
    let preset = bench_row(rows, scene, &is_preset)?;
    let mut config = preset["config"].clone();
    for (key, value) in changes {
        config[*key] = value.clone();
    }
    rows.iter()
        .find(|r| r["scene"] == scene && r["preset"] == false && r["config"] == config)
}

/// Two significant digits, as the prose writes ratios.
fn sig2(x: f64) -> String {
    let digits = (1 - x.abs().log10().floor() as i32).max(0) as usize;
    format!("{x:.digits$}")
}

/// The full bench's prose under its table: the presets' largest error, temporal upsampling at
/// 1/16 against each preset's full march, and `storm`'s light steps and octave counts.
fn full_bench_prose(rows: &[serde_json::Value]) -> String {
    let scenes = scenes_of(rows);
    let preset = |s: &str| bench_row(rows, s, &is_preset).expect("a preset row");
    let worst = scenes
        .iter()
        .max_by(|a, b| f(preset(a), "flip").total_cmp(&f(preset(b), "flip")))
        .unwrap();
    let sixteenth = |s: &str| {
        rows.iter().find(|r| {
            r["scene"] == s
                && r["config"]["temporal"] == "1/16"
                && r["config"]["checkerboard"] == false
        })
    };
    let (mut diff, mut samples, mut time) = (0.0f64, Vec::new(), Vec::new());
    for s in &scenes {
        if let Some(t) = sixteenth(s) {
            let p = preset(s);
            diff = diff.max((f(t, "flip") - f(p, "flip")).abs());
            samples.push(f(t, "samples_pp") / f(p, "samples_pp"));
            time.push(f(t, "gpu_ms") / f(p, "gpu_ms"));
        }
    }
    let storm = sixteenth("storm").expect("storm's 1/16 row");
    let flip_of = |changes: &[(&str, serde_json::Value)]| {
        variant(rows, "storm", changes).map_or("-".into(), |r| format!("{:.3}", f(r, "flip")))
    };
    use serde_json::json;
    format!(
        "\nEvery preset is within FLIP {:.3} of the truth at 128x72 (`{worst}` the largest). \
         Temporal upsampling at 1/16 leaves every preset's error within {diff:.4} of its full \
         march's, at {} of the samples a pixel and {} of the time (`storm` {:.4} at {:.1} ms \
         against {:.1} ms). On `storm` 4, 6 and 8 light steps measure FLIP {}, {:.3} and {}, \
         and 2 and 4 octaves {} and {} against the fitted 3's {:.3}: the constants are fitted \
         for 3.\n",
        f(preset(worst), "flip"),
        span(&samples, 3),
        span(&time, 2),
        f(storm, "flip"),
        f(storm, "gpu_ms"),
        f(preset("storm"), "gpu_ms"),
        flip_of(&[("light_steps", json!(4))]),
        f(preset("storm"), "flip"),
        flip_of(&[("light_steps", json!(8))]),
        flip_of(&[("octaves", json!(2))]),
        flip_of(&[("octaves", json!(4))]),
        f(preset("storm"), "flip"),
    )
}

/// The baselines' prose: how much further from the truth the basic marcher is, at what time,
/// and what the sprites' sort costs of their frame.
fn baselines_prose(rows: &[serde_json::Value]) -> String {
    let scenes = scenes_of(rows);
    let pair = |s: &str| {
        let model = bench_row(rows, s, &is_preset).expect("a preset row");
        let basic = bench_row(rows, s, &is_method("basic")).expect("a basic row");
        (
            f(basic, "flip") / f(model, "flip"),
            f(basic, "gpu_ms") / f(model, "gpu_ms"),
        )
    };
    let by = |i: usize| {
        let mut v: Vec<(f64, &String)> = scenes
            .iter()
            .map(|s| (if i == 0 { pair(s).0 } else { pair(s).1 }, s))
            .collect();
        v.sort_by(|a, b| a.0.total_cmp(&b.0));
        (v[0], v[v.len() - 1])
    };
    let ((lo, lo_scene), (hi, hi_scene)) = by(0);
    let ((tlo, _), (thi, _)) = by(1);
    let sprites: Vec<&serde_json::Value> = scenes
        .iter()
        .filter_map(|s| bench_row(rows, s, &is_method("sprites")))
        .collect();
    format!(
        "\nThe basic marcher is {} (`{lo_scene}`) to {} (`{hi_scene}`) times further from the \
         truth than the model, at {} to {} times its time. The sprites' rank sort of 4096 \
         sprites takes {} ms of their {} ms frame.\n",
        sig2(lo),
        sig2(hi),
        sig2(tlo),
        sig2(thi),
        span(
            &sprites
                .iter()
                .map(|r| f(&r["passes"], "sprite-sort"))
                .collect::<Vec<_>>(),
            0
        ),
        span(
            &sprites.iter().map(|r| f(r, "gpu_ms")).collect::<Vec<_>>(),
            0
        ),
    )
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
    t + &baselines_prose(&rows)
}

/// The quick bench's headline: each preset with octaves against the all-orders truth, with the
/// pre-fit constants beside it.
fn quick_presets_prose() -> String {
    let rows = bench_rows("docs/bench-quick.json");
    let parts: Vec<String> = scenes_of(&rows)
        .iter()
        .filter_map(|s| {
            let preset = bench_row(&rows, s, &is_preset)?;
            let prefit = bench_row(&rows, s, &is_prefit)?;
            Some(format!(
                "{:.3} (`{s}`; {:.3} with the pre-fit constants)",
                f(preset, "flip"),
                f(prefit, "flip")
            ))
        })
        .collect();
    format!(
        "Against the all-orders truth the presets measure FLIP {}, at the same work as the \
         pre-fit rows (samples/px identical).\n",
        parts.join(", ")
    )
}

#[test]
fn the_bench_tables_match_the_committed_results() {
    docs_block(
        "docs/bench.md",
        "presets: docs/bench-quick.json",
        &quick_presets_prose(),
    );
    docs_block("docs/bench.md", "docs/bench-full.json", &full_bench_table());
    docs_block("docs/bench.md", "docs/bench-quick.json", &baselines_table());
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
        span(&values, digits)
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
            "the temporal rows take {} times the preset's time",
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

/// A measurement-like number of a doc: a decimal, or a whole number with a unit of time, size,
/// angle, ratio or share ("15 ms", "7%", "2x", "1,230 s").
#[derive(Debug)]
struct DocNumber {
    line: usize,
    text: String,
    value: f64,
    decimals: i32,
    percent: bool,
}

/// The units that make a whole number a measurement; longer spellings first.
const UNITS: [&str; 13] = [
    "ms", "µs", "us", "min", "MB", "GB", "KB", "fps", "s", "x", "×", "%", "°",
];

/// The prose of a markdown line: no inline code, link targets or HTML comments.
fn prose(line: &str) -> String {
    let mut out = String::new();
    let mut rest = line;
    while !rest.is_empty() {
        if let Some(r) = rest.strip_prefix('`') {
            rest = r.find('`').map_or("", |e| &r[e + 1..]);
        } else if let Some(r) = rest.strip_prefix("](") {
            rest = r.find(')').map_or("", |e| &r[e + 1..]);
            out.push(']');
        } else if let Some(r) = rest.strip_prefix("<!--") {
            rest = r.find("-->").map_or("", |e| &r[e + 3..]);
        } else {
            let c = rest.chars().next().unwrap();
            out.push(c);
            rest = &rest[c.len_utf8()..];
        }
    }
    out
}

/// The measurement-like numbers of one line of prose (see [`DocNumber`]).
fn numbers_of(line_no: usize, line: &str) -> Vec<DocNumber> {
    let text = prose(line);
    let chars: Vec<char> = text.chars().collect();
    let mut found = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let before = if i > 0 { chars[i - 1] } else { ' ' };
        if !chars[i].is_ascii_digit()
            || before.is_alphanumeric()
            || matches!(before, '.' | '_' | '/' | '#' | '^' | ',')
            || before == '-' && i > 1 && chars[i - 2].is_alphanumeric()
        {
            i += 1;
            continue;
        }
        let start = i;
        let mut digits = String::new();
        while i < chars.len() {
            if chars[i].is_ascii_digit() {
                digits.push(chars[i]);
                i += 1;
            } else if chars[i] == ','
                && i + 3 < chars.len() + 1
                && chars[i + 1..]
                    .iter()
                    .take(3)
                    .filter(|c| c.is_ascii_digit())
                    .count()
                    == 3
                && chars.get(i + 4).is_none_or(|c| !c.is_ascii_digit())
            {
                i += 1; // a thousands separator
            } else {
                break;
            }
        }
        let mut decimals = 0;
        if chars.get(i) == Some(&'.') && chars.get(i + 1).is_some_and(|c| c.is_ascii_digit()) {
            digits.push('.');
            i += 1;
            while i < chars.len() && chars[i].is_ascii_digit() {
                digits.push(chars[i]);
                decimals += 1;
                i += 1;
            }
        }
        // A version (1.97.1), a section (4.1.2) or an identifier (v64, 128x32x128) is no
        // measurement.
        let after: String = chars[i..].iter().collect();
        if after.starts_with('.') && chars.get(i + 1).is_some_and(|c| c.is_ascii_digit())
            || chars
                .get(i)
                .is_some_and(|c| c.is_alphanumeric() || *c == '_')
                && !UNITS.iter().any(|u| after.starts_with(u))
        {
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '.') {
                i += 1;
            }
            continue;
        }
        let unit = UNITS.iter().find(|u| {
            let tail = after.strip_prefix(' ').unwrap_or(&after);
            tail.starts_with(**u)
                && tail[u.len()..]
                    .chars()
                    .next()
                    .is_none_or(|c| !c.is_alphanumeric())
        });
        if decimals == 0 && unit.is_none() {
            continue;
        }
        found.push(DocNumber {
            line: line_no,
            text: chars[start..i].iter().collect(),
            value: digits.parse().unwrap(),
            decimals,
            percent: unit == Some(&"%"),
        });
    }
    found
}

/// Every number of a text file, as a results file or source code writes it.
fn numbers_in(text: &str) -> Vec<f64> {
    let mut values = Vec::new();
    let bytes = text.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        if !bytes[i].is_ascii_digit() {
            i += 1;
            continue;
        }
        let start = i;
        while i < bytes.len() && (bytes[i].is_ascii_digit() || bytes[i] == b'.') {
            i += 1;
        }
        if i < bytes.len() && matches!(bytes[i], b'e' | b'E') {
            let mut j = i + 1;
            if j < bytes.len() && matches!(bytes[j], b'-' | b'+') {
                j += 1;
            }
            if j < bytes.len() && bytes[j].is_ascii_digit() {
                i = j;
                while i < bytes.len() && bytes[i].is_ascii_digit() {
                    i += 1;
                }
            }
        }
        let token = text[start..i].trim_end_matches('.');
        let parts: Vec<&str> = token.split('.').collect();
        if parts.len() > 2 {
            // A version: 0.33.2 holds 0.33 (and 33.2).
            for pair in parts.windows(2) {
                values.extend(format!("{}.{}", pair[0], pair[1]).parse::<f64>());
            }
        } else if let Ok(v) = token.parse::<f64>() {
            values.push(v);
        }
    }
    values
}

/// What a `<!-- numbers: ... -->` marker says of the numbers after it.
#[derive(Debug, Clone)]
enum Provenance {
    /// `source FILE, FILE`: each number is a value of one of the committed files, as written
    /// to the number's decimals (a percentage may be a fraction of them).
    Source(Vec<String>),
    /// `record ...`: a measurement, kept as history; the marker names the command that
    /// printed it.
    Record,
    /// `cited ...`: constants from the papers or specifications the marker names.
    Cited,
    /// `test NAME`: a test of this repository, `fn NAME`, holds these numbers to their source.
    Test,
}

fn provenance(doc: &str, line_no: usize, marker: &str) -> Provenance {
    let (kind, rest) = marker
        .split_once(char::is_whitespace)
        .unwrap_or_else(|| panic!("{doc}:{line_no}: `numbers: {marker}` lacks a kind or its text"));
    let kind = kind.trim_end_matches(':');
    let rest = rest.trim().to_string();
    match kind.trim() {
        "source" => Provenance::Source(rest.split(',').map(|s| s.trim().to_string()).collect()),
        "record" => {
            assert!(
                rest.matches('`').count() >= 2,
                "{doc}:{line_no}: a record names the command that printed it, in backticks"
            );
            Provenance::Record
        }
        "cited" => {
            assert!(
                rest.len() >= 8,
                "{doc}:{line_no}: `cited` names the papers or specifications"
            );
            Provenance::Cited
        }
        "test" => {
            assert!(
                test_exists(&rest),
                "{doc}:{line_no}: no test `fn {rest}` under tests/ or crates/*/tests"
            );
            Provenance::Test
        }
        other => {
            panic!("{doc}:{line_no}: unknown provenance `{other}` (source, record, cited, test)")
        }
    }
}

/// Whether a test `fn name` is defined in a test file of the workspace.
fn test_exists(name: &str) -> bool {
    fn walk(dir: &Path, needle: &str) -> bool {
        let Ok(entries) = std::fs::read_dir(dir) else {
            return false;
        };
        entries.flatten().any(|e| {
            let path = e.path();
            if path.is_dir() {
                walk(&path, needle)
            } else {
                path.extension().is_some_and(|x| x == "rs")
                    && std::fs::read_to_string(&path).is_ok_and(|t| t.contains(needle))
            }
        })
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let needle = format!("fn {name}(");
    walk(&root.join("tests"), &needle)
        || std::fs::read_dir(root.join("crates"))
            .unwrap()
            .flatten()
            .any(|c| walk(&c.path().join("tests"), &needle))
}

/// Each measurement-like number of `doc` with the provenance in force at its line. A marker
/// holds to the next marker of its section or the end of its section (its subsections
/// included); generated blocks and code are left out (they are checked against their source
/// or are not prose).
fn numbers_with_provenance(doc: &str) -> Vec<(DocNumber, Option<Provenance>)> {
    let text = read(doc);
    let mut out = Vec::new();
    let mut stack: Vec<(usize, Provenance)> = Vec::new();
    let mut level = 0;
    let (mut code, mut generated) = (false, false);
    for (n, line) in text.lines().enumerate() {
        let line_no = n + 1;
        let trimmed = line.trim_start();
        if trimmed.starts_with("```") {
            code = !code;
            continue;
        }
        if code {
            continue;
        }
        if trimmed.starts_with("<!-- generated:") {
            generated = true;
        }
        if trimmed.starts_with("<!-- end generated") {
            generated = false;
        }
        if generated {
            continue;
        }
        if let Some(h) = trimmed.strip_prefix('#') {
            level = 1 + h.chars().take_while(|c| *c == '#').count();
            stack.retain(|(l, _)| *l < level);
        }
        if let Some(m) = trimmed.strip_prefix("<!-- numbers:") {
            let m = m.trim().trim_end_matches("-->").trim();
            stack.retain(|(l, _)| *l < level);
            stack.push((level, provenance(doc, line_no, m)));
            continue;
        }
        // A marker after text on a line holds for that line's numbers alone.
        // Code spans may show a marker's syntax; only one outside them counts.
        let mut in_code = false;
        let at = line.char_indices().find_map(|(i, c)| {
            if c == '`' {
                in_code = !in_code;
            }
            (!in_code && line[i..].starts_with("<!-- numbers:")).then_some(i)
        });
        let inline = at.map(|at| {
            let m = &line[at + "<!-- numbers:".len()..];
            let m = m.split("-->").next().unwrap_or(m).trim();
            provenance(doc, line_no, m)
        });
        for number in numbers_of(line_no, line) {
            let p = inline
                .clone()
                .or_else(|| stack.last().map(|(_, p)| p.clone()));
            out.push((number, p));
        }
    }
    out
}

/// The docs whose numbers must name their source.
fn docs() -> Vec<String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut docs = vec!["README.md".to_string()];
    let mut pages: Vec<String> = std::fs::read_dir(root.join("docs"))
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|n| n.ends_with(".md"))
        .map(|n| format!("docs/{n}"))
        .collect();
    pages.sort();
    docs.extend(pages);
    docs
}

/// Every measurement-like number of the README and docs/*.md names where it comes from with a
/// `<!-- numbers: ... -->` marker, and a number whose source is a committed file is one of that
/// file's values: a new bench, fit or preset that changes the file fails here until the prose
/// follows it.
#[test]
fn every_number_in_the_docs_is_a_value_of_its_source() {
    let mut problems = Vec::new();
    let mut counts = (0, 0, 0, 0);
    for doc in docs() {
        let mut cache: std::collections::HashMap<String, Vec<f64>> = Default::default();
        for (number, provenance) in numbers_with_provenance(&doc) {
            let where_ = format!("{doc}:{}: {}", number.line, number.text);
            match provenance {
                None => problems.push(format!("{where_}: no `<!-- numbers: ... -->` marker")),
                Some(Provenance::Record) => counts.1 += 1,
                Some(Provenance::Cited) => counts.2 += 1,
                Some(Provenance::Test) => counts.3 += 1,
                Some(Provenance::Source(files)) => {
                    counts.0 += 1;
                    let tolerance = 0.5 * 10f64.powi(-number.decimals) * (1.0 + 1e-9);
                    let found = files.iter().any(|file| {
                        let values = cache
                            .entry(file.clone())
                            .or_insert_with(|| numbers_in(&read(file)));
                        values.iter().any(|v| {
                            (v.abs() - number.value).abs() <= tolerance
                                || number.percent
                                    && (100.0 * v.abs() - number.value).abs() <= tolerance
                        })
                    });
                    if !found {
                        problems.push(format!("{where_}: not a value of {}", files.join(", ")));
                    }
                }
            }
        }
    }
    eprintln!(
        "docs numbers: {} held to a committed file, {} by a named test, {} records, {} cited",
        counts.0, counts.3, counts.1, counts.2
    );
    assert!(
        problems.is_empty(),
        "{} numbers lack a source or disagree with it:\n{}",
        problems.len(),
        problems.join("\n")
    );
}

/// docs/temporal.md's table of the three cheaper marches, from docs/bench-quick.json: the
/// ranges over its scenes of the samples saved, the time against the preset's (`sunset`, whose
/// moving frames recompute the sky, apart) and the motion FLIP.
#[test]
fn the_temporal_table_matches_the_quick_results() {
    let rows = bench_rows("docs/bench-quick.json");
    let doc = read("docs/temporal.md")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    let scenes = scenes_of(&rows);
    let find = |scene: &str, pick: &dyn Fn(&serde_json::Value) -> bool| {
        rows.iter()
            .find(|r| r["scene"] == scene && pick(r))
            .unwrap_or_else(|| panic!("no such row of {scene}"))
    };
    let config = |r: &serde_json::Value, key: &str| r["config"][key].clone();
    let plain = |r: &serde_json::Value| {
        !r["preset"].as_bool().unwrap()
            && config(r, "method") == "volumetric"
            && config(r, "view_steps") == 64
            && config(r, "light_steps") == 6
            && config(r, "jitter") == true
            && config(r, "prefit") == false
    };
    let dynamic = |r: &serde_json::Value| plain(r) && config(r, "dynamic_step") == true;
    let skip = |r: &serde_json::Value| plain(r) && config(r, "empty_space_skip") == true;
    let sixteenth = |r: &serde_json::Value| {
        plain(r) && config(r, "temporal") == "1/16" && config(r, "checkerboard") == false
    };
    let checker = |r: &serde_json::Value| {
        plain(r) && config(r, "temporal") == "1/16" && config(r, "checkerboard") == true
    };
    // "lo-hi" of `value` over the scenes `keep` accepts.
    let range = |keep: &dyn Fn(&str) -> bool, value: &dyn Fn(&str) -> f64, digits: usize| {
        let v: Vec<f64> = scenes
            .iter()
            .filter(|s| keep(s))
            .map(|s| value(s))
            .collect();
        span(&v, digits)
    };
    let all = |_: &str| true;
    let not_sunset = |s: &str| s != "sunset";
    let fewer = |pick: &dyn Fn(&serde_json::Value) -> bool,
                 base: &dyn Fn(&serde_json::Value) -> bool| {
        range(
            &all,
            &|s| 100.0 * (1.0 - f(find(s, pick), "samples_pp") / f(find(s, base), "samples_pp")),
            0,
        )
    };
    let time = |pick: &dyn Fn(&serde_json::Value) -> bool| {
        (
            range(&not_sunset, &|s| f(find(s, pick), "time_vs_preset"), 2),
            format!("{:.2}", f(find("sunset", pick), "time_vs_preset")),
        )
    };
    let (dynamic_time, dynamic_sunset) = time(&dynamic);
    let (skip_time, skip_sunset) = time(&skip);
    let worst = scenes
        .iter()
        .map(|s| f(find(s, &dynamic), "motion_flip_worst"))
        .fold(0.0, f64::max);
    let claims = [
        format!(
            "samples/px {}% fewer; {dynamic_time} of the time (`sunset` {dynamic_sunset},",
            fewer(&dynamic, &is_preset)
        ),
        format!(
            "FLIP {} against the full march of each frame (worst frame {worst:.4})",
            range(&all, &|s| f(find(s, &dynamic), "motion_flip"), 4)
        ),
        format!("samples/px {}% fewer (", fewer(&skip, &is_preset)),
        format!("{skip_time} of the time (`sunset` {skip_sunset})"),
        format!(
            "samples/px {}% fewer than 1/16 alone",
            fewer(&checker, &sixteenth)
        ),
        format!(
            "its march pass takes {} times the plain 1/16 march's",
            range(
                &all,
                &|s| f(&find(s, &checker)["passes"], "march")
                    / f(&find(s, &sixteenth)["passes"], "march"),
                2
            )
        ),
    ];
    for claim in claims {
        assert!(
            doc.contains(&claim),
            "docs/temporal.md should say {claim:?} (from docs/bench-quick.json)"
        );
    }
}

/// docs/model.md names each fitted constant with its value, "`name` value": each is the `after`
/// row of docs/fit/README.md, the table `stratus fit-scattering` writes, so a refit that moves
/// a constant fails here until the model's description follows.
#[test]
fn the_model_names_the_fitted_constants_the_fit_wrote() {
    let fit = read("docs/fit/README.md");
    let header_line = fit
        .lines()
        .find(|l| l.starts_with("| | N | a | b | c |"))
        .expect("the constants' table");
    let after_line = fit
        .lines()
        .find(|l| l.starts_with("| after |"))
        .expect("the `after` row");
    let cells = |l: &str| -> Vec<String> {
        l.trim_matches('|')
            .split('|')
            .map(|c| c.trim().to_string())
            .collect()
    };
    let (header, after) = (cells(header_line), cells(after_line));
    let column = |name: &str| {
        let i = header
            .iter()
            .position(|h| h == name)
            .unwrap_or_else(|| panic!("docs/fit/README.md has no column {name:?}"));
        after[i].clone()
    };
    // A cell "0.30 (0.50)" holds two constants.
    let first = |c: String| c.split(' ').next().unwrap().parse::<f64>().unwrap();
    let second = |c: String| {
        c.split('(')
            .nth(1)
            .unwrap()
            .trim_end_matches(')')
            .parse::<f64>()
            .unwrap()
    };
    let constants = [
        ("buildup_m", first(column("build-up (m)"))),
        ("side_light", first(column("side light"))),
        ("coverage_exponent", first(column("coverage exponent"))),
        ("far_chord_m", first(column("far chord (m)"))),
        ("limb_darkening", first(column("limb darkening"))),
        ("forward_lobe", first(column("forward lobe (g)"))),
        ("forward_lobe_g", second(column("forward lobe (g)"))),
        ("vertical_anisotropy", first(column("vertical anisotropy"))),
        ("deck_escape", first(column("deck escape"))),
        ("steep_light", first(column("deck column (scale)"))),
        ("steep_light_scale", second(column("deck column (scale)"))),
        ("downward_dimming", first(column("downward dimming"))),
    ];
    let model = read("docs/model.md")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    for (name, value) in constants {
        let key = format!("`{name}` ");
        let stated: Vec<f64> = model
            .match_indices(&key)
            .filter_map(|(at, _)| {
                let rest = &model[at + key.len()..];
                let end = rest
                    .find(|c: char| !(c.is_ascii_digit() || c == '.'))
                    .unwrap_or(rest.len());
                rest[..end].trim_end_matches('.').parse().ok()
            })
            .collect();
        assert!(
            !stated.is_empty(),
            "docs/model.md should name `{name}` with its value ({value})"
        );
        for v in stated {
            assert!(
                (v - value).abs() < 1e-9,
                "docs/model.md says `{name}` {v}; docs/fit/README.md's fit has {value}"
            );
        }
    }
}
