//! A METAR report turned into a scene: the weather state its present weather and cover
//! suggest, its cloud groups as cloud layers, its wind and, for fog and mist, a ground fog
//! layer from its visibility.

use stratus_scene::{CloudLayer, DEFAULT_CIRRUS_DENSITY, MAX_EXTRA_LAYERS, Scene};

use crate::haze;
use crate::metar::{CloudGroup, Convective, Cover, Intensity, Metar};
use crate::states::{
    self, WeatherState, cell_coverage_for_fraction, coverage_for_fraction,
    fog_density_for_visibility, fog_layer,
};

/// A scene derived from weather observations, with what was derived from what.
#[derive(Clone, Debug, PartialEq)]
pub struct Derived {
    /// The scene (valid: [`Scene::validate`] accepts it).
    pub scene: Scene,
    /// The weather state the scene starts from.
    pub state: &'static WeatherState,
    /// One line per decision: the state and why, the wind, each layer and its source.
    pub notes: Vec<String>,
}

impl Derived {
    /// The scene as a TOML file headed by the notes as comments (every field written, so the
    /// file does not depend on a preset).
    pub fn to_toml(&self, source: &str) -> String {
        let mut out = format!("# Derived by `stratus weather` from: {source}\n");
        for n in &self.notes {
            out.push_str("# ");
            out.push_str(n);
            out.push('\n');
        }
        out.push('\n');
        out.push_str(&self.scene.to_toml());
        out
    }
}

/// Bases closer than this (metres) are one layer: two groups cannot both fit.
const MERGE_M: f64 = 150.0;
/// Gap left between a layer's top and the next layer's base, metres.
const GAP_M: f64 = 50.0;

/// What a cloud group becomes.
struct Kind {
    /// The layer's depth (m).
    thickness: f64,
    /// Cloud type within [0, 1].
    cloud_type: f64,
    /// Density multiplier.
    density: f64,
    /// Cirrus share (ice cloud in fibres).
    cirrus: f64,
    /// Cellular share (cloudlets on the layer's convection cells).
    cellular: f64,
    /// The cloud's name, for the notes.
    name: &'static str,
}

/// What cloud group `g` based at `base` m becomes. `precipitating`: the lowest group of a
/// report with rain or snow, whose closed deck is nimbostratus.
fn cloud_kind(g: &CloudGroup, base: f64, precipitating: bool) -> Kind {
    let closed = matches!(g.cover, Cover::Broken | Cover::Overcast);
    let (thickness, cloud_type, density, name) = match (g.convective, base) {
        // Nimbostratus: thick and stratiform, its base low.
        (None, b) if precipitating && closed && b < 2000.0 => (3000.0, 0.25, 1.0, "nimbostratus"),
        // Cumulonimbus reach the tropopause; towering cumulus about half as far.
        (Some(Convective::Cumulonimbus), _) => (8000.0, 1.0, 1.0, "cumulonimbus"),
        (Some(Convective::ToweringCumulus), _) => (4000.0, 1.0, 1.0, "towering cumulus"),
        (None, b) if b < 300.0 => (600.0, 0.0, 1.0, "stratus"),
        (None, b) if b < 2000.0 => match g.cover {
            Cover::Few | Cover::Scattered => (1500.0, 1.0, 1.0, "cumulus"),
            Cover::Broken | Cover::Overcast => (1000.0, 0.5, 1.0, "stratocumulus"),
        },
        // Middle clouds, thinner water clouds: altocumulus in patches, altostratus where the
        // sky is overcast.
        (None, b) if b < 6000.0 && g.cover == Cover::Overcast => (1000.0, 0.35, 0.6, "altostratus"),
        (None, b) if b < 6000.0 => (1000.0, 0.35, 0.6, "altocumulus"),
        // High clouds: ice, thin and fibrous (cirrus; closed, a cirrostratus veil). The WMO
        // puts high clouds' bases at 5-13 km in temperate regions (International Cloud Atlas,
        // 2017); a cirrus layer is typically 1-2 km deep (Sassen and Campbell 2001).
        (None, _) if !closed => (1500.0, 0.0, DEFAULT_CIRRUS_DENSITY, "cirrus"),
        (None, _) => (1500.0, 0.0, DEFAULT_CIRRUS_DENSITY, "cirrostratus"),
    };
    let share = |yes: bool| if yes { 1.0 } else { 0.0 };
    Kind {
        thickness,
        cloud_type,
        density,
        cirrus: share(matches!(name, "cirrus" | "cirrostratus")),
        // Stratocumulus and altocumulus are fields of cloudlets (`clouds.cellular`).
        cellular: share(matches!(name, "stratocumulus" | "altocumulus")),
        name,
    }
}

fn cover_name(c: Cover) -> &'static str {
    match c {
        Cover::Few => "FEW",
        Cover::Scattered => "SCT",
        Cover::Broken => "BKN",
        Cover::Overcast => "OVC",
    }
}

/// The state a report's present weather and largest cover suggest.
fn classify(m: &Metar) -> (&'static str, String) {
    let present = |code: &str| {
        m.weather
            .iter()
            .any(|w| w.intensity != Intensity::InVicinity && w.has(code))
    };
    let cb = m
        .clouds
        .iter()
        .any(|g| g.convective == Some(Convective::Cumulonimbus));
    if present("TS") || cb {
        return (
            "thunderstorm",
            "thunderstorm (TS) or cumulonimbus (CB) reported".into(),
        );
    }
    for (codes, state) in [
        (&["SN", "SG", "PL", "GS"][..], "snow"),
        (&["RA", "DZ", "GR"][..], "rain"),
        (&["FG"][..], "fog"),
        (&["BR", "HZ"][..], "mist"),
    ] {
        if let Some(c) = codes.iter().find(|c| present(c)) {
            return (state, format!("present weather {c}"));
        }
    }
    let cover = m.clouds.iter().map(|g| g.cover).max_by_key(|c| c.oktas().1);
    match cover {
        None => ("clear", "no cloud groups".into()),
        Some(c) => {
            let state = match c {
                Cover::Few => "few",
                Cover::Scattered => "scattered",
                Cover::Broken => "broken",
                Cover::Overcast => "overcast",
            };
            (state, format!("largest cover {}", cover_name(c)))
        }
    }
}

/// Precipitation from the intensity of the report's precipitation groups (0 when none).
fn precipitation(m: &Metar) -> f64 {
    m.weather
        .iter()
        .filter(|w| {
            ["RA", "DZ", "SN", "SG", "PL", "GS", "GR"]
                .iter()
                .any(|c| w.has(c))
        })
        .map(|w| match w.intensity {
            Intensity::Light => 0.4,
            Intensity::Moderate => 0.7,
            Intensity::Heavy => 1.0,
            Intensity::InVicinity => 0.0,
        })
        .fold(0.0, f64::max)
}

/// Moderate thunderstorms' flashes a minute (a report's TS without `-` or `+`, and the weather
/// service's 雷阵雨); light ones flash 6 a minute, heavy ones 40 (ordinary storms flash a few
/// times a minute, severe ones tens of times: Williams et al. 1999).
pub(crate) const MODERATE_FLASHES_PER_MINUTE: f64 = 20.0;

/// What falls and flashes: `falls` draws its particles and (rain) its shafts below the
/// precipitating layer, their density that layer's precipitation; `flashes` a minute of
/// lightning in the main layer.
pub(crate) fn precipitate(
    scene: &mut Scene,
    falls: Option<stratus_scene::PrecipitationKind>,
    flashes: Option<f64>,
    notes: &mut Vec<String>,
) {
    if let Some(kind) = falls {
        let snow = kind == stratus_scene::PrecipitationKind::Snow;
        let p = &mut scene.precipitation;
        p.kind = kind;
        p.particles = 1.0;
        p.shafts = if snow { 0.0 } else { 1.0 };
        notes.push(format!(
            "precipitation: {} particles below the precipitating layer{}",
            kind.name(),
            if snow { "" } else { ", and rain shafts" }
        ));
    }
    if let Some(rate) = flashes {
        scene.lightning.flashes_per_minute = rate;
        notes.push(format!(
            "lightning: thunderstorm -> {rate} flashes a minute in the main layer"
        ));
    }
}

/// A report's rain or snow (its precipitation `rain` > 0) and thunderstorm (TS, its rate by
/// intensity), as [`precipitate`] draws them.
fn precipitation_and_lightning(m: &Metar, rain: f64, scene: &mut Scene, notes: &mut Vec<String>) {
    let snow = m.weather.iter().any(|w| {
        w.intensity != Intensity::InVicinity
            && ["SN", "SG", "PL", "GS"].iter().any(|c| w.has(c))
            && !w.has("RA")
    });
    let falls = (rain > 0.0).then_some(if snow {
        stratus_scene::PrecipitationKind::Snow
    } else {
        stratus_scene::PrecipitationKind::Rain
    });
    let flashes = m
        .weather
        .iter()
        .find(|w| w.intensity != Intensity::InVicinity && w.has("TS"))
        .map(|ts| match ts.intensity {
            Intensity::Light => 6.0,
            Intensity::Heavy => 40.0,
            _ => MODERATE_FLASHES_PER_MINUTE,
        });
    precipitate(scene, falls, flashes, notes);
}

/// The aerosol of the physical sky from the report's visibility, or from a haze, smoke, dust
/// or mist group without one. Not where a fog layer is drawn: that layer holds the visibility.
fn haze_from_metar(m: &Metar, fog_drawn: bool, scene: &mut Scene, notes: &mut Vec<String>) {
    let present = |codes: &[&'static str]| -> Option<&'static str> {
        m.weather.iter().find_map(|w| {
            (w.intensity != Intensity::InVicinity)
                .then(|| codes.iter().find(|c| w.has(c)).copied())
                .flatten()
        })
    };
    let named = present(&["FU", "VA", "DU", "SA", "HZ", "BR", "FG"]);
    let visibility = m.visibility_m.filter(|v| *v < haze::CLEAR_VISIBILITY_M);
    if fog_drawn {
        return;
    }
    let (v, why) = match (visibility, named) {
        (Some(v), _) => (v, format!("visibility {v:.0} m")),
        (None, Some(code)) => (
            haze::HAZE_VISIBILITY_M,
            format!(
                "{code} without a visibility: {:.0} m",
                haze::HAZE_VISIBILITY_M
            ),
        ),
        (None, None) => {
            // Only the humidity, from the temperature and dew point: the clean air's aerosol
            // grown to it.
            if let (Some(t), Some(d)) = (m.temperature_c, m.dewpoint_c) {
                haze::humid(scene, haze::relative_humidity(t, d), notes);
            }
            return;
        }
    };
    let precipitating = present(&["RA", "DZ", "SN", "SG", "PL", "GS", "GR"]).is_some();
    let kind = match named {
        Some("FU" | "VA") => haze::Aerosol::Smoke,
        Some("DU" | "SA") => haze::Aerosol::Dust,
        Some("BR" | "FG") => haze::Aerosol::Water,
        _ if precipitating => haze::Aerosol::Water,
        _ => haze::Aerosol::Continental,
    };
    haze::apply(scene, v, kind, &why, notes);
}

/// The scene for report `m`, built on `base` (its camera, sun, noise, lighting model and
/// quality are kept).
pub fn scene_from_metar(m: &Metar, base: &Scene) -> Derived {
    let mut notes = Vec::new();
    let (name, why) = classify(m);
    let state = states::find(name).expect("classify names a known state");
    notes.push(format!("state: {name} ({why}): {}", state.about));
    let mut scene = base.clone();
    state.params.apply(&mut scene);
    scene.clouds.layers.clear();

    if let Some(w) = &m.wind {
        scene.clouds.wind_speed_m_s = w.speed_m_s;
        let gust = w
            .gust_m_s
            .map(|g| format!(", gusts {g:.1} m/s (not modelled)"))
            .unwrap_or_default();
        match w.direction_deg {
            // METAR gives where the wind comes from; the scene where it blows to.
            Some(from) => {
                scene.clouds.wind_direction_deg = (from + 180.0).rem_euclid(360.0);
                notes.push(format!(
                    "wind: from {from:.0} deg at {:.1} m/s{gust} -> blowing toward {:.0} deg",
                    w.speed_m_s, scene.clouds.wind_direction_deg
                ));
            }
            None => notes.push(format!(
                "wind: variable at {:.1} m/s{gust}; direction kept ({:.0} deg)",
                w.speed_m_s, scene.clouds.wind_direction_deg
            )),
        }
    }

    // Cloud groups, lowest first; bases too close to separate merge (the larger cover wins).
    let mut groups: Vec<(f64, CloudGroup)> = Vec::new();
    for g in &m.clouds {
        let Some(b) = g.base_m else {
            notes.push(format!(
                "{} group without a base (///): skipped",
                cover_name(g.cover)
            ));
            continue;
        };
        groups.push((b, *g));
    }
    // A vertical visibility (`VV005`) says the sky is hidden by what hangs from the ground up:
    // without cloud groups that height is the obscured deck's base, unless fog or mist is
    // reported, whose ground layer (below) is the obscuration.
    let fog_reported = m
        .weather
        .iter()
        .any(|w| w.intensity != Intensity::InVicinity && (w.has("FG") || w.has("BR")));
    if let Some(vv) = m.vertical_visibility_m {
        if groups.is_empty() && !fog_reported {
            notes.push(format!(
                "VV{:03}: the sky is obscured -> an overcast base at {vv:.0} m",
                (vv / 30.48).round()
            ));
            groups.push((
                vv,
                CloudGroup {
                    cover: Cover::Overcast,
                    base_m: Some(vv),
                    convective: None,
                },
            ));
        }
    }
    groups.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut merged: Vec<(f64, CloudGroup)> = Vec::new();
    for (b, g) in groups {
        match merged.last_mut() {
            Some((lb, lg)) if b - *lb < MERGE_M => {
                notes.push(format!(
                    "{}{:03} merged into the layer at {:.0} m (bases closer than {MERGE_M} m)",
                    cover_name(g.cover),
                    (b / 30.48).round(),
                    lb
                ));
                if g.cover.oktas().1 > lg.cover.oktas().1 {
                    lg.cover = g.cover;
                }
                lg.convective = lg.convective.or(g.convective);
            }
            _ => merged.push((b, g)),
        }
    }
    if merged.len() > MAX_EXTRA_LAYERS + 1 {
        notes.push(format!(
            "{} cloud groups: the lowest {} are drawn",
            merged.len(),
            MAX_EXTRA_LAYERS + 1
        ));
        merged.truncate(MAX_EXTRA_LAYERS + 1);
    }

    let rain = precipitation(m);
    let mut layers: Vec<CloudLayer> = Vec::new();
    // Fair-weather cumulus stand on convective cells (`clouds.convective_cells`), which
    // apply to every cumulus-type layer of the scene: not where the report has towering
    // cumulus or cumulonimbus, whose kilometres-tall columns the cells do not shape (each
    // cell's column, marched in 64 steps, is a noisy curtain).
    let towers = merged.iter().any(|(_, g)| g.convective.is_some());
    let mut cells = false;
    for (i, (b, g)) in merged.iter().enumerate() {
        let precipitating = i == 0 && matches!(name, "rain" | "snow");
        let Kind {
            thickness,
            cloud_type,
            density,
            cirrus,
            cellular,
            name: kind,
        } = cloud_kind(g, *b, precipitating);
        let mut top = b + thickness;
        if let Some((next, _)) = merged.get(i + 1) {
            top = top.min(next - GAP_M);
        }
        let (lo, hi) = g.cover.oktas();
        let on_cells = kind == "cumulus" && !towers;
        cells |= on_cells;
        let fraction = (f64::from(lo) + f64::from(hi)) / 16.0;
        let coverage = if on_cells {
            cell_coverage_for_fraction(fraction)
        } else {
            coverage_for_fraction(fraction)
        };
        // Precipitation falls from the lowest layer.
        let precipitation = if i == 0 { rain } else { 0.0 };
        notes.push(format!(
            "layer {}: {}{:03}{} -> {kind}{} from {:.0} to {:.0} m, coverage {coverage:.2} ({lo}-{hi} oktas), type {cloud_type}, density {density}{}",
            i + 1,
            cover_name(g.cover),
            (b / 30.48).round(),
            match g.convective {
                Some(Convective::Cumulonimbus) => "CB",
                Some(Convective::ToweringCumulus) => "TCU",
                None => "",
            },
            if on_cells { " on convective cells" } else { "" },
            b,
            top,
            if precipitation > 0.0 {
                format!(", precipitation {precipitation}")
            } else {
                String::new()
            }
        ));
        layers.push(CloudLayer {
            bottom_m: *b,
            top_m: top,
            coverage,
            density,
            cloud_type,
            precipitation,
            cirrus,
            cellular,
        });
    }
    if layers.is_empty() && !matches!(name, "fog" | "mist" | "rain" | "snow" | "thunderstorm") {
        // Clear: no groups (CAVOK, NSC, SKC, CLR or none reported).
        scene.clouds.coverage = 0.0;
        notes.push("no cloud layers: clear sky".into());
    } else if layers.is_empty() {
        notes.push(format!(
            "no cloud groups: the {name} state's deck from {:.0} to {:.0} m",
            scene.atmosphere.cloud_bottom_m, scene.atmosphere.cloud_top_m
        ));
    }

    // Ground fog from the visibility (Koschmieder), below the lowest layer.
    let fog = m
        .weather
        .iter()
        .any(|w| w.intensity != Intensity::InVicinity && (w.has("FG") || w.has("BR")));
    let mut fog_layer_opt = None;
    if fog {
        let visibility = m
            .visibility_m
            .unwrap_or(if name == "fog" { 300.0 } else { 3000.0 });
        let visibility = visibility.clamp(50.0, 10_000.0);
        // The stratus profile fills the lowest ~35% of its layer: a 1000 m layer holds
        // fog about 350 m deep (a vertical visibility, VV, says the sky is hidden, not how
        // deep the fog is).
        let mut top: f64 = 1000.0;
        let lowest = layers
            .first()
            .map(|l| l.bottom_m)
            .unwrap_or(scene.atmosphere.cloud_bottom_m);
        top = top.min(lowest - GAP_M);
        if top >= 100.0 {
            let density = fog_density_for_visibility(visibility);
            notes.push(format!(
                "fog: visibility {visibility:.0} m -> a ground stratus layer to {top:.0} m, density {density:.3} (Koschmieder: 3.912 / extinction)"
            ));
            fog_layer_opt = Some(fog_layer(top, density));
        } else {
            notes.push("fog: no room below the lowest layer; not drawn".into());
        }
    }

    haze_from_metar(m, fog_layer_opt.is_some(), &mut scene, &mut notes);
    precipitation_and_lightning(m, rain, &mut scene, &mut notes);

    // The lowest cloud group is the main layer (its geometry is `[atmosphere]`, its weather
    // `[clouds]`); the other groups and the fog are extra layers. Fog alone keeps the state's
    // main deck.
    let mut layers = layers.into_iter();
    if let Some(main) = layers.next() {
        scene.clouds.convective_cells = if cells { 1.0 } else { 0.0 };
        // A cumulonimbus spreads into an anvil at its top. Anvils take only layers deep enough
        // to be one (density.wgsl::anvil_cover), so a fair cumulus layer beside it keeps its
        // domes.
        let cb = merged
            .iter()
            .any(|(_, g)| g.convective == Some(Convective::Cumulonimbus));
        scene.clouds.anvil = if cb { 1.0 } else { 0.0 };
        scene.atmosphere.cloud_bottom_m = main.bottom_m;
        scene.atmosphere.cloud_top_m = main.top_m;
        scene.clouds.coverage = main.coverage;
        scene.clouds.density = main.density;
        scene.clouds.cloud_type = main.cloud_type;
        scene.clouds.precipitation = main.precipitation;
        scene.clouds.cirrus = main.cirrus;
        scene.clouds.cellular = main.cellular;
    } else if rain > 0.0 {
        scene.clouds.precipitation = rain;
    }
    let mut all: Vec<CloudLayer> = layers.collect();
    if let Some(f) = fog_layer_opt {
        if all.len() >= MAX_EXTRA_LAYERS {
            let dropped = all.pop().expect("non-empty");
            notes.push(format!(
                "four layers and fog: the highest layer ({:.0} m) is dropped",
                dropped.bottom_m
            ));
        }
        all.push(f);
    }
    scene.clouds.layers = all;
    notes.push(format!(
        "{} cloud layer(s) in all",
        1 + scene.clouds.layers.len()
    ));
    Derived {
        scene,
        state,
        notes,
    }
}
