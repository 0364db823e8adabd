//! What the CLI tests share: running the `stratus` binary as a user does.

use std::{
    path::{Path, PathBuf},
    process::Command,
};

/// Runs `stratus` with `args` and the extra environment `env`: whether it succeeded, and its
/// stdout and stderr together.
pub fn stratus_with(args: &[&str], env: &[(&str, &str)]) -> (bool, String) {
    run(Command::new(env!("CARGO_BIN_EXE_stratus")), args, env)
}

/// Runs `stratus` with `args` and the extra environment `env` in the working directory `dir`.
#[allow(dead_code)] // not every test file uses it
pub fn stratus_in(dir: &Path, args: &[&str], env: &[(&str, &str)]) -> (bool, String) {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_stratus"));
    cmd.current_dir(dir);
    run(cmd, args, env)
}

fn run(mut cmd: Command, args: &[&str], env: &[(&str, &str)]) -> (bool, String) {
    let out = cmd
        .args(args)
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .envs(env.iter().copied())
        .output()
        .expect("running stratus");
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    (out.status.success(), text)
}

/// Runs `stratus` with `args`.
#[allow(dead_code)] // not every test file uses both
pub fn stratus(args: &[&str]) -> (bool, String) {
    stratus_with(args, &[])
}

/// An empty folder `name` under the test target's scratch space.
#[allow(dead_code)] // not every test file uses it
pub fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir
}
