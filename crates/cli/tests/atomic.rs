//! Files the CLI writes are complete or absent: a render killed while it writes its image
//! leaves no half-written image under the name asked for.

mod common;

use std::{
    process::{Command, Stdio},
    time::{Duration, Instant},
};

use common::scratch;

/// A 2048x2048 EXR of a camera looking at the ground (no cloud to march, so the frame is quick
/// and the write, about 9 MB, is the slow part): the render is killed the moment a file appears
/// in the output folder, that is while the image is being written.
#[test]
fn a_render_killed_mid_write_leaves_no_partial_image() {
    let dir = scratch("atomic-write");
    let scene = dir.join("down.toml");
    std::fs::write(&scene, "[camera]\npitch_deg = -60.0\n").expect("scene");
    let out_dir = dir.join("out");
    std::fs::create_dir_all(&out_dir).expect("out dir");
    let out = out_dir.join("big.exr");
    let run = || {
        Command::new(env!("CARGO_BIN_EXE_stratus"))
            .args(["render", "--scene"])
            .arg(&scene)
            .args(["--size", "2048x2048", "--out"])
            .arg(&out)
            .env("XDG_RUNTIME_DIR", std::env::temp_dir())
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("starting stratus")
    };

    let mut child = run();
    let start = Instant::now();
    let mut seen = Vec::new();
    while start.elapsed() < Duration::from_secs(120) {
        seen = std::fs::read_dir(&out_dir)
            .expect("out dir")
            .flatten()
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .collect();
        if !seen.is_empty() || child.try_wait().expect("polling stratus").is_some() {
            break;
        }
        std::thread::sleep(Duration::from_millis(1));
    }
    let _ = child.kill();
    let status = child.wait().expect("waiting for stratus");
    assert!(
        !seen.is_empty(),
        "stratus ended ({status}) before writing anything"
    );
    // Killed while writing: the image is absent (only the hidden temporary file may be
    // left), or, had the write already finished, complete.
    if out.exists() {
        let image = stratus_compare::Image::load(&out).expect("a complete image");
        assert_eq!((image.width, image.height), (2048, 2048));
    } else {
        assert!(
            seen.iter()
                .all(|n| n.starts_with(".big.exr.") && n.ends_with(".partial.exr")),
            "files while writing: {seen:?}"
        );
    }

    // Left to finish, the same render leaves the image and no temporary file.
    let status = run().wait().expect("waiting for stratus");
    assert!(status.success(), "{status}");
    let image = stratus_compare::Image::load(&out).expect("the image");
    assert_eq!((image.width, image.height), (2048, 2048));
    let left: Vec<String> = std::fs::read_dir(&out_dir)
        .expect("out dir")
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n != "big.exr" && !n.ends_with(".partial.exr"))
        .collect();
    assert!(left.is_empty(), "{left:?}");
    let partial_of_this_run = std::fs::read_dir(&out_dir)
        .expect("out dir")
        .flatten()
        .filter(|e| e.file_name().to_string_lossy().ends_with(".partial.exr"))
        .count();
    assert!(partial_of_this_run <= 1, "temporary files pile up");
}
