//! Extra cloud layers: validation names the broken rule, and the uniform block carries them.

use stratus_scene::{CloudLayer, Method, Scene};

fn with_layers(layers: Vec<CloudLayer>) -> Scene {
    let mut s = Scene::default();
    s.clouds.layers = layers;
    s
}

fn error(s: &Scene) -> String {
    s.validate().expect_err("should be refused").to_string()
}

#[test]
fn layers_may_not_overlap_or_be_too_many() {
    let high = CloudLayer::default();
    assert!(with_layers(vec![high.clone()]).validate().is_ok());
    let overlapping = CloudLayer {
        bottom_m: 3000.0,
        top_m: 5000.0,
        ..high.clone()
    };
    let e = error(&with_layers(vec![overlapping]));
    assert!(
        e.contains("must not overlap") && e.contains("the main layer"),
        "{e}"
    );
    let e = error(&with_layers(vec![high.clone(); 4]));
    assert!(e.contains("at most 3 extra layers"), "{e}");
    let upside_down = CloudLayer {
        bottom_m: 7000.0,
        top_m: 6000.0,
        ..high.clone()
    };
    let e = error(&with_layers(vec![upside_down]));
    assert!(e.contains("layer 1: top_m = 6000"), "{e}");
    let mut sprites = with_layers(vec![high.clone()]);
    sprites.quality.method = Method::Sprites;
    assert!(error(&sprites).contains("several layers need"));
}

#[test]
fn the_uniforms_carry_each_layer_with_its_own_weather_offset() {
    let s = with_layers(vec![
        CloudLayer::default(),
        CloudLayer {
            bottom_m: 9000.0,
            top_m: 9500.0,
            coverage: 0.2,
            ..CloudLayer::default()
        },
    ]);
    let u = s.uniforms();
    assert_eq!(u.extra_layers, 2);
    assert_eq!(
        [
            u.layer1_bottom,
            u.layer1_top,
            u.layer1_coverage,
            u.layer1_density
        ],
        [6000.0, 7000.0, 0.5, 0.3]
    );
    assert_eq!(
        [u.layer2_bottom, u.layer2_top, u.layer2_coverage],
        [9000.0, 9500.0, 0.2]
    );
    assert_eq!(
        [
            u.layer3_bottom,
            u.layer3_top,
            u.layer3_coverage,
            u.layer3_density
        ],
        [0.0; 4]
    );
    // Offsets differ from the main layer's and from each other, within one period.
    let period = s.clouds.weather_period_m as f32;
    let main = [u.weather_offset[0], u.weather_offset[1]];
    let o1 = [u.layer1_weather_offset[0], u.layer1_weather_offset[1]];
    let o2 = [u.layer2_weather_offset[0], u.layer2_weather_offset[1]];
    assert!(main != o1 && o1 != o2 && main != o2);
    assert!(o1.iter().chain(&o2).all(|&v| (0.0..period).contains(&v)));
    // Without extra layers the block is what it was.
    assert_eq!(Scene::default().uniforms().extra_layers, 0);
}

#[test]
fn cirrus_is_a_share_and_the_baselines_refuse_it() {
    let mut s = Scene::default();
    s.clouds.cirrus = 1.5;
    assert!(error(&s).contains("clouds.cirrus"), "{}", error(&s));
    s.clouds.cirrus = 1.0;
    assert!(s.validate().is_ok());
    s.quality.method = Method::Basic;
    let e = error(&s);
    assert!(
        e.contains("clouds.cirrus") && e.contains("draws water cloud only"),
        "{e}"
    );
    let e = error(&with_layers(vec![CloudLayer {
        cirrus: -0.5,
        ..CloudLayer::default()
    }]));
    assert!(e.contains("layer 1: cirrus = -0.5"), "{e}");
}

/// A cellular share outside [0, 1] is refused by name, on the main layer and on an extra one,
/// and so is a cellular main layer under a baseline method.
#[test]
fn cellular_is_a_share_and_the_baselines_refuse_it() {
    let mut s = Scene::default();
    s.clouds.cellular = 1.5;
    let e = error(&s);
    assert!(e.contains("clouds.cellular"), "{e}");
    s.clouds.cellular = 1.0;
    assert!(s.validate().is_ok());
    s.quality.method = Method::Basic;
    let e = error(&s);
    assert!(
        e.contains("clouds.cellular") && e.contains("cellular layers need"),
        "{e}"
    );
    let e = error(&with_layers(vec![CloudLayer {
        cellular: 2.0,
        ..CloudLayer::default()
    }]));
    assert!(e.contains("layer 1: cellular = 2"), "{e}");
}
