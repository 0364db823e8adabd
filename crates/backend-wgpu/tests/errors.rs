//! What a user sees when the device goes away or a Vulkan piece is missing: one sentence
//! naming what happened and what to do, never a panic or wgpu's internal message alone.
//!
//! - Device loss: a renderer on its own device, and one on an application's device, render a
//!   frame; the device is destroyed (`wgpu::Device::destroy`, the loss WebGPU defines and the
//!   one a test can cause); the next frame must fail, saying the device was lost
//!   ([`Error::DeviceLost`] on the renderer's own device, whose lost callback it sets).
//! - A missing validation layer: this test binary runs again in a child process with the
//!   loader's layer path pointed at nothing, so the parent's own Vulkan state is untouched.

use std::process::Command;

use stratus_backend_wgpu::{Api, Error, Options, Renderer};
use stratus_graph::{FrameInput, FramePlan, Program};
use stratus_test_support::{record_wgpu_log, small, small_noise, take_wgpu_log};

const CHILD: &str = "STRATUS_WGPU_ERROR_CHILD";

/// Renders a frame, destroys the device, and returns what the next frame says.
fn lose_device(r: &mut Renderer, destroy: impl FnOnce(&Renderer)) -> Error {
    let scene = small("cumulus-noon", 16, 9);
    let noise = small_noise(0);
    let plan = FramePlan::for_scene(&scene, false).expect("plan");
    let frame = FrameInput::new(&plan, &scene, &noise);
    r.render(&frame).expect("the frame before the loss renders");
    destroy(r);
    let err = r.render(&frame).expect_err("a lost device renders nothing");
    // And it stays lost, with the same sentence, frame after frame.
    let again = r.render(&frame).expect_err("still lost");
    assert_eq!(err.to_string(), again.to_string());
    err
}

#[test]
fn a_lost_device_of_its_own_is_named_and_stays_lost() {
    record_wgpu_log();
    let mut r = Renderer::new(Options {
        api: Api::Vulkan,
        validation: false,
    })
    .expect("renderer");
    let err = lose_device(&mut r, |r| r.device().destroy());
    assert!(matches!(err, Error::DeviceLost { .. }), "{err:?}");
    let text = err.to_string();
    assert!(
        text.contains("was lost") && text.contains("Destroyed") && text.contains("new renderer"),
        "{text}"
    );
    // What wgpu logged about the destroyed device is expected here, not a validation failure.
    take_wgpu_log();
}

#[test]
fn a_lost_application_device_is_named() {
    record_wgpu_log();
    // The application's own device, as `examples/` create one; the renderer sets no callback
    // on it (the application keeps its own), so the loss shows through wgpu's errors.
    let instance = wgpu::Instance::new({
        let mut d = wgpu::InstanceDescriptor::new_without_display_handle();
        d.backends = wgpu::Backends::VULKAN;
        d
    });
    let adapter = pollster::block_on(instance.request_adapter(&Default::default()))
        .expect("a Vulkan adapter");
    let (device, queue) =
        pollster::block_on(adapter.request_device(&Default::default())).expect("device");
    let mut r = Renderer::from_device(device.clone(), queue, Program::embedded().expect("program"))
        .expect("renderer");
    let err = lose_device(&mut r, |_| device.destroy());
    // wgpu reports a loss only through the callback, which is the application's: the
    // renderer sees a read-back fail, and says what that can mean.
    assert!(err.to_string().contains("the device was lost"), "{err}");
    take_wgpu_log();
}

/// In the child: create a renderer with validation and print the error between markers.
#[test]
fn child() {
    if std::env::var(CHILD).is_err() {
        return; // Not a child: nothing to do.
    }
    match Renderer::new(Options {
        api: Api::Vulkan,
        validation: true,
    }) {
        Ok(r) => println!("<<<ok {}>>>", r.adapter()),
        Err(e) => println!("<<<{e}>>>"),
    }
}

#[test]
fn no_validation_layer_names_vulkan_validationlayers() {
    let exe = std::env::current_exe().expect("test binary");
    let out = Command::new(exe)
        .args(["--exact", "child", "--nocapture", "--test-threads=1"])
        .env(CHILD, "validation")
        .env("VK_LAYER_PATH", "/nonexistent")
        .env_remove("VK_ADD_LAYER_PATH")
        .output()
        .expect("child runs");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "child failed: {stdout}");
    let start = stdout.find("<<<").expect("child printed a result") + 3;
    let end = stdout[start..].find(">>>").expect("end marker") + start;
    let message = &stdout[start..end];
    assert!(
        message.contains("VK_LAYER_KHRONOS_validation")
            && message.contains("apt-get install vulkan-validationlayers"),
        "{message}"
    );
}
