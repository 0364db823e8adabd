//! Device limits as a user meets them: a clear error naming the limit, never a panic.

mod common;

use common::stratus;

/// The largest accepted size on wgpu: a clear error naming the device limit before anything
/// is allocated where the read-back would not fit (lavapipe: 4 GiB against 2 GiB), never a
/// panic (an NVIDIA H100 panicked here on an empty mapped buffer before).
#[test]
fn the_largest_size_is_refused_clearly_where_it_does_not_fit() {
    let (ok, text) = stratus(&[
        "render",
        "--backend",
        "wgpu",
        "--size",
        "16384x16384",
        "--out",
        "/nonexistent-dir/big.png",
    ]);
    assert!(!text.contains("panicked"), "{text}");
    if !ok {
        assert!(
            text.contains("max_buffer_size") || text.contains("max_texture_dimension"),
            "{text}"
        );
    }
}
