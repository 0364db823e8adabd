//! `weather_from_png`: round trips and error reporting.

use std::path::PathBuf;
use std::sync::atomic::{AtomicU32, Ordering};

use stratus_noise::{NoiseError, weather_from_png};

/// A fresh path under the system temp dir, unique per process, call and time.
fn temp_path(name: &str) -> PathBuf {
    static COUNTER: AtomicU32 = AtomicU32::new(0);
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_nanos())
        .unwrap_or(0);
    std::env::temp_dir().join(format!(
        "stratus-noise-{}-{}-{nanos}-{name}",
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::Relaxed)
    ))
}

/// Removes the file when dropped, so failing assertions do not leave files behind.
struct TempFile(PathBuf);

impl Drop for TempFile {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
    }
}

fn pattern(w: u32, h: u32, channels: u32) -> Vec<u8> {
    (0..w * h * channels)
        .map(|i| (i.wrapping_mul(37) ^ (i >> 3)) as u8)
        .collect()
}

#[test]
fn rgba_png_round_trips() {
    let (w, h) = (5, 3); // not square, not a power of two: allowed
    let data = pattern(w, h, 4);
    let file = TempFile(temp_path("rgba.png"));
    image::RgbaImage::from_raw(w, h, data.clone())
        .unwrap()
        .save(&file.0)
        .unwrap();
    let tex = weather_from_png(&file.0).unwrap();
    assert_eq!(tex.size, [w, h]);
    assert_eq!(tex.data, data);
    assert_eq!(tex.texel(4, 2), [data[56], data[57], data[58], data[59]]);
}

#[test]
fn rgb_png_gets_opaque_alpha() {
    let (w, h) = (4, 4);
    let data = pattern(w, h, 3);
    let file = TempFile(temp_path("rgb.png"));
    image::RgbImage::from_raw(w, h, data.clone())
        .unwrap()
        .save(&file.0)
        .unwrap();
    let tex = weather_from_png(&file.0).unwrap();
    assert_eq!(tex.size, [w, h]);
    let expected: Vec<u8> = data
        .chunks_exact(3)
        .flat_map(|p| [p[0], p[1], p[2], 255])
        .collect();
    assert_eq!(tex.data, expected);
}

#[test]
fn missing_file_is_an_io_error_naming_the_path() {
    let path = temp_path("does-not-exist.png");
    let err = weather_from_png(&path).unwrap_err();
    assert!(matches!(err, NoiseError::Io { .. }), "{err:?}");
    let msg = err.to_string();
    assert!(msg.contains(&path.display().to_string()), "{msg}");
    assert!(std::error::Error::source(&err).is_some());
}

#[test]
fn non_png_is_a_decode_error_naming_the_path() {
    let file = TempFile(temp_path("not-a.png"));
    std::fs::write(&file.0, b"this is not a PNG file\n").unwrap();
    let err = weather_from_png(&file.0).unwrap_err();
    assert!(matches!(err, NoiseError::Decode { .. }), "{err:?}");
    let msg = err.to_string();
    assert!(msg.contains(&file.0.display().to_string()), "{msg}");
    assert!(msg.contains("not a valid PNG"), "{msg}");
}

#[test]
fn grey_png_is_rejected_with_its_format() {
    let file = TempFile(temp_path("grey.png"));
    image::GrayImage::from_raw(2, 2, vec![0, 64, 128, 255])
        .unwrap()
        .save(&file.0)
        .unwrap();
    let err = weather_from_png(&file.0).unwrap_err();
    assert!(
        matches!(err, NoiseError::UnsupportedFormat { .. }),
        "{err:?}"
    );
    let msg = err.to_string();
    assert!(msg.contains(&file.0.display().to_string()), "{msg}");
    assert!(msg.contains("L8") && msg.contains("RGB"), "{msg}");
}
