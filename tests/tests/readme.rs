//! The README's numbers against the committed results they come from: a claim that a new fit,
//! bench or preset made stale fails here instead of going on being read.

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
