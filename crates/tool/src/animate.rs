//! `stratus animate`: render a scene's animation with one persistent renderer and encode the
//! frames as a video (MP4 through ffmpeg) or an animated GIF.

use std::{
    io::Write as _,
    path::PathBuf,
    process::{Command, Stdio},
};

use anyhow::{Context, Result, bail};
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use stratus_graph::Readback;
use stratus_scene::{Scene, Temporal};
use stratus_weather::states::{self, WeatherParams};

use crate::{
    backends::{Backend, open_realtime},
    render::{frame_scene, parse_temporal},
    scene_io::{check_finite, load_scene, parse_size},
};

/// Options of `stratus animate`.
#[derive(Args, Debug)]
pub struct AnimateArgs {
    /// A built-in preset (see `stratus presets`).
    #[arg(long, conflicts_with = "scene")]
    preset: Option<String>,
    /// A scene file (TOML); its [animation] moves the camera, and the wind moves with time.
    #[arg(long)]
    scene: Option<PathBuf>,
    /// Seconds of animation to render (default: the scene's animation.duration_s, else 4).
    #[arg(long)]
    seconds: Option<f64>,
    /// Frames per second of the video; scene time advances 1/fps per frame.
    #[arg(long, default_value_t = 30, value_parser = clap::value_parser!(u32).range(1..=240))]
    fps: u32,
    /// Output: .mp4 (H.264, through ffmpeg) or .gif.
    #[arg(long, default_value = "clouds.mp4")]
    out: PathBuf,
    /// Image size as WIDTHxHEIGHT (overrides the scene's camera.resolution).
    #[arg(long, value_parser = parse_size)]
    size: Option<(u32, u32)>,
    /// The renderer (a real-time one).
    #[arg(long, value_enum, default_value_t = Backend::Auto)]
    backend: Backend,
    /// Temporal upsampling (overrides the scene's quality.temporal).
    #[arg(long, value_name = "MODE", value_parser = parse_temporal)]
    temporal: Option<Temporal>,
    /// A weather transition: from this weather state (`stratus weather --list`) ...
    #[arg(long, value_name = "STATE", requires = "to")]
    from: Option<String>,
    /// ... to this one, smoothstep-eased over --seconds (seed 001's transitions). The wind
    /// carries the clouds by the integral of its changing speed, so they never jump.
    #[arg(long, value_name = "STATE", requires = "from")]
    to: Option<String>,
    /// Measure temporal smoothness: the FLIP between each frame and the one before, and print
    /// the largest and the mean (and the frame of the largest).
    #[arg(long)]
    flip: bool,
}

/// Runs `stratus animate`.
pub fn run(args: AnimateArgs) -> Result<()> {
    let ext = args
        .out
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let codec: &[&str] = match ext.as_deref() {
        // yuv420p needs even sizes: pad by one pixel where the image is odd.
        Some("mp4") => &[
            "-vf",
            "pad=ceil(iw/2)*2:ceil(ih/2)*2",
            "-c:v",
            "libx264",
            "-pix_fmt",
            "yuv420p",
            "-crf",
            "20",
            "-movflags",
            "+faststart",
        ],
        Some("gif") => &[
            "-vf",
            "split[a][b];[a]palettegen=stats_mode=diff[p];[b][p]paletteuse=dither=bayer",
            "-loop",
            "0",
        ],
        _ => bail!(
            "--out {}: unknown video type; use a .mp4 or .gif file name",
            args.out.display()
        ),
    };
    let (mut scene, name) = load_scene(args.preset.as_deref(), args.scene.as_ref(), args.size)?;
    if let Some(t) = args.temporal {
        scene.quality.temporal = t;
    }
    let seconds = args
        .seconds
        .or(scene.animation.as_ref().map(|a| a.duration_s))
        .unwrap_or(4.0);
    if !(seconds.is_finite() && seconds > 0.0) {
        bail!("--seconds {seconds}: must be a positive number");
    }
    let frames = ((seconds * f64::from(args.fps)).round() as u32).max(1);
    let transition = match (&args.from, &args.to) {
        (Some(a), Some(b)) => {
            let from = states::find(a).map_err(|e| anyhow::anyhow!("--from: {e}"))?;
            let to = states::find(b).map_err(|e| anyhow::anyhow!("--to: {e}"))?;
            Some((from.params, to.params))
        }
        _ => None,
    };
    let [w, h] = scene.camera.resolution;

    // The video is complete or absent: ffmpeg writes a temporary file that is renamed into
    // place once it has finished.
    let (flips, backend) = stratus_compare::write_atomically(&args.out, |tmp| {
        // ffmpeg first: a missing encoder fails before any rendering.
        let mut ffmpeg = Command::new("ffmpeg")
            .args(["-hide_banner", "-loglevel", "error", "-y"])
            .args([
                "-f",
                "rawvideo",
                "-pix_fmt",
                "rgba",
                "-s",
                &format!("{w}x{h}"),
            ])
            .args(["-r", &args.fps.to_string(), "-i", "-"])
            .args(codec)
            .arg(tmp)
            .stdin(Stdio::piped())
            .spawn()
            .context("starting ffmpeg (install it: apt-get install ffmpeg)")?;
        let mut stdin = ffmpeg.stdin.take().context("ffmpeg's stdin")?;

        let mut renderer = open_realtime(args.backend, false)?;
        // A weather transition can change the plan's key (a layer's detail, the sky) mid-animation:
        // the plan is checked against every frame's scene.
        let mut prepared = stratus::Prepared::new(&scene)?;
        let bar = ProgressBar::new(u64::from(frames));
        if let Ok(style) =
            ProgressStyle::with_template("{msg} [{elapsed_precise}] {wide_bar} {pos}/{len} frames")
        {
            bar.set_style(style);
        }
        bar.set_message("rendering");
        let mut previous: Option<stratus_compare::Image> = None;
        let mut flips: Vec<(f64, u32)> = Vec::new();
        for i in 0..frames {
            let mut s = frame_scene(&scene, i, f64::from(args.fps));
            if let Some((from, to)) = &transition {
                apply_transition(
                    &mut s,
                    &scene,
                    from,
                    to,
                    f64::from(i) / f64::from(args.fps),
                    seconds,
                );
            }
            prepared.update(&s).with_context(|| format!("frame {i}"))?;
            let out = renderer
                .render(&prepared.frame(&s).with_readback(Readback::output()))
                .map_err(|e| anyhow::anyhow!("frame {i}: {e}"))?;
            check_finite(&out).with_context(|| format!("frame {i}"))?;
            if args.flip {
                let image = stratus_compare::Image::from_frame_display(&out);
                if let Some(p) = &previous {
                    let c = stratus_compare::compare(
                        &image,
                        p,
                        &stratus_compare::CompareOptions::default(),
                    )
                    .map_err(|e| anyhow::anyhow!("frame {i}: {e}"))?;
                    flips.push((c.flip.mean, i));
                }
                previous = Some(image);
            }
            stdin
                .write_all(&out.image)
                .context("writing a frame to ffmpeg")?;
            bar.inc(1);
        }
        bar.finish_and_clear();
        drop(stdin);
        let status = ffmpeg.wait().context("waiting for ffmpeg")?;
        if !status.success() {
            bail!("ffmpeg failed ({status}) writing {}", args.out.display());
        }
        Ok((flips, renderer.describe()))
    })
    .map_err(|e| match e {
        stratus_compare::AtomicError::Write(e) => e,
        stratus_compare::AtomicError::Io(e) => {
            anyhow::anyhow!("moving the video into place at {}: {e}", args.out.display())
        }
    })?;
    if let Some(&(worst, at)) = flips.iter().max_by(|a, b| a.0.total_cmp(&b.0)) {
        let mean = flips.iter().map(|f| f.0).sum::<f64>() / flips.len() as f64;
        println!(
            "consecutive-frame FLIP (mean over each image): largest {worst:.5} (frames {} -> {at}), mean {mean:.5} over {} pairs",
            at - 1,
            flips.len()
        );
    }
    println!(
        "wrote {} ({frames} frames, {w}x{h}, {} fps, {seconds} s of scene {name}; backend {}, temporal {})",
        args.out.display(),
        args.fps,
        backend,
        scene.quality.temporal.name()
    );
    Ok(())
}

/// Writes the weather `t` seconds into a transition of `duration` seconds from `from` to `to`
/// into the frame's scene `s` (the base scene `base` at that time). The wind's time is set so
/// that speed * time is the distance the eased wind has carried the clouds.
pub fn apply_transition(
    s: &mut Scene,
    base: &Scene,
    from: &WeatherParams,
    to: &WeatherParams,
    t: f64,
    duration: f64,
) {
    let params = WeatherParams::transition(from, to, t, duration);
    params.apply(s);
    let distance = WeatherParams::wind_distance(from, to, t, duration);
    s.clouds.time_s = if params.wind_speed_m_s > 0.0 {
        base.clouds.time_s + distance / params.wind_speed_m_s
    } else {
        base.clouds.time_s
    };
}
