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

/// `--fields-only` measures the cloud fields from above of the cumulus presets and weather
/// states and writes them, without a sweep: the states on convective cells count many more
/// clouds than the presets on the weather map alone, and every row is the committed
/// `docs/cloud-fields.csv`'s (which docs/cloud-fields.md's table quotes), within what another
/// build of the same device rounds differently.
#[test]
fn fields_only_measures_the_cloud_fields() {
    let dir = scratch("bench-fields-only");
    let out = dir.join("out");
    let (ok, text) = stratus_with(
        &[
            "bench",
            "--fields-only",
            "--out",
            out.to_str().expect("utf-8 path"),
        ],
        &[],
    );
    assert!(ok, "{text}");
    let csv = std::fs::read_to_string(out.join("fields.csv")).expect("fields.csv");
    let rows: Vec<Vec<&str>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect())
        .collect();
    let names: Vec<&str> = rows.iter().map(|r| r[0]).collect();
    assert_eq!(
        names,
        [
            "cumulus-noon",
            "sunset",
            "above-clouds",
            "state few",
            "state scattered",
            "state broken"
        ],
        "{csv}"
    );
    let clouds = |name: &str| -> u64 {
        rows.iter().find(|r| r[0] == name).unwrap()[2]
            .parse()
            .unwrap()
    };
    // The presets stand on convective cells: many separate clouds (the weather map alone
    // drew 18 over the default's square).
    assert!(clouds("cumulus-noon") >= 100, "{csv}");
    assert!(!out.join("results.json").exists(), "it swept: {text}");
    // The committed rows are lavapipe's; another device draws its own (the conformance
    // suite's device classes).
    if std::env::var("STRATUS_DEVICE_CLASS").is_ok_and(|c| c == "other") {
        return;
    }
    let committed = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/cloud-fields.csv"),
    )
    .expect("docs/cloud-fields.csv");
    assert_eq!(csv.lines().next(), committed.lines().next(), "the columns");
    let num = |s: &str| -> Option<f64> { s.parse().ok() };
    for (got, want) in csv.lines().zip(committed.lines()).skip(1) {
        let (g, w): (Vec<&str>, Vec<&str>) = (got.split(',').collect(), want.split(',').collect());
        assert_eq!(g[0], w[0], "{csv}");
        // fraction, clouds, cut, largest (m), D, its s.e., b, its s.e., b's sizes (m).
        let tolerance = [
            0.003, 3.0, 3.0, 150.0, 0.01, 0.005, 0.05, 0.05, 400.0, 600.0,
        ];
        for (k, tol) in tolerance.iter().enumerate() {
            match (num(g[k + 1]), num(w[k + 1])) {
                (Some(a), Some(b)) => assert!(
                    (a - b).abs() <= *tol,
                    "{}: column {} is {a}, the committed {b}\n{csv}",
                    g[0],
                    k + 1
                ),
                (None, None) => {}
                _ => panic!("{}: column {} fitted in one only\n{csv}", g[0], k + 1),
            }
        }
    }
    assert_eq!(csv.lines().count(), committed.lines().count(), "{csv}");
}
