//! The WGSL tree: source files, the module list (`wgsl/modules.toml`) and composition of several
//! files into one naga module with a map back to the original files.

use std::{
    collections::BTreeMap,
    fmt,
    path::{Path, PathBuf},
};

use serde::Deserialize;
use sha2::{Digest, Sha256};

/// The name of the file under `wgsl/` that lists modules and their variants.
pub const MODULES_FILE: &str = "modules.toml";

/// The name of the frame graph file under `wgsl/`.
pub const GRAPH_FILE: &str = "graph.toml";

/// Every WGSL source file and the module list, as read from a folder or embedded at build time.
#[derive(Clone, Debug)]
pub struct ShaderTree {
    /// How paths are shown in diagnostics, e.g. `wgsl` (so errors read `wgsl/clouds.wgsl:3:1`).
    pub label: String,
    /// File contents by path relative to the tree root, `/`-separated.
    pub files: BTreeMap<String, String>,
    /// The modules declared in `modules.toml`, in declaration order.
    pub modules: Vec<ModuleSpec>,
}

/// One WGSL program: files concatenated in order, plus its exported variants.
#[derive(Clone, Debug, PartialEq)]
pub struct ModuleSpec {
    /// Module name; output files are called `<name>.<variant>.<ext>`.
    pub name: String,
    /// Source files (relative to the tree root), composed in this order.
    pub files: Vec<String>,
    /// Named sets of override values, each translated to every target language.
    pub variants: Vec<VariantSpec>,
}

/// A named set of pipeline-override values (naga resolves them before translation).
#[derive(Clone, Debug, PartialEq)]
pub struct VariantSpec {
    /// Variant name, used in file names and by the frame plan.
    pub name: String,
    /// What the variant is for, one line.
    pub description: String,
    /// Override values by WGSL identifier; booleans are 0 or 1, as WebGPU passes them.
    pub overrides: BTreeMap<String, f64>,
}

/// Errors reading the tree itself (not WGSL diagnostics).
#[derive(Debug, thiserror::Error)]
pub enum TreeError {
    /// A file or folder could not be read.
    #[error("{path}: {source}")]
    Io {
        /// The path that failed.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
    /// `modules.toml` is malformed or names something that does not exist.
    #[error("{label}/{file}: {message}")]
    Modules {
        /// Tree label.
        label: String,
        /// Always [`MODULES_FILE`].
        file: &'static str,
        /// What is wrong.
        message: String,
    },
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ModulesToml {
    #[serde(default)]
    module: Vec<ModuleToml>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ModuleToml {
    name: String,
    files: Vec<String>,
    #[serde(default)]
    variant: Vec<VariantToml>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct VariantToml {
    name: String,
    description: String,
    #[serde(default)]
    overrides: BTreeMap<String, toml::Value>,
}

impl ShaderTree {
    /// The WGSL embedded into this crate at build time (the workspace's `wgsl/` folder).
    pub fn embedded() -> Result<Self, TreeError> {
        let files = crate::EMBEDDED_FILES
            .iter()
            .map(|(p, t)| (p.to_string(), t.to_string()))
            .collect();
        Self::from_files("wgsl", files)
    }

    /// Reads every `.wgsl` file, `modules.toml` and `graph.toml` below `dir`. `label` is how the folder is
    /// named in diagnostics.
    pub fn from_dir(dir: &Path, label: &str) -> Result<Self, TreeError> {
        let mut files = BTreeMap::new();
        read_dir_into(dir, dir, &mut files)?;
        Self::from_files(label, files)
    }

    /// Builds a tree from in-memory files (path relative to the root -> contents).
    pub fn from_files(label: &str, files: BTreeMap<String, String>) -> Result<Self, TreeError> {
        let modules_err = |message: String| TreeError::Modules {
            label: label.to_string(),
            file: MODULES_FILE,
            message,
        };
        let text = files
            .get(MODULES_FILE)
            .ok_or_else(|| modules_err("missing: it must list the WGSL modules".into()))?;
        let parsed: ModulesToml = toml::from_str(text).map_err(|e| {
            let at = e
                .span()
                .map(|s| {
                    let (line, col) = line_col(text, s.start);
                    format!("{line}:{col}: ")
                })
                .unwrap_or_default();
            modules_err(format!("{at}{}", e.message()))
        })?;
        let mut modules = Vec::new();
        for m in parsed.module {
            for f in &m.files {
                if !files.contains_key(f) {
                    return Err(modules_err(format!(
                        "module `{}` lists `{f}`, which does not exist",
                        m.name
                    )));
                }
            }
            if m.variant.is_empty() {
                return Err(modules_err(format!(
                    "module `{}` declares no variant",
                    m.name
                )));
            }
            let mut variants = Vec::new();
            for v in m.variant {
                let mut overrides = BTreeMap::new();
                for (k, val) in v.overrides {
                    let x = match val {
                        toml::Value::Boolean(b) => f64::from(u8::from(b)),
                        toml::Value::Integer(i) => i as f64,
                        toml::Value::Float(f) => f,
                        other => {
                            return Err(modules_err(format!(
                                "variant `{}.{}`: override `{k}` = {other}: must be a boolean or a number",
                                m.name, v.name
                            )));
                        }
                    };
                    overrides.insert(k, x);
                }
                variants.push(VariantSpec {
                    name: v.name,
                    description: v.description,
                    overrides,
                });
            }
            modules.push(ModuleSpec {
                name: m.name,
                files: m.files,
                variants,
            });
        }
        Ok(Self {
            label: label.to_string(),
            files,
            modules,
        })
    }

    /// The module called `name`, if declared.
    pub fn module(&self, name: &str) -> Option<&ModuleSpec> {
        self.modules.iter().find(|m| m.name == name)
    }

    /// SHA-256 over every file (path and contents), hex: changes whenever any source changes.
    pub fn sha256(&self) -> String {
        let mut h = Sha256::new();
        for (path, text) in &self.files {
            h.update(path.as_bytes());
            h.update([0]);
            h.update(text.as_bytes());
            h.update([0]);
        }
        hex(&h.finalize())
    }

    /// Concatenates a module's files into one WGSL string, remembering where each came from.
    pub fn compose(&self, module: &ModuleSpec) -> Composed {
        let mut text = String::new();
        let mut segments = Vec::new();
        for f in &module.files {
            let body = &self.files[f];
            segments.push(Segment {
                start: text.len(),
                len: body.len(),
                file: format!("{}/{}", self.label, f),
            });
            text.push_str(body);
            if !body.ends_with('\n') {
                text.push('\n');
            }
        }
        Composed { text, segments }
    }
}

fn read_dir_into(
    base: &Path,
    dir: &Path,
    out: &mut BTreeMap<String, String>,
) -> Result<(), TreeError> {
    let io = |path: &Path| {
        let path = path.to_path_buf();
        move |source| TreeError::Io { path, source }
    };
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .map_err(io(dir))?
        .collect::<Result<_, _>>()
        .map_err(io(dir))?;
    entries.sort_by_key(|e| e.path());
    for e in entries {
        let path = e.path();
        if path.is_dir() {
            read_dir_into(base, &path, out)?;
        } else if path.extension().is_some_and(|x| x == "wgsl")
            || path
                .file_name()
                .is_some_and(|n| n == MODULES_FILE || n == GRAPH_FILE)
        {
            let text = std::fs::read_to_string(&path).map_err(io(&path))?;
            let rel = path
                .strip_prefix(base)
                .expect("walked below base")
                .to_string_lossy()
                .replace('\\', "/");
            out.insert(rel, text);
        }
    }
    Ok(())
}

/// A module's composed WGSL and the map from byte offsets back to the original files.
#[derive(Clone, Debug)]
pub struct Composed {
    /// The concatenated source handed to naga.
    pub text: String,
    segments: Vec<Segment>,
}

#[derive(Clone, Debug)]
struct Segment {
    start: usize,
    len: usize,
    file: String,
}

/// A position in an original source file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Location {
    /// Path as shown to the user, e.g. `wgsl/clouds.wgsl`.
    pub file: String,
    /// 1-based line.
    pub line: u32,
    /// 1-based column, in characters.
    pub col: u32,
    /// The whole source line, without its newline.
    pub line_text: String,
}

impl Composed {
    /// Maps a byte offset in [`Composed::text`] to the file, line and column it came from.
    pub fn locate(&self, offset: usize) -> Location {
        let seg = self
            .segments
            .iter()
            .rev()
            .find(|s| s.start <= offset)
            .or(self.segments.first())
            .expect("a module has at least one file");
        let body = &self.text[seg.start..seg.start + seg.len];
        let local = offset.saturating_sub(seg.start).min(body.len());
        let (line, col) = line_col(body, local);
        let line_start = body[..local].rfind('\n').map_or(0, |i| i + 1);
        let line_end = body[local..].find('\n').map_or(body.len(), |i| local + i);
        Location {
            file: seg.file.clone(),
            line,
            col,
            line_text: body[line_start..line_end].to_string(),
        }
    }

    /// The first file of the module, for errors that carry no span.
    pub fn first_file(&self) -> &str {
        &self.segments[0].file
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}:{}", self.file, self.line, self.col)
    }
}

/// 1-based (line, column in characters) of a byte offset.
fn line_col(text: &str, offset: usize) -> (u32, u32) {
    let offset = floor_char_boundary(text, offset.min(text.len()));
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let col = before[line_start..].chars().count() + 1;
    (line as u32, col as u32)
}

fn floor_char_boundary(s: &str, mut i: usize) -> usize {
    while !s.is_char_boundary(i) {
        i -= 1;
    }
    i
}

/// Lower-case hex of bytes.
pub fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tree(files: &[(&str, &str)]) -> ShaderTree {
        ShaderTree::from_files(
            "wgsl",
            files
                .iter()
                .map(|(a, b)| (a.to_string(), b.to_string()))
                .collect(),
        )
        .unwrap()
    }

    #[test]
    fn composed_offsets_map_back_to_each_file() {
        let t = tree(&[
            (
                MODULES_FILE,
                "[[module]]\nname = \"m\"\nfiles = [\"a.wgsl\", \"b.wgsl\"]\n[[module.variant]]\nname = \"v\"\ndescription = \"d\"\n",
            ),
            ("a.wgsl", "const A = 1;\nconst B = 2;"),
            ("b.wgsl", "// b\nconst C = 3;\n"),
        ]);
        let c = t.compose(&t.modules[0]);
        let at = c.text.find("C = 3").unwrap();
        let loc = c.locate(at);
        assert_eq!(
            (loc.file.as_str(), loc.line, loc.col),
            ("wgsl/b.wgsl", 2, 7)
        );
        assert_eq!(loc.line_text, "const C = 3;");
        let at = c.text.find("B = 2").unwrap();
        assert_eq!(c.locate(at).to_string(), "wgsl/a.wgsl:2:7");
    }

    #[test]
    fn modules_file_errors_name_the_problem() {
        let err = ShaderTree::from_files(
            "wgsl",
            [(
                MODULES_FILE.to_string(),
                "[[module]]\nname = \"m\"\nfiles = [\"nope.wgsl\"]\n".to_string(),
            )]
            .into_iter()
            .collect(),
        )
        .unwrap_err();
        assert_eq!(
            err.to_string(),
            "wgsl/modules.toml: module `m` lists `nope.wgsl`, which does not exist"
        );
    }
}
