//! Small text helpers for error messages: number and TOML value formatting, edit distance,
//! "did you mean" suggestions.

use std::fmt::Write as _;

/// Formats a float the way a TOML file would spell it, without noise: `1.7`, `4000`, `nan`,
/// `inf`, `-inf`, `1e300`.
pub(crate) fn num(v: f64) -> String {
    if v.is_nan() {
        "nan".to_owned()
    } else if v.is_infinite() {
        if v > 0.0 { "inf" } else { "-inf" }.to_owned()
    } else if v != 0.0 && !(1e-5..1e16).contains(&v.abs()) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

/// Formats a float array: `[0, 0, 0]`.
pub(crate) fn nums(v: &[f64]) -> String {
    let parts: Vec<String> = v.iter().map(|&x| num(x)).collect();
    format!("[{}]", parts.join(", "))
}

/// Formats a TOML value compactly, as it would appear in a file.
pub(crate) fn toml_value(v: &toml::Value) -> String {
    match v {
        toml::Value::String(s) => quote(s),
        toml::Value::Integer(i) => i.to_string(),
        toml::Value::Float(f) => num(*f),
        toml::Value::Boolean(b) => b.to_string(),
        toml::Value::Datetime(d) => d.to_string(),
        toml::Value::Array(a) => {
            let parts: Vec<String> = a.iter().map(toml_value).collect();
            format!("[{}]", parts.join(", "))
        }
        toml::Value::Table(t) => {
            if t.is_empty() {
                return "{}".to_owned();
            }
            let parts: Vec<String> = t
                .iter()
                .map(|(k, v)| format!("{k} = {}", toml_value(v)))
                .collect();
            format!("{{ {} }}", parts.join(", "))
        }
    }
}

/// A double-quoted string with TOML basic-string escapes.
pub(crate) fn quote(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\t' => out.push_str("\\t"),
            '\r' => out.push_str("\\r"),
            c if c.is_control() => {
                let _ = write!(out, "\\u{:04X}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// Levenshtein edit distance between two strings, in characters.
pub(crate) fn levenshtein(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let substitution = diagonal + usize::from(ca != cb);
            diagonal = row[j + 1];
            row[j + 1] = substitution.min(row[j] + 1).min(row[j + 1] + 1);
        }
    }
    row[b.len()]
}

/// The candidate closest to `word` by edit distance (ignoring case and `-`/`_`), if it is
/// close enough to be a plausible misspelling; failing that, the only candidate that contains
/// `word` or is contained in it.
pub(crate) fn nearest<'a>(word: &str, candidates: &[&'a str]) -> Option<&'a str> {
    let norm = |s: &str| s.to_lowercase().replace('-', "_");
    let w = norm(word);
    let mut best: Option<(usize, &str)> = None;
    for &c in candidates {
        let d = levenshtein(&w, &norm(c));
        if best.is_none_or(|(bd, _)| d < bd) {
            best = Some((d, c));
        }
    }
    if let Some((d, c)) = best {
        let len = w.chars().count().max(c.chars().count());
        if d <= (len / 3).max(2).min(len.saturating_sub(1)) {
            return Some(c);
        }
    }
    let containing: Vec<&str> = candidates
        .iter()
        .copied()
        .filter(|c| {
            let c = norm(c);
            w.len() >= 3 && (c.contains(&w) || w.contains(&c))
        })
        .collect();
    match containing.as_slice() {
        [one] => Some(one),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levenshtein_basics() {
        assert_eq!(levenshtein("", ""), 0);
        assert_eq!(levenshtein("abc", ""), 3);
        assert_eq!(levenshtein("", "abc"), 3);
        assert_eq!(levenshtein("kitten", "sitting"), 3);
        assert_eq!(levenshtein("covrage", "coverage"), 1);
        assert_eq!(levenshtein("flaw", "lawn"), 2);
    }

    #[test]
    fn nearest_picks_plausible_names_only() {
        let fields = ["coverage", "density", "cloud_type", "wind_speed_m_s"];
        assert_eq!(nearest("covrage", &fields), Some("coverage"));
        assert_eq!(nearest("Coverage", &fields), Some("coverage"));
        assert_eq!(nearest("cloud-type", &fields), Some("cloud_type"));
        assert_eq!(nearest("wind_speed", &fields), Some("wind_speed_m_s"));
        assert_eq!(nearest("zzz", &fields), None);
        assert_eq!(nearest("x", &["y"]), None);
    }

    #[test]
    fn numbers_read_like_toml() {
        assert_eq!(num(1.7), "1.7");
        assert_eq!(num(4000.0), "4000");
        assert_eq!(num(-0.5), "-0.5");
        assert_eq!(num(f64::NAN), "nan");
        assert_eq!(num(f64::NEG_INFINITY), "-inf");
        assert_eq!(num(1e300), "1e300");
        assert_eq!(nums(&[0.0, 1.0, 0.25]), "[0, 1, 0.25]");
    }
}
