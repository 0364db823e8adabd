//! `stratus`: render, inspect and compare volumetric clouds.

use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// Stratus renders physically grounded volumetric clouds from one WGSL source on wgpu, raw
/// Vulkan and the CPU.
#[derive(Parser)]
#[command(name = "stratus", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Validate the embedded WGSL with naga and list its modules, variants and entry points.
    Shaders,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Shaders => shaders(),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}

fn shaders() -> anyhow::Result<()> {
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
            println!("  variant {:<12} {}", v.name, v.description);
        }
    }
    Ok(())
}
