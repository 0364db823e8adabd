//! The WGSL's constants and their Rust twins hold the same values. The CPU reference
//! (`crates/reference`), the uniform flags (`crates/scene`) and the host's side of the engine
//! contract (`crates/stratus`) restate constants of `wgsl/` under the same names; a value
//! changed on one side alone (the anvil's ANVIL_CORE once was 0.85 in the WGSL and 0.7 in the
//! CPU twin) makes the two renderers disagree only where that constant matters, which no image
//! test may happen to look at. Here every constant of the same name in both is compared.

use std::{
    collections::BTreeMap,
    path::{Path, PathBuf},
};

use stratus_test_support::files_with_extension;

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// Constants whose Rust name matches a WGSL constant but which are not its twin: (crate
/// directory, name, why).
const NOT_TWINS: &[(&str, &str, &str)] = &[(
    "scene",
    "MAX_VIEW_STEPS",
    "the validator's cap on quality.view_steps; the WGSL's is the march's bound in \
     step-length mode, whose twin is crates/reference's",
)];

/// `const NAME[: TYPE] = EXPR;` declarations in `text` (Rust's with any visibility), as (name,
/// expression). Declarations inside `#[cfg(test)]` modules count too: a test's constant
/// named after the WGSL's is meant to be it.
fn consts(text: &str) -> Vec<(String, String)> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(i) = rest.find("const ") {
        let before = &rest[..i];
        let line_start = before.rfind('\n').map_or(0, |n| n + 1);
        let head = before[line_start..].trim();
        rest = &rest[i + "const ".len()..];
        // Only declarations: at the start of a line, after an optional visibility.
        if !(head.is_empty() || head.starts_with("pub")) {
            continue;
        }
        let name: String = rest
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
            .collect();
        if name.is_empty() || !name.chars().next().unwrap().is_ascii_uppercase() {
            continue;
        }
        let Some(eq) = rest.find('=') else { break };
        let Some(end) = rest[eq..].find(';') else {
            break;
        };
        out.push((name, rest[eq + 1..eq + end].trim().to_string()));
    }
    out
}

/// The numbers a constant's expression holds, in order: literals (decimal, hex, with `_`
/// separators and WGSL's `u`, `i`, `f` suffixes), `A << B` evaluated and
/// `std::f64::consts::PI` as pi; identifiers' digits (`vec3`, `f32`, `V3`) are not numbers.
fn numbers(expr: &str) -> Result<Vec<f64>, String> {
    if expr.contains("consts::PI") {
        return Ok(vec![std::f64::consts::PI]);
    }
    if let Some((a, b)) = expr.split_once("<<") {
        let (a, b) = (numbers(a)?, numbers(b)?);
        if let ([a], [b]) = (a.as_slice(), b.as_slice()) {
            return Ok(vec![a * 2f64.powi(*b as i32)]);
        }
        return Err(format!("`{expr}`: a shift of more than two numbers"));
    }
    let chars: Vec<char> = expr.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let after_ident = i > 0 && (chars[i - 1].is_ascii_alphanumeric() || chars[i - 1] == '_');
        if !c.is_ascii_digit() || after_ident {
            // Skip the rest of an identifier that holds digits.
            i += 1;
            continue;
        }
        let start = i;
        let hex = c == '0' && chars.get(i + 1).is_some_and(|x| *x == 'x' || *x == 'X');
        if hex {
            i += 2;
            while i < chars.len() && (chars[i].is_ascii_hexdigit() || chars[i] == '_') {
                i += 1;
            }
            let digits: String = chars[start + 2..i].iter().filter(|c| **c != '_').collect();
            out.push(
                u64::from_str_radix(&digits, 16).map_err(|e| format!("`{expr}`: {e}"))? as f64,
            );
        } else {
            while i < chars.len() {
                let x = chars[i];
                let exponent_sign =
                    (x == '-' || x == '+') && i > start && matches!(chars[i - 1], 'e' | 'E');
                if x.is_ascii_digit()
                    || x == '.'
                    || x == '_'
                    || x == 'e'
                    || x == 'E'
                    || exponent_sign
                {
                    i += 1;
                } else {
                    break;
                }
            }
            let literal: String = chars[start..i].iter().filter(|c| **c != '_').collect();
            out.push(
                literal
                    .parse::<f64>()
                    .map_err(|e| format!("`{expr}`: `{literal}`: {e}"))?,
            );
        }
        // WGSL's type suffixes.
        while i < chars.len() && matches!(chars[i], 'u' | 'i' | 'f' | 'h') {
            i += 1;
        }
    }
    Ok(out)
}

#[test]
fn numbers_reads_the_forms_the_sources_write() {
    assert_eq!(numbers("4u").unwrap(), [4.0]);
    assert_eq!(numbers("0.6e-3").unwrap(), [0.6e-3]);
    assert_eq!(numbers("15_000.0").unwrap(), [15000.0]);
    assert_eq!(numbers("0xD40Bu").unwrap(), [54283.0]);
    assert_eq!(numbers("1 << 10").unwrap(), [1024.0]);
    assert_eq!(
        numbers("vec2<f32>(4000.0, 6000.0)").unwrap(),
        [4000.0, 6000.0]
    );
    assert_eq!(
        numbers("V3::new(0.85, 0.9, 1.0)").unwrap(),
        [0.85, 0.9, 1.0]
    );
    assert_eq!(numbers("[32, 32]").unwrap(), [32.0, 32.0]);
    assert_eq!(
        numbers("std::f64::consts::PI").unwrap(),
        [std::f64::consts::PI]
    );
}

#[test]
fn every_rust_twin_of_a_wgsl_constant_holds_its_value() {
    let root = workspace();
    let wgsl = files_with_extension(&root.join("wgsl"), "wgsl");
    let mut shader: BTreeMap<String, (String, String)> = BTreeMap::new();
    for f in &wgsl {
        let text = std::fs::read_to_string(f).unwrap();
        for (name, expr) in consts(&text) {
            let file = f.strip_prefix(&root).unwrap().display().to_string();
            if let Some((other, _)) = shader.insert(name.clone(), (file.clone(), expr)) {
                panic!("`{name}` is declared in both {other} and {file}");
            }
        }
    }
    assert!(shader.len() > 100, "the WGSL's constants: {}", shader.len());

    let mut compared = 0;
    let mut wrong = Vec::new();
    for krate in ["reference", "scene", "stratus"] {
        let rust = files_with_extension(&root.join("crates").join(krate).join("src"), "rs");
        for f in &rust {
            let text = std::fs::read_to_string(f).unwrap();
            for (name, expr) in consts(&text) {
                let Some((wfile, wexpr)) = shader.get(&name) else {
                    continue;
                };
                if NOT_TWINS.iter().any(|(k, n, _)| *k == krate && *n == name) {
                    continue;
                }
                let at = f.strip_prefix(&root).unwrap().display();
                let (w, r) = match (numbers(wexpr), numbers(&expr)) {
                    (Ok(w), Ok(r)) => (w, r),
                    (w, r) => {
                        wrong.push(format!("{name}: unreadable: {w:?} ({wfile}), {r:?} ({at})"));
                        continue;
                    }
                };
                compared += 1;
                let same = w.len() == r.len()
                    && w.iter()
                        .zip(&r)
                        .all(|(a, b)| (a - b).abs() <= 1e-12 * a.abs().max(b.abs()));
                if !same {
                    wrong.push(format!(
                        "{name}: {wfile} says `{wexpr}`, {at} says `{expr}`"
                    ));
                }
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "twins that disagree:\n{}",
        wrong.join("\n")
    );
    // The CPU reference alone restates about a hundred.
    assert!(compared > 90, "only {compared} constants compared");
}
