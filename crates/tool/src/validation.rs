//! Validation for the commands that run GPU work for long (`view`, `soak`): with it on, every
//! warning or error wgpu logs (the Vulkan validation layer's messages about wgpu's calls
//! arrive this way) is recorded here, so that the command can fail on any. The ash backend
//! gathers its layer's messages itself and returns them as errors.

use std::sync::Mutex;

struct Messages(Mutex<Vec<String>>);

impl log::Log for Messages {
    fn enabled(&self, m: &log::Metadata) -> bool {
        // EGL start-up logs the platforms it tries before settling on one that works; those
        // are not validation messages.
        m.level() <= log::Level::Warn
            && m.target().starts_with("wgpu")
            && !m.target().starts_with("wgpu_hal::gles::egl")
    }
    fn log(&self, r: &log::Record) {
        if self.enabled(r.metadata())
            && let Ok(mut v) = self.0.lock()
        {
            v.push(format!("{} {}: {}", r.level(), r.target(), r.args()));
        }
    }
    fn flush(&self) {}
}

static MESSAGES: Messages = Messages(Mutex::new(Vec::new()));

/// Installs the recorder as the process's logger (the first call does; later ones nothing).
pub fn record() {
    if log::set_logger(&MESSAGES).is_ok() {
        log::set_max_level(log::LevelFilter::Warn);
    }
}

/// What wgpu logged since the last call (and forgets it).
pub fn take() -> Vec<String> {
    std::mem::take(&mut *MESSAGES.0.lock().unwrap_or_else(|e| e.into_inner()))
}
