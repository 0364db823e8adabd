//! The GPU uniform block and the geometry helpers behind it.

use std::mem::{offset_of, size_of};

use stratus_scene::{FrameUniforms, HeightModel, Integration, PhaseModel, Scene};

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn assert_close(a: [f64; 3], b: [f64; 3]) {
    for i in 0..3 {
        assert!((a[i] - b[i]).abs() < 1e-12, "{a:?} != {b:?}");
    }
}

/// The members tile the block with no implicit padding (every gap is a named padding member,
/// so a C or HLSL mirror built from the list has the same layout) and none crosses a 16-byte
/// row (where std140 and HLSL cbuffer packing would move it).
#[test]
fn members_tile_the_block_row_by_row() {
    assert_eq!(size_of::<FrameUniforms>() % 16, 0);
    let mut end = 0;
    for m in FrameUniforms::MEMBERS {
        assert_eq!(m.offset, end, "a gap before {}", m.name);
        assert_eq!(
            m.offset / 16,
            (m.offset + m.size - 1) / 16,
            "{} crosses a 16-byte row",
            m.name
        );
        end = m.offset + m.size;
    }
    assert_eq!(end, FrameUniforms::SIZE);
    assert_eq!(offset_of!(FrameUniforms, camera_position), 0);
    assert_eq!(
        Scene::default().uniforms().as_bytes().len(),
        FrameUniforms::SIZE
    );
}

#[test]
fn wind_offsets_wrap_after_a_million_seconds() {
    for direction in [0.0, 37.0, 90.0, 180.0, 225.0, 300.0] {
        for time in [1e6, -1e6, 3.6e3 * 24.0, 0.0] {
            let mut scene = Scene::default();
            scene.clouds.wind_direction_deg = direction;
            scene.clouds.wind_speed_m_s = 17.3;
            scene.clouds.time_s = time;
            let c = &scene.clouds;
            let periods = [
                c.weather_period_m,
                c.shape_period_m,
                c.detail_period_m,
                c.curl_period_m,
            ];
            let offsets = scene.wind_offsets();
            let (dx, dz) = direction.to_radians().sin_cos();
            let distance = c.wind_speed_m_s * time;
            for (offset, period) in offsets.iter().zip(periods) {
                for (o, unwrapped) in offset.iter().zip([dx * distance, dz * distance]) {
                    assert!((0.0..period).contains(o), "{o} not in [0, {period})");
                    // Same point of the tiling texture as the unwrapped offset.
                    let turns = (unwrapped - o) / period;
                    assert!((turns - turns.round()).abs() < 1e-9, "{unwrapped} vs {o}");
                }
            }
            let u = scene.uniforms();
            let flat = [
                u.weather_offset,
                u.shape_offset,
                u.detail_offset,
                u.curl_offset,
            ]
            .concat();
            for (i, o) in flat.iter().enumerate() {
                let period = periods[i / 2] as f32;
                assert!((0.0..period).contains(o), "{o} not in [0, {period})");
                // Equal up to f32 rounding, on the circle of the period (period == 0).
                let diff = (f64::from(*o) - offsets[i / 2][i % 2]).rem_euclid(f64::from(period));
                assert!(
                    diff.min(f64::from(period) - diff) < 1e-2,
                    "{o} vs {:?}",
                    offsets[i / 2]
                );
            }
        }
    }
}

#[test]
fn wind_blows_toward_its_direction() {
    let mut scene = Scene::default();
    scene.clouds.wind_direction_deg = 90.0; // toward the east, +X
    scene.clouds.wind_speed_m_s = 10.0;
    scene.clouds.time_s = 2.0;
    let [x, z] = scene.wind_offsets()[0];
    assert!((x - 20.0).abs() < 1e-9 && z.abs() < 1e-9, "{x} {z}");
}

#[test]
fn sun_direction() {
    let mut scene = Scene::default();
    scene.sun.elevation_deg = 90.0;
    assert_close(scene.sun_direction(), [0.0, 1.0, 0.0]);
    scene.sun.elevation_deg = 0.0;
    scene.sun.azimuth_deg = 90.0;
    assert_close(scene.sun_direction(), [1.0, 0.0, 0.0]);
    scene.sun.azimuth_deg = 0.0;
    assert_close(scene.sun_direction(), [0.0, 0.0, 1.0]);
    scene.sun.direction = Some([0.0, 3.0, -4.0]);
    assert_close(scene.sun_direction(), [0.0, 0.6, -0.8]);
}

#[test]
fn camera_basis_is_orthonormal() {
    let mut scene = Scene::default();
    for yaw in [0.0, 33.0, 90.0, 180.0, -135.0, 400.0] {
        for pitch in [-90.0, -45.0, -12.5, 0.0, 12.0, 60.0, 90.0] {
            scene.camera.yaw_deg = yaw;
            scene.camera.pitch_deg = pitch;
            let (f, r, u) = scene.camera_basis();
            for v in [f, r, u] {
                assert!((dot(v, v) - 1.0).abs() < 1e-12);
            }
            assert!(dot(f, r).abs() < 1e-12 && dot(f, u).abs() < 1e-12 && dot(r, u).abs() < 1e-12);
            assert_close(cross(r, u), f);
            assert!(r[1] == 0.0, "right stays horizontal");
        }
    }
    scene.camera.yaw_deg = 0.0;
    scene.camera.pitch_deg = 0.0;
    let (f, r, u) = scene.camera_basis();
    assert_close(f, [0.0, 0.0, 1.0]);
    assert_close(r, [1.0, 0.0, 0.0]);
    assert_close(u, [0.0, 1.0, 0.0]);
    scene.camera.yaw_deg = 90.0;
    let (f, r, _) = scene.camera_basis();
    assert_close(f, [1.0, 0.0, 0.0]);
    assert_close(r, [0.0, 0.0, -1.0]);
}

#[test]
fn uniforms_carry_the_scene() {
    let mut scene = Scene::preset("sunset").unwrap().with_size(640, 320);
    scene.lighting.beer_powder = true;
    scene.quality.integration = Integration::Riemann;
    scene.clouds.height_model = HeightModel::CloudTypes;
    let u = scene.uniforms();
    assert_eq!((u.size, u.view_steps, u.light_steps), ([640, 320], 64, 6));
    assert_eq!(
        [u.phase_model, u.integration, u.height_model, u.flags],
        [
            PhaseModel::TWO_LOBE_HG,
            Integration::RIEMANN,
            HeightModel::CLOUD_TYPES,
            // sunset is in the physical sky.
            FrameUniforms::FLAG_BEER_POWDER
                | FrameUniforms::FLAG_JITTER
                | FrameUniforms::FLAG_PHYSICAL_SKY,
        ]
    );
    assert_eq!(u.aspect, 2.0);
    assert!((u.tan_half_fov - 30f32.to_radians().tan()).abs() < 1e-6);
    assert_eq!(
        [
            u.planet_radius,
            u.cloud_bottom,
            u.cloud_top,
            u.cutoff_distance
        ],
        [6_360_000.0, 1500.0, 4000.0, 60_000.0]
    );
    assert_eq!(u.step_length, 0.0, "no fixed step length");
    assert_eq!(
        [u.octaves, u.frame_index, u.path_orders, u.extra_layers],
        [scene.lighting.multiple_scattering.octaves, 0, 0, 0]
    );
    let s = scene.sun_direction();
    assert_eq!(&u.sun_direction[..3], &s.map(|x| x as f32));
    assert!((u.sun_cos_radius - 0.2665f32.to_radians().cos()).abs() < 1e-7);
}

/// `[camera.orientation]` replaces yaw and pitch: a file that gives the basis of a yaw and
/// pitch makes the same uniform block, and a rolled basis reaches the block as given.
#[test]
fn an_orientation_replaces_yaw_and_pitch() {
    let mut by_angles = Scene::default();
    by_angles.camera.yaw_deg = 35.0;
    by_angles.camera.pitch_deg = 12.0;
    let (forward, right, up) = by_angles.camera_basis();
    let text = format!(
        "[camera]\nyaw_deg = -80.0\npitch_deg = 12.0\n\n[camera.orientation]\nforward = {forward:?}\nright = {right:?}\nup = {up:?}\n"
    );
    let by_basis = Scene::from_toml_str(&text, "basis.toml").expect("a valid orientation");
    assert_eq!(by_basis.uniforms(), by_angles.uniforms());
    // Rolled 90 degrees about the view axis: the image's up is the old right.
    let mut rolled = Scene::default();
    rolled.camera.orientation = Some(stratus_scene::Orientation {
        forward,
        right: up.map(|x| -x),
        up: right,
    });
    rolled.validate().expect("a rolled camera is valid");
    let u = rolled.uniforms();
    assert_eq!(u.camera_up, right.map(|x| x as f32));
    assert_eq!(u.camera_forward, forward.map(|x| x as f32));
}
