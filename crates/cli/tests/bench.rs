//! `stratus bench --references-only` as a user runs it on a machine with a GPU: it fills the
//! reference cache, measures nothing, and a second run finds everything there. Validation is
//! on (`STRATUS_VALIDATION=1`).

mod common;

use common::{scratch, stratus_with};

/// The stability case (single scattering: its references are the CPU's converged quadrature)
/// at a tiny size, so the test takes seconds.
#[test]
fn references_only_fills_the_cache_and_measures_nothing() {
    let dir = scratch("bench-references-only");
    let out = dir.join("out");
    let cache = dir.join("xdg");
    let args = [
        "bench",
        "--references-only",
        "--quick",
        "--scenes",
        "stress-thick",
        "--size",
        "16x9",
        "--out",
        out.to_str().expect("utf-8 path"),
    ];
    let env = [
        ("STRATUS_VALIDATION", "1"),
        ("XDG_CACHE_HOME", cache.to_str().expect("utf-8 path")),
    ];
    let files = || {
        std::fs::read_dir(cache.join("stratus"))
            .map(|d| d.count())
            .unwrap_or(0)
    };
    let (ok, text) = stratus_with(&args, &env);
    assert!(ok, "{text}");
    assert!(text.contains("every reference of the sweep ("), "{text}");
    let first = files();
    // The sweep's configurations differ in what the quadrature renders (phase model,
    // Beer-Powder, ...): more than one reference.
    assert!(first > 1, "{first} references cached\n{text}");
    assert!(!out.join("results.csv").exists(), "it measured: {text}");
    assert!(!out.join("results.json").exists(), "it measured: {text}");
    // Everything is cached now: the second run renders nothing new.
    let (ok, text) = stratus_with(&args, &env);
    assert!(ok, "{text}");
    assert_eq!(files(), first, "{text}");
}

/// `--references-only` and `--replot` ask for opposite things.
#[test]
fn references_only_and_replot_are_refused_together() {
    let (ok, text) = stratus_with(&["bench", "--references-only", "--replot"], &[]);
    assert!(!ok, "{text}");
    assert!(
        text.contains("--replot") && text.contains("cannot be used with"),
        "{text}"
    );
}
