//! The house rules a reviewer would otherwise check by reading: no import circles between the
//! modules of a crate (a module that needs another's item while that one needs it back means
//! the item belongs in a third), and `spirv-out/` small enough that a WGSL edit stays
//! reviewable.

use std::{
    collections::{BTreeMap, BTreeSet},
    path::{Path, PathBuf},
};

use stratus_test_support::files_with_extension;

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The top-level module a source file belongs to (`None` for the crate root).
fn top_module(src: &Path, file: &Path) -> Option<String> {
    let rel = file.strip_prefix(src).ok()?;
    let first = rel.components().next()?.as_os_str().to_string_lossy();
    let name = first.trim_end_matches(".rs").to_string();
    (!matches!(name.as_str(), "lib" | "main")).then_some(name)
}

/// The code of a file without comments and without its `#[cfg(test)] mod tests` (tests may
/// reach anywhere in their crate).
fn code(text: &str) -> String {
    let text = text.split("#[cfg(test)]\nmod tests").next().unwrap_or(text);
    text.lines()
        .map(|l| l.split("//").next().unwrap_or(""))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The top-level modules `code` names through `crate::` paths, including inside
/// `use crate::{a::x, b}` groups.
fn uses(code: &str, modules: &BTreeSet<String>) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    let mut rest = code;
    while let Some(i) = rest.find("crate::") {
        rest = &rest[i + "crate::".len()..];
        let names: Vec<&str> = if let Some(group) = rest.strip_prefix('{') {
            // A group: every path's first segment at depth 0.
            let end = group.find("};").unwrap_or(group.len());
            let mut depth = 0;
            let mut firsts = Vec::new();
            let mut start = true;
            for (k, ch) in group[..end].char_indices() {
                match ch {
                    '{' => depth += 1,
                    '}' => depth -= 1,
                    ',' if depth == 0 => start = true,
                    c if start && (c.is_alphanumeric() || c == '_') => {
                        start = false;
                        let len = group[k..]
                            .find(|c: char| !(c.is_alphanumeric() || c == '_'))
                            .unwrap_or(group.len() - k);
                        firsts.push(&group[k..k + len]);
                    }
                    _ => {}
                }
            }
            firsts
        } else {
            let w = rest
                .split(|c: char| !(c.is_alphanumeric() || c == '_'))
                .next()
                .unwrap_or("");
            vec![w]
        };
        for n in names {
            if modules.contains(n) {
                out.insert(n.to_string());
            }
        }
    }
    out
}

/// A cycle in `edges` through `start`, if any (depth-first).
fn cycle_from(
    start: &str,
    edges: &BTreeMap<String, BTreeSet<String>>,
    path: &mut Vec<String>,
) -> Option<Vec<String>> {
    let last = path.last().cloned().unwrap_or_else(|| start.to_string());
    for next in edges.get(&last).into_iter().flatten() {
        if next == start {
            let mut c = path.clone();
            c.insert(0, start.to_string());
            c.push(start.to_string());
            return Some(c);
        }
        if !path.contains(next) && next.as_str() > start {
            path.push(next.clone());
            if let Some(c) = cycle_from(start, edges, path) {
                return Some(c);
            }
            path.pop();
        }
    }
    None
}

#[test]
fn no_crate_has_an_import_circle_between_its_modules() {
    let root = workspace();
    let mut sources: Vec<PathBuf> = vec![root.join("xtask/src"), root.join("tests/src")];
    for e in std::fs::read_dir(root.join("crates")).unwrap().flatten() {
        sources.push(e.path().join("src"));
    }
    let mut circles = Vec::new();
    let mut crates_seen = 0;
    for src in sources.iter().filter(|s| s.is_dir()) {
        crates_seen += 1;
        let files = files_with_extension(src, "rs");
        let modules: BTreeSet<String> = files.iter().filter_map(|f| top_module(src, f)).collect();
        let mut edges: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
        for f in &files {
            let Some(m) = top_module(src, f) else {
                continue;
            };
            let text = std::fs::read_to_string(f).unwrap();
            let mut used = uses(&code(&text), &modules);
            used.remove(&m);
            edges.entry(m).or_default().extend(used);
        }
        for m in &modules {
            if let Some(c) = cycle_from(m, &edges, &mut Vec::new()) {
                circles.push(format!("{}: {}", src.display(), c.join(" -> ")));
            }
        }
    }
    assert!(crates_seen >= 10, "found only {crates_seen} crates");
    assert!(
        circles.is_empty(),
        "modules that import each other (move what both need into a module of its own):\n{}",
        circles.join("\n")
    );
}

/// The check itself finds a circle, through a group import and a path.
#[test]
fn a_circle_is_found() {
    let modules: BTreeSet<String> = ["a", "b", "c"].map(String::from).into();
    assert_eq!(
        uses("use crate::{b::X, c};\nfn f() { crate::a::g() }", &modules),
        modules
    );
    let edges: BTreeMap<String, BTreeSet<String>> =
        [("a", vec!["b"]), ("b", vec!["c"]), ("c", vec!["a"])]
            .into_iter()
            .map(|(k, v)| (k.to_string(), v.into_iter().map(String::from).collect()))
            .collect();
    assert_eq!(
        cycle_from("a", &edges, &mut Vec::new()),
        Some(
            vec!["a", "b", "c", "a"]
                .into_iter()
                .map(String::from)
                .collect()
        )
    );
    assert_eq!(code("use crate::b; // crate::c\n"), "use crate::b; ");
}

/// spirv-out/ holds what runs and stays small: at most 40 files and 4 MB (GLSL, HLSL and MSL
/// are made on demand).
#[test]
fn spirv_out_stays_small() {
    let dir = workspace().join("spirv-out");
    let (mut files, mut bytes) = (0, 0);
    for e in std::fs::read_dir(&dir).unwrap().flatten() {
        files += 1;
        bytes += e.metadata().unwrap().len();
    }
    assert!(
        files <= 40 && bytes <= 4_000_000,
        "spirv-out/ has {files} files and {bytes} bytes (at most 40 and 4 MB)"
    );
}
