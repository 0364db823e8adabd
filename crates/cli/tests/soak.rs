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

#[test]
fn create_destroy_cycles_leave_nothing_alive_under_validation() {
    // With --validate the Vulkan layer's object tracking reports any object still alive when a
    // device is destroyed, and the soak fails on any message (the ash backend's own test
    // checks that a leaked object is reported).
    for backend in ["wgpu", "ash"] {
        let (ok, text) = stratus(&["soak", "--cycles", "12", "--validate", "--backend", backend]);
        assert!(ok, "{backend}: {text}");
        assert!(
            text.contains("cycles: 12 renderers created") && text.contains("non-finite values: 0"),
            "{text}"
        );
        assert!(
            text.contains("validation: on, no messages over 12 device teardowns"),
            "{text}"
        );
        assert!(text.contains("a cycle over the last 2"), "{text}");
    }
    // The CPU renderer has no layer to ask: said, not claimed.
    let (ok, text) = stratus(&["soak", "--cycles", "2", "--validate", "--backend", "cpu"]);
    assert!(ok, "{text}");
    assert!(
        text.contains("validation: asked for, but the CPU renderer has no validation layer"),
        "{text}"
    );
    let (ok, text) = stratus(&[
        "soak",
        "--frames",
        "8",
        "--size",
        "32x18",
        "--settle",
        "2",
        "--validate",
    ]);
    assert!(ok, "{text}");
    assert!(
        text.contains("validation: on, no messages over 8 frames"),
        "{text}"
    );
}
