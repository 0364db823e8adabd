//! `cargo xtask build-shaders` and `cargo xtask validate`: the WGSL into `spirv-out/` (what
//! runs) and `tests/out/` (the pinned translations), every variant's GLSL, HLSL and MSL on
//! demand, and the external validators over them.

use std::{collections::BTreeMap, path::Path, process::Command};

use anyhow::{Context, Result, bail};

use stratus_shaders::{Languages, ShaderTree, build_outputs, is_committed};

use crate::{label, target_dir};

/// What `cargo xtask build-shaders` writes besides `spirv-out/`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub(crate) enum LanguageChoice {
    /// spirv-out/ (SPIR-V, composed WGSL, manifest) and the pinned translations in tests/out/.
    Spirv,
    /// As `spirv`, and GLSL, HLSL and MSL of every variant in the translations folder.
    All,
}

/// The files `cargo xtask build-shaders` owns in a folder: a file name (or a path below the
/// folder, `/`-separated) -> bytes.
pub(crate) type Files = BTreeMap<String, Vec<u8>>;

/// Builds the shaders from `wgsl`: writes `spirv-out` and the pinned translations
/// (`tests/out/`), or with `check` fails naming every stale, missing or extra file there. With
/// `translations`, also writes every variant's GLSL, HLSL and MSL into that folder.
pub(crate) fn build_shaders(
    root: &Path,
    wgsl: &Path,
    out: &Path,
    check: bool,
    translations: Option<&Path>,
) -> Result<()> {
    // The generated WGSL (the uniform block's struct) first: the tree is read from the folder.
    let mut problems = Vec::new();
    for (name, text) in stratus_shaders::generated_sources() {
        let path = wgsl.join(name);
        if std::fs::read_to_string(&path).ok().as_deref() == Some(text.as_str()) {
            continue;
        }
        if check {
            problems.push(format!(
                "stale (generated from crates/scene/src/uniforms.rs): {}",
                path.display()
            ));
        } else {
            std::fs::write(&path, text).with_context(|| format!("writing {}", path.display()))?;
            println!("wrote {} (generated)", path.display());
        }
    }
    let tree = ShaderTree::from_dir(wgsl, &label(root, wgsl))?;
    // One build of every language: the pinned set needs GLSL, HLSL and MSL, and compiling the
    // tree (not translating it) is most of the time.
    let all = match build_outputs(&tree, Languages::All) {
        Ok(o) => o,
        Err(diags) => {
            eprintln!("{diags}");
            bail!("{} WGSL error(s) in {}", diags.0.len(), wgsl.display());
        }
    };
    let committed: Files = all
        .iter()
        .filter(|(name, _)| is_committed(name))
        .map(|(n, b)| (n.clone(), b.clone()))
        .collect();
    let pinned_dir = root.join("tests/out");
    let targets = [
        (out.to_path_buf(), committed),
        (pinned_dir, stratus_shaders::pinned(&all)),
    ];
    for (dir, files) in &targets {
        problems.extend(differences(dir, files)?);
    }
    if check {
        if problems.is_empty() {
            for (dir, files) in &targets {
                println!("{} is fresh ({} files)", label(root, dir), files.len());
            }
        } else {
            for p in &problems {
                eprintln!("{p}");
            }
            bail!(
                "generated shaders are out of date with {} ({} file(s)); run `cargo xtask build-shaders`",
                wgsl.display(),
                problems.len()
            );
        }
    } else {
        for (dir, files) in &targets {
            let changed = sync(dir, files)?;
            println!(
                "wrote {} files to {} ({changed} changed)",
                files.len(),
                label(root, dir)
            );
        }
    }
    if let Some(dir) = translations {
        let files: Files = all.into_iter().filter(|(n, _)| !is_committed(n)).collect();
        let changed = sync(dir, &files)?;
        println!(
            "wrote {} GLSL, HLSL and MSL files to {} ({changed} changed)",
            files.len(),
            dir.display()
        );
    }
    Ok(())
}

/// Every file of `dir` that `files` would add, change or remove, as a line naming it.
pub(crate) fn differences(dir: &Path, files: &Files) -> Result<Vec<String>> {
    let existing = list_generated(dir)?;
    let mut problems = Vec::new();
    for (name, bytes) in files {
        match existing.get(name) {
            None => problems.push(format!("missing: {}", dir.join(name).display())),
            Some(old) if old != bytes => {
                problems.push(format!("stale: {}", dir.join(name).display()))
            }
            _ => {}
        }
    }
    for name in existing.keys().filter(|n| !files.contains_key(*n)) {
        problems.push(format!(
            "extra (no longer generated): {}",
            dir.join(name).display()
        ));
    }
    Ok(problems)
}

/// Makes the generated files of `dir` exactly `files` (writing only what changed); returns how
/// many files it wrote or removed.
pub(crate) fn sync(dir: &Path, files: &Files) -> Result<usize> {
    let existing = list_generated(dir)?;
    let mut changed = 0;
    for name in existing.keys().filter(|n| !files.contains_key(*n)) {
        std::fs::remove_file(dir.join(name))
            .with_context(|| format!("removing {}", dir.join(name).display()))?;
        changed += 1;
    }
    for (name, bytes) in files {
        if existing.get(name) != Some(bytes) {
            let path = dir.join(name);
            if let Some(parent) = path.parent() {
                std::fs::create_dir_all(parent)
                    .with_context(|| format!("creating {}", parent.display()))?;
            }
            std::fs::write(&path, bytes).with_context(|| format!("writing {}", path.display()))?;
            changed += 1;
        }
    }
    Ok(changed)
}

/// The files below `dir` that build-shaders owns, by ending (so stray README files are left
/// alone), as `/`-separated paths relative to `dir`.
pub(crate) fn list_generated(dir: &Path) -> Result<Files> {
    let mut files = Files::new();
    let mut pending = vec![dir.to_path_buf()];
    while let Some(folder) = pending.pop() {
        let Ok(entries) = std::fs::read_dir(&folder) else {
            continue;
        };
        for e in entries {
            let path = e?.path();
            if path.is_dir() {
                pending.push(path);
                continue;
            }
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            let owned = [".spv", ".glsl", ".hlsl", ".metal", ".wgsl", "manifest.json"]
                .iter()
                .any(|ext| name.ends_with(ext));
            if owned && path.is_file() {
                let rel = path.strip_prefix(dir).expect("below dir");
                let rel = rel
                    .components()
                    .map(|c| c.as_os_str().to_string_lossy())
                    .collect::<Vec<_>>()
                    .join("/");
                files.insert(rel, std::fs::read(&path)?);
            }
        }
    }
    Ok(files)
}

#[derive(Clone, Copy, PartialEq)]
pub(crate) enum Verdict {
    Pass,
    Fail,
    Skipped,
}

pub(crate) struct Row {
    file: String,
    tool: String,
    verdict: Verdict,
    detail: String,
}

pub(crate) fn run_tool(cmd: &mut Command) -> (Verdict, String) {
    match cmd.output() {
        Ok(o) if o.status.success() => (Verdict::Pass, String::new()),
        Ok(o) => (
            Verdict::Fail,
            format!(
                "{}{}",
                String::from_utf8_lossy(&o.stdout),
                String::from_utf8_lossy(&o.stderr)
            ),
        ),
        Err(e) => (
            Verdict::Fail,
            format!("could not run {:?}: {e}", cmd.get_program()),
        ),
    }
}

pub(crate) fn validate(root: &Path, out: &Path) -> Result<()> {
    // The translations are not committed: make them afresh from the WGSL (spirv-out/ is held
    // to the same WGSL by `build-shaders --check`).
    let translations = target_dir(root).join("shaders");
    build_shaders(root, &root.join("wgsl"), out, true, Some(&translations))?;
    let manifest_path = out.join("manifest.json");
    let manifest = stratus_shaders::Manifest::from_json(
        &std::fs::read_to_string(&manifest_path)
            .with_context(|| format!("reading {}", manifest_path.display()))?,
    )
    .with_context(|| format!("parsing {}", manifest_path.display()))?;
    let tmp = std::env::temp_dir().join(format!("stratus-validate-{}", std::process::id()));
    std::fs::create_dir_all(&tmp)?;
    let has_metal = Command::new("xcrun")
        .arg("--find")
        .arg("metal")
        .output()
        .is_ok_and(|o| o.status.success());
    let mut rows = Vec::new();
    for m in &manifest.modules {
        for v in &m.variants {
            let f = &v.files;
            let (verdict, detail) = run_tool(Command::new("spirv-val").arg(out.join(&f.spv)));
            rows.push(Row {
                file: f.spv.clone(),
                tool: "spirv-val".into(),
                verdict,
                detail,
            });
            for (entry, file) in &f.glsl {
                let stage = m
                    .entry_point(entry)
                    .map_or("comp", |e| e.stage.glsl_suffix());
                let (verdict, detail) = run_tool(
                    Command::new("glslangValidator")
                        .args(["-S", stage])
                        .arg(translations.join(file)),
                );
                rows.push(Row {
                    file: file.clone(),
                    tool: "glslangValidator".into(),
                    verdict,
                    detail,
                });
            }
            for ep in &m.entry_points {
                let spv = tmp.join(format!("{}.{}.{}.spv", m.name, v.name, ep.name));
                let stage = ep.stage.glsl_suffix();
                let (mut verdict, mut detail) = run_tool(
                    Command::new("glslangValidator")
                        .args(["-D", "-V", "-e", &ep.name, "-S", stage, "-o"])
                        .arg(&spv)
                        .arg(translations.join(&f.hlsl)),
                );
                if verdict == Verdict::Pass {
                    (verdict, detail) = run_tool(Command::new("spirv-val").arg(&spv));
                }
                rows.push(Row {
                    file: format!("{} ({})", f.hlsl, ep.name),
                    tool: "glslangValidator -D -V + spirv-val".into(),
                    verdict,
                    detail,
                });
            }
            if has_metal {
                let (verdict, detail) = run_tool(
                    Command::new("xcrun")
                        .args(["-sdk", "macosx", "metal", "-c", "-o"])
                        .arg(tmp.join("out.air"))
                        .arg(translations.join(&f.metal)),
                );
                rows.push(Row {
                    file: f.metal.clone(),
                    tool: "xcrun metal".into(),
                    verdict,
                    detail,
                });
            } else {
                rows.push(Row {
                    file: f.metal.clone(),
                    tool: "xcrun metal".into(),
                    verdict: Verdict::Skipped,
                    detail: "not compiled: no Metal toolchain here".into(),
                });
            }
        }
    }
    let _ = std::fs::remove_dir_all(&tmp);

    let wf = rows.iter().map(|r| r.file.len()).max().unwrap_or(4).max(4);
    let wt = rows.iter().map(|r| r.tool.len()).max().unwrap_or(4).max(4);
    println!("{:wf$}  {:wt$}  result", "file", "tool");
    println!("{}  {}  {}", "-".repeat(wf), "-".repeat(wt), "-".repeat(7));
    for r in &rows {
        let v = match r.verdict {
            Verdict::Pass => "PASS".to_string(),
            Verdict::Fail => "FAIL".to_string(),
            Verdict::Skipped => format!("SKIPPED ({})", r.detail),
        };
        println!("{:wf$}  {:wt$}  {v}", r.file, r.tool);
    }
    let failed: Vec<_> = rows.iter().filter(|r| r.verdict == Verdict::Fail).collect();
    for r in &failed {
        eprintln!("\n--- {} ({}) ---\n{}", r.file, r.tool, r.detail.trim_end());
    }
    let pass = rows.iter().filter(|r| r.verdict == Verdict::Pass).count();
    let skipped = rows
        .iter()
        .filter(|r| r.verdict == Verdict::Skipped)
        .count();
    println!(
        "validate: {pass} passed, {} failed, {skipped} skipped",
        failed.len()
    );
    if !failed.is_empty() {
        bail!("{} validation(s) failed", failed.len());
    }
    Ok(())
}
