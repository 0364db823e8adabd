//! Times the default noise set: `cargo run -p stratus-noise --release --example noise_bench`.
//!
//! After one untimed warm-up run, generates each texture of `NoiseConfig::default()` 5 times, then
//! the whole set 5 times, and prints the median wall time of each.

use std::time::{Duration, Instant};

use stratus_noise::{
    NoiseConfig, NoiseSet, curl_texture, detail_texture, shape_texture, weather_texture,
};

const RUNS: usize = 5;

fn median(mut f: impl FnMut()) -> Duration {
    let mut times: Vec<Duration> = (0..RUNS)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed()
        })
        .collect();
    times.sort();
    times[RUNS / 2]
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

fn main() {
    let cfg = NoiseConfig::default();
    println!(
        "stratus-noise: default set (seed {}, shape {}, detail {}^3, curl {}^2, weather {}^2), \
         median of {RUNS} runs, {} rayon threads",
        cfg.seed,
        cfg.shape,
        cfg.detail_size,
        cfg.curl_size,
        cfg.weather_size,
        rayon::current_num_threads()
    );
    // Warm-up: starts rayon's thread pool and faults in the allocator's pages.
    drop(NoiseSet::generate(&cfg));
    let shape = median(|| drop(shape_texture(cfg.seed, cfg.shape.dims())));
    let detail = median(|| drop(detail_texture(cfg.seed, cfg.detail_size)));
    let curl = median(|| drop(curl_texture(cfg.seed, cfg.curl_size)));
    let weather = median(|| drop(weather_texture(cfg.seed, cfg.weather_size)));
    let total = median(|| drop(NoiseSet::generate(&cfg)));
    println!("shape    {:8.1} ms", ms(shape));
    println!("detail   {:8.1} ms", ms(detail));
    println!("curl     {:8.1} ms", ms(curl));
    println!("weather  {:8.1} ms", ms(weather));
    println!("total    {:8.1} ms  (NoiseSet::generate)", ms(total));
}
