//! The configurations a scene is measured with: one axis at a time around its own settings,
//! plus cheap combinations.

use stratus::quality::Config;
use stratus_scene::{Integration, PhaseModel, ShapeTexture};

/// The sweep for a scene whose own settings are `base`: one axis at a time around `base`,
/// plus cheap combinations.
pub(super) fn sweep(base: &Config, quick: bool) -> Vec<Config> {
    let mut out = vec![base.clone()];
    let mut push = |c: Config| {
        if !out.contains(&c) {
            out.push(c);
        }
    };
    let views: &[u32] = if quick {
        &[8, 16, 32, 128]
    } else {
        &[4, 8, 16, 24, 32, 48, 96, 128, 256]
    };
    for &v in views {
        push(Config {
            view_steps: v,
            ..base.clone()
        });
    }
    let lights: &[u32] = if quick {
        &[0, 1, 2, 4]
    } else {
        &[0, 1, 2, 3, 4, 8, 12, 16]
    };
    for &l in lights {
        push(Config {
            light_steps: l,
            ..base.clone()
        });
    }
    for v in [16, base.view_steps] {
        push(Config {
            view_steps: v,
            integration: Integration::Riemann,
            ..base.clone()
        });
    }
    for p in [
        PhaseModel::Hg,
        PhaseModel::TwoLobeHg,
        PhaseModel::CornetteShanks,
    ] {
        push(Config {
            phase: p,
            ..base.clone()
        });
    }
    push(Config {
        beer_powder: !base.beer_powder,
        ..base.clone()
    });
    let octaves: &[u32] = if quick {
        &[0, 1, 4]
    } else {
        &[0, 1, 2, 3, 4, 6, 8]
    };
    for &o in octaves {
        push(Config {
            octaves: o,
            ..base.clone()
        });
    }
    push(Config {
        jitter: !base.jitter,
        ..base.clone()
    });
    push(Config {
        shape_texture: match base.shape_texture {
            ShapeTexture::Thesis => ShapeTexture::Hzd,
            ShapeTexture::Hzd => ShapeTexture::Thesis,
        },
        ..base.clone()
    });
    let combos: &[(u32, u32, Option<u32>)] = if quick {
        &[
            (16, 2, None),
            (32, 4, None),
            (16, 2, Some(0)),
            (32, 2, Some(1)),
        ]
    } else {
        &[
            (16, 2, None),
            (32, 4, None),
            (16, 2, Some(0)),
            (32, 2, Some(1)),
            (24, 3, Some(1)),
            (48, 4, Some(1)),
            (8, 1, Some(0)),
            (128, 8, None),
        ]
    };
    for &(v, l, o) in combos {
        push(Config {
            view_steps: v,
            light_steps: l,
            octaves: o.unwrap_or(base.octaves),
            ..base.clone()
        });
    }
    out
}
