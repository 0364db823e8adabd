//! Comparison metrics on synthetic images with known answers.

use stratus_compare::{CompareOptions, Encoding, Image, compare, flip_stats, heatmap_rgb8};

/// A smooth linear test image: horizontal and vertical ramps in r and g, a blob in b.
fn ramp(w: u32, h: u32) -> Image {
    let mut rgba = Vec::new();
    for y in 0..h {
        for x in 0..w {
            let (u, v) = (x as f32 / w as f32, y as f32 / h as f32);
            let d = (u - 0.5).powi(2) + (v - 0.5).powi(2);
            rgba.extend([u * 2.0, v, (-d * 20.0).exp(), 1.0]);
        }
    }
    Image::from_linear_rgba(w, h, rgba)
}

/// Deterministic uniform noise in [-1, 1] (xorshift).
fn noise(n: usize, seed: u64) -> Vec<f32> {
    let mut s = seed | 1;
    (0..n)
        .map(|_| {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0
        })
        .collect()
}

#[test]
fn identical_images_give_zero() {
    let a = ramp(64, 48);
    let c = compare(&a, &a.clone(), &CompareOptions::default()).unwrap();
    assert_eq!(c.rmse, 0.0);
    assert_eq!(c.max_abs, 0.0);
    assert_eq!(c.flip.mean, 0.0);
    assert_eq!(c.flip.max, 0.0);
    assert!(c.flip_map.iter().all(|&v| v == 0.0));
}

#[test]
fn known_perturbation_gives_expected_rmse_and_max() {
    let a = ramp(32, 16);
    let mut b = a.clone();
    // Add 0.1 to every red value, and 0.5 to the green of pixel (5, 3).
    for p in b.rgba.chunks_exact_mut(4) {
        p[0] += 0.1;
    }
    b.rgba[4 * (3 * 32 + 5) + 1] += 0.5;
    let c = compare(&a, &b, &CompareOptions::default()).unwrap();
    let n = (32 * 16 * 3) as f64;
    let expected = ((32.0 * 16.0 * 0.01 + 0.25) / n).sqrt();
    assert!((c.rmse - expected).abs() < 1e-6, "{} vs {expected}", c.rmse);
    assert!((c.max_abs - 0.5).abs() < 1e-6);
    assert_eq!((c.worst.x, c.worst.y, c.worst.channel), (5, 3, 1));
    assert!((c.worst.test[1] - c.worst.reference[1] - 0.5).abs() < 1e-6);

    // Alpha counts only when asked.
    let mut d = a.clone();
    d.rgba[3] = 0.0;
    assert_eq!(
        compare(&a, &d, &CompareOptions::default()).unwrap().max_abs,
        0.0
    );
    let with_alpha = CompareOptions {
        include_alpha: true,
        ..CompareOptions::default()
    };
    let c = compare(&a, &d, &with_alpha).unwrap();
    assert_eq!(c.max_abs, 1.0);
    assert_eq!((c.worst.x, c.worst.y, c.worst.channel), (0, 0, 3));
}

#[test]
fn flip_grows_with_noise() {
    let a = ramp(96, 64);
    let base = noise(a.rgba.len(), 42);
    let mut means = Vec::new();
    for level in [0.01f32, 0.05, 0.2] {
        let mut b = a.clone();
        for (i, v) in b.rgba.iter_mut().enumerate() {
            if i % 4 != 3 {
                *v = (*v + level * base[i]).max(0.0);
            }
        }
        let c = compare(&a, &b, &CompareOptions::default()).unwrap();
        assert!(c.flip.mean > 0.0);
        assert!(c.flip.p95 >= c.flip.p50 && c.flip.p99 >= c.flip.p95 && c.flip.max >= c.flip.p99);
        means.push((c.flip.mean, c.rmse));
    }
    assert!(
        means.windows(2).all(|w| w[1].0 > w[0].0 && w[1].1 > w[0].1),
        "FLIP means and RMSE must grow with the noise: {means:?}"
    );
}

#[test]
fn mismatches_are_errors() {
    let a = ramp(8, 8);
    let b = ramp(8, 4);
    assert!(compare(&a, &b, &CompareOptions::default()).is_err());
    let d = Image::from_display_rgba8(8, 8, &[128; 8 * 8 * 4]);
    let e = compare(&a, &d, &CompareOptions::default()).unwrap_err();
    assert!(e.to_string().contains("PNG with PNG"), "{e}");
}

#[test]
fn stats_and_heatmap() {
    let map: Vec<f32> = (0..100).map(|i| i as f32 / 100.0).collect();
    let s = flip_stats(&map);
    assert!((s.mean - 0.495).abs() < 1e-6);
    assert!((s.p50 - 0.49).abs() < 1e-6);
    assert!((s.p95 - 0.94).abs() < 1e-6);
    assert!((s.p99 - 0.98).abs() < 1e-6);
    assert!((s.max - 0.99).abs() < 1e-6);
    let heat = heatmap_rgb8(10, 10, &map);
    assert_eq!(heat.len(), 300);
    // Magma: dark at 0, bright at 1.
    let lum = |i: usize| {
        heat[3 * i..3 * i + 3]
            .iter()
            .map(|&v| u32::from(v))
            .sum::<u32>()
    };
    assert!(lum(99) > lum(0) + 300);
}

#[test]
fn png_and_exr_round_trip() {
    let dir = std::env::temp_dir().join(format!("stratus-compare-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let a = ramp(16, 8);

    let exr = dir.join("a.exr");
    a.save(&exr).unwrap();
    let back = Image::load(&exr).unwrap();
    assert_eq!(back.encoding, Encoding::Linear);
    assert_eq!((back.width, back.height), (16, 8));
    assert_eq!(back.rgba, a.rgba);

    let d = Image::from_display_rgba8(
        16,
        8,
        &a.to_rgb8(1.0)
            .chunks(3)
            .flat_map(|p| [p[0], p[1], p[2], 255])
            .collect::<Vec<_>>(),
    );
    let png = dir.join("a.png");
    d.save(&png).unwrap();
    let back = Image::load(&png).unwrap();
    assert_eq!(back.encoding, Encoding::Display);
    let c = compare(&d, &back, &CompareOptions::default()).unwrap();
    assert_eq!(c.max_abs, 0.0);
    assert!(Image::load(&dir.join("a.bmp")).is_err());
    std::fs::remove_dir_all(&dir).ok();
}

/// An EXR whose header declares far more pixels than it holds (686 GB of them: the input the
/// fuzzer found, `fuzz/regressions/image_exr/`) is refused by name instead of aborting the
/// process on the allocation.
#[test]
fn an_exr_declaring_a_huge_image_is_refused_before_allocating() {
    let bytes = include_bytes!("../../../fuzz/regressions/image_exr/huge-declared-size.exr");
    let err = stratus_compare::Image::decode(bytes, stratus_compare::FileKind::Exr, "huge.exr")
        .expect_err("a huge declared image is refused");
    let text = err.to_string();
    assert!(
        text.contains("huge.exr") && text.contains("more than the"),
        "{text}"
    );
}
