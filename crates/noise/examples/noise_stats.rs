//! Prints per-channel statistics of the default noise set:
//! `cargo run -p stratus-noise --release --example noise_stats [seed]`.
//!
//! Used to choose the bands asserted in `tests/textures.rs`.

use stratus_noise::{NoiseConfig, NoiseSet};

fn report(name: &str, data: &[u8]) {
    for (c, label) in ["R", "G", "B", "A"].iter().enumerate() {
        let mut v: Vec<u8> = data.iter().skip(c).step_by(4).copied().collect();
        let n = v.len() as f64;
        let mean = v.iter().map(|&x| f64::from(x)).sum::<f64>() / n;
        let var = v
            .iter()
            .map(|&x| (f64::from(x) - mean).powi(2))
            .sum::<f64>()
            / n;
        v.sort_unstable();
        let pct = |p: f64| v[((v.len() - 1) as f64 * p) as usize];
        let frac = |pred: &dyn Fn(u8) -> bool| v.iter().filter(|&&x| pred(x)).count() as f64 / n;
        println!(
            "{name:8} {label}: mean {mean:6.1} ({:.3}) var {var:7.1} (sd {:.3}) min {:3} p1 {:3} p10 {:3} p50 {:3} p90 {:3} p99 {:3} max {:3}  <26: {:.3} >229: {:.3}",
            mean / 255.0,
            var.sqrt() / 255.0,
            v[0],
            pct(0.01),
            pct(0.1),
            pct(0.5),
            pct(0.9),
            pct(0.99),
            v[v.len() - 1],
            frac(&|x| x < 26),
            frac(&|x| x > 229),
        );
    }
}

fn main() {
    let seed = std::env::args()
        .nth(1)
        .map(|s| s.parse().expect("seed must be a u64"))
        .unwrap_or(0);
    let set = NoiseSet::generate(&NoiseConfig {
        seed,
        ..NoiseConfig::default()
    });
    report("shape", &set.shape.data);
    report("detail", &set.detail.data);
    report("curl", &set.curl.data);
    report("weather", &set.weather.data);
}
