//! Helpers every Stratus test shares, written once: the recorder that turns wgpu's (and through
//! it the Vulkan validation layer's) warnings into test failures, bit-exact frame diffs, noise
//! generated once per seed, small scenes and the source files below a folder. Dev-only: no
//! renderer depends on it.

#![deny(missing_docs)]

use std::{
    collections::HashMap,
    path::{Path, PathBuf},
    sync::{Arc, Mutex, OnceLock},
};

use stratus_graph::FrameOutput;
pub use stratus_graph::output::median;
use stratus_noise::{NoiseConfig, NoiseSet, ShapeSize};
use stratus_scene::Scene;

/// Records every warning or error that wgpu logs (the Vulkan validation layer's messages about
/// wgpu's calls arrive this way), so that wgpu is held to the same standard as the ash
/// backend's validation. EGL start-up logs the platforms it tries before settling on one that
/// works (e.g. "DRI2: failed to load driver" without /dev/dri); those are not validation
/// messages and are ignored.
struct Recorder(Mutex<Vec<String>>);

impl log::Log for Recorder {
    fn enabled(&self, m: &log::Metadata) -> bool {
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

static RECORDER: Recorder = Recorder(Mutex::new(Vec::new()));

/// Installs the recorder as the test binary's logger (once; later calls do nothing).
pub fn record_wgpu_log() {
    static ONCE: OnceLock<()> = OnceLock::new();
    ONCE.get_or_init(|| {
        log::set_logger(&RECORDER).expect("the only logger in this test binary");
        log::set_max_level(log::LevelFilter::Warn);
    });
}

/// The messages logged since the last call (and forgets them).
pub fn take_wgpu_log() -> Vec<String> {
    std::mem::take(&mut *RECORDER.0.lock().unwrap_or_else(|e| e.into_inner()))
}

/// Fails with every message logged since the last call.
pub fn assert_no_wgpu_messages() {
    let msgs = take_wgpu_log();
    assert!(msgs.is_empty(), "wgpu logged:\n{}", msgs.join("\n"));
}

fn float_difference(name: &str, what: &str, a: &[f32], b: &[f32]) -> Option<String> {
    let differing = a
        .iter()
        .zip(b)
        .filter(|(x, y)| x.to_bits() != y.to_bits())
        .count();
    if differing == 0 && a.len() == b.len() {
        return None;
    }
    let max = a
        .iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0f32, f32::max);
    Some(format!(
        "{name}: {what}: {differing} of {} floats differ (lengths {} and {}), max abs difference {max:e}",
        a.len().min(b.len()),
        a.len(),
        b.len()
    ))
}

/// Every way two frames differ bit for bit (radiance, depth, image, counters, other
/// read-back resources), each as a sentence starting with `name`; empty when identical.
pub fn frame_differences(name: &str, a: &FrameOutput, b: &FrameOutput) -> Vec<String> {
    let mut problems = Vec::new();
    problems.extend(float_difference(name, "radiance", &a.radiance, &b.radiance));
    problems.extend(float_difference(name, "depth", &a.depth, &b.depth));
    if a.image != b.image {
        let n = a.image.iter().zip(&b.image).filter(|(x, y)| x != y).count();
        problems.push(format!("{name}: image: {n} bytes differ"));
    }
    if a.stats != b.stats {
        problems.push(format!(
            "{name}: counters differ: {:?} and {:?}",
            a.stats, b.stats
        ));
    }
    if a.resources != b.resources {
        problems.push(format!("{name}: read-back resources differ"));
    }
    problems
}

/// Noise sets by seed (and shape size), generated once each: slow in debug builds. Shared as
/// `Arc`s, so that a persistent renderer uploads each once.
#[derive(Default)]
pub struct NoiseCache(HashMap<(u64, bool), Arc<NoiseSet>>);

impl NoiseCache {
    /// The noise set of `scene`'s seed and shape texture.
    pub fn get(&mut self, scene: &Scene) -> Arc<NoiseSet> {
        let seed = scene.noise.seed;
        let hzd = scene.noise.shape_texture == stratus_scene::ShapeTexture::Hzd;
        self.0
            .entry((seed, hzd))
            .or_insert_with(|| {
                Arc::new(NoiseSet::generate(&NoiseConfig {
                    seed,
                    shape: if hzd {
                        ShapeSize::Hzd
                    } else {
                        ShapeSize::Thesis
                    },
                    ..Default::default()
                }))
            })
            .clone()
    }
}

/// Small noise textures, quick to make, for tests about life cycles rather than clouds.
pub fn small_noise(seed: u64) -> Arc<NoiseSet> {
    Arc::new(NoiseSet::generate(&NoiseConfig {
        seed,
        shape: ShapeSize::Thesis,
        weather_size: 64,
        curl_size: 16,
        detail_size: 8,
    }))
}

/// The preset `name` at a small size.
pub fn small(name: &str, w: u32, h: u32) -> Scene {
    Scene::preset(name)
        .unwrap_or_else(|e| panic!("preset {name}: {e}"))
        .with_size(w, h)
}

/// Holds the block of the repository's `doc` (a path from the workspace root) between
/// `<!-- generated: ID -->` and `<!-- end generated -->` to `expected`, the text a test derives
/// from the block's source; with `STRATUS_UPDATE_DOCS=1` rewrites the block instead. This is how
/// a table of docs/ stays what its source says: the test that computes it owns it.
pub fn docs_block(doc: &str, id: &str, expected: &str) {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let path = root.join(doc);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("reading {doc}: {e}"));
    let begin = format!("<!-- generated: {id} -->\n");
    let end = "<!-- end generated -->";
    let start = text
        .find(&begin)
        .unwrap_or_else(|| panic!("{doc} has no `{}`", begin.trim()))
        + begin.len();
    let stop = start
        + text[start..]
            .find(end)
            .unwrap_or_else(|| panic!("{doc}: `{}` is not closed", begin.trim()));
    if text[start..stop] == *expected {
        return;
    }
    if std::env::var_os("STRATUS_UPDATE_DOCS").is_some() {
        let new = format!("{}{expected}{}", &text[..start], &text[stop..]);
        std::fs::write(&path, new).unwrap_or_else(|e| panic!("writing {doc}: {e}"));
        return;
    }
    panic!(
        "{doc}'s block `{id}` no longer matches its source; rerun the test with \
         `STRATUS_UPDATE_DOCS=1` to rewrite it.\nexpected:\n{expected}\nfound:\n{}",
        &text[start..stop]
    );
}

/// Every file below `dir` (recursively) whose extension is `ext` (`"rs"`, `"wgsl"`), in the
/// order the file system lists them; none where `dir` cannot be read.
pub fn files_with_extension(dir: &Path, ext: &str) -> Vec<PathBuf> {
    fn walk(dir: &Path, ext: &str, out: &mut Vec<PathBuf>) {
        let Ok(entries) = std::fs::read_dir(dir) else {
            return;
        };
        for e in entries.flatten() {
            let path = e.path();
            if path.is_dir() {
                walk(&path, ext, out);
            } else if path.extension().is_some_and(|x| x == ext) {
                out.push(path);
            }
        }
    }
    let mut out = Vec::new();
    walk(dir, ext, &mut out);
    out
}
