//! `stratus compare A B`: how far apart two renders are.

use std::path::PathBuf;

use anyhow::{Result, bail};
use clap::Args;
use stratus_compare::{CompareOptions, Encoding, Image, compare, write_heatmap};

/// Options of `stratus compare`.
#[derive(Args, Debug)]
pub struct CompareArgs {
    /// The reference image (PNG or EXR).
    reference: PathBuf,
    /// The image to test against it (same size, same type).
    test: PathBuf,
    /// Write the FLIP error map as a heat map PNG (black: no difference, yellow: 1).
    #[arg(long)]
    diff: Option<PathBuf>,
    /// Exposure applied to linear (EXR) images before tone mapping them for FLIP.
    #[arg(long, default_value_t = 1.0)]
    exposure: f32,
}

/// Runs `stratus compare`.
pub fn run(args: CompareArgs) -> Result<()> {
    let a = Image::load(&args.reference)?;
    let b = Image::load(&args.test)?;
    if a.encoding != b.encoding {
        bail!(
            "{} is {:?} and {} is {:?}: compare two PNGs or two EXRs",
            args.reference.display(),
            a.encoding,
            args.test.display(),
            b.encoding
        );
    }
    let c = compare(
        &a,
        &b,
        &CompareOptions {
            exposure: args.exposure,
            ..CompareOptions::default()
        },
    )?;
    println!("{}x{} ({:?})", c.width, c.height, c.encoding);
    println!(
        "FLIP: mean {:.5}  p50 {:.5}  p95 {:.5}  p99 {:.5}  max {:.5}",
        c.flip.mean, c.flip.p50, c.flip.p95, c.flip.p99, c.flip.max
    );
    let what = if c.encoding == Encoding::Linear {
        "linear radiance"
    } else {
        "8-bit display values"
    };
    println!("{what}: RMSE {:.6}  max abs {:.6}", c.rmse, c.max_abs);
    let w = &c.worst;
    println!(
        "worst pixel ({}, {}) channel {}: {:?} vs {:?}",
        w.x, w.y, w.channel, w.reference, w.test
    );
    if let Some(path) = &args.diff {
        write_heatmap(path, c.width, c.height, &c.flip_map)?;
        println!("wrote {}", path.display());
    }
    Ok(())
}
