//! `stratus soak` as a user runs it: a short loop reports no non-finite values, its memory and
//! GPU object figures and the drift after a stop, and refuses the still-only reference.

mod common;

use common::stratus;

#[test]
fn a_short_soak_reports_its_figures() {
    for backend in ["wgpu", "ash"] {
        let (ok, text) = stratus(&[
            "soak",
            "--frames",
            "40",
            "--size",
            "32x18",
            "--settle",
            "4",
            "--backend",
            backend,
        ]);
        assert!(ok, "{backend}: {text}");
        assert!(
            text.contains("non-finite values: 0 (in 0 of 40 frames)"),
            "{text}"
        );
        assert!(text.contains("RSS: ") && text.contains("MiB"), "{text}");
        // A steady loop creates no GPU objects after its first frame (the command fails if it
        // does), and says so.
        assert!(
            text.contains("at the end (a steady loop creates none)"),
            "{text}"
        );
        assert!(text.contains("drift: 4 frames after the stop"), "{text}");
    }
    let (ok, text) = stratus(&["soak", "--frames", "2", "--backend", "reference"]);
    assert!(!ok && text.contains("stills only"), "{text}");
}
