//! METAR (aviation routine weather report) parsing.
//!
//! [`parse`] turns one report such as `KJFK 221651Z 31012G20KT 10SM FEW045 12/M02 A3012` into a
//! [`Metar`] whose quantities are in metres, metres per second, degrees Celsius and hectopascals,
//! whatever units the station used, so the weather mapper never has to care about US versus ICAO
//! conventions.
//!
//! Only the body of the report is decoded. Trend forecasts (`NOSIG`, `TEMPO`, `BECMG`, `INTER`,
//! `PROB30`, `FM1200`) and remarks (`RMK`) describe other times or station-specific details, so
//! parsing stops there. Groups that carry nothing the renderer uses (runway visual range,
//! directional minimum visibility, recent weather, wind shear, runway and sea state, Australian
//! rainfall, military colour states) are recognised and skipped, so that real reports parse while
//! a typo still fails.
//!
//! The parser is total: it never panics, whatever the input (it is fuzzed). METARs are ASCII by
//! definition, so every matcher works on ASCII bytes and a report containing any other character
//! is rejected outright instead of risking a slice inside a multi-byte character.
//!
//! ```
//! let metar = stratus_weather::metar::parse("YPAD 092100Z 22001KT CAVOK 18/09 Q1015 NOSIG")?;
//! assert_eq!(metar.station, "YPAD");
//! assert!(metar.cavok);
//! assert_eq!(metar.temperature_c, Some(18.0));
//! assert_eq!(metar.pressure_hpa, Some(1015.0));
//! # Ok::<(), stratus_weather::metar::MetarError>(())
//! ```

use serde::Serialize;

/// Metres per foot: cloud bases and vertical visibility are reported in hundreds of feet.
const M_PER_FT: f64 = 0.3048;
/// The highest cloud base (or vertical visibility) a report may give, metres: above the
/// tropopause (at most about 18 km, in the tropics) no cloud of the weather forms.
pub const MAX_CLOUD_BASE_M: f64 = 20_000.0;

/// Metres per statute mile (US and Canadian visibility).
const M_PER_SM: f64 = 1609.344;
/// Metres per second per knot.
const M_S_PER_KT: f64 = 0.514444;
/// Hectopascals per inch of mercury (US altimeter setting).
const HPA_PER_INHG: f64 = 33.8639;
/// `9999` and `CAVOK` both mean "10 km or more"; 10 km is the honest lower bound.
const TEN_KM: f64 = 10_000.0;

/// One decoded METAR: the observed state of the atmosphere at an aerodrome.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Metar {
    /// ICAO station identifier, 4 characters (`KJFK`).
    pub station: String,
    /// Day of month and UTC time of the observation (`DDHHMMZ`), when reported.
    pub time: Option<ObservationTime>,
    /// `AUTO`: the observation was made without a human observer.
    pub auto: bool,
    /// Surface wind; `None` when the group is missing or reported as `/////KT`.
    pub wind: Option<Wind>,
    /// Prevailing visibility in metres. Statute miles are converted; `9999` and `CAVOK` are
    /// stored as 10 000 m (meaning "10 km or more"); `P6SM` and `M1/4SM` store the bound.
    pub visibility_m: Option<f64>,
    /// `CAVOK`: visibility 10 km or more, no cloud below 5000 ft, no cumulonimbus, no weather.
    pub cavok: bool,
    /// Present weather groups, in report order.
    pub weather: Vec<PresentWeather>,
    /// Cloud layers in report order (all of them; the mapper decides how many to use). Layers
    /// whose cover an automatic station could not determine (`///030`) are left out.
    pub clouds: Vec<CloudGroup>,
    /// Vertical visibility into an obscured sky (`VV002`), in metres.
    pub vertical_visibility_m: Option<f64>,
    /// `NSC`, `NCD`, `SKC` or `CLR`: the report states there is no (significant) cloud.
    pub no_significant_cloud: bool,
    /// Air temperature in degrees Celsius.
    pub temperature_c: Option<f64>,
    /// Dew point in degrees Celsius.
    pub dewpoint_c: Option<f64>,
    /// Altimeter setting / QNH in hectopascals (`Q1013`, or `A2992` converted from inHg).
    pub pressure_hpa: Option<f64>,
}

/// Observation time: day of month and UTC hour and minute.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub struct ObservationTime {
    /// Day of month, 1-31.
    pub day: u8,
    /// Hour, 0-23 UTC.
    pub hour: u8,
    /// Minute, 0-59.
    pub minute: u8,
}

/// Surface wind, converted to metres per second.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Wind {
    /// Direction the wind blows from, degrees true; `None` for variable (`VRB`).
    pub direction_deg: Option<f64>,
    /// Mean speed in metres per second.
    pub speed_m_s: f64,
    /// Gust speed in metres per second, when gusts were reported.
    pub gust_m_s: Option<f64>,
    /// Extremes of a varying direction (`dddVddd`), degrees true, clockwise from the first.
    pub variable_from_to_deg: Option<(f64, f64)>,
}

/// Intensity or proximity qualifier of a present-weather group.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub enum Intensity {
    /// `-`
    Light,
    /// No qualifier.
    Moderate,
    /// `+`
    Heavy,
    /// `VC`: in the vicinity (5-10 km) rather than at the aerodrome.
    InVicinity,
}

/// One present-weather group such as `+TSRA` or `FZFG`.
#[derive(Clone, Debug, PartialEq, Eq, Hash, Serialize)]
pub struct PresentWeather {
    /// Intensity or proximity.
    pub intensity: Intensity,
    /// Descriptor: `MI BC PR DR BL SH TS FZ`.
    pub descriptor: Option<String>,
    /// Phenomena (two-letter codes such as `RA`, `SN`, `FG`), possibly none for `TS` / `VCSH`.
    pub phenomena: Vec<String>,
}

impl PresentWeather {
    /// Whether the descriptor or any phenomenon is `code` (e.g. `has("TS")` for `+TSRA`).
    pub fn has(&self, code: &str) -> bool {
        self.descriptor.as_deref() == Some(code) || self.phenomena.iter().any(|p| p == code)
    }
}

/// How much of the sky a cloud layer covers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub enum Cover {
    /// `FEW`: 1-2 oktas.
    Few,
    /// `SCT`: 3-4 oktas.
    Scattered,
    /// `BKN`: 5-7 oktas.
    Broken,
    /// `OVC`: 8 oktas.
    Overcast,
}

impl Cover {
    /// The range of sky eighths (oktas) the code stands for, inclusive.
    pub fn oktas(self) -> (u8, u8) {
        match self {
            Cover::Few => (1, 2),
            Cover::Scattered => (3, 4),
            Cover::Broken => (5, 7),
            Cover::Overcast => (8, 8),
        }
    }
}

/// Convective cloud type appended to a cloud group.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub enum Convective {
    /// `CB`
    Cumulonimbus,
    /// `TCU`
    ToweringCumulus,
}

/// One cloud layer such as `BKN025CB`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct CloudGroup {
    /// Sky cover.
    pub cover: Cover,
    /// Height of the base above the aerodrome in metres; `None` when reported as `///`.
    pub base_m: Option<f64>,
    /// Cumulonimbus or towering cumulus, when flagged.
    pub convective: Option<Convective>,
}

/// Why a report could not be parsed, naming the offending group and where it is.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("METAR: {message}: `{token}` at character {position} (group {index})")]
pub struct MetarError {
    /// The offending group as written (empty when the report ended too early).
    pub token: String,
    /// 0-based character offset of the group in the report.
    pub position: usize,
    /// 0-based index of the group among the report's whitespace-separated groups.
    pub index: usize,
    /// What is wrong.
    pub message: String,
}

/// Parses one METAR or SPECI report (see the [module documentation](self)).
///
/// Lower-case input is accepted; a trailing `=` is ignored.
///
/// # Errors
///
/// A [`MetarError`] for an empty or `NIL` report, a missing or malformed station, an impossible
/// time, a non-ASCII character, or any group that is not valid where it stands.
pub fn parse(report: &str) -> Result<Metar, MetarError> {
    // Bulletins terminate each report with `=`; it carries no data.
    let body = report.trim_end().trim_end_matches('=');
    let tokens = tokenize(body);
    let end = Token {
        text: "",
        upper: String::new(),
        position: body.chars().count(),
    };
    let error = |index: usize, message: &str| {
        let token = tokens.get(index).unwrap_or(&end);
        MetarError {
            token: token.text.to_owned(),
            position: token.position,
            index,
            message: message.to_owned(),
        }
    };
    if tokens.is_empty() {
        return Err(error(0, "empty report"));
    }
    if let Some(index) = tokens.iter().position(|t| !t.text.is_ascii()) {
        return Err(error(index, "non-ASCII character in report"));
    }
    let upper = |index: usize| tokens.get(index).map(|t| t.upper.as_bytes());

    let mut index = 0;
    if matches!(upper(0), Some(b"METAR" | b"SPECI")) {
        index += 1;
    }
    if matches!(upper(index), Some(b"COR" | b"AMD")) {
        index += 1;
    }
    let station = match upper(index) {
        Some(b) if is_station(b) => String::from_utf8_lossy(b).into_owned(),
        Some(_) => {
            return Err(error(
                index,
                "expected a 4-character ICAO station identifier",
            ));
        }
        None => return Err(error(index, "missing station identifier")),
    };
    index += 1;

    let mut metar = Metar {
        station,
        time: None,
        auto: false,
        wind: None,
        visibility_m: None,
        cavok: false,
        weather: Vec::new(),
        clouds: Vec::new(),
        vertical_visibility_m: None,
        no_significant_cloud: false,
        temperature_c: None,
        dewpoint_c: None,
        pressure_hpa: None,
    };

    // Header: the time and report modifiers, in whatever order stations emit them.
    while let Some(b) = upper(index) {
        match b {
            b"AUTO" => metar.auto = true,
            // Corrections: `COR`, and Canada's `CCA`, `CCB`, ...
            b"COR" | b"AMD" | b"RTD" | [b'C', b'C', b'A'..=b'Z'] => {}
            b"NIL" => return Err(error(index, "report is NIL")),
            _ if metar.time.is_none() && b.len() == 7 && b.ends_with(b"Z") => {
                metar.time = Some(observation_time(b).map_err(|m| error(index, m))?);
            }
            _ => break,
        }
        index += 1;
    }

    // Body: each group may be any of the stages from the current one on, so optional groups can
    // be missing but a group out of METAR order is an error.
    let mut stage = 0;
    while let Some(b) = upper(index) {
        if ends_body(b) {
            break;
        }
        if b == b"NIL" {
            return Err(error(index, "report is NIL"));
        }
        let rest = tokens.get(index..).unwrap_or_default();
        let mut matched = None;
        for (k, &(parse, repeats)) in STAGES.iter().enumerate().skip(stage) {
            if let Some(consumed) = parse(rest, &mut metar).map_err(|m| error(index, m))? {
                matched = Some((k, repeats, consumed));
                break;
            }
        }
        let Some((k, repeats, consumed)) = matched else {
            return Err(error(index, "unrecognised or out-of-order group"));
        };
        stage = if repeats { k } else { k + 1 };
        index += consumed.max(1);
    }
    Ok(metar)
}

/// A whitespace-separated group of the report.
struct Token<'a> {
    /// As written, for error messages.
    text: &'a str,
    /// ASCII upper-cased, which every matcher works on (so lower-case reports parse).
    upper: String,
    /// 0-based character offset in the report.
    position: usize,
}

fn tokenize(report: &str) -> Vec<Token<'_>> {
    // (start byte, end byte, start char) of each token; byte offsets come from `char_indices`,
    // so slicing stays on character boundaries.
    let mut spans = Vec::new();
    let mut start: Option<(usize, usize)> = None;
    for (chars, (byte, c)) in report.char_indices().enumerate() {
        if c.is_whitespace() {
            if let Some((from, position)) = start.take() {
                spans.push((from, byte, position));
            }
        } else if start.is_none() {
            start = Some((byte, chars));
        }
    }
    if let Some((from, position)) = start {
        spans.push((from, report.len(), position));
    }
    spans
        .into_iter()
        .map(|(from, to, position)| {
            let text = report.get(from..to).unwrap_or_default();
            Token {
                text,
                upper: text.to_ascii_uppercase(),
                position,
            }
        })
        .collect()
}

/// A parser for one kind of group. It returns how many tokens it consumed, `None` when the
/// tokens are not its kind, or an error when they are its kind but malformed.
type StageFn = fn(&[Token<'_>], &mut Metar) -> Result<Option<usize>, &'static str>;

/// The body groups in METAR order, each with whether it may occur several times in a row.
const STAGES: [(StageFn, bool); 10] = [
    (wind, false),
    (wind_variation, false),
    (visibility, false),
    (minimum_visibility, true),
    (runway_visual_range, true),
    (present_weather, true),
    (clouds, true),
    (temperatures, false),
    (pressure, true),
    (supplementary, true),
];

/// The upper-cased bytes of token `i`, empty past the end.
fn group<'t>(tokens: &'t [Token<'_>], i: usize) -> &'t [u8] {
    tokens
        .get(i)
        .map(|t| t.upper.as_bytes())
        .unwrap_or_default()
}

/// The first token's upper-cased bytes.
fn first<'t>(tokens: &'t [Token<'_>]) -> &'t [u8] {
    group(tokens, 0)
}

/// Trend forecasts and remarks: everything from here on is not part of the observation.
fn ends_body(b: &[u8]) -> bool {
    matches!(b, b"RMK" | b"NOSIG" | b"TEMPO" | b"BECMG" | b"INTER")
        || b.strip_prefix(b"PROB")
            .is_some_and(|d| d.len() == 2 && number(d).is_some())
        || b.strip_prefix(b"FM")
            .is_some_and(|d| d.len() == 4 && number(d).is_some())
}

fn is_station(b: &[u8]) -> bool {
    b.len() == 4
        && b.first().is_some_and(u8::is_ascii_alphabetic)
        && b.iter().all(u8::is_ascii_alphanumeric)
}

fn observation_time(b: &[u8]) -> Result<ObservationTime, &'static str> {
    let field = |range: std::ops::Range<usize>| {
        b.get(range)
            .filter(|d| d.len() == 2)
            .and_then(number)
            .and_then(|n| u8::try_from(n).ok())
            .ok_or("malformed observation time (expected DDHHMMZ)")
    };
    let (day, hour, minute) = (field(0..2)?, field(2..4)?, field(4..6)?);
    if !(1..=31).contains(&day) {
        return Err("day of month out of range 1-31");
    }
    if hour > 23 {
        return Err("hour out of range 0-23");
    }
    if minute > 59 {
        return Err("minute out of range 0-59");
    }
    Ok(ObservationTime { day, hour, minute })
}

/// A run of 1 to 6 ASCII digits; the length cap keeps the value far from overflow.
fn number(b: &[u8]) -> Option<u32> {
    if b.is_empty() || b.len() > 6 || !b.iter().all(u8::is_ascii_digit) {
        return None;
    }
    Some(b.iter().fold(0, |n, d| n * 10 + u32::from(d - b'0')))
}

/// Exactly `len` digits.
fn digits(b: &[u8], len: usize) -> Option<u32> {
    if b.len() == len { number(b) } else { None }
}

/// Splits at the first `sep`, dropping it.
fn split_once(b: &[u8], sep: u8) -> Option<(&[u8], &[u8])> {
    let at = b.iter().position(|&c| c == sep)?;
    let (left, right) = b.split_at(at);
    Some((left, right.get(1..)?))
}

/// A direction in degrees, 3 digits, at most 360.
fn direction(b: &[u8]) -> Result<Option<f64>, &'static str> {
    match digits(b, 3) {
        Some(d) if d <= 360 => Ok(Some(f64::from(d))),
        Some(_) => Err("wind direction above 360 degrees"),
        None => Ok(None),
    }
}

fn wind(tokens: &[Token<'_>], metar: &mut Metar) -> Result<Option<usize>, &'static str> {
    let b = first(tokens);
    let units: [(&[u8], f64); 3] = [(b"KT", M_S_PER_KT), (b"MPS", 1.0), (b"KMH", 1.0 / 3.6)];
    let Some((body, to_m_s)) = units
        .iter()
        .find_map(|&(unit, factor)| Some((b.strip_suffix(unit)?, factor)))
    else {
        return Ok(None);
    };
    if body == b"/////" {
        return Ok(Some(1));
    }
    const MALFORMED: &str = "malformed wind group (expected dddff[Gff]KT)";
    let (dir, speeds) = body.split_at_checked(3).ok_or(MALFORMED)?;
    let direction_deg = match dir {
        b"VRB" => None,
        _ => Some(direction(dir)?.ok_or(MALFORMED)?),
    };
    let (speed, gust) = match split_once(speeds, b'G') {
        Some((speed, gust)) => (speed, Some(gust)),
        None => (speeds, None),
    };
    let speed_value = |s: &[u8]| {
        let n = number(s)
            .filter(|_| (2..=3).contains(&s.len()))
            .ok_or(MALFORMED)?;
        Ok::<_, &'static str>(f64::from(n) * to_m_s)
    };
    metar.wind = Some(Wind {
        direction_deg,
        speed_m_s: speed_value(speed)?,
        gust_m_s: gust.map(speed_value).transpose()?,
        variable_from_to_deg: None,
    });
    Ok(Some(1))
}

fn wind_variation(tokens: &[Token<'_>], metar: &mut Metar) -> Result<Option<usize>, &'static str> {
    let b = first(tokens);
    let Some((from, to)) = split_once(b, b'V').filter(|(f, t)| f.len() == 3 && t.len() == 3) else {
        return Ok(None);
    };
    let (Some(from), Some(to)) = (direction(from)?, direction(to)?) else {
        return Ok(None);
    };
    // A variation without a wind group has nothing to attach to; keep it only with a wind.
    if let Some(wind) = &mut metar.wind {
        wind.variable_from_to_deg = Some((from, to));
    }
    Ok(Some(1))
}

/// `n/d` with a non-zero denominator, in miles.
fn fraction(b: &[u8]) -> Option<f64> {
    let (n, d) = split_once(b, b'/')?;
    let (n, d) = (
        number(n).filter(|_| n.len() <= 2)?,
        number(d).filter(|_| d.len() <= 2)?,
    );
    (d != 0).then(|| f64::from(n) / f64::from(d))
}

fn visibility(tokens: &[Token<'_>], metar: &mut Metar) -> Result<Option<usize>, &'static str> {
    let b = first(tokens);
    match b {
        b"CAVOK" => {
            metar.cavok = true;
            metar.visibility_m = Some(TEN_KM);
            return Ok(Some(1));
        }
        b"////" | b"////SM" => return Ok(Some(1)),
        _ => {}
    }
    // Metres: `0800`, `9999`, `4000NDV` (no directional variation: an automatic sensor).
    if let Some(m) = digits(b.strip_suffix(b"NDV").unwrap_or(b), 4) {
        metar.visibility_m = Some(if m == 9999 { TEN_KM } else { f64::from(m) });
        return Ok(Some(1));
    }
    // Statute miles split over two groups: `1 1/2SM`.
    if let Some(whole) = number(b).filter(|_| b.len() <= 2) {
        if let Some(part) = group(tokens, 1).strip_suffix(b"SM").and_then(fraction) {
            metar.visibility_m = Some((f64::from(whole) + part) * M_PER_SM);
            return Ok(Some(2));
        }
    }
    // `10SM`, `1/2SM`; `P6SM` (more than) and `M1/4SM` (less than) keep the bound.
    if let Some(miles) = b.strip_suffix(b"SM") {
        let miles = miles
            .strip_prefix(b"P")
            .or_else(|| miles.strip_prefix(b"M"))
            .unwrap_or(miles);
        let value = fraction(miles)
            .or_else(|| number(miles).filter(|_| miles.len() <= 3).map(f64::from))
            .ok_or("malformed visibility in statute miles")?;
        metar.visibility_m = Some(value * M_PER_SM);
        return Ok(Some(1));
    }
    Ok(None)
}

/// `2000SW`: the lowest visibility and its direction, which the renderer does not use.
fn minimum_visibility(tokens: &[Token<'_>], _: &mut Metar) -> Result<Option<usize>, &'static str> {
    let b = first(tokens);
    let found = b.split_at_checked(4).is_some_and(|(m, dir)| {
        digits(m, 4).is_some()
            && matches!(
                dir,
                b"N" | b"NE" | b"E" | b"SE" | b"S" | b"SW" | b"W" | b"NW"
            )
    });
    Ok(found.then_some(1))
}

/// `04`, `22L`, `09R`, `36C`.
fn is_runway(b: &[u8]) -> bool {
    match b {
        [a, b] => a.is_ascii_digit() && b.is_ascii_digit(),
        [a, b, side] => {
            a.is_ascii_digit() && b.is_ascii_digit() && matches!(side, b'L' | b'C' | b'R')
        }
        _ => false,
    }
}

/// `R04R/P1500N`, `R22L/0600V1000FT/U`: runway visual range, skipped.
fn runway_visual_range(tokens: &[Token<'_>], _: &mut Metar) -> Result<Option<usize>, &'static str> {
    let found = first(tokens)
        .strip_prefix(b"R")
        .and_then(|r| split_once(r, b'/'))
        .is_some_and(|(runway, value)| {
            is_runway(runway)
                && value
                    .first()
                    .is_some_and(|c| c.is_ascii_digit() || b"PM/".contains(c))
                && value.iter().all(|c| b"0123456789PMVUDNFT/".contains(c))
        });
    Ok(found.then_some(1))
}

const DESCRIPTORS: [&str; 8] = ["MI", "BC", "PR", "DR", "BL", "SH", "TS", "FZ"];
const PHENOMENA: [&str; 22] = [
    "DZ", "RA", "SN", "SG", "IC", "PL", "GR", "GS", "UP", "BR", "FG", "FU", "VA", "DU", "SA", "HZ",
    "PY", "PO", "SQ", "FC", "SS", "DS",
];

fn lookup(table: &[&'static str], code: &[u8]) -> Option<&'static str> {
    table.iter().copied().find(|t| t.as_bytes() == code)
}

/// `[-|+|VC][descriptor]phenomena...`, e.g. `+TSRA`, `VCSH`, `FZFG`, `-RADZ`.
fn weather_group(b: &[u8]) -> Option<PresentWeather> {
    let (intensity, rest) = if let Some(r) = b.strip_prefix(b"-") {
        (Intensity::Light, r)
    } else if let Some(r) = b.strip_prefix(b"+") {
        (Intensity::Heavy, r)
    } else if let Some(r) = b.strip_prefix(b"VC") {
        (Intensity::InVicinity, r)
    } else {
        (Intensity::Moderate, b)
    };
    let descriptor = rest.get(..2).and_then(|d| lookup(&DESCRIPTORS, d));
    let rest = if descriptor.is_some() {
        rest.get(2..)?
    } else {
        rest
    };
    if rest.len() % 2 != 0 {
        return None;
    }
    let phenomena = rest
        .chunks(2)
        .map(|code| lookup(&PHENOMENA, code).map(str::to_owned))
        .collect::<Option<Vec<_>>>()?;
    // Only thunder (`TS`) and showers in the vicinity (`VCSH`) stand without a phenomenon.
    if phenomena.is_empty() && !matches!(descriptor, Some("TS" | "SH")) {
        return None;
    }
    Some(PresentWeather {
        intensity,
        descriptor: descriptor.map(str::to_owned),
        phenomena,
    })
}

fn present_weather(tokens: &[Token<'_>], metar: &mut Metar) -> Result<Option<usize>, &'static str> {
    let b = first(tokens);
    // `//`: not observed (automatic station); `NSW`: no significant weather.
    if matches!(b, b"//" | b"NSW") {
        return Ok(Some(1));
    }
    let Some(weather) = weather_group(b) else {
        return Ok(None);
    };
    metar.weather.push(weather);
    Ok(Some(1))
}

/// Hundreds of feet (`045`) to metres; `///` is unknown.
fn hundreds_of_feet(b: &[u8]) -> Option<Option<f64>> {
    if b == b"///" {
        return Some(None);
    }
    Some(Some(f64::from(digits(b, 3)?) * 100.0 * M_PER_FT))
}

fn clouds(tokens: &[Token<'_>], metar: &mut Metar) -> Result<Option<usize>, &'static str> {
    let b = first(tokens);
    if matches!(b, b"NSC" | b"NCD" | b"SKC" | b"CLR") {
        metar.no_significant_cloud = true;
        return Ok(Some(1));
    }
    if let Some(height) = b.strip_prefix(b"VV").and_then(hundreds_of_feet) {
        if height.is_some_and(|h| h > MAX_CLOUD_BASE_M) {
            return Err("a vertical visibility above 20 km: no cloud or fog reaches there");
        }
        metar.vertical_visibility_m = height;
        return Ok(Some(1));
    }
    let (Some(cover), Some(height), Some(kind)) = (b.get(..3), b.get(3..6), b.get(6..)) else {
        return Ok(None);
    };
    let cover = match cover {
        b"FEW" => Some(Cover::Few),
        b"SCT" => Some(Cover::Scattered),
        b"BKN" => Some(Cover::Broken),
        b"OVC" => Some(Cover::Overcast),
        b"///" => None,
        _ => return Ok(None),
    };
    let Some(base_m) = hundreds_of_feet(height) else {
        return Ok(None);
    };
    if base_m.is_some_and(|h| h > MAX_CLOUD_BASE_M) {
        return Err(
            "a cloud base above 20 km: no cloud forms there (the tropopause is at most about 18 km)",
        );
    }
    let convective = match kind {
        b"" | b"///" => None,
        b"CB" => Some(Convective::Cumulonimbus),
        b"TCU" => Some(Convective::ToweringCumulus),
        _ => return Ok(None),
    };
    // An automatic station that cannot tell the cover (`//////`, `///030`) gives no layer.
    if let Some(cover) = cover {
        metar.clouds.push(CloudGroup {
            cover,
            base_m,
            convective,
        });
    }
    Ok(Some(1))
}

/// `12`, `M05` (minus) or `//`, and what follows it.
fn temperature(b: &[u8]) -> Option<(Option<f64>, &[u8])> {
    if let Some(rest) = b.strip_prefix(b"//") {
        return Some((None, rest));
    }
    let (negative, b) = match b.strip_prefix(b"M") {
        Some(rest) => (true, rest),
        None => (false, b),
    };
    let (value, rest) = b.split_at_checked(2)?;
    let value = f64::from(digits(value, 2)?);
    // `M00` is a temperature just below zero; report 0 rather than IEEE negative zero.
    let value = if negative && value > 0.0 {
        -value
    } else {
        value
    };
    Some((Some(value), rest))
}

/// `12/M02`, `M05/M08`, `12/`, `/////`.
fn temperatures(tokens: &[Token<'_>], metar: &mut Metar) -> Result<Option<usize>, &'static str> {
    let parsed = temperature(first(tokens)).and_then(|(air, rest)| {
        let dew = match rest.strip_prefix(b"/")? {
            b"" | b"//" => None,
            dew => match temperature(dew)? {
                (value, b"") => value,
                _ => return None,
            },
        };
        Some((air, dew))
    });
    Ok(parsed.map(|(air, dew)| {
        metar.temperature_c = air;
        metar.dewpoint_c = dew;
        1
    }))
}

/// `Q1013` (hPa), `A3012` (hundredths of inHg), `Q////`. Some stations give both; the first wins.
fn pressure(tokens: &[Token<'_>], metar: &mut Metar) -> Result<Option<usize>, &'static str> {
    let Some((&unit, value)) = first(tokens).split_first() else {
        return Ok(None);
    };
    let to_hpa = match unit {
        b'Q' => 1.0,
        b'A' => HPA_PER_INHG / 100.0,
        _ => return Ok(None),
    };
    let hpa = match value {
        b"////" => None,
        _ => match digits(value, 4) {
            Some(v) => Some(f64::from(v) * to_hpa),
            None => return Ok(None),
        },
    };
    if metar.pressure_hpa.is_none() {
        metar.pressure_hpa = hpa;
    }
    Ok(Some(1))
}

/// Groups after the pressure that the renderer does not use: recent weather (`RERA`), wind
/// shear (`WS R04`, `WS ALL RWY`), runway state (`R24/290050`, `R21/SNOCLO`), sea state
/// (`W15/S2`), Australian rainfall (`RF00.0/000.0`) and military colour states (`BLU`, `BLACKAMB`).
fn supplementary(tokens: &[Token<'_>], _: &mut Metar) -> Result<Option<usize>, &'static str> {
    let b = first(tokens);
    if b == b"WS" {
        let runway = |r: &[u8]| {
            r.strip_prefix(b"RWY")
                .or_else(|| r.strip_prefix(b"R"))
                .is_some_and(is_runway)
        };
        return match (group(tokens, 1), group(tokens, 2)) {
            (b"ALL", b"RWY") => Ok(Some(3)),
            (r, _) if runway(r) => Ok(Some(2)),
            _ => Err("malformed wind shear group (expected WS Rdd or WS ALL RWY)"),
        };
    }
    let recent = b.strip_prefix(b"RE").is_some_and(|w| {
        w == b"//" || weather_group(w).is_some_and(|w| w.intensity == Intensity::Moderate)
    });
    let runway_state = matches!(b, b"R/SNOCLO" | b"SNOCLO")
        || b.strip_prefix(b"R")
            .and_then(|r| split_once(r, b'/'))
            .is_some_and(|(runway, state)| {
                is_runway(runway)
                    && (matches!(state, b"SNOCLO" | b"D")
                        || state.strip_prefix(b"CLRD").is_some_and(|d| d.len() == 2)
                        || (2..=6).contains(&state.len())
                            && state
                                .iter()
                                .all(|c| c.is_ascii_digit() || b"/D".contains(c)))
            });
    // `W` + sea temperature (`15`, `M01`, `//`) + `/` + state (`S4`) or wave height (`H12`).
    let sea_state = b.strip_prefix(b"W").is_some_and(|r| {
        let r = r.strip_prefix(b"M").unwrap_or(r);
        let (temperature, state) = r.split_at_checked(3).unwrap_or_default();
        let known = |c: &u8| c.is_ascii_digit();
        let temperature_ok = match temperature {
            [a, b, b'/'] => (known(a) && known(b)) || (*a == b'/' && *b == b'/'),
            _ => false,
        };
        temperature_ok && state.len() >= 2 && matches!(state.first(), Some(b'S' | b'H'))
    });
    let rainfall = b.strip_prefix(b"RF").is_some_and(|r| {
        !r.is_empty() && r.iter().all(|c| c.is_ascii_digit() || b"./".contains(c))
    });
    let colour = {
        let c = b.strip_prefix(b"BLACK").unwrap_or(b);
        let c = c.strip_suffix(b"+").unwrap_or(c);
        matches!(
            c,
            b"BLU" | b"WHT" | b"GRN" | b"YLO" | b"YLO1" | b"YLO2" | b"AMB" | b"RED"
        )
    };
    Ok((recent || runway_state || sea_state || rainfall || colour).then_some(1))
}
