//! What a user sees when Vulkan pieces are missing: one sentence naming what is missing and
//! the package that provides it. Each case runs this test binary again in a child process
//! with the loader pointed at nothing (environment variables of the Vulkan loader), so the
//! parent's own Vulkan state is untouched.

use std::process::Command;

use stratus_backend_ash::{Options, Renderer};

const CHILD: &str = "STRATUS_ASH_ERROR_CHILD";

/// In the child: create a renderer and print the error between markers.
#[test]
fn child() {
    let Ok(case) = std::env::var(CHILD) else {
        return; // Not a child: nothing to do.
    };
    let validation = case == "validation";
    match Renderer::new(Options { validation }) {
        Ok(r) => {
            println!("<<<ok {}>>>", r.adapter());
            r.finish().expect("teardown");
        }
        Err(e) => println!("<<<{e}>>>"),
    }
}

fn run_child(case: &str, env: &[(&str, &str)]) -> String {
    let exe = std::env::current_exe().expect("test binary");
    let mut cmd = Command::new(exe);
    cmd.args(["--exact", "child", "--nocapture", "--test-threads=1"])
        .env(CHILD, case);
    for (k, v) in env {
        cmd.env(k, v);
    }
    let out = cmd.output().expect("child runs");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "child failed: {stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let start = stdout.find("<<<").expect("child printed a result") + 3;
    let end = stdout[start..].find(">>>").expect("end marker") + start;
    stdout[start..end].to_string()
}

#[test]
fn no_driver_names_mesa_vulkan_drivers() {
    let message = run_child(
        "driver",
        &[
            ("VK_ICD_FILENAMES", "/nonexistent/icd.json"),
            ("VK_DRIVER_FILES", "/nonexistent/icd.json"),
        ],
    );
    assert!(
        message.contains("no usable Vulkan device") && message.contains("mesa-vulkan-drivers"),
        "{message}"
    );
}

#[test]
fn no_validation_layer_names_vulkan_validationlayers() {
    let message = run_child("validation", &[("VK_LAYER_PATH", "/nonexistent")]);
    assert!(
        message.contains("VK_LAYER_KHRONOS_validation")
            && message.contains("apt-get install vulkan-validationlayers"),
        "{message}"
    );
}
