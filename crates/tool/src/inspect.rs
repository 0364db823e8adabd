//! The small commands that inspect what Stratus carries: `presets`, `scene check` and
//! `shaders`.

/// `stratus presets`: every built-in preset, one a line.
pub fn presets() -> anyhow::Result<()> {
    let list = stratus_scene::presets();
    let width = list.iter().map(|p| p.name.len()).max().unwrap_or(0);
    for p in list {
        let default = if p.name == stratus_scene::DEFAULT_PRESET {
            " (default)"
        } else {
            ""
        };
        println!("{:width$}  {}{default}", p.name, p.description);
    }
    Ok(())
}

/// `stratus scene check FILE`: the scene in full (defaults filled in), or every problem.
pub fn scene_check(file: &std::path::Path) -> anyhow::Result<()> {
    match stratus_scene::Scene::from_file(file) {
        Ok(scene) => {
            print!("{}", scene.to_toml());
            eprintln!("{}: ok", file.display());
            Ok(())
        }
        Err(e) => {
            eprintln!("{e}");
            anyhow::bail!("{}: {} problem(s)", file.display(), e.problems().len())
        }
    }
}

/// `stratus shaders`: the embedded WGSL's modules, variants and entry points, validated.
pub fn shaders() -> anyhow::Result<()> {
    let tree = stratus_shaders::ShaderTree::embedded()?;
    let compiled = stratus_shaders::compile_all(&tree)?;
    for m in &compiled {
        let entries: Vec<_> = m
            .module
            .entry_points
            .iter()
            .map(|e| e.name.as_str())
            .collect();
        println!(
            "module {} ({} files): entry points {}",
            m.spec.name,
            m.spec.files.len(),
            entries.join(", ")
        );
        for v in &m.spec.variants {
            println!("  variant {:<18} {}", v.name, v.description);
        }
    }
    Ok(())
}
